#include "fcl_solver.hpp"

#include <fcl/narrowphase/detail/convexity_based_algorithm/gjk.h>

#include <optional>
#include <utility>

#include "../geometry/unit_direction.hpp"
#include "../queries/verdict.hpp"
#include "exact_solver.hpp"
#include "fcl_shape.hpp"
#include "minkowski.hpp"
#include "witness.hpp"

namespace swarmcollide::detail {

namespace {

// GJK's stopping threshold in frame units (the bodies lie in the unit ball): relative precision
// near double's; whatever GJK leaves unproven goes to the exact solver.
constexpr Scalar kGjkTolerance = 1e-14;
// A verdict's: fcl::CollisionRequest's default gjk_tolerance, at which FCL's own collide runs its
// GJK. A verdict needs only a direction that separates the pair beyond the tolerance, or an
// enclosing simplex; where FCL's coarser answer proves neither, the exact solver goes on from it.
constexpr Scalar kVerdictGjkTolerance = 1e-6;
// FCL's GJK on the pair; on return `gjk` holds its final simplex in A's shape frame, and
// `gjk.shape` the pair's Minkowski difference. That difference is set up in `gjk.shape` itself,
// which `evaluate` copies onto itself: a difference of its own cost a constructor's call more.
fcl::detail::GJK<Scalar>::Status run_gjk(const FramedPair& pair, const fcl::ShapeBased& a,
                                         const fcl::ShapeBased& b, fcl::detail::GJK<Scalar>& gjk) {
  // B's placement seen from A's shape frame, and directions from there into B's, from the
  // rotations themselves (no 4 x 4 transforms to build, invert and multiply).
  const Matrix3& rotation_a = pair.a.rotation();
  const Matrix3& rotation_b = pair.b.rotation();
  fcl::detail::MinkowskiDiff<Scalar>& difference = gjk.shape;
  difference.shapes[0] = &a;
  difference.shapes[1] = &b;
  difference.toshape1.noalias() = rotation_b.transpose() * rotation_a;
  difference.toshape0.linear().noalias() = rotation_a.transpose() * rotation_b;
  difference.toshape0.translation().noalias() =
      rotation_a.transpose() * (pair.b.offset() - pair.a.offset());
  // Start towards B, as seen from A.
  Vector3 guess = -difference.toshape0.translation();
  if (!(guess.norm() > 0)) guess = Vector3::UnitX();
  return gjk.evaluate(difference, guess);
}

// The index of `body`'s support point along `local`, a direction in its own frame: a small
// body's scan inline, without the tests of its kind, else local_support_index's.
[[gnu::always_inline]] inline int support_along(const FramedBody& body, const Vector3& local) {
  return body.scanned() ? body.scanned_local_support_index(local)
                        : body.local_support_index(local, -1);
}

// The verdict along `towards_b` (from A towards B, any length), where the pair's separation
// along it proves them apart: that separation (the lower bound) and the two support points found
// with it (the upper bound). Without the proof, nothing: the witness made for every pair cost each
// verdict that GJK goes on to settle some 200 instructions more at 4 to 64 vertices
// (callgrind_query.py --gap).
std::optional<Answer> apart_along(const FramedPair& pair, const Vector3& towards_b) {
  const Vector3 n = unit_direction_or(towards_b, Vector3::UnitX());
  int ia = -1;  // large bodies climb from their hulls' cube maps of starts
  int ib = -1;
  const Scalar lower = separation(pair.a, pair.b, n, ia, ib);
  if (!separation_proves_apart(pair, lower)) return {};
  Answer answer = answer_from_witness(pair, vertex_witness(pair, ia, ib));
  answer.lower = lower;
  answer.direction = n;
  answer.evaluations = 1;
  return answer;
}

// True for a curved shape placed by a pose (a compound body's part, placed_shape.hpp): FCL's
// primitives sit at their own origins.
bool placed_curved(const FramedBody& body) {
  return body.curved() && body.body().curved()->parameters().placed;
}

}  // namespace

Answer solve_fcl(const FramedPair& pair, const QueryOptions& options, Goal goal) {
  if (placed_curved(pair.a) || placed_curved(pair.b)) return solve_exact(pair, options, goal);
  // FCL's GJK has no early exit for an intersection test: it runs to the distance. The centres'
  // line proves most separated pairs apart in two support scans (as libccd's test would stop).
  const fcl::ShapeBased& shape_a = fcl_shape(pair.a);
  const fcl::ShapeBased& shape_b = fcl_shape(pair.b);
  if (goal == Goal::verdict) {
    const Vector3 between = pair.b.offset() - pair.a.offset();
    if (std::optional<Answer> screened = apart_along(pair, between)) return *screened;
  }
  using Gjk = fcl::detail::GJK<Scalar>;
  const int max_iterations = options.exact.max_iterations;
  Gjk gjk(static_cast<unsigned int>(max_iterations),
          goal == Goal::verdict ? kVerdictGjkTolerance : kGjkTolerance);
  const Gjk::Status status = run_gjk(pair, shape_a, shape_b, gjk);
  // A verdict FCL finds apart is proven by the separation along its last direction, in two
  // scans: its ray, the nearest point of A - B in A's frame, points from B towards A. The corral
  // of its simplex's points below costs a scan per point and a witness more.
  if (goal == Goal::verdict && status == Gjk::Valid) {
    if (std::optional<Answer> apart = apart_along(pair, pair.a.rotation() * -gjk.ray)) {
      return *apart;
    }
  }
  // FCL's simplex as the bodies' own points: the support indices along each simplex vertex's
  // direction, found in the bodies' own frames as the solvers find them: on a small body a scan
  // of its points by coordinate, two heights at a time (a single pass for all the directions, one
  // height and one comparison at a time, cost 70 to 900 instructions more per query at 4-32
  // vertices in callgrind_query.py, though 41 fewer on overlapping 4-vertex pairs; all of A's
  // scans before B's, 60 to 140 more than each pair's in turn), on a large one a climb from its
  // hull's cube map of starts (Hull::climb_starts), a few neighbour checks where a scan would cost
  // as much as an iteration of FCL's GJK (whose supports scan every vertex), on a curved one its
  // support function's point. Any points of the bodies give a valid witness: the bounds are
  // computed from these points, not from FCL's.
  const Gjk::Simplex& simplex = *gjk.getSimplex();
  MinNormPoint corral;
  Scalar total = 0;
  for (unsigned int k = 0; k < simplex.rank; ++k) {
    const Scalar weight = simplex.p[k];
    if (!(weight > 0)) continue;  // a point the last projection gave no weight
    const Vector3& along_a = simplex.c[k]->d;
    const Vector3 along_b = -(gjk.shape.toshape1 * along_a);
    const int ia = support_along(pair.a, along_a);
    const int ib = support_along(pair.b, along_b);
    total += weight;
    // Two of FCL's points may be the same pair of vertices: one corral point, their weights
    // summed.
    int same = 0;
    while (same < corral.size && !(corral.corral[same].ia == ia && corral.corral[same].ib == ib))
      ++same;
    if (same == corral.size) {
      // Its Minkowski point stays zero until place_corral places it.
      corral.corral[same].ia = ia;
      corral.corral[same].ib = ib;
      corral.weights[same] = weight;
      ++corral.size;
    } else {
      corral.weights[same] += weight;
    }
  }
  for (int k = 0; k < corral.size; ++k) corral.weights[k] /= total;
  // The corral's Minkowski points, placed only for those that read them (the enclosure test, the
  // exact solver): the witness places the bodies' points itself, and a distance whose witnesses
  // prove contact, or a corral of fewer than four points, needs nothing more.
  bool placed = false;
  const auto place_corral = [&pair, &corral, &placed] {
    if (placed) return;
    for (int k = 0; k < corral.size; ++k) {
      OraclePoint& q = corral.corral[k];
      q.p = pair.b.vertex(q.ib) - pair.a.vertex(q.ia);
    }
    placed = true;
  };
  const auto settles = [&pair, goal](const Answer& answer) {
    return goal_reached(pair, goal, answer.lower, answer.upper, answer.intersection_proven);
  };
  const bool usable = status != Gjk::Failed && corral.size > 0;
  if (usable) {
    // A corral around the origin proves the overlap, which settles a verdict whatever the
    // separation along the witnesses: it skips the two scans. A distance is settled by witnesses
    // within the tolerance only (zero, its lower bound, needs no scan then), so it takes no
    // enclosure test: FCL's weights on the corral's points, found again by support scans, can
    // leave the witnesses of an enclosing corral apart (census case 49:8148).
    const bool distance_goal = goal == Goal::distance;
    // The witness inline (combined_witness(pair, corral), its call out of line, cost 20 more).
    Witness witness = combined_witness(
        corral, [&pair](int i) { return pair.a.vertex(i); },
        [&pair](int j) { return pair.b.vertex(j); });
    const bool witnesses_contact = distance_goal && witnesses_prove_contact(pair, witness);
    if (!distance_goal && corral.size == 4) {
      place_corral();
      witness.encloses_origin = corral_encloses_origin(corral);
    }
    const bool contact = witness.encloses_origin || witnesses_contact;
    const bool separated = !contact || goal == Goal::signed_distance;
    if (!separated) {
      // Without a separation the answer's lower bound stays Answer::kUnmeasured: whether it
      // settles the goal is known before it is made, and the answer is made where it is returned
      // (a named answer returned was moved, 50 instructions of every overlapping pair).
      if (goal_reached(pair, goal, Answer::kUnmeasured, witness.distance,
                       witness.encloses_origin)) {
        return answer_from_corral(pair, corral, witness, false);
      }
    } else {
      Answer answer = answer_from_corral(pair, corral, witness, true);
      if (settles(answer)) return answer;
    }
  }
  // Where FCL's answer does not settle the goal, the exact solver takes over: distances from
  // FCL's simplex (FCL stops when a support point comes within sqrt(its tolerance) of an earlier
  // one, often an iteration or two short), then from the direction if that simplex was too
  // degenerate to continue; signed distances from its direction.
  place_corral();
  const Vector3 start =
      usable ? Vector3(combination(corral.corral, corral.weights, corral.size))
             : Vector3::Zero();
  Answer exact;
  if (goal == Goal::signed_distance) {
    exact = exact_signed_distance(pair, max_iterations, start);
    // As a distance's second try below: where Wolfe's restarts from FCL's simplex stall short of
    // the tolerance (a needle of an ellipsoid 8e-7 from a cone, 1.5e-7 between the bounds), the
    // exact method's own start, along the centres' line, may settle it; the tighter answer stays.
    if (!settles(exact)) {
      Answer again = exact_signed_distance(pair, max_iterations, Vector3::Zero());
      if (settles(again) || again.upper - again.lower < exact.upper - exact.lower) {
        again.iterations += exact.iterations;
        again.evaluations += exact.evaluations;
        exact = std::move(again);
      }
    }
  } else {
    if (usable) exact = exact_distance(pair, max_iterations, corral);
    if (!usable || !settles(exact)) exact = exact_distance(pair, max_iterations, start);
  }
  exact.answered_by = Method::exact;
  return exact;
}

}  // namespace swarmcollide::detail
