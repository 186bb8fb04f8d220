#include "swarmcollide/queries/methods.hpp"

#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "../solvers/dual_swarm.hpp"
#include "../solvers/exact_solver.hpp"
#include "../solvers/fcl_solver.hpp"
#include "../solvers/libccd_solver.hpp"
#include "../solvers/penalty_method.hpp"
#include "../solvers/primal_swarm.hpp"
#include "../detail/number_text.hpp"
#include "dispatch.hpp"

namespace swarmcollide {

namespace {

using Kind = ParameterInfo::Kind;

// A parameter read from and written to the field `field` of the options group `group`.
template <auto group, auto field>
ParameterInfo parameter(const char* name, Kind kind, double minimum, double maximum,
                        const char* description, std::vector<const char*> choices = {}) {
  return {name,
          kind,
          description,
          minimum,
          maximum,
          false,
          std::move(choices),
          [](const QueryOptions& o) { return static_cast<double>((o.*group).*field); },
          [](QueryOptions& o, double value) {
            using T = std::decay_t<decltype((o.*group).*field)>;
            if constexpr (std::is_floating_point_v<T>) {
              (o.*group).*field = value;
            } else {
              (o.*group).*field = static_cast<T>(static_cast<long long>(value));
            }
          }};
}

// A parameter that must be positive: its minimum 0 is excluded.
ParameterInfo positive(ParameterInfo p) {
  p.minimum_excluded = true;
  return p;
}
// Caps on what a query can run: a swarm's arrays hold swarm_size x (vertices of both bodies)
// entries (checked by the swarm), and its iterations take time in proportion.
constexpr double kMaxIterations = 1e6;
constexpr double kMaxSwarmSize = 1e5;

std::vector<ParameterInfo> primal_swarm_parameters(bool with_accelerations) {
  std::vector<ParameterInfo> p = {
      parameter<&QueryOptions::swarm, &SwarmOptions::swarm_size>(
          "swarm_size", Kind::integer, 2, kMaxSwarmSize, "N_p, the number of particles"),
      parameter<&QueryOptions::swarm, &SwarmOptions::max_iterations>(
          "max_iterations", Kind::integer, 0, kMaxIterations, "G_m, the iteration budget"),
      parameter<&QueryOptions::swarm, &SwarmOptions::w_min>(
          "w_min", Kind::real, 0, 10, "smallest inertia weight (w_min of (8), w_end of (7))"),
      parameter<&QueryOptions::swarm, &SwarmOptions::w_max>(
          "w_max", Kind::real, 0, 10, "largest inertia weight (w_max of (8), w_start of (7))"),
      positive(parameter<&QueryOptions::swarm, &SwarmOptions::velocity_limit>(
          "velocity_limit", Kind::real, 0, 1e6,
          "largest velocity component (the weights live in [0, 1])")),
      parameter<&QueryOptions::swarm, &SwarmOptions::feasibility_tolerance>(
          "feasibility_tolerance", Kind::real, 0, 1,
          "largest constraint violation (6) that counts as feasible"),
      parameter<&QueryOptions::swarm, &SwarmOptions::constraint_handling>(
          "constraint_handling", Kind::choice, 0, 1,
          "'projection' onto the simplexes after every move, or the paper's 'feasibility' rules "
          "(Conditions 1-3)",
          {"feasibility", "projection"}),
  };
  if (with_accelerations) {
    p.push_back(parameter<&QueryOptions::swarm, &SwarmOptions::c1>(
        "c1", Kind::real, 0, 10, "acceleration towards the personal best, (3)"));
    p.push_back(parameter<&QueryOptions::swarm, &SwarmOptions::c2>(
        "c2", Kind::real, 0, 10, "acceleration towards the global best, (3)"));
  }
  return p;
}

ParameterInfo exact_iterations() {
  return parameter<&QueryOptions::exact, &ExactOptions::max_iterations>(
      "max_iterations", Kind::integer, 1, kMaxIterations,
      "iteration cap of every loop the method runs");
}

}  // namespace

namespace detail {

// Constant-initialised (function addresses and flags only), so a query's lookups need no guard of
// a function-local static; the method table below reads its capabilities from here.
const MethodDispatch kMethodDispatch[kMethodCount] = {
    {kDistance | kCollide | kSignedDistance | kCurvedShapes, solve_dual},
    {kDistance | kCollide, solve_primal_swarm},
    {kDistance | kCollide, solve_primal_swarm},
    {kDistance | kCollide, solve_penalty},
    {kDistance | kCollide | kSignedDistance | kCurvedShapes, solve_exact},
    {kDistance | kCollide | kSignedDistance | kCurvedShapes, solve_fcl},
    {kCollide | kSignedDistance | kCurvedShapes, solve_libccd},
};

}  // namespace detail

namespace {

// The dispatch entry of `method` (listed in the enum's order).
const detail::MethodDispatch& dispatch_of(Method method) {
  return detail::kMethodDispatch[static_cast<std::size_t>(method)];
}

const std::vector<MethodInfo>& entries() {
  static const std::vector<MethodInfo> table = {
      {Method::dual,
       "dual",
       "the paper's rank-adaptive swarm (8)-(11) over separating directions, with an exact "
       "finish: certified",
       dispatch_of(Method::dual).capabilities,
       true,
       {parameter<&QueryOptions::dual, &DualOptions::swarm_size>(
            "swarm_size", Kind::integer, 2, 10000, "N_p, the number of particles of a round"),
        parameter<&QueryOptions::dual, &DualOptions::max_iterations>(
            "max_iterations", Kind::integer, 0, kMaxIterations,
            "the iteration budget of one round"),
        parameter<&QueryOptions::dual, &DualOptions::w_min>("w_min", Kind::real, 0, 10,
                                                            "smallest inertia weight of (8)"),
        parameter<&QueryOptions::dual, &DualOptions::w_max>("w_max", Kind::real, 0, 10,
                                                            "largest inertia weight of (8)"),
        parameter<&QueryOptions::dual, &DualOptions::feature_tolerance>(
            "feature_tolerance", Kind::real, 0, 1,
            "slack, relative to the pair's size, of the supporting features of the finish"),
        parameter<&QueryOptions::dual, &DualOptions::max_rounds>(
            "max_rounds", Kind::integer, 1, 10000,
            "the largest number of swarm rounds (re-seeded around the best direction)")}},
      {Method::ipso, "ipso",
       "the paper's improved PSO on model (2): rank-adaptive inertia and acceleration (8)-(9)",
       dispatch_of(Method::ipso).capabilities, false, primal_swarm_parameters(false)},
      {Method::pso, "pso", "the standard PSO on model (2) with linearly decreasing inertia (7)",
       dispatch_of(Method::pso).capabilities, false, primal_swarm_parameters(true)},
      {Method::penalty,
       "penalty",
       "the paper's penalty-function baseline: exterior quadratic penalty minimised by L-BFGS",
       dispatch_of(Method::penalty).capabilities,
       false,
       {positive(parameter<&QueryOptions::penalty, &PenaltyOptions::initial_weight>(
            "initial_weight", Kind::real, 0, 1e12, "mu_0, the first penalty weight")),
        positive(parameter<&QueryOptions::penalty, &PenaltyOptions::growth_factor>(
            "growth_factor", Kind::real, 1, 1e6,
            "growth of the penalty weight between subproblems")),
        parameter<&QueryOptions::penalty, &PenaltyOptions::outer_iterations>(
            "outer_iterations", Kind::integer, 1, 100, "the number of subproblems"),
        parameter<&QueryOptions::penalty, &PenaltyOptions::inner_iterations>(
            "inner_iterations", Kind::integer, 1, kMaxIterations,
            "the L-BFGS iteration cap of each subproblem")}},
      {Method::exact,
       "exact",
       "the library's own exact solvers: Wolfe's nearest points and a certified penetration "
       "depth",
       dispatch_of(Method::exact).capabilities,
       true,
       {exact_iterations()}},
      {Method::fcl,
       "fcl",
       "FCL's GJK (on FCL's own cylinder, cone and ellipsoid for curved shapes), checked by the "
       "certificate; penetration by the library's exact solver",
       dispatch_of(Method::fcl).capabilities,
       true,
       {exact_iterations()}},
      {Method::libccd,
       "libccd",
       "libccd's GJK intersection test and EPA penetration depth (capped), checked by the "
       "certificate; no distance",
       dispatch_of(Method::libccd).capabilities,
       true,
       {exact_iterations()}},
  };
  return table;
}

const MethodInfo& entry(Method method) {
  // The table lists the methods in the enum's order, so every query finds its method's entry at
  // its index, without a search.
  const std::vector<MethodInfo>& table = entries();
  const auto index = static_cast<std::size_t>(method);
  if (index < table.size() && table[index].method == method) return table[index];
  for (const MethodInfo& e : table) {
    if (e.method == method) return e;
  }
  throw std::invalid_argument("unknown method");
}

std::string names() {
  std::string list;
  for (const MethodInfo& e : entries())
    list += std::string(list.empty() ? "'" : ", '") + e.name + "'";
  return list;
}

const ParameterInfo& find_parameter(const MethodInfo& info, const std::string& name) {
  for (const ParameterInfo& p : info.parameters) {
    if (name == p.name) return p;
  }
  std::string list;
  for (const ParameterInfo& p : info.parameters)
    list += std::string(list.empty() ? "" : ", ") + p.name;
  throw std::invalid_argument(name + " does not apply to method '" + info.name +
                              "' (its parameters: tolerance, seed" +
                              (list.empty() ? "" : ", " + list) + ")");
}

std::string number(double value) {
  if (value == std::floor(value) && std::abs(value) < 1e15) {
    return std::to_string(static_cast<long long>(value));
  }
  std::ostringstream text;
  text << value;
  return text.str();
}

void check_value(const ParameterInfo& p, double value) {
  const bool integral = p.kind != Kind::real;
  const bool above = p.minimum_excluded ? value > p.minimum : value >= p.minimum;
  if (!std::isfinite(value) || (integral && value != std::floor(value)) || !above ||
      value > p.maximum) {
    const std::string kind = integral ? "an integer" : "a number";
    throw std::invalid_argument(std::string(p.name) + " must be " + kind + " in " +
                                (p.minimum_excluded ? "(" : "[") + number(p.minimum) + ", " +
                                number(p.maximum) + "], got " + number(value));
  }
}

}  // namespace

const std::vector<MethodInfo>& method_table() { return entries(); }

const MethodInfo& method_info(Method method) { return entry(method); }

const char* method_name(Method method) { return entry(method).name; }

Method method_from_name(const std::string& name) {
  for (const MethodInfo& e : entries()) {
    if (name == e.name) return e.method;
  }
  throw std::invalid_argument("unknown method '" + name + "'; choose one of " + names());
}

void set_parameter(QueryOptions& options, const std::string& name, double value) {
  const ParameterInfo& p = find_parameter(method_info(options.method), name);
  check_value(p, value);
  p.set(options, value);
}

int choice_index(const QueryOptions& options, const std::string& name, const std::string& choice) {
  const ParameterInfo& p = find_parameter(method_info(options.method), name);
  std::string list;
  for (std::size_t k = 0; k < p.choices.size(); ++k) {
    if (choice == p.choices[k]) return static_cast<int>(k);
    list += std::string(k ? ", '" : "'") + p.choices[k] + "'";
  }
  throw std::invalid_argument(name + " must be one of " + list + ", got '" + choice + "'");
}

void QueryOptions::validate() const {
  if (!(tolerance >= 0 && tolerance <= 1)) {
    throw std::invalid_argument(
        "tolerance must be a number in [0, 1] (relative to the pair's size), got " +
        detail::number_text(tolerance));
  }
  const MethodInfo& info = method_info(method);
  for (const ParameterInfo& p : info.parameters) check_value(p, p.get(*this));
  const auto ordered = [](double low, double high) {
    if (low > high) throw std::invalid_argument("w_min must not exceed w_max");
  };
  if (method == Method::ipso || method == Method::pso) ordered(swarm.w_min, swarm.w_max);
  if (method == Method::dual) ordered(dual.w_min, dual.w_max);
}

namespace detail {

void refuse_method(Method) { throw std::invalid_argument("unknown method"); }

namespace {

// The message of require_curved_capable.
[[noreturn]] void refuse_curved(Method method, const ConvexPolyhedron* curved) {
  std::string able;
  for (const MethodInfo& e : entries()) {
    if (e.capabilities & kCurvedShapes)
      able += std::string(able.empty() ? "'" : ", '") + e.name + "'";
  }
  throw std::invalid_argument(std::string("method '") + method_name(method) +
                              "' reads a body's points (vertices) as the body, and a " +
                              curved->curved()->name() +
                              " is a curved shape defined by its support function: use method " +
                              able + ", which answer every pair of shapes");
}

}  // namespace

void require_curved_capable(Method method, const ConvexPolyhedron* curved) {
  if (!(method_dispatch(method).capabilities & kCurvedShapes)) refuse_curved(method, curved);
}

}  // namespace detail

}  // namespace swarmcollide
