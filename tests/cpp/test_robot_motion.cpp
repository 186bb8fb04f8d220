// Robot motions: the link motion bound (every point of a geometry moves no farther than its
// pair's speed bound allows, and a self pair's distance changes no faster than its bound, which
// leaves out the joints both chains share, as do its directional and twist bounds in the frame
// where the chains part), and robot_check_motion's bracket on a bar turning into a post, against
// the closed form (at several time tolerances and contact thresholds), also as a self pair
// carried by a turn both links share.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "robot/link_motion_bound.hpp"
#include "swarmcollide/geometry/shapes.hpp"
#include "swarmcollide/queries/query.hpp"
#include "swarmcollide/robot/kinematics.hpp"
#include "swarmcollide/robot/robot_model.hpp"
#include "swarmcollide/robot/robot_motion.hpp"

namespace swarmcollide::testing {
namespace {

Pose placed(const Vector3& translation, const Vector3& rotation_vector = Vector3::Zero()) {
  Pose pose;
  pose.translation = translation;
  if (rotation_vector.norm() > 0) {
    pose.rotation =
        Eigen::AngleAxis<Scalar>(rotation_vector.norm(), rotation_vector.normalized())
            .toRotationMatrix();
  }
  return pose;
}

// A spatial arm with tilted joint origins and axes: a turn, a shoulder, a slide, a fixed
// wrist, a mimic finger on the shoulder's link, and a box obstacle.
RobotModel spatial_arm() {
  std::vector<Link> links{{"base"}, {"l1"}, {"l2"}, {"l3"}, {"l4"}, {"l5"}};
  std::vector<Joint> joints(5);
  joints[0] = {"turn", JointType::revolute, 0, 1, placed({0, 0, 0.1}, {0.1, 0, 0}),
               Vector3(0, 0.2, 1), -2.5, 2.5, 0};
  joints[1] = {"shoulder", JointType::continuous, 1, 2, placed({0.05, 0, 0.3}, {0, 0.3, 0.2}),
               Vector3(0.1, 1, 0), 0, 0, 0.4};
  joints[2] = {"slide", JointType::prismatic, 2, 3, placed({0.4, 0.02, 0}, {0.2, 0, 0}),
               Vector3(1, 0.1, 0), -0.1, 0.3, 0.05};
  joints[3] = {"wrist", JointType::fixed, 3, 4, placed({0.1, 0, 0.03}, {0, 0, 0.5}),
               Vector3::UnitZ(), 0, 0, 0};
  joints[4] = {"finger", JointType::revolute, 2, 5, placed({0.2, 0, 0.05}), Vector3::UnitZ(),
               -5, 5, 0};
  joints[4].mimic = 0;
  joints[4].multiplier = -1.5;
  joints[4].offset = 0.2;
  std::vector<Geometry> geometries{
      {"base", 0, placed({0, 0, 0.05}), Box(Vector3(0.08, 0.08, 0.05)), std::nullopt},
      {"column", 1, placed({0.01, 0, 0.15}, {0.1, 0.1, 0}), Box(Vector3(0.04, 0.04, 0.1)),
       std::nullopt},
      {"upper", 2, placed({0.22, 0, 0}), Box(Vector3(0.22, 0.03, 0.03)), std::nullopt},
      {"carriage", 3, placed({0.02, 0.01, 0}), Box(Vector3(0.05, 0.05, 0.05), 0.01), std::nullopt},
      {"hand", 4, placed({0.08, 0, 0}, {0.3, 0, 0}), Box(Vector3(0.08, 0.04, 0.01)), std::nullopt},
      {"finger", 5, placed({0.1, 0, 0}), Box(Vector3(0.1, 0.01, 0.01)), std::nullopt},
      {"table", -1, placed({0, 0, -0.02}), Box(Vector3(0.6, 0.6, 0.01)), std::nullopt},
  };
  return RobotModel(links, joints, geometries);
}

// Geometry g's pose at the configuration q (its origin for one fixed in the world, link -1).
Pose geometry_pose(const RobotModel& model, const Eigen::RowVectorXd& q, int g) {
  const Geometry& geometry = model.geometries()[g];
  if (geometry.link < 0) return geometry.origin;
  std::vector<Pose> links;
  link_poses(model, q.data(), links);
  return compose(links[geometry.link], geometry.origin);
}

// Vertex x of a geometry at `pose`, in the coordinates of the frame `common`.
Vector3 in_frame(const Pose& common, const Pose& pose, const Vector3& x) {
  return common.rotation.transpose() * (pose.rotation * x + pose.translation - common.translation);
}

Eigen::RowVectorXd random_configuration(std::mt19937_64& rng) {
  std::uniform_real_distribution<Scalar> unit(0, 1);
  const Scalar lower[] = {-2.5, -M_PI, -0.1};
  const Scalar upper[] = {2.5, M_PI, 0.3};
  Eigen::RowVectorXd q(3);
  for (int d = 0; d < 3; ++d) q(d) = lower[d] + (upper[d] - lower[d]) * unit(rng);
  return q;
}

// A random motion of the arm, set on `bound`, and a random time s of it with its configuration
// and link poses.
struct TimeOfMotion {
  Eigen::RowVectorXd q0;
  Eigen::RowVectorXd q1;
  Scalar s;
  Eigen::RowVectorXd qs;
  std::vector<Pose> links;
};

TimeOfMotion random_time(const RobotModel& model, detail::LinkMotionBound& bound,
                         std::mt19937_64& rng) {
  std::uniform_real_distribution<Scalar> unit(0, 1);
  TimeOfMotion at;
  at.q0 = random_configuration(rng);
  at.q1 = random_configuration(rng);
  bound.set_motion(at.q0.data(), at.q1.data());
  at.s = unit(rng);
  at.qs = at.q0 + at.s * (at.q1 - at.q0);
  link_poses(model, at.qs.data(), at.links);
  return at;
}

// A second time t of the motion `at` to measure from at.s, either way from it: any time on even
// samples, within 0.01 of at.s on odd ones (where the bounds are tight); h = |t - at.s|, the
// configuration then, and link `common`'s pose then (the identity for -1, the world's frame).
struct OtherTime {
  Scalar t;
  Scalar h;
  Eigen::RowVectorXd q;
  Pose common;
};

OtherTime other_time(const RobotModel& model, const TimeOfMotion& at, int sample, int common,
                     std::mt19937_64& rng) {
  std::uniform_real_distribution<Scalar> unit(0, 1);
  OtherTime other;
  other.t = sample % 2 == 0 ? unit(rng) : at.s + (unit(rng) - 0.5) * 0.02;
  other.h = std::abs(other.t - at.s);
  other.q = at.q0 + other.t * (at.q1 - at.q0);
  if (common >= 0) {
    std::vector<Pose> links;
    link_poses(model, other.q.data(), links);
    other.common = links[common];
  }
  return other;
}

TEST(RobotMotion, EveryPointMovesNoFartherThanItsGeometrysBound) {
  const RobotModel arm = spatial_arm();
  ASSERT_EQ(arm.dof(), 3);  // the wrist is fixed, the finger mimics the turn
  detail::LinkMotionBound bound(arm);
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<Scalar> unit(0, 1);
  const int table = 6;
  Scalar tightest = 0;
  for (int motion = 0; motion < 200; ++motion) {
    const Eigen::RowVectorXd q0 = random_configuration(rng);
    // Short and long motions: the bound is linear in the joints' changes.
    const Eigen::RowVectorXd q1 =
        q0 + (random_configuration(rng) - q0) * (motion % 2 == 0 ? 1.0 : 0.01);
    bound.set_motion(q0.data(), q1.data());
    for (int sample = 0; sample < 10; ++sample) {
      Scalar s = unit(rng);
      Scalar t = unit(rng);
      if (s > t) std::swap(s, t);
      const Eigen::RowVectorXd qs = q0 + s * (q1 - q0);
      const Eigen::RowVectorXd qt = q0 + t * (q1 - q0);
      for (int g = 0; g < table; ++g) {
        // Against the still table, the pair's bound is the geometry's own.
        const Scalar allowed = bound.pair_speed({g, table}) * (t - s);
        const Pose from = geometry_pose(arm, qs, g);
        const Pose to = geometry_pose(arm, qt, g);
        const VertexMatrix& vertices = arm.geometries()[g].body.vertices();
        for (int v = 0; v < vertices.rows(); ++v) {
          const Vector3 x = vertices.row(v).transpose();
          const Scalar moved =
              ((to.rotation * x + to.translation) - (from.rotation * x + from.translation)).norm();
          ASSERT_LE(moved, allowed * (1 + 1e-12) + 1e-15)
              << "geometry " << g << ", motion " << motion;
          if (allowed > 0) tightest = std::max(tightest, moved / allowed);
        }
      }
    }
  }
  // The bound is not vacuous: some point moves by more than a third of it.
  EXPECT_GT(tightest, 0.33);
}

TEST(RobotMotion, PointsMoveNoFartherThanTheLocalBoundAroundAConfiguration) {
  const RobotModel arm = spatial_arm();
  detail::LinkMotionBound bound(arm);
  std::mt19937_64 rng(9);
  const int table = 6;
  Scalar tightest = 0;
  for (int motion = 0; motion < 200; ++motion) {
    const TimeOfMotion at = random_time(arm, bound, rng);
    for (int sample = 0; sample < 10; ++sample) {
      const OtherTime other = other_time(arm, at, sample, -1, rng);
      const Scalar h = other.h;
      const Eigen::RowVectorXd& qt = other.q;
      for (int g = 0; g < table; ++g) {
        const Pose from = geometry_pose(arm, at.qs, g);
        const Pose to = geometry_pose(arm, qt, g);
        const auto local =
            bound.local_speed({g, table}, at.links, from, arm.geometries()[table].origin);
        const Scalar allowed = local.at * h + local.growth * h * h / 2;
        const VertexMatrix& vertices = arm.geometries()[g].body.vertices();
        for (int v = 0; v < vertices.rows(); ++v) {
          const Vector3 x = vertices.row(v).transpose();
          const Scalar moved =
              ((to.rotation * x + to.translation) - (from.rotation * x + from.translation)).norm();
          ASSERT_LE(moved, allowed * (1 + 1e-12) + 1e-15) << "geometry " << g;
          if (allowed > 0 && h < 0.02) tightest = std::max(tightest, moved / allowed);
        }
      }
    }
  }
  // Over short times the local bound is close: some point moves by more than half of it.
  EXPECT_GT(tightest, 0.5);
}

TEST(RobotMotion, PointsMoveAlongADirectionNoFartherThanTheDirectionalBound) {
  const RobotModel arm = spatial_arm();
  detail::LinkMotionBound bound(arm);
  std::mt19937_64 rng(13);
  std::normal_distribution<Scalar> normal;
  const int table = 6;
  Scalar tightest = 0;
  for (int motion = 0; motion < 200; ++motion) {
    const TimeOfMotion at = random_time(arm, bound, rng);
    // Vertical (the table's normal: the turn about z moves nothing along it) and random.
    const Vector3 n = motion % 2 == 0 ? Vector3::UnitZ()
                                      : Vector3(normal(rng), normal(rng), normal(rng)).normalized();
    for (int sample = 0; sample < 10; ++sample) {
      const OtherTime other = other_time(arm, at, sample, -1, rng);
      const Scalar h = other.h;
      const Eigen::RowVectorXd& qt = other.q;
      for (int g = 0; g < table; ++g) {
        const Pose from = geometry_pose(arm, at.qs, g);
        const Pose to = geometry_pose(arm, qt, g);
        const auto speed = bound.directional_speed({g, table}, n, at.links, from,
                                                   arm.geometries()[table].origin);
        const Scalar allowed =
            h * (speed.linear + h * (speed.quadratic / 2 + h * speed.cubic / 3));
        const VertexMatrix& vertices = arm.geometries()[g].body.vertices();
        for (int v = 0; v < vertices.rows(); ++v) {
          const Vector3 x = vertices.row(v).transpose();
          const Scalar moved =
              std::abs(n.dot((to.rotation * x + to.translation) - (from.rotation * x + from.translation)));
          ASSERT_LE(moved, allowed * (1 + 1e-12) + 1e-15) << "geometry " << g;
          if (allowed > 0 && h < 0.02) tightest = std::max(tightest, moved / allowed);
        }
      }
    }
  }
  EXPECT_GT(tightest, 0.3);
}

TEST(RobotMotion, SelfPairsMoveAlongADirectionTurningWithTheirCommonFrameWithinTheBound) {
  const RobotModel arm = spatial_arm();
  detail::LinkMotionBound bound(arm);
  std::mt19937_64 rng(17);
  std::normal_distribution<Scalar> normal;
  // Pairs whose chains share joints, with the links where they part: upper and finger part at
  // the shoulder's link, carriage and finger too, column and hand at the turn's link; base and
  // hand share none (the world's frame).
  const GeometryPair pairs[] = {{2, 5}, {3, 5}, {1, 4}, {0, 4}};
  const int commons[] = {2, 2, 1, -1};
  for (int p = 0; p < 4; ++p) EXPECT_EQ(bound.common_link(pairs[p]), commons[p]);
  Scalar tightest = 0;
  for (int motion = 0; motion < 200; ++motion) {
    const TimeOfMotion at = random_time(arm, bound, rng);
    const Vector3 n = Vector3(normal(rng), normal(rng), normal(rng)).normalized();
    for (int p = 0; p < 4; ++p) {
      const GeometryPair& pair = pairs[p];
      const Pose common_s = commons[p] < 0 ? Pose{} : at.links[commons[p]];
      const auto speed = bound.directional_speed(
          pair, n, at.links, geometry_pose(arm, at.qs, pair.a), geometry_pose(arm, at.qs, pair.b));
      EXPECT_EQ(speed.loss > 0, commons[p] >= 0);
      EXPECT_LT(speed.loss, 1e-12);
      // The direction in the common frame's coordinates.
      const Vector3 m = common_s.rotation.transpose() * n;
      for (int sample = 0; sample < 10; ++sample) {
        const OtherTime other = other_time(arm, at, sample, commons[p], rng);
        const Scalar h = other.h;
        const Eigen::RowVectorXd& qt = other.q;
        const Pose& common_t = other.common;
        const Scalar allowed =
            h * (speed.linear + h * (speed.quadratic / 2 + h * speed.cubic / 3));
        // Each body's points move along m, in the common frame, by at most its share: the
        // farthest moving point of each, together, within the bound.
        Scalar moved = 0;
        for (const int g : {pair.a, pair.b}) {
          const Pose from = geometry_pose(arm, at.qs, g);
          const Pose to = geometry_pose(arm, qt, g);
          const VertexMatrix& vertices = arm.geometries()[g].body.vertices();
          Scalar most = 0;
          for (int v = 0; v < vertices.rows(); ++v) {
            const Vector3 x = vertices.row(v).transpose();
            most = std::max(
                most, std::abs(m.dot(in_frame(common_t, to, x) - in_frame(common_s, from, x))));
          }
          moved += most;
        }
        ASSERT_LE(moved, allowed * (1 + 1e-12) + 1e-15) << "pair " << p << ", motion " << motion;
        if (allowed > 0 && h < 0.02) tightest = std::max(tightest, moved / allowed);
      }
    }
  }
  EXPECT_GT(tightest, 0.3);
}

TEST(RobotMotion, SeparationsAlongADirectionCloseNoFasterThanTheTwistBoundEitherWay) {
  const RobotModel arm = spatial_arm();
  detail::LinkMotionBound bound(arm);
  std::mt19937_64 rng(19);
  std::normal_distribution<Scalar> normal;
  // Self pairs measured in the frame where their chains part, and links against the table.
  const GeometryPair pairs[] = {{2, 5}, {3, 5}, {1, 4}, {0, 4}, {2, 6}, {4, 6}, {5, 6}, {3, 6}};
  Scalar tightest = 0;
  for (int motion = 0; motion < 200; ++motion) {
    const TimeOfMotion at = random_time(arm, bound, rng);
    const Vector3 n = Vector3(normal(rng), normal(rng), normal(rng)).normalized();
    for (const GeometryPair& pair : pairs) {
      const int common = bound.common_link(pair);
      const Pose common_s = common < 0 ? Pose{} : at.links[common];
      detail::LinkMotionBound::PlacedChain chain_a;
      detail::LinkMotionBound::PlacedChain chain_b;
      bound.place_chain(pair.a, at.links, geometry_pose(arm, at.qs, pair.a), chain_a);
      bound.place_chain(pair.b, at.links, geometry_pose(arm, at.qs, pair.b), chain_b);
      const auto twist = bound.twist_speed(pair, n, chain_a, chain_b);
      // The direction in the common frame's coordinates.
      const Vector3 m = common_s.rotation.transpose() * n;
      for (int sample = 0; sample < 10; ++sample) {
        const OtherTime other = other_time(arm, at, sample, common, rng);
        const Scalar h = other.h;
        const Eigen::RowVectorXd& qt = other.q;
        const Pose& common_t = other.common;
        const Scalar rate = other.t > at.s ? twist.forward : twist.backward;
        const Scalar allowed =
            h * (rate + h * (twist.a0 / 2 + h * (twist.a1 / 6 + h * twist.a2 / 12)));
        // How far the separation of any point of A and any of B along m shrank: A's points
        // moving along m the most, B's the least (the motions are affine in the points, so
        // vertices attain both).
        Scalar most_a = -1e300;
        Scalar least_b = 1e300;
        for (const int g : {pair.a, pair.b}) {
          const Pose from = geometry_pose(arm, at.qs, g);
          const Pose to = geometry_pose(arm, qt, g);
          const VertexMatrix& vertices = arm.geometries()[g].body.vertices();
          for (int v = 0; v < vertices.rows(); ++v) {
            const Vector3 x = vertices.row(v).transpose();
            const Scalar moved = m.dot(in_frame(common_t, to, x) - in_frame(common_s, from, x));
            if (g == pair.a) most_a = std::max(most_a, moved);
            if (g == pair.b) least_b = std::min(least_b, moved);
          }
        }
        const Scalar closed = most_a - least_b;
        ASSERT_LE(closed, allowed + 1e-12 * std::abs(allowed) + 1e-15)
            << "pair " << pair.a << "-" << pair.b << ", motion " << motion << ", h " << h;
        if (allowed > 0 && h < 0.02) tightest = std::max(tightest, closed / allowed);
      }
    }
  }
  // Over short times the bound is close (box corners lie on their balls): some pair closes by
  // more than half of it (0.9999 on these draws).
  EXPECT_GT(tightest, 0.5) << tightest;
}

void expect_same_chain(const detail::LinkMotionBound::PlacedChain& x,
                       const detail::LinkMotionBound::PlacedChain& y, std::size_t length,
                       int g) {
  for (std::size_t k = 0; k < length; ++k) {
    EXPECT_EQ(x.axis[k], y.axis[k]) << "geometry " << g << ", joint " << k;
    EXPECT_EQ(x.reach[k], y.reach[k]) << "geometry " << g << ", joint " << k;
    EXPECT_EQ(x.origin[k], y.origin[k]) << "geometry " << g << ", joint " << k;
  }
  EXPECT_EQ(x.centre, y.centre) << g;
  EXPECT_EQ(x.radius, y.radius) << g;
}

TEST(RobotMotion, TheEndChainsAreTheChainsPlacedAtTheMotionsEndsBitForBit) {
  // robot_check_motion places every geometry's chain at the two ends from set_motion's axes, and
  // the sampled pairs' chains into one PlacedChain whatever chain was placed in it before.
  const RobotModel arm = spatial_arm();
  detail::LinkMotionBound bound(arm);
  std::mt19937_64 rng(23);
  // Chain lengths 0 (base) to 3 (carriage, hand), placed longest first and shortest last.
  const int order[] = {4, 3, 5, 2, 1, 0};
  for (int motion = 0; motion < 50; ++motion) {
    const Eigen::RowVectorXd q0 = random_configuration(rng);
    const Eigen::RowVectorXd q1 = random_configuration(rng);
    bound.set_motion(q0.data(), q1.data());
    detail::LinkMotionBound::PlacedChain reused;
    for (int end = 0; end < 2; ++end) {
      const Eigen::RowVectorXd& q = end == 0 ? q0 : q1;
      std::vector<Pose> links;
      link_poses(arm, q.data(), links);
      for (const int g : order) {
        const Pose pose = geometry_pose(arm, q, g);
        const std::size_t length = bound.shared_count({g, g});
        detail::LinkMotionBound::PlacedChain fresh;
        bound.place_chain(g, links, pose, fresh);
        detail::LinkMotionBound::PlacedChain at_end;
        bound.place_end_chain(g, end, links, pose, at_end);
        expect_same_chain(fresh, at_end, length, g);
        bound.place_chain(g, links, pose, reused);
        expect_same_chain(fresh, reused, length, g);
      }
    }
  }
}

TEST(RobotMotion, SelfPairDistancesChangeNoFasterThanTheirBound) {
  const RobotModel arm = spatial_arm();
  detail::LinkMotionBound bound(arm);
  QueryOptions options;
  options.method = Method::exact;
  options.tolerance = 1e-12;
  const Query query(options);
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<Scalar> unit(0, 1);
  // Pairs whose chains share joints: upper and finger share the turn and the shoulder's link's
  // chain; carriage and finger share the turn and the shoulder; column and hand the turn.
  const GeometryPair pairs[] = {{2, 5}, {3, 5}, {1, 4}, {0, 4}};
  for (int motion = 0; motion < 100; ++motion) {
    const Eigen::RowVectorXd q0 = random_configuration(rng);
    const Eigen::RowVectorXd q1 = random_configuration(rng);
    bound.set_motion(q0.data(), q1.data());
    for (const GeometryPair& pair : pairs) {
      Scalar s = unit(rng);
      Scalar t = unit(rng);
      if (s > t) std::swap(s, t);
      const auto distance = [&](Scalar time) {
        const Eigen::RowVectorXd q = q0 + time * (q1 - q0);
        return query.signed_distance(arm.geometries()[pair.a].body,
                                     geometry_pose(arm, q, pair.a),
                                     arm.geometries()[pair.b].body,
                                     geometry_pose(arm, q, pair.b));
      };
      const DistanceResult at_s = distance(s);
      const DistanceResult at_t = distance(t);
      ASSERT_TRUE(at_s.certified && at_t.certified);
      // Both answers are within their bounds' width of the true distances.
      const Scalar slack = (at_s.distance - at_s.lower_bound) + (at_t.distance - at_t.lower_bound);
      EXPECT_LE(std::abs(at_t.distance - at_s.distance),
                bound.pair_speed(pair) * (t - s) + slack + 1e-15)
          << "pair " << pair.a << "-" << pair.b << ", motion " << motion;
    }
  }
}

TEST(RobotMotion, ARoundedBallTurningAboutItsCentreDoesNotMove) {
  std::vector<Link> links{{"base"}, {"ball"}};
  std::vector<Joint> joints{{"turn", JointType::revolute, 0, 1, Pose{}, Vector3::UnitZ(), -3, 3,
                             0}};
  std::vector<Geometry> geometries{{"ball", 1, Pose{}, Sphere(0.5), std::nullopt},
                                   {"bar", 1, placed({0.5, 0, 0}), Box(Vector3(0.5, 0.1, 0.1)),
                                    std::nullopt},
                                   {"wall", -1, placed({3, 0, 0}), Box(Vector3::Constant(1)),
                                    std::nullopt}};
  const RobotModel model(links, joints, geometries);
  detail::LinkMotionBound bound(model);
  const Scalar q0 = -1;
  const Scalar q1 = 1;
  bound.set_motion(&q0, &q1);
  EXPECT_EQ(bound.pair_speed({0, 2}), 0);
  // The bar's far edges are sqrt(1 + 0.01) off the axis: times the 2 radians turned.
  EXPECT_NEAR(bound.pair_speed({1, 2}), 2 * std::sqrt(1.01), 1e-12);
}

TEST(RobotMotion, ALinkFoldedOntoAnAxisIsBoundedByItsMeasuredDistanceFromIt) {
  // A box at the end of an arm 1 long folded back onto the base's axis: the chain bounds the
  // box's distance from that axis by the arm's length, the box's corners at the two ends of a
  // turn of the base alone by its half diagonal across the axis.
  std::vector<Link> links{{"base"}, {"arm"}, {"forearm"}};
  std::vector<Joint> joints{
      {"turn", JointType::revolute, 0, 1, Pose{}, Vector3::UnitZ(), -3, 3, 0},
      {"elbow", JointType::revolute, 1, 2, placed({1, 0, 0}), Vector3::UnitZ(), -3, 3, 0}};
  std::vector<Geometry> geometries{
      {"box", 2, placed({-1, 0, 0}), Box(Vector3::Constant(0.1)), std::nullopt},
      {"wall", -1, placed({3, 0, 0}), Box(Vector3::Constant(1)), std::nullopt}};
  const RobotModel model(links, joints, geometries);
  detail::LinkMotionBound bound(model);
  const Scalar q0[] = {0, 0};
  const Scalar q1[] = {1, 0};
  bound.set_motion(q0, q1);
  EXPECT_NEAR(bound.pair_speed({0, 1}), std::sqrt(0.02), 1e-12);
  // The chain's bound, 1 + hypot(1.1, 0.1), still holds when the elbow turns too.
  const Scalar q2[] = {1, 0.5};
  bound.set_motion(q0, q2);
  const Scalar elbow = 0.5 * std::hypot(1.1, 0.1);
  EXPECT_LT(bound.pair_speed({0, 1}), 1 + 2 * elbow);
}

TEST(RobotMotion, TheKinematicsOfAPairsChainsEqualTheWholeKinematicsThere) {
  // robot_check_motion places a pair from the joints above its two links alone.
  const RobotModel arm = spatial_arm();
  std::mt19937_64 rng(5);
  for (int trial = 0; trial < 50; ++trial) {
    const Eigen::RowVectorXd q = random_configuration(rng);
    std::vector<Pose> whole;
    link_poses(arm, q.data(), whole);
    // The finger's chain (turn, finger) and the carriage's (turn, shoulder, slide), in order.
    const std::vector<int> joints{0, 1, 2, 4};
    std::vector<Pose> some(arm.links().size());
    link_poses(arm, q.data(), joints, some);
    for (int link : {0, 1, 2, 3, 5}) {
      EXPECT_EQ(some[link].rotation, whole[link].rotation) << link;
      EXPECT_EQ(some[link].translation, whole[link].translation) << link;
    }
    // The wrist's link (below the fixed joint 3, not asked) is left as it was.
    EXPECT_EQ(some[4].rotation, Matrix3::Identity());
    EXPECT_EQ(some[4].translation, Vector3::Zero());
  }
}

// Motion 0 of `check`, a bar from the axis to x = 1, 0.02 thick, turning 2 rad into a post 0.02
// wide at (0, 0.6), bracketed at the closed-form contact.
void expect_bar_contact_bracketed(const RobotMotionCheck& check,
                                  const TimeOfImpactOptions& options) {
  // The bar's leading face (y = 0.01 in its frame) meets the post's corner (0.01, 0.59).
  const Scalar corner = std::atan2(0.59, 0.01);
  const Scalar reach = std::sqrt(0.59 * 0.59 + 0.01 * 0.01);
  const Scalar contact = (corner - std::asin(0.01 / reach)) / 2;
  EXPECT_TRUE(check.touches(0));
  EXPECT_LE(check.t_lower(0), contact);
  // Within the tolerance of contact, a few 1e-9 of the motion early at most: the bar's corner
  // closes at 2 x 0.59 per unit time, the contact threshold is tolerance x (sum of the balls'
  // diameters, below 4).
  const Scalar early = options.query.tolerance * 4 / (2 * 0.58);
  EXPECT_GE(check.t_upper(0), contact - early);
  EXPECT_LE(check.t_upper(0) - check.t_lower(0), options.time_tolerance);
}

// A bar from the axis of a turn about z to x = 1, 0.02 thick; a post 0.02 wide at (0, 0.6).
RobotModel bar_and_post() {
  std::vector<Link> links{{"base"}, {"arm"}};
  std::vector<Joint> joints{{"turn", JointType::revolute, 0, 1, Pose{}, Vector3::UnitZ(), -3, 3,
                             0}};
  std::vector<Geometry> geometries{
      {"bar", 1, placed({0.5, 0, 0}), Box(Vector3(0.5, 0.01, 0.01)), std::nullopt},
      {"post", -1, placed({0, 0.6, 0}), Box(Vector3(0.01, 0.01, 1)), std::nullopt}};
  return RobotModel(links, joints, geometries);
}

TEST(RobotMotion, ABarTurningIntoAPostIsBracketedAtTheClosedForm) {
  const RobotModel model = bar_and_post();
  Configurations q0(2, 1);
  Configurations q1(2, 1);
  q0 << 0, 0;
  q1 << 2, 1;
  TimeOfImpactOptions options;
  options.time_tolerance = 1e-9;
  for (int threads : {1, 2}) {
    const RobotMotionCheck check =
        robot_check_motion(model, {{0, 1}}, q0, q1, options, BatchSettings{threads});
    ASSERT_TRUE(check.certified(0) && check.certified(1));
    expect_bar_contact_bracketed(check, options);
    EXPECT_EQ(check.pair(0), 0);
    EXPECT_NEAR(check.configuration(0, 0), 2 * check.t_upper(0), 1e-15);
    // Turning to 1 rad stops short of the post.
    EXPECT_FALSE(check.touches(1));
    EXPECT_EQ(check.pair(1), -1);
    EXPECT_EQ(check.status[1], MotionStatus::converged);
  }
}

TEST(RobotMotion, ABarTurningIntoAPostIsBracketedAtEveryTimeTolerance) {
  // Where the steps fall below the time tolerance with a contact sampled ahead, the bracket is
  // closed by a sample one tolerance ahead (or the interval split): at every width and contact
  // threshold the bracket must hold the closed form's contact (at 1e-3 the sample ahead closes
  // it, one tolerance wide, where splitting gave half of one).
  const RobotModel model = bar_and_post();
  Configurations q0(1, 1);
  Configurations q1(1, 1);
  q0 << 0;
  q1 << 2;
  for (const Scalar time_tolerance : {1e-3, 1e-5, 1e-7}) {
    for (const Scalar tolerance : {1e-6, 1e-9}) {
      TimeOfImpactOptions options;
      options.time_tolerance = time_tolerance;
      options.query.tolerance = tolerance;
      const RobotMotionCheck check = robot_check_motion(model, {{0, 1}}, q0, q1, options, {});
      ASSERT_TRUE(check.certified(0)) << time_tolerance << " " << tolerance;
      expect_bar_contact_bracketed(check, options);
    }
  }
}

TEST(RobotMotion, ASelfPairIsBracketedInTheFrameWhereItsChainsPart) {
  // The bar-and-post motion above, carried by a tilted turn far from the world's origin that
  // both geometries share: check_motion places the pair in the carrier's frame (the turn is not
  // evaluated there) and must answer for the world, where the carrier sweeps 3 rad meanwhile.
  std::vector<Link> links{{"base"}, {"carrier"}, {"arm"}};
  std::vector<Joint> joints{
      {"turn", JointType::revolute, 0, 1, placed({3, -2, 5}, {0.4, 0.2, 0.1}),
       Vector3(0.2, 0.1, 1).normalized(), -4, 4, 0},
      {"elbow", JointType::revolute, 1, 2, Pose{}, Vector3::UnitZ(), -3, 3, 0}};
  std::vector<Geometry> geometries{
      {"bar", 2, placed({0.5, 0, 0}), Box(Vector3(0.5, 0.01, 0.01)), std::nullopt},
      {"post", 1, placed({0, 0.6, 0}), Box(Vector3(0.01, 0.01, 1)), std::nullopt}};
  const RobotModel model(links, joints, geometries);
  Configurations q0(2, 2);
  Configurations q1(2, 2);
  q0 << 0, 0, -1, 0;
  q1 << 3, 2, 2, 1;
  TimeOfImpactOptions options;
  options.time_tolerance = 1e-9;
  const RobotMotionCheck check = robot_check_motion(model, {{0, 1}}, q0, q1, options, {});
  ASSERT_TRUE(check.certified(0) && check.certified(1));
  expect_bar_contact_bracketed(check, options);
  // The world's signed distance at t_upper, asked whole, is within the tolerance of contact.
  EXPECT_LE(check.distance(0), options.query.tolerance * 4);
  EXPECT_GE(check.distance(0), -options.query.tolerance * 4);
  EXPECT_FALSE(check.touches(1));
}

}  // namespace
}  // namespace swarmcollide::testing
