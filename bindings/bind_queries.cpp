#include <pybind11/eigen.h>
#include <pybind11/stl.h>
#include <pybind11/typing.h>

#include <sstream>
#include <string>

#include "conversions.hpp"
#include "queries.hpp"
#include "swarmcollide/queries/methods.hpp"

namespace swarmcollide::bindings {

namespace {

const char* status_name(SolverStatus status) {
  return status == SolverStatus::converged ? "converged" : "max_iterations";
}

std::string repr(const DistanceResult& r) {
  std::ostringstream out;
  out.precision(6);
  out << "DistanceResult(method='" << method_name(r.method) << "'";
  if (r.escalated_from) out << ", escalated_from='" << method_name(*r.escalated_from) << "'";
  out << ", distance=" << r.distance << ", lower_bound=" << r.lower_bound
      << ", colliding=" << (r.colliding ? "True" : "False")
      << ", certified=" << (r.certified ? "True" : "False") << ", iterations=" << r.iterations
      << ", status='" << status_name(r.status) << "')";
  return out.str();
}

py::array_t<Scalar> as_array(const std::vector<Scalar>& values) {
  return py::array_t<Scalar>(static_cast<py::ssize_t>(values.size()), values.data());
}

bool is_bool(const py::handle& value) { return PyBool_Check(value.ptr()); }
bool is_integer(const py::handle& value) { return !is_bool(value) && PyIndex_Check(value.ptr()); }
bool is_real(const py::handle& value) {
  return !is_bool(value) && (PyFloat_Check(value.ptr()) || is_integer(value) ||
                             py::isinstance(value, py::module_::import("numpy").attr("floating")));
}

const char* kind_name(ParameterInfo::Kind kind) {
  switch (kind) {
    case ParameterInfo::Kind::integer:
      return "integer";
    case ParameterInfo::Kind::real:
      return "real";
    case ParameterInfo::Kind::choice:
      break;
  }
  return "choice";
}

// The method table as Python dictionaries, with each parameter's default for its method.
py::list method_table_for_python() {
  py::list table;
  for (const MethodInfo& info : method_table()) {
    QueryOptions defaults;
    defaults.method = info.method;
    py::list queries;
    if (info.capabilities & kDistance) queries.append("distance");
    if (info.capabilities & kCollide) queries.append("collide");
    if (info.capabilities & kSignedDistance) queries.append("signed_distance");
    py::list parameters;
    for (const ParameterInfo& p : info.parameters) {
      py::dict entry;
      entry["name"] = p.name;
      entry["kind"] = kind_name(p.kind);
      entry["description"] = p.description;
      entry["minimum"] = p.minimum;
      entry["maximum"] = p.maximum;
      entry["minimum_excluded"] = p.minimum_excluded;
      py::list choices;
      for (const char* c : p.choices) choices.append(c);
      entry["choices"] = py::tuple(choices);
      const double value = p.get(defaults);
      if (p.kind == ParameterInfo::Kind::integer) {
        entry["default"] = static_cast<long long>(value);
      } else if (p.kind == ParameterInfo::Kind::choice) {
        entry["default"] = p.choices[static_cast<std::size_t>(value)];
      } else {
        entry["default"] = value;
      }
      parameters.append(entry);
    }
    py::dict method;
    method["name"] = info.name;
    method["summary"] = info.summary;
    method["queries"] = py::tuple(queries);
    method["always_certified"] = info.always_certified;
    method["parameters"] = py::tuple(parameters);
    table.append(method);
  }
  return table;
}

// The parameters a query's method reads, with their values, for its repr and `parameters`.
py::dict parameters_of(const QueryOptions& options) {
  py::dict values;
  for (const ParameterInfo& p : method_info(options.method).parameters) {
    const double value = p.get(options);
    if (p.kind == ParameterInfo::Kind::integer) {
      values[p.name] = static_cast<long long>(value);
    } else if (p.kind == ParameterInfo::Kind::choice) {
      values[p.name] = p.choices[static_cast<std::size_t>(value)];
    } else {
      values[p.name] = value;
    }
  }
  return values;
}

// `query(a, pose_a, b, pose_b)` without the GIL, the bodies converted while holding it: the
// compound queries (a CompoundResult) when either body is a CompoundBody, else the convex ones.
// What the queries return: a CompoundResult (a DistanceResult naming parts) for compound bodies.
using AnyResult = py::typing::Union<DistanceResult, CompoundResult>;

template <typename Call>
py::object on_pair(const py::handle& a, const py::handle& b, const py::handle& pose_a,
                   const py::handle& pose_b, const Call& call) {
  const Pose place_a = to_pose(pose_a, "pose_a");
  const Pose place_b = to_pose(pose_b, "pose_b");
  if (is_compound(a) || is_compound(b)) {
    const CompoundArgument body_a(a, "a");
    const CompoundArgument body_b(b, "b");
    auto result = [&] {
      py::gil_scoped_release release;
      return call(body_a.get(), place_a, body_b.get(), place_b);
    }();
    return py::cast(std::move(result));
  }
  const BodyArgument body_a(a, "a");
  const BodyArgument body_b(b, "b");
  auto result = [&] {
    py::gil_scoped_release release;
    return call(body_a.get(), place_a, body_b.get(), place_b);
  }();
  return py::cast(std::move(result));
}

}  // namespace

// Types are checked here, values by the method table (which names the valid range).
QueryOptions make_options(const py::handle& method, const py::handle& tolerance,
                          const py::handle& seed, const py::kwargs& parameters) {
  QueryOptions options;
  options.method = method_from_name(to_name(method, "method"));
  if (!is_real(tolerance)) {
    throw py::type_error("tolerance must be a real number, got " + type_name(tolerance));
  }
  options.tolerance = tolerance.cast<double>();
  if (!is_integer(seed)) throw py::type_error("seed must be an integer, got " + type_name(seed));
  const py::int_ seed_value = py::reinterpret_steal<py::int_>(PyNumber_Index(seed.ptr()));
  if (seed_value < py::int_(0) ||
      seed_value >= py::int_(py::module_::import("builtins").attr("pow")(2, 64))) {
    throw py::value_error("seed must lie in [0, 2**64), got " + std::string(py::str(seed_value)));
  }
  options.seed = seed_value.cast<std::uint64_t>();
  for (const auto& [key, value] : parameters) {
    const std::string name = key.cast<std::string>();
    if (value.is_none()) continue;
    const MethodInfo& info = method_info(options.method);
    const ParameterInfo* parameter = nullptr;
    for (const ParameterInfo& p : info.parameters) {
      if (name == p.name) parameter = &p;
    }
    if (parameter == nullptr) {
      set_parameter(options, name, 0);  // throws, listing the method's parameters
    } else if (parameter->kind == ParameterInfo::Kind::real) {
      if (!is_real(value))
        throw py::type_error(name + " must be a real number, got " + type_name(value));
      set_parameter(options, name, value.cast<double>());
    } else if (parameter->kind == ParameterInfo::Kind::integer) {
      if (!is_integer(value))
        throw py::type_error(name + " must be an integer, got " + type_name(value));
      const py::int_ integer = py::reinterpret_steal<py::int_>(PyNumber_Index(value.ptr()));
      // Beyond double's exact integers, the range check still rejects the value.
      set_parameter(options, name, py::float_(integer).cast<double>());
    } else {
      if (!py::isinstance<py::str>(value)) {
        throw py::type_error(name + " must be a string, got " + type_name(value));
      }
      set_parameter(options, name, choice_index(options, name, value.cast<std::string>()));
    }
  }
  options.validate();
  return options;
}

void bind_distance_result(py::module_& m) {
  py::class_<DistanceResult>(m, "DistanceResult", R"doc(
The answer of every query, whatever the method, in the units of the input.

``lower_bound <= true value <= distance`` always holds (up to rounding, about 1e-14 of the pair's
size): ``distance`` is achieved by the witness points ``point_a`` and ``point_b`` (convex
combinations of the bodies' points with ``weights_a`` and ``weights_b``), and ``lower_bound`` is
the separation along ``direction``. For signed distances the true value is minus the penetration
depth when the bodies overlap, and ``point_b - point_a = distance * direction``.
)doc")
      .def_readonly("distance", &DistanceResult::distance,
                    "Upper bound on the distance (signed distance), achieved by the witnesses.")
      .def_readonly("lower_bound", &DistanceResult::lower_bound,
                    "Lower bound on the distance (signed distance), certified by ``direction``.")
      .def_readonly("point_a", &DistanceResult::point_a, "Witness point on A.")
      .def_readonly("point_b", &DistanceResult::point_b, "Witness point on B.")
      .def_property_readonly(
          "weights_a", [](const DistanceResult& r) { return r.weights_a.dense(); },
          "lambda of model (2): nonnegative, summing to one (built when read).")
      .def_property_readonly(
          "weights_b", [](const DistanceResult& r) { return r.weights_b.dense(); },
          "delta of model (2): nonnegative, summing to one (built when read).")
      .def_readonly("direction", &DistanceResult::direction,
                    "Unit direction from A to B certifying ``lower_bound`` (zero if none).")
      .def_readonly("iterations", &DistanceResult::iterations)
      .def_readonly("evaluations", &DistanceResult::evaluations)
      .def_property_readonly(
          "history", [](const DistanceResult& r) { return as_array(r.history); },
          "Best upper bound after initialisation and after each iteration.")
      .def_readonly("colliding", &DistanceResult::colliding,
                    "True when the bodies are within the tolerance of each other.")
      .def_readonly("certified", &DistanceResult::certified,
                    "True when the bounds prove the verdict (and, for signed distances, the "
                    "value to within the tolerance).")
      .def_property_readonly(
          "method", [](const DistanceResult& r) { return method_name(r.method); },
          "The method that produced the answer.")
      .def_property_readonly(
          "escalated_from",
          [](const DistanceResult& r) -> py::object {
            if (!r.escalated_from) return py::none();
            return py::str(method_name(*r.escalated_from));
          },
          "The method asked for, when another one answered (None otherwise).")
      .def_property_readonly(
          "status", [](const DistanceResult& r) { return status_name(r.status); },
          "'converged' (the bounds are within the tolerance, or contact is proven) or "
          "'max_iterations'.")
      .def_property_readonly(
          "gap", [](const DistanceResult& r) { return r.distance - r.lower_bound; },
          "``distance - lower_bound``: how far from exact the answer can be.")
      .def("__repr__", &repr);
}

py::class_<Query> bind_queries(py::module_& m) {
  m.def("method_table", &method_table_for_python,
        "Every method as a dictionary: name, summary, queries, always_certified, parameters.");

  py::class_<Query> query(m, "Query", R"doc(
A method with its parameters, validated once, that answers queries between pairs of bodies.

Every query computes in a frame centred on the pair and scaled to its size, so answers scale with
the unit of length. ``tolerance`` is relative to the pair's size (the diameter of a ball around
both bodies): it is the precision of every answer and the distance below which bodies collide.
)doc");
  query
      .def(py::init([](const py::object& method, const py::object& tolerance,
                       const py::object& seed, const py::kwargs& parameters) {
             return Query(make_options(method, tolerance, seed, parameters));
           }),
           py::arg("method") = "dual", py::arg("tolerance") = kDefaultTolerance,
           py::arg("seed") = 0)
      .def_property_readonly("method",
                             [](const Query& q) { return method_name(q.options().method); })
      .def_property_readonly("tolerance", [](const Query& q) { return q.options().tolerance; })
      .def_property_readonly("seed", [](const Query& q) { return q.options().seed; })
      .def_property_readonly(
          "parameters", [](const Query& q) { return parameters_of(q.options()); },
          "The method's parameters and their values.")
      .def(
          "distance",
          [](const Query& q, const py::handle& a, const py::handle& b, const py::handle& pose_a,
             const py::handle& pose_b) {
            return AnyResult(on_pair(a, b, pose_a, pose_b,
                                     [&q](const auto&... args) { return q.distance(args...); }));
          },
          py::arg("a"), py::arg("b"), py::arg("pose_a") = py::none(),
          py::arg("pose_b") = py::none())
      .def(
          "collision",
          [](const Query& q, const py::handle& a, const py::handle& b, const py::handle& pose_a,
             const py::handle& pose_b, bool escalate) {
            return AnyResult(on_pair(a, b, pose_a, pose_b, [&](const auto&... args) {
              return q.collision(args..., escalate);
            }));
          },
          py::arg("a"), py::arg("b"), py::arg("pose_a") = py::none(),
          py::arg("pose_b") = py::none(), py::arg("escalate") = true)
      .def(
          "collide",
          [](const Query& q, const py::handle& a, const py::handle& b, const py::handle& pose_a,
             const py::handle& pose_b, bool escalate) {
            return on_pair(a, b, pose_a, pose_b,
                           [&](const auto&... args) { return q.collide(args..., escalate); })
                .cast<bool>();
          },
          py::arg("a"), py::arg("b"), py::arg("pose_a") = py::none(),
          py::arg("pose_b") = py::none(), py::arg("escalate") = true)
      .def(
          "signed_distance",
          [](const Query& q, const py::handle& a, const py::handle& b, const py::handle& pose_a,
             const py::handle& pose_b) {
            return AnyResult(on_pair(a, b, pose_a, pose_b, [&q](const auto&... args) {
              return q.signed_distance(args...);
            }));
          },
          py::arg("a"), py::arg("b"), py::arg("pose_a") = py::none(),
          py::arg("pose_b") = py::none())
      .def("__repr__", [](const Query& q) {
        std::string text = "Query(method='" + std::string(method_name(q.options().method)) + "'";
        std::ostringstream tol;
        tol << q.options().tolerance;
        text += ", tolerance=" + tol.str() + ", seed=" + std::to_string(q.options().seed);
        for (const auto& [key, value] : parameters_of(q.options())) {
          text += ", " + std::string(py::str(key)) + "=" + std::string(py::repr(value));
        }
        return text + ")";
      });
  return query;
}

}  // namespace swarmcollide::bindings
