#pragma once

#include <pybind11/pybind11.h>

#include <string>

#include "conversions.hpp"
#include "swarmcollide/queries/query.hpp"

namespace swarmcollide::bindings {

namespace py = pybind11;

/// Options from the keyword arguments of `Query(...)` (and `Scene(...)`): TypeError for a value
/// of the wrong type (a method that is not a str included), ValueError for an unknown method or
/// parameter or a value out of range.
QueryOptions make_options(const py::handle& method, const py::handle& tolerance,
                          const py::handle& seed, const py::kwargs& parameters);

/// A query's options as pickled: (method, tolerance, seed, parameters), the arguments of
/// `Query(method, tolerance, seed, **parameters)`.
py::tuple options_state(const QueryOptions& options);

/// Options from the next four items of `state` (options_state's), validated as `Query(...)`
/// validates its arguments.
QueryOptions options_from_state(PickledState& state);

/// A DistanceResult as pickled: every field, as Python reads it.
py::tuple distance_result_state(const DistanceResult& result);

/// A DistanceResult from distance_result_state's tuple; ValueError naming what is wrong.
DistanceResult distance_result_from_state(const py::handle& state);

/// Binds DistanceResult, before CompoundResult (its subclass) and the queries returning either.
void bind_distance_result(py::module_& m);

/// Binds the method table and Query; returns Query's class so that other areas (batches) can add
/// their methods to it.
py::class_<Query> bind_queries(py::module_& m);

}  // namespace swarmcollide::bindings
