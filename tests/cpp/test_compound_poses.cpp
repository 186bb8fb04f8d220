// Compound bodies whose parts have poses of their own: every query answers as the parts queried
// one by one at the composed poses (the part's pose, then the body's), for curved parts (whose
// support function is moved) and polyhedra (whose points are) alike.
#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "shapes.hpp"
#include "swarmcollide/geometry/compound_body.hpp"
#include "swarmcollide/geometry/placed_shape.hpp"
#include "swarmcollide/geometry/shapes.hpp"
#include "swarmcollide/queries/batch.hpp"
#include "swarmcollide/queries/methods.hpp"
#include "swarmcollide/queries/query.hpp"
#include "swarmcollide/scene/scene.hpp"

namespace swarmcollide::testing {
namespace {

constexpr Scalar kPiOver2 = 1.57079632679489661923;

Pose then(const Pose& outer, const Pose& inner) {
  return {outer.rotation * inner.rotation, outer.rotation * inner.translation + outer.translation};
}

Query query_of(Method method) {
  QueryOptions options;
  options.method = method;
  return Query(options);
}

// A cylinder lying along x above a box, a cone tipped over beside it, an ellipsoid turned
// anyhow, and a rounded box: every kind of part, each with a pose.
struct Posed {
  std::vector<ConvexPolyhedron> parts;
  std::vector<Pose> poses;
  CompoundBody body;
};

Posed posed_body(Random& rng) {
  std::vector<ConvexPolyhedron> parts = {Cylinder(0.2, 0.9), Box(Vector3(0.8, 0.5, 0.1)),
                                         Cone(0.3, 0.4), Ellipsoid(Vector3(0.1, 0.3, 0.2)),
                                         Box(Vector3(0.1, 0.2, 0.1), 0.05)};
  std::vector<Pose> poses;
  poses.push_back(at(Vector3(0, 0, 0.35), Eigen::AngleAxisd(kPiOver2, Vector3::UnitY()).matrix()));
  poses.push_back(at(Vector3(0.1, -0.2, 0)));
  for (int k = 2; k < 5; ++k) poses.push_back(at(rng.vector(0.8), rng.rotation()));
  CompoundBody body(parts, poses);
  return {parts, poses, body};
}

TEST(CompoundPoses, PartsArePlacedAndGivenBack) {
  Random rng(3);
  const Posed p = posed_body(rng);
  ASSERT_EQ(p.body.size(), 5);
  const std::vector<Pose> poses = p.body.part_poses();
  for (int i = 0; i < 5; ++i) {
    EXPECT_EQ(poses[i].rotation, p.poses[i].rotation);
    EXPECT_EQ(poses[i].translation, p.poses[i].translation);
    EXPECT_EQ(p.body.given_parts()[i].vertices(), p.parts[i].vertices());
    // The placed part's support points are the given part's moved, and its box holds them.
    const ConvexPolyhedron& placed = p.body.parts()[i];
    EXPECT_EQ(placed.curved() != nullptr, p.parts[i].curved() != nullptr);
    for (int k = 0; k < 40; ++k) {
      const Vector3 d = rng.unit();
      const Vector3 moved =
          p.poses[i].rotation * p.parts[i].support(p.poses[i].rotation.transpose() * d) +
          p.poses[i].translation;
      EXPECT_NEAR(d.dot(placed.support(d)), d.dot(moved), 1e-14);
      const Vector3 s = placed.support(d);
      EXPECT_TRUE((s.array() >= placed.aabb().min.array()).all() &&
                  (s.array() <= placed.aabb().max.array()).all());
    }
  }
  // The lying cylinder spans x in [-0.9, 0.9]: its box is the moved shape's, not its points'.
  EXPECT_NEAR(p.body.parts()[0].aabb().max.x(), 0.9, 1e-12);
  EXPECT_NEAR(p.body.parts()[0].aabb().min.z(), 0.15, 1e-12);
  // Without poses, every pose is the identity and the parts are as given.
  const CompoundBody plain({Cylinder(0.2, 0.9)});
  EXPECT_EQ(plain.part_poses()[0].rotation, Matrix3::Identity());
  EXPECT_EQ(&plain.given_parts(), &plain.parts());
}

TEST(CompoundPoses, BadPosesAreRefusedNamingThem) {
  const std::vector<ConvexPolyhedron> parts = {Cylinder(0.2, 0.9), unit_cube()};
  EXPECT_THROW(CompoundBody(parts, {Pose{}}), std::invalid_argument);
  Pose skewed;
  skewed.rotation(0, 1) = 0.5;
  try {
    CompoundBody(parts, {Pose{}, skewed});
    ADD_FAILURE() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("poses[1]"), std::string::npos) << e.what();
  }
  Pose far;
  far.translation.x() = std::numeric_limits<Scalar>::quiet_NaN();
  EXPECT_THROW(CompoundBody(parts, {far, Pose{}}), std::invalid_argument);
}

TEST(CompoundPoses, QueriesAnswerAsThePartsAtTheirComposedPoses) {
  Random rng(5);
  const Posed p = posed_body(rng);
  const std::vector<ConvexPolyhedron> others = {Sphere(0.3), Capsule(0.1, 0.4),
                                                Cylinder(0.25, 0.3), unit_cube()};
  for (Method method : {Method::dual, Method::exact, Method::fcl, Method::libccd}) {
    SCOPED_TRACE(method_name(method));
    const Query query = query_of(method);
    const bool distances = method != Method::libccd;
    int colliding = 0;
    for (int trial = 0; trial < 24; ++trial) {
      const ConvexPolyhedron& other = others[trial % others.size()];
      const Pose pa = at(rng.vector(0.2), rng.rotation());
      const Pose pb = at(rng.vector(1.3), rng.rotation());
      // The oracle: each given part at its composed pose.
      Scalar best = std::numeric_limits<Scalar>::infinity();
      Scalar best_signed = best;
      for (std::size_t i = 0; i < p.parts.size(); ++i) {
        const Pose composed = then(pa, p.poses[i]);
        const DistanceResult s = query.signed_distance(p.parts[i], composed, other, pb);
        EXPECT_TRUE(s.certified) << trial << " part " << i;
        best_signed = std::min(best_signed, s.distance);
        if (distances) best = std::min(best, query.distance(p.parts[i], composed, other, pb).distance);
      }
      const CompoundBody b(other);
      const Scalar size = 2 * (p.body.bounds().radius + other.bounds().radius + 1.5);
      const Scalar slack = 2 * kDefaultTolerance * size;
      const CompoundResult s = query.signed_distance(p.body, pa, b, pb);
      EXPECT_TRUE(s.certified) << trial;
      EXPECT_NEAR(s.distance, best_signed, slack) << trial;
      if (distances) {
        const CompoundResult d = query.distance(p.body, pa, b, pb);
        EXPECT_TRUE(d.certified) << trial;
        EXPECT_NEAR(d.distance, best, slack) << trial;
      }
      const CompoundResult c = query.collision(p.body, pa, b, pb);
      EXPECT_TRUE(c.certified) << trial;
      EXPECT_EQ(c.colliding, best_signed <= kDefaultTolerance * size) << trial;
      colliding += c.colliding;
    }
    EXPECT_GT(colliding, 2);
    EXPECT_LT(colliding, 22);
  }
}

TEST(CompoundPoses, BatchesAndScenesAnswerAsThePairQueries) {
  Random rng(7);
  const Posed p = posed_body(rng);
  const CompoundBody ball(Sphere(0.4));
  BatchPoses poses;
  for (int row = 0; row < 30; ++row) {
    poses.a.push_back(at(Vector3::Zero(), rng.rotation()));
    poses.b.push_back(at(rng.vector(1.4), rng.rotation()));
  }
  const Query query = query_of(Method::dual);
  const BatchResult distances = distance_many(p.body, ball, QueryOptions{}, {}, poses);
  int colliding = 0;
  for (int row = 0; row < 30; ++row) {
    const CompoundResult one = query.distance(p.body, poses.a[row], ball, poses.b[row]);
    EXPECT_TRUE(distances.certified(row));
    EXPECT_NEAR(distances.distance(row), one.distance, 1e-8) << row;
    colliding += one.colliding;
  }
  EXPECT_GT(colliding, 0);
  // A scene: the lying cylinder reaches the ball at its end, not the one below its centre
  // (which a cylinder standing at the origin would hold).
  const CompoundBody lying({Cylinder(0.2, 0.9)}, {p.poses[0]});
  Scene scene{SceneOptions{}};
  const BodyId bar = scene.add(lying);
  const BodyId end = scene.add(Sphere(0.1), at(Vector3(0.85, 0, 0.45)));
  scene.add(Sphere(0.1), at(Vector3(0, 0, -0.5)));
  const SceneResult hits = scene.colliding_pairs();
  ASSERT_EQ(hits.size(), 1);
  EXPECT_TRUE(hits.certified(0));
  EXPECT_EQ(std::min(hits.pairs(0, 0), hits.pairs(0, 1)), std::min(bar, end));
  EXPECT_EQ(std::max(hits.pairs(0, 0), hits.pairs(0, 1)), std::max(bar, end));
}

}  // namespace
}  // namespace swarmcollide::testing
