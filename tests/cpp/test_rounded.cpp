// Rounded bodies (a radius on a ConvexPolyhedron) and the shapes made of them, Sphere, Capsule
// and Box, against closed forms: every query answers on the cores and subtracts the radii.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <vector>

#include "geometry/framed_body.hpp"
#include "queries/rounded.hpp"
#include "shapes.hpp"
#include "swarmcollide/geometry/compound_body.hpp"
#include "swarmcollide/geometry/shapes.hpp"
#include "swarmcollide/queries/methods.hpp"
#include "swarmcollide/queries/query.hpp"

namespace swarmcollide::testing {
namespace {

Query query_of(Method method, Scalar tolerance = kDefaultTolerance) {
  QueryOptions options;
  options.method = method;
  options.tolerance = tolerance;
  return Query(options);
}

// Distance between the point p and the segment (q0, q1).
Scalar point_to_segment(const Vector3& p, const Vector3& q0, const Vector3& q1) {
  const Vector3 d = q1 - q0;
  const Scalar t = std::clamp((p - q0).dot(d) / d.squaredNorm(), 0.0, 1.0);
  return (p - (q0 + t * d)).norm();
}

// Distance between segments by brute force: a grid over the first segment's parameter, then a
// ternary search (the distance to a segment is convex along a segment) around the best node.
Scalar segment_to_segment(const Vector3& p0, const Vector3& p1, const Vector3& q0,
                          const Vector3& q1) {
  const auto at_s = [&](Scalar s) { return point_to_segment(p0 + s * (p1 - p0), q0, q1); };
  constexpr int kNodes = 1000;
  int best = 0;
  for (int i = 1; i <= kNodes; ++i) {
    if (at_s(Scalar(i) / kNodes) < at_s(Scalar(best) / kNodes)) best = i;
  }
  Scalar lo = std::max(0.0, Scalar(best - 1) / kNodes);
  Scalar hi = std::min(1.0, Scalar(best + 1) / kNodes);
  for (int k = 0; k < 200; ++k) {
    const Scalar m1 = lo + (hi - lo) / 3;
    const Scalar m2 = hi - (hi - lo) / 3;
    (at_s(m1) < at_s(m2) ? hi : lo) = at_s(m1) < at_s(m2) ? m2 : m1;
  }
  return at_s((lo + hi) / 2);
}

// Distance from p to the axis-aligned box of half extents h about the origin.
Scalar point_to_box(const Vector3& p, const Vector3& h) {
  return (p.cwiseAbs() - h).cwiseMax(0.0).norm();
}

// The bounds enclose `expected` and the distance is within the tolerance of it, certified.
void expect_answer(const DistanceResult& r, Scalar expected, Scalar size,
                   Scalar tolerance = kDefaultTolerance) {
  const Scalar slack = 1e-13 * size;
  EXPECT_TRUE(r.certified);
  EXPECT_LE(r.lower_bound, expected + slack);
  EXPECT_GE(r.distance, expected - slack);
  EXPECT_NEAR(r.distance, expected, tolerance * size + slack);
}

const std::vector<Method> kMeasuring = {Method::dual, Method::exact, Method::fcl};
const std::vector<Method> kSigned = {Method::dual, Method::exact, Method::fcl, Method::libccd};

// shifted_by_radii moves an inexact `core - r_a - r_b` out by its rounding's bound, then to the
// next double outward, stepping the bits as next_down does: std::nextafter's value, bit for bit,
// for bounds of either sign and near zero.
TEST(Rounded, ShiftedBoundsStepAsNextafterDoes) {
  const Sphere a(0.3);
  const Sphere b(0.1);
  const detail::FramedPair pair =
      detail::frame_pair(a, at(Vector3::Zero()), b, at(Vector3(1, 0, 0)), kDefaultTolerance);
  const Scalar radii = pair.radius_a + pair.radius_b;
  const auto bits = [](Scalar x) {
    std::uint64_t b;
    std::memcpy(&b, &x, sizeof b);
    return b;
  };
  Random rng(5);
  std::vector<Scalar> cores{0.0, -0.0, radii, -radii, 1e-310, -1e-310, radii * (1 + 1e-15)};
  for (int k = 0; k < 200; ++k) cores.push_back(rng.uniform(-2, 2));
  int stepped = 0;
  for (const Scalar core : cores) {
    for (const Scalar outward : {-1.0, 1.0}) {
      const Scalar shifted = detail::shifted_by_radii(pair, core, outward);
      if (shifted == core - radii) continue;  // proven exact, not moved
      ++stepped;
      const Scalar moved = core - radii + outward * detail::subtraction_rounding(pair, core);
      EXPECT_EQ(bits(shifted),
                bits(std::nextafter(moved, outward * std::numeric_limits<Scalar>::infinity())))
          << "core " << core << ", outward " << outward;
    }
  }
  EXPECT_GT(stepped, 200);
}

// A closed form rounds its bounds for its goal test and keeps them (Answer::rounded):
// round_answer takes them for the very bounds they round, and rounds any other bounds anew.
TEST(Rounded, RoundAnswerTakesTheBoundsAClosedFormRounded) {
  const Sphere a(0.3);
  const Sphere b(0.1);
  const detail::FramedPair pair =
      detail::frame_pair(a, at(Vector3::Zero()), b, at(Vector3(1, 0, 0)), kDefaultTolerance);
  const Scalar core_lower = 0.37;
  const Scalar core_upper = 0.38;
  const detail::RoundedBounds rounded = detail::rounded_bounds(pair, core_lower, core_upper);
  EXPECT_EQ(rounded.lower, detail::rounded_lower(pair, core_lower));
  EXPECT_EQ(rounded.upper, detail::rounded_upper(pair, core_upper));
  // The balls' closed form shifts both in one call, to the same values.
  const detail::RoundedBounds shifted = detail::shifted_bounds(pair, core_lower, core_upper);
  EXPECT_EQ(shifted.lower, rounded.lower);
  EXPECT_EQ(shifted.upper, rounded.upper);
  const auto answer_of = [&](Scalar lower, Scalar upper) {
    detail::Answer answer;
    answer.lower = lower;
    answer.upper = upper;
    answer.direction = Vector3::UnitX();
    answer.point_b = Vector3(upper, 0, 0);
    return answer;
  };
  // Kept bounds that differ from rounding anew show which was taken.
  detail::Answer kept = answer_of(core_lower, core_upper);
  kept.rounded = {core_lower, core_upper, 0.125, 0.25};
  detail::round_answer(pair, detail::Goal::signed_distance, kept);
  EXPECT_EQ(kept.lower, 0.125);
  EXPECT_EQ(kept.upper, 0.25);
  // Bounds changed since they were kept, or never kept, are rounded anew.
  for (const bool keep : {true, false}) {
    detail::Answer changed = answer_of(core_lower, core_upper * 2);
    if (keep) changed.rounded = {core_lower, core_upper, 0.125, 0.25};
    detail::round_answer(pair, detail::Goal::signed_distance, changed);
    EXPECT_EQ(changed.lower, detail::rounded_lower(pair, core_lower));
    EXPECT_EQ(changed.upper, detail::rounded_upper(pair, core_upper * 2));
  }
}

TEST(Rounded, SpheresMatchTheClosedForm) {
  Random rng(3);
  for (int trial = 0; trial < 20; ++trial) {
    const Sphere a(rng.uniform(0.1, 2));
    const Sphere b(rng.uniform(0.1, 2));
    const Pose pa = at(rng.vector(3));
    const Pose pb = at(rng.vector(3));
    const Scalar centres = (pb.translation - pa.translation).norm();
    const Scalar signed_distance = centres - a.radius() - b.radius();
    const Scalar size = size_of(a, pa, b, pb);
    for (Method method : kSigned) {
      SCOPED_TRACE(method_name(method));
      const Query query = query_of(method);
      const DistanceResult s = query.signed_distance(a, pa, b, pb);
      expect_answer(s, signed_distance, size);
      // The witnesses are on the spheres, and along the normal.
      EXPECT_NEAR((s.point_a - pa.translation).norm(), a.radius(), 1e-12 * size);
      EXPECT_NEAR((s.point_b - pb.translation).norm(), b.radius(), 1e-12 * size);
      EXPECT_NEAR((s.point_b - s.point_a - s.distance * s.direction).norm(), 0, 1e-12 * size);
      EXPECT_EQ(query.collide(a, pa, b, pb), signed_distance <= 0);
      if (method == Method::libccd) continue;
      const DistanceResult d = query.distance(a, pa, b, pb);
      expect_answer(d, std::max(signed_distance, 0.0), size);
      EXPECT_NEAR((d.point_b - d.point_a).norm(), d.distance, 1e-12 * size);
    }
  }
}

// Concentric and overlapping spheres: the cores are one point twice, or two points closer than
// the radii; the depth is the radii less the centres' distance.
TEST(Rounded, OverlappingSpheresHaveTheirDepth) {
  const Sphere a(1.5);
  const Sphere b(0.5);
  for (Scalar centres : {0.0, 0.25, 1.0, 1.9}) {
    SCOPED_TRACE(centres);
    const Pose pb = at(Vector3(0, centres, 0));
    for (Method method : kSigned) {
      SCOPED_TRACE(method_name(method));
      const Query query = query_of(method);
      const DistanceResult s = query.signed_distance(a, {}, b, pb);
      expect_answer(s, centres - 2, size_of(a, {}, b, pb));
      EXPECT_TRUE(s.colliding);
      EXPECT_TRUE(query.collide(a, {}, b, pb));
      if (method == Method::libccd) continue;
      const DistanceResult d = query.distance(a, {}, b, pb);
      EXPECT_EQ(d.distance, 0);
      EXPECT_TRUE(d.certified);
      // One witness, within both spheres.
      EXPECT_EQ(d.point_a, d.point_b);
      EXPECT_LE(d.point_a.norm(), a.radius() + 1e-12);
      EXPECT_LE((d.point_b - pb.translation).norm(), b.radius() + 1e-12);
    }
  }
}

TEST(Rounded, SphereAndBoxMatchThePointToBoxDistance) {
  Random rng(5);
  const Vector3 half(1, 0.5, 2);
  const Box box(half);
  for (int trial = 0; trial < 20; ++trial) {
    const Sphere ball(rng.uniform(0.05, 1));
    const Matrix3 turn = rng.rotation();
    const Vector3 centre = rng.vector(4);
    const Pose pose_box = at(Vector3(0.3, -0.2, 0.1), turn);
    const Pose pose_ball = at(pose_box.rotation * centre + pose_box.translation);
    const Scalar expected = point_to_box(centre, half) - ball.radius();
    if (point_to_box(centre, half) == 0) continue;  // a centre inside: a depth, not this form
    const Scalar size = size_of(box, pose_box, ball, pose_ball);
    for (Method method : kMeasuring) {
      SCOPED_TRACE(method_name(method));
      const Query query = query_of(method);
      expect_answer(query.signed_distance(box, pose_box, ball, pose_ball), expected, size);
      expect_answer(query.distance(box, pose_box, ball, pose_ball), std::max(expected, 0.0), size);
    }
  }
}

TEST(Rounded, CapsulesMatchTheSegmentDistanceLessTheRadii) {
  Random rng(7);
  for (int trial = 0; trial < 20; ++trial) {
    const Capsule a(rng.uniform(0.05, 0.5), rng.uniform(0.1, 2));
    const Capsule b(rng.uniform(0.05, 0.5), rng.uniform(0.1, 2));
    const Pose pa = at(rng.vector(2), rng.rotation());
    const Pose pb = at(rng.vector(2), rng.rotation());
    const auto end = [](const Capsule& c, const Pose& p, Scalar sign) -> Vector3 {
      return p.rotation * Vector3(0, 0, sign * c.half_length()) + p.translation;
    };
    const Scalar segments = segment_to_segment(end(a, pa, -1), end(a, pa, 1), end(b, pb, -1),
                                               end(b, pb, 1));
    const Scalar expected = segments - a.radius() - b.radius();
    const Scalar size = size_of(a, pa, b, pb);
    for (Method method : kMeasuring) {
      SCOPED_TRACE(method_name(method));
      const Query query = query_of(method);
      const DistanceResult d = query.distance(a, pa, b, pb);
      expect_answer(d, std::max(expected, 0.0), size);
      if (segments > 0) expect_answer(query.signed_distance(a, pa, b, pb), expected, size);
      EXPECT_EQ(query.collide(a, pa, b, pb), expected <= kDefaultTolerance * size);
    }
  }
}

// Crossing and collinear overlapping segments touch (their depth is 0): two capsules so placed
// overlap by both radii.
TEST(Rounded, CrossingCapsulesOverlapByBothRadii) {
  const Capsule a(0.25, 1);
  const Capsule b(0.5, 1);
  Matrix3 lying;
  lying << 1, 0, 0, 0, 0, -1, 0, 1, 0;  // z onto y
  for (const Pose& pb : {at(Vector3::Zero(), lying), at(Vector3(0, 0, 0.5))}) {
    for (Method method : kSigned) {
      SCOPED_TRACE(method_name(method));
      const DistanceResult s = query_of(method).signed_distance(a, {}, b, pb);
      expect_answer(s, -0.75, size_of(a, {}, b, pb));
    }
  }
}

TEST(Rounded, RoundedBoxesMatchTheSharpBoxesLessTheRadius) {
  const Vector3 half(1, 1, 1);
  const Box sharp(half);
  const Box round(half, 0.25);
  EXPECT_EQ(round.aabb().max.x(), std::nextafter(1.25, 2.0));
  // Face to face, and corner to corner along the diagonal.
  const Pose beside = at(Vector3(3, 0.5, 0));
  const Pose diagonal = at(Vector3(3, 3, 3));
  for (Method method : kMeasuring) {
    SCOPED_TRACE(method_name(method));
    const Query query = query_of(method);
    expect_answer(query.distance(round, {}, sharp, beside), 0.75,
                  size_of(round, {}, sharp, beside));
    expect_answer(query.distance(round, {}, round, diagonal), std::sqrt(3.0) - 0.5,
                  size_of(round, {}, round, diagonal));
    expect_answer(query.signed_distance(round, {}, sharp, at(Vector3(2, 0, 0))), -0.25,
                  size_of(round, {}, sharp, at(Vector3(2, 0, 0))));
  }
}

// The same pair in any unit of length gets the same answer in that unit.
TEST(Rounded, AnswersScaleWithTheUnitOfLength) {
  for (int e = -100; e <= 100; e += 25) {
    const Scalar unit = std::pow(10.0, e);
    SCOPED_TRACE(unit);
    const Capsule a(0.5 * unit, 1 * unit);
    const Sphere b(0.25 * unit);
    const Pose pb = at(Vector3(2, 0, 0.5) * unit);
    for (Method method : kMeasuring) {
      SCOPED_TRACE(method_name(method));
      const Query query = query_of(method);
      expect_answer(query.distance(a, {}, b, pb), 1.25 * unit, size_of(a, {}, b, pb));
      const Pose inside = at(Vector3(0.5, 0, 0.25) * unit);
      expect_answer(query.signed_distance(a, {}, b, inside), -0.25 * unit,
                    size_of(a, {}, b, inside));
    }
  }
}

// Touching spheres moved apart and together by 1e-9 of the pair's size, at a tolerance far
// below that: both verdicts are proven, by every method.
TEST(Rounded, VerdictsAtTouchingArePrecise) {
  const Sphere a(1);
  const Capsule b(0.5, 1);
  const Scalar size = 4.5;  // the centres 1.5 apart, plus twice the capsule's reach of 1.5
  for (Scalar sign : {-1.0, 1.0}) {
    const Pose pb = at(Vector3(1.5 + sign * 1e-9 * size, 0, 0));
    for (Method method : {Method::dual, Method::exact, Method::fcl, Method::libccd}) {
      SCOPED_TRACE(method_name(method));
      const DistanceResult r = query_of(method, 1e-12).collision(a, {}, b, pb);
      EXPECT_TRUE(r.certified);
      EXPECT_EQ(r.colliding, sign < 0);
    }
  }
}

TEST(Rounded, CompoundBodiesOfRoundedParts) {
  const CompoundBody dumbbell(std::vector<ConvexPolyhedron>{
      ConvexPolyhedron(point_set({Vector3(-2, 0, 0)}).vertices(), 1),
      ConvexPolyhedron(point_set({Vector3(2, 0, 0)}).vertices(), 0.5)});
  const CompoundBody ball(ConvexPolyhedron(Sphere(0.25)));
  const Query query = query_of(Method::dual);
  const CompoundResult d = query.distance(dumbbell, {}, ball, at(Vector3(4, 1, 0)));
  expect_answer(d, std::sqrt(5.0) - 0.75, 12);
  EXPECT_EQ(d.part_a, 1);
  EXPECT_FALSE(query.collide(dumbbell, {}, ball, at(Vector3(0, 0, 0))));
  EXPECT_TRUE(query.collide(dumbbell, {}, ball, at(Vector3(-0.9, 0, 0))));
  const CompoundResult s = query.signed_distance(dumbbell, {}, ball, at(Vector3(-1.5, 0, 0)));
  expect_answer(s, -0.75, 12);
}

// Random hulls rounded by random radii, under random poses: every method's signed distance is
// the exact method's on the cores less both radii, symmetric in A and B, and its bounds hold.
TEST(Rounded, RandomRoundedHullsAreTheirCoresLessTheRadii) {
  Random rng(11);
  const Query exact = query_of(Method::exact);
  for (int trial = 0; trial < 30; ++trial) {
    const ConvexPolyhedron core_a = rng.body(3 + trial % 6);
    const ConvexPolyhedron core_b = rng.body(4 + trial % 5);
    const Scalar r = trial % 3 == 0 ? 0 : rng.uniform(0.01, 1);
    const Scalar s = rng.uniform(0.01, 1);
    const ConvexPolyhedron a(core_a.vertices(), r);
    const ConvexPolyhedron b(core_b.vertices(), s);
    const Pose pa = at(rng.vector(1), rng.rotation());
    const Pose pb = at(rng.vector(3), rng.rotation());
    const Scalar size = size_of(a, pa, b, pb);
    const DistanceResult cores = exact.signed_distance(core_a, pa, core_b, pb);
    ASSERT_TRUE(cores.certified);
    for (Method method : kSigned) {
      SCOPED_TRACE(method_name(method));
      const Query query = query_of(method);
      const DistanceResult ab = query.signed_distance(a, pa, b, pb);
      const DistanceResult ba = query.signed_distance(b, pb, a, pa);
      // The cores' value is known to their own tolerance, which the rounded pair's size exceeds.
      const Scalar value = cores.distance - r - s;
      const Scalar known = cores.distance - cores.lower_bound + 1e-13 * size;
      EXPECT_TRUE(ab.certified);
      EXPECT_LE(ab.lower_bound, value + known);
      EXPECT_GE(ab.distance, value - known);
      EXPECT_NEAR(ab.distance, ba.distance, 2 * kDefaultTolerance * size);
      EXPECT_NEAR((ab.point_b - ab.point_a - ab.distance * ab.direction).norm(), 0,
                  1e-9 * size);
      EXPECT_EQ(query.collide(a, pa, b, pb), ab.colliding);
    }
  }
}

TEST(Rounded, BadParametersAreRefusedByName) {
  const Scalar nan = std::numeric_limits<Scalar>::quiet_NaN();
  const Scalar inf = std::numeric_limits<Scalar>::infinity();
  for (Scalar bad : {0.0, -1.0, nan, inf}) {
    SCOPED_TRACE(bad);
    EXPECT_THROW(Sphere{bad}, std::invalid_argument);
    EXPECT_THROW(Capsule(bad, 1), std::invalid_argument);
    EXPECT_THROW(Capsule(1, bad), std::invalid_argument);
    EXPECT_THROW(Box(Vector3(1, bad, 1)), std::invalid_argument);
    if (bad != 0) {
      EXPECT_THROW(ConvexPolyhedron(point_set({Vector3::Zero()}).vertices(), bad),
                   std::invalid_argument);
      EXPECT_THROW(Box(Vector3::Ones(), bad), std::invalid_argument);
    }
  }
  try {
    Capsule(1, -2);
    ADD_FAILURE();
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("half_length"), std::string::npos);
  }
  // A radius that takes the body past the double range.
  EXPECT_THROW(Sphere(std::numeric_limits<Scalar>::max()), std::invalid_argument);
  EXPECT_NO_THROW(Box(Vector3::Ones(), 0));
}

}  // namespace
}  // namespace swarmcollide::testing
