#include "conversions.hpp"

#include <cmath>
#include <initializer_list>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>

#include "fast_calls.hpp"
#include "swarmcollide/geometry/shapes.hpp"
#include "swarmcollide/queries/batch.hpp"

namespace swarmcollide::bindings {

bool is_rotation(const py::handle& value) {
  return !py::isinstance<py::array>(value) && !PyList_Check(value.ptr()) &&
         !PyTuple_Check(value.ptr()) && py::hasattr(value, "as_matrix");
}

bool is_masked(const py::handle& value) {
  // A plain ndarray, the usual argument, is told apart by its type alone: only a subclass pays
  // for the lookup.
  if (!py::isinstance<py::array>(value) ||
      Py_TYPE(value.ptr()) == reinterpret_cast<PyTypeObject*>(
                                  py::detail::npy_api::get().PyArray_Type_)) {
    return false;
  }
  static PyObject* const masked =
      py::object(py::module_::import("numpy.ma").attr("MaskedArray")).release().ptr();
  return PyObject_IsInstance(value.ptr(), masked) == 1;
}

void refuse_masked(const py::handle& value, const std::string& name) {
  if (is_masked(value)) {
    throw py::type_error(name + " is a NumPy masked array, whose mask would be ignored: pass " +
                         name + ".filled(value) with the value the masked entries should take, "
                         "or a plain array");
  }
}

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
  refuse_masked(value, name);
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

// `value` as a NumPy array of real numbers; nothing for anything else (text, a ragged sequence,
// objects).
std::optional<py::array> real_numbers(const py::handle& value) {
  if (py::isinstance<py::str>(value) || py::isinstance<py::bytes>(value)) return std::nullopt;
  py::array array;
  try {
    array = py::module_::import("numpy").attr("asarray")(value);
  } catch (py::error_already_set&) {
    return std::nullopt;
  }
  const char kind = array.dtype().kind();
  if (kind != 'f' && kind != 'i' && kind != 'u') return std::nullopt;
  return array;
}

// A tuple or list of `length` items.
bool is_sequence_of(const py::handle& value, std::size_t length) {
  return (PyTuple_Check(value.ptr()) || PyList_Check(value.ptr())) &&
         static_cast<std::size_t>(PyObject_Length(value.ptr())) == length;
}

// The matrices of a rotation object (is_rotation), or nothing.
std::optional<py::object> rotation_matrices(const py::handle& rotation) {
  if (!is_rotation(rotation)) return std::nullopt;
  return rotation.attr("as_matrix")();
}

// A pose argument given as a rotation object alone stands for the pair (rotation, no
// translation); a pair whose rotation is a rotation object, for the pair of its matrices.
py::object with_rotation_matrices(const py::handle& pose) {
  if (const auto matrices = rotation_matrices(pose)) {
    // The translations' shape: the rotations' without their last axis, (3,) or (m, 3).
    const py::array rotations = py::module_::import("numpy").attr("asarray")(*matrices);
    py::list shape;
    for (py::ssize_t axis = 0; axis + 1 < rotations.ndim(); ++axis) {
      shape.append(rotations.shape(axis));
    }
    return py::make_tuple(rotations, py::module_::import("numpy").attr("zeros")(py::tuple(shape)));
  }
  if (is_sequence_of(pose, 2)) {
    const py::sequence parts = py::reinterpret_borrow<py::sequence>(pose);
    // Two rotation objects are two poses, not a rotation and its translation.
    if (is_rotation(parts[1])) return py::reinterpret_borrow<py::object>(pose);
    if (const auto matrices = rotation_matrices(parts[0])) {
      return py::make_tuple(*matrices, parts[1]);
    }
  }
  return py::reinterpret_borrow<py::object>(pose);
}

}  // namespace

std::string type_name(const py::handle& object) {
  return std::string(py::str(py::type::handle_of(object).attr("__name__")));
}

const char* status_name(MotionStatus status) {
  switch (status) {
    case MotionStatus::converged:
      return "converged";
    case MotionStatus::max_iterations:
      return "max_iterations";
    case MotionStatus::unresolved:
      return "unresolved";
  }
  return "unknown";
}

// A mesh from another library (trimesh's Trimesh or PointCloud: anything with a `vertices`
// attribute that is not itself an array, a sequence of points or a ConvexPolyhedron) stands for
// its vertices; their convex hull is the body, as for the points of any array. Its faces are not
// needed: the hull of the vertices is the hull of the mesh. Arrays and sequences are told apart
// first, so that the usual arguments never pay for the attribute lookup.
bool is_mesh(const py::handle& body) {
  return !py::isinstance<py::array>(body) && !PyList_Check(body.ptr()) &&
         !PyTuple_Check(body.ptr()) && !py::isinstance<ConvexPolyhedron>(body) &&
         py::hasattr(body, "vertices");
}

py::object points_of(const py::handle& body) {
  if (is_mesh(body)) return body.attr("vertices");
  return py::reinterpret_borrow<py::object>(body);
}

py::object unplaced_shape(const CurvedShapeParameters& shape) {
  switch (shape.kind) {
    case CurvedShapeParameters::Kind::cylinder:
      return py::cast(Cylinder(shape.radius, shape.half_length));
    case CurvedShapeParameters::Kind::cone:
      return py::cast(Cone(shape.radius, shape.half_length));
    case CurvedShapeParameters::Kind::ellipsoid:
      return py::cast(Ellipsoid(shape.radii));
  }
  throw std::logic_error("unknown curved shape");
}

py::object typed_body(const ConvexPolyhedron& body) {
  const SupportFunction* curved = body.curved();
  if (!curved) return py::cast(body);
  const CurvedShapeParameters shape = curved->parameters();
  return shape.placed ? py::cast(body) : unplaced_shape(shape);
}

py::object added_body(const ConvexPolyhedron& body) {
  if (body.curved()) return typed_body(body);
  const VertexMatrix& points = body.vertices();
  const Scalar radius = body.radius();
  try {
    if (points.rows() == 1 && radius > 0 && (points.array() == 0).all()) {
      return py::cast(Sphere(radius));
    }
    if (points.rows() == 2 && radius > 0) {
      const Capsule capsule(radius, std::abs(points(0, 2)));
      if (capsule.vertices() == points) return py::cast(capsule);
    }
    if (points.rows() == 8) {
      const Box box(points.cwiseAbs().colwise().maxCoeff().transpose(), radius);
      if (box.vertices() == points) return py::cast(box);
    }
  } catch (const std::invalid_argument&) {
    // Points no such shape has (a zero extent, say): the polyhedron it is.
  }
  return py::cast(body);
}

VertexMatrix to_vertex_matrix(const py::handle& points, const char* name) {
  const auto doubles = real_array(points_of(points), {-1, 3}, name, "an (n, 3) array of numbers");
  if (doubles.shape(0) == 0) {
    throw py::value_error(std::string(name) + " is empty: a polyhedron needs at least one point");
  }
  return Eigen::Map<const VertexMatrix>(doubles.data(), doubles.shape(0), 3);
}

BodyArgument::BodyArgument(const py::handle& body, const char* name) {
  if ((body_ = body_instance(body.ptr()))) return;
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
  // The common arguments, a ConvexPolyhedron or a shape, are told apart by their type alone: the
  // generic isinstance goes through the metaclass's __instancecheck__, a cost the size of a small
  // query.
  if (body_instance(body.ptr())) return false;
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

namespace {

using RowMatrix3 = Eigen::Matrix<Scalar, 3, 3, Eigen::RowMajor>;
using RowMatrix34 = Eigen::Matrix<Scalar, 3, 4, Eigen::RowMajor>;

// The pose of a transform's `rows` rows, row-major: a (4, 4) homogeneous transform, whose last
// row must be [0, 0, 0, 1], or its top (3, 4) rows [R | t]. `at()` names it in messages, made
// only for one: a name made for every pose of a scene's frame was 2.5% of its time.
template <typename Name>
Pose from_rows(const Scalar* data, py::ssize_t rows, const Name& at) {
  if (rows == 4 && !(Eigen::Map<const Eigen::RowVector4d>(data + 12) ==
                     Eigen::RowVector4d(0, 0, 0, 1))) {
    // A NaN fails the last row's test too; named first, as validate_pose names it.
    if (!Eigen::Map<const Eigen::Matrix<Scalar, 16, 1>>(data).allFinite()) {
      throw py::value_error(at() + " has a NaN or infinite entry");
    }
    throw py::value_error(at() +
                          " must be a homogeneous rigid transform: its last row must be "
                          "[0, 0, 0, 1]");
  }
  const Eigen::Map<const RowMatrix34> top(data);
  Pose pose;
  pose.rotation = top.leftCols<3>();
  pose.translation = top.col(3);
  return pose;
}

// How far from a rotation (|R^T R - I| and |det R - 1|), in units of the epsilon of the floats
// it was read from, a rotation narrower than double may be and still stand for the nearest
// rotation. Rounding a rotation leaves |R^T R - I| within about 2 epsilons, and computing one in
// those floats (a quaternion turned into a matrix, a chain of products) a few dozen: 84 epsilons
// are 1e-5 for float32 (whose rounding is near 1e-7, far beyond the 1e-9 a pose may be off) and
// 0.08 for float16. float16 rotations are taken, not refused: a robot's poses in half precision
// (a network's output, say) mean the rotations they round, no cast to float32 would make them
// any closer to one, and a matrix off by more than its floats' own error is still refused.
constexpr Scalar kNarrowRotationEpsilons = 84;

// The epsilon of the floats `value` holds when they are narrower than double (float32,
// float16); 0 for anything else.
Scalar narrow_float_epsilon(const py::handle& value) {
  const py::module_ numpy = py::module_::import("numpy");
  const py::array array = numpy.attr("asarray")(value);
  if (array.dtype().kind() != 'f' ||
      array.dtype().itemsize() >= static_cast<py::ssize_t>(sizeof(Scalar))) {
    return 0;
  }
  return numpy.attr("finfo")(array.dtype()).attr("eps").cast<Scalar>();
}

// A rotation read from floats of epsilon `epsilon` (narrow_float_epsilon; 0 for doubles, left
// as they are) as the rotation it is a rounding of: within kNarrowRotationEpsilons of one, the
// nearest rotation, which Newton-Schulz steps R <- R (3I - R^T R) / 2 reach to double precision
// (each about squares the error: four from 0.08, and one to spare); anything farther (a scaling,
// a shear) unchanged, for validate_pose to refuse with its usual message.
Matrix3 rounded_rotation(const Matrix3& rotation, Scalar epsilon) {
  if (epsilon == 0) return rotation;
  const Scalar tolerance = kNarrowRotationEpsilons * epsilon;
  const Scalar orthogonality =
      (rotation.transpose() * rotation - Matrix3::Identity()).cwiseAbs().maxCoeff();
  if (!(orthogonality <= tolerance) || !(std::abs(rotation.determinant() - 1) <= tolerance)) {
    return rotation;
  }
  Matrix3 nearest = rotation;
  for (int step = 0; step < 5; ++step) {
    nearest = nearest * (3 * Matrix3::Identity() - nearest.transpose() * nearest) / 2;
  }
  return nearest;
}

}  // namespace

namespace {

// `given` when it is a C-contiguous float64 array of exactly this shape, else null.
const Scalar* float64_data(const py::handle& given, std::initializer_list<py::ssize_t> shape) {
  // A masked array goes the general way, which refuses it.
  if (!py::isinstance<py::array_t<Scalar, py::array::c_style>>(given) || is_masked(given)) {
    return nullptr;
  }
  const auto array = py::reinterpret_borrow<py::array>(given);
  if (array.ndim() != static_cast<py::ssize_t>(shape.size())) return nullptr;
  py::ssize_t axis = 0;
  for (const py::ssize_t extent : shape) {
    if (array.shape(axis++) != extent) return nullptr;
  }
  return static_cast<const Scalar*>(array.data());
}

// The usual poses, a C-contiguous float64 (4, 4) or (3, 4) array or a tuple or list of a (3, 3)
// rotation and a (3,) translation of such arrays, read in place (not validated): the general
// path (numpy.asarray, scipy rotations, checks naming what is wrong) costs 0.5-4 us, more than a
// small query. Nothing when `given` is none of these. A tuple or list is told apart first, and its
// items read without new references: asking it for an array's shapes, and pybind11's item
// accessors, cost a pose pair about 250 instructions of the call's ~6,600 (sc.distance, 8
// vertices).
std::optional<Pose> read_in_place(const py::handle& given, const char* name) {
  PyObject* const object = given.ptr();
  if (PyTuple_Check(object) || PyList_Check(object)) {
    if (PySequence_Fast_GET_SIZE(object) != 2) return std::nullopt;
    PyObject* const* const parts = PySequence_Fast_ITEMS(object);
    const Scalar* rotation = float64_data(parts[0], {3, 3});
    const Scalar* translation = rotation ? float64_data(parts[1], {3}) : nullptr;
    if (translation == nullptr) return std::nullopt;
    Pose pose;
    pose.rotation = Eigen::Map<const RowMatrix3>(rotation);
    pose.translation = Eigen::Map<const Vector3>(translation);
    return pose;
  }
  for (const py::ssize_t rows : {4, 3}) {
    if (const Scalar* data = float64_data(given, {rows, 4})) {
      return from_rows(data, rows, [name] { return std::string(name); });
    }
  }
  return std::nullopt;
}

}  // namespace

Pose read_pose(const py::handle& given, const char* name) {
  Pose result;
  if (given.is_none()) return result;
  if (const std::optional<Pose> read = read_in_place(given, name)) return *read;
  const std::string arg(name);
  const py::object pose = with_rotation_matrices(given);
  const std::string forms =
      "a (4, 4) or (3, 4) rigid transform or a pair (rotation, translation)";
  if (is_sequence_of(pose, 2)) {
    const py::sequence parts = py::reinterpret_borrow<py::sequence>(pose);
    const auto rotation =
        real_array(parts[0], {3, 3}, arg + "'s rotation", "a (3, 3) rotation matrix");
    const auto translation =
        real_array(parts[1], {3}, arg + "'s translation", "a (3,) translation");
    result.rotation = Eigen::Map<const RowMatrix3>(rotation.data());
    result.translation = Eigen::Map<const Vector3>(translation.data());
    result.rotation = rounded_rotation(result.rotation, narrow_float_epsilon(parts[0]));
  } else {
    // A sequence of 3 or 4 rows is a transform written as lists; no other length can be one.
    if ((PyTuple_Check(pose.ptr()) || PyList_Check(pose.ptr())) && !is_sequence_of(pose, 3) &&
        !is_sequence_of(pose, 4)) {
      throw py::value_error(arg + " must be " + forms + ", got a sequence of " +
                            std::to_string(py::len(pose)) + " items");
    }
    const auto matrix = real_array(pose, {-1, 4}, arg, forms);
    if (matrix.shape(0) != 3 && matrix.shape(0) != 4) {
      throw py::value_error(arg + " must be " + forms + ", got shape " + shape_of(matrix));
    }
    result = from_rows(matrix.data(), matrix.shape(0), [&arg] { return arg; });
    result.rotation = rounded_rotation(result.rotation, narrow_float_epsilon(pose));
  }
  return result;
}

Pose to_pose(const py::handle& given, const char* name) {
  const Pose result = read_pose(given, name);
  try {
    validate_pose(result, name);
  } catch (const std::invalid_argument& error) {
    throw py::value_error(error.what());
  }
  return result;
}

py::array_t<Scalar> homogeneous(const Pose& pose) {
  py::array_t<Scalar> out({4, 4});
  auto m = out.mutable_unchecked<2>();
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) {
      m(r, c) = r < 3 ? (c < 3 ? pose.rotation(r, c) : pose.translation(r)) : (c == 3 ? 1 : 0);
    }
  }
  return out;
}

namespace {

// A pair (rotations, translations) rather than one array of transforms.
bool is_pose_pair(const py::handle& poses) {
  if (!is_sequence_of(poses, 2)) return false;
  const py::sequence parts = py::reinterpret_borrow<py::sequence>(poses);
  py::array first;
  try {
    first = py::module_::import("numpy").attr("asarray")(parts[0]);
  } catch (py::error_already_set&) {
    return false;  // ragged: not an array of rotations, and the transforms' message says so
  }
  return first.ndim() >= 2 && first.shape(first.ndim() - 1) == 3 &&
         first.shape(first.ndim() - 2) == 3;
}

}  // namespace

std::vector<Pose> to_poses(const py::handle& given, std::size_t count, const char* name) {
  std::vector<Pose> result;
  if (given.is_none()) return result;
  const std::string arg(name);
  const py::object poses = with_rotation_matrices(given);
  const auto n = static_cast<py::ssize_t>(count);
  const std::string shapes =
      count == 1
          ? "a (4, 4) or (3, 4) transform, a (1, 4, 4) or (1, 3, 4) array of them or a pair "
            "(rotation, translation)"
          : "a (" + std::to_string(count) + ", 4, 4) or (" + std::to_string(count) +
                ", 3, 4) array of transforms or a pair (rotations (" + std::to_string(count) +
                ", 3, 3), translations (" + std::to_string(count) + ", 3))";
  result.resize(count);
  if (is_pose_pair(poses)) {
    const py::sequence parts = py::reinterpret_borrow<py::sequence>(poses);
    const py::array first = py::module_::import("numpy").attr("asarray")(parts[0]);
    const bool single = count == 1 && first.ndim() == 2;
    // Each part named with its own shape: the transforms' shapes described neither.
    const std::string m = std::to_string(count);
    const auto rotations =
        single ? real_array(parts[0], {3, 3}, arg + "'s rotation", "a (3, 3) rotation")
               : real_array(parts[0], {n, 3, 3}, arg + "'s rotations",
                            "a (" + m + ", 3, 3) array of rotation matrices (or a SciPy "
                            "Rotation of " + m + "), one per row");
    const auto translations =
        single ? real_array(parts[1], {3}, arg + "'s translation", "a (3,) translation")
               : real_array(parts[1], {n, 3}, arg + "'s translations",
                            "a (" + m + ", 3) array, one translation per rotation");
    const Scalar epsilon = narrow_float_epsilon(parts[0]);
    for (std::size_t i = 0; i < count; ++i) {
      result[i].rotation = Eigen::Map<const RowMatrix3>(rotations.data() + 9 * i);
      result[i].translation = Eigen::Map<const Vector3>(translations.data() + 3 * i);
      result[i].rotation = rounded_rotation(result[i].rotation, epsilon);
    }
  } else if (is_sequence_of(given, count) && !real_numbers(poses)) {
    // A pose per body, each in any form to_pose reads: (Rotation, translation) pairs, Rotations,
    // transforms of both shapes mixed.
    const py::sequence items = py::reinterpret_borrow<py::sequence>(given);
    for (std::size_t i = 0; i < count; ++i) {
      result[i] = to_pose(items[i], (arg + "[" + std::to_string(i) + "]").c_str());
    }
  } else {
    py::array raw;
    try {
      raw = py::module_::import("numpy").attr("asarray")(poses);
    } catch (py::error_already_set& error) {
      throw py::value_error(arg + " must be " + shapes + ": " + error.what());
    }
    const bool single = count == 1 && raw.ndim() == 2;
    const auto matrices = single ? real_array(poses, {-1, 4}, arg, shapes)
                                 : real_array(poses, {n, -1, 4}, arg, shapes);
    const py::ssize_t rows = matrices.shape(matrices.ndim() - 2);
    if (rows != 3 && rows != 4) {
      throw py::value_error(arg + " must be " + shapes + ", got shape " + shape_of(matrices));
    }
    const Scalar epsilon = narrow_float_epsilon(poses);
    for (std::size_t i = 0; i < count; ++i) {
      result[i] = from_rows(matrices.data() + rows * 4 * i, rows,
                            [&arg, i] { return arg + "[" + std::to_string(i) + "]"; });
      result[i].rotation = rounded_rotation(result[i].rotation, epsilon);
    }
  }
  return result;
}

bool is_single_pose(const py::handle& given) {
  if (given.is_none()) return false;
  const py::object pose = with_rotation_matrices(given);
  if (const auto transform = real_numbers(pose)) {
    return transform->ndim() == 2 && (transform->shape(0) == 3 || transform->shape(0) == 4) &&
           transform->shape(1) == 4;
  }
  if (!is_sequence_of(pose, 2)) return false;
  const auto rotation = real_numbers(py::reinterpret_borrow<py::sequence>(pose)[0]);
  return rotation && rotation->ndim() == 2 && rotation->shape(0) == 3 && rotation->shape(1) == 3;
}

std::size_t pose_count(const py::handle& given) {
  if (given.is_none()) return 0;
  if (is_single_pose(given)) return 1;
  const py::object poses = with_rotation_matrices(given);
  std::optional<py::array> leading;
  if (is_pose_pair(poses)) {
    leading = real_numbers(py::reinterpret_borrow<py::sequence>(poses)[0]);
  } else {
    leading = real_numbers(poses);
  }
  if (leading) return leading->ndim() == 3 ? static_cast<std::size_t>(leading->shape(0)) : 1;
  if (PyTuple_Check(given.ptr()) || PyList_Check(given.ptr())) return py::len(given);
  return 1;
}

Vector3 finite_vector3(const py::handle& vector, const char* name) {
  const auto values = real_array(vector, {3}, name, "a 3-vector of real numbers");
  const Vector3 result = Eigen::Map<const Vector3>(values.data());
  if (!result.allFinite()) throw py::value_error(std::string(name) + " must be finite");
  return result;
}

VectorX finite_weights(const py::handle& weights, const char* name) {
  const auto values = real_array(weights, {-1}, name, "a 1-D array of real numbers");
  const VectorX result = Eigen::Map<const VectorX>(values.data(), values.shape(0));
  if (!result.allFinite()) {
    throw py::value_error(std::string(name) + " has a NaN or infinite weight");
  }
  return result;
}

int thread_count(const py::handle& threads) {
  if (PyBool_Check(threads.ptr()) || !PyIndex_Check(threads.ptr())) {
    throw py::type_error("threads must be an integer or None, got " + type_name(threads));
  }
  // Compared as Python integers: 2**63 threads is out of range, not an overflow.
  const py::int_ count = py::reinterpret_steal<py::int_>(PyNumber_Index(threads.ptr()));
  if (count < py::int_(1) || count > py::int_(kMaxThreads)) {
    throw py::value_error("threads must be in [1, " + std::to_string(kMaxThreads) +
                          "] (None: one per hardware thread), got " + std::string(py::str(count)));
  }
  return count.cast<int>();
}

std::string to_name(const py::handle& value, const char* name) {
  // pybind11 would take bytes for a std::string; a name is text.
  if (!py::isinstance<py::str>(value)) {
    throw py::type_error(std::string(name) + " must be a string, got " + type_name(value));
  }
  return value.cast<std::string>();
}

bool is_array(const py::handle& value) {
  return py::isinstance<py::array>(value) && value.cast<py::array>().ndim() > 0;
}

Scalar to_real(const py::handle& value, const char* name) {
  if (PyBool_Check(value.ptr()) || py::isinstance<py::str>(value) ||
      py::isinstance<py::bytes>(value) || is_array(value) || !PyNumber_Check(value.ptr())) {
    throw py::type_error(std::string(name) + " must be a real number, got " + type_name(value));
  }
  PyObject* real = PyNumber_Float(value.ptr());
  if (real == nullptr) {
    PyErr_Clear();
    throw py::type_error(std::string(name) + " must be a real number, got " + type_name(value));
  }
  return py::reinterpret_steal<py::float_>(real).cast<Scalar>();
}

int to_count(const py::handle& value, const char* name, int least) {
  if (PyBool_Check(value.ptr()) || is_array(value) || !PyIndex_Check(value.ptr())) {
    throw py::type_error(std::string(name) + " must be an integer, got " + type_name(value));
  }
  const py::int_ count = py::reinterpret_steal<py::int_>(PyNumber_Index(value.ptr()));
  if (count < py::int_(least)) {
    throw py::value_error(std::string(name) + " must be at least " + std::to_string(least) +
                          ", got " + std::string(py::str(count)));
  }
  if (count > py::int_(std::numeric_limits<int>::max())) {
    throw py::value_error(std::string(name) + " must be at most 2**31 - 1, got " +
                          std::string(py::str(count)));
  }
  return count.cast<int>();
}

bool to_bool(const py::handle& value, const char* name) {
  if (PyBool_Check(value.ptr())) return value.ptr() == Py_True;
  if (py::isinstance(value, py::module_::import("numpy").attr("bool_"))) {
    return value.cast<bool>();
  }
  throw py::type_error(std::string(name) + " must be True or False, got " + type_name(value));
}

MotionKind to_motion_kind(const py::handle& motion) {
  const std::string name = to_name(motion, "motion");
  try {
    return motion_kind_from_name(name);
  } catch (const std::invalid_argument& e) {
    throw py::value_error(e.what());
  }
}

MotionStatus motion_status(const py::handle& value, const char* name) {
  const std::string given = to_name(value, name);
  for (MotionStatus status :
       {MotionStatus::converged, MotionStatus::max_iterations, MotionStatus::unresolved}) {
    if (given == status_name(status)) return status;
  }
  throw py::value_error(std::string(name) +
                        " must be 'converged', 'max_iterations' or 'unresolved', got '" + given +
                        "'");
}

PickledState::PickledState(const py::handle& state, std::string type, std::size_t items)
    : type_(std::move(type)) {
  if (!PyTuple_Check(state.ptr())) {
    throw error("expected a tuple, got " + type_name(state));
  }
  items_ = py::reinterpret_borrow<py::tuple>(state);
  const py::handle version = items_.size() > 0 ? items_[0] : py::handle(Py_None);
  if (PyBool_Check(version.ptr()) || !PyLong_Check(version.ptr()) ||
      !py::int_(kStateVersion).equal(version)) {
    throw error("format version " + std::string(py::repr(version)) + " is not " +
                std::to_string(kStateVersion) + " (pickled by another version of swarmcollide?)");
  }
  if (items_.size() != items + 1) {
    throw error("expected " + std::to_string(items + 1) + " items (the version and " +
                std::to_string(items) + " fields), got " + std::to_string(items_.size()));
  }
}

py::value_error PickledState::error(const std::string& what) const {
  return py::value_error("cannot unpickle " + type_ + ": " + what);
}

std::string PickledState::naming(const std::string& item, const std::string& message) {
  return item.empty() || message.rfind(item, 0) == 0 ? message : item + ": " + message;
}

std::string PickledState::described(const py::handle& item) {
  if (PyList_Check(item.ptr()) || PyTuple_Check(item.ptr())) {
    return "a " + type_name(item) + " of length " + std::to_string(PyObject_Length(item.ptr()));
  }
  if (!py::isinstance<py::array>(item)) return type_name(item);
  const auto array = py::reinterpret_borrow<py::array>(item);
  return "an array of shape " + shape_of(array) + " and dtype " +
         std::string(py::str(array.dtype()));
}

py::int_ PickledState::to_integer(const py::handle& item, const char* name) {
  if (PyBool_Check(item.ptr()) || is_array(item) || !PyIndex_Check(item.ptr())) {
    throw py::type_error(std::string(name) + " must be an integer, got " + type_name(item));
  }
  return py::reinterpret_steal<py::int_>(PyNumber_Index(item.ptr()));
}

std::string unequal_lengths(std::initializer_list<std::pair<const char*, Eigen::Index>> columns) {
  const auto& [first, length] = *columns.begin();
  for (const auto& [name, rows] : columns) {
    if (rows != length) {
      return std::string(name) + " has " + std::to_string(rows) + " rows where " + first +
             " has " + std::to_string(length);
    }
  }
  return {};
}

py::dict instance_attributes(const py::handle& instance) {
  const py::object attributes = py::getattr(instance, "__dict__", py::none());
  return attributes.is_none() ? py::dict() : py::dict(attributes);
}

py::dict state_attributes(PickledState& state) {
  return state.next("attributes", [](const py::handle& item) {
    if (!PyDict_Check(item.ptr())) {
      throw py::type_error("must be a dict, got " + type_name(item));
    }
    return py::reinterpret_borrow<py::dict>(item);
  });
}

}  // namespace swarmcollide::bindings
