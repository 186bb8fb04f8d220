// Compound bodies against a brute-force oracle: every part pair asked of Query, the smallest
// answer kept. The tree may prune, never change the answer beyond the tolerance.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>
#include <vector>

#include "compound_oracle.hpp"
#include "shapes.hpp"
#include "swarmcollide/queries/batch.hpp"
#include "swarmcollide/queries/methods.hpp"
#include "swarmcollide/queries/query.hpp"
#include "swarmcollide/scene/scene.hpp"

namespace swarmcollide {
namespace {

using swarmcollide::testing::best_part_pair;
using swarmcollide::testing::box;

Matrix3 random_rotation(std::mt19937_64& rng) {
  std::normal_distribution<Scalar> normal;
  Eigen::Quaterniond q(normal(rng), normal(rng), normal(rng), normal(rng));
  q.normalize();
  return q.toRotationMatrix();
}

// A U of three boxes: two posts of height 2 on a base, the gap between them 1 wide.
CompoundBody u_shape() {
  return CompoundBody(
      {box({0, 0, 0}, {3, 1, 0.5}), box({0, 0, 0.5}, {1, 1, 2}), box({2, 0, 0.5}, {3, 1, 2})});
}

// A row of `n` random hulls along x: many parts, most far from a body beside the row's end.
CompoundBody random_row(std::mt19937_64& rng, int n) {
  std::uniform_real_distribution<Scalar> unit(-0.4, 0.4);
  std::vector<ConvexPolyhedron> parts;
  for (int k = 0; k < n; ++k) {
    VertexMatrix points(8, 3);
    for (int i = 0; i < 8; ++i) points.row(i) << k + unit(rng), unit(rng), unit(rng);
    parts.emplace_back(points);
  }
  return CompoundBody(parts);
}

TEST(CompoundBody, TreeHoldsEveryPartInEachNodesVolumes) {
  std::mt19937_64 rng(3);
  const CompoundBody body = random_row(rng, 13);
  ASSERT_EQ(body.tree().size(), 25u);
  std::vector<int> seen(13, 0);
  // Each node's volumes hold the parts below it.
  std::vector<std::vector<int>> below(body.tree().size());
  for (int at = static_cast<int>(body.tree().size()) - 1; at >= 0; --at) {
    const PartNode& node = body.tree()[at];
    if (node.leaf()) {
      ++seen[node.part];
      below[at] = {node.part};
    } else {
      below[at] = below[node.left];
      below[at].insert(below[at].end(), below[node.right].begin(), below[node.right].end());
    }
    for (int part : below[at]) {
      const VertexMatrix& points = body.parts()[part].vertices();
      for (int i = 0; i < points.rows(); ++i) {
        const Vector3 p = points.row(i);
        EXPECT_LE((p - node.centre).norm(), node.radius * (1 + 1e-12));
        EXPECT_TRUE((p.array() >= node.box.min.array()).all());
        EXPECT_TRUE((p.array() <= node.box.max.array()).all());
      }
    }
  }
  EXPECT_EQ(std::count(seen.begin(), seen.end(), 1), 13);
  EXPECT_EQ(body.point_count(), 13 * 8);
  EXPECT_EQ(body.envelope().size(), 13 * 8);
}

TEST(CompoundBody, RejectsNoParts) {
  EXPECT_THROW(CompoundBody(std::vector<ConvexPolyhedron>{}), std::invalid_argument);
}

TEST(CompoundQuery, OnePartIsTheConvexQuery) {
  const ConvexPolyhedron a = box({0, 0, 0}, {1, 1, 1});
  const ConvexPolyhedron b = box({2.5, 0.2, 0.1}, {3, 1, 1});
  const Query query;
  const CompoundResult r = query.distance(CompoundBody(a), CompoundBody(b));
  // Bit for bit: a pair of one part each is answered as the convex pair.
  const DistanceResult convex = query.distance(a, b);
  EXPECT_EQ(r.distance, convex.distance);
  EXPECT_EQ(r.lower_bound, convex.lower_bound);
  EXPECT_EQ(r.point_a, convex.point_a);
  EXPECT_TRUE(r.certified);
  EXPECT_EQ(r.stats.part_pairs, 1);
  EXPECT_EQ(r.stats.solved, 1);
}

TEST(CompoundQuery, DistancesMatchEveryPartPairAtRandomPoses) {
  std::mt19937_64 rng(11);
  const CompoundBody a = random_row(rng, 12);
  const CompoundBody b = random_row(rng, 9);
  std::uniform_real_distribution<Scalar> offset(-6, 6);
  for (const char* name : {"dual", "exact", "fcl"}) {
    QueryOptions options;
    options.method = method_from_name(name);
    const Query query(options);
    long pruned = 0;
    long total = 0;
    for (int trial = 0; trial < 20; ++trial) {
      const Pose pose_a{random_rotation(rng), Vector3(offset(rng), offset(rng), offset(rng))};
      const Pose pose_b{random_rotation(rng), Vector3(offset(rng), offset(rng), offset(rng))};
      const CompoundResult r = query.distance(a, pose_a, b, pose_b);
      const DistanceResult oracle = best_part_pair(query, a, pose_a, b, pose_b, false);
      const Scalar tolerance = 1e-8 * (1 + oracle.distance);
      EXPECT_NEAR(r.distance, oracle.distance, tolerance) << name << " trial " << trial;
      EXPECT_LE(r.lower_bound, oracle.distance + tolerance);
      EXPECT_GE(r.distance, oracle.distance - tolerance);
      EXPECT_TRUE(r.certified) << name << " trial " << trial;
      // The witnesses lie on the parts named, at the distance reported.
      EXPECT_NEAR((r.point_b - r.point_a).norm(), r.distance, 1e-9 * (1 + r.distance));
      const VectorX wa = r.weights_a.dense();
      ASSERT_EQ(wa.size(), a.parts()[r.part_a].size());
      const Vector3 on_a =
          pose_a.rotation * (a.parts()[r.part_a].vertices().transpose() * wa) + pose_a.translation;
      EXPECT_NEAR((on_a - r.point_a).norm(), 0, 1e-9);
      pruned += r.stats.pruned();
      total += r.stats.part_pairs;
    }
    // Most part pairs are never looked at.
    EXPECT_GT(pruned, total / 2) << name;
  }
}

TEST(CompoundQuery, SignedDistanceIsTheDeepestPartPair) {
  std::mt19937_64 rng(5);
  const CompoundBody a = random_row(rng, 6);
  const CompoundBody b = random_row(rng, 5);
  const Query query;
  for (int trial = 0; trial < 10; ++trial) {
    const Pose pose_a{random_rotation(rng), Vector3::Zero()};
    const Pose pose_b{random_rotation(rng), Vector3(0.3 * trial, 0.2, 0)};
    const CompoundResult r = query.signed_distance(a, pose_a, b, pose_b);
    const DistanceResult oracle = best_part_pair(query, a, pose_a, b, pose_b, true);
    EXPECT_NEAR(r.distance, oracle.distance, 1e-8) << trial;
    EXPECT_TRUE(r.certified) << trial;
    EXPECT_EQ(r.colliding, oracle.distance <= 1e-8) << trial;
  }
}

TEST(CompoundQuery, APegInTheGapOfAUDoesNotCollideThoughTheHullsDo) {
  const CompoundBody u = u_shape();
  const CompoundBody peg(box({1.2, 0.2, 0.8}, {1.8, 0.8, 3}));
  const Query query;
  EXPECT_TRUE(query.collide(u.envelope(), peg.envelope()));
  const CompoundResult r = query.collision(u, peg);
  EXPECT_FALSE(r.colliding);
  EXPECT_TRUE(r.certified);
  EXPECT_GT(r.lower_bound, 0.19);
  EXPECT_NEAR(query.distance(u, peg).distance, 0.2, 1e-9);
  // Lowered onto the base, it touches the base part.
  const Pose down{Matrix3::Identity(), Vector3(0, 0, -0.3)};
  const CompoundResult touching = query.collision(u, Pose{}, peg, down);
  EXPECT_TRUE(touching.colliding);
  EXPECT_TRUE(touching.certified);
  EXPECT_EQ(touching.part_a, 0);
}

TEST(CompoundQuery, CollisionVerdictsMatchEveryPartPair) {
  std::mt19937_64 rng(9);
  const CompoundBody a = random_row(rng, 8);
  const CompoundBody b = random_row(rng, 8);
  std::uniform_real_distribution<Scalar> offset(-3, 3);
  const Query query;
  for (int trial = 0; trial < 30; ++trial) {
    const Pose pose_b{random_rotation(rng), Vector3(offset(rng), offset(rng), offset(rng))};
    const CompoundResult r = query.collision(a, Pose{}, b, pose_b);
    bool any = false;
    for (const ConvexPolyhedron& pa : a.parts()) {
      for (const ConvexPolyhedron& pb : b.parts()) any |= query.collide(pa, Pose{}, pb, pose_b);
    }
    EXPECT_EQ(r.colliding, any) << trial;
    EXPECT_TRUE(r.certified);
    EXPECT_LE(r.lower_bound, r.distance);
  }
}

TEST(CompoundQuery, RigidMotionsAndSwappingLeaveDistancesUnchanged) {
  std::mt19937_64 rng(21);
  const CompoundBody a = random_row(rng, 7);
  const CompoundBody b = random_row(rng, 4);
  const Query query;
  const Pose pose_b{random_rotation(rng), Vector3(2, 3, 1)};
  const Scalar d = query.distance(a, Pose{}, b, pose_b).distance;
  const Matrix3 turn = random_rotation(rng);
  const Vector3 shift(10, -4, 7);
  const Pose moved_a{turn, shift};
  const Pose moved_b{turn * pose_b.rotation, turn * pose_b.translation + shift};
  EXPECT_NEAR(query.distance(a, moved_a, b, moved_b).distance, d, 1e-9);
  EXPECT_NEAR(query.distance(b, pose_b, a, Pose{}).distance, d, 1e-9);
}

TEST(CompoundQuery, BatchesNameTheParts) {
  const CompoundBody u = u_shape();
  const CompoundBody peg(box({1.2, 0.2, 0.8}, {1.8, 0.8, 3}));
  BatchPoses poses;
  poses.b = {Pose{}, Pose{Matrix3::Identity(), Vector3(0, 0, -0.3)}};
  const BatchResult r =
      collide_many(std::vector<CompoundBody>{u, u}, std::vector<CompoundBody>{peg, peg},
                   QueryOptions{}, {}, poses);
  EXPECT_FALSE(r.colliding(0));
  EXPECT_TRUE(r.colliding(1));
  EXPECT_EQ(r.part_a(1), 0);
  const BatchResult d =
      distance_many(std::vector<CompoundBody>{u}, std::vector<CompoundBody>{peg}, QueryOptions{});
  EXPECT_NEAR(d.distance(0), 0.2, 1e-9);
}

TEST(CompoundQuery, MethodsWithoutTheQueryAreRefused) {
  QueryOptions options;
  options.method = Method::ipso;
  const CompoundBody u = u_shape();
  EXPECT_THROW(Query(options).signed_distance(u, u), std::invalid_argument);
}

TEST(CompoundScene, CompoundBodiesPairAsTheirQueriesSay) {
  for (const bool warm : {true, false}) {
    SceneOptions options;
    options.threads = 1;
    options.warm_start = warm;
    Scene scene(options);
    const BodyId u = scene.add(u_shape());
    const BodyId peg = scene.add(box({1.2, 0.2, 0.8}, {1.8, 0.8, 3}));
    const BodyId far = scene.add(u_shape(), Pose{Matrix3::Identity(), Vector3(10, 0, 0)});
    ASSERT_NE(scene.compound(u), nullptr);
    EXPECT_EQ(scene.compound(peg), nullptr);
    // In the gap: the envelopes overlap, the parts do not.
    for (int frame = 0; frame < 2; ++frame) {
      EXPECT_EQ(scene.colliding_pairs().size(), 0) << warm;
    }
    const SceneResult near = scene.pairs_within(0.5);
    ASSERT_EQ(near.size(), 1);
    EXPECT_NEAR(near.distance(0), 0.2, 1e-9);
    EXPECT_TRUE(near.certified(0));
    // Lowered onto the base: in contact, with the base's face under the peg's four corners.
    scene.set_poses({peg}, {Pose{Matrix3::Identity(), Vector3(0, 0, -0.3)}});
    const SceneResult hits = scene.colliding_pairs();
    ASSERT_EQ(hits.size(), 1);
    EXPECT_EQ(hits.pairs(0, 0), u);
    EXPECT_TRUE(hits.certified(0));
    const ContactResult touching = scene.contacts();
    ASSERT_EQ(touching.size(), 1);
    EXPECT_NEAR(touching.distance(0), 0, 1e-9);
    EXPECT_EQ(touching.counts(0), 4);
    const SceneResult nearest = scene.nearest({far}, 1);
    ASSERT_EQ(nearest.size(), 1);
    // The other U's right post (x = 3) is 7 from this one's left post; the peg is 8.2 away.
    EXPECT_EQ(nearest.pairs(0, 1), u);
    EXPECT_NEAR(nearest.distance(0), 7, 1e-9);
  }
}

}  // namespace
}  // namespace swarmcollide
