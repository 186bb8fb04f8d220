// The solver behind each method; private to the library's sources.
#pragma once

#include <cstddef>
#include <string>

#include "../geometry/framed_body.hpp"
#include "../solvers/answer.hpp"
#include "swarmcollide/geometry/compound_body.hpp"
#include "swarmcollide/queries/compound_result.hpp"
#include "swarmcollide/queries/distance_result.hpp"
#include "swarmcollide/queries/methods.hpp"
#include "swarmcollide/queries/options.hpp"
#include "verdict.hpp"

namespace swarmcollide::detail {

/// A method's solver: answers `goal` for a framed pair (the options are validated).
using Solver = Answer (*)(const FramedPair& pair, const QueryOptions& options, Goal goal);

/// The number of methods (the enum's values).
inline constexpr std::size_t kMethodCount = static_cast<std::size_t>(Method::libccd) + 1;

/// What a query needs of its method: its `Capability` flags and its solver.
struct MethodDispatch {
  unsigned capabilities;
  Solver solve;
};

/// Every method's, in the enum's order (methods.cpp, whose method table reads the capabilities).
extern const MethodDispatch kMethodDispatch[kMethodCount];

/// Throws std::invalid_argument for a value outside the Method enum.
[[noreturn]] void refuse_method(Method method);

/// The dispatch entry of `method`.
inline const MethodDispatch& method_dispatch(Method method) {
  const auto index = static_cast<std::size_t>(method);
  if (index >= kMethodCount) refuse_method(method);
  return kMethodDispatch[index];
}

/// The solver of `method`.
inline Solver solver_for(Method method) { return method_dispatch(method).solve; }

/// The names of the methods with `capability`, quoted and comma-separated ('dual', 'exact', ...),
/// for the messages that refuse a method without it.
std::string methods_with(Capability capability);

/// Throws std::invalid_argument naming the methods that can answer `query` (which has
/// `capability`), which `method` cannot.
[[noreturn]] void refuse_capability(Method method, Capability capability, const char* query);

/// Throws std::invalid_argument when `method` cannot answer `query` (which has `capability`),
/// naming the methods that can. Inline: every query asks it.
inline void require(Method method, Capability capability, const char* query) {
  if (!(method_dispatch(method).capabilities & capability)) {
    refuse_capability(method, capability, query);
  }
}

/// Throws std::invalid_argument naming the methods that answer curved shapes when `method` is
/// not one of them (`curved` is the curved body the message names); reads
/// the dispatch table (method_info's table, behind its static's guard and a call, was 45
/// instructions of every curved query). Out of line (methods.cpp): inline, its table read changed
/// the code of the polytope queries around it (a distance 1 instruction longer).
void require_curved_capable(Method method, const ConvexPolyhedron* curved);

/// Throws std::invalid_argument when `method` cannot answer a pair with the curved body `a` or
/// `b` (ConvexPolyhedron::curved), naming the methods that can. Cheap for polyhedra.
inline void require_shapes(Method method, const ConvexPolyhedron& a, const ConvexPolyhedron& b) {
  if (!a.curved() && !b.curved()) return;
  // The default method answers curved shapes (its entry's kCurvedShapes): asked of it, the
  // call was some 17 instructions of every curved query. Its entry is not read here: the table
  // read inline made every polytope query 2 instructions longer (session 41, callgrind_query);
  // test_methods asserts that the entry has the flag.
  if (method == Method::dual) return;
  require_curved_capable(method, a.curved() ? &a : &b);
}

/// The same for compound bodies with curved parts (CompoundBody::curved_part).
inline void require_parts(Method method, const CompoundBody& a, const CompoundBody& b) {
  const ConvexPolyhedron* curved = a.curved_part() ? a.curved_part() : b.curved_part();
  if (curved) require_curved_capable(method, curved);
}

/// What Query answers between the convex bodies of `pair` (framed, so with their poses checked)
/// for `goal`, with options already validated and the method's capability already required:
/// the method's answer, and for a verdict that it leaves unproven, with `escalate`, the exact
/// method's. Query's convex queries and the batches (which validate once per batch, and report no
/// weights) share it.
DistanceResult answer_pair(const QueryOptions& options, Goal goal, const FramedPair& pair,
                           bool escalate, Weights weights = Weights::given);

/// The same between compound bodies (compound_query.cpp); the poses are validated here.
CompoundResult answer_compound(const QueryOptions& options, Goal goal, bool escalate,
                               const CompoundBody& a, const Pose& pose_a, const CompoundBody& b,
                               const Pose& pose_b);

}  // namespace swarmcollide::detail
