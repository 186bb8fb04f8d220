// Time of impact: constructed motions with known first contacts, at every scale.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

#include "shapes.hpp"
#include "swarmcollide/geometry/shapes.hpp"
#include "swarmcollide/motion/time_of_impact.hpp"

namespace swarmcollide {
namespace {

using testing::at;

Matrix3 turn_z(Scalar angle) {
  return Eigen::AngleAxis<Scalar>(angle, Vector3::UnitZ()).toRotationMatrix();
}

RigidMotion slide(const Vector3& from, const Vector3& to) { return {at(from), at(to)}; }

RigidMotion still(const Vector3& where = Vector3::Zero()) { return slide(where, where); }

TimeOfImpactOptions with_tolerance(Scalar tolerance) {
  TimeOfImpactOptions options;
  options.query.tolerance = tolerance;
  return options;
}

// The sum of the bodies' bounding-ball diameters: the motion's size.
Scalar size_of(const ConvexPolyhedron& a, const ConvexPolyhedron& b) {
  return 2 * (a.bounds().radius + b.bounds().radius);
}

TEST(RigidMotion, InterpolatesTranslationAndTurnsAboutAFixedAxis) {
  const RigidMotion motion(at(Vector3(1, 2, 3)), at(Vector3(3, 2, 1), turn_z(1.2)));
  EXPECT_NEAR(motion.angle(), 1.2, 1e-15);
  const Pose half = motion.at(0.5);
  EXPECT_TRUE(half.translation.isApprox(Vector3(2, 2, 2), 1e-15));
  EXPECT_TRUE(half.rotation.isApprox(turn_z(0.6), 1e-15));
  EXPECT_TRUE(motion.at(1).rotation.isApprox(turn_z(1.2), 1e-15));
  // A half turn, and a turn about a tilted axis from a turned start: the end is reached.
  const Matrix3 start = Eigen::AngleAxis<Scalar>(0.7, Vector3(1, 2, 3).normalized()).matrix();
  const Matrix3 end =
      start * Eigen::AngleAxis<Scalar>(M_PI, Vector3(0, 1, 1).normalized()).matrix();
  const RigidMotion half_turn(at(Vector3::Zero(), start), at(Vector3::Zero(), end));
  EXPECT_NEAR(half_turn.angle(), M_PI, 1e-12);
  EXPECT_LT((half_turn.at(1).rotation - end).norm(), 1e-14);
}

TEST(RigidMotion, ScrewTurnsAboutAFixedAxisWhileSlidingAlongIt) {
  // A screw about the vertical line through (1, 0, 0): a turn by 1.2 and a slide of 0.5 up. The
  // origin stays 1 from the axis, on a helix.
  const Vector3 axis_point(1, 0, 0);
  const auto screw_at = [&](Scalar t) {
    Pose pose;
    pose.rotation = turn_z(1.2 * t);
    pose.translation = axis_point - pose.rotation * axis_point + Vector3(0, 0, 0.5 * t);
    return pose;
  };
  const RigidMotion motion(Pose{}, screw_at(1), MotionKind::screw);
  EXPECT_EQ(motion.kind(), MotionKind::screw);
  EXPECT_TRUE(motion.twist_translation().isApprox(Vector3(0, -1.2, 0.5), 1e-14));
  for (const Scalar t : {0.0, 0.25, 0.5, 0.9, 1.0}) {
    const Pose pose = motion.at(t);
    const Pose exact = screw_at(t);
    EXPECT_LT((pose.translation - exact.translation).norm(), 1e-15) << t;
    EXPECT_LT((pose.rotation - exact.rotation).norm(), 1e-15) << t;
  }
  // The same ends moved linearly: the origin on the chord, not the helix.
  const RigidMotion linear(Pose{}, screw_at(1));
  EXPECT_EQ(linear.kind(), MotionKind::linear);
  EXPECT_TRUE(linear.at(0.5).translation.isApprox(screw_at(1).translation / 2, 1e-15));
  EXPECT_GT((linear.at(0.5).translation - screw_at(0.5).translation).norm(), 0.1);
  // From a turned and moved start, a half turn: the end is reached.
  const Matrix3 start = Eigen::AngleAxis<Scalar>(0.7, Vector3(1, 2, 3).normalized()).matrix();
  const Matrix3 end =
      start * Eigen::AngleAxis<Scalar>(M_PI, Vector3(0, 1, 1).normalized()).matrix();
  const RigidMotion half_turn(at(Vector3(1, -2, 3), start), at(Vector3(-4, 5, 2), end),
                              MotionKind::screw);
  EXPECT_LT((half_turn.at(1).translation - Vector3(-4, 5, 2)).norm(), 1e-13);
  EXPECT_LT((half_turn.at(1).rotation - end).norm(), 1e-14);
  EXPECT_EQ(motion_kind_from_name("screw"), MotionKind::screw);
  EXPECT_THROW(motion_kind_from_name("helix"), std::invalid_argument);
}

TEST(RigidMotion, ShiftedIsTheMotionOfTheShiftedPosesBitForBit) {
  const Matrix3 start = Eigen::AngleAxis<Scalar>(0.7, Vector3(1, 2, 3).normalized()).matrix();
  const Matrix3 end = start * Eigen::AngleAxis<Scalar>(2.1, Vector3(0, 1, 1).normalized()).matrix();
  const Vector3 shift(-1.25, 3.5e3, 1e-7);
  for (const MotionKind kind : {MotionKind::linear, MotionKind::screw}) {
    const Pose from = at(Vector3(1, -2, 3), start);
    const Pose to = at(Vector3(-4, 5, 2), end);
    const RigidMotion moved = RigidMotion(from, to, kind).shifted(shift);
    const RigidMotion built(at(from.translation + shift, start), at(to.translation + shift, end),
                            kind);
    EXPECT_EQ(moved.kind(), kind);
    EXPECT_EQ(moved.start().translation, built.start().translation);
    EXPECT_EQ(moved.end().translation, built.end().translation);
    EXPECT_EQ(moved.rotation_vector(), built.rotation_vector());
    EXPECT_EQ(moved.twist_translation(), built.twist_translation());
    EXPECT_EQ(moved.start_rotation_norm(), built.start_rotation_norm());
    for (const Scalar t : {0.0, 0.3, 1.0}) {
      EXPECT_EQ(moved.at(t).translation, built.at(t).translation) << t;
      EXPECT_EQ(moved.at(t).rotation, built.at(t).rotation) << t;
    }
  }
}

TEST(RigidMotion, RefusesPosesThatAreNotRigidOrFinite) {
  Pose scaled;
  scaled.rotation *= 1.01;
  EXPECT_THROW(RigidMotion(scaled, Pose{}, "pose_a"), std::invalid_argument);
  Pose nan;
  nan.translation(1) = std::nan("");
  EXPECT_THROW(RigidMotion(Pose{}, nan, "pose_b"), std::invalid_argument);
  try {
    RigidMotion(Pose{}, scaled, "pose_b");
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("pose_b end"), std::string::npos) << e.what();
  }
}

TEST(TimeOfImpact, RefusesOptionsItCannotProve) {
  const Box cube(Vector3::Constant(0.5));
  TimeOfImpactOptions options;
  options.time_tolerance = 0;
  EXPECT_THROW(time_of_impact(cube, still(), cube, still(Vector3(3, 0, 0)), options),
               std::invalid_argument);
  options = with_tolerance(0);
  EXPECT_THROW(time_of_impact(cube, still(), cube, still(Vector3(3, 0, 0)), options),
               std::invalid_argument);
  options = {};
  options.query.method = Method::ipso;
  EXPECT_THROW(time_of_impact(cube, still(), cube, still(Vector3(3, 0, 0)), options),
               std::invalid_argument);
}

// A cube crossing a plate 1e-3 thick in one step: neither end touches, the motion does.
TEST(TimeOfImpact, FindsACubeCrossingAThinPlateAtEveryScale) {
  for (const Scalar scale : {1e-100, 1e-6, 1e-3, 1.0, 1e3, 1e6, 1e100}) {
    const Box cube(Vector3::Constant(0.5 * scale));
    const Box plate(Vector3(5e-4, 5, 5) * scale);
    const TimeOfImpactOptions options;
    const TimeOfImpactResult r = time_of_impact(
        cube, slide(Vector3(-10 * scale, 0, 0), Vector3(10 * scale, 0, 0)), plate, still(),
        options);
    // The cube's face reaches the plate's at x = -5e-4 - 0.5: after 9.4995 of 20.
    const Scalar first = 9.4995 / 20;
    const Scalar within = options.query.tolerance * size_of(cube, plate) / (20 * scale);
    ASSERT_TRUE(r.touches) << scale;
    EXPECT_TRUE(r.certified) << scale;
    EXPECT_EQ(r.status, MotionStatus::converged);
    EXPECT_LE(r.t_lower, first * (1 + 1e-12)) << scale;
    EXPECT_GE(r.t_upper, first - within - 1e-12) << scale;
    EXPECT_LE(r.t_upper - r.t_lower, options.time_tolerance) << scale;
    EXPECT_NEAR(std::abs(r.normal.x()), 1, 1e-6) << scale;
    EXPECT_NEAR(r.pose_a.translation.x() / scale, -10 + 20 * r.t_upper, 1e-9) << scale;
    EXPECT_LE(r.distance, options.query.tolerance * size_of(cube, plate)) << scale;
  }
}

TEST(TimeOfImpact, FindsABarTurningIntoAPostAndPassesAShortOne) {
  const Box post(Vector3::Constant(0.05));
  const RigidMotion stays = still(Vector3(0, 1.5, 0));
  const RigidMotion turns(Pose{}, at(Vector3::Zero(), turn_z(0.9 * M_PI)));
  // The bar's leading face (0.1 from its axis) meets the post's corner (0.05, 1.45):
  // -0.05 sin(phi) + 1.45 cos(phi) = 0.1.
  Scalar low = 0, high = M_PI / 2;
  for (int k = 0; k < 200; ++k) {
    const Scalar mid = (low + high) / 2;
    (-0.05 * std::sin(mid) + 1.45 * std::cos(mid) > 0.1 ? low : high) = mid;
  }
  const Scalar first = low / (0.9 * M_PI);
  const Box bar(Vector3(2, 0.1, 0.1));
  const TimeOfImpactResult hit = time_of_impact(bar, turns, post, stays);
  ASSERT_TRUE(hit.touches);
  EXPECT_TRUE(hit.certified);
  EXPECT_LE(hit.t_lower, first + 1e-12);
  EXPECT_GE(hit.t_upper, first - 1e-6);
  EXPECT_LE(hit.t_upper - hit.t_lower, kDefaultTimeTolerance);

  const Box short_bar(Vector3(1.4, 0.1, 0.1));
  const TimeOfImpactResult miss = time_of_impact(short_bar, turns, post, stays);
  EXPECT_FALSE(miss.touches);
  EXPECT_TRUE(miss.certified);
  EXPECT_EQ(miss.t_lower, 1);
}

// A cube sliding past another, 1e-9 of the size apart or into it, at a tolerance of 1e-12.
TEST(TimeOfImpact, TellsGrazingMissesFromGrazingContacts) {
  for (const Scalar scale : {1e-6, 1.0, 1e6}) {
    const Box cube(Vector3::Constant(0.5 * scale));
    const Scalar size = size_of(cube, cube);
    for (const Scalar gap : {1e-9, -1e-9}) {
      const Scalar y = scale + gap * size;
      const TimeOfImpactResult r =
          time_of_impact(cube, slide(Vector3(-5 * scale, y, 0), Vector3(5 * scale, y, 0)), cube,
                         still(), with_tolerance(1e-12));
      EXPECT_TRUE(r.certified) << scale << " " << gap;
      EXPECT_EQ(r.touches, gap < 0) << scale << " " << gap;
      if (gap < 0) {
        // The faces overlap from x = -1: after 4 of 10.
        EXPECT_LE(r.t_lower, 0.4 + 1e-12);
        EXPECT_GE(r.t_upper, 0.4 - 1e-9);
      }
    }
  }
}

TEST(TimeOfImpact, AnswersBodiesStartingInContactAndBodiesThatDoNotMove) {
  const Box cube(Vector3::Constant(0.5));
  const TimeOfImpactResult start = time_of_impact(cube, slide(Vector3::Zero(), Vector3(5, 0, 0)),
                                                  cube, still(Vector3(0.9, 0, 0)));
  EXPECT_TRUE(start.touches && start.certified);
  EXPECT_EQ(start.t_lower, 0);
  EXPECT_EQ(start.t_upper, 0);
  EXPECT_EQ(start.iterations, 1);

  const TimeOfImpactResult apart = time_of_impact(cube, still(), cube, still(Vector3(3, 0, 0)));
  EXPECT_FALSE(apart.touches);
  EXPECT_TRUE(apart.certified);
  EXPECT_EQ(apart.iterations, 1);
}

TEST(TimeOfImpact, CurvedAndRoundedBodiesAndCompoundBodies) {
  const Sphere ball(0.5);
  const Cylinder cylinder(0.5, 1);
  // The ball falls onto the cylinder's cap (z = 1) from z = 5 to z = -5: contact when its centre
  // is at 1.5, after 3.5 of 10.
  const TimeOfImpactResult r =
      time_of_impact(ball, slide(Vector3(0, 0, 5), Vector3(0, 0, -5)), cylinder, still());
  ASSERT_TRUE(r.touches && r.certified);
  EXPECT_LE(r.t_lower, 0.35 + 1e-12);
  EXPECT_GE(r.t_upper, 0.35 - 1e-6);

  const CompoundBody pair(
      {Box(Vector3::Constant(0.5)), testing::moved(Box(Vector3::Constant(0.5)), Vector3(3, 0, 0))});
  const CompoundBody ball_body(ball);
  // The ball passes between the two cubes (gap 2 wide at x in [0.5, 2.5]), then hits the second.
  const TimeOfImpactResult between = time_of_impact(
      ball_body, slide(Vector3(1.5, -5, 0), Vector3(1.5, 5, 0)), pair, still());
  EXPECT_FALSE(between.touches);
  EXPECT_TRUE(between.certified);
  const TimeOfImpactResult into = time_of_impact(
      ball_body, slide(Vector3(-3, 0, 0), Vector3(1.5, 0, 0)), pair, still());
  ASSERT_TRUE(into.touches && into.certified);
  // Its centre reaches x = -1 after 2 of 4.5.
  EXPECT_LE(into.t_lower, 2 / 4.5 + 1e-12);
  EXPECT_GE(into.t_upper, 2 / 4.5 - 1e-6);
}

TEST(TimeOfImpact, BatchesAnswerAsSingleCallsOnAnyThreads) {
  const Box cube(Vector3::Constant(0.5));
  testing::Random random(7);
  std::vector<RigidMotion> motions;
  for (int i = 0; i < 40; ++i) {
    const Vector3 from(random.uniform(-4, 4), random.uniform(-4, 4), random.uniform(-4, 4));
    const Vector3 to(random.uniform(-4, 4), random.uniform(-4, 4), random.uniform(-4, 4));
    motions.emplace_back(at(from), at(to, turn_z(random.uniform(-3, 3))));
  }
  const std::vector<RigidMotion> fixed{still()};
  const auto one = time_of_impact_many(cube, motions, cube, fixed, {}, 1);
  const auto three = time_of_impact_many(cube, motions, cube, fixed, {}, 3);
  ASSERT_EQ(one.size(), motions.size());
  for (std::size_t i = 0; i < motions.size(); ++i) {
    const TimeOfImpactResult single = time_of_impact(cube, motions[i], cube, still());
    for (const auto* r : {&one[i], &three[i]}) {
      EXPECT_EQ(r->touches, single.touches);
      EXPECT_EQ(r->t_lower, single.t_lower);
      EXPECT_EQ(r->t_upper, single.t_upper);
      EXPECT_EQ(r->iterations, single.iterations);
    }
  }
  EXPECT_THROW(time_of_impact_many(cube, motions, cube, std::vector<RigidMotion>(3), {}, 1),
               std::invalid_argument);
  // No rows: no answers, as the other batches give.
  EXPECT_TRUE(time_of_impact_many(cube, {}, cube, fixed, {}, 1).empty());
  EXPECT_THROW(time_of_impact_many(cube, {}, cube, std::vector<RigidMotion>(2, still()), {}, 1),
               std::invalid_argument);
}

}  // namespace
}  // namespace swarmcollide
