#include <pybind11/eigen.h>

#include <optional>
#include <string>
#include <vector>

#include "conversions.hpp"
#include "swarmcollide/queries/batch.hpp"

namespace swarmcollide::bindings {

namespace {

using Stack = py::array_t<Scalar, py::array::c_style | py::array::forcecast>;

// An (m, n, 3) array as a C-contiguous array of doubles; nothing for anything else.
std::optional<Stack> as_stack(const py::handle& bodies, const char* name) {
  if (!py::isinstance<py::array>(bodies) || bodies.cast<py::array>().ndim() != 3) {
    return std::nullopt;
  }
  auto stack = Stack::ensure(bodies);
  if (!stack || stack.shape(2) != 3 || stack.shape(1) == 0) {
    throw py::value_error(std::string(name) + " must have shape (m, n, 3) with n >= 1");
  }
  return stack;
}

// Bodies from a sequence of polyhedra or (n, 3) array-likes, or from an (m, n, 3) array.
std::vector<ConvexPolyhedron> to_polyhedra(const py::handle& bodies, const char* name) {
  std::vector<ConvexPolyhedron> result;
  if (const std::optional<Stack> stack = as_stack(bodies, name)) {
    const auto n = stack->shape(1);
    result.reserve(static_cast<std::size_t>(stack->shape(0)));
    for (py::ssize_t i = 0; i < stack->shape(0); ++i) {
      try {
        result.emplace_back(Eigen::Map<const VertexMatrix>(stack->data(i, 0, 0), n, 3));
      } catch (const std::invalid_argument& error) {
        throw py::value_error(std::string(name) + "[" + std::to_string(i) + "]: " + error.what());
      }
    }
    return result;
  }
  if (py::isinstance<py::str>(bodies) || !py::isinstance<py::iterable>(bodies)) {
    throw py::type_error(std::string(name) +
                         " must be a sequence of polyhedra or an (m, n, 3) array, got " +
                         std::string(py::str(bodies.get_type().attr("__name__"))));
  }
  std::size_t index = 0;
  for (const py::handle body : bodies) {
    const std::string item = std::string(name) + "[" + std::to_string(index++) + "]";
    result.push_back(to_polyhedron(body, item.c_str()));
  }
  return result;
}

int to_threads(const py::object& threads) { return threads.is_none() ? 0 : threads.cast<int>(); }

VertexStack view(const Stack& stack, const char* name) {
  return {stack.data(), static_cast<std::size_t>(stack.shape(0)), stack.shape(1), name};
}

// `query(as, bs)` without the GIL. Two (m, n, 3) arrays are passed as vertex stacks, so that the
// threads build and free the bodies; anything else is converted to bodies here first.
template <typename Query>
BatchResult run(const py::object& as, const py::object& bs, const Query& query) {
  const std::optional<Stack> stack_a = as_stack(as, "As");
  const std::optional<Stack> stack_b = as_stack(bs, "Bs");
  if (stack_a && stack_b) {
    py::gil_scoped_release release;
    return query(view(*stack_a, "As"), view(*stack_b, "Bs"));
  }
  const auto bodies_a = to_polyhedra(as, "As");
  const auto bodies_b = to_polyhedra(bs, "Bs");
  py::gil_scoped_release release;
  return query(bodies_a, bodies_b);
}

}  // namespace

void bind_batch(py::module_& m) {
  py::class_<BatchResult>(m, "BatchResult", R"doc(
Answers to many queries, one entry (or row) per pair, as NumPy arrays.

Attributes
----------
distance, lower_bound : numpy.ndarray, shape (m,)
point_a, point_b : numpy.ndarray, shape (m, 3)
colliding, certified, escalated : numpy.ndarray of bool, shape (m,)
iterations : numpy.ndarray of int, shape (m,)
)doc")
      .def_readonly("distance", &BatchResult::distance)
      .def_readonly("lower_bound", &BatchResult::lower_bound)
      .def_readonly("point_a", &BatchResult::point_a)
      .def_readonly("point_b", &BatchResult::point_b)
      .def_readonly("colliding", &BatchResult::colliding)
      .def_readonly("certified", &BatchResult::certified)
      .def_readonly("iterations", &BatchResult::iterations)
      .def_readonly("escalated", &BatchResult::escalated)
      .def("__len__", [](const BatchResult& r) { return r.distance.size(); })
      .def("__repr__", [](const BatchResult& r) {
        return "BatchResult(" + std::to_string(r.distance.size()) + " pairs, " +
               std::to_string(r.colliding.count()) + " colliding, " +
               std::to_string(r.certified.count()) + " certified)";
      });

  m.def(
      "distance_many",
      [](const py::object& as, const py::object& bs, const DistanceOptions& options,
         const py::object& threads) {
        const int count = to_threads(threads);
        return run(as, bs, [&](const auto& a, const auto& b) {
          return distance_many(a, b, options, count);
        });
      },
      py::arg("As"), py::arg("Bs"), py::arg("options"), py::arg("threads"));
  m.def(
      "collide_many",
      [](const py::object& as, const py::object& bs, const DistanceOptions& options, bool escalate,
         const py::object& threads) {
        const int count = to_threads(threads);
        return run(as, bs, [&](const auto& a, const auto& b) {
          return collide_many(a, b, options, escalate, count);
        });
      },
      py::arg("As"), py::arg("Bs"), py::arg("options"), py::arg("escalate"), py::arg("threads"));
  m.def("pair_seed", &pair_seed, py::arg("seed"), py::arg("index"),
        "The seed of pair ``index`` in a batch seeded with ``seed``.");
}

}  // namespace swarmcollide::bindings
