#include <sstream>

#include "conversions.hpp"
#include "swarmcollide/solvers/swarm.hpp"

namespace swarmcollide::bindings {

void bind_solvers(py::module_& m) {
  py::class_<ParticleCoefficients>(m, "ParticleCoefficients",
                                   "Inertia weight ``w`` and accelerations ``c1``, ``c2`` of one "
                                   "particle.")
      .def_readonly("w", &ParticleCoefficients::w)
      .def_readonly("c1", &ParticleCoefficients::c1)
      .def_readonly("c2", &ParticleCoefficients::c2)
      .def(pickle_fields<ParticleCoefficients>(
          "ParticleCoefficients", any_values, field("w", &ParticleCoefficients::w),
          field("c1", &ParticleCoefficients::c1), field("c2", &ParticleCoefficients::c2)))
      .def("__repr__", [](const ParticleCoefficients& c) {
        std::ostringstream out;
        out << "ParticleCoefficients(w=" << c.w << ", c1=" << c.c1 << ", c2=" << c.c2 << ")";
        return out.str();
      });
  m.def("rank_adaptive_coefficients", &rank_adaptive_coefficients, py::arg("rank"),
        py::arg("swarm_size"), py::arg("w_min") = 0.4, py::arg("w_max") = 0.9,
        "(8)-(9): ``(w, c1, c2)`` of the particle ranked ``rank`` (1 = best).");
  m.def("linear_decreasing_inertia", &linear_decreasing_inertia, py::arg("iteration"),
        py::arg("max_iterations"), py::arg("w_start") = 0.9, py::arg("w_end") = 0.4,
        "(7): the inertia weight after ``iteration`` of ``max_iterations``.");
}

}  // namespace swarmcollide::bindings
