// Motions: time of impact of a pair, and of many.
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <initializer_list>
#include <memory>
#include <optional>
#include <sstream>
#include <utility>
#include <string>
#include <vector>

#include "conversions.hpp"
#include "fast_calls.hpp"
#include "swarmcollide/queries/methods.hpp"
#include "swarmcollide/motion/time_of_impact.hpp"

namespace py = pybind11;

namespace swarmcollide::bindings {

namespace {

using RowMatrix4 = Eigen::Matrix<Scalar, 4, 4, Eigen::RowMajor>;

RowMatrix4 transform(const Pose& pose) {
  RowMatrix4 m = RowMatrix4::Identity();
  m.topLeftCorner<3, 3>() = pose.rotation;
  m.topRightCorner<3, 1>() = pose.translation;
  return m;
}

std::string repr(const TimeOfImpactResult& r) {
  std::ostringstream out;
  out.precision(10);
  out << "TimeOfImpactResult(touches=" << (r.touches ? "True" : "False")
      << ", t_lower=" << r.t_lower << ", t_upper=" << r.t_upper;
  if (r.touches) out << ", distance=" << r.distance;
  out << ", certified=" << (r.certified ? "True" : "False") << ", iterations=" << r.iterations
      << ", status='" << status_name(r.status) << "')";
  return out.str();
}

// True when `given` is one pose as a (rotation, translation) pair (a body that stays there),
// rather than a pair of poses (start, end): its first item is a (3, 3) rotation.
bool is_one_pose(const py::sequence& given) {
  const py::object first = given[0];
  if (py::isinstance<py::array>(first)) {
    const py::array array = py::reinterpret_borrow<py::array>(first);
    return array.ndim() == 2 && array.shape(0) == 3 && array.shape(1) == 3;
  }
  // Told apart before the sequences: a SciPy Rotation has a length and items, so Python counts
  // it as one. A Rotation and its translation are one pose; two Rotations a start and an end.
  if (is_rotation(first)) return !is_rotation(given[1]);
  if (!py::isinstance<py::sequence>(first) || py::isinstance<py::str>(first)) return false;
  try {
    const py::array array = py::module_::import("numpy").attr("asarray")(first);
    return array.ndim() == 2 && array.shape(0) == 3 && array.shape(1) == 3;
  } catch (py::error_already_set&) {
    return false;  // ragged: the start and end poses' own checks say what is wrong
  }
}

// True when `given` is an array of two transforms, (2, 4, 4) or (2, 3, 4): a motion's start
// and end poses stacked (np.stack([start, end])), which no single pose's shape is.
bool is_stacked_motion(const py::handle& given) {
  if (!py::isinstance<py::array>(given)) return false;
  const py::array array = py::reinterpret_borrow<py::array>(given);
  return array.ndim() == 3 && array.shape(0) == 2 &&
         (array.shape(1) == 4 || array.shape(1) == 3) && array.shape(2) == 4;
}

// A motion argument: None (still at the identity), one pose (still there), or a pair
// (start, end) of poses: a list or tuple of two, or an array of two transforms.
RigidMotion to_motion(const py::handle& given, const char* name, MotionKind kind) {
  const std::string arg(name);
  if (given.is_none()) return RigidMotion(Pose{}, Pose{}, kind, name);
  if (((py::isinstance<py::tuple>(given) || py::isinstance<py::list>(given)) &&
       py::len(given) == 2 && !is_one_pose(py::reinterpret_borrow<py::sequence>(given))) ||
      is_stacked_motion(given)) {
    const py::sequence ends = py::reinterpret_borrow<py::sequence>(given);
    return RigidMotion(to_pose(ends[0], (arg + " start").c_str()),
                       to_pose(ends[1], (arg + " end").c_str()), kind, name);
  }
  const Pose pose = to_pose(given, name);
  return RigidMotion(pose, pose, kind, name);
}

// Motions of a batch: None (all still at the identity), or a pair (starts, ends) of pose arrays
// (see to_poses) of `count` rows, or of one row for all.
std::vector<RigidMotion> to_motions(const py::handle& given, std::size_t count, const char* name,
                                    MotionKind kind) {
  const std::string arg(name);
  if (given.is_none()) return {RigidMotion(Pose{}, Pose{}, kind, name)};
  if (!py::isinstance<py::sequence>(given) || py::len(given) != 2 ||
      py::isinstance<py::array>(given)) {
    throw py::value_error(arg + " must be a pair (starts, ends) of pose arrays, each an (m, 4, 4) "
                                "or (m, 3, 4) array or a pair (rotations, translations)");
  }
  const py::sequence ends = py::reinterpret_borrow<py::sequence>(given);
  const std::vector<Pose> starts = to_poses(ends[0], count, (arg + " starts").c_str());
  const std::vector<Pose> finals = to_poses(ends[1], count, (arg + " ends").c_str());
  std::vector<RigidMotion> motions;
  motions.reserve(count);
  for (std::size_t i = 0; i < count; ++i) {
    motions.emplace_back(starts[i], finals[i], kind,
                         (arg + "[" + std::to_string(i) + "]").c_str());
  }
  return motions;
}

// The arguments of a batch, by name and entries (1: one for every row), hold one entry per row,
// checked here rather than by the core, whose message names its own arguments (motions_a for
// poses_a) and takes the longest for the rows: the rows are the count most arguments share (the
// larger on a tie), so that the message names the argument that is the odd one out.
void check_rows(std::initializer_list<std::pair<const char*, std::size_t>> arguments) {
  std::size_t rows = 1;
  std::size_t sharing = 0;
  for (const auto& [name, count] : arguments) {
    if (count == 1) continue;
    std::size_t same = 0;
    for (const auto& other : arguments) same += other.second == count;
    if (same > sharing || (same == sharing && count > rows)) {
      rows = count;
      sharing = same;
    }
  }
  for (const auto& [name, count] : arguments) {
    if (count == 1 || count == rows) continue;
    std::string others;
    for (const auto& other : arguments) {
      if (other.second != rows) continue;
      others += (others.empty() ? "" : " and ") + std::string(other.first);
    }
    throw py::value_error(std::string(name) + " has " + std::to_string(count) + " entries where " +
                          others + (sharing > 1 ? " have " : " has ") + std::to_string(rows) +
                          "; give one per row, or one for all");
  }
}

// Rows of motions given: the leading length of their start poses (1 for a single pose or None).
std::size_t motion_rows(const py::handle& given) {
  if (given.is_none() || !py::isinstance<py::sequence>(given) || py::len(given) != 2) return 1;
  py::handle starts = py::reinterpret_borrow<py::sequence>(given)[0];
  if (py::isinstance<py::tuple>(starts) || py::isinstance<py::list>(starts)) {
    if (py::len(starts) == 2) starts = py::reinterpret_borrow<py::sequence>(starts)[0];
  }
  try {
    const py::array array = py::module_::import("numpy").attr("asarray")(starts);
    return array.ndim() == 3 ? static_cast<std::size_t>(array.shape(0)) : 1;
  } catch (py::error_already_set&) {
    return 1;
  }
}

// Types are checked here, values by TimeOfImpactOptions::validate.
TimeOfImpactOptions motion_options(const py::handle& method, const py::handle& tolerance,
                                   const py::handle& time_tolerance,
                                   const py::handle& max_iterations) {
  TimeOfImpactOptions options;
  options.query.method = method_from_name(to_name(method, "method"));
  options.query.tolerance = to_real(tolerance, "tolerance");
  options.time_tolerance = to_real(time_tolerance, "time_tolerance");
  options.max_iterations = to_count(max_iterations, "max_iterations", 1);
  try {
    options.validate();
  } catch (const std::invalid_argument& e) {
    throw py::value_error(e.what());
  }
  return options;
}

// time_of_impact's Python definition (swarmcollide.motion): the C++ function below hands it every
// call it does not answer itself.
PyObject* motion_python_path = nullptr;

// The keyword arguments of a call to time_of_impact, as written in it (null where not given).
struct MotionCall {
  PyObject* pose_a = Py_None;
  PyObject* pose_b = Py_None;
  PyObject* method = nullptr;
  PyObject* tolerance = nullptr;
  PyObject* time_tolerance = nullptr;
  PyObject* max_iterations = nullptr;
  PyObject* motion = nullptr;
};

// Reads a call's keywords into `call` by identity with their interned names (a keyword written in
// a call is interned too); false for any other keyword, which the Python path then refuses.
bool read_motion_keywords(PyObject* const* values, PyObject* names, MotionCall& call) {
  if (names == nullptr) return true;
  static PyObject* const pose_a = PyUnicode_InternFromString("pose_a");
  static PyObject* const pose_b = PyUnicode_InternFromString("pose_b");
  static PyObject* const method = PyUnicode_InternFromString("method");
  static PyObject* const tolerance = PyUnicode_InternFromString("tolerance");
  static PyObject* const time_tolerance = PyUnicode_InternFromString("time_tolerance");
  static PyObject* const max_iterations = PyUnicode_InternFromString("max_iterations");
  static PyObject* const motion = PyUnicode_InternFromString("motion");
  const std::pair<PyObject*, PyObject**> fields[] = {
      {pose_a, &call.pose_a},       {pose_b, &call.pose_b},
      {method, &call.method},       {tolerance, &call.tolerance},
      {time_tolerance, &call.time_tolerance}, {max_iterations, &call.max_iterations},
      {motion, &call.motion}};
  for (Py_ssize_t i = 0; i < PyTuple_GET_SIZE(names); ++i) {
    PyObject* const name = PyTuple_GET_ITEM(names, i);
    bool known = false;
    for (const auto& [field, value] : fields) {
      if (name == field) {
        *value = values[i];
        known = true;
      }
    }
    if (!known) return false;
  }
  return true;
}

// The options of a call, converted and checked as time_of_impact's pybind11 definition does; the
// defaults' once.
TimeOfImpactOptions call_options(const MotionCall& call) {
  static PyObject* const exact = PyUnicode_InternFromString("exact");
  static PyObject* const tolerance = PyFloat_FromDouble(kDefaultTolerance);
  static PyObject* const time_tolerance = PyFloat_FromDouble(kDefaultTimeTolerance);
  static PyObject* const max_iterations = PyLong_FromLong(kDefaultMotionIterations);
  static const TimeOfImpactOptions defaults =
      motion_options(exact, tolerance, time_tolerance, max_iterations);
  if (!call.method && !call.tolerance && !call.time_tolerance && !call.max_iterations) {
    return defaults;
  }
  return motion_options(call.method ? call.method : exact,
                        call.tolerance ? call.tolerance : tolerance,
                        call.time_tolerance ? call.time_tolerance : time_tolerance,
                        call.max_iterations ? call.max_iterations : max_iterations);
}

// time_of_impact in C++: `time_of_impact(a, b, *, pose_a, pose_b, method, tolerance,
// time_tolerance, max_iterations, motion)` between two ConvexPolyhedron or shapes answered here,
// with the pybind11 definition's conversions, about a microsecond sooner than through pybind11's
// argument matching; other bodies, other keywords and calls that raise go to the Python
// definition, which answers them or raises as it always has.
PyObject* time_of_impact_function(PyObject*, PyObject* const* arguments, Py_ssize_t count,
                                  PyObject* names) {
  MotionCall call;
  if (count == 2 && read_motion_keywords(arguments + 2, names, call)) {
    const ConvexPolyhedron* a = body_instance(arguments[0]);
    const ConvexPolyhedron* b = a ? body_instance(arguments[1]) : nullptr;
    if (b != nullptr) {
      try {
        const TimeOfImpactOptions options = call_options(call);
        const MotionKind kind = call.motion ? to_motion_kind(call.motion) : MotionKind::linear;
        const RigidMotion motion_a = to_motion(call.pose_a, "pose_a", kind);
        const RigidMotion motion_b = to_motion(call.pose_b, "pose_b", kind);
        TimeOfImpactResult result;
        {
          py::gil_scoped_release release;
          result = time_of_impact(*a, motion_a, *b, motion_b, options);
        }
        return py::cast(std::move(result)).release().ptr();
      } catch (...) {
        // The Python path raises it again, with the message it has always given.
      }
    }
  }
  return PyObject_Vectorcall(motion_python_path, arguments, static_cast<std::size_t>(count),
                             names);
}

// `python_path`, swarmcollide.motion's time_of_impact, as time_of_impact_function.
py::object make_motion_function(const py::function& python_path,
                                const std::string& text_signature) {
  Py_XDECREF(motion_python_path);
  motion_python_path = python_path.inc_ref().ptr();
  return fast_function(&time_of_impact_function, python_path, text_signature);
}

// The bodies of one side of a batch, converted where they are not bodies already.
template <typename Body, typename Argument>
class Side {
 public:
  Side(const py::handle& given, const char* name) {
    const bool many = (py::isinstance<py::list>(given) || py::isinstance<py::tuple>(given)) ||
                      (py::isinstance<py::array>(given) &&
                       py::reinterpret_borrow<py::array>(given).ndim() == 3);
    if (!many) {
      arguments_.emplace_back(given, name);
      return;
    }
    std::size_t i = 0;
    for (const py::handle item : given) {
      names_.push_back(std::string(name) + "[" + std::to_string(i++) + "]");
    }
    // Reserved: an argument may point into itself (a body it built), so it must not move.
    arguments_.reserve(names_.size());
    i = 0;
    for (const py::handle item : given) arguments_.emplace_back(item, names_[i++].c_str());
    many_ = true;
  }
  BatchBodies<Body> bodies() const {
    if (!many_) return BatchBodies<Body>(arguments_.front().get());
    std::vector<const Body*> list;
    for (const Argument& argument : arguments_) list.push_back(&argument.get());
    return BatchBodies<Body>(std::move(list));
  }
  std::size_t rows() const { return many_ ? arguments_.size() : 1; }

 private:
  std::vector<std::string> names_;
  std::vector<Argument> arguments_;
  bool many_ = false;
};

// Many answers, read as NumPy arrays (built when read) or one by one.
struct TimeOfImpactBatch {
  std::vector<TimeOfImpactResult> results;
};

py::tuple time_of_impact_state(const TimeOfImpactResult& r) {
  return py::make_tuple(kStateVersion, r.touches, r.t_lower, r.t_upper, transform(r.pose_a),
                        transform(r.pose_b), r.distance, r.point_a, r.point_b, r.normal,
                        r.certified, r.iterations, status_name(r.status));
}

TimeOfImpactResult time_of_impact_from_state(const py::object& state) {
  PickledState items(state, "TimeOfImpactResult", 12);
  const auto pose = [](const char* name) {
    return [name](const py::handle& item) { return to_pose(item, name); };
  };
  TimeOfImpactResult r;
  r.touches = items.next<bool>("touches");
  r.t_lower = items.next<Scalar>("t_lower");
  r.t_upper = items.next<Scalar>("t_upper");
  r.pose_a = items.next("pose_a", pose("pose_a"));
  r.pose_b = items.next("pose_b", pose("pose_b"));
  r.distance = items.next<Scalar>("distance");
  r.point_a = items.next<Vector3>("point_a");
  r.point_b = items.next<Vector3>("point_b");
  r.normal = items.next<Vector3>("normal");
  r.certified = items.next<bool>("certified");
  r.iterations = items.next<int>("iterations");
  r.status = items.next("status", [](const py::handle& item) {
    return motion_status(item, "status");
  });
  return r;
}

template <typename Field>
py::array_t<Scalar> column(const TimeOfImpactBatch& batch, Field field) {
  py::array_t<Scalar> out(static_cast<py::ssize_t>(batch.results.size()));
  auto view = out.mutable_unchecked<1>();
  for (std::size_t i = 0; i < batch.results.size(); ++i) view(i) = field(batch.results[i]);
  return out;
}

template <typename Field>
py::array_t<bool> flags(const TimeOfImpactBatch& batch, Field field) {
  py::array_t<bool> out(static_cast<py::ssize_t>(batch.results.size()));
  auto view = out.mutable_unchecked<1>();
  for (std::size_t i = 0; i < batch.results.size(); ++i) view(i) = field(batch.results[i]);
  return out;
}

template <typename Field>
py::array_t<Scalar> vectors(const TimeOfImpactBatch& batch, Field field) {
  py::array_t<Scalar> out({static_cast<py::ssize_t>(batch.results.size()), py::ssize_t{3}});
  auto view = out.mutable_unchecked<2>();
  for (std::size_t i = 0; i < batch.results.size(); ++i) {
    const Vector3 v = field(batch.results[i]);
    for (int k = 0; k < 3; ++k) view(i, k) = v(k);
  }
  return out;
}

template <typename Field>
py::array_t<Scalar> transforms(const TimeOfImpactBatch& batch, Field field) {
  py::array_t<Scalar> out(
      {static_cast<py::ssize_t>(batch.results.size()), py::ssize_t{4}, py::ssize_t{4}});
  auto view = out.mutable_unchecked<3>();
  for (std::size_t i = 0; i < batch.results.size(); ++i) {
    const RowMatrix4 m = transform(field(batch.results[i]));
    for (int r = 0; r < 4; ++r) {
      for (int c = 0; c < 4; ++c) view(i, r, c) = m(r, c);
    }
  }
  return out;
}

}  // namespace

void bind_motion(py::module_& m) {
  py::class_<TimeOfImpactResult>(m, "TimeOfImpactResult", R"doc(
The first contact of two moving bodies (``time_of_impact``).

When ``certified``: ``touches`` is False only when the bodies are proven never to overlap during
the motion; when True, they are proven apart before ``t_lower`` and within ``tolerance x size``
of each other at ``t_upper``, with ``t_upper - t_lower <= time_tolerance``. Uncertified answers
err on the side of contact: ``t_lower`` is still proven, ``touches`` is True.
)doc")
      .def_readonly("touches", &TimeOfImpactResult::touches,
                    "True when the bodies come within the tolerance of each other.")
      .def_readonly("t_lower", &TimeOfImpactResult::t_lower,
                    "The bodies are proven apart before this time (1 for a free motion).")
      .def_readonly("t_upper", &TimeOfImpactResult::t_upper,
                    "The bodies are proven in contact at this time (1 for a free motion).")
      .def_property_readonly(
          "pose_a", [](const TimeOfImpactResult& r) { return transform(r.pose_a); },
          "A's pose at ``t_upper``, a (4, 4) transform.")
      .def_property_readonly(
          "pose_b", [](const TimeOfImpactResult& r) { return transform(r.pose_b); },
          "B's pose at ``t_upper``, a (4, 4) transform.")
      .def_readonly("distance", &TimeOfImpactResult::distance,
                    "Signed distance at ``t_upper`` (NaN for a free motion).")
      .def_readonly("point_a", &TimeOfImpactResult::point_a, "Witness point on A at t_upper.")
      .def_readonly("point_b", &TimeOfImpactResult::point_b, "Witness point on B at t_upper.")
      .def_readonly("normal", &TimeOfImpactResult::normal,
                    "Unit contact normal from A to B at ``t_upper`` (zero for a free motion).")
      .def_readonly("certified", &TimeOfImpactResult::certified,
                    "True when the answer is proven.")
      .def_readonly("iterations", &TimeOfImpactResult::iterations,
                    "Distance queries run.")
      .def_property_readonly(
          "status", [](const TimeOfImpactResult& r) { return status_name(r.status); },
          "'converged', 'max_iterations' or 'unresolved'.")
      .def(py::pickle(&time_of_impact_state, &time_of_impact_from_state))
      .def("__repr__", &repr);

  py::class_<TimeOfImpactBatch>(m, "TimeOfImpactBatch", R"doc(
The answers of ``time_of_impact_many``: NumPy arrays with one entry per row (built when read),
and each row's ``TimeOfImpactResult`` by indexing.
)doc")
      .def("__len__", [](const TimeOfImpactBatch& b) { return b.results.size(); })
      .def("__getitem__",
           [](const TimeOfImpactBatch& b, py::ssize_t i) {
             const auto n = static_cast<py::ssize_t>(b.results.size());
             if (i < 0) i += n;
             if (i < 0 || i >= n) throw py::index_error("row out of range");
             return b.results[static_cast<std::size_t>(i)];
           })
      .def_property_readonly(
          "touches",
          [](const TimeOfImpactBatch& b) {
            return flags(b, [](const TimeOfImpactResult& r) { return r.touches; });
          })
      .def_property_readonly(
          "certified",
          [](const TimeOfImpactBatch& b) {
            return flags(b, [](const TimeOfImpactResult& r) { return r.certified; });
          })
      .def_property_readonly(
          "t_lower",
          [](const TimeOfImpactBatch& b) {
            return column(b, [](const TimeOfImpactResult& r) { return r.t_lower; });
          })
      .def_property_readonly(
          "t_upper",
          [](const TimeOfImpactBatch& b) {
            return column(b, [](const TimeOfImpactResult& r) { return r.t_upper; });
          })
      .def_property_readonly(
          "distance",
          [](const TimeOfImpactBatch& b) {
            return column(b, [](const TimeOfImpactResult& r) { return r.distance; });
          })
      .def_property_readonly(
          "iterations",
          [](const TimeOfImpactBatch& b) {
            py::array_t<int> out(static_cast<py::ssize_t>(b.results.size()));
            for (std::size_t i = 0; i < b.results.size(); ++i) {
              out.mutable_at(static_cast<py::ssize_t>(i)) = b.results[i].iterations;
            }
            return out;
          })
      .def_property_readonly(
          "point_a",
          [](const TimeOfImpactBatch& b) {
            return vectors(b, [](const TimeOfImpactResult& r) { return r.point_a; });
          })
      .def_property_readonly(
          "point_b",
          [](const TimeOfImpactBatch& b) {
            return vectors(b, [](const TimeOfImpactResult& r) { return r.point_b; });
          })
      .def_property_readonly(
          "normal",
          [](const TimeOfImpactBatch& b) {
            return vectors(b, [](const TimeOfImpactResult& r) { return r.normal; });
          })
      .def_property_readonly(
          "pose_a",
          [](const TimeOfImpactBatch& b) {
            return transforms(b, [](const TimeOfImpactResult& r) { return r.pose_a; });
          })
      .def_property_readonly(
          "pose_b",
          [](const TimeOfImpactBatch& b) {
            return transforms(b, [](const TimeOfImpactResult& r) { return r.pose_b; });
          })
      .def(py::pickle(
          [](const TimeOfImpactBatch& b) { return py::make_tuple(kStateVersion, b.results); },
          [](const py::object& state) {
            PickledState items(state, "TimeOfImpactBatch", 1);
            return TimeOfImpactBatch{items.next<std::vector<TimeOfImpactResult>>("results")};
          }))
      .def("__repr__", [](const TimeOfImpactBatch& b) {
        std::size_t touching = 0, certified = 0;
        for (const TimeOfImpactResult& r : b.results) {
          touching += r.touches;
          certified += r.certified;
        }
        return "TimeOfImpactBatch(rows=" + std::to_string(b.results.size()) +
               ", touching=" + std::to_string(touching) +
               ", certified=" + std::to_string(certified) + ")";
      });

  m.def(
      "time_of_impact",
      [](const py::object& a, const py::object& b, const py::object& pose_a,
         const py::object& pose_b, const py::object& method, const py::object& tolerance,
         const py::object& time_tolerance, const py::object& max_iterations,
         const py::object& motion) {
        const TimeOfImpactOptions options =
            motion_options(method, tolerance, time_tolerance, max_iterations);
        const MotionKind kind = to_motion_kind(motion);
        const RigidMotion motion_a = to_motion(pose_a, "pose_a", kind);
        const RigidMotion motion_b = to_motion(pose_b, "pose_b", kind);
        if (is_compound(a) || is_compound(b)) {
          const CompoundArgument body_a(a, "a");
          const CompoundArgument body_b(b, "b");
          py::gil_scoped_release release;
          return time_of_impact(body_a.get(), motion_a, body_b.get(), motion_b, options);
        }
        const BodyArgument body_a(a, "a");
        const BodyArgument body_b(b, "b");
        py::gil_scoped_release release;
        return time_of_impact(body_a.get(), motion_a, body_b.get(), motion_b, options);
      },
      py::arg("a"), py::arg("b"), py::kw_only(), py::arg("pose_a") = py::none(),
      py::arg("pose_b") = py::none(), py::arg("method") = "exact",
      py::arg("tolerance") = kDefaultTolerance, py::arg("time_tolerance") = kDefaultTimeTolerance,
      py::arg("max_iterations") = kDefaultMotionIterations, py::arg("motion") = "linear",
      "The first contact of A and B moving from their start to their end poses (see "
      "swarmcollide.time_of_impact).");

  m.def("motion_function", &make_motion_function, py::arg("python_path"),
        py::arg("text_signature"), R"doc(
``python_path``, swarmcollide.motion's ``time_of_impact``, as a C++ function with its name,
module, documentation and ``text_signature`` (without annotations): it answers calls between two
ConvexPolyhedron itself, with the conversions of ``_core.time_of_impact``, and hands every other
call (compound bodies, points, calls that raise) to ``python_path``.
)doc");

  m.def(
      "time_of_impact_many",
      [](const py::object& as, const py::object& bs, const py::object& poses_a,
         const py::object& poses_b, const py::object& method, const py::object& tolerance,
         const py::object& time_tolerance, const py::object& max_iterations,
         const py::object& threads, const py::object& motion) {
        const TimeOfImpactOptions options =
            motion_options(method, tolerance, time_tolerance, max_iterations);
        const int thread_number = threads.is_none() ? 0 : thread_count(threads);
        const MotionKind kind = to_motion_kind(motion);
        const std::vector<RigidMotion> motions_a =
            to_motions(poses_a, motion_rows(poses_a), "poses_a", kind);
        const std::vector<RigidMotion> motions_b =
            to_motions(poses_b, motion_rows(poses_b), "poses_b", kind);
        TimeOfImpactBatch batch;
        if (holds_compound(as) || holds_compound(bs) || is_compound(as) || is_compound(bs)) {
          const Side<CompoundBody, CompoundArgument> side_a(as, "As");
          const Side<CompoundBody, CompoundArgument> side_b(bs, "Bs");
          check_rows({{"As", side_a.rows()},
                      {"Bs", side_b.rows()},
                      {"poses_a", motions_a.size()},
                      {"poses_b", motions_b.size()}});
          py::gil_scoped_release release;
          batch.results = time_of_impact_many(side_a.bodies(), motions_a, side_b.bodies(),
                                              motions_b, options, thread_number);
          return batch;
        }
        const Side<ConvexPolyhedron, BodyArgument> side_a(as, "As");
        const Side<ConvexPolyhedron, BodyArgument> side_b(bs, "Bs");
        check_rows({{"As", side_a.rows()},
                    {"Bs", side_b.rows()},
                    {"poses_a", motions_a.size()},
                    {"poses_b", motions_b.size()}});
        py::gil_scoped_release release;
        batch.results = time_of_impact_many(side_a.bodies(), motions_a, side_b.bodies(),
                                            motions_b, options, thread_number);
        return batch;
      },
      py::arg("As"), py::arg("Bs"), py::kw_only(), py::arg("poses_a") = py::none(),
      py::arg("poses_b") = py::none(), py::arg("method") = "exact",
      py::arg("tolerance") = kDefaultTolerance, py::arg("time_tolerance") = kDefaultTimeTolerance,
      py::arg("max_iterations") = kDefaultMotionIterations, py::arg("threads") = py::none(),
      py::arg("motion") = "linear",
      "time_of_impact for every row (see swarmcollide.time_of_impact_many).");
}

}  // namespace swarmcollide::bindings
