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

// A real array of exactly `shape` (a -1 entry matches any length), converted to doubles.
py::array_t<Scalar, py::array::c_style | py::array::forcecast> real_array(
    const py::handle& value, std::initializer_list<py::ssize_t> shape, const std::string& name,
    const std::string& expected) {
  if (py::isinstance<py::str>(value) || py::isinstance<py::bytes>(value)) {
    throw py::type_error(name + " must be " + expected + ", got " + type_name(value));
  }
  py::array array;
  try {
    array = py::module_::import("numpy").attr("asarray")(value);
  } catch (py::error_already_set& error) {
    throw py::value_error(name + " must be " + expected + ": " + error.what());
  }
  const char kind = array.dtype().kind();
  if (kind != 'f' && kind != 'i' && kind != 'u') {
    throw py::type_error(name + " must hold real numbers, got an array of dtype " +
                         std::string(py::str(array.dtype())));
  }
  bool matches = array.ndim() == static_cast<py::ssize_t>(shape.size());
  py::ssize_t axis = 0;
  for (py::ssize_t length : shape) {
    if (matches && length >= 0 && array.shape(axis) != length) matches = false;
    ++axis;
  }
  if (!matches) {
    throw py::value_error(name + " must be " + expected + ", got shape " + shape_of(array));
  }
  return py::array_t<Scalar, py::array::c_style | py::array::forcecast>::ensure(array);
}

}  // namespace

std::string type_name(const py::handle& object) {
  return std::string(py::str(py::type::handle_of(object).attr("__name__")));
}

VertexMatrix to_vertex_matrix(const py::handle& points, const char* name) {
  const auto doubles = real_array(points, {-1, 3}, name, "an (n, 3) array of numbers");
  if (doubles.shape(0) == 0) {
    throw py::value_error(std::string(name) + " is empty: a polyhedron needs at least one point");
  }
  return Eigen::Map<const VertexMatrix>(doubles.data(), doubles.shape(0), 3);
}

BodyArgument::BodyArgument(const py::handle& body, const char* name) {
  if (py::isinstance<ConvexPolyhedron>(body)) {
    body_ = &body.cast<const ConvexPolyhedron&>();
    return;
  }
  try {
    owned_.emplace(to_vertex_matrix(body, name));
  } catch (const std::invalid_argument& error) {
    throw py::value_error(std::string(name) + ": " + error.what());
  }
  body_ = &*owned_;
}

bool is_compound(const py::handle& body) {
  // The common argument, an exact ConvexPolyhedron, is told apart by its type alone: the generic
  // isinstance goes through the metaclass's __instancecheck__, a cost the size of a small query.
  static PyTypeObject* const convex =
      reinterpret_cast<PyTypeObject*>(py::type::of<ConvexPolyhedron>().ptr());
  if (Py_TYPE(body.ptr()) == convex) return false;
  return py::isinstance<CompoundBody>(body);
}

// True when `bodies` is a sequence (not an array) holding a CompoundBody.
bool holds_compound(const py::handle& bodies) {
  if (py::isinstance<py::array>(bodies) || py::isinstance<py::str>(bodies) ||
      !py::isinstance<py::sequence>(bodies)) {
    return false;
  }
  for (const py::handle body : bodies) {
    if (is_compound(body)) return true;
  }
  return false;
}

CompoundArgument::CompoundArgument(const py::handle& body, const char* name) {
  if (is_compound(body)) {
    body_ = &body.cast<const CompoundBody&>();
    return;
  }
  owned_.emplace(BodyArgument(body, name).get());
  body_ = &*owned_;
}

Pose to_pose(const py::handle& pose, const char* name) {
  Pose result;
  if (pose.is_none()) return result;
  const std::string arg(name);
  if (py::isinstance<py::tuple>(pose) || py::isinstance<py::list>(pose)) {
    const py::sequence parts = py::reinterpret_borrow<py::sequence>(pose);
    if (parts.size() != 2) {
      throw py::value_error(arg +
                            " must be a (4, 4) matrix or a pair (rotation, translation), "
                            "got a sequence of " +
                            std::to_string(parts.size()) + " items");
    }
    const auto rotation =
        real_array(parts[0], {3, 3}, arg + "'s rotation", "a (3, 3) rotation matrix");
    const auto translation =
        real_array(parts[1], {3}, arg + "'s translation", "a (3,) translation");
    result.rotation =
        Eigen::Map<const Eigen::Matrix<Scalar, 3, 3, Eigen::RowMajor>>(rotation.data());
    result.translation = Eigen::Map<const Vector3>(translation.data());
  } else {
    const auto matrix = real_array(
        pose, {4, 4}, arg, "a (4, 4) homogeneous transform or a pair (rotation, translation)");
    const Eigen::Map<const Eigen::Matrix<Scalar, 4, 4, Eigen::RowMajor>> m(matrix.data());
    if (!(m.row(3) == Eigen::RowVector4d(0, 0, 0, 1))) {
      throw py::value_error(arg +
                            " must be a homogeneous rigid transform: its last row must be "
                            "[0, 0, 0, 1]");
    }
    result.rotation = m.topLeftCorner<3, 3>();
    result.translation = m.topRightCorner<3, 1>();
  }
  try {
    validate_pose(result, name);
  } catch (const std::invalid_argument& error) {
    throw py::value_error(error.what());
  }
  return result;
}

namespace {

using RowMatrix3 = Eigen::Matrix<Scalar, 3, 3, Eigen::RowMajor>;
using RowMatrix4 = Eigen::Matrix<Scalar, 4, 4, Eigen::RowMajor>;

// A pair (rotations, translations) rather than one array of transforms.
bool is_pose_pair(const py::handle& poses) {
  if (!py::isinstance<py::tuple>(poses) && !py::isinstance<py::list>(poses)) return false;
  const py::sequence parts = py::reinterpret_borrow<py::sequence>(poses);
  if (parts.size() != 2) return false;
  const py::array first = py::module_::import("numpy").attr("asarray")(parts[0]);
  return first.ndim() >= 2 && first.shape(first.ndim() - 1) == 3 &&
         first.shape(first.ndim() - 2) == 3;
}

}  // namespace

std::vector<Pose> to_poses(const py::handle& poses, std::size_t count, const char* name) {
  std::vector<Pose> result;
  if (poses.is_none()) return result;
  const std::string arg(name);
  const auto n = static_cast<py::ssize_t>(count);
  const std::string shapes =
      count == 1
          ? "a (4, 4) transform, a (1, 4, 4) array of them or a pair "
            "(rotation, translation)"
          : "a (" + std::to_string(count) + ", 4, 4) or (" + std::to_string(count) +
                ", 3, 4) array of transforms or a pair (rotations (" +
                std::to_string(count) + ", 3, 3), translations (" + std::to_string(count) + ", 3))";
  result.resize(count);
  if (is_pose_pair(poses)) {
    const py::sequence parts = py::reinterpret_borrow<py::sequence>(poses);
    const py::array first = py::module_::import("numpy").attr("asarray")(parts[0]);
    const bool single = count == 1 && first.ndim() == 2;
    const auto rotations =
        single ? real_array(parts[0], {3, 3}, arg + "'s rotation", "a (3, 3) rotation")
               : real_array(parts[0], {n, 3, 3}, arg + "'s rotations", shapes);
    const auto translations =
        single ? real_array(parts[1], {3}, arg + "'s translation", "a (3,) translation")
               : real_array(parts[1], {n, 3}, arg + "'s translations", shapes);
    for (std::size_t i = 0; i < count; ++i) {
      result[i].rotation = Eigen::Map<const RowMatrix3>(rotations.data() + 9 * i);
      result[i].translation = Eigen::Map<const Vector3>(translations.data() + 3 * i);
    }
  } else {
    const py::array raw = py::module_::import("numpy").attr("asarray")(poses);
    const bool single = count == 1 && raw.ndim() == 2;
    // (m, 3, 4): the transforms without their constant last row.
    const bool affine = !single && raw.ndim() == 3 && raw.shape(1) == 3 && raw.shape(2) == 4;
    if (affine) {
      const auto matrices = real_array(poses, {n, 3, 4}, arg, shapes);
      for (std::size_t i = 0; i < count; ++i) {
        const Eigen::Map<const Eigen::Matrix<Scalar, 3, 4, Eigen::RowMajor>> m(matrices.data() +
                                                                                12 * i);
        result[i].rotation = m.leftCols<3>();
        result[i].translation = m.col(3);
      }
      return result;
    }
    const auto matrices =
        single ? real_array(poses, {4, 4}, arg, shapes) : real_array(poses, {n, 4, 4}, arg, shapes);
    for (std::size_t i = 0; i < count; ++i) {
      const Eigen::Map<const RowMatrix4> m(matrices.data() + 16 * i);
      if (!(m.row(3) == Eigen::RowVector4d(0, 0, 0, 1))) {
        throw py::value_error(arg + "[" + std::to_string(i) +
                              "] must be a homogeneous rigid transform: its last row must be "
                              "[0, 0, 0, 1]");
      }
      result[i].rotation = m.topLeftCorner<3, 3>();
      result[i].translation = m.topRightCorner<3, 1>();
    }
  }
  return result;
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
