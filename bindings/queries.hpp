#pragma once

#include <pybind11/pybind11.h>

#include "swarmcollide/queries/query.hpp"

namespace swarmcollide::bindings {

namespace py = pybind11;

/// Binds DistanceResult, the method table and Query; returns Query's class so that other areas
/// (batches) can add their methods to it.
py::class_<Query> bind_queries(py::module_& m);

}  // namespace swarmcollide::bindings
