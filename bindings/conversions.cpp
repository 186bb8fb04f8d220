#include "conversions.hpp"

#include <stdexcept>
#include <string>

namespace swarmcollide::bindings {

namespace {

std::string shape_of(const py::array& array) {
  std::string text = "(";
  for (py::ssize_t i = 0; i < array.ndim(); ++i) {
    text += std::to_string(array.shape(i)) + (array.ndim() == 1 || i + 1 < array.ndim() ? "," : "");
    if (i + 1 < array.ndim()) text += " ";
  }
  return text + ")";
}

}  // namespace

VertexMatrix to_vertex_matrix(const py::handle& points, const char* name) {
  const std::string arg(name);
  if (py::isinstance<py::str>(points) || py::isinstance<py::bytes>(points)) {
    throw py::type_error(arg + " must be an (n, 3) array of numbers, got " +
                         std::string(py::str(points.get_type().attr("__name__"))));
  }
  py::array array;
  try {
    array = py::module_::import("numpy").attr("asarray")(points);
  } catch (py::error_already_set& error) {
    throw py::value_error(arg + " must be an (n, 3) array of numbers: " + error.what());
  }
  const char kind = array.dtype().kind();
  if (kind != 'f' && kind != 'i' && kind != 'u') {
    throw py::type_error(arg + " must hold real numbers, got an array of dtype " +
                         std::string(py::str(array.dtype())));
  }
  if (array.ndim() != 2 || array.shape(1) != 3) {
    throw py::value_error(arg + " must have shape (n, 3), got shape " + shape_of(array));
  }
  if (array.shape(0) == 0) {
    throw py::value_error(arg + " is empty: a polyhedron needs at least one point");
  }
  const auto doubles =
      py::array_t<Scalar, py::array::c_style | py::array::forcecast>::ensure(array);
  return Eigen::Map<const VertexMatrix>(doubles.data(), doubles.shape(0), 3);
}

ConvexPolyhedron to_polyhedron(const py::handle& body, const char* name) {
  if (py::isinstance<ConvexPolyhedron>(body)) return body.cast<ConvexPolyhedron>();
  try {
    return ConvexPolyhedron(to_vertex_matrix(body, name));
  } catch (const std::invalid_argument& error) {
    throw py::value_error(std::string(name) + ": " + error.what());
  }
}

Vector3 finite_vector3(const Vector3& vector, const char* name) {
  if (!vector.allFinite()) throw py::value_error(std::string(name) + " must be finite");
  return vector;
}

const VectorX& finite_weights(const VectorX& weights, const char* name) {
  if (!weights.allFinite()) {
    throw py::value_error(std::string(name) + " has a NaN or infinite weight");
  }
  return weights;
}

}  // namespace swarmcollide::bindings
