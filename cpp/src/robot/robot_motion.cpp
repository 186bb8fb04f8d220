#include "swarmcollide/robot/robot_motion.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

#include "../detail/row_threads.hpp"
#include "../geometry/framed_body.hpp"
#include "../geometry/unit_direction.hpp"
#include "../motion/advancement_steps.hpp"
#include "../queries/rounded.hpp"
#include "../queries/verdict.hpp"
#include "../solvers/exact_solver.hpp"
#include "../solvers/minkowski.hpp"
#include "box_screen.hpp"
#include "geometry_pairs.hpp"
#include "link_motion_bound.hpp"
#include "swarmcollide/queries/query.hpp"

namespace swarmcollide {

namespace {

constexpr Scalar kUnit = 0x1p-53;
constexpr Scalar kInfinity = std::numeric_limits<Scalar>::infinity();

// The time a gap `apart` lasts when it closes at most at `at + s growth` at a time s from now:
// the root of at h + growth h^2 / 2 = apart, rounded down.
Scalar local_reach(Scalar apart, const detail::LinkMotionBound::LocalSpeed& speed) {
  if (!(apart > 0)) return 0;
  const Scalar root = std::sqrt(speed.at * speed.at + 2 * speed.growth * apart);
  const Scalar denominator = speed.at + root;
  if (denominator == 0) return kInfinity;
  return 2 * apart / denominator * (1 - 8 * kUnit);
}

// The closing linear h + quadratic h^2/2 + cubic h^3/3 in a time h >= 0, as computed: with
// every coefficient nonnegative each rounded operation is nondecreasing in its operands, so the
// computed closing is nondecreasing in h too.
Scalar closing(Scalar h, const detail::LinkMotionBound::DirectionalSpeed& speed) {
  return h * (speed.linear + h * (speed.quadratic / 2 + h * speed.cubic / 3));
}

// The time a gap `apart` lasts when it closes by at most `closing` in a time h: the root, by
// bisection (the closing is increasing in h), rounded down.
Scalar directional_reach(Scalar apart, const detail::LinkMotionBound::DirectionalSpeed& speed) {
  if (!(apart > 0)) return 0;
  // Each term alone reaching the gap bounds the root above.
  Scalar high = kInfinity;
  if (speed.linear > 0) high = std::min(high, apart / speed.linear);
  if (speed.quadratic > 0) high = std::min(high, std::sqrt(2 * apart / speed.quadratic));
  if (speed.cubic > 0) high = std::min(high, std::cbrt(3 * apart / speed.cubic));
  if (high == kInfinity) return kInfinity;
  Scalar low = 0;
  for (int i = 0; i < 30; ++i) {
    const Scalar middle = (low + high) / 2;
    (closing(middle, speed) <= apart ? low : high) = middle;
  }
  return low * (1 - 8 * kUnit);
}

// The closing `rate h + a0 h^2/2 + a1 h^3/6 + a2 h^4/12` of a twist bound in a time h >= 0
// (`rate` the forward or backward one, of either sign), rounded up: each of the few rounded
// operations is within a roundoff of the magnitudes |rate| h and the curve's, 16 cover them.
Scalar twist_closing(Scalar h, Scalar rate, const detail::LinkMotionBound::TwistSpeed& speed) {
  const Scalar curve = h * (speed.a0 / 2 + h * (speed.a1 / 6 + h * speed.a2 / 12));
  return h * (rate + curve) + 16 * kUnit * h * (std::abs(rate) + curve);
}

// A time over which a gap `apart` lasts under twist_closing (proven, within 1e-4 of the latest
// or after 4 rounds): the exact closing is convex in h and 0 at 0, so the times it keeps within
// the gap are an interval from 0, and a time whose computed closing (above the exact one) is
// within the gap is in it. The root is bracketed by [lo, hi]: the secant over it lies above
// the closing there, so its root is at or before the closing's, and the tangent at lo lies below
// it, so its root is at or after; each is tried and kept on the side its closing puts it
// (bisection's 30 halvings cost 860 instructions a call, these rounds about 150).
Scalar twist_reach(Scalar apart, Scalar rate, const detail::LinkMotionBound::TwistSpeed& speed) {
  if (!(apart > 0)) return 0;
  Scalar hi = 1;
  Scalar closed_hi = twist_closing(hi, rate, speed);
  // Past the motion's length a reach proves nothing more.
  if (!(closed_hi > apart)) return 1;
  Scalar lo = 0;
  Scalar closed_lo = 0;
  const auto keep = [&](Scalar x) {
    const Scalar closed = twist_closing(x, rate, speed);
    if (closed > apart) {
      hi = x;
      closed_hi = closed;
      return false;
    }
    lo = x;
    closed_lo = closed;
    return true;
  };
  for (int round = 0; round < 4 && lo < hi * (1 - 1e-4); ++round) {
    const Scalar secant = lo + (apart - closed_lo) / (closed_hi - closed_lo) * (hi - lo);
    if (!(secant > lo && secant < hi) || !keep(secant)) continue;
    const Scalar slope = rate + lo * (speed.a0 + lo * (speed.a1 / 2 + lo * speed.a2 / 3));
    Scalar tangent = slope > 0 ? lo + (apart - closed_lo) / slope : hi;
    if (!(tangent < hi)) tangent = (lo + hi) / 2;
    if (tangent > lo) keep(tangent);
  }
  return lo;
}

// A separation measured again along a query's direction is stepped from while it is at least
// this fraction of what the query proved; below it the pair's nearest features have moved on,
// and a query finds its new direction. (bench/robot_motion_profile.py's 200 edges, callgrind
// inside robot_check_motion: 264.3M instructions and 42.2 queries per edge with none measured
// again; 246.0M and 28.3 at 0.5; 245.2M and 25.9 at 0.25. After the self pairs' directional
// bound in their common frame and the end screens' reach: 178.4M and 17.4 at 0.25 with the
// speculative sample at 0.8; with it at 0.6, 174.9M and 16.2 at 0.15, 176.3M and 15.9 at 0.1.
// Once a query after the first started from the last one's corral, on 1000 edges: 558.65M and
// 14.94 at 0.08, 555.34M and 15.26 at 0.15, 553.87M and 16.04 at 0.3, 557.29M and 17.27 at 0.5,
// 566.32M and 19.10 at 0.75.)
constexpr Scalar kRemeasured = 0.3;

// What one pair's distance at one time proves.
struct Sample {
  Scalar t;
  // Proven within the tolerance of contact at t.
  bool contact;
  // The time after t, and before it, over which the pair is proven apart.
  Scalar forward;
  Scalar backward;
};

// How one pair's advancement up to a horizon ended.
struct PairRun {
  enum Outcome { free, contact, unproven } outcome = free;
  // Proven apart before this time.
  Scalar lower = 0;
  // Proven in contact at this time (contact), or the earliest time found in contact (unproven;
  // +inf when none was).
  Scalar upper = kInfinity;
  MotionStatus status = MotionStatus::converged;
};

// A pair left unproven: proven apart before `lower` only.
struct Unproven {
  int pair;
  Scalar lower;
  MotionStatus status;
};

// A pair's speed and margin over the motion, and its screened reach from t = 0.
struct PairPlan {
  int pair;
  Scalar speed;
  Scalar margin;
  Scalar first_contact;
  // The screens' reach back from t = 1.
  Scalar from_end;
  // Neither geometry is compound: the queries' lower bound is a separation along a direction.
  bool convex;
  // A geometry is a curved shape (the exact method can leave it unproven near contact).
  bool curved;
  // What a distance in the samples' frame is at most in the world's, as a factor (1 in the
  // world's frame; MotionCheck::sample).
  Scalar stretch;
};

// One motion of a robot: the pairs advanced one by one, each up to the earliest contact found so
// far (a pair in contact later cannot change the answer; one in contact earlier lowers it).
class MotionCheck {
 public:
  MotionCheck(const RobotModel& model, const std::vector<GeometryPair>& pairs,
              const Configurations& q0, const Configurations& q1,
              const TimeOfImpactOptions& options, RobotMotionCheck& check)
      : model_(model), pairs_(pairs), q0_(q0), q1_(q1), options_(options), check_(check),
        bound_(model), q_(model.dof()) {
    // Per pair, the joints that place its two links below the link where their chains part,
    // in the model's order: a joint on both chains (bits 1 and 2) is one they share.
    std::vector<char> needed;
    for (const GeometryPair& pair : pairs) {
      needed.assign(model.joints().size(), 0);
      for (const int g : {pair.a, pair.b}) {
        const char bit = g == pair.a ? 1 : 2;
        for (int link = model.geometries()[static_cast<std::size_t>(g)].link;
             link >= 0 && model.parent_joint(link) >= 0;) {
          const int j = model.parent_joint(link);
          needed[static_cast<std::size_t>(j)] |= bit;
          link = model.joints()[static_cast<std::size_t>(j)].parent;
        }
      }
      std::vector<int>& joints = pair_joints_.emplace_back();
      for (const int j : model.joint_order()) {
        if (needed[static_cast<std::size_t>(j)] == 1 || needed[static_cast<std::size_t>(j)] == 2) {
          joints.push_back(j);
        }
      }
      common_links_.push_back(bound_.common_link(pair));
      shared_.push_back(bound_.shared_count(pair));
      stretch_.push_back(1 + 2 * bound_.common_sigma(pair));
    }
  }

  void operator()(std::size_t row) {
    const auto i = static_cast<Eigen::Index>(row);
    start_ = q0_.row(q0_.rows() == 1 ? 0 : i);
    end_ = q1_.row(q1_.rows() == 1 ? 0 : i);
    delta_ = end_ - start_;
    configuration_at(0);
    start_links_ = links_;
    configuration_at(1);
    end_links_ = links_;
    bound_.set_motion(start_.data(), end_.data(), start_links_, end_links_);
    // Every motion's queries take the caller's seed, as time_of_impact_many's do, so that a row
    // of a batch answers as the same motion alone (seeded by its row, a row whose samples the
    // dual method decided differed from it, within its bounds).
    QueryOptions query = options_.query;
    // A quarter of the motion's tolerance, as time_of_impact asks it: near contact the queries'
    // bounds are then within 3/8 of the threshold of each other, so a time not proven in contact
    // is proven apart by 5/8 of it less the margin, and bisection ends (motions.md).
    query.tolerance /= 4;
    const Query solver(query);
    query_ = &solver;
    second_.reset();
    iterations_ = 0;
    plan();
    Scalar horizon = 1;
    Scalar lower = 1;
    int best = -1;
    unproven_.clear();
    for (const PairPlan& plan : plans_) {
      if (plan.first_contact > horizon) continue;  // proven apart before the horizon
      if (iterations_ >= options_.max_iterations) {
        // Left unanswered: only its screened reach from t = 0 is proven.
        lower = std::min(lower, plan.first_contact);
        unproven_.push_back({plan.pair, plan.first_contact, MotionStatus::max_iterations});
        continue;
      }
      const PairRun run = advance(plan, horizon);
      if (run.outcome == PairRun::free) continue;
      lower = std::min(lower, run.lower);
      if (run.outcome == PairRun::unproven) unproven_.push_back({plan.pair, run.lower, run.status});
      // Ties keep the pair taken first; a contact at the motion's end is a contact too.
      if (run.upper < horizon || (best < 0 && run.upper == horizon)) {
        horizon = run.upper;
        best = plan.pair;
      }
    }
    // A pair left unproven matters only where it is not proven apart: before the contact found,
    // or anywhere when none was.
    int unproven = -1;
    MotionStatus status = MotionStatus::converged;
    for (const Unproven& pair : unproven_) {
      if (best >= 0 && pair.lower >= horizon) continue;
      unproven = pair.pair;
      status = pair.status;
      break;
    }
    const bool certified = status == MotionStatus::converged;
    check_.certified(i) = certified;
    check_.status[row] = status;
    check_.iterations(i) = iterations_;
    check_.t_lower(i) = std::min(lower, horizon);
    if (best < 0 && certified) {
      check_.touches(i) = false;
      check_.t_upper(i) = 1;
      check_.configuration.row(i) = end_;
      return;
    }
    const int named = best >= 0 ? best : unproven;
    check_.touches(i) = true;
    check_.t_upper(i) = horizon;
    check_.pair(i) = named;
    configuration_at(horizon);
    check_.configuration.row(i) = q_;
    place(pairs_[static_cast<std::size_t>(named)]);
    const GeometryPair& pair = pairs_[static_cast<std::size_t>(named)];
    // The samples asked distances; the answer gives the signed distance there.
    const DistanceResult contact =
        detail::signed_distance_of(*query_, model_, pair, pose_a_, pose_b_);
    check_.distance(i) = contact.distance;
    check_.point_a.row(i) = contact.point_a.transpose();
    check_.point_b.row(i) = contact.point_b.transpose();
    check_.normal.row(i) = contact.direction.transpose();
  }

 private:
  // The pair being advanced: its last query's unit separating direction (in the coordinates of
  // the frame its links' chains part at, as the samples are placed), the support points the
  // last measurement along it found (-1: none yet), and what that query proved apart.
  struct Separating {
    Vector3 direction;
    int ia;
    int ib;
    Scalar apart;
  };

  // Every pair's speed and margin, and the pairs in increasing order of their first possible
  // contact from their screens at t = 0, less those proven apart over the whole motion from the
  // screens at both ends.
  void plan() {
    plans_.clear();
    place_all(start_links_, start_world_, start_centres_, start_sizes_);
    place_all(end_links_, end_world_, end_centres_, end_sizes_);
    for (std::vector<char>& placed : chain_placed_) placed.assign(start_world_.size(), 0);
    for (auto& chains : end_chains_) chains.resize(start_world_.size());
    for (std::vector<char>& placed : box_placed_) placed.assign(start_world_.size(), 0);
    for (auto& boxes : end_boxes_) boxes.resize(start_world_.size());
    for (std::size_t p = 0; p < pairs_.size(); ++p) {
      const GeometryPair& pair = pairs_[p];
      const Scalar speed = bound_.pair_speed(pair);
      const Scalar margin = bound_.pair_margin(pair);
      // The balls at both ends first, then each end's local speed bound and its boxes, until
      // the reaches from the two ends meet.
      const Scalar balls_start =
          ball_separation(pair, start_centres_[pair.a], start_sizes_[pair.a],
                          start_centres_[pair.b], start_sizes_[pair.b]);
      const Scalar balls_end = ball_separation(pair, end_centres_[pair.a], end_sizes_[pair.a],
                                               end_centres_[pair.b], end_sizes_[pair.b]);
      if (detail::reach_over(balls_start - margin, speed) +
              detail::reach_over(balls_end - margin, speed) > 1) {
        continue;
      }
      const Scalar from_start = screened_reach(pair, 0, speed, margin, balls_start, 1);
      if (from_start > 1) continue;
      const Scalar from_end = screened_reach(pair, 1, speed, margin, balls_end, 1 - from_start);
      // Apart over the whole motion when the reaches from both ends meet.
      if (from_start + from_end > 1) continue;
      const Geometry& a = model_.geometries()[pair.a];
      const Geometry& b = model_.geometries()[pair.b];
      const bool convex = !a.parts && !b.parts;
      const bool curved = (!a.parts && a.body.curved()) || (!b.parts && b.body.curved());
      plans_.push_back(
          {static_cast<int>(p), speed, margin, from_start, from_end, convex, curved, stretch_[p]});
    }
    std::sort(plans_.begin(), plans_.end(), [](const PairPlan& x, const PairPlan& y) {
      return x.first_contact < y.first_contact ||
             (x.first_contact == y.first_contact && x.pair < y.pair);
    });
  }

  // The time either way from the motion's start (`end` 0) or end (1) over which the pair's screens
  // prove it apart: by the whole motion's speed bound, or the local one; from the balls'
  // separation `balls`, then from the boxes' face axes too unless the balls' alone reach past
  // `needed`.
  Scalar screened_reach(const GeometryPair& pair, int end, Scalar speed, Scalar margin,
                        Scalar balls, Scalar needed) {
    Scalar apart = balls - margin;
    Scalar reach = detail::reach_over(apart, speed);
    if (reach > needed) return reach;
    const detail::LinkMotionBound::LocalSpeed local =
        bound_.local_speed(pair, end_chain(end, pair.a), end_chain(end, pair.b));
    reach = std::max(reach, local_reach(apart, local));
    if (reach > needed) return reach;
    // The boxes' separation over their 6 face axes alone, not the 9 cross axes too: of the
    // 68.5k screens of bench/robot_motion_profile.py's 1000 edges (+20 warm-up), 57k do not
    // prove the pair apart either way, and the cross axes' twice the work bought them reaches
    // that saved fewer samples than they cost (callgrind 553.80M -> 512.48M instructions; 16.04
    // -> 16.37 queries per edge. The cross axes only where the face axes' reach is within half
    // of `needed`: 528.98M; the world's axes alone, from each box's world extent: 539.11M).
    const Scalar boxes =
        detail::face_separation(end_box(end, pair.a), end_box(end, pair.b)) - margin;
    if (!(boxes > apart)) return reach;
    return std::max(detail::reach_over(boxes, speed), local_reach(boxes, local));
  }

  // Geometry g's chain placed at the motion's start (`end` 0) or end (1), placed once per motion
  // for all the pairs of the geometry.
  const detail::LinkMotionBound::PlacedChain& end_chain(int end, int g) {
    const auto i = static_cast<std::size_t>(g);
    detail::LinkMotionBound::PlacedChain& chain = end_chains_[end][i];
    if (!chain_placed_[end][i]) {
      bound_.place_end_chain(g, end, end == 0 ? start_links_ : end_links_,
                             (end == 0 ? start_world_ : end_world_)[i], chain);
      chain_placed_[end][i] = 1;
    }
    return chain;
  }

  // Geometry g's box placed at the motion's start (`end` 0) or end (1), placed once per motion
  // for all the pairs of the geometry.
  const detail::PlacedBox& end_box(int end, int g) {
    const auto i = static_cast<std::size_t>(g);
    if (!box_placed_[end][i]) {
      end_boxes_[end][i] = detail::PlacedBox(model_.geometries()[i].body.bounds().box,
                                             (end == 0 ? start_world_ : end_world_)[i]);
      box_placed_[end][i] = 1;
    }
    return end_boxes_[end][i];
  }

  // Conservative advancement of one pair over [0, horizon] (time_of_impact's, with the horizon
  // in place of the motion's end).
  PairRun advance(const PairPlan& plan, Scalar horizon) {
    const GeometryPair& pair = pairs_[static_cast<std::size_t>(plan.pair)];
    const Scalar width = options_.time_tolerance;
    // Sampled times after `low`, nearest last: each one still to be reached.
    std::vector<Sample>& ahead = ahead_;
    ahead.clear();
    // The reach of the sample `low` replaced (none before the first step).
    Scalar before = kInfinity;
    Sample low;
    separating_.reset();
    corral_.size = 0;
    if (plan.first_contact > 0) {
      // The plan's screens prove the pair apart up to `first_contact`: the advancement starts
      // there rather than with a query at t = 0, and as from a reach that grew (from none), with
      // the speculative sample past it. (Queries per edge of bench/robot_motion.py's 1000 edges:
      // 76.1 with a query at t = 0; 56.1 from the screens' reach; 47.2 with the speculative
      // sample; 58.0 with a first sample midway between the two ends' screened reaches.)
      low = {0, false, plan.first_contact, 0};
      before = 0;
    } else {
      low = sample(pair, plan, 0, horizon);
      if (low.contact) return {PairRun::contact, 0, 0};
    }
    while (true) {
      if (!ahead.empty()) {
        const Sample& next = ahead.back();
        if (low.forward + next.backward >= next.t - low.t) {
          // Proven apart from both ends.
          before = low.forward;
          low = next;
          ahead.pop_back();
          if (low.contact) return {PairRun::contact, low.t, low.t};
          continue;
        }
        if (next.contact && next.t - low.t <= width) return {PairRun::contact, low.t, next.t};
      } else if (low.forward > horizon - low.t || low.forward + plan.from_end > 1 - low.t) {
        // Proven apart up to the horizon, or to where the screens at the end prove it apart
        // (over [1 - from_end, 1], which holds a horizon below 1 as well).
        return {PairRun::free, horizon, kInfinity};
      }
      if (iterations_ >= options_.max_iterations) {
        return unproven(low, MotionStatus::max_iterations);
      }
      const Scalar limit = ahead.empty() ? horizon : ahead.back().t;
      if (low.forward >= width) {
        const Scalar t = detail::advanced(low.t, low.forward);
        if (t > low.t && t < limit) {
          if (ahead.empty()) {
            // A sample past `t` whose reach back meets it proves more than one at `t` for the
            // same query. Near a configuration the reach changes roughly linearly in time: when
            // it went from `before` to `forward` over the last step (ratio rho = forward /
            // before, at most 1), the reach at a time f forward past `t` is about (1 - (1 + f)
            // (1 - rho)) forward, which is f forward for f = rho / (2 - rho); twice that is
            // sampled (capped halfway to the end, below). A pair moving apart (rho = 1) is
            // sampled twice the reach past `t`. When the sample does not reach back, the step to
            // `t` follows, and the sample still proves part of what is left after it. (Before the
            // cap, 0.6 of f was sampled. Queries per edge of bench/robot_motion.py's
            // 1000: moving apart only, 0.4 of the reach 90.0, 0.6 88.4, 0.8 87.9, 1 89.8, 1.5
            // 92.3, as of robotmotion31; later, with the closing pairs too, 47.2 -> 42.5 at 0.8
            // of f, 42.7 at 0.6, 44.8 at 1; after the self pairs' directional bound in their
            // common frame and the end screens' reach, 16.48 at 0.8 of f, 16.01 at 0.6, 17.28
            // at 1, and with kRemeasured 0.15, 15.91 at 0.8, 15.37 at 0.6, 15.54 at 0.5, 15.95
            // at 0.4: samples of either kind per edge 56.9, 54.0, 53.9, 54.7.) After a query at
            // t = 0 (no last step to take rho from) the pair is sampled as one moving apart.
            //
            // The pair is proven apart past `end` already (the horizon, or where the screens at
            // the motion's end prove it apart): a sample halfway from `t` to there proves the
            // rest with half its reach either way, where one farther out needs more than half
            // back and one nearer more than half forward, so the sample is taken at most halfway.
            // (bench/robot_motion_profile.py under callgrind, 300 edges: 140.21M -> 133.24M
            // instructions, and 16.71 -> 15.35 queries per edge on 1000; at most 0.4 of the way
            // 134.60M, at most 0.6 134.85M, halfway only where `far` is past `end` 135.82M; the
            // sample after a query at t = 0 taken so too, 133.24M -> 132.65M. Then with the cap
            // the sample is better placed farther out: 0.6 of f 132.65M, 0.8 128.99M, 1 126.81M,
            // 1.3 125.13M, 2 124.29M and 13.47 queries per edge, 4 125.51M.)
            const Scalar rho = before < kInfinity ? std::min<Scalar>(1, low.forward / before) : 1;
            Scalar far = detail::advanced(t, 2 * rho / (2 - rho) * low.forward);
            const Scalar end = std::min(limit, 1 - plan.from_end);
            if (t < end) far = std::min(far, t + (end - t) / 2);
            if (far > t && far < limit) {
              before = low.forward;
              ahead.push_back(sample(pair, plan, far, horizon));
              continue;
            }
          }
          const Sample reached = sample(pair, plan, t, horizon);
          if (reached.contact) return {PairRun::contact, t, t};
          before = low.forward;
          low = reached;
          continue;
        }
      }
      if (ahead.empty()) {
        if (low.t == horizon) {
          // Apart before the horizon, unproven at it: enough below the earliest contact found.
          if (horizon < 1) return {PairRun::free, horizon, kInfinity};
          return unproven(low, MotionStatus::unresolved);
        }
        // Steps are below the time tolerance: look one tolerance ahead.
        ahead.push_back(sample(pair, plan, std::min(horizon, low.t + width), horizon));
        continue;
      }
      // Steps are below the time tolerance with a contact ahead: look one tolerance ahead rather
      // than split the interval, as with none ahead. The steps stall where the pair closes at
      // about the speed that bounds them, so the contact is mostly within the tolerance, and a
      // contact there closes the bracket; a sample found apart is one more sample ahead.
      // (bench/robot_motion_profile.py's 1000 edges: queries per edge 15.45 -> 15.26; callgrind
      // on 200 edges 129.67M -> 128.53M. Probing past where `low`'s reach ends and closing the
      // bracket from there, 14.81 queries per edge but 132.03M: the contact sample then
      // overlaps, and the signed distance at the first contact runs the penetration solver.)
      const Scalar probe = detail::advanced(low.t, width);
      if (ahead.back().contact && probe > low.t && probe < limit) {
        ahead.push_back(sample(pair, plan, probe, horizon));
        continue;
      }
      // Neither end proves the interval: split it.
      const Scalar middle = low.t + (limit - low.t) / 2;
      if (!(middle > low.t && middle < limit)) return unproven(low, MotionStatus::unresolved);
      ahead.push_back(sample(pair, plan, middle, horizon));
    }
  }

  PairRun unproven(const Sample& low, MotionStatus status) const {
    PairRun run{PairRun::unproven, low.t, kInfinity, status};
    for (const Sample& s : ahead_) {
      if (s.contact) run.upper = std::min(run.upper, s.t);
    }
    return run;
  }

  // The pair at time t: its screens when they alone prove it apart up to the horizon; else the
  // separation along its last query's direction while that proves enough (kRemeasured); else a
  // distance query.
  //
  // The pair is placed in the frame of the link C where its links' chains part (the world's
  // when they share no joint), from the joints below C alone: C's frame is the identity, so the
  // joints they share are not evaluated. Every statement a sample makes is one about that
  // frame's coordinates, and carries over to the world's: there the points are p = R x + T with
  // x their coordinates in C and R^T R = I + S, |S| <= sigma_C (C's chain's deviation from
  // rigid; link_motion_bound.hpp), so a distance d in C is a distance between sqrt(1 - sigma_C)
  // d and sqrt(1 + sigma_C) d in the world. Apart in C (d > 0) is apart in the world, and the
  // speeds bound how fast C's distances shrink as they bound the world's: the shared joints move
  // nothing in C (as they move nothing relative in the world, which pair_speed and local_speed
  // pay the frames' deviation for), and the joints below C move the points in C by what their
  // terms bound, each frame from C down rigid within the chain's sigma to it (the factors 1 +
  // 4 sigma_j), the placed chains measured in C. The directional bound is the one in C's
  // coordinates (a separation measured there needs no loss; taking it anyway only shortens the
  // step). Within the tolerance of contact in C is within it in the world once stretched by
  // 1 + 2 sigma_C (`stretch`, above sqrt(1 + sigma_C) by 1.5 sigma_C >= 12 roundoffs, which
  // covers the product's rounding). The margin covers the rounding of the frames below C as of
  // the whole chains (C's coordinates are smaller than the world's: the chains' reach z at C is
  // at most the extent).
  Sample sample(const GeometryPair& pair, const PairPlan& plan, Scalar t, Scalar horizon) {
    const std::size_t p = static_cast<std::size_t>(plan.pair);
    configuration_at(t, &pair_joints_[p], common_links_[p]);
    place(pair);
    // t = 0 is sampled only where the plan's screens proved nothing there. Once a query gave a
    // direction, the separation along it is measured rather than the boxes': at about the same
    // cost, it bounds the distance much closer.
    if (t > 0) {
      // What the screens must prove: apart up to the horizon, or, from before where the
      // screens at the motion's end prove it apart, up to there (advance's test; a sample
      // after it is asked as before, for one ahead of `low` proves only its own reach).
      const bool before_end = t < 1 - plan.from_end;
      const Scalar needed =
          before_end ? std::min(horizon - t, 1 - plan.from_end - t) : horizon - t;
      const Scalar enough = plan.margin + plan.speed * needed;
      const Scalar balls = ball_separation(pair, pose_a_, pose_b_);
      const Scalar screened = detail::reach_over(
          (balls > enough || separating_ ? balls : screen_boxes(pair, pose_a_, pose_b_, balls)) -
              plan.margin,
          plan.speed);
      if (screened > horizon - t || (before_end && screened + plan.from_end > 1 - t)) {
        return {t, false, screened, screened};
      }
    }
    // The joints both chains share are not read by the pair's speeds: not placed.
    const std::size_t shared = shared_[static_cast<std::size_t>(plan.pair)];
    bound_.place_chain(pair.a, links_, pose_a_, chain_a_, shared);
    bound_.place_chain(pair.b, links_, pose_b_, chain_b_, shared);
    const detail::LinkMotionBound::LocalSpeed local =
        bound_.local_speed(pair, chain_a_, chain_b_);
    const BodyBounds& a = model_.geometries()[pair.a].body.bounds();
    const BodyBounds& b = model_.geometries()[pair.b].body.bounds();
    // The motion's size for this pair: the sum of the two bounding balls' diameters.
    const Scalar threshold = options_.query.tolerance * 2 * (a.radius + b.radius);
    const bool polytopes =
        query_->options().method == Method::exact && plan.convex && !plan.curved;
    if (separating_ || polytopes) {
      const detail::FramedPair framed = frame(pair);
      if (separating_) {
        // The separation along the last query's direction is a lower bound on the distance as
        // a query's is (the same support climbs), at a tenth of a query's cost; it is stepped
        // from while it keeps 0.3 of what that query proved (kRemeasured). Any direction gives
        // a lower bound: one fixed in the frame where the links' chains part (the samples'
        // frame) turns with both links as the joints they share move, and keeps their
        // separation (directional_speed).
        const Scalar apart = separation_along(framed, *separating_) - plan.margin;
        if (apart > threshold && apart >= kRemeasured * separating_->apart) {
          return apart_sample(pair, plan, t, apart, separating_->direction, local);
        }
      }
      if (polytopes) {
        // Query::distance's answer for two polytopes with the exact method (its solver's on
        // the same framed pair), without framing the pair again; after the pair's first query,
        // Wolfe's algorithm starts from that query's last corral (exact_distance_again).
        // (bench/robot_motion_profile.py's 1000 edges under callgrind: 577.7M -> 555.4M
        // instructions. Started from the last query's direction instead of the centres'
        // difference, Wolfe's steps were as many: on 200 edges, exact_distance 27.98M -> 27.84M.)
        ++iterations_;
        detail::Answer answer =
            detail::exact_distance_again(framed, query_->options().exact.max_iterations, corral_);
        return answered(pair, plan, t, local, threshold,
                        detail::finish_result(framed, std::move(answer), Method::exact,
                                              detail::Goal::distance, detail::Weights::none));
      }
    }
    ++iterations_;
    // A distance, as time_of_impact asks: its lower bound is all the advancement needs, and a
    // pair in contact is not measured further (its penetration depth).
    return answered(pair, plan, t, local, threshold,
                    detail::distance_of(*query_, model_, pair, pose_a_, pose_b_));
  }

  // A sample from the query's `result` at t (the pair placed there, `local` its local speed):
  // the answer asked again where it is unproven, then contact, or the time it proves apart.
  Sample answered(const GeometryPair& pair, const PairPlan& plan, Scalar t,
                  const detail::LinkMotionBound::LocalSpeed& local, Scalar threshold,
                  DistanceResult result) {
    if (!result.certified) {
      // Near contact a method can leave a pair unproven where another proves it: ask it too
      // rather than bisect down to times that cannot be split. After any method but exact, the
      // exact one. After the exact method, only where the answer decides nothing (neither
      // proven in contact nor proven farther apart than the threshold: an unproven lower bound
      // still steps as a proven one would, as in time_of_impact): for a polytope pair its signed
      // distance, whose penetration step proves the contacts its distance left unproven (3 of
      // bench/robot_motion.py's 1000 edges uncertified without it, 0 with it, some 40 queries
      // asked again; the dual method certifies them too at some 2.4 times the motion's whole
      // cost), for a curved pair the dual method's distance.
      const bool exact_first = query_->options().method == Method::exact;
      const bool undecided = !((result.distance + plan.margin) * plan.stretch <= threshold) &&
                             !(result.lower_bound - plan.margin > threshold);
      if (!exact_first || undecided) {
        ++iterations_;
        DistanceResult second;
        if (exact_first && !plan.curved) {
          second = detail::signed_distance_of(*query_, model_, pair, pose_a_, pose_b_);
        } else {
          if (!second_) {
            QueryOptions options = query_->options();
            options.method = exact_first ? Method::dual : Method::exact;
            second_.emplace(options);
          }
          second = detail::distance_of(*second_, model_, pair, pose_a_, pose_b_);
        }
        if (second.certified) result = std::move(second);
      }
    }
    if ((result.distance + plan.margin) * plan.stretch <= threshold) return {t, true, 0, 0};
    const Scalar apart = result.lower_bound - plan.margin;
    if (!(apart > 0) && result.distance <= threshold) {
      // In contact, but its distance (0 for an overlap) is not proven within the threshold of
      // it once the margin is added: far from the world's origin the placed frames' rounding
      // exceeds the threshold (a robot 1e4 times its pairs' size away). An overlap deeper than
      // the margin still proves contact; the signed distance measures it.
      ++iterations_;
      const DistanceResult depth =
          detail::signed_distance_of(*query_, model_, pair, pose_a_, pose_b_);
      if ((depth.distance + plan.margin) * plan.stretch <= threshold) return {t, true, 0, 0};
    }
    if (!(apart > 0)) return {t, false, 0, 0};
    // The lower bound is the separation along `direction` (a compound geometry's is not).
    const Scalar length = result.direction.norm();
    if (!(plan.convex && length > 0.5)) {
      separating_.reset();
      return apart_sample(pair, plan, t, apart, Vector3::Zero(), local);
    }
    separating_ = Separating{result.direction / length, -1, -1, apart};
    return apart_sample(pair, plan, t, apart, separating_->direction, local);
  }

  // A sample proven `apart` (beyond the pair's margin) at t, by a separation along the unit
  // `direction` (zero when the bound is not one, as a compound geometry's): the time it lasts
  // either way, by the whole motion's speed, the local one, and along `direction`.
  Sample apart_sample(const GeometryPair& pair, const PairPlan& plan, Scalar t, Scalar apart,
                      const Vector3& direction,
                      const detail::LinkMotionBound::LocalSpeed& local) const {
    Sample s{t, false, 0, 0};
    s.forward = s.backward =
        std::max(detail::reach_over(apart, plan.speed), local_reach(apart, local));
    if (direction.squaredNorm() > 0) {
      const detail::LinkMotionBound::DirectionalSpeed speed =
          bound_.directional_speed(pair, direction, chain_a_, chain_b_);
      // What is left of the gap in the frame the pair is measured in (rounded down).
      const Scalar gap = speed.loss > 0 ? apart * (1 - speed.loss) * (1 - 4 * kUnit) : apart;
      // The bodies' own velocities along the direction, either way (link_motion_bound.hpp's
      // twist bound: bench/robot_motion_profile.py's samples per edge 52.9 -> 40.3).
      const detail::LinkMotionBound::TwistSpeed twist =
          bound_.twist_speed(pair, direction, chain_a_, chain_b_);
      s.forward = std::max(s.forward, twist_reach(gap, twist.forward, twist));
      s.backward = std::max(s.backward, twist_reach(gap, twist.backward, twist));
      // The bisection's time keeps closing <= gap, so where the closing over the reach
      // already taken exceeds the gap it stays below that reach (the computed closing is
      // nondecreasing in h): the root is sought only where it can lengthen a step.
      const Scalar shorter = std::min(s.forward, s.backward);
      if (!(closing(shorter, speed) > gap)) {
        const Scalar reach = directional_reach(gap, speed);
        s.forward = std::max(s.forward, reach);
        s.backward = std::max(s.backward, reach);
      }
    }
    return s;
  }

  // The pair's separation at its current poses along the last query's direction (in world
  // units, as a query's lower bound: the rounded bodies' if they have radii), the supports'
  // climbs starting where the last ones ended.
  Scalar separation_along(const detail::FramedPair& framed, Separating& last) const {
    return framed.frame.length_to_world(detail::rounded_lower(
        framed, detail::separation(framed.a, framed.b, last.direction, last.ia, last.ib)));
  }

  // The pair at its current poses framed as its queries frame it (the poses the kinematics made
  // need no validation).
  detail::FramedPair frame(const GeometryPair& pair) const {
    return detail::frame_validated_pair(model_.geometries()[pair.a].body, pose_a_,
                                        model_.geometries()[pair.b].body, pose_b_,
                                        query_->options().tolerance);
  }

  // A proven lower bound on the pair's distance at `pose_a` and `pose_b` from its geometries'
  // bounding balls (as robot_check screens).
  Scalar ball_separation(const GeometryPair& pair, const Pose& pose_a, const Pose& pose_b) const {
    const Vector3 ca = centre(pair.a, pose_a);
    const Vector3 cb = centre(pair.b, pose_b);
    return ball_separation(pair, ca, ca.lpNorm<Eigen::Infinity>(), cb,
                           cb.lpNorm<Eigen::Infinity>());
  }

  // The same from the balls' centres placed, `ca` and `cb`, and their largest coordinates'
  // magnitudes, `size_a` and `size_b` (what the margin is taken of).
  Scalar ball_separation(const GeometryPair& pair, const Vector3& ca, Scalar size_a,
                         const Vector3& cb, Scalar size_b) const {
    const BodyBounds& a = model_.geometries()[pair.a].body.bounds();
    const BodyBounds& b = model_.geometries()[pair.b].body.bounds();
    const Scalar margin = 1e-12 * (size_a + size_b + a.radius + b.radius);
    // Without overflow: centres 1.4e154 apart made the plain norm's squares infinite, and that
    // infinite separation proved a pair apart over motions ending in contact.
    return detail::robust_length(ca - cb) - a.radius - b.radius - margin;
  }

  // The better of `balls`, the pair's ball separation, and its boxes' over their face axes (-inf
  // when neither separates them), as the plan screens: a sample's screen decides only whether
  // it proves the pair apart to the horizon, and the cross axes' work cost more than the
  // samples they saved (bench/robot_motion_profile.py's 1000 edges under callgrind 510.72M ->
  // 501.70M instructions with the face axes alone; 16.37 -> 16.71 queries per edge).
  Scalar screen_boxes(const GeometryPair& pair, const Pose& pose_a, const Pose& pose_b,
                      Scalar balls) const {
    const BodyBounds& a = model_.geometries()[pair.a].body.bounds();
    const BodyBounds& b = model_.geometries()[pair.b].body.bounds();
    return std::max(balls, detail::face_separation(detail::PlacedBox(a.box, pose_a),
                                                   detail::PlacedBox(b.box, pose_b)));
  }

  // Geometry g's bounding ball's centre with the geometry at `pose`.
  Vector3 centre(int g, const Pose& pose) const {
    return pose.rotation * model_.geometries()[static_cast<std::size_t>(g)].body.bounds().centre +
           pose.translation;
  }

  // Every geometry's pose at the configuration of `links`, its bounding ball's centre there and
  // the centre's largest coordinate magnitude (placed once for all its pairs).
  void place_all(const std::vector<Pose>& links, std::vector<Pose>& world,
                 std::vector<Vector3>& centres, std::vector<Scalar>& sizes) const {
    world.resize(model_.geometries().size());
    centres.resize(world.size());
    sizes.resize(world.size());
    for (std::size_t g = 0; g < world.size(); ++g) {
      world[g] = placed(links, static_cast<int>(g));
      centres[g] = centre(static_cast<int>(g), world[g]);
      sizes[g] = centres[g].lpNorm<Eigen::Infinity>();
    }
  }

  // q(t) into q_, and the poses at it of every link, or of the children of `joints` alone into
  // links_, in the frame of link `frame` (its pose the identity; -1: the world's).
  void configuration_at(Scalar t, const std::vector<int>* joints = nullptr, int frame = -1) {
    if (t == 1) {
      q_ = end_;
    } else {
      q_ = start_ + t * delta_;
    }
    if (joints) {
      links_.resize(model_.links().size());
      if (frame >= 0) links_[static_cast<std::size_t>(frame)] = Pose{};
      link_poses(model_, q_.data(), *joints, links_);
    } else {
      link_poses(model_, q_.data(), links_);
    }
  }

  void place(const GeometryPair& pair) {
    pose_a_ = placed(pair.a);
    pose_b_ = placed(pair.b);
  }

  Pose placed(int g) const { return placed(links_, g); }

  Pose placed(const std::vector<Pose>& links, int g) const {
    return geometry_pose(model_, links, g);
  }

  const RobotModel& model_;
  const std::vector<GeometryPair>& pairs_;
  const Configurations& q0_;
  const Configurations& q1_;
  const TimeOfImpactOptions& options_;
  RobotMotionCheck& check_;
  // Per motion, reused from one to the next by the thread that owns this.
  detail::LinkMotionBound bound_;
  const Query* query_ = nullptr;
  // The second method (exact after any other, dual after exact), seeded as `query_`, made when a
  // query first stays unproven.
  std::optional<Query> second_;
  std::optional<Separating> separating_;
  // The pair's last query's corral (size 0: none yet), the next query's start.
  detail::MinNormPoint corral_;
  int iterations_ = 0;
  Eigen::Matrix<Scalar, 1, Eigen::Dynamic> start_;
  Eigen::Matrix<Scalar, 1, Eigen::Dynamic> end_;
  Eigen::Matrix<Scalar, 1, Eigen::Dynamic> delta_;
  Eigen::Matrix<Scalar, 1, Eigen::Dynamic> q_;
  // Per pair, the joints that place its links below the link where its links' chains part (in
  // the model's order), that link (-1: the world), and the samples' stretch (PairPlan).
  std::vector<std::vector<int>> pair_joints_;
  std::vector<int> common_links_;
  std::vector<Scalar> stretch_;
  // Per pair, the number of joints its two chains share.
  std::vector<std::size_t> shared_;
  std::vector<Pose> links_;
  std::vector<Pose> start_links_;
  std::vector<Pose> end_links_;
  std::vector<Pose> start_world_;
  std::vector<Pose> end_world_;
  std::vector<Vector3> start_centres_;
  std::vector<Vector3> end_centres_;
  std::vector<Scalar> start_sizes_;
  std::vector<Scalar> end_sizes_;
  Pose pose_a_;
  Pose pose_b_;
  // The sampled pair's chains at its poses.
  detail::LinkMotionBound::PlacedChain chain_a_;
  detail::LinkMotionBound::PlacedChain chain_b_;
  // Per geometry, its chain at the motion's start and end, and whether it is placed yet.
  std::vector<detail::LinkMotionBound::PlacedChain> end_chains_[2];
  std::vector<char> chain_placed_[2];
  // Per geometry, its box at the motion's start and end, and whether it is placed yet.
  std::vector<detail::PlacedBox> end_boxes_[2];
  std::vector<char> box_placed_[2];
  std::vector<PairPlan> plans_;
  std::vector<Sample> ahead_;
  std::vector<Unproven> unproven_;
};

void require_dof(const RobotModel& model, const Configurations& q, const char* name) {
  if (q.cols() != model.dof()) {
    throw std::invalid_argument(std::string(name) + " must have " + std::to_string(model.dof()) +
                                " values per configuration, got " + std::to_string(q.cols()));
  }
}

}  // namespace

RobotMotionCheck robot_check_motion(const RobotModel& model, const std::vector<GeometryPair>& pairs,
                                    const Configurations& q0, const Configurations& q1,
                                    const TimeOfImpactOptions& options,
                                    const BatchSettings& settings) {
  options.validate();
  validate_pairs(model, pairs);
  require_dof(model, q0, "q0");
  require_dof(model, q1, "q1");
  if (q0.rows() != q1.rows() && q0.rows() != 1 && q1.rows() != 1) {
    throw std::invalid_argument("q0 has " + std::to_string(q0.rows()) + " rows and q1 " +
                                std::to_string(q1.rows()) +
                                ": give one motion per row of each, or one row for all");
  }
  detail::require_geometry_shapes(model, pairs, options.query.method);
  const Eigen::Index m = q0.rows() == 0 || q1.rows() == 0 ? 0 : std::max(q0.rows(), q1.rows());
  RobotMotionCheck check;
  check.touches.setConstant(m, false);
  check.t_lower.setConstant(m, 1);
  check.t_upper.setConstant(m, 1);
  check.configuration.setZero(m, model.dof());
  check.pair.setConstant(m, -1);
  check.distance.setConstant(m, std::numeric_limits<Scalar>::quiet_NaN());
  check.point_a.setZero(m, 3);
  check.point_b.setZero(m, 3);
  check.normal.setZero(m, 3);
  check.certified.setConstant(m, true);
  check.iterations.setZero(m);
  check.status.assign(static_cast<std::size_t>(m), MotionStatus::converged);
  // One checker per thread: its buffers are the thread's own; each writes only its rows.
  detail::over_rows(
      static_cast<std::size_t>(m), settings.threads,
      [&] { return MotionCheck(model, pairs, q0, q1, options, check); }, "motion");
  return check;
}

}  // namespace swarmcollide
