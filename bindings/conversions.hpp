#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <limits>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "swarmcollide/geometry/compound_body.hpp"
#include "swarmcollide/geometry/convex_polyhedron.hpp"
#include "swarmcollide/geometry/pose.hpp"
#include "swarmcollide/motion/rigid_motion.hpp"
#include "swarmcollide/motion/time_of_impact.hpp"
#include "swarmcollide/types.hpp"

namespace swarmcollide::bindings {

namespace py = pybind11;

/// True for a NumPy masked array (numpy.ma.MaskedArray): an ndarray whose mask NumPy's
/// conversions drop, so that its masked entries would be read as numbers.
bool is_masked(const py::handle& value);

/// TypeError naming `name` for a masked array (is_masked), saying to pass `name.filled(...)` or a
/// plain array.
void refuse_masked(const py::handle& value, const std::string& name);

/// An `(n, 3)` array-like as a vertex matrix; TypeError for non-numeric input, ValueError for a
/// wrong shape. `name` is the argument's name in the messages.
VertexMatrix to_vertex_matrix(const py::handle& points, const char* name);

/// A body argument: a ConvexPolyhedron used in place (no copy), or one built from `(n, 3)`
/// points; errors name the argument `name`.
class BodyArgument {
 public:
  BodyArgument(const py::handle& body, const char* name);
  const ConvexPolyhedron& get() const { return *body_; }

 private:
  std::optional<ConvexPolyhedron> owned_;
  const ConvexPolyhedron* body_;
};

/// True when `body` is a CompoundBody (the argument then needs the compound queries).
bool is_compound(const py::handle& body);

/// True when `bodies` is a sequence (not an array) holding a CompoundBody.
bool holds_compound(const py::handle& bodies);

/// A body argument for the compound queries: a CompoundBody used in place, or a compound body of
/// one part built from a ConvexPolyhedron (sharing its hull) or from `(n, 3)` points.
class CompoundArgument {
 public:
  CompoundArgument(const py::handle& body, const char* name);
  const CompoundBody& get() const { return *body_; }

 private:
  std::optional<CompoundBody> owned_;
  const CompoundBody* body_;
};

/// True for a rotation object from another library (SciPy's Rotation: anything with an
/// `as_matrix()` method that is not itself an array, a list or a tuple).
bool is_rotation(const py::handle& value);

/// A pose argument: None (the identity), a `(4, 4)` homogeneous rigid transform, or a pair
/// `(rotation (3, 3), translation (3,))`; TypeError or ValueError naming `name` otherwise. A
/// rotation given in floats narrower than double (float32, float16) within 84 of their epsilons
/// of a rotation (1e-5 for float32, 0.08 for float16) is taken for the nearest rotation, as
/// to_poses takes it.
Pose to_pose(const py::handle& pose, const char* name);

/// to_pose without its check that the pose is rigid and finite, for a caller that hands it to a
/// query of the core, which checks it under the same name (validate_pose's message) before it
/// reads it: checked twice, a posed sphere-box call from Python took 491 ns where it takes 481.
Pose read_pose(const py::handle& pose, const char* name);

/// `pose` as a `(4, 4)` homogeneous transform.
py::array_t<Scalar> homogeneous(const Pose& pose);

/// Poses for `count` bodies: None (none: every body at the identity), a `(count, 4, 4)` array of
/// homogeneous rigid transforms (or `(count, 3, 4)`, without their last row), a pair
/// `(rotations (count, 3, 3), translations (count, 3))`, or a list or tuple of `count` poses that
/// is not an array of numbers, each read by to_pose as `name[i]`; for one body also a single
/// `(4, 4)` or `(3, 4)` transform or `((3, 3), (3,))` pair. TypeError or ValueError naming `name`
/// (and the offending `name[i]`) for another shape or a last row other than [0, 0, 0, 1]. Whether
/// each pose of an array is a rigid motion is left to the core (Scene, the batches), which names
/// it alike and checks it once.
std::vector<Pose> to_poses(const py::handle& poses, std::size_t count, const char* name);

/// True when `poses` is one pose in a form to_pose reads (a `(4, 4)` or `(3, 4)` transform, a
/// pair whose rotation is a `(3, 3)` matrix or a rotation object, or a rotation object alone)
/// rather than poses for several bodies.
bool is_single_pose(const py::handle& poses);

/// The number of poses an argument of to_poses holds: 0 for None, 1 for a single pose, the
/// leading length of an array of transforms or of a pair (rotations, translations) (a rotation
/// object's length), the length of a list or tuple of poses; 1 for anything else (to_poses then
/// checks it all).
std::size_t pose_count(const py::handle& poses);

/// A 3-vector of real, finite numbers; TypeError (complex numbers, text, objects) or ValueError
/// (a shape other than (3,), NaN or infinity) naming `name` otherwise.
Vector3 finite_vector3(const py::handle& vector, const char* name);

/// A 1-D array of real, finite weights; TypeError or ValueError naming `name` otherwise.
VectorX finite_weights(const py::handle& weights, const char* name);

/// A `threads` argument other than None: an integer in [1, kMaxThreads]; TypeError for another
/// type (bool included), ValueError for a value out of range however large.
int thread_count(const py::handle& threads);

/// A name argument (a method, a broadphase): TypeError naming `name` for anything but a str
/// (bytes included, which pybind11 would otherwise take for a std::string).
std::string to_name(const py::handle& value, const char* name);

/// A `motion` argument ("linear" or "screw"); TypeError for anything but a str, ValueError for
/// another name.
MotionKind to_motion_kind(const py::handle& motion);

/// True for a mesh from another library (an object with a `vertices` attribute, such as
/// trimesh's Trimesh, that is not an array, a sequence or a ConvexPolyhedron).
bool is_mesh(const py::handle& body);

/// `body`'s points when it is a mesh (is_mesh); else `body`.
py::object points_of(const py::handle& body);

/// A curved shape (Cylinder, Cone, Ellipsoid) in its own frame, of its own type.
py::object unplaced_shape(const CurvedShapeParameters& shape);

/// A body as Python sees it: a curved shape as its own Cylinder, Cone or Ellipsoid (a new one of
/// its parameters: the same body, with its parameters and repr); any other body, and a curved
/// shape placed by a pose, as the ConvexPolyhedron it is.
py::object typed_body(const ConvexPolyhedron& body);

/// A body as it was added to a scene: typed_body's, or a Sphere, Capsule or Box when its points
/// and radius are exactly those that class builds. A scene keeps bodies as ConvexPolyhedron,
/// which these shapes are with nothing of their own but their parameters, read back from the
/// points; a polyhedron built from the very points of a box is the same body, and comes back a
/// Box too.
py::object added_body(const ConvexPolyhedron& body);

/// True for a NumPy array of one or more dimensions, which Python's number protocols would turn
/// into a scalar or refuse with NumPy's own message.
bool is_array(const py::handle& value);

/// A real number (Python's or NumPy's) as `name`: TypeError for text, arrays, bools and other
/// types. Its value is checked where it is used.
Scalar to_real(const py::handle& value, const char* name);

/// An integer (Python's or NumPy's) in [least, 2**31 - 1] as `name`: TypeError for another type
/// (bool included), ValueError naming the range for a value outside it however large.
int to_count(const py::handle& value, const char* name, int least);

/// A flag (Python's bool or NumPy's) as `name`: TypeError for anything else.
bool to_bool(const py::handle& value, const char* name);

/// An argument as the caller gave it, for to_bool, to_count, to_real or to_name to check with a
/// message naming it and what it accepts: pybind11's own conversion to `T` would take None or 2
/// for a bool and 2.7 for an int without a word, and refuse "no" or 2**40 with a message naming
/// neither. Signatures and stubs still show `T`.
template <typename T>
struct Given {
  py::object value;
};

/// The name of the type of `object`, for messages.
std::string type_name(const py::handle& object);

/// A motion's status as Python reads it: 'converged', 'max_iterations' or 'unresolved'.
const char* status_name(MotionStatus status);

/// A motion's status from status_name's name; ValueError naming `name` for another.
MotionStatus motion_status(const py::handle& value, const char* name);

/// The first item of every pickled state (a tuple: this number, then the object's fields). A
/// state whose first item differs was written by a version of the library that pickled
/// differently, and is refused.
inline constexpr int kStateVersion = 1;

/// True for a std::vector (which Python gives as a list).
template <typename T>
struct IsVector : std::false_type {};
template <typename T>
struct IsVector<std::vector<T>> : std::true_type {};

/// The state given to a class's `__setstate__`, read item by item: a tuple of kStateVersion and
/// `items` more items. Whatever is wrong with it (not a tuple, another version or length, an item
/// of the wrong type, shape or value) is a ValueError naming the class and the item, never a
/// crash: a state may be corrupted, or come from another program.
class PickledState {
 public:
  PickledState(const py::handle& state, std::string type, std::size_t items);

  /// The next item as `T`: a bool, an integer or a real number (Python's or NumPy's), the
  /// object itself (py::object), else anything pybind11 casts to `T` (an Eigen matrix, a
  /// std::vector, a bound class).
  template <typename T>
  T next(const char* name) {
    return next(name, [name](const py::handle& item) -> T {
      if constexpr (std::is_same_v<T, bool>) {
        return to_bool(item, name);
      } else if constexpr (std::is_integral_v<T>) {
        return integer_of<T>(to_integer(item, name), name);
      } else if constexpr (std::is_floating_point_v<T>) {
        return to_real(item, name);
      } else if constexpr (std::is_same_v<T, py::object>) {
        return py::reinterpret_borrow<py::object>(item);
      } else {
        try {
          return item.cast<T>();
        } catch (const py::cast_error&) {
          throw py::type_error(std::string(name) + " must be " + expected<T>() + ", got " +
                               described(item));
        }
      }
    });
  }

  /// The next item through `read` (a conversion of this file, say), whose errors become this
  /// state's, naming the item.
  template <typename Read>
  auto next(const char* name, const Read& read) {
    const py::handle item = items_[position_++];
    return guarded(name, [&] { return read(item); });
  }

  /// `make()` (a constructor, which validates the values read), its errors this state's.
  template <typename Make>
  auto build(const Make& make) const {
    return guarded("", make);
  }

  /// A ValueError naming the class and `what`.
  py::value_error error(const std::string& what) const;

 private:
  // `run()`, with what it raises for a wrong value (TypeError, ValueError, a constructor's
  // std::invalid_argument) raised as error() naming `item` (unless the message does); other
  // errors pass.
  template <typename Run>
  auto guarded(const std::string& item, const Run& run) const {
    try {
      return run();
    } catch (const py::builtin_exception& wrong) {
      throw error(naming(item, wrong.what()));
    } catch (const std::invalid_argument& wrong) {
      throw error(naming(item, wrong.what()));
    } catch (py::error_already_set& raised) {
      if (!raised.matches(PyExc_TypeError) && !raised.matches(PyExc_ValueError)) throw;
      throw error(naming(item, py::str(raised.value())));
    }
  }
  // `message`, preceded by `item: ` unless it starts with the item's name.
  static std::string naming(const std::string& item, const std::string& message);

  // What an item read as `T` must be, for messages: an array's shape, a list of what, a type.
  template <typename T>
  static std::string expected() {
    if constexpr (std::is_base_of_v<Eigen::EigenBase<T>, T>) {
      const auto length = [](int n) {
        return n == Eigen::Dynamic ? std::string("n") : std::to_string(n);
      };
      return "an array of shape (" + length(T::RowsAtCompileTime) +
             (T::ColsAtCompileTime == 1 ? ",)" : ", " + length(T::ColsAtCompileTime) + ")");
    } else if constexpr (IsVector<T>::value) {
      return "a list, each item " + expected<typename T::value_type>();
    } else if constexpr (std::is_same_v<T, std::string>) {
      return "a str";
    } else if constexpr (std::is_arithmetic_v<T>) {
      return "a number";
    } else if constexpr (std::is_same_v<T, py::tuple>) {
      return "a tuple";
    } else {
      return "a " + std::string(py::str(py::type::of<T>().attr("__name__")));
    }
  }
  // `item`'s type, with an array's shape and dtype or a sequence's length.
  static std::string described(const py::handle& item);

  static py::int_ to_integer(const py::handle& item, const char* name);

  // `value` as a `T`, a ValueError naming `name` and T's range outside it (pybind11's cast
  // refused it with a message naming neither).
  template <typename T>
  static T integer_of(const py::int_& value, const char* name) {
    const py::int_ lowest(std::numeric_limits<T>::min());
    const py::int_ highest(std::numeric_limits<T>::max());
    if (value < lowest || value > highest) {
      throw py::value_error(std::string(name) + " must be an integer from " +
                            std::string(py::str(lowest)) + " to " +
                            std::string(py::str(highest)) + ", got " +
                            std::string(py::str(value)));
    }
    return value.cast<T>();
  }

  py::tuple items_;
  std::string type_;
  std::size_t position_ = 1;
};

/// A member of a struct pickled as it is, with its name for messages.
template <typename Owner, typename Type>
struct Field {
  const char* name;
  Type Owner::*member;
};

/// `member` of an `Owner`, named `name`: pickle_fields' argument.
template <typename Owner, typename Type>
Field<Owner, Type> field(const char* name, Type Owner::*member) {
  return {name, member};
}

/// A struct pickled as its fields, in the order given: the state is (kStateVersion, fields...).
/// `consistent(value)` says what is wrong with a rebuilt value (columns of different lengths,
/// say), or nothing.
template <typename T, typename Consistent, typename... Owners, typename... Types>
auto pickle_fields(const char* type, Consistent consistent, Field<Owners, Types>... fields) {
  return py::pickle(
      // A plain tuple in the signature: typed by its items, a subclass's state (ContactResult's,
      // SceneResult's and more) contradicts its base's in the stubs.
      [fields...](const T& value) {
        return py::tuple(py::make_tuple(kStateVersion, value.*(fields.member)...));
      },
      [type, consistent, fields...](const py::object& state) {
        PickledState items(state, type, sizeof...(Types));
        T value;
        ((value.*(fields.member) = items.next<Types>(fields.name)), ...);
        if (const std::string wrong = consistent(value); !wrong.empty()) throw items.error(wrong);
        return value;
      });
}

/// pickle_fields' `consistent` for a struct whose fields take any values of their types.
inline constexpr auto any_values = [](const auto&) { return std::string(); };

/// The first column whose length differs from the first's, as a message; nothing when all are
/// alike. Each column is its name and its length.
std::string unequal_lengths(std::initializer_list<std::pair<const char*, Eigen::Index>> columns);

/// An instance's own attributes (its `__dict__`: a Python subclass's), empty for an instance of
/// a bound class: pickled with the C++ state, so that a subclass keeps them.
py::dict instance_attributes(const py::handle& instance);

/// The next item of `state` as instance_attributes' dictionary.
py::dict state_attributes(PickledState& state);

}  // namespace swarmcollide::bindings

namespace pybind11::detail {

template <typename T>
struct type_caster<swarmcollide::bindings::Given<T>> {
  PYBIND11_TYPE_CASTER(swarmcollide::bindings::Given<T>, make_caster<T>::name);
  bool load(handle source, bool) {
    value.value = reinterpret_borrow<object>(source);
    return true;
  }
  static handle cast(const swarmcollide::bindings::Given<T>& given, return_value_policy, handle) {
    return given.value.inc_ref();
  }
};

}  // namespace pybind11::detail
