#include "swarmcollide/queries/query.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>

#include "../geometry/framed_body.hpp"
#include "../geometry/pose_check.hpp"
#include "ball_screen.hpp"
#include "dispatch.hpp"
#include "row_answer.hpp"
#include "swarmcollide/queries/methods.hpp"
#include "verdict.hpp"

namespace swarmcollide {

namespace {

// The pose of a body given without one: valid by construction, so the overloads without poses
// frame their pairs without validating it (frame_validated_pair).
const Pose kIdentity{};

}  // namespace

namespace detail {

std::string methods_with(Capability capability) {
  std::string able;
  for (const MethodInfo& info : method_table()) {
    if (info.capabilities & capability)
      able += std::string(able.empty() ? "'" : ", '") + info.name + "'";
  }
  return able;
}

void refuse_capability(Method method, Capability capability, const char* query) {
  throw std::invalid_argument(std::string(query) + " is not available with method '" +
                              method_name(method) + "'; use one of " + methods_with(capability));
}

}  // namespace detail

using detail::require;

namespace {

// The result of `options.method`'s solver working towards `goal` on `pair`.
DistanceResult answer(const QueryOptions& options, detail::Goal goal,
                      const detail::FramedPair& pair, detail::Weights weights) {
  return detail::finish_result(pair, detail::solver_for(options.method)(pair, options, goal),
                               options.method, goal, weights);
}

// The options an unproven verdict is escalated with: the exact method, at the query's tolerance
// and with its own iteration cap -- a budget too small for the method asked for (max_iterations
// of 1, say) must not leave the verdict unproven again.
QueryOptions escalation(const QueryOptions& options) {
  QueryOptions exact;
  exact.method = Method::exact;
  exact.tolerance = options.tolerance;
  exact.exact.max_iterations = std::max(options.exact.max_iterations, exact.exact.max_iterations);
  return exact;
}

// detail::answer_pair, always inline into Query's convex queries (answer_pair itself, out of
// line, is for the scenes): the call between them, with its arguments and its own frame, was
// some 20 instructions of every query.
[[gnu::always_inline]] inline DistanceResult answered_pair(const QueryOptions& options,
                                                           detail::Goal goal,
                                                           const detail::FramedPair& pair,
                                                           bool escalate,
                                                           detail::Weights weights) {
  using detail::Goal;
  if (pair.a.curved() || pair.b.curved()) {
    detail::require_shapes(options.method, pair.a.body(), pair.b.body());
  }
  // One named result, returned on every path, is made in the caller's place: returning either of
  // two named results moved the one returned, 70 instructions of every distance query.
  DistanceResult result = answer(options, goal, pair, weights);
  if (goal == Goal::verdict && !result.certified && escalate) {
    result = answer(escalation(options), goal, pair, weights);
    if (options.method != Method::exact) result.escalated_from = options.method;
  }
  return result;
}

// detail::answer_row, always inline into Query::collide (answer_row itself, out of line, is for
// the batches), as answered_pair is.
[[gnu::always_inline]] inline detail::RowAnswer answered_row(const QueryOptions& options,
                                                             detail::Solver solve,
                                                             detail::Goal goal,
                                                             const detail::FramedPair& pair,
                                                             bool escalate) {
  using detail::Goal;
  detail::Answer found = solve(pair, options, goal);
  // The values made in place in the row (assigned, they were made aside and copied in).
  detail::RowAnswer row{detail::finish_values(pair, found, goal),
                        found.answered_by.has_value() && *found.answered_by != options.method};
  if (goal != Goal::verdict || row.values.certified || !escalate) return row;
  detail::Answer decided = detail::solver_for(Method::exact)(pair, escalation(options), goal);
  row.escalated = options.method != Method::exact ||
                  (decided.answered_by.has_value() && *decided.answered_by != Method::exact);
  row.values = detail::finish_values(pair, decided, goal);
  return row;
}

// Whether `pair` collides, as collision() decides it: collide returns only the verdict, so it
// is taken from the values a batch row keeps, without the DistanceResult (weights over the
// given points, history) that collision() builds, a tenth of an overlapping verdict's cost
// between small bodies. Its callers have required the method to answer the pair's shapes
// (before the balls, which would settle a curved pair for a method that cannot answer it).
bool verdict_of(const QueryOptions& options, const detail::FramedPair& pair, bool escalate) {
  return answered_row(options, detail::solver_for(options.method), detail::Goal::verdict, pair,
                      escalate)
      .values.colliding;
}

}  // namespace

namespace detail {

DistanceResult answer_pair(const QueryOptions& options, Goal goal, const FramedPair& pair,
                           bool escalate, Weights weights) {
  return answered_pair(options, goal, pair, escalate, weights);
}

RowAnswer answer_row(const QueryOptions& options, Solver solve, Goal goal, const FramedPair& pair,
                     bool escalate) {
  return answered_row(options, solve, goal, pair, escalate);
}

}  // namespace detail

Query::Query(QueryOptions options) : options_(std::move(options)) { options_.validate(); }

DistanceResult Query::distance(const ConvexPolyhedron& a, const ConvexPolyhedron& b) const {
  require(options_.method, kDistance, "distance");
  return answered_pair(
      options_, detail::Goal::distance,
      detail::frame_validated_pair(a, kIdentity, b, kIdentity, options_.tolerance), false,
      detail::Weights::given);
}

DistanceResult Query::distance(const ConvexPolyhedron& a, const Pose& pose_a,
                               const ConvexPolyhedron& b, const Pose& pose_b) const {
  require(options_.method, kDistance, "distance");
  return answered_pair(options_, detail::Goal::distance,
                       detail::frame_pair(a, pose_a, b, pose_b, options_.tolerance), false,
                       detail::Weights::given);
}

DistanceResult Query::collision(const ConvexPolyhedron& a, const ConvexPolyhedron& b,
                                bool escalate) const {
  require(options_.method, kCollide, "collide");
  return answered_pair(
      options_, detail::Goal::verdict,
      detail::frame_validated_pair(a, kIdentity, b, kIdentity, options_.tolerance), escalate,
      detail::Weights::given);
}

DistanceResult Query::collision(const ConvexPolyhedron& a, const Pose& pose_a,
                                const ConvexPolyhedron& b, const Pose& pose_b,
                                bool escalate) const {
  require(options_.method, kCollide, "collide");
  return answered_pair(options_, detail::Goal::verdict,
                       detail::frame_pair(a, pose_a, b, pose_b, options_.tolerance), escalate,
                       detail::Weights::given);
}

bool Query::collide(const ConvexPolyhedron& a, const ConvexPolyhedron& b, bool escalate) const {
  require(options_.method, kCollide, "collide");
  detail::require_shapes(options_.method, a, b);
  if (detail::outer_balls_apart(a, kIdentity, false, b, kIdentity, false, options_.tolerance)) {
    return false;
  }
  return verdict_of(options_,
                    detail::frame_validated_pair(a, kIdentity, b, kIdentity, options_.tolerance),
                    escalate);
}

bool Query::collide(const ConvexPolyhedron& a, const Pose& pose_a, const ConvexPolyhedron& b,
                    const Pose& pose_b, bool escalate) const {
  require(options_.method, kCollide, "collide");
  // frame_pair's checks, made before the balls read the poses.
  const detail::PoseTurns turned = detail::validated_turns(pose_a, pose_b);
  detail::require_shapes(options_.method, a, b);
  if (detail::outer_balls_apart(a, pose_a, turned.a, b, pose_b, turned.b, options_.tolerance)) {
    return false;
  }
  return verdict_of(options_,
                    detail::frame_turned_pair(a, pose_a, turned.a, b, pose_b, turned.b,
                                              options_.tolerance),
                    escalate);
}

DistanceResult Query::signed_distance(const ConvexPolyhedron& a, const ConvexPolyhedron& b) const {
  require(options_.method, kSignedDistance, "signed_distance");
  return answered_pair(
      options_, detail::Goal::signed_distance,
      detail::frame_validated_pair(a, kIdentity, b, kIdentity, options_.tolerance), false,
      detail::Weights::given);
}

DistanceResult Query::signed_distance(const ConvexPolyhedron& a, const Pose& pose_a,
                                      const ConvexPolyhedron& b, const Pose& pose_b) const {
  require(options_.method, kSignedDistance, "signed_distance");
  return answered_pair(options_, detail::Goal::signed_distance,
                       detail::frame_pair(a, pose_a, b, pose_b, options_.tolerance), false,
                       detail::Weights::given);
}

DistanceResult distance(const ConvexPolyhedron& a, const ConvexPolyhedron& b,
                        const QueryOptions& options) {
  return Query(options).distance(a, b);
}

bool collide(const ConvexPolyhedron& a, const ConvexPolyhedron& b, const QueryOptions& options) {
  return Query(options).collide(a, b);
}

DistanceResult signed_distance(const ConvexPolyhedron& a, const ConvexPolyhedron& b,
                               const QueryOptions& options) {
  return Query(options).signed_distance(a, b);
}

}  // namespace swarmcollide
