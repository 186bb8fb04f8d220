#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <sstream>

#include "conversions.hpp"
#include "swarmcollide/solvers/distance_result.hpp"
#include "swarmcollide/solvers/dual_options.hpp"
#include "swarmcollide/solvers/exact_options.hpp"
#include "swarmcollide/solvers/penalty_options.hpp"
#include "swarmcollide/solvers/swarm.hpp"

namespace swarmcollide::bindings {

namespace {

std::string status_name(SolverStatus status) {
  switch (status) {
    case SolverStatus::converged:
      return "converged";
    case SolverStatus::max_iterations:
      return "max_iterations";
    case SolverStatus::exact:
      return "exact";
  }
  return "unknown";
}

std::string repr(const DistanceResult& r) {
  std::ostringstream out;
  out.precision(6);
  out << "DistanceResult(method='" << r.method << "'";
  if (!r.escalated_from.empty()) out << ", escalated_from='" << r.escalated_from << "'";
  out << ", distance=" << r.distance << ", lower_bound=" << r.lower_bound
      << ", colliding=" << (r.colliding ? "True" : "False")
      << ", certified=" << (r.certified ? "True" : "False") << ", iterations=" << r.iterations
      << ", status='" << status_name(r.status) << "')";
  return out.str();
}

py::array_t<Scalar> as_array(const std::vector<Scalar>& values) {
  return py::array_t<Scalar>(static_cast<py::ssize_t>(values.size()), values.data());
}

}  // namespace

void bind_solvers(py::module_& m) {
  py::enum_<InertiaStrategy>(m, "InertiaStrategy",
                             "How inertia and acceleration are chosen: rank-adaptive (8)-(9) or "
                             "linearly decreasing (7).")
      .value("rank_adaptive", InertiaStrategy::rank_adaptive)
      .value("linear_decreasing", InertiaStrategy::linear_decreasing);
  py::enum_<ConstraintHandling>(m, "ConstraintHandling",
                                "How particles meet the constraints of model (2).")
      .value("feasibility", ConstraintHandling::feasibility)
      .value("projection", ConstraintHandling::projection);

  py::class_<SwarmOptions>(m, "SwarmOptions",
                           "Parameters of the swarm solvers; defaults are the paper's.")
      .def(py::init<>())
      .def_readwrite("inertia", &SwarmOptions::inertia)
      .def_readwrite("constraint_handling", &SwarmOptions::constraint_handling)
      .def_readwrite("swarm_size", &SwarmOptions::swarm_size)
      .def_readwrite("max_iterations", &SwarmOptions::max_iterations)
      .def_readwrite("w_min", &SwarmOptions::w_min)
      .def_readwrite("w_max", &SwarmOptions::w_max)
      .def_readwrite("c1", &SwarmOptions::c1)
      .def_readwrite("c2", &SwarmOptions::c2)
      .def_readwrite("velocity_limit", &SwarmOptions::velocity_limit)
      .def_readwrite("tolerance", &SwarmOptions::tolerance)
      .def_readwrite("feasibility_tolerance", &SwarmOptions::feasibility_tolerance)
      .def_readwrite("seed", &SwarmOptions::seed)
      .def("validate", &SwarmOptions::validate,
           "Raise ValueError naming the first invalid parameter.");

  py::class_<PenaltyOptions>(m, "PenaltyOptions",
                             "Parameters of the exterior quadratic penalty baseline.")
      .def(py::init<>())
      .def_readwrite("initial_weight", &PenaltyOptions::initial_weight)
      .def_readwrite("growth_factor", &PenaltyOptions::growth_factor)
      .def_readwrite("outer_iterations", &PenaltyOptions::outer_iterations)
      .def_readwrite("inner_iterations", &PenaltyOptions::inner_iterations)
      .def_readwrite("tolerance", &PenaltyOptions::tolerance)
      .def("validate", &PenaltyOptions::validate,
           "Raise ValueError naming the first invalid parameter.");

  py::class_<DualOptions>(m, "DualOptions", R"doc(
Parameters of the dual swarm (method ``"dual"``): the paper's rank-adaptive swarm over unit
directions, with an exact finish on the supporting features.

``tolerance`` is absolute; 0 (the default) means ``relative_tolerance`` times the bodies' size.
``feature_tolerance`` is relative to the bodies' size.
)doc")
      .def(py::init<>())
      .def_readwrite("swarm_size", &DualOptions::swarm_size)
      .def_readwrite("max_iterations", &DualOptions::max_iterations)
      .def_readwrite("w_min", &DualOptions::w_min)
      .def_readwrite("w_max", &DualOptions::w_max)
      .def_readwrite("tolerance", &DualOptions::tolerance)
      .def_readwrite("relative_tolerance", &DualOptions::relative_tolerance)
      .def_readwrite("feature_tolerance", &DualOptions::feature_tolerance)
      .def_readwrite("max_rounds", &DualOptions::max_rounds)
      .def_readwrite("seed", &DualOptions::seed)
      .def("validate", &DualOptions::validate,
           "Raise ValueError naming the first invalid parameter.");

  py::enum_<PenetrationAlgorithm>(m, "PenetrationAlgorithm",
                                  "libccd's penetration routine: EPA or MPR.")
      .value("epa", PenetrationAlgorithm::epa)
      .value("mpr", PenetrationAlgorithm::mpr);

  py::class_<ExactOptions>(m, "ExactOptions", "Parameters of the exact reference methods.")
      .def(py::init<>())
      .def_readwrite("distance_tolerance", &ExactOptions::distance_tolerance)
      .def_readwrite("penetration_tolerance", &ExactOptions::penetration_tolerance)
      .def_readwrite("max_iterations", &ExactOptions::max_iterations)
      .def_readwrite("tolerance", &ExactOptions::tolerance)
      .def_readwrite("penetration", &ExactOptions::penetration)
      .def("validate", &ExactOptions::validate,
           "Raise ValueError naming the first invalid parameter.");

  py::class_<DistanceResult>(m, "DistanceResult", R"doc(
The answer of every distance query, whatever the method.

``lower_bound <= true distance <= distance`` always holds: ``distance`` is achieved by the witness
points ``point_a`` and ``point_b`` (convex combinations of the bodies' points with ``weights_a``
and ``weights_b``), and ``lower_bound`` is the separation along ``direction``.
)doc")
      .def_readonly("distance", &DistanceResult::distance,
                    "Upper bound on the distance, achieved by the witness points.")
      .def_readonly("lower_bound", &DistanceResult::lower_bound,
                    "Lower bound on the distance, certified by ``direction``.")
      .def_readonly("point_a", &DistanceResult::point_a, "Witness point on A.")
      .def_readonly("point_b", &DistanceResult::point_b, "Witness point on B.")
      .def_readonly("weights_a", &DistanceResult::weights_a,
                    "lambda of model (2): nonnegative, summing to one.")
      .def_readonly("weights_b", &DistanceResult::weights_b,
                    "delta of model (2): nonnegative, summing to one.")
      .def_readonly("direction", &DistanceResult::direction,
                    "Unit direction certifying ``lower_bound`` (zero if none separates).")
      .def_readonly("iterations", &DistanceResult::iterations)
      .def_readonly("evaluations", &DistanceResult::evaluations)
      .def_property_readonly(
          "history", [](const DistanceResult& r) { return as_array(r.history); },
          "Best distance after initialisation and after each iteration.")
      .def_readonly("colliding", &DistanceResult::colliding)
      .def_readonly("certified", &DistanceResult::certified,
                    "True when the bounds prove the verdict.")
      .def_readonly("method", &DistanceResult::method, "The method that produced the answer.")
      .def_readonly("escalated_from", &DistanceResult::escalated_from,
                    "The method whose unproven collision verdict was handed to ``method`` "
                    "(empty if none).")
      .def_property_readonly(
          "status", [](const DistanceResult& r) { return status_name(r.status); },
          "'converged', 'max_iterations' or 'exact'.")
      .def_property_readonly(
          "gap", [](const DistanceResult& r) { return r.distance - r.lower_bound; },
          "``distance - lower_bound``: how far from exact the answer can be.")
      .def("__repr__", &repr);

  py::class_<ParticleCoefficients>(m, "ParticleCoefficients")
      .def_readonly("w", &ParticleCoefficients::w)
      .def_readonly("c1", &ParticleCoefficients::c1)
      .def_readonly("c2", &ParticleCoefficients::c2)
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
