// Queries between compound bodies: branch and bound over the two bodies' bounding-volume trees,
// each part pair answered as Query answers a convex pair.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <queue>
#include <utility>
#include <vector>

#include "../geometry/framed_body.hpp"
#include "../geometry/normalise.hpp"
#include "../geometry/unit_direction.hpp"
#include "../solvers/dual_swarm.hpp"
#include "../solvers/minkowski.hpp"
#include "dispatch.hpp"
#include "rounded.hpp"
#include "swarmcollide/queries/batch.hpp"
#include "swarmcollide/queries/query.hpp"
#include "verdict.hpp"

namespace swarmcollide {

namespace {

using detail::Answer;
using detail::FramedPair;
using detail::Goal;
using detail::robust_length;
using detail::times_power_of_two;
using detail::unit_direction;
using detail::unit_direction_or;

constexpr Scalar kInfinity = std::numeric_limits<Scalar>::infinity();
// Rounding of the world-unit bounds computed here (placed volumes, sums of bounds), relative to
// the magnitudes involved: a few roundings of numbers at most that large.
constexpr Scalar kWorldRounding = 1e-12;

const Pose kIdentity{};

// A tree node placed in the world: its ball, and the box of its box's eight corners.
struct PlacedVolume {
  Vector3 centre;
  Scalar radius;
  Vector3 low;
  Vector3 high;
  // The magnitude of the numbers above, for their rounding.
  Scalar scale;
};

std::vector<PlacedVolume> place(const CompoundBody& body, const Pose& pose) {
  std::vector<PlacedVolume> placed;
  placed.reserve(body.tree().size());
  const Matrix3 spread = pose.rotation.cwiseAbs();
  for (const PartNode& node : body.tree()) {
    const Vector3 box_centre =
        pose.rotation * ((node.box.min + node.box.max) / 2) + pose.translation;
    const Vector3 half = spread * ((node.box.max - node.box.min) / 2);
    const Vector3 centre = pose.rotation * node.centre + pose.translation;
    // Every coordinate computed from this node (its volumes, and its envelope's separations,
    // which add the translation to points in the body's frame) is at most this large.
    const Scalar scale = centre.cwiseAbs().maxCoeff() + box_centre.cwiseAbs().maxCoeff() +
                         half.sum() + node.radius + node.centre.cwiseAbs().sum() +
                         pose.translation.cwiseAbs().sum();
    placed.push_back({centre, node.radius, box_centre - half, box_centre + half, scale});
  }
  return placed;
}

// A lower bound on the signed distance (so on the distance) between any convex set in `a` and
// any in `b`: the larger of the balls' signed distance and the boxes'. Both volumes hold their
// parts, so a translation separating the volumes separates the parts, and the parts are at
// least as far apart as the volumes. Lengths are robust_length's: volumes 1e154 apart have
// squared distances beyond the double range (their bound was infinite, and pruned every pair).
Scalar volume_bound(const PlacedVolume& a, const PlacedVolume& b) {
  const Scalar balls = robust_length(b.centre - a.centre) - a.radius - b.radius;
  const Vector3 gaps = (a.low - b.high).cwiseMax(b.low - a.high);
  // -overlap when inside
  const Scalar boxes = gaps.maxCoeff() > 0 ? robust_length(gaps.cwiseMax(0.0)) : gaps.maxCoeff();
  return std::max(balls, boxes) - kWorldRounding * (a.scale + b.scale);
}

struct NodePair {
  Scalar bound;
  int a;
  int b;
  bool operator>(const NodePair& other) const { return bound > other.bound; }
};

// One part pair's answer in world units, with the parts that gave it.
struct PartAnswer {
  DistanceResult result;
  int part_a = -1;
  int part_b = -1;
};

// The search for one query between two compound bodies.
class CompoundSearch {
 public:
  CompoundSearch(const QueryOptions& options, Goal goal, bool escalate, const CompoundBody& a,
                 const Pose& pose_a, const CompoundBody& b, const Pose& pose_b)
      : options_(options),
        goal_(goal),
        escalate_(escalate),
        a_(a),
        b_(b),
        pose_a_(pose_a),
        pose_b_(pose_b) {
    // The pair of whole bodies sets the tolerance, in world units, of every part pair; its frame
    // also validates the poses and the pair's extent.
    const FramedPair whole =
        detail::frame_pair(a.envelope(), pose_a, b.envelope(), pose_b, options.tolerance);
    size_ = whole.frame.length_to_world(whole.frame.size);
    tolerance_ = whole.frame.length_to_world(whole.tolerance);
    stats_.part_pairs = static_cast<long>(a.size()) * b.size();
    placed_a_ = place(a, pose_a);
    placed_b_ = place(b, pose_b);
    hints_a_.assign(a.tree().size(), 0);
    hints_b_.assign(b.tree().size(), 0);
    method_can_measure_ = method_info(options.method).capabilities & kDistance;
  }

  CompoundResult run() {
    std::priority_queue<NodePair, std::vector<NodePair>, std::greater<NodePair>> open;
    open.push({bound(0, 0), 0, 0});
    // The bounds of the pairs left unopened: the first one popped past the cut is the smallest.
    Scalar unopened = kInfinity;
    while (!open.empty() && !done_) {
      const NodePair next = open.top();
      open.pop();
      if (cut(next.bound)) {
        unopened = next.bound;
        break;
      }
      const PartNode& na = a_.tree()[next.a];
      const PartNode& nb = b_.tree()[next.b];
      if (na.leaf() && nb.leaf()) {
        answer_parts(na.part, nb.part);
        continue;
      }
      // Open the larger volume (a leaf cannot be opened), so the bounds tighten fastest.
      const bool open_a = !na.leaf() && (nb.leaf() || na.radius >= nb.radius);
      for (const int child :
           open_a ? std::array<int, 2>{na.left, na.right} : std::array<int, 2>{nb.left, nb.right}) {
        const int ca = open_a ? child : next.a;
        const int cb = open_a ? next.b : child;
        const Scalar lower = bound(ca, cb);
        if (cut(lower)) {
          unopened = std::min(unopened, lower);
        } else {
          open.push({lower, ca, cb});
        }
      }
    }
    lower_ = std::min(lower_, unopened);
    if (!best_) witness_nearest();
    return finish();
  }

 private:
  Scalar bound(int na, int nb) {
    ++stats_.volume_tests;
    const PlacedVolume& va = placed_a_[na];
    const PlacedVolume& vb = placed_b_[nb];
    Scalar lower = volume_bound(va, vb);
    if (goal_ != Goal::signed_distance) lower = std::max(lower, 0.0);
    if (cut(lower)) return lower;
    // The nodes' envelopes, separated along the line between their balls' centres and along
    // the direction that separates the best pair found so far: the convex BVH's own bound,
    // far tighter than the balls for the slabs a decomposition makes.
    const Vector3 between = vb.centre - va.centre;
    if (const auto n = unit_direction(between)) lower = std::max(lower, separation(na, nb, *n));
    if (best_ && best_->result.direction.squaredNorm() > 0 && !cut(lower)) {
      lower = std::max(lower, separation(na, nb, best_->result.direction));
    }
    return lower;
  }

  // The separation of nodes `na` and `nb` along the world unit direction `n` (a lower bound on
  // the signed distance of every part pair below them), less its rounding: each support point
  // is found in its body's own frame, so no point is moved.
  // Large envelopes are climbed (over their hulls, computed once per body) from the support
  // point their node had last.
  Scalar separation(int na, int nb, const Vector3& n) {
    const ConvexPolyhedron& ea = a_.node_envelopes()[na];
    const ConvexPolyhedron& eb = b_.node_envelopes()[nb];
    const Vector3 da = pose_a_.rotation.transpose() * n;
    const Vector3 db = pose_b_.rotation.transpose() * n;
    int& ha = hints_a_[na];
    int& hb = hints_b_[nb];
    ha = ea.support_index(da, ha);
    hb = eb.support_index(-db, hb);
    const Scalar high_a = da.dot(ea.vertices().row(ha).transpose()) + n.dot(pose_a_.translation);
    const Scalar low_b = db.dot(eb.vertices().row(hb).transpose()) + n.dot(pose_b_.translation);
    // The envelopes are rounded by their parts' largest radius (the scales count it).
    return low_b - high_a - (ea.radius() + eb.radius()) -
           kWorldRounding * (placed_a_[na].scale + placed_b_[nb].scale);
  }

  // True when every part pair at least `lower` apart can be left out: it cannot come closer
  // than the best found by more than the tolerance, or (for a verdict) it is proven apart.
  bool cut(Scalar lower) const {
    if (goal_ == Goal::verdict) return lower - kWorldRounding * size_ > tolerance_;
    return lower >= upper() - tolerance_;
  }

  Scalar upper() const { return best_ ? best_->result.distance : kInfinity; }

  // A separation `s` of the cores of the pair's frame as a certified world-unit bound on the
  // (rounded) parts' distance.
  static Scalar world(const FramedPair& pair, Scalar s) {
    return pair.frame.length_to_world(detail::rounded_lower(pair, s) - detail::kFrameRounding);
  }

  // The pair of parts i (of A) and j (of B) in their own frame, its tolerance the whole pair's.
  FramedPair frame(int i, int j) const {
    FramedPair pair = detail::frame_pair(a_.parts()[i], pose_a_, b_.parts()[j], pose_b_, 0);
    pair.tolerance = times_power_of_two(tolerance_, -pair.frame.exponent);
    return pair;
  }

  Answer solve(const FramedPair& pair, const QueryOptions& options, Goal goal,
               const detail::DualStart& start) const {
    if (options.method == Method::dual) return detail::solve_dual(pair, options, goal, start);
    return detail::solver_for(options.method)(pair, options, goal);
  }

  void offer(DistanceResult&& result, int i, int j) {
    lower_ = std::min(lower_, result.lower_bound);
    iterations_ += result.iterations;
    evaluations_ += result.evaluations;
    if (!best_ || result.distance < best_->result.distance) {
      best_ = PartAnswer{std::move(result), i, j};
    }
  }

  void answer_parts(int i, int j) {
    FramedPair pair = frame(i, j);
    // The line between the parts' centres settles most pairs in two support evaluations.
    const Vector3 between = pair.b.offset() - pair.a.offset();
    Vector3 n = unit_direction_or(between, Vector3::UnitX());
    int ia = -1;
    int ib = -1;
    Scalar s = detail::separation(pair.a, pair.b, n, ia, ib);
    // The direction that separates the best pair found so far often separates its neighbours
    // by more than the centres' line does (parts of a decomposition are slabs, not balls).
    if (best_ && best_->result.direction.squaredNorm() > 0 && !cut(world(pair, s))) {
      const Vector3 m = best_->result.direction;
      int ja = -1;
      int jb = -1;
      const Scalar t = detail::separation(pair.a, pair.b, m, ja, jb);
      if (t > s) {
        s = t;
        n = m;
        ia = ja;
        ib = jb;
      }
    }
    const Scalar s_world = world(pair, s);
    if (cut(s_world)) {
      ++stats_.screened;
      lower_ = std::min(lower_, s_world);
      if (goal_ == Goal::verdict) offer_witnesses(pair, n, s_world, ia, ib, i, j);
      return;
    }
    ++stats_.solved;
    QueryOptions options = options_;
    options.seed = pair_seed(options_.seed, (static_cast<std::uint64_t>(i) << 32) | j);
    const detail::DualStart start{n, ia, ib};
    switch (goal_) {
      case Goal::verdict:
        return decide(pair, options, start, i, j);
      case Goal::distance:
        return measure(pair, options, start, i, j);
      case Goal::signed_distance:
        break;
    }
    offer(detail::finish_result(pair, solve(pair, options, Goal::signed_distance, start),
                                options.method, Goal::signed_distance),
          i, j);
  }

  // Collision: the part pair's verdict, escalated as Query::collision escalates; a contact
  // proven ends the search.
  void decide(const FramedPair& pair, const QueryOptions& options, const detail::DualStart& start,
              int i, int j) {
    // Methods without distances decide by their signed distance, as Query::collision does.
    const Goal verdict = method_can_measure_ ? Goal::verdict : Goal::signed_distance;
    DistanceResult r =
        detail::finish_result(pair, solve(pair, options, verdict, start), options.method, verdict);
    if (!r.certified && escalate_) {
      QueryOptions exact = options;
      exact.method = Method::exact;
      exact.exact.max_iterations =
          std::max(options.exact.max_iterations, ExactOptions{}.max_iterations);
      r = detail::finish_result(pair, detail::solver_for(Method::exact)(pair, exact, Goal::verdict),
                                Method::exact, Goal::verdict);
      if (options.method != Method::exact) r.escalated_from = options.method;
    }
    if (r.colliding) {
      if (r.certified || !contact_) contact_ = PartAnswer{r, i, j};
      done_ = r.certified;
    }
    offer(std::move(r), i, j);
  }

  // Distance: first whether the pair can beat the best found (a verdict at that threshold,
  // which stops as soon as the pair is proven farther), then its distance if it can.
  void measure(const FramedPair& pair, const QueryOptions& options, const detail::DualStart& start,
               int i, int j) {
    std::optional<detail::DualStart> from = start;
    const Scalar threshold = upper() - tolerance_;
    if (std::isfinite(threshold) && threshold > tolerance_) {
      FramedPair gate = pair;
      gate.tolerance = times_power_of_two(threshold, -pair.frame.exponent);
      const Goal verdict = method_can_measure_ ? Goal::verdict : Goal::signed_distance;
      Answer screened = solve(gate, options, verdict, start);
      if (detail::verdict_proven(gate, screened.lower, kInfinity, false)) {
        lower_ = std::min(lower_, world(pair, screened.lower));
        iterations_ += screened.iterations;
        evaluations_ += screened.evaluations;
        return;
      }
      if (detail::goal_reached(pair, Goal::distance, screened.lower, screened.upper,
                               screened.intersection_proven)) {
        return offer(
            detail::finish_result(pair, std::move(screened), options.method, Goal::distance), i, j);
      }
      if (screened.direction.squaredNorm() > 0) from->direction = screened.direction;
    }
    offer(detail::finish_result(pair, solve(pair, options, Goal::distance, *from), options.method,
                                Goal::distance),
          i, j);
  }

  // A part pair's witnesses from a separation: the support points along `n` (moved out to the
  // rounded parts' surfaces) bound the distance from above, the separation from below.
  void offer_witnesses(const FramedPair& pair, const Vector3& n, Scalar s_world, int ia, int ib,
                       int i, int j) {
    DistanceResult r;
    Answer core;
    core.point_a = pair.a.vertex(ia);
    core.point_b = pair.b.vertex(ib);
    core.upper = robust_length(core.point_b - core.point_a);
    detail::round_answer(pair, Goal::distance, core);
    r.point_a = pair.frame.point_to_world(core.point_a);
    r.point_b = pair.frame.point_to_world(core.point_b);
    r.distance = robust_length(r.point_b - r.point_a) * (1 + kWorldRounding);
    r.lower_bound = s_world;
    r.weights_a =
        pair.a.given_weights(ConvexWeights(pair.a.size(), {ia, 0, 0, 0}, {1, 0, 0, 0}, 1));
    r.weights_b =
        pair.b.given_weights(ConvexWeights(pair.b.size(), {ib, 0, 0, 0}, {1, 0, 0, 0}, 1));
    r.direction = n;
    r.method = options_.method;
    r.certified = true;
    r.status = SolverStatus::converged;
    if (!best_ || r.distance < best_->result.distance) best_ = PartAnswer{std::move(r), i, j};
  }

  // A verdict of "apart" settled by the volumes alone has met no part pair: the witnesses are
  // those of the pair of leaves reached by always opening the nearest volumes.
  void witness_nearest() {
    int na = 0;
    int nb = 0;
    while (!a_.tree()[na].leaf() || !b_.tree()[nb].leaf()) {
      const PartNode& x = a_.tree()[na];
      const PartNode& y = b_.tree()[nb];
      const bool open_a = !x.leaf() && (y.leaf() || x.radius >= y.radius);
      const int first = open_a ? x.left : y.left;
      const int second = open_a ? x.right : y.right;
      const Scalar to_first = open_a ? volume_bound(placed_a_[first], placed_b_[nb])
                                     : volume_bound(placed_a_[na], placed_b_[first]);
      const Scalar to_second = open_a ? volume_bound(placed_a_[second], placed_b_[nb])
                                      : volume_bound(placed_a_[na], placed_b_[second]);
      (open_a ? na : nb) = to_first <= to_second ? first : second;
    }
    const int i = a_.tree()[na].part;
    const int j = b_.tree()[nb].part;
    const FramedPair pair = frame(i, j);
    const Vector3 between = pair.b.offset() - pair.a.offset();
    const Vector3 n = unit_direction_or(between, Vector3::UnitX());
    int ia = -1;
    int ib = -1;
    const Scalar s = detail::separation(pair.a, pair.b, n, ia, ib);
    offer_witnesses(pair, n, world(pair, s), ia, ib, i, j);
  }

  CompoundResult finish() {
    const PartAnswer& chosen = contact_ ? *contact_ : *best_;
    CompoundResult out;
    static_cast<DistanceResult&>(out) = chosen.result;
    out.part_a = chosen.part_a;
    out.part_b = chosen.part_b;
    out.stats = stats_;
    out.iterations = iterations_;
    out.evaluations = evaluations_;
    const Scalar margin = kWorldRounding * size_;
    if (goal_ == Goal::verdict) {
      // A contact proven, or every part pair proven apart (else an unproven contact).
      if (!contact_) out.lower_bound = std::max(lower_, 0.0);
      out.colliding = contact_.has_value();
      out.certified = contact_ ? contact_->result.certified : true;
      out.status = out.certified ? SolverStatus::converged : SolverStatus::max_iterations;
      return out;
    }
    out.lower_bound = goal_ == Goal::signed_distance ? lower_ : std::max(lower_, 0.0);
    const bool apart = out.lower_bound - margin > tolerance_;
    const bool close = chosen.result.colliding && chosen.result.certified;
    const bool exact = out.distance - out.lower_bound <= tolerance_ + margin;
    out.colliding = !apart;
    out.certified = (apart || close) && (goal_ != Goal::signed_distance || exact);
    out.status = exact || (close && goal_ != Goal::signed_distance) ? SolverStatus::converged
                                                                    : SolverStatus::max_iterations;
    return out;
  }

  const QueryOptions& options_;
  Goal goal_;
  bool escalate_;
  const CompoundBody& a_;
  const CompoundBody& b_;
  const Pose& pose_a_;
  const Pose& pose_b_;
  Scalar size_ = 0;
  Scalar tolerance_ = 0;
  bool method_can_measure_ = true;
  std::vector<PlacedVolume> placed_a_;
  std::vector<PlacedVolume> placed_b_;
  // Support points of each node's envelope, where the next climb starts.
  std::vector<int> hints_a_;
  std::vector<int> hints_b_;
  CompoundStats stats_;
  // The smallest lower bound of every part pair met or left out so far.
  Scalar lower_ = kInfinity;
  std::optional<PartAnswer> best_;
  // Collision: the part pair in contact (proven, or the first unproven one).
  std::optional<PartAnswer> contact_;
  bool done_ = false;
  int iterations_ = 0;
  long evaluations_ = 0;
};

// A pair of bodies of one part each, answered as Query answers the convex pair of their parts:
// a convex body wrapped in a compound one (as a batch wraps every row's once any row holds a
// compound body) answers alike, bit for bit. The search's own start and part-pair seed made
// such rows differ from the convex query's within their bounds.
CompoundResult one_part_each(const QueryOptions& options, Goal goal, bool escalate,
                             const CompoundBody& a, const Pose& pose_a, const CompoundBody& b,
                             const Pose& pose_b) {
  CompoundResult out;
  static_cast<DistanceResult&>(out) = detail::answer_pair(
      options, goal, detail::frame_pair(a.parts()[0], pose_a, b.parts()[0], pose_b,
                                        options.tolerance),
      escalate);
  out.part_a = 0;
  out.part_b = 0;
  out.stats.part_pairs = 1;
  out.stats.solved = 1;
  return out;
}

}  // namespace

namespace detail {

CompoundResult answer_compound(const QueryOptions& options, Goal goal, bool escalate,
                               const CompoundBody& a, const Pose& pose_a, const CompoundBody& b,
                               const Pose& pose_b) {
  // The part pairs are answered by the method's solver itself, past answer_pair's check.
  require_parts(options.method, a, b);
  if (a.size() == 1 && b.size() == 1) {
    return one_part_each(options, goal, escalate, a, pose_a, b, pose_b);
  }
  return CompoundSearch(options, goal, escalate, a, pose_a, b, pose_b).run();
}

}  // namespace detail

CompoundResult Query::distance(const CompoundBody& a, const CompoundBody& b) const {
  return distance(a, kIdentity, b, kIdentity);
}

CompoundResult Query::distance(const CompoundBody& a, const Pose& pose_a, const CompoundBody& b,
                               const Pose& pose_b) const {
  detail::require(options_.method, kDistance, "distance");
  return detail::answer_compound(options_, Goal::distance, false, a, pose_a, b, pose_b);
}

CompoundResult Query::collision(const CompoundBody& a, const CompoundBody& b, bool escalate) const {
  return collision(a, kIdentity, b, kIdentity, escalate);
}

CompoundResult Query::collision(const CompoundBody& a, const Pose& pose_a, const CompoundBody& b,
                                const Pose& pose_b, bool escalate) const {
  detail::require(options_.method, kCollide, "collide");
  return detail::answer_compound(options_, Goal::verdict, escalate, a, pose_a, b, pose_b);
}

bool Query::collide(const CompoundBody& a, const CompoundBody& b, bool escalate) const {
  return collision(a, b, escalate).colliding;
}

bool Query::collide(const CompoundBody& a, const Pose& pose_a, const CompoundBody& b,
                    const Pose& pose_b, bool escalate) const {
  return collision(a, pose_a, b, pose_b, escalate).colliding;
}

CompoundResult Query::signed_distance(const CompoundBody& a, const CompoundBody& b) const {
  return signed_distance(a, kIdentity, b, kIdentity);
}

CompoundResult Query::signed_distance(const CompoundBody& a, const Pose& pose_a,
                                      const CompoundBody& b, const Pose& pose_b) const {
  detail::require(options_.method, kSignedDistance, "signed_distance");
  return detail::answer_compound(options_, Goal::signed_distance, false, a, pose_a, b, pose_b);
}

}  // namespace swarmcollide
