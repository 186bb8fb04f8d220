#include <pybind11/eigen.h>

#include <optional>
#include <string>
#include <vector>

#include "conversions.hpp"
#include "queries.hpp"
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

// Bodies from a sequence of polyhedra or (n, 3) array-likes.
std::vector<ConvexPolyhedron> to_polyhedra(const py::handle& bodies, const char* name,
                                           std::uint64_t first_index) {
  if (py::isinstance<py::str>(bodies) || !py::isinstance<py::iterable>(bodies)) {
    throw py::type_error(std::string(name) +
                         " must be a sequence of polyhedra or an (m, n, 3) array, got " +
                         type_name(bodies));
  }
  std::vector<ConvexPolyhedron> result;
  std::uint64_t index = first_index;
  for (const py::handle body : bodies) {
    const std::string item = std::string(name) + "[" + std::to_string(index++) + "]";
    result.push_back(BodyArgument(body, item.c_str()).get());
  }
  return result;
}

VertexStack view(const Stack& stack, const char* name) {
  return {stack.data(), static_cast<std::size_t>(stack.shape(0)), stack.shape(1), name};
}

BatchSettings settings_of(const py::object& threads, const py::object& first_index, bool escalate) {
  BatchSettings settings;
  settings.escalate = escalate;
  if (!threads.is_none()) {
    settings.threads = thread_count(threads);
  }
  if (PyBool_Check(first_index.ptr()) || !PyIndex_Check(first_index.ptr()) ||
      py::int_(first_index) < py::int_(0)) {
    throw py::value_error("first_index must be a nonnegative integer");
  }
  settings.first_index = py::int_(first_index).cast<std::uint64_t>();
  return settings;
}

BatchPoses poses_of(const py::object& poses_a, const py::object& poses_b, std::size_t count) {
  return {to_poses(poses_a, count, "poses_a"), to_poses(poses_b, count, "poses_b")};
}

// Compound bodies from a sequence of compound bodies, polyhedra or (n, 3) array-likes.
std::vector<CompoundBody> to_compounds(const py::handle& bodies, const char* name,
                                       std::uint64_t first_index) {
  std::vector<CompoundBody> result;
  std::uint64_t index = first_index;
  for (const py::handle body : bodies) {
    const std::string item = std::string(name) + "[" + std::to_string(index++) + "]";
    result.push_back(CompoundArgument(body, item.c_str()).get());
  }
  return result;
}

// `query(as, bs, poses)` without the GIL. Sequences holding a CompoundBody are answered by the
// compound queries. Two (m, n, 3) arrays are passed as vertex stacks, so that the threads build
// and free the bodies; anything else is converted to bodies here first.
template <typename Ask>
BatchResult run(const py::object& as, const py::object& bs, const py::object& poses_a,
                const py::object& poses_b, const BatchSettings& settings, const Ask& ask) {
  if (holds_compound(as) || holds_compound(bs)) {
    const auto bodies_a = to_compounds(as, "As", settings.first_index);
    const auto bodies_b = to_compounds(bs, "Bs", settings.first_index);
    const BatchPoses poses = poses_of(poses_a, poses_b, bodies_a.size());
    py::gil_scoped_release release;
    return ask(bodies_a, bodies_b, poses);
  }
  const std::optional<Stack> stack_a = as_stack(as, "As");
  const std::optional<Stack> stack_b = as_stack(bs, "Bs");
  if (stack_a && stack_b) {
    const BatchPoses poses =
        poses_of(poses_a, poses_b, static_cast<std::size_t>(stack_a->shape(0)));
    py::gil_scoped_release release;
    return ask(view(*stack_a, "As"), view(*stack_b, "Bs"), poses);
  }
  const auto bodies_a = to_polyhedra(as, "As", settings.first_index);
  const auto bodies_b = to_polyhedra(bs, "Bs", settings.first_index);
  const BatchPoses poses = poses_of(poses_a, poses_b, bodies_a.size());
  py::gil_scoped_release release;
  return ask(bodies_a, bodies_b, poses);
}

constexpr const char* kBatchDoc = R"doc(
The query for every pair ``(As[i], Bs[i])``, in C++ threads without the GIL.

Pair i is seeded with ``pair_seed(seed, first_index + i)``, so answers do not depend on the
number of threads or on how a batch is split. ``As`` and ``Bs`` are sequences of polyhedra or
``(n, 3)`` arrays (or compound bodies), or ``(m, n, 3)`` arrays (the fastest: each pair's bodies are then built and
freed by the thread that answers it). ``poses_a`` and ``poses_b`` place them: None (the identity),
an ``(m, 4, 4)`` array of rigid transforms or a pair ``(rotations (m, 3, 3), translations (m, 3))``.
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
      .def_readonly("distance", &BatchResult::distance)
      .def_readonly("lower_bound", &BatchResult::lower_bound)
      .def_readonly("point_a", &BatchResult::point_a)
      .def_readonly("point_b", &BatchResult::point_b)
      .def_readonly("direction", &BatchResult::direction)
      .def_readonly("colliding", &BatchResult::colliding)
      .def_readonly("certified", &BatchResult::certified)
      .def_readonly("iterations", &BatchResult::iterations)
      .def_readonly("escalated", &BatchResult::escalated)
      .def_readonly("part_a", &BatchResult::part_a)
      .def_readonly("part_b", &BatchResult::part_b)
      .def("__len__", [](const BatchResult& r) { return r.distance.size(); })
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
             const py::object& first_index, bool escalate, const py::object& poses_a,
             const py::object& poses_b) {
            const BatchSettings settings = settings_of(threads, first_index, escalate);
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
