#include <pybind11/eigen.h>

#include <algorithm>
#include <cstdint>
#include <deque>
#include <initializer_list>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "conversions.hpp"
#include "queries.hpp"
#include "signals.hpp"
#include "swarmcollide/queries/batch.hpp"

namespace swarmcollide::bindings {

namespace {

using Stack = py::array_t<Scalar, py::array::c_style | py::array::forcecast>;

// An (m, n, 3) array of real numbers as a C-contiguous array of doubles; nothing for anything
// that is not a 3-D array.
std::optional<Stack> as_stack(const py::handle& bodies, const char* name) {
  if (!py::isinstance<py::array>(bodies) || bodies.cast<py::array>().ndim() != 3) {
    return std::nullopt;
  }
  refuse_masked(bodies, name);
  const py::array array = bodies.cast<py::array>();
  const char kind = array.dtype().kind();
  if (kind != 'f' && kind != 'i' && kind != 'u') {
    throw py::type_error(std::string(name) + " must hold real numbers, got an array of dtype " +
                         std::string(py::str(array.dtype())));
  }
  auto stack = Stack::ensure(array);
  if (!stack || stack.shape(2) != 3 || stack.shape(1) == 0) {
    throw py::value_error(std::string(name) + " must have shape (m, n, 3) with n >= 1");
  }
  return stack;
}

// True when `bodies` is one body for every row: a ConvexPolyhedron, a CompoundBody, an (n, 3)
// NumPy array (a nested list stays a sequence of bodies) or a mesh such as a trimesh.Trimesh.
bool is_single(const py::handle& bodies) {
  if (py::isinstance<py::array>(bodies)) return bodies.cast<py::array>().ndim() == 2;
  return py::isinstance<ConvexPolyhedron>(bodies) || is_compound(bodies) || is_mesh(bodies);
}

// One side of a batch as the core reads it: the bodies where Python holds them (kept alive here
// while the GIL is released), and those built here from points; a single body serves every row.
// `Argument` is BodyArgument or CompoundArgument, which use a body in place or build one.
template <typename Body, typename Argument>
class BatchSide {
 public:
  BatchSide(const py::handle& bodies, const char* name, std::uint64_t first_index) {
    if (is_single(bodies)) {
      keep_ = py::reinterpret_borrow<py::object>(bodies);
      const Body& body = arguments_.emplace_back(bodies, name).get();
      bodies_.emplace(body);
      return;
    }
    if (py::isinstance<py::str>(bodies) || !py::isinstance<py::iterable>(bodies)) {
      throw py::type_error(std::string(name) +
                           " must be a body (for every row), a sequence of bodies or an (m, n, 3) "
                           "array, got " +
                           type_name(bodies));
    }
    // A tuple of the items holds them even if the caller's sequence changes meanwhile.
    const py::tuple items(py::reinterpret_borrow<py::object>(bodies));
    keep_ = items;
    std::vector<const Body*> pointers;
    pointers.reserve(items.size());
    std::uint64_t index = first_index;
    for (const py::handle body : items) {
      const std::string item = std::string(name) + "[" + std::to_string(index++) + "]";
      pointers.push_back(&arguments_.emplace_back(body, item.c_str()).get());
    }
    bodies_.emplace(std::move(pointers));
  }

  const BatchBodies<Body>& get() const { return *bodies_; }

 private:
  py::object keep_;
  // A deque never moves its items, which point into themselves when they own their body.
  std::deque<Argument> arguments_;
  std::optional<BatchBodies<Body>> bodies_;
};

using ConvexSide = BatchSide<ConvexPolyhedron, BodyArgument>;
using CompoundSide = BatchSide<CompoundBody, CompoundArgument>;

VertexStack view(const Stack& stack, const char* name) {
  return {stack.data(), static_cast<std::size_t>(stack.shape(0)), stack.shape(1), name};
}

BatchSettings settings_of(const py::object& threads, const py::object& first_index, bool escalate) {
  BatchSettings settings;
  settings.escalate = escalate;
  if (!threads.is_none()) {
    settings.threads = thread_count(threads);
  }
  // Seeds are 64-bit: past 2**64 - 1 the conversion below failed with pybind11's cast error.
  if (PyBool_Check(first_index.ptr()) || !PyIndex_Check(first_index.ptr()) ||
      py::int_(first_index) < py::int_(0) ||
      py::int_(first_index) > py::int_(std::numeric_limits<std::uint64_t>::max())) {
    throw py::value_error("first_index must be a nonnegative integer below 2**64");
  }
  settings.first_index = py::int_(first_index).cast<std::uint64_t>();
  return settings;
}

// The rows of a batch whose sides hold `count_a` and `count_b` bodies (0 for a single body): the
// length of a sequence, or with single bodies on both sides the number of poses (one without).
std::size_t row_count(std::size_t count_a, std::size_t count_b, const py::object& poses_a,
                      const py::object& poses_b) {
  if (count_a > 0 || count_b > 0) return std::max(count_a, count_b);
  const std::size_t posed = std::max(pose_count(poses_a), pose_count(poses_b));
  return posed > 0 ? posed : 1;
}

template <typename Side>
std::size_t rows_given(const Side& side) {
  return side.get().single() ? 0 : side.get().size();
}

// `value` when it is an aligned, C-contiguous float64 NumPy array of `shape`, which can be read
// in place.
std::optional<py::array> doubles_in_place(const py::handle& value,
                                          std::initializer_list<py::ssize_t> shape) {
  // A masked array goes the general way (to_poses), which refuses it.
  if (!py::isinstance<py::array>(value) || is_masked(value)) return std::nullopt;
  const py::array array = py::reinterpret_borrow<py::array>(value);
  if (!array.dtype().is(py::dtype::of<Scalar>()) || !(array.flags() & py::array::c_style) ||
      array.ndim() != static_cast<py::ssize_t>(shape.size()) ||
      reinterpret_cast<std::uintptr_t>(array.data()) % alignof(Scalar) != 0) {
    return std::nullopt;
  }
  py::ssize_t axis = 0;
  for (py::ssize_t length : shape) {
    if (array.shape(axis++) != length) return std::nullopt;
  }
  return array;
}

// The poses of `count` rows read in place, for the forms that need no conversion: an (m, 4, 4)
// array of transforms whose last rows are all [0, 0, 0, 1], an (m, 3, 4) one, or a pair of
// (m, 3, 3) rotations and (m, 3) translations, all C-contiguous float64. Nothing for any other
// form: to_poses converts it, or names what is wrong with it. `keep` holds the arrays read. Copying
// the poses would cost more than many rows do (a pass over them while the GIL is held, and fresh
// memory); the core validates each pose where it answers its row, as it does a copied one.
std::optional<PoseArray> pose_array(const py::handle& given, std::size_t count,
                                    std::vector<py::object>& keep) {
  const auto m = static_cast<py::ssize_t>(count);
  if (PyTuple_Check(given.ptr()) || PyList_Check(given.ptr())) {
    const py::sequence parts = py::reinterpret_borrow<py::sequence>(given);
    if (parts.size() != 2) return std::nullopt;
    const auto rotations = doubles_in_place(parts[0], {m, 3, 3});
    const auto translations = doubles_in_place(parts[1], {m, 3});
    if (!rotations || !translations) return std::nullopt;
    keep.push_back(*rotations);
    keep.push_back(*translations);
    return PoseArray{static_cast<const Scalar*>(rotations->data()),
                     static_cast<const Scalar*>(translations->data()), count, 9, 3, 3, 1};
  }
  for (const py::ssize_t rows : {4, 3}) {
    const auto transforms = doubles_in_place(given, {m, rows, 4});
    if (!transforms) continue;
    const auto* data = static_cast<const Scalar*>(transforms->data());
    if (rows == 4) {
      for (std::size_t i = 0; i < count; ++i) {
        const Scalar* last = data + 16 * i + 12;
        if (!(last[0] == 0 && last[1] == 0 && last[2] == 0 && last[3] == 1)) return std::nullopt;
      }
    }
    keep.push_back(*transforms);
    return PoseArray{data, data + 3, count, rows * 4, 4, rows * 4, 4};
  }
  return std::nullopt;
}

// A single pose for all `count` rows, as a single body serves every row: stored once (held in
// `keep`) and read by every row, its strides zero.
PoseArray every_row(const py::handle& given, std::size_t count, const char* name,
                    std::vector<py::object>& keep) {
  const Pose pose = to_pose(given, name);
  py::array_t<Scalar> stored(12);
  Scalar* const data = stored.mutable_data();
  Eigen::Map<Eigen::Matrix<Scalar, 3, 3, Eigen::RowMajor>> rotation(data);
  Eigen::Map<Vector3> translation(data + 9);
  rotation = pose.rotation;
  translation = pose.translation;
  keep.push_back(stored);
  return PoseArray{data, data + 9, count, 0, 3, 0, 1};
}

// One side's poses for `count` rows: into `array` when read in place or given once for every
// row, else converted into `list`.
void read_poses(const py::object& given, std::size_t count, const char* name,
                std::vector<py::object>& keep, PoseArray& array, std::vector<Pose>& list) {
  if (const auto in_place = pose_array(given, count, keep)) {
    array = *in_place;
  } else if (count != 1 && is_single_pose(given)) {
    array = every_row(given, count, name, keep);
  } else {
    list = to_poses(given, count, name);
  }
}

BatchPoses poses_of(const py::object& poses_a, const py::object& poses_b, std::size_t count,
                    std::vector<py::object>& keep) {
  BatchPoses poses;
  read_poses(poses_a, count, "poses_a", keep, poses.array_a, poses.a);
  read_poses(poses_b, count, "poses_b", keep, poses.array_b, poses.b);
  return poses;
}

// True when `bodies` is a CompoundBody or a sequence holding one.
bool compound_side(const py::handle& bodies) {
  return is_compound(bodies) || holds_compound(bodies);
}

// `query(as, bs, poses)` without the GIL, stopped by Ctrl-C (interruptible: the calling thread's
// rows check for it, and the other threads' rows stop with them). A CompoundBody on either side
// (alone or in a sequence) makes it a compound batch. Two (m, n, 3) arrays are passed as vertex
// stacks, so that the threads build and free the bodies; other bodies are read where they are,
// and points converted to bodies here first. A single body on a side serves every row. When the
// sequences of the two sides differ in length the core names both lengths; the poses are
// converted for the sides' rows.
template <typename Ask>
BatchResult run(const py::object& as, const py::object& bs, const py::object& poses_a,
                const py::object& poses_b, const BatchSettings& settings, const Ask& ask) {
  // The pose arrays read in place, held until the GIL is back.
  std::vector<py::object> keep;
  if (compound_side(as) || compound_side(bs)) {
    const CompoundSide side_a(as, "As", settings.first_index);
    const CompoundSide side_b(bs, "Bs", settings.first_index);
    const BatchPoses poses =
        poses_of(poses_a, poses_b,
                 row_count(rows_given(side_a), rows_given(side_b), poses_a, poses_b), keep);
    return interruptible([&] {
      py::gil_scoped_release release;
      return ask(side_a.get(), side_b.get(), poses);
    });
  }
  const std::optional<Stack> stack_a = as_stack(as, "As");
  const std::optional<Stack> stack_b = as_stack(bs, "Bs");
  if (stack_a && stack_b) {
    const BatchPoses poses =
        poses_of(poses_a, poses_b, static_cast<std::size_t>(stack_a->shape(0)), keep);
    return interruptible([&] {
      py::gil_scoped_release release;
      return ask(view(*stack_a, "As"), view(*stack_b, "Bs"), poses);
    });
  }
  const ConvexSide side_a(as, "As", settings.first_index);
  const ConvexSide side_b(bs, "Bs", settings.first_index);
  const BatchPoses poses = poses_of(
      poses_a, poses_b, row_count(rows_given(side_a), rows_given(side_b), poses_a, poses_b), keep);
  return interruptible([&] {
    py::gil_scoped_release release;
    return ask(side_a.get(), side_b.get(), poses);
  });
}

// A getter of one of a BatchResult's arrays as a read-only NumPy view of it, which keeps the
// result alive.
template <typename Map>
py::cpp_function read_only(Map BatchResult::*field) {
  using Plain = typename Map::PlainObject;
  using Constant = Eigen::Map<const Plain>;
  return py::cpp_function(
      [field](const BatchResult& result) {
        const Map& values = result.*field;
        return Constant(values.data(), values.rows(), values.cols());
      },
      py::return_value_policy::reference_internal);
}

// A column of a BatchResult, copied out of its block (pickled as its own array).
template <typename Map>
typename Map::PlainObject copied(const Map& column) {
  return column;
}

// Column `name` of a pickled BatchResult into `column`, which has `rows` rows like the others.
template <typename Map>
void read_column(PickledState& items, const char* name, Map& column) {
  const auto values = items.next<typename Map::PlainObject>(name);
  if (values.rows() != column.rows()) {
    throw items.error(unequal_lengths({{"distance", column.rows()}, {name, values.rows()}}));
  }
  column = values;
}

py::tuple batch_state(const BatchResult& r) {
  return py::make_tuple(kStateVersion, copied(r.distance), copied(r.lower_bound),
                        copied(r.point_a), copied(r.point_b), copied(r.direction),
                        copied(r.colliding), copied(r.certified), copied(r.iterations),
                        copied(r.escalated), copied(r.part_a), copied(r.part_b));
}

BatchResult batch_from_state(const py::object& state) {
  PickledState items(state, "BatchResult", 11);
  const auto distance = items.next<VectorX>("distance");
  BatchResult r(static_cast<std::size_t>(distance.size()));
  r.distance = distance;
  read_column(items, "lower_bound", r.lower_bound);
  read_column(items, "point_a", r.point_a);
  read_column(items, "point_b", r.point_b);
  read_column(items, "direction", r.direction);
  read_column(items, "colliding", r.colliding);
  read_column(items, "certified", r.certified);
  read_column(items, "iterations", r.iterations);
  read_column(items, "escalated", r.escalated);
  read_column(items, "part_a", r.part_a);
  read_column(items, "part_b", r.part_b);
  return r;
}

constexpr const char* kBatchDoc = R"doc(
The query for every row ``(As[i], Bs[i])``, in C++ threads without the GIL.

Row i is seeded with ``pair_seed(seed, first_index + i)``, so answers do not depend on the
number of threads or on how a batch is split. ``As`` and ``Bs`` are each a single body used in
every row (a ConvexPolyhedron, a CompoundBody or an ``(n, 3)`` NumPy array, never copied, or a
mesh such as a ``trimesh.Trimesh``: its vertices' hull), a sequence of bodies (polyhedra,
compound bodies or ``(n, 3)`` arrays), or an ``(m, n, 3)`` array (each row's bodies then built
and freed by the thread that answers it). ``poses_a`` and ``poses_b`` place them: None (the
identity), an ``(m, 4, 4)`` or ``(m, 3, 4)`` array of rigid transforms, a pair
``(rotations (m, 3, 3), translations (m, 3))`` or a list of m poses (each as ``distance`` takes
it); a single pose serves every row, as a single body does. With a single body on both sides the
poses set the number of rows: "A against B at these m poses" is one call.
)doc";

}  // namespace

void bind_batch(py::module_& m, py::class_<Query>& query) {
  py::class_<BatchResult>(m, "BatchResult", R"doc(
Answers to many queries, one entry (or row) per pair, as NumPy arrays.

Attributes
----------
distance, lower_bound : numpy.ndarray, shape (m,)
point_a, point_b, direction : numpy.ndarray, shape (m, 3)
colliding, certified, escalated : numpy.ndarray of bool, shape (m,)
iterations : numpy.ndarray of int, shape (m,)
part_a, part_b : numpy.ndarray of int, shape (m,)
    The parts of compound bodies that realise each answer (0 for convex bodies).
)doc")
      .def_property_readonly("distance", read_only(&BatchResult::distance))
      .def_property_readonly("lower_bound", read_only(&BatchResult::lower_bound))
      .def_property_readonly("point_a", read_only(&BatchResult::point_a))
      .def_property_readonly("point_b", read_only(&BatchResult::point_b))
      .def_property_readonly("direction", read_only(&BatchResult::direction))
      .def_property_readonly("colliding", read_only(&BatchResult::colliding))
      .def_property_readonly("certified", read_only(&BatchResult::certified))
      .def_property_readonly("iterations", read_only(&BatchResult::iterations))
      .def_property_readonly("escalated", read_only(&BatchResult::escalated))
      .def_property_readonly("part_a", read_only(&BatchResult::part_a))
      .def_property_readonly("part_b", read_only(&BatchResult::part_b))
      .def("__len__", &BatchResult::rows)
      .def(py::pickle(&batch_state, &batch_from_state))
      .def("__repr__", [](const BatchResult& r) {
        return "BatchResult(" + std::to_string(r.distance.size()) + " pairs, " +
               std::to_string(r.colliding.count()) + " colliding, " +
               std::to_string(r.certified.count()) + " certified)";
      });

  query
      .def(
          "distance_many",
          [](const Query& q, const py::object& as, const py::object& bs, const py::object& threads,
             const py::object& first_index, const py::object& poses_a, const py::object& poses_b) {
            const BatchSettings settings = settings_of(threads, first_index, true);
            return run(as, bs, poses_a, poses_b, settings,
                       [&](const auto& a, const auto& b, const BatchPoses& poses) {
                         return distance_many(a, b, q.options(), settings, poses);
                       });
          },
          py::arg("As"), py::arg("Bs"), py::arg("threads") = py::none(), py::arg("first_index") = 0,
          py::arg("poses_a") = py::none(), py::arg("poses_b") = py::none(), kBatchDoc)
      .def(
          "collide_many",
          [](const Query& q, const py::object& as, const py::object& bs, const py::object& threads,
             const py::object& first_index, const Given<bool>& escalate,
             const py::object& poses_a, const py::object& poses_b) {
            const BatchSettings settings =
                settings_of(threads, first_index, to_bool(escalate.value, "escalate"));
            return run(as, bs, poses_a, poses_b, settings,
                       [&](const auto& a, const auto& b, const BatchPoses& poses) {
                         return collide_many(a, b, q.options(), settings, poses);
                       });
          },
          py::arg("As"), py::arg("Bs"), py::arg("threads") = py::none(), py::arg("first_index") = 0,
          py::arg("escalate") = true, py::arg("poses_a") = py::none(),
          py::arg("poses_b") = py::none(), kBatchDoc)
      .def(
          "signed_distance_many",
          [](const Query& q, const py::object& as, const py::object& bs, const py::object& threads,
             const py::object& first_index, const py::object& poses_a, const py::object& poses_b) {
            const BatchSettings settings = settings_of(threads, first_index, true);
            return run(as, bs, poses_a, poses_b, settings,
                       [&](const auto& a, const auto& b, const BatchPoses& poses) {
                         return signed_distance_many(a, b, q.options(), settings, poses);
                       });
          },
          py::arg("As"), py::arg("Bs"), py::arg("threads") = py::none(), py::arg("first_index") = 0,
          py::arg("poses_a") = py::none(), py::arg("poses_b") = py::none(), kBatchDoc);
  m.def("pair_seed", &pair_seed, py::arg("seed"), py::arg("index"),
        "The seed of the pair with global index ``index`` in a batch seeded with ``seed``.");
}

}  // namespace swarmcollide::bindings
