#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "conversions.hpp"
#include "fast_calls.hpp"
#include "queries.hpp"
#include "signals.hpp"
#include "swarmcollide/queries/methods.hpp"

namespace swarmcollide::bindings {

/// What the pair queries return: a DistanceResult, or for compound bodies a CompoundResult (a
/// DistanceResult naming parts), typed in signatures as the base class both are. A union there
/// reads `A | B`, which the stubs' generator (pybind11-stubgen 2.5.5) copies unparsed, with
/// module paths the stubs never import: type checkers read those returns as errors.
class AnyResult : public py::object {
 public:
  AnyResult() = default;
  explicit AnyResult(py::object result) : py::object(std::move(result)) {}
};

}  // namespace swarmcollide::bindings

namespace pybind11::detail {

template <>
struct handle_type_name<swarmcollide::bindings::AnyResult> {
  static constexpr auto name = const_name<swarmcollide::DistanceResult>();
};

}  // namespace pybind11::detail

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

py::array_t<Scalar> as_array(const History& values) {
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

// The pair queries of Query and of the module's functions (swarmcollide.queries).
enum class PairQuery { distance, signed_distance, collision, collide };

// Above this many points read in a pair (read_point_count), an exact method's query releases
// the GIL while it runs. Below, a query takes microseconds (a first one on a body also finds its
// hull, in milliseconds only for bodies of thousands of points): releasing the GIL and taking it
// back (0.1-0.2 us, a quarter of a query between 64-vertex hulls) would cost more than another
// thread could gain in that time. python-fcl and coal never release it.
constexpr int kReleaseAbovePoints = 1024;

// Whether a query of `options` between bodies of `points` points in all releases the GIL: the
// swarms (the methods not always certified) run hundreds of iterations whatever the size. The
// points are those the solvers read (ConvexPolyhedron::read_point_count): a body of 2,000 points
// whose hull has 45 vertices answers as fast as that hull, and the release and retake, counted
// by its given points, cost its collision verdicts that the bodies' balls settle (25 ns in C++)
// a fifth more than its hull's (bench/hull_points.py).
bool releases_gil(const QueryOptions& options, int points) {
  return points > kReleaseAbovePoints || !method_info(options.method).always_certified;
}

// `solve()` without the GIL and stopped by Ctrl-C (interruptible) where `release` says so
// (releases_gil), as it is with the GIL otherwise: the small queries of the always certified
// methods end in microseconds, and the interruption guard cost each of them 15-20 ns
// (bench/per_call.py, 8 vertices apart, against coal's ComputeDistance in the same run:
// Query.distance dual 0.80x with it on every query, 0.73x without it on these; 0.76x before it).
template <typename Solve>
auto released_if(bool release, const Solve& solve) {
  if (!release) return solve();
  return interruptible([&] {
    py::gil_scoped_release released;
    return solve();
  });
}

// `kind` between convex bodies or compound bodies, `escalate` for the verdicts. Without poses
// (`placed` false: both were None) through the overloads without poses, which validate none.
template <typename Body>
auto answer_bodies(const Query& query, PairQuery kind, const Body& a, const Pose& pose_a,
                   const Body& b, const Pose& pose_b, bool escalate, bool placed) {
  if (!placed) {
    switch (kind) {
      case PairQuery::distance:
        return query.distance(a, b);
      case PairQuery::signed_distance:
        return query.signed_distance(a, b);
      case PairQuery::collision:
      case PairQuery::collide:
        break;
    }
    return query.collision(a, b, escalate);
  }
  switch (kind) {
    case PairQuery::distance:
      return query.distance(a, pose_a, b, pose_b);
    case PairQuery::signed_distance:
      return query.signed_distance(a, pose_a, b, pose_b);
    case PairQuery::collision:
    case PairQuery::collide:
      break;
  }
  return query.collision(a, pose_a, b, pose_b, escalate);
}

// `kind` between `a` and `b` as Python sees it: a bool for collide, else a DistanceResult (a
// CompoundResult when either body is a CompoundBody). The arguments are converted while holding
// the GIL, which the query itself releases unless it is a small one (releases_gil); Python's
// signal handlers run while a query without the GIL solves (released_if): Ctrl-C raises
// KeyboardInterrupt.
py::object answer(const Query& query, PairQuery kind, const py::handle& a, const py::handle& b,
                  const py::handle& pose_a, const py::handle& pose_b, bool escalate) {
  // The query checks both poses (as "pose_a" and "pose_b") before anything reads them.
  const Pose place_a = read_pose(pose_a, "pose_a");
  const Pose place_b = read_pose(pose_b, "pose_b");
  const bool placed = !pose_a.is_none() || !pose_b.is_none();
  if (is_compound(a) || is_compound(b)) {
    const CompoundArgument body_a(a, "a");
    const CompoundArgument body_b(b, "b");
    CompoundResult result = interruptible([&] {
      py::gil_scoped_release release;
      return answer_bodies(query, kind, body_a.get(), place_a, body_b.get(), place_b, escalate,
                           placed);
    });
    if (kind == PairQuery::collide) return py::bool_(result.colliding);
    return py::cast(std::move(result));
  }
  const ConvexPolyhedron* polyhedron_a = body_instance(a.ptr());
  const ConvexPolyhedron* polyhedron_b = polyhedron_a ? body_instance(b.ptr()) : nullptr;
  std::optional<BodyArgument> body_a, body_b;
  if (!polyhedron_b) {
    polyhedron_a = &body_a.emplace(a, "a").get();
    polyhedron_b = &body_b.emplace(b, "b").get();
  }
  const bool release = releases_gil(
      query.options(), polyhedron_a->read_point_count() + polyhedron_b->read_point_count());
  if (kind == PairQuery::collide) {
    // The verdict alone: Query::collide builds no DistanceResult.
    const auto decide = [&] {
      return placed ? query.collide(*polyhedron_a, place_a, *polyhedron_b, place_b, escalate)
                    : query.collide(*polyhedron_a, *polyhedron_b, escalate);
    };
    return py::bool_(released_if(release, decide));
  }
  const auto solve = [&] {
    return answer_bodies(query, kind, *polyhedron_a, place_a, *polyhedron_b, place_b, escalate,
                         placed);
  };
  return py::cast(released_if(release, solve));
}

// The module's query functions (swarmcollide.queries) as written in Python, by PairQuery: their
// C++ versions (query_function) hand them every call they do not answer themselves.
PyObject* python_paths[4] = {};

// The keywords a query function reads in C++, interned: a keyword written in a call is interned
// too, so comparing identities finds it (any other spelling goes to the Python path).
struct KeywordNames {
  PyObject* method = PyUnicode_InternFromString("method");
  PyObject* tolerance = PyUnicode_InternFromString("tolerance");
  PyObject* seed = PyUnicode_InternFromString("seed");
  PyObject* pose_a = PyUnicode_InternFromString("pose_a");
  PyObject* pose_b = PyUnicode_InternFromString("pose_b");
  PyObject* escalate = PyUnicode_InternFromString("escalate");
};

// The arguments of a call to a query function, defaults for those not given.
struct QueryCall {
  PyObject* method = nullptr;
  PyObject* tolerance = nullptr;
  PyObject* seed = nullptr;
  PyObject* pose_a = Py_None;
  PyObject* pose_b = Py_None;
  bool escalate = true;
};

// Reads the keywords of a call to the query function of `kind` into `call`; false for a call
// the C++ path leaves to Python: a solver parameter, `escalate` that is not a bool, a keyword
// that does not apply to `kind` (Python then says so).
bool read_keywords(PairQuery kind, PyObject* const* values, PyObject* names, QueryCall& call) {
  if (names == nullptr) return true;
  static const KeywordNames keyword;
  const bool verdict = kind == PairQuery::collision || kind == PairQuery::collide;
  for (Py_ssize_t i = 0; i < PyTuple_GET_SIZE(names); ++i) {
    PyObject* const name = PyTuple_GET_ITEM(names, i);
    PyObject* const value = values[i];
    if (name == keyword.pose_a) {
      call.pose_a = value;
    } else if (name == keyword.pose_b) {
      call.pose_b = value;
    } else if (name == keyword.method) {
      call.method = value;
    } else if (name == keyword.tolerance) {
      call.tolerance = value;
    } else if (name == keyword.seed) {
      call.seed = value;
    } else if (name == keyword.escalate && verdict && PyBool_Check(value)) {
      call.escalate = value == Py_True;
    } else {
      return false;
    }
  }
  return true;
}

// The method a str names, or none (Python then says which names are valid). The names of the
// method table are interned, as are names written in calls, so identities usually decide.
std::optional<Method> method_named(PyObject* name) {
  static const std::vector<PyObject*> interned = [] {
    std::vector<PyObject*> names;
    for (const MethodInfo& info : method_table()) {
      names.push_back(PyUnicode_InternFromString(info.name));
    }
    return names;
  }();
  const std::vector<MethodInfo>& table = method_table();
  for (std::size_t i = 0; i < table.size(); ++i) {
    if (name == interned[i]) return table[i].method;
  }
  for (std::size_t i = 0; i < table.size(); ++i) {
    if (PyUnicode_CompareWithASCIIString(name, table[i].name) == 0) return table[i].method;
  }
  return std::nullopt;
}

// The Query of a call's method, tolerance and seed, built on first use with Query(...)'s checks
// (as Python's query() builds it) and kept; none when they are not a str, a float and an int,
// which the Python path tells apart by type (True is not 1) or rejects. Called with the GIL held,
// which guards the cache; a copy is returned because another thread may clear the cache while
// this one answers without the GIL.
std::optional<Query> query_for(const QueryCall& call) {
  static PyObject* const default_method = PyUnicode_InternFromString("dual");
  static PyObject* const default_tolerance = PyFloat_FromDouble(kDefaultTolerance);
  static PyObject* const default_seed = PyLong_FromLong(0);
  static std::map<std::tuple<Method, double, unsigned long long>, Query> cache;
  constexpr std::size_t kCacheSize = 256;  // as Python's query() cache
  PyObject* const method = call.method ? call.method : default_method;
  PyObject* const tolerance = call.tolerance ? call.tolerance : default_tolerance;
  PyObject* const seed = call.seed ? call.seed : default_seed;
  // A NaN tolerance would match any key of the map: Python rejects it.
  if (!PyUnicode_CheckExact(method) || !PyFloat_CheckExact(tolerance) ||
      std::isnan(PyFloat_AS_DOUBLE(tolerance)) || !PyLong_CheckExact(seed)) {
    return std::nullopt;
  }
  const std::optional<Method> named = method_named(method);
  const unsigned long long seed_value = PyLong_AsUnsignedLongLong(seed);
  if (!named || PyErr_Occurred()) {
    PyErr_Clear();  // a negative or huge seed: Python says so
    return std::nullopt;
  }
  const auto key = std::make_tuple(*named, PyFloat_AS_DOUBLE(tolerance), seed_value);
  const auto found = cache.find(key);
  if (found != cache.end()) return found->second;
  Query built(make_options(method, tolerance, seed, py::kwargs()));
  if (cache.size() >= kCacheSize) cache.clear();
  cache.emplace(key, built);
  return built;
}

// The query function of `kind` in C++: `kind(a, b, *, method, tolerance, seed, pose_a, pose_b)`
// (and `escalate` for the verdicts) answered here, about half a microsecond sooner than through
// Python; any other call, and any call that raises, goes to the Python definition, which answers
// it or raises its own error.
template <PairQuery kind>
PyObject* query_function(PyObject*, PyObject* const* arguments, Py_ssize_t count,
                         PyObject* names) {
  QueryCall call;
  if (count == 2 && read_keywords(kind, arguments + 2, names, call)) {
    try {
      if (const std::optional<Query> query = query_for(call)) {
        return answer(*query, kind, arguments[0], arguments[1], call.pose_a, call.pose_b,
                      call.escalate)
            .release()
            .ptr();
      }
    } catch (SignalRaised& raised) {
      raised.restore();  // a KeyboardInterrupt: the call is not retried
      return nullptr;
    } catch (...) {
      // The Python path raises it again, with the message it has always given.
    }
  }
  return PyObject_Vectorcall(python_paths[static_cast<int>(kind)], arguments,
                             static_cast<std::size_t>(count), names);
}

// `python_path`, the Python definition of one of the module's query functions (told by its
// name), as a C++ function with its name, module, documentation and signature.
py::object make_query_function(const py::function& python_path,
                               const std::string& text_signature) {
  const auto name = python_path.attr("__name__").cast<std::string>();
  FastCall entry = nullptr;
  PairQuery kind = PairQuery::distance;
  if (name == "distance") {
    entry = &query_function<PairQuery::distance>;
  } else if (name == "signed_distance") {
    kind = PairQuery::signed_distance;
    entry = &query_function<PairQuery::signed_distance>;
  } else if (name == "collision") {
    kind = PairQuery::collision;
    entry = &query_function<PairQuery::collision>;
  } else if (name == "collide") {
    kind = PairQuery::collide;
    entry = &query_function<PairQuery::collide>;
  } else {
    throw py::value_error(
        "python_path must be distance, signed_distance, collision or collide, got " + name);
  }
  PyObject*& held = python_paths[static_cast<int>(kind)];
  Py_XDECREF(held);
  held = python_path.inc_ref().ptr();
  return fast_function(entry, python_path, text_signature);
}

// Query's pybind11 methods, by PairQuery: the C++ methods below (query_method) hand them every
// call they do not answer themselves, so that such calls behave and fail as they always have.
PyObject* bound_methods[4] = {};

// Reads the arguments of a call to Query's method `kind` after `a` and `b`: `pose_a`, `pose_b`
// and, for the verdicts, `escalate`, by position or keyword; false for anything else (a keyword
// given twice, `escalate` that is not a bool), which pybind11's method then refuses or converts.
bool read_method_arguments(PairQuery kind, PyObject* const* arguments, Py_ssize_t count,
                           PyObject* names, QueryCall& call) {
  static const KeywordNames keyword;
  const bool verdict = kind == PairQuery::collision || kind == PairQuery::collide;
  if (count < 2 || count > (verdict ? 5 : 4)) return false;
  if (count > 2) call.pose_a = arguments[2];
  if (count > 3) call.pose_b = arguments[3];
  if (count > 4) {
    if (!PyBool_Check(arguments[4])) return false;
    call.escalate = arguments[4] == Py_True;
  }
  const Py_ssize_t keywords = names ? PyTuple_GET_SIZE(names) : 0;
  for (Py_ssize_t i = 0; i < keywords; ++i) {
    PyObject* const name = PyTuple_GET_ITEM(names, i);
    PyObject* const value = arguments[count + i];
    if (name == keyword.pose_a && count <= 2) {
      call.pose_a = value;
    } else if (name == keyword.pose_b && count <= 3) {
      call.pose_b = value;
    } else if (name == keyword.escalate && verdict && count <= 4 && PyBool_Check(value)) {
      call.escalate = value == Py_True;
    } else {
      return false;
    }
  }
  return true;
}

// Query's method `kind` in C++: pybind11's dispatch costs about a tenth of a microsecond, a
// quarter of a query between small bodies. Calls it does not read, and calls that raise, go to
// the pybind11 method.
template <PairQuery kind>
PyObject* query_method(PyObject* self, PyObject* const* arguments, Py_ssize_t count,
                       PyObject* names) {
  QueryCall call;
  const Query* query = exact_instance<Query>(self);
  if (query != nullptr && read_method_arguments(kind, arguments, count, names, call)) {
    try {
      return answer(*query, kind, arguments[0], arguments[1], call.pose_a, call.pose_b,
                    call.escalate)
          .release()
          .ptr();
    } catch (SignalRaised& raised) {
      raised.restore();  // a KeyboardInterrupt: the call is not retried
      return nullptr;
    } catch (...) {
      // The pybind11 method raises it again, with the message it has always given.
    }
  }
  const Py_ssize_t keywords = names ? PyTuple_GET_SIZE(names) : 0;
  std::vector<PyObject*> with_self(static_cast<std::size_t>(count + keywords + 1));
  with_self[0] = self;
  std::copy(arguments, arguments + count + keywords, with_self.begin() + 1);
  return PyObject_Vectorcall(bound_methods[static_cast<int>(kind)], with_self.data(),
                             static_cast<std::size_t>(count + 1), names);
}

// Replaces Query's pybind11 method `name` by query_method<kind>, with its documentation (whose
// first line is pybind11's typed signature, which the stubs read).
template <PairQuery kind>
void answer_in_cpp(py::class_<Query>& query_class, const char* name) {
  const py::object bound = query_class.attr(name);
  bound_methods[static_cast<int>(kind)] = bound.inc_ref().ptr();
  // Kept for the life of the module, as the class keeps its methods.
  const auto* const documentation = new std::string(py::str(bound.attr("__doc__")));
  auto* const definition = new PyMethodDef{
      name, reinterpret_cast<PyCFunction>(reinterpret_cast<void (*)()>(&query_method<kind>)),
      METH_FASTCALL | METH_KEYWORDS, documentation->c_str()};
  PyObject* const method =
      PyDescr_NewMethod(reinterpret_cast<PyTypeObject*>(query_class.ptr()), definition);
  if (method == nullptr) throw py::error_already_set();
  py::setattr(query_class, name, py::reinterpret_steal<py::object>(method));
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
  // CPython refuses negative and too large values alike (OverflowError), with no 2**64 to build.
  const unsigned long long seed_bits = PyLong_AsUnsignedLongLong(seed_value.ptr());
  if (seed_bits == static_cast<unsigned long long>(-1) && PyErr_Occurred()) {
    PyErr_Clear();
    throw py::value_error("seed must lie in [0, 2**64), got " + std::string(py::str(seed_value)));
  }
  options.seed = seed_bits;
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

py::tuple options_state(const QueryOptions& options) {
  return py::make_tuple(method_name(options.method), options.tolerance, options.seed,
                        parameters_of(options));
}

QueryOptions options_from_state(PickledState& state) {
  const auto method = state.next<py::object>("method");
  const auto tolerance = state.next<py::object>("tolerance");
  const auto seed = state.next<py::object>("seed");
  const auto parameters = state.next("parameters", [](const py::handle& item) {
    if (!PyDict_Check(item.ptr())) throw py::type_error("must be a dict, got " + type_name(item));
    return py::reinterpret_borrow<py::kwargs>(item);
  });
  return state.build([&] { return make_options(method, tolerance, seed, parameters); });
}

py::tuple distance_result_state(const DistanceResult& r) {
  return py::make_tuple(
      kStateVersion, r.distance, r.lower_bound, r.point_a, r.point_b, r.weights_a.dense(),
      r.weights_b.dense(), r.direction, r.iterations, r.evaluations, as_array(r.history),
      r.colliding, r.certified, method_name(r.method),
      r.escalated_from ? py::object(py::str(method_name(*r.escalated_from))) : py::none(),
      status_name(r.status));
}

DistanceResult distance_result_from_state(const py::handle& state) {
  PickledState items(state, "DistanceResult", 15);
  const auto weights = [](const char* name) {
    return [name](const py::handle& item) {
      const VectorX dense = finite_weights(item, name);
      return dense.size() == 0 ? ConvexWeights() : ConvexWeights(dense);
    };
  };
  const auto method = [](const py::handle& item) {
    return method_from_name(to_name(item, "method"));
  };
  DistanceResult r;
  r.distance = items.next<Scalar>("distance");
  r.lower_bound = items.next<Scalar>("lower_bound");
  r.point_a = items.next<Vector3>("point_a");
  r.point_b = items.next<Vector3>("point_b");
  r.weights_a = items.next("weights_a", weights("weights_a"));
  r.weights_b = items.next("weights_b", weights("weights_b"));
  r.direction = items.next<Vector3>("direction");
  r.iterations = items.next<int>("iterations");
  r.evaluations = items.next<long>("evaluations");
  for (Scalar value : items.next<VectorX>("history")) r.history.push_back(value);
  r.colliding = items.next<bool>("colliding");
  r.certified = items.next<bool>("certified");
  r.method = items.next("method", method);
  r.escalated_from = items.next("escalated_from", [&](const py::handle& item) {
    return item.is_none() ? std::nullopt : std::optional<Method>(method(item));
  });
  r.status = items.next("status", [](const py::handle& item) {
    const std::string name = to_name(item, "status");
    if (name != "converged" && name != "max_iterations") {
      throw py::value_error("must be 'converged' or 'max_iterations', got '" + name + "'");
    }
    return name == "converged" ? SolverStatus::converged : SolverStatus::max_iterations;
  });
  return r;
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
      .def(py::pickle(&distance_result_state,
                      [](const py::object& state) { return distance_result_from_state(state); }))
      .def("__repr__", &repr);
}

py::class_<Query> bind_queries(py::module_& m) {
  m.def("method_table", &method_table_for_python,
        "Every method as a dictionary: name, summary, queries, always_certified, parameters.");
  m.def("query_function", &make_query_function, py::arg("python_path"), py::arg("text_signature"),
        R"doc(
``python_path`` (``distance``, ``signed_distance``, ``collision`` or ``collide`` of
swarmcollide.queries, told by its ``__name__``) as a C++ function with its name, module,
documentation and ``text_signature`` (without annotations).

The C++ function answers ``f(a, b, *, method, tolerance, seed, pose_a, pose_b, escalate)``
itself (a method that is a str, a float tolerance, an int seed, ``escalate`` a bool and only for
the verdicts), with a Query per method, tolerance and seed kept as Python's ``query`` keeps them,
and hands every other call (solver parameters, other types, calls that raise) to
``python_path``, which answers it or raises as it always has.
)doc");

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
            return AnyResult(answer(q, PairQuery::distance, a, b, pose_a, pose_b, false));
          },
          py::arg("a"), py::arg("b"), py::arg("pose_a") = py::none(),
          py::arg("pose_b") = py::none())
      .def(
          "collision",
          [](const Query& q, const py::handle& a, const py::handle& b, const py::handle& pose_a,
             const py::handle& pose_b, const Given<bool>& escalate) {
            return AnyResult(answer(q, PairQuery::collision, a, b, pose_a, pose_b,
                                    to_bool(escalate.value, "escalate")));
          },
          py::arg("a"), py::arg("b"), py::arg("pose_a") = py::none(),
          py::arg("pose_b") = py::none(), py::arg("escalate") = true)
      .def(
          "collide",
          [](const Query& q, const py::handle& a, const py::handle& b, const py::handle& pose_a,
             const py::handle& pose_b, const Given<bool>& escalate) {
            return answer(q, PairQuery::collide, a, b, pose_a, pose_b,
                          to_bool(escalate.value, "escalate"))
                       .ptr() == Py_True;
          },
          py::arg("a"), py::arg("b"), py::arg("pose_a") = py::none(),
          py::arg("pose_b") = py::none(), py::arg("escalate") = true)
      .def(
          "signed_distance",
          [](const Query& q, const py::handle& a, const py::handle& b, const py::handle& pose_a,
             const py::handle& pose_b) {
            return AnyResult(answer(q, PairQuery::signed_distance, a, b, pose_a, pose_b, false));
          },
          py::arg("a"), py::arg("b"), py::arg("pose_a") = py::none(),
          py::arg("pose_b") = py::none())
      .def(py::pickle(
          [](const Query& q) {
            return py::tuple(py::make_tuple(kStateVersion) + options_state(q.options()));
          },
          [](const py::object& state) {
            PickledState items(state, "Query", 4);
            return Query(options_from_state(items));
          }))
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
  answer_in_cpp<PairQuery::distance>(query, "distance");
  answer_in_cpp<PairQuery::signed_distance>(query, "signed_distance");
  answer_in_cpp<PairQuery::collision>(query, "collision");
  answer_in_cpp<PairQuery::collide>(query, "collide");
  return query;
}

}  // namespace swarmcollide::bindings
