#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include "swarmcollide/geometry/convex_polyhedron.hpp"
#include "swarmcollide/types.hpp"

namespace swarmcollide::bindings {

namespace py = pybind11;

/// An `(n, 3)` array-like as a vertex matrix; TypeError for non-numeric input, ValueError for a
/// wrong shape. `name` is the argument's name in the messages.
VertexMatrix to_vertex_matrix(const py::handle& points, const char* name);

/// A ConvexPolyhedron as is, or one built from `(n, 3)` points; errors name the argument `name`.
ConvexPolyhedron to_polyhedron(const py::handle& body, const char* name);

/// A 3-vector that must be finite; ValueError naming `name` otherwise.
Vector3 finite_vector3(const Vector3& vector, const char* name);

/// A 1-D array of finite weights; ValueError naming `name` otherwise.
const VectorX& finite_weights(const VectorX& weights, const char* name);

}  // namespace swarmcollide::bindings
