#include "fcl_solver.hpp"

#include <fcl/geometry/shape/convex.h>
#include <fcl/narrowphase/detail/convexity_based_algorithm/gjk.h>

#include <memory>
#include <vector>

#include "../geometry/normalise.hpp"
#include "../queries/verdict.hpp"
#include "exact_solver.hpp"
#include "minkowski.hpp"
#include "witness.hpp"

namespace swarmcollide::detail {

namespace {

// GJK's stopping threshold in frame units (the bodies lie in the unit ball): relative precision
// near double's; whatever GJK leaves unproven goes to the exact solver.
constexpr Scalar kGjkTolerance = 1e-14;
// A body's hull as an fcl::Convexd: local points around the body's box centre, divided by
// 2^exponent, as FramedBody places them before its rotation. Built once per body and exponent.
struct FclConvex {
  std::shared_ptr<const fcl::Convexd> shape;
};

FclConvex make_convex(const FramedBody& framed) {
  const Hull& hull = framed.hull();
  auto vertices = std::make_shared<std::vector<fcl::Vector3d>>();
  vertices->reserve(hull.vertex_indices.size());
  for (int i : hull.vertex_indices) {
    fcl::Vector3d p;
    for (int k = 0; k < 3; ++k) {
      p(k) = times_power_of_two(framed.local_points()(i, k), -framed.exponent());
    }
    vertices->push_back(p);
  }
  // No faces: GJK_indep's supports (fcl::detail::MinkowskiDiff) scan the vertices whatever the
  // size, never walking the faces, which would only cost the constructor an adjacency build.
  return {std::make_shared<const fcl::Convexd>(vertices, 0, std::make_shared<std::vector<int>>())};
}

// Kept with the body (ConvexPolyhedron::derived), found without a lock or a reference count.
const FclConvex& convex_of(const FramedBody& body) {
  return body.body().derived<FclConvex>([&body] { return make_convex(body); }, body.exponent());
}

fcl::Transform3d transform_of(const FramedBody& body) {
  fcl::Transform3d transform = fcl::Transform3d::Identity();
  transform.linear() = body.rotation();
  transform.translation() = body.offset();
  return transform;
}

// FCL's GJK on the pair; on return `gjk` holds its final simplex in A's shape frame.
fcl::detail::GJK<Scalar>::Status run_gjk(const FramedPair& pair, const FclConvex& a,
                                         const FclConvex& b, fcl::detail::GJK<Scalar>& gjk,
                                         fcl::detail::MinkowskiDiff<Scalar>& difference) {
  const fcl::Transform3d place_a = transform_of(pair.a);
  const fcl::Transform3d place_b = transform_of(pair.b);
  difference.shapes[0] = a.shape.get();
  difference.shapes[1] = b.shape.get();
  difference.toshape1.noalias() = place_b.linear().transpose() * place_a.linear();
  difference.toshape0 = place_a.inverse(Eigen::Isometry) * place_b;
  // Start towards B, as seen from A.
  Vector3 guess = place_a.linear().transpose() * (pair.a.offset() - pair.b.offset());
  if (!(guess.norm() > 0)) guess = Vector3::UnitX();
  return gjk.evaluate(difference, guess);
}

// The answer along the line between the bodies' centres: its separation (the lower bound) and
// the two support points (the upper bound).
Answer along_centres(const FramedPair& pair) {
  const Vector3 between = pair.b.offset() - pair.a.offset();
  const Vector3 n = between.norm() > 0 ? Vector3(between.normalized()) : Vector3::UnitX();
  int ia = -1;  // large bodies climb from their hulls' cube maps of starts
  int ib = -1;
  const Scalar lower = separation(pair.a, pair.b, n, ia, ib);
  Answer answer = answer_from_witness(pair, vertex_witness(pair, ia, ib));
  answer.lower = lower;
  answer.direction = n;
  answer.evaluations = 1;
  return answer;
}

}  // namespace

Answer solve_fcl(const FramedPair& pair, const QueryOptions& options, Goal goal) {
  // FCL's GJK has no early exit for an intersection test: it runs to the distance. The centres'
  // line proves most separated pairs apart in two support scans (as libccd's test would stop).
  const FclConvex& convex_a = convex_of(pair.a);
  const FclConvex& convex_b = convex_of(pair.b);
  if (goal == Goal::verdict) {
    Answer screened = along_centres(pair);
    if (verdict_proven(pair, screened)) return screened;
  }
  using Gjk = fcl::detail::GJK<Scalar>;
  const int max_iterations = options.exact.max_iterations;
  Gjk gjk(static_cast<unsigned int>(max_iterations), kGjkTolerance);
  fcl::detail::MinkowskiDiff<Scalar> difference;
  const Gjk::Status status = run_gjk(pair, convex_a, convex_b, gjk, difference);
  // FCL's simplex as the bodies' own points: the support indices along each simplex vertex's
  // direction, found in the bodies' own frames; on large bodies by a climb from their hulls' cube
  // maps of starts (Hull::climb_starts), a few neighbour checks where a scan would cost as much
  // as an iteration of FCL's GJK (whose supports scan every vertex). Any points of the bodies give a valid witness: the
  // bounds are computed from these points, not from FCL's.
  const Gjk::Simplex& simplex = *gjk.getSimplex();
  const Matrix3 to_b = difference.toshape1;
  MinNormPoint corral;
  Scalar total = 0;
  for (unsigned int k = 0; k < simplex.rank; ++k) {
    if (!(simplex.p[k] > 0)) continue;  // a point the last projection gave no weight
    const Vector3 d = simplex.c[k]->d;
    const Vector3 d_b = -(to_b * d);
    const int ia = pair.a.local_support_index(d, -1);
    const int ib = pair.b.local_support_index(d_b, -1);
    total += simplex.p[k];
    // Two of FCL's points may be the same pair of vertices: one corral point (Wolfe's affine
    // solves need distinct points).
    int same = 0;
    while (same < corral.size && !(corral.corral[same].ia == ia && corral.corral[same].ib == ib))
      ++same;
    if (same == corral.size) {
      corral.corral[corral.size++] = {pair.b.vertex(ib) - pair.a.vertex(ia), ia, ib};
      corral.weights[same] = 0;
    }
    corral.weights[same] += simplex.p[k];
  }
  for (int k = 0; k < corral.size; ++k) corral.weights[k] /= total;
  const auto settles = [&pair, goal](const Answer& answer) {
    return goal_reached(pair, goal, answer.lower, answer.upper, answer.intersection_proven);
  };
  const bool usable = status != Gjk::Failed && corral.size > 0;
  if (usable) {
    Answer answer = answer_from_corral(pair, corral);
    if (settles(answer)) return answer;
  }
  // Where FCL's answer does not settle the goal, the exact solver takes over: distances from
  // FCL's simplex (FCL stops when a support point comes within sqrt(its tolerance) of an earlier
  // one, often an iteration or two short), then from the direction if that simplex was too
  // degenerate to continue; signed distances from its direction.
  const Vector3 start =
      usable ? Vector3(combination(corral.corral, corral.weights, corral.size))
             : Vector3::Zero();
  Answer exact;
  if (goal == Goal::signed_distance) {
    exact = exact_signed_distance(pair, max_iterations, start);
  } else {
    if (usable) exact = exact_distance(pair, max_iterations, corral);
    if (!usable || !settles(exact)) exact = exact_distance(pair, max_iterations, start);
  }
  exact.answered_by = Method::exact;
  return exact;
}

}  // namespace swarmcollide::detail
