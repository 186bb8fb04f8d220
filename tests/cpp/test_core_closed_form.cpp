// Spheres and capsules against each other and spheres against boxes: their cores (a point, a
// segment, a box) are answered from the nearest points' closed form (core_closed_form.hpp), in one
// iteration, with bounds proven as any search's.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "shapes.hpp"
#include "swarmcollide/geometry/shapes.hpp"
#include "swarmcollide/queries/query.hpp"

namespace swarmcollide::testing {
namespace {

using Long = long double;

// Distance from p to the segment (q0, q1), in long double.
Long to_segment(const Vector3& p, const Vector3& q0, const Vector3& q1) {
  Long along = 0;
  Long length = 0;
  for (int k = 0; k < 3; ++k) {
    along += Long(p(k) - q0(k)) * Long(q1(k) - q0(k));
    length += Long(q1(k) - q0(k)) * Long(q1(k) - q0(k));
  }
  const Long t = length > 0 ? std::clamp(along / length, Long(0), Long(1)) : 0;
  Long squared = 0;
  for (int k = 0; k < 3; ++k) {
    const Long d = Long(p(k)) - (Long(q0(k)) + t * (Long(q1(k)) - Long(q0(k))));
    squared += d * d;
  }
  return std::sqrt(squared);
}

// Distance between two segments: the distance to the second is convex along the first, so a
// golden-section search over the first's parameter finds its least value.
Long between_segments(const Vector3& p0, const Vector3& p1, const Vector3& q0,
                      const Vector3& q1) {
  const auto at = [&](Long s) {
    const Vector3 p = (p0.cast<Long>() + s * (p1 - p0).cast<Long>()).cast<Scalar>();
    return to_segment(p, q0, q1);
  };
  Long lo = 0;
  Long hi = 1;
  for (int step = 0; step < 200; ++step) {
    const Long m1 = lo + (hi - lo) * 0.381966L;
    const Long m2 = hi - (hi - lo) * 0.381966L;
    if (at(m1) < at(m2)) {
      hi = m2;
    } else {
      lo = m1;
    }
  }
  return std::min({at(0), at(1), at((lo + hi) / 2)});
}

// A sphere or a capsule of radius `radius` whose core is the segment (p0, p1) of the world (a
// point when they coincide: a capsule of length zero).
struct Rounded {
  ConvexPolyhedron body;
  Vector3 p0;
  Vector3 p1;
};

Rounded rounded(const Vector3& p0, const Vector3& p1, Scalar radius) {
  VertexMatrix ends(2, 3);
  ends.row(0) = p0.transpose();
  ends.row(1) = p1.transpose();
  return {ConvexPolyhedron(ends, radius), p0, p1};
}

// Every goal, both orders: certified, one iteration (the closed form, not a search), the bounds
// enclosing `expected` (the signed distance) and the distance within the tolerance of it.
void expect_closed_form(const ConvexPolyhedron& a, const Pose& pa, const ConvexPolyhedron& b,
                        const Pose& pb, Scalar expected, Scalar size) {
  const Query query;
  const Scalar slack = 1e-13 * size;
  for (bool swapped : {false, true}) {
    SCOPED_TRACE(swapped ? "B first" : "A first");
    const ConvexPolyhedron& first = swapped ? b : a;
    const ConvexPolyhedron& second = swapped ? a : b;
    const Pose& pose_first = swapped ? pb : pa;
    const Pose& pose_second = swapped ? pa : pb;
    const DistanceResult s = query.signed_distance(first, pose_first, second, pose_second);
    const DistanceResult d = query.distance(first, pose_first, second, pose_second);
    const DistanceResult v = query.collision(first, pose_first, second, pose_second);
    for (const DistanceResult* r : {&s, &d}) {
      const Scalar value = r == &s ? expected : std::max(expected, Scalar(0));
      EXPECT_EQ(r->iterations, 1);
      EXPECT_TRUE(r->certified);
      EXPECT_LE(r->lower_bound, value + slack);
      EXPECT_GE(r->distance, value - slack);
      EXPECT_NEAR(r->distance, value, kDefaultTolerance * size + slack);
    }
    EXPECT_EQ(v.iterations, 1);
    EXPECT_TRUE(v.certified);
    if (std::abs(expected) > 1e-6 * size) EXPECT_EQ(v.colliding, expected < 0);
  }
}

// Spheres and capsules placed at random, apart and overlapping, at scales from 1e-100 to 1e100.
TEST(CoreClosedForm, BallsAndCapsulesInBothOrdersAtEveryScale) {
  Random rng(61);
  for (Scalar scale : {1e-100, 1e-20, 1.0, 1e20, 1e100}) {
    for (int trial = 0; trial < 30; ++trial) {
      SCOPED_TRACE(::testing::Message() << "scale " << scale << " trial " << trial);
      const auto core = [&](bool segment) {
        const Vector3 c = rng.vector(2) * scale;
        const Vector3 half = segment ? Vector3(rng.unit() * rng.uniform(0.1, 1) * scale)
                                     : Vector3::Zero();
        return std::make_pair(Vector3(c - half), Vector3(c + half));
      };
      const auto [p0, p1] = core(trial % 3 != 0);
      const auto [q0, q1] = core(trial % 3 != 1);
      const Rounded a = rounded(p0, p1, rng.uniform(0.05, 1) * scale);
      const Rounded b = rounded(q0, q1, rng.uniform(0.05, 1) * scale);
      const Scalar cores = Scalar(between_segments(p0, p1, q0, q1));
      const Scalar expected = cores - a.body.radius() - b.body.radius();
      expect_closed_form(a.body, {}, b.body, {}, expected, size_of(a.body, {}, b.body, {}));
    }
  }
}

// Capsules side by side and in line: parallel segments, whose lines' nearest points are not
// defined, overlapping along their length or not, apart and overlapping; and segments crossing
// at right angles above each other.
TEST(CoreClosedForm, ParallelAndCrossingCapsules) {
  const Capsule a(0.25, 1);
  const Capsule b(0.5, 2);
  Matrix3 lying;
  lying << 1, 0, 0, 0, 0, -1, 0, 1, 0;  // z onto y
  struct Case {
    Pose pose;
    Scalar expected;
  };
  const std::vector<Case> cases = {
      {at(Vector3(1, 0, 0)), 1 - 0.75},                    // side by side, overlapping lengths
      {at(Vector3(1, 0, 2.5)), 1 - 0.75},                  // side by side, partly overlapping
      {at(Vector3(0.5, 0, 0)), 0.5 - 0.75},                // side by side, overlapping
      {at(Vector3(0, 0, 3.5)), 0.5 - 0.75},                // in line, ends 0.5 apart
      {at(Vector3(0, 0, 4)), 1 - 0.75},                    // in line, ends 1 apart
      {at(Vector3(3, 0, 4)), std::hypot(3, 1) - 0.75},     // parallel, past each other's ends
      {at(Vector3(2, 0, 0), lying), 2 - 0.75},             // crossing at right angles
      {at(Vector3(0.6, 0.3, 0.2), lying), 0.6 - 0.75},     // crossing, overlapping
      {at(Vector3(1, 0, 1.5), lying), std::hypot(1, 0.5) - 0.75},  // past A's end
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(::testing::Message() << c.pose.translation.transpose());
    expect_closed_form(a, {}, b, c.pose, c.expected, size_of(a, {}, b, c.pose));
  }
}

// A capsule of length zero is a sphere: its two ends are one point.
TEST(CoreClosedForm, ZeroLengthCapsulesAreBalls) {
  const Rounded ball = rounded(Vector3(0, 0, 1), Vector3(0, 0, 1), 0.5);
  const Capsule capsule(0.25, 1);
  for (const Vector3& at_point : {Vector3(2, 0, 1), Vector3(0, 0, 3), Vector3(0.3, 0.4, 0.5)}) {
    const Pose moved = at(at_point - Vector3(0, 0, 1));
    const Scalar expected =
        Scalar(to_segment(at_point, Vector3(0, 0, -1), Vector3(0, 0, 1))) - 0.75;
    expect_closed_form(ball.body, moved, capsule, {}, expected,
                       size_of(ball.body, moved, capsule, {}));
  }
}

// Spheres whose surfaces touch (their centres exactly the sum of the radii apart), graze (a
// rounding apart), or overlap deeply (centres almost together).
TEST(CoreClosedForm, TouchingGrazingAndDeeplyOverlappingBalls) {
  const Sphere a(1);
  const Sphere b(2);
  for (const Vector3& centre : {Vector3(3, 0, 0), Vector3(0, 0, 3 + 4e-16), Vector3(0, 0, -3),
                                Vector3(1e-3, 0, 0), Vector3(0, 1e-12, 0)}) {
    SCOPED_TRACE(::testing::Message() << centre.transpose());
    expect_closed_form(a, {}, b, at(centre), centre.norm() - 3, size_of(a, {}, b, at(centre)));
  }
}

// A sphere against a box, turned and moved, its centre beside a face, an edge or a corner, at
// scales from 1e-100 to 1e100; the centre inside (a depth, which the search answers) is not this
// form's.
TEST(CoreClosedForm, BallsAgainstBoxes) {
  Random rng(67);
  for (Scalar scale : {1e-100, 1.0, 1e100}) {
    const Vector3 half = Vector3(1, 0.5, 2) * scale;
    const Box box(half);
    for (int trial = 0; trial < 30; ++trial) {
      SCOPED_TRACE(::testing::Message() << "scale " << scale << " trial " << trial);
      const Sphere ball(rng.uniform(0.05, 1) * scale);
      const Pose pose_box = at(rng.vector(1) * scale, rng.rotation());
      Vector3 local = rng.vector(4) * scale;
      if (trial % 3 == 0) local(trial % 2) = rng.uniform(-0.4, 0.4) * scale;  // beside a face
      if (((local.cwiseAbs() - half).array() <= 0).all()) continue;
      const Pose pose_ball = at(pose_box.rotation * local + pose_box.translation);
      const Scalar expected = (local.cwiseAbs() - half).cwiseMax(0.0).norm() - ball.radius();
      expect_closed_form(box, pose_box, ball, pose_ball, expected,
                         size_of(box, pose_box, ball, pose_ball));
    }
  }
}

// The signed distance of a ball of radius `radius` whose centre is `centre` (world) inside the
// box of half extents `half` at `pose`, in long double: minus the centre's least distance to a
// face in the box's frame (the pose's rotation transposed as its inverse), less the radius; NaN
// for a centre outside the box or on it.
Long inside_box(const Vector3& half, const Pose& pose, const Vector3& centre, Scalar radius) {
  Long depth = HUGE_VALL;
  for (int k = 0; k < 3; ++k) {
    Long local = 0;
    for (int j = 0; j < 3; ++j) {
      local += Long(pose.rotation(j, k)) * (Long(centre(j)) - Long(pose.translation(j)));
    }
    depth = std::min(depth, Long(half(k)) - std::fabs(local));
  }
  return depth > 0 ? -depth - Long(radius) : Long(NAN);
}

// The witness of a body without radius as its weights give it: the combination of its points.
Vector3 from_weights(const ConvexPolyhedron& body, const Pose& pose, const ConvexWeights& w) {
  Vector3 point = Vector3::Zero();
  w.for_each([&](int i, Scalar weight) {
    point += weight * (pose.rotation * body.vertices().row(i).transpose() + pose.translation);
  });
  return point;
}

// A signed distance of a ball whose centre lies inside a box, both orders: answered in closed form
// (one iteration), certified, its bounds enclosing the exact value `expected` (long double, within
// the tolerance of each other), colliding, the contact normal and the witnesses consistent, and
// the box's witness on its surface as its weights make it.
void expect_inside_closed_form(const ConvexPolyhedron& box, const Pose& pose_box,
                               const Sphere& ball, const Pose& pose_ball, Long expected) {
  const Scalar size = size_of(box, pose_box, ball, pose_ball);
  const Scalar slack = 1e-13 * size;
  for (bool swapped : {false, true}) {
    SCOPED_TRACE(swapped ? "ball first" : "box first");
    const DistanceResult r = swapped ? Query().signed_distance(ball, pose_ball, box, pose_box)
                                     : Query().signed_distance(box, pose_box, ball, pose_ball);
    EXPECT_EQ(r.iterations, 1);
    EXPECT_TRUE(r.certified);
    EXPECT_TRUE(r.colliding);
    // The bounds are proven up to the frame's rounding (kFrameRounding, 128 roundoffs of the
    // size), which the verdicts take off: expect_closed_form's slack.
    EXPECT_LE(Long(r.lower_bound), expected + Long(slack));
    EXPECT_GE(Long(r.distance), expected - Long(slack));
    EXPECT_LE(r.distance - r.lower_bound, kDefaultTolerance * size);
    const Vector3 between = r.point_b - r.point_a;
    EXPECT_LE((between - r.distance * r.direction).norm(), 1e-12 * size);
    const Vector3 on_box = swapped ? r.point_b : r.point_a;
    EXPECT_LE((on_box - from_weights(box, pose_box, swapped ? r.weights_b : r.weights_a)).norm(),
              1e-12 * size);
  }
}

// A ball's centre inside a box, turned and moved, at scales from 1e-100 to 1e100: anywhere, at the
// box's centre, at equal depths below two or three faces, and just below a face. The closed form
// answers (one iteration, where the search takes several) with the depth below the nearest face,
// both bounds proven.
TEST(CoreClosedForm, BallCentresInsideBoxesHaveTheirDepth) {
  Random rng(71);
  for (Scalar scale : {1e-100, 1e-20, 1.0, 1e20, 1e100}) {
    const Vector3 half = Vector3(1, 0.5, 2) * scale;
    const Box box(half);
    for (int trial = 0; trial < 24; ++trial) {
      SCOPED_TRACE(::testing::Message() << "scale " << scale << " trial " << trial);
      const Sphere ball(rng.uniform(0.05, 1) * scale);
      const Pose pose_box =
          at(rng.vector(1) * scale, trial % 4 == 0 ? Matrix3::Identity() : rng.rotation());
      Vector3 local = Vector3(rng.uniform(), rng.uniform(), rng.uniform()).cwiseProduct(half);
      switch (trial % 6) {
        case 1:  // the box's centre
          local = Vector3::Zero();
          break;
        case 2:  // as deep below the two smaller faces
          local = Vector3(0.75, 0.25, rng.uniform()) * scale;
          break;
        case 3:  // as deep below all three (0.25 each)
          local = Vector3(0.75, -0.25, 1.75) * scale;
          break;
        case 4:  // 1e-6 of the box below a face
          local(trial / 6 % 3) = (1 - 1e-6) * half(trial / 6 % 3);
          break;
        default:
          break;
      }
      const Pose pose_ball = at(pose_box.rotation * local + pose_box.translation);
      const Long expected = inside_box(half, pose_box, pose_ball.translation, ball.radius());
      ASSERT_FALSE(std::isnan(double(expected)));
      expect_inside_closed_form(box, pose_box, ball, pose_ball, expected);
    }
  }
  // A centre exactly on a face, an edge or a corner has no depth to prove: the search answers.
  const Box box(Vector3(1, 0.5, 2));
  const Sphere ball(0.25);
  for (const Vector3& centre : {Vector3(1, 0, 0), Vector3(0.5, -0.5, 2), Vector3(-1, 0.5, -2)}) {
    SCOPED_TRACE(::testing::Message() << centre.transpose());
    for (bool swapped : {false, true}) {
      const DistanceResult s = swapped ? Query().signed_distance(ball, at(centre), box, {})
                                       : Query().signed_distance(box, {}, ball, at(centre));
      EXPECT_TRUE(s.certified);
      EXPECT_NEAR(s.distance, -0.25, 1e-9 * 5);
      EXPECT_LE(s.lower_bound, -0.25 + 1e-13);
    }
  }
  // Inside, a distance and a collision are the searches' (they prove the overlap).
  const Pose inside = at(Vector3(0.2, 0.1, -0.3));
  const DistanceResult d = Query().distance(box, {}, ball, inside);
  EXPECT_TRUE(d.certified);
  EXPECT_EQ(d.distance, 0);
  EXPECT_TRUE(Query().collide(ball, inside, box, {}));
}

// A box given as eight points in another order than a Box's (its corners read one by one): the
// closed form answers a centre inside, apart beside a face, an edge and a corner, each witness on
// the box as the weights make it.
TEST(CoreClosedForm, BoxesOfPointsInAnyOrder) {
  VertexMatrix corners(8, 3);
  const int order[8] = {5, 2, 7, 0, 3, 6, 1, 4};
  const Vector3 half(0.5, 1, 0.25);
  for (int i = 0; i < 8; ++i) {
    for (int k = 0; k < 3; ++k) corners(i, k) = (order[i] >> k) & 1 ? half(k) : -half(k);
  }
  const ConvexPolyhedron box(corners);
  Random rng(73);
  const Pose pose_box = at(Vector3(3, -2, 1), rng.rotation());
  const Sphere ball(0.125);
  const Vector3 inside(0.25, -0.5, 0.125);
  const Pose pose_inside = at(pose_box.rotation * inside + pose_box.translation);
  expect_inside_closed_form(box, pose_box, ball, pose_inside,
                            inside_box(half, pose_box, pose_inside.translation, ball.radius()));
  for (const Vector3& beside : {Vector3(0.25, 2, 0.125), Vector3(1, 2, 0), Vector3(1, -2, 1)}) {
    SCOPED_TRACE(::testing::Message() << beside.transpose());
    const Pose pose_ball = at(pose_box.rotation * beside + pose_box.translation);
    const Scalar expected = (beside.cwiseAbs() - half).cwiseMax(0.0).norm() - ball.radius();
    expect_closed_form(box, pose_box, ball, pose_ball, expected,
                       size_of(box, pose_box, ball, pose_ball));
    const DistanceResult r = Query().signed_distance(box, pose_box, ball, pose_ball);
    EXPECT_LE((r.point_a - from_weights(box, pose_box, r.weights_a)).norm(), 1e-12);
  }
}

// Eight points that are not a box's corners (a Box's with its first corner moved in) are never
// read as a box: the reading is kept with the body (core_closed_form.cpp's box_corners), and at
// every query it says so; the search answers, beside a face the moved corner is not on, with the
// box's distance. The Box beside it is read as one at every query too.
TEST(CoreClosedForm, EightPointsOfNoBoxAreSearchedAtEveryQuery) {
  const Box box(Vector3(0.5, 1, 0.25));
  VertexMatrix points = box.vertices();
  points.row(0) << -0.4, -0.9, -0.2;
  const ConvexPolyhedron dented(points);
  const Sphere ball(0.125);
  Random rng(79);
  const Pose pose = at(Vector3(3, -2, 1), rng.rotation());
  const Pose beside = at(pose.rotation * Vector3(2, 0.25, 0) + pose.translation);
  for (int asked = 0; asked < 2; ++asked) {
    const DistanceResult searched = Query().signed_distance(dented, pose, ball, beside);
    EXPECT_TRUE(searched.certified);
    EXPECT_NEAR(searched.distance, 1.5 - 0.125, 1e-9);
    const DistanceResult read = Query().signed_distance(box, pose, ball, beside);
    EXPECT_TRUE(read.certified);
    EXPECT_EQ(read.iterations, 1);
    EXPECT_NEAR(read.distance, 1.5 - 0.125, 1e-9);
  }
}

}  // namespace
}  // namespace swarmcollide::testing
