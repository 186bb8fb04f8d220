#include "dual_swarm.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <utility>
#include <vector>

#include "../detail/interruption.hpp"
#include "../queries/verdict.hpp"
#include "best_bounds.hpp"
#include "closed_forms.hpp"
#include "direction_swarm.hpp"
#include "distance_finish.hpp"
#include "exact_solver.hpp"
#include "minkowski.hpp"
#include "whole_search.hpp"
#include "wolfe_min_norm.hpp"
#include "witness.hpp"

namespace swarmcollide::detail {

namespace {

constexpr Scalar kPi = 3.14159265358979323846;

// Where a search starts: the given start's direction and support points (a scene's pair seen
// before), else the direction between the bodies' centres and no support hints.
DualStart first_start(const FramedPair& pair, const DualStart* start) {
  if (start != nullptr) return *start;
  const Vector3 between = pair.b.offset() - pair.a.offset();
  // One square root (normalized() would take the norm again).
  const Scalar length = between.norm();
  return {length > 0 ? Vector3(between / length) : Vector3::UnitX(), -1, -1};
}

// Where overlap_first's walk on a curved pair left it, found apart: a corral of oracle points
// whose last is the support along `direction` (unit), and the oracle calls and Wolfe steps spent.
struct SearchStart {
  MinNormPoint corral;
  Vector3 direction;
  long evaluations = 1;
  int iterations = 0;
};

// The search for the distance (or only a verdict): Wolfe's algorithm on the whole difference
// from the given start or the direction between the bodies' centres, which settles most pairs;
// where it stops short (rounding, its iteration cap), the exact finish on the supporting features
// of the best direction, then rounds of the direction swarm whose improvements the finish
// polishes, re-seeded around the best direction in discs that shrink unless the best moved far.
class DualSearch {
 public:
  // `first`: the oracle's point along the start's direction from its hints, when the caller
  // has asked it already (overlap_first); `walked`: where the caller's Wolfe walk on a curved
  // pair left off, to go on from instead.
  DualSearch(const FramedPair& pair, const QueryOptions& options, Goal goal, const DualStart* start,
             const OraclePoint* first = nullptr, const SearchStart* walked = nullptr)
      : pair_(pair),
        start_(start),
        first_(first),
        walked_(walked),
        options_(options.dual),
        seed_(options.seed),
        goal_(goal),
        exact_iterations_(options.exact.max_iterations),
        finish_(pair, options.dual.feature_tolerance * pair.frame.size,
                options.exact.max_iterations) {}

  Answer run() {
    const DualStart first = first_start(pair_, start_);
    hint_a_ = first.support_a;
    hint_b_ = first.support_b;
    const bool enclosure = start_ != nullptr && start_->enclosure;
    bool done = walked_ != nullptr
                    ? finish_.whole_from_corral(walked_->direction, walked_->corral, hint_a_,
                                                hint_b_, bounds_, goal_, enclosure)
                    : finish_.whole(first.direction, hint_a_, hint_b_, bounds_, goal_, enclosure,
                                    first_);
    record();
    if (!done) done = finish_.from(bounds_.normal(), hint_a_, hint_b_, bounds_, goal_);
    // A verdict within a hair of the tolerance stays unproven, whatever follows.
    if (!done) done = bounds_.out_of_reach(pair_, goal_);
    // A curved pair the finish leaves unsettled lies within a few tolerances of the verdict's
    // border, or its supports' rounding hides the last digits of the value: the exact method's
    // search (Wolfe's restarts, its corral's planes) settles it, where the swarm's rounds search
    // directions until max_rounds and then hand over all the same (sc.collide of a polytope 1.1
    // tolerances from a cylinder: 0.75 s, 45 of 210 bisection steps to such borders over 20 s).
    // A value proven is not enough: certified needs the verdict too, which a pair a hair beyond
    // the tolerance has only from a direction a hair off the optimum, so the search from the
    // centres' direction is tried as well (as the exact method's).
    if (!done && (pair_.a.curved() || pair_.b.curved())) {
      const auto settles = [this](const Answer& a) {
        return goal_reached(pair_, goal_, a.lower, a.upper, a.intersection_proven) &&
               verdict_proven(pair_, a);
      };
      Answer exact = exact_distance(pair_, exact_iterations_, bounds_.normal());
      if (!settles(exact)) {
        Answer again = exact_distance(pair_, exact_iterations_, Vector3::Zero());
        again.iterations += exact.iterations;
        again.evaluations += exact.evaluations;
        exact = std::move(again);
      }
      if (settles(exact)) {
        exact.iterations += iterations_;
        exact.evaluations += finish_.evaluations();
        if (goal_ != Goal::verdict && options_.record_history) history_.push_back(exact.upper);
        exact.history = std::move(history_);
        return exact;
      }
    }
    Scalar radius = kPi / 2;
    Vector3 round_centre = bounds_.normal();
    for (int r = 0; r < options_.max_rounds && !done; ++r) {
      done = round(round_centre, radius);
      if (done) break;
      const Scalar moved =
          std::acos(std::clamp(round_centre.dot(bounds_.normal()), Scalar(-1), Scalar(1)));
      radius = std::min(radius, std::max(2 * moved, radius / 4));
      round_centre = bounds_.normal();
    }
    Answer answer = bounds_.answer(pair_);
    answer.iterations = iterations_;
    answer.evaluations = (swarm_ ? swarm_->evaluations() : 0) + finish_.evaluations();
    answer.history = std::move(history_);
    return answer;
  }

 private:
  bool reached() const { return bounds_.reached(pair_, goal_); }

  // The best upper bound after the start and after each iteration; a verdict keeps none, nor
  // does a search asked not to.
  void record() {
    if (goal_ != Goal::verdict && options_.record_history) {
      history_.push_back(bounds_.upper().distance);
    }
  }

  // The swarm's global best becomes a lower bound, and the finish runs from it whenever it
  // reaches a new pair of support points (or always, with `force`).
  void improve(bool force) {
    const Vector3 n = swarm_->best_direction();
    bounds_.offer_lower(n, swarm_->best_value());
    const std::pair<int, int> supports{swarm_->best_support_a(), swarm_->best_support_b()};
    if (!force && supports == finished_) return;
    finished_ = supports;
    hint_a_ = supports.first;
    hint_b_ = supports.second;
    finish_.from(n, hint_a_, hint_b_, bounds_, goal_);
  }

  // Returns whether the bounds settle the goal.
  bool round(const Vector3& centre, Scalar radius) {
    // Built at the first round: Wolfe's algorithm settles most pairs without one.
    if (!swarm_) swarm_.emplace(pair_, options_, seed_);
    swarm_->seed(centre, radius, hint_a_, hint_b_);
    finished_ = {-1, -1};
    improve(false);
    // Rounds of the largest swarm for the largest budget run for hours.
    const InterruptionPoll stop_if_interrupted;
    for (int iteration = 0; iteration < options_.max_iterations && !stop(); ++iteration) {
      stop_if_interrupted();
      if (swarm_->step()) improve(false);
      ++iterations_;
      record();
    }
    if (stop()) return true;
    improve(true);
    return stop();
  }

  // The goal is reached, or it is a verdict that no search can prove.
  bool stop() const { return reached() || bounds_.out_of_reach(pair_, goal_); }

  const FramedPair& pair_;
  const DualStart* start_;
  const OraclePoint* first_;
  const SearchStart* walked_;
  const DualOptions& options_;
  const std::uint64_t seed_;
  const Goal goal_;
  const int exact_iterations_;
  std::optional<DirectionSwarm> swarm_;
  DistanceFinish finish_;
  BestBounds bounds_;
  std::pair<int, int> finished_{-1, -1};
  int hint_a_ = -1;
  int hint_b_ = -1;
  int iterations_ = 0;
  History history_;
};

// Where Wolfe's walk towards an intersection proof starts: `direction` turned 45 degrees about an
// axis across it. From the contact direction itself (the centres', or a scene's last normal) the
// walk ends on a tetrahedron pressed against the contact region, the origin a hair from one face,
// from which the expanding polytope needs half as many steps again to surround the depth's ball
// (bench/penetration_coal.cpp: 41 against 24 iterations at 4,096 vertices overlapping by 0.6;
// coal's 27 start from a fixed axis, as unrelated to the contact as this one).
Vector3 tilted(const Vector3& direction) {
  if (!(direction.norm() > 0)) return direction;
  const Vector3 unit = direction.normalized();
  int least = 0;
  for (int k = 1; k < 3; ++k) {
    if (std::abs(unit(k)) < std::abs(unit(least))) least = k;
  }
  return (unit + unit.cross(Vector3::Unit(least)).normalized()).normalized();
}

// A signed distance's overlapping pairs skip the search: once the separation along the start's
// direction (or the centres') leaves the bodies possibly in contact, Wolfe's algorithm on B - A
// runs from it, tilted. A corral around the origin proves the
// overlap, which no separating direction can, and its tetrahedron starts the penetration solver's
// expanding polytope; a nearest point whose separation settles the value (apart or touching
// pairs) is the answer as well. Otherwise nothing: the search runs as for any distance, and its
// direction, the contact normal, is the penetration solver's hint. Pairs apart along the start
// leave its oracle point in `along_start` for the search to start from (unset otherwise), and so
// do curved pairs whose Wolfe walk meets a direction separating them by more than the tolerance:
// its corral and new point, for the distance search to go on from. Run to the end, the walk
// converges on curved bodies only linearly, down to its own gap test (1e-14) far below the
// tolerance the search stops at (callgrind_curved: 3 of 20 cylinder-ellipsoid pairs apart took
// the walk, 68,000 instructions each); polytopes' walks end in a few exact steps.
std::optional<Answer> overlap_first(const FramedPair& pair, const QueryOptions& options,
                                    const DualStart* start,
                                    std::optional<OraclePoint>& along_start,
                                    const SearchStart*& walked) {
  const DualStart first = first_start(pair, start);
  const Vector3& direction = first.direction;
  int ia = first.support_a;
  int ib = first.support_b;
  long evaluations = 1;
  const OraclePoint q = minkowski_support(pair.a, pair.b, direction, ia, ib);
  if (direction.dot(q.p) > pair.tolerance) {
    along_start = q;
    return std::nullopt;
  }
  const auto oracle = [&](const Vector3& d) {
    ++evaluations;
    return minkowski_support(pair.a, pair.b, d, ia, ib);
  };
  // Two small polytopes are scanned inline (FramedBody::scanned_support_index, the index
  // minkowski_support's out-of-line scans find), in a walk of their own: a test in the one oracle
  // cost the 64-vertex pairs' walks 246 instructions a query.
  const auto scans = [&](const Vector3& d) {
    ++evaluations;
    ia = pair.a.scanned_support_index(d);
    ib = pair.b.scanned_support_index(-d);
    return OraclePoint{pair.b.vertex(ib) - pair.a.vertex(ia), ia, ib};
  };
  // The walk's corral `now` and its new point `q`, when q separates the bodies along now's point
  // by more than the tolerance (curved pairs only): the search goes on from both, its first step
  // their nearest point, and measures q along now.x / |now.x| as its own steps do.
  const bool curved = pair.a.curved() || pair.b.curved();
  const auto apart = [&](const MinNormPoint& now, Scalar norm, const OraclePoint* next) {
    if (next == nullptr || !(now.x.dot(next->p) > pair.tolerance * norm)) return false;
    // Kept on this thread for the search that goes on from it (solve_dual_from reads it before
    // this thread walks again): held in the caller's frame, it cost every query a few dozen
    // instructions.
    thread_local SearchStart kept;
    // One oracle call per step after the centres' and the tilted start's.
    kept = SearchStart{now, now.x * (1 / norm), evaluations, static_cast<int>(evaluations) - 2};
    kept.corral.corral[now.size] = *next;  // now.size < 4: the walk asks no point for four
    kept.corral.weights[now.size] = 0;
    ++kept.corral.size;
    // No nearest point yet: the search's first step settles the corral (as exact_distance's).
    kept.corral.x = Vector3::Constant(std::numeric_limits<Scalar>::infinity());
    walked = &kept;
    return true;
  };
  // Polytopes' walks take no stop test (their steps are exact and few). The small pairs' walk is
  // flattened, as DistanceFinish::whole's searches are: left to the inliner, it called the
  // projection (nearest_simplex_point, and its tetrahedron's) out of line at every step.
  const auto scanned_walk = [&]() SWARMCOLLIDE_FLATTEN {
    return wolfe_min_norm(scans, tilted(direction), 2, options.exact.max_iterations);
  };
  const MinNormPoint corral =
      curved ? wolfe_min_norm(oracle, tilted(direction), 2, options.exact.max_iterations, apart)
      : pair.a.scanned() && pair.b.scanned()
          ? scanned_walk()
          : wolfe_min_norm(oracle, tilted(direction), 2, options.exact.max_iterations);
  if (walked != nullptr) return std::nullopt;
  Answer answer;
  if (corral.size == MinNormPoint::kCapacity) {
    // A corral of four holds the origin inside, up to rounding. The expanding polytope starts
    // from its tetrahedron only once each face is proven oriented with the origin inside
    // (make_face), and its verified surface proves the depth: an upper bound below minus the
    // frame's rounding proves the bodies share a point, as the tetrahedron's own test would (its
    // faces more than 4 kFrameRounding from the origin) at the cost of a second proof of the
    // same faces (475 of 13,473 instructions per signed distance at 8 vertices overlapping).
    // Where rounding leaves the tetrahedron undecided (touching pairs), the solver goes on from
    // the corral's nearest point, as exact_signed_distance does; its answer is taken if it
    // settles the value, else the search runs.
    answer = exact_penetration(pair, options.exact.max_iterations, direction,
                               std::numeric_limits<Scalar>::infinity(), &corral);
    answer.intersection_proven = answer.upper + kFrameRounding < 0;
    if (!answer.intersection_proven && !value_proven(pair, answer)) return std::nullopt;
  } else {
    answer = answer_from_corral(pair, corral, combined_witness(pair, corral));
    ++evaluations;
    const bool apart = answer.lower > kFrameRounding && value_proven(pair, answer);
    if (!apart && !settles_signed_distance(pair, corral, answer)) return std::nullopt;
  }
  answer.iterations += corral.iterations;
  answer.evaluations += evaluations;
  return answer;
}

Answer solve_dual_from(const FramedPair& pair, const QueryOptions& options, Goal goal,
                       const DualStart* start) {
  // A distance or a verdict is the search's answer, returned as it is made: a named answer
  // returned among others is moved out, which cost every batch row of distance_many 57
  // instructions (swarmcollide-thread-scaling count, 8 vertices).
  if (goal != Goal::signed_distance) return DualSearch(pair, options, goal, start).run();
  std::optional<OraclePoint> along_start;
  const SearchStart* walked = nullptr;
  if (std::optional<Answer> settled = overlap_first(pair, options, start, along_start, walked)) {
    return *settled;
  }
  Answer answer = DualSearch(pair, options, Goal::distance, start,
                             along_start ? &*along_start : nullptr, walked)
                      .run();
  if (walked != nullptr) {
    // The search counted the start's newest oracle point; the walk that found it is added.
    answer.evaluations += walked->evaluations - 1;
    answer.iterations += walked->iterations;
  }
  // A separating direction settles a signed distance as a distance, whose contact normal is the
  // witnesses' direction (`point_b - point_a = distance * direction`): the swarm's best direction
  // may be a tolerance's worth of angle away from it. When the separation along the witnesses
  // leaves the bounds further apart than the tolerance, Wolfe's algorithm from them closes it.
  if (answer.lower > kFrameRounding) {
    const Vector3 between = answer.point_b - answer.point_a;
    const Vector3 n = between / answer.upper;
    // Along unit directions n and m, the separations of B - A differ by at most |n - m| times
    // its largest point, at most 2 in the frame: the search's best separation, along a direction
    // that is mostly the witnesses' own up to rounding, bounds the one along them without a scan
    // (4 roundoffs for the subtraction, 8 for the product and the norm).
    const Scalar moved = answer.lower - (2 * (n - answer.direction).norm() + 4 * kRoundoff) *
                                            (1 + 8 * kRoundoff);
    const Scalar s = value_proven(pair, moved, answer.upper) ? moved
                                                             : separation(pair.a, pair.b, n);
    if (value_proven(pair, s, answer.upper)) {
      answer.direction = n;
      answer.lower = s;
      return answer;
    }
    Answer exact = settled_distance(pair, options.exact.max_iterations, between);
    exact.iterations += answer.iterations;
    exact.evaluations += answer.evaluations;
    exact.history = std::move(answer.history);
    return exact;
  }
  // Touching polytopes, mostly: the best separation bounds the signed distance below as well (no
  // direction separates overlapping bodies by more than minus their depth), so once it is within
  // the tolerance of the witnesses' distance the value is settled, and its direction is a
  // contact normal along which the gap is the signed distance to the tolerance (curved surfaces
  // excepted: settles_signed_distance).
  if (!pair.a.curved() && !pair.b.curved() && value_proven(pair, answer)) return answer;
  Answer overlap =
      exact_penetration(pair, options.exact.max_iterations, answer.direction, answer.upper);
  overlap.iterations += answer.iterations;
  overlap.evaluations += answer.evaluations;
  overlap.history = std::move(answer.history);
  overlap.intersection_proven = overlap.intersection_proven || answer.intersection_proven;
  return overlap;
}

// A closed form's answer where one settles the pair (point_against_curved, core_closed_form),
// else the search's. One named answer on every path, made in the caller's place: returned beside
// the search's answers, the closed form's was moved out.
Answer closed_form_or_search(const FramedPair& pair, const QueryOptions& options, Goal goal,
                             const DualStart* start) {
  Answer answer;
  if (!answered_in_closed_form(pair, goal, options.exact.max_iterations, answer)) {
    answer = solve_dual_from(pair, options, goal, start);
  }
  return answer;
}

}  // namespace

Answer solve_dual(const FramedPair& pair, const QueryOptions& options, Goal goal) {
  if (closed_form_pair(pair)) return closed_form_or_search(pair, options, goal, nullptr);
  return solve_dual_from(pair, options, goal, nullptr);
}

Answer solve_dual(const FramedPair& pair, const QueryOptions& options, Goal goal,
                  const DualStart& start) {
  if (closed_form_pair(pair)) return closed_form_or_search(pair, options, goal, &start);
  return solve_dual_from(pair, options, goal, &start);
}

}  // namespace swarmcollide::detail
