#include <pybind11/eigen.h>

#include "conversions.hpp"
#include "swarmcollide/problem/certificate.hpp"
#include "swarmcollide/problem/distance_model.hpp"
#include "swarmcollide/problem/simplex.hpp"

namespace swarmcollide::bindings {

void bind_problem(py::module_& m) {
  m.def(
      "objective",
      [](const py::object& a, const py::object& b, const py::object& lambda,
         const py::object& delta) {
        return objective(BodyArgument(a, "a").get(), BodyArgument(b, "b").get(),
                         finite_weights(lambda, "weights_a"), finite_weights(delta, "weights_b"));
      },
      py::arg("a"), py::arg("b"), py::arg("weights_a"), py::arg("weights_b"), R"doc(
Objective (5): ``|| sum_j weights_b[j] y_j - sum_i weights_a[i] x_i ||``.

The weights need not be feasible; see ``constraint_violation`` and ``is_feasible``.
)doc");
  m.def(
      "constraint_violation",
      [](const py::object& lambda, const py::object& delta) {
        return constraint_violation(finite_weights(lambda, "weights_a"),
                                    finite_weights(delta, "weights_b"));
      },
      py::arg("weights_a"), py::arg("weights_b"),
      "Constraint violation (6): ``(sum(weights_a) - 1)**2 + (sum(weights_b) - 1)**2``.");
  m.def(
      "is_feasible",
      [](const py::object& lambda, const py::object& delta, Scalar tolerance) {
        return is_feasible(finite_weights(lambda, "weights_a"), finite_weights(delta, "weights_b"),
                           tolerance);
      },
      py::arg("weights_a"), py::arg("weights_b"), py::arg("tolerance") = 1e-10,
      "True when all weights lie in [0, 1] and the violation (6) is at most ``tolerance``.");
  m.def(
      "separation",
      [](const py::object& a, const py::object& b, const py::object& direction) {
        return separation(BodyArgument(a, "a").get(), BodyArgument(b, "b").get(),
                          finite_vector3(direction, "direction"));
      },
      py::arg("a"), py::arg("b"), py::arg("direction"), R"doc(
Separation of A and B along ``direction``: ``min_j n.y_j - max_i n.x_i`` for the unit ``n``.

Every direction gives a lower bound on the distance; the best direction gives the distance itself
when the bodies are apart.

Examples
--------
>>> import swarmcollide as sc
>>> a = sc.ConvexPolyhedron([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]])
>>> b = sc.ConvexPolyhedron([[3, 0, 0], [4, 0, 0], [3, 1, 0], [3, 0, 1]])
>>> sc.separation(a, b, [1, 0, 0])
2.0
)doc");
  m.def(
      "project_onto_simplex",
      [](const py::object& weights) {
        return VectorX(project_onto_simplex(finite_weights(weights, "weights")));
      },
      py::arg("weights"), "Euclidean projection onto the probability simplex.");
}

}  // namespace swarmcollide::bindings
