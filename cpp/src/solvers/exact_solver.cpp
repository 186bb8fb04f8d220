#include "exact_solver.hpp"

#include <algorithm>
#include <limits>
#include <type_traits>
#include <utility>

#include "../queries/verdict.hpp"
#include "closed_forms.hpp"
#include "minkowski.hpp"
#include "penetration.hpp"
#include "witness.hpp"

namespace swarmcollide::detail {

namespace {

// Wolfe's algorithm on B - A from `start` (a direction or a corral), the support hints starting
// at `hint_a` and `hint_b`; its support evaluations are added to `evaluations`.
template <class Start>
MinNormPoint wolfe_corral(const FramedPair& pair, int max_iterations, const Start& start,
                          int hint_a, int hint_b, long& evaluations) {
  const auto oracle = [&](const Vector3& d) {
    ++evaluations;
    return minkowski_support(pair.a, pair.b, d, hint_a, hint_b);
  };
  if constexpr (std::is_same_v<Start, MinNormPoint>) {
    return wolfe_min_norm_from(oracle, start, 2, max_iterations);
  } else {
    return wolfe_min_norm(oracle, start, 2, max_iterations);
  }
}

// Restarts of Wolfe's algorithm on curved bodies (each a few iterations).
constexpr int kCurvedRestarts = 8;

// The same; for curved bodies, restarted from its nearest point's direction while it leaves an
// apart pair's distance or verdict unproven. On a curved difference every oracle point is new,
// and the squared norm's decrease falls below rounding (Wolfe's stop) while the separation along
// the corral's direction still lags the distance by more than the tolerance; a corral built
// afresh from points near the optimum goes on from there. Kept while the gap shrinks. A pair
// apart by a hair more than the tolerance has its value proven long before the separation
// passes the tolerance (a polytope 1.0001 tolerances from a cylinder: 2e-10 short of it).
template <class Start>
MinNormPoint nearest_corral(const FramedPair& pair, int max_iterations, const Start& start,
                            int hint_a, int hint_b, long& evaluations) {
  MinNormPoint nearest = wolfe_corral(pair, max_iterations, start, hint_a, hint_b, evaluations);
  if (!pair.a.curved() && !pair.b.curved()) return nearest;
  Answer best = answer_from_corral(pair, nearest);
  for (int k = 0; k < kCurvedRestarts && best.upper > pair.tolerance &&
                  !(value_proven(pair, best) && verdict_proven(pair, best));
       ++k) {
    const MinNormPoint again =
        wolfe_corral(pair, max_iterations, Vector3(nearest.x), -1, -1, evaluations);
    const Answer answer = answer_from_corral(pair, again);
    if (!(answer.upper - answer.lower < best.upper - best.lower)) break;
    best = answer;
    nearest = again;
  }
  return nearest;
}

// The answer of Wolfe's corral, with its iterations and evaluations.
Answer corral_answer(const FramedPair& pair, const MinNormPoint& nearest, long evaluations) {
  Answer answer = answer_from_corral(pair, nearest);
  answer.iterations = nearest.iterations;
  answer.evaluations = evaluations;
  return answer;
}

// Wolfe's answer from `start`, its corral in `nearest`. Where it leaves the value unproven, the
// planes of its corral are tried (settles_value): a pair a hair apart face to face has a nearest
// point whose direction is off by the rounding of unit points over its norm, and the separation
// along it loses that angle times the faces' width (a polytope 2e-9 of its size from a box's
// face: lower bound 0, uncertified, where a signed distance was certified).
template <class Start>
Answer nearest_points(const FramedPair& pair, int max_iterations, const Start& start, int hint_a,
                      int hint_b, MinNormPoint& nearest) {
  long evaluations = 0;
  nearest = nearest_corral(pair, max_iterations, start, hint_a, hint_b, evaluations);
  Answer answer = corral_answer(pair, nearest, evaluations);
  settles_value(pair, nearest, answer);
  return answer;
}

template <class Start>
Answer nearest_points(const FramedPair& pair, int max_iterations, const Start& start, int hint_a,
                      int hint_b) {
  MinNormPoint nearest;
  return nearest_points(pair, max_iterations, start, hint_a, hint_b, nearest);
}

// A corral as a start: one of several points counts as no point reached yet, since one already
// at its nearest point (FCL's projections leave it so) would otherwise end the search as making
// no progress.
MinNormPoint corral_start(const MinNormPoint& corral) {
  MinNormPoint start = corral;
  start.x = corral.size > 1 ? Vector3::Constant(std::numeric_limits<Scalar>::infinity())
                            : corral.corral[0].p;
  return start;
}

Vector3 start_direction(const FramedPair& pair, const Vector3& start) {
  return start.norm() > 0 ? start : Vector3(pair.b.offset() - pair.a.offset());
}

}  // namespace

Answer exact_distance(const FramedPair& pair, int max_iterations, const Vector3& start) {
  return nearest_points(pair, max_iterations, start_direction(pair, start), -1, -1);
}

Answer exact_distance(const FramedPair& pair, int max_iterations, const MinNormPoint& corral) {
  return nearest_points(pair, max_iterations, corral_start(corral), corral.corral[0].ia,
                        corral.corral[0].ib);
}

Answer exact_distance_again(const FramedPair& pair, int max_iterations, MinNormPoint& corral) {
  Answer answer;
  if (corral.size == 0) {
    answer = nearest_points(pair, max_iterations, start_direction(pair, Vector3::Zero()), -1, -1,
                            corral);
  } else {
    for (int k = 0; k < corral.size; ++k) {
      OraclePoint& point = corral.corral[k];
      point.p = pair.b.vertex(point.ib) - pair.a.vertex(point.ia);
    }
    answer = nearest_points(pair, max_iterations, corral_start(corral), corral.corral[0].ia,
                            corral.corral[0].ib, corral);
  }
  if (corral.size >= MinNormPoint::kCapacity) corral.size = 0;
  return answer;
}

Answer settled_distance(const FramedPair& pair, int max_iterations, const Vector3& start) {
  // Wolfe's algorithm reaches a polytope pair's 1e-14 gap in a few steps: no stop is worth it.
  if (!pair.a.curved() && !pair.b.curved()) return exact_distance(pair, max_iterations, start);
  long evaluations = 0;
  int hint_a = -1;
  int hint_b = -1;
  const auto oracle = [&](const Vector3& d) {
    ++evaluations;
    return minkowski_support(pair.a, pair.b, d, hint_a, hint_b);
  };
  // The separation of the corral's new point along its point's direction x / |x| within the
  // tolerance of |x|: the witnesses' direction is x's up to rounding, so the separation along it
  // (answer_from_corral's scan) will likely prove the value too.
  const auto settled = [&pair](const MinNormPoint& now, Scalar norm, const OraclePoint* q) {
    return q != nullptr && value_proven(pair, now.x.dot(q->p) / norm, norm);
  };
  const MinNormPoint nearest =
      wolfe_min_norm(oracle, start_direction(pair, start), 2, max_iterations, settled);
  // The separation along the witnesses is one more oracle call.
  Answer answer = corral_answer(pair, nearest, evaluations + 1);
  if (value_proven(pair, answer)) return answer;
  Answer exact = exact_distance(pair, max_iterations, start);
  exact.iterations += answer.iterations;
  exact.evaluations += answer.evaluations;
  return exact;
}

namespace {

// Whether `n` keeps `answer`'s witnesses within the tolerance of `upper * n`: taken as the
// answer's direction, the lower bound is its separation along n, and `point_b - point_a =
// distance * direction` must still hold to the tolerance. Bodies a hair apart (upper within a few
// tolerances) always keep it; a pair farther apart whose plane proves the value from a direction
// an angle off the witnesses' moves them by the distance times that angle.
bool keeps_witnesses(const FramedPair& pair, const Answer& answer, const Vector3& n) {
  return (answer.point_b - answer.point_a - answer.upper * n).norm() <= pair.tolerance;
}

// True when the plane through p0, p1 and p2 (points of B - A) proves `answer`'s value: the
// separation along its normal, either way, within the tolerance of `answer.upper`. The normal
// of three points of norm about 1 is as accurate as they are, where the direction of a nearest
// point a hair from the origin is not.
bool plane_settles(const FramedPair& pair, const OraclePoint& p0, const Vector3& p1,
                   const Vector3& p2, Answer& answer) {
  Vector3 normal = (p1 - p0.p).cross(p2 - p0.p);
  const Scalar length = normal.norm();
  if (!(length > 0)) return false;
  // Towards the triangle from the origin first: B - A lies beyond the plane on that side.
  normal /= normal.dot(p0.p) < 0 ? -length : length;
  for (const Vector3& n : {normal, Vector3(-normal)}) {
    int hint_a = p0.ia;
    int hint_b = p0.ib;
    const Scalar s = separation(pair.a, pair.b, n, hint_a, hint_b);
    if (value_proven(pair, s, answer.upper) && keeps_witnesses(pair, answer, n)) {
      answer.lower = s;
      answer.direction = n;
      return true;
    }
  }
  return false;
}

}  // namespace

bool settles_signed_distance(const FramedPair& pair, const MinNormPoint& corral, Answer& answer) {
  if (pair.a.curved() || pair.b.curved()) return false;
  return settles_value(pair, corral, answer);
}

bool settles_value(const FramedPair& pair, const MinNormPoint& corral, Answer& answer) {
  if (value_proven(pair, answer)) return true;
  const std::array<OraclePoint, MinNormPoint::kCapacity>& p = corral.corral;
  if (corral.size == 3) return plane_settles(pair, p[0], p[1].p, p[2].p, answer);
  if (corral.size != 2) return false;
  // The nearest point lies inside a segment of B - A: an edge of it (bodies touching edge to
  // edge along parallel edges), or a chord of a face (face to face). Its direction is off by the
  // rounding of the points over its norm, 1e-5 radians for points of norm 1 a hair apart, and
  // the separation along it loses that angle times the segment's length. With its part along
  // the segment taken off it points into the segment's normal plane to the rounding of unit
  // quantities, and the angle left within that plane costs nothing inside the normal cone of an
  // edge. Out of it, or for a chord, the lowest point along it lies off the segment's line, on
  // the face the segment borders or crosses: that plane's normal proves the value.
  const Vector3 edge = p[1].p - p[0].p;
  const Scalar squared = edge.squaredNorm();
  if (!(squared > 0)) return false;
  const Vector3 across = corral.x - (corral.x.dot(edge) / squared) * edge;
  const Scalar norm = across.norm();
  if (!(norm > 0)) return false;
  const Vector3 n = across / norm;
  int hint_a = p[0].ia;
  int hint_b = p[0].ib;
  const Vector3 lowest = minkowski_support(pair.a, pair.b, n, hint_a, hint_b).p;
  const Scalar s = n.dot(lowest);  // the separation along n
  if (value_proven(pair, s, answer.upper) && keeps_witnesses(pair, answer, n)) {
    answer.lower = s;
    answer.direction = n;
    return true;
  }
  return plane_settles(pair, p[0], p[1].p, lowest, answer);
}

Answer exact_penetration(const FramedPair& pair, int max_iterations, const Vector3& hint,
                         Scalar distance_upper, const MinNormPoint* nearest,
                         KeptSurface* surface) {
  PenetrationBounds bounds =
      penetration(pair.a, pair.b, hint, nearest, pair.tolerance, max_iterations, surface);
  Answer answer;
  // The separation less what the scans in the bodies' own frames may fall short by: the query
  // layer's verdicts subtract kFrameRounding, which covers the rest of the solver's margin (64 u
  // times the largest coordinate, at most 1 in the frame).
  answer.lower = bounds.separation - bounds.scan_shortfall;
  answer.upper = std::min(bounds.upper, distance_upper);
  answer.direction = bounds.normal;
  answer.point_a = bounds.point_a;
  answer.point_b = bounds.point_b;
  answer.weights_a = std::move(bounds.weights_a);
  answer.weights_b = std::move(bounds.weights_b);
  answer.iterations = bounds.iterations;
  // Each step of the solver's loops (Wolfe's, the expanding polytope's, a cylinder's side chain,
  // a rolling ball's) asks one support point of B - A; the searches for witnesses and the scans
  // that measure a separation are not counted.
  answer.evaluations = bounds.iterations;
  answer.witnesses_along_direction = bounds.witnesses_along_normal;
  // The witnesses are points of the bodies, so their distance bounds the signed distance above
  // too. Where the solver stopped before its bounds met on a pair it did not show overlapping (an
  // iteration budget of 1 or 2, say), the witnesses of its best separation may lie nearer than
  // the upper bound it proved (0.033 against 0.136 on census case 47:3210), off its normal. The
  // answer is then theirs where that brackets the value more tightly, as a distance's is: their
  // distance, their direction and the separation along it, so that `point_b - point_a = upper *
  // direction` and the lower bound is the separation along the direction, as every answer's are.
  // (Not on a touching pair: the direction between witnesses a few roundoffs apart is noise.)
  const Vector3 between = answer.point_b - answer.point_a;
  const Scalar apart = between.norm();
  if (apart > 0 && apart < answer.upper) {
    const Vector3 direction = between / apart;
    const Scalar lower = separation(pair.a, pair.b, direction);
    if (apart - lower < answer.upper - answer.lower) {
      answer.upper = apart;
      answer.lower = lower;
      answer.direction = direction;
      answer.witnesses_along_direction = true;
    }
  }
  return answer;
}

Answer exact_signed_distance(const FramedPair& pair, int max_iterations, const Vector3& hint) {
  long evaluations = 0;
  const MinNormPoint nearest =
      nearest_corral(pair, max_iterations, start_direction(pair, hint), -1, -1, evaluations);
  Answer apart = corral_answer(pair, nearest, evaluations);
  // A positive separation proves the bodies apart, and their distance is the signed distance,
  // its value settled as exact_distance settles it, curved bodies' too (the corral's planes, where
  // Wolfe's restarts leave its direction short: a capsule 3.5e-5 from a flat ellipsoid, 2.8e-9
  // between the bounds, uncertified where the distance was certified); a touching pair's may be
  // settled without the expanding polytope (polytopes only: settles_signed_distance).
  if (apart.lower > kFrameRounding) {
    settles_value(pair, nearest, apart);
    return apart;
  }
  if (settles_signed_distance(pair, nearest, apart)) return apart;
  const Vector3 start = hint.norm() > 0 ? hint : apart.direction;
  // Wolfe's corral is not computed again; around the origin it starts the expanding polytope.
  Answer overlap = exact_penetration(pair, max_iterations, start, apart.upper, &nearest);
  overlap.iterations += apart.iterations;
  overlap.evaluations += apart.evaluations;
  overlap.intersection_proven = apart.intersection_proven;
  return overlap;
}

Answer solve_exact(const FramedPair& pair, const QueryOptions& options, Goal goal) {
  if (closed_form_pair(pair)) {
    Answer closed;
    if (answered_in_closed_form(pair, goal, options.exact.max_iterations, closed)) return closed;
  }
  if (goal == Goal::signed_distance) {
    return exact_signed_distance(pair, options.exact.max_iterations, Vector3::Zero());
  }
  return exact_distance(pair, options.exact.max_iterations, Vector3::Zero());
}

}  // namespace swarmcollide::detail
