// Robots: forward kinematics against the closed form of a planar arm, the limit modes, the pair
// filter, and queries over configurations equal to the single query on the posed bodies.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "robot/box_screen.hpp"
#include "shapes.hpp"
#include "swarmcollide/geometry/shapes.hpp"
#include "swarmcollide/queries/methods.hpp"
#include "swarmcollide/queries/query.hpp"
#include "swarmcollide/robot/kinematics.hpp"
#include "swarmcollide/robot/pair_filter.hpp"
#include "swarmcollide/robot/robot_checker.hpp"
#include "swarmcollide/robot/robot_model.hpp"
#include "swarmcollide/robot/robot_queries.hpp"

namespace swarmcollide::testing {
namespace {

Pose translation(Scalar x, Scalar y, Scalar z) {
  Pose pose;
  pose.translation = Vector3(x, y, z);
  return pose;
}

// base -(revolute z)- upper -(revolute z, 1 along x)- fore -(fixed, 1 along x)- hand, each link
// with a 0.1 box at its origin; a slider on the base carries a box too.
RobotModel planar_arm() {
  std::vector<Link> links{{"base"}, {"upper"}, {"fore"}, {"hand"}, {"slider"}};
  std::vector<Joint> joints(4);
  joints[0] = {"shoulder", JointType::revolute, 0, 1, Pose{}, Vector3::UnitZ(), -2, 2, 0};
  joints[1] = {"elbow", JointType::continuous, 1, 2, translation(1, 0, 0), Vector3(0, 0, 2), 0, 0,
               0};
  joints[2] = {"wrist", JointType::fixed, 2, 3, translation(1, 0, 0), Vector3::UnitZ(), 0, 0, 0};
  joints[3] = {"slide", JointType::prismatic, 0, 4, translation(0, -1, 0), Vector3::UnitX(), -1,
               1, 0};
  std::vector<Geometry> geometries;
  const char* names[] = {"base", "upper", "fore", "hand", "slider"};
  for (int l = 0; l < 5; ++l) {
    geometries.push_back({names[l], l, Pose{}, Box(Vector3::Constant(0.1))});
  }
  return RobotModel(links, joints, geometries);
}

TEST(Robot, ForwardKinematicsIsThePlanarArmsClosedForm) {
  const RobotModel arm = planar_arm();
  ASSERT_EQ(arm.dof(), 3);
  Configurations q(2, 3);
  q << 0.3, -1.1, 0.25, -1.9, 2.5, -0.5;
  std::vector<Scalar> transforms(2 * 5 * 16);
  forward_kinematics(arm, q, transforms.data());
  for (int i = 0; i < 2; ++i) {
    const Scalar a = q(i, 0);
    const Scalar b = a + q(i, 1);
    const Scalar* hand = transforms.data() + (i * 5 + 3) * 16;
    EXPECT_NEAR(hand[3], std::cos(a) + std::cos(b), 1e-15);
    EXPECT_NEAR(hand[7], std::sin(a) + std::sin(b), 1e-15);
    EXPECT_NEAR(hand[0], std::cos(b), 1e-15);
    const Scalar* slider = transforms.data() + (i * 5 + 4) * 16;
    EXPECT_EQ(slider[3], q(i, 2));
    EXPECT_EQ(slider[7], -1);
  }
}

// Turns about a coordinate axis (either sign) take link_poses' fast path: it must give the poses
// of the plain products (the parent's pose, the origin, then Eigen's angle-axis matrix) bit for
// bit, after general origins, origins turned about a coordinate axis (URDF's single rpy angles)
// and identities alike, whose translations have none to three nonzero coordinates (the origins'
// products skip their exact zeros: OriginZeros); so must the geometries' poses at the links.
TEST(Robot, TurnsAboutCoordinateAxesComposeAsTheAngleAxisMatrixDoes) {
  const Vector3 axes[] = {Vector3::UnitZ(), -Vector3::UnitZ(), Vector3::UnitX(),
                          -Vector3::UnitX(), Vector3::UnitY(), -Vector3::UnitY(),
                          Vector3(0.6, 0, 0.8)};
  const int n = 7;
  std::vector<Link> links;
  std::vector<Joint> joints;
  std::vector<Geometry> geometries;
  for (int l = 0; l <= n; ++l) links.push_back({"l" + std::to_string(l)});
  for (int j = 0; j < n; ++j) {
    // A general origin, or a roll, pitch or yaw alone as URDF's rpy gives it (1 on the axis, exact
    // zeros off it), or none.
    Pose origin;
    if (j % 3 == 0) {
      origin.rotation = Eigen::AngleAxis<Scalar>(0.4 + j, Vector3(1, 2, 3 - j).normalized())
                            .toRotationMatrix();
    } else if (j != 5) {
      const int k = j % 3;
      const Scalar angle = 1.57079632679 * (j - 3);
      origin.rotation.setZero();
      origin.rotation(k, k) = 1;
      origin.rotation((k + 1) % 3, (k + 1) % 3) = origin.rotation((k + 2) % 3, (k + 2) % 3) =
          std::cos(angle);
      origin.rotation((k + 2) % 3, (k + 1) % 3) = std::sin(angle);
      origin.rotation((k + 1) % 3, (k + 2) % 3) = -std::sin(angle);
    }
    // j % 4 nonzero coordinates, from the j % 3-th on.
    origin.translation.setZero();
    for (int c = 0; c < j % 4; ++c) origin.translation[(j + c) % 3] = 0.1 * (j + 1) - 0.2 * c;
    joints.push_back({"j" + std::to_string(j), JointType::revolute, j, j + 1, origin, axes[j], -4,
                      4, 0.1 * j});
  }
  geometries.push_back({"g", n, Pose{}, Box(Vector3::Constant(0.1))});
  // Geometries at origins of every kind of the joints' too, on the links with general poses.
  for (int j = 0; j < n; ++j) {
    geometries.push_back({"g" + std::to_string(j), n - j,
                          joints[static_cast<std::size_t>(j)].origin, Box(Vector3::Constant(0.1))});
  }
  const RobotModel model(links, joints, geometries);
  const Scalar q[] = {0.3, -1.1, 2.5, -3.9, 1e-9, 3.14159, -0.7};
  std::vector<Pose> got;
  link_poses(model, q, got);
  Pose expected;
  for (int j = 0; j < n; ++j) {
    const Joint& joint = model.joints()[static_cast<std::size_t>(j)];
    Pose turn;
    turn.rotation =
        Eigen::AngleAxis<Scalar>(q[j] - joint.reference, joint.axis).toRotationMatrix();
    const auto product = [](const Pose& outer, const Pose& inner) {
      Pose pose;
      pose.rotation = outer.rotation * inner.rotation;
      pose.translation = outer.rotation * inner.translation + outer.translation;
      return pose;
    };
    expected = product(product(expected, joint.origin), turn);
    const Pose& pose = got[static_cast<std::size_t>(j + 1)];
    for (int r = 0; r < 3; ++r) {
      EXPECT_EQ(pose.translation(r), expected.translation(r)) << "joint " << j;
      for (int c = 0; c < 3; ++c) {
        EXPECT_EQ(pose.rotation(r, c), expected.rotation(r, c)) << "joint " << j;
      }
    }
  }
  for (int g = 1; g <= n; ++g) {
    const Geometry& geometry = model.geometries()[static_cast<std::size_t>(g)];
    const Pose& link = got[static_cast<std::size_t>(geometry.link)];
    const Pose pose = geometry_pose(model, got, g);
    const Matrix3 rotation = link.rotation * geometry.origin.rotation;
    const Vector3 translation = link.rotation * geometry.origin.translation + link.translation;
    for (int r = 0; r < 3; ++r) {
      EXPECT_EQ(pose.translation(r), translation(r)) << "geometry " << g;
      for (int c = 0; c < 3; ++c) {
        EXPECT_EQ(pose.rotation(r, c), rotation(r, c)) << "geometry " << g;
      }
    }
  }
}

TEST(Robot, LimitsRaiseClampOrWrapNamingTheJoint) {
  const RobotModel arm = planar_arm();
  Configurations q(1, 3);
  q << 4.5, 7, 0;
  try {
    admit_configurations(arm, q, LimitMode::raise);
    FAIL() << "accepted a shoulder angle outside its limits";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("q[0], joint 'shoulder'"), std::string::npos);
  }
  // Values as their shortest exact text: 2.1, not 2.1000000000000001.
  q << 2.1, 7, 0;
  try {
    admit_configurations(arm, q, LimitMode::raise);
    FAIL() << "accepted a shoulder angle outside its limits";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find(": 2.1 is outside its limits [-2, 2]"),
              std::string::npos)
        << error.what();
  }
  q << 4.5, 7, 0;
  EXPECT_EQ(admit_configurations(arm, q, LimitMode::clamp)(0, 0), 2);
  // 4.5 - 2 pi is within [-2, 2]; the continuous elbow is left as it is.
  EXPECT_NEAR(admit_configurations(arm, q, LimitMode::wrap)(0, 0), 4.5 - 2 * M_PI, 1e-15);
  EXPECT_EQ(admit_configurations(arm, q, LimitMode::wrap)(0, 1), 7);
  q << 2.5, 0, 0;  // 2.5 - 2 pi is below -2: no turn brings it within
  EXPECT_THROW(admit_configurations(arm, q, LimitMode::wrap), std::invalid_argument);
  q << 0, 0, 1.5;
  EXPECT_THROW(admit_configurations(arm, q, LimitMode::wrap), std::invalid_argument);
  q << 0, NAN, 0;
  EXPECT_THROW(admit_configurations(arm, q, LimitMode::clamp), std::invalid_argument);
  EXPECT_THROW(admit_configurations(arm, Configurations(1, 2), LimitMode::raise),
               std::invalid_argument);
}

TEST(Robot, AMimicIndexBelowMinusOneIsRefusedNotReadAsNone) {
  Joint joint{"j", JointType::revolute, 0, 1, Pose{}, Vector3::UnitZ(), -1, 1, 0};
  joint.mimic = -2;
  try {
    RobotModel({{"a"}, {"b"}}, {joint}, {});
    FAIL() << "took mimic -2 for no mimic";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("joint 'j': mimic must be a joint index, or -1 for "
                                             "none, got -2"),
              std::string::npos)
        << error.what();
  }
}

TEST(Robot, AdjacentLinksIncludeThoseJoinedByFixedJoints) {
  const RobotModel arm = planar_arm();
  EXPECT_TRUE(adjacent_links(arm, 0, 1));
  EXPECT_TRUE(adjacent_links(arm, 1, 3));  // upper - elbow - fore = hand
  EXPECT_TRUE(adjacent_links(arm, 0, 4));
  EXPECT_FALSE(adjacent_links(arm, 0, 2));
  EXPECT_FALSE(adjacent_links(arm, 1, 4));
  std::vector<std::pair<int, int>> got;
  for (const GeometryPair& p : default_pairs(arm)) got.emplace_back(p.a, p.b);
  const std::vector<std::pair<int, int>> expected{{0, 2}, {0, 3}, {1, 4}, {2, 4}, {3, 4}};
  EXPECT_EQ(got, expected);
}

TEST(Robot, ChecksEqualTheSingleQueriesOnThePosedBodiesWhateverTheThreads) {
  const RobotModel arm = planar_arm();
  const std::vector<GeometryPair> pairs = default_pairs(arm);
  Configurations q(40, 3);
  for (int i = 0; i < 40; ++i) q.row(i) << -1.9 + 0.1 * i, 3.1 - 0.15 * i, -0.9 + 0.045 * i;
  BatchSettings one;
  one.threads = 1;
  BatchSettings two;
  two.threads = 2;
  const RobotCheck check = robot_check(arm, pairs, q, {}, one, true);
  const RobotCheck check2 = robot_check(arm, pairs, q, {}, two, true);
  const RobotDistances distances = robot_distances(arm, pairs, q, {}, two);
  EXPECT_TRUE((check.min_distance.array() == check2.min_distance.array()).all());
  EXPECT_TRUE((check.gradient.array() == check2.gradient.array()).all());
  const Query query;
  std::vector<Pose> links;
  int colliding = 0;
  for (int i = 0; i < 40; ++i) {
    link_poses(arm, q.row(i).data(), links);
    Scalar least = INFINITY;
    for (std::size_t p = 0; p < pairs.size(); ++p) {
      const Geometry& a = arm.geometries()[pairs[p].a];
      const Geometry& b = arm.geometries()[pairs[p].b];
      const DistanceResult single = query.signed_distance(a.body, links[a.link], b.body,
                                                          links[b.link]);
      EXPECT_EQ(distances.distance(i, p), single.distance);
      least = std::min(least, single.distance);
    }
    EXPECT_EQ(check.min_distance(i), least);
    EXPECT_TRUE(check.certified(i));
    EXPECT_EQ(check.colliding(i), least <= 0);
    colliding += check.colliding(i);
  }
  EXPECT_GT(colliding, 0);
  EXPECT_LT(colliding, 40);
}

TEST(Robot, ACheckerAnswersEachConfigurationAsItsRowOfTheBatch) {
  const RobotModel arm = planar_arm();
  const std::vector<GeometryPair> pairs = default_pairs(arm);
  Configurations q(20, 3);
  for (int i = 0; i < 20; ++i) q.row(i) << -1.9 + 0.2 * i, 3.1 - 0.3 * i, -0.9 + 0.09 * i;
  for (const bool nearest : {true, false}) {
    const RobotCheck batch = robot_check(arm, pairs, q, {}, {}, nearest, nearest);
    RobotChecker checker(arm, pairs, {}, nearest, nearest);
    for (int i = 0; i < 20; ++i) {
      // Row i's seed, and row 0's as a single configuration's: the same answers here.
      const RobotCheckRow row = checker.check(q.row(i).data(), static_cast<std::size_t>(i));
      const RobotCheckRow& single = checker.admit_and_check(q.row(i).data(), 3, LimitMode::raise);
      for (const RobotCheckRow* answer : {&row, &single}) {
        EXPECT_EQ(answer->colliding, batch.colliding(i));
        EXPECT_EQ(answer->certified, batch.certified(i));
        EXPECT_EQ(answer->pair, batch.pair(i));
        if (nearest) {
          EXPECT_EQ(answer->min_distance, batch.min_distance(i));
          EXPECT_EQ(answer->lower_bound, batch.lower_bound(i));
          EXPECT_TRUE(answer->point_a == batch.point_a.row(i).transpose());
          EXPECT_TRUE(answer->gradient == batch.gradient.row(i).transpose());
        } else {
          EXPECT_TRUE(std::isnan(answer->min_distance));
        }
      }
    }
  }
  EXPECT_THROW(RobotChecker(arm, pairs, {}, false, true), std::invalid_argument);
  RobotChecker checker(arm, pairs, {}, true, false);
  const Scalar short_q[2] = {0, 0};
  EXPECT_THROW(checker.admit_and_check(short_q, 2, LimitMode::raise), std::invalid_argument);
}

// On a slide along x, a link with a sphere (radius 0.1) and a compound of two boxes 0.1 across
// (at y = 0.3 and 0.7), all at height 0; an obstacle cylinder (radius 0.2, z in [-0.5, 0.5]) at
// the origin.
RobotModel slide_past_a_cylinder() {
  std::vector<Link> links{{"world"}, {"rail"}};
  std::vector<Joint> joints(1);
  joints[0] = {"x", JointType::prismatic, 0, 1, Pose{}, Vector3::UnitX(), -3, 3, 0};
  std::vector<ConvexPolyhedron> parts{box(Vector3(-0.05, 0.25, -0.05), Vector3(0.05, 0.35, 0.05)),
                                      box(Vector3(-0.05, 0.65, -0.05), Vector3(0.05, 0.75, 0.05))};
  std::vector<Geometry> geometries;
  geometries.push_back({"ball", 1, Pose{}, Sphere(0.1), std::nullopt});
  geometries.push_back({"boxes", 1, Pose{}, parts.front(), CompoundBody(parts)});
  geometries.push_back({"post", -1, Pose{}, Cylinder(0.2, 0.5), std::nullopt});
  return RobotModel(links, joints, geometries);
}

TEST(Robot, CurvedGeometriesHaveTheirClosedFormDistances) {
  const RobotModel model = slide_past_a_cylinder();
  const std::vector<GeometryPair> pairs = default_pairs(model);
  ASSERT_EQ(pairs.size(), 2u);  // ball - post, boxes - post (a compound against a cylinder)
  Configurations q(4, 1);
  q << -1.0, -0.25, 0.02, 0.6;
  BatchSettings two;
  two.threads = 2;
  const RobotDistances distances = robot_distances(model, pairs, q, {}, two);
  const RobotCheck check = robot_check(model, pairs, q, {}, two, true);
  for (int i = 0; i < 4; ++i) {
    const Scalar x = q(i, 0);
    const Scalar ball = std::abs(x) - 0.3;
    // The nearer box (y in [0.25, 0.35]) faces the cylinder's side while |x| <= 0.05, and its
    // corner edge is nearest otherwise.
    const Scalar off = std::max(std::abs(x) - 0.05, Scalar{0});
    const Scalar boxes = std::hypot(off, 0.25) - 0.2;
    EXPECT_NEAR(distances.distance(i, 0), ball, 1e-9) << "row " << i;
    EXPECT_NEAR(distances.distance(i, 1), boxes, 1e-9) << "row " << i;
    EXPECT_TRUE(distances.certified(i, 0) && distances.certified(i, 1));
    EXPECT_EQ(check.min_distance(i), std::min(distances.distance(i, 0), distances.distance(i, 1)));
    EXPECT_TRUE(check.certified(i));
    EXPECT_EQ(check.colliding(i), ball <= 0 || boxes <= 0);
  }
  // At x = 0.6 the ball is nearest, moving away at unit speed.
  EXPECT_EQ(check.pair(3), 0);
  EXPECT_NEAR(check.gradient(3, 0), 1, 1e-9);
}

TEST(Robot, MethodsThatReadPointsRefuseCurvedGeometriesNamingThem) {
  const RobotModel model = slide_past_a_cylinder();
  // The paper's swarm reads a body's points (fcl and libccd answer curved shapes as FCL's
  // primitives or through their support functions).
  QueryOptions swarm;
  swarm.method = Method::ipso;
  Configurations q(1, 1);
  q << 1.0;
  for (const auto& call : {std::function<void()>([&] {
                             robot_check(model, default_pairs(model), q, swarm);
                           }),
                           std::function<void()>([&] {
                             robot_distances(model, default_pairs(model), q, swarm);
                           })}) {
    try {
      call();
      FAIL() << "the ipso method answered a cylinder";
    } catch (const std::invalid_argument& error) {
      EXPECT_NE(std::string(error.what()).find("geometry 'post' is a cylinder"), std::string::npos)
          << error.what();
    }
  }
}

// The 8 corners of the box of centre `centre` and half-widths `half`, one per row.
VertexMatrix box_corners(const Vector3& centre, const Vector3& half) {
  VertexMatrix corners(8, 3);
  for (int k = 0; k < 8; ++k) {
    const Vector3 sign(k & 1 ? 1 : -1, k & 2 ? 1 : -1, k & 4 ? 1 : -1);
    corners.row(k) = (centre + sign.cwiseProduct(half)).transpose();
  }
  return corners;
}

// Half-widths of a random box, 0.01 to 1 each.
Vector3 random_half_widths(Random& rng) {
  return Vector3(rng.uniform(0.01, 1), rng.uniform(0.01, 1), rng.uniform(0.01, 1));
}

// The robot checks' box screen: its separation of two placed boxes is a lower bound on the exact
// distance of their corners' hulls, and it finds most clearly separated boxes apart. Its face axes
// alone (check_motion screens by them) are a subset of the 15, so never above the whole test's
// separation, and box_separation's answer when its first 6 axes are enough.
TEST(BoxScreen, TheBoxesSeparationIsALowerBoundOnTheirDistance) {
  Random rng(17);
  QueryOptions options;
  options.method = Method::exact;
  const Query exact(options);
  int apart = 0;
  int clearly = 0;
  int faces_apart = 0;
  int faces_below = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const Vector3 ha = random_half_widths(rng);
    const Vector3 hb = random_half_widths(rng);
    const Vector3 ca = rng.vector(0.5);
    const Vector3 cb = rng.vector(0.5);
    const Aabb a{ca - ha, ca + ha};
    const Aabb b{cb - hb, cb + hb};
    const Pose pa = at(rng.vector(1), rng.rotation());
    const Pose pb = at(rng.vector(1), rng.rotation());
    const DistanceResult d = exact.distance(ConvexPolyhedron(box_corners(ca, ha)), pa,
                                            ConvexPolyhedron(box_corners(cb, hb)), pb);
    const Scalar separation = detail::box_separation(a, pa, b, pb);
    const detail::PlacedBox placed_a(a, pa);
    const detail::PlacedBox placed_b(b, pb);
    const Scalar faces = detail::face_separation(placed_a, placed_b);
    EXPECT_LE(faces, separation) << trial;
    EXPECT_EQ(faces, detail::box_separation(placed_a, placed_b, [](Scalar) { return true; }))
        << trial;
    faces_apart += faces > 0;
    faces_below += faces > 0 && faces < separation;
    if (separation > 0) {
      ++apart;
      // The exact distance is proven within 1e-15 of the pair's size: below it, above the bound.
      EXPECT_LE(separation, d.distance) << trial;
      EXPECT_LE(separation, d.lower_bound + 1e-13) << trial;
    }
    clearly += d.lower_bound > 0.3;
  }
  // Boxes 0.3 apart are separated along one of the 15 axes.
  EXPECT_GT(apart, clearly);
  EXPECT_GT(apart, 100);
  // The face axes separate most of those pairs, the cross axes some farther.
  EXPECT_GT(faces_apart, 100);
  EXPECT_GT(faces_below, 0);
}

// Boxes turned from each other by 1e-17 to 1e-13 rad (columns parallel to a few ulps), the one's
// centre inside the other: no axis separates them. The near-parallel columns' cross products are
// rounding alone, along which the triple products the screen reads are off by some u (the slack
// in box_separation); without it, 2,492 of 200,000 such pairs were called 0.26 apart.
TEST(BoxScreen, NearlyParallelBoxesThatOverlapAreNotCalledApart) {
  Random rng(23);
  for (int trial = 0; trial < 20000; ++trial) {
    const Matrix3 r = rng.rotation();
    const Scalar angle = std::pow(10.0, rng.uniform(-17, -13));
    const Matrix3 turned = r * Eigen::AngleAxis<Scalar>(angle, rng.unit()).toRotationMatrix();
    const Vector3 ha = random_half_widths(rng);
    const Vector3 hb = random_half_widths(rng);
    const Pose pa = at(rng.vector(1), r);
    const Vector3 inside = rng.vector(1).cwiseProduct(ha);
    const Pose pb = at(r * inside + pa.translation, turned);
    EXPECT_FALSE(detail::box_separation(Aabb{-ha, ha}, pa, Aabb{-hb, hb}, pb) > 0) << trial;
  }
}

}  // namespace
}  // namespace swarmcollide::testing
