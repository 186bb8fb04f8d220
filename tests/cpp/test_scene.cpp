// Scenes against a brute-force oracle (every pair asked of Query), poses against transformed
// vertices, and contact manifolds on boxes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <set>
#include <stdexcept>
#include <utility>
#include <vector>

#include "swarmcollide/queries/batch.hpp"
#include "swarmcollide/queries/query.hpp"
#include "swarmcollide/scene/scene.hpp"

namespace swarmcollide {
namespace {

using Pair = std::pair<BodyId, BodyId>;

Matrix3 random_rotation(std::mt19937_64& rng) {
  std::normal_distribution<Scalar> normal;
  Eigen::Quaterniond q(normal(rng), normal(rng), normal(rng), normal(rng));
  q.normalize();
  return q.toRotationMatrix();
}

// A rotation by `angle` about a random axis.
Matrix3 small_rotation(std::mt19937_64& rng, Scalar angle) {
  std::normal_distribution<Scalar> normal;
  const Vector3 axis = Vector3(normal(rng), normal(rng), normal(rng)).normalized();
  return Eigen::AngleAxisd(angle, axis).toRotationMatrix();
}

// 4 to 12 random points in a ball of radius 0.3 to 0.8, off-centre in their own frame.
ConvexPolyhedron random_body(std::mt19937_64& rng) {
  std::uniform_int_distribution<int> count(4, 12);
  std::uniform_real_distribution<Scalar> size(0.3, 0.8);
  std::normal_distribution<Scalar> normal;
  const int n = count(rng);
  const Scalar r = size(rng);
  VertexMatrix points(n, 3);
  for (int i = 0; i < n; ++i) {
    points.row(i) =
        (r * Vector3(normal(rng), normal(rng), normal(rng)).normalized() + Vector3(0.2, -0.1, 0.3))
            .transpose();
  }
  return ConvexPolyhedron(points);
}

Pose random_pose(std::mt19937_64& rng, Scalar side) {
  std::uniform_real_distribution<Scalar> where(0, side);
  return {random_rotation(rng), Vector3(where(rng), where(rng), where(rng))};
}

ConvexPolyhedron box(const Vector3& lo, const Vector3& hi) {
  VertexMatrix v(8, 3);
  for (int k = 0; k < 8; ++k) {
    v.row(k) << (k & 1 ? hi.x() : lo.x()), (k & 2 ? hi.y() : lo.y()), (k & 4 ? hi.z() : lo.z());
  }
  return ConvexPolyhedron(v);
}

ConvexPolyhedron transformed(const ConvexPolyhedron& body, const Pose& pose) {
  VertexMatrix moved = body.vertices();
  for (Eigen::Index i = 0; i < moved.rows(); ++i) {
    moved.row(i) =
        (pose.rotation * body.vertices().row(i).transpose() + pose.translation).transpose();
  }
  return ConvexPolyhedron(moved);
}

// The scene's bodies as the oracle sees them.
struct World {
  std::map<BodyId, ConvexPolyhedron> bodies;
  std::map<BodyId, Pose> poses;
  std::map<BodyId, BodyFilter> filters;
  std::set<Pair> excluded;

  bool pairable(BodyId a, BodyId b) const {
    return filters.at(a).pairs_with(filters.at(b)) &&
           excluded.count({std::min(a, b), std::max(a, b)}) == 0;
  }
  std::vector<Pair> pairs() const {
    std::vector<Pair> all;
    for (auto i = bodies.begin(); i != bodies.end(); ++i) {
      for (auto j = std::next(i); j != bodies.end(); ++j) {
        if (pairable(i->first, j->first)) all.emplace_back(i->first, j->first);
      }
    }
    return all;
  }
  DistanceResult distance(const Query& q, BodyId a, BodyId b) const {
    return q.distance(bodies.at(a), poses.at(a), bodies.at(b), poses.at(b));
  }
};

std::set<Pair> pairs_of(const SceneResult& r) {
  std::set<Pair> pairs;
  for (Eigen::Index k = 0; k < r.size(); ++k) {
    pairs.emplace(static_cast<BodyId>(r.pairs(k, 0)), static_cast<BodyId>(r.pairs(k, 1)));
  }
  return pairs;
}

// The bounds of every row enclose the exact distance, and the witnesses are that far apart.
void expect_bounds(const SceneResult& r, const World& world, const Query& exact) {
  for (Eigen::Index k = 0; k < r.size(); ++k) {
    const BodyId a = static_cast<BodyId>(r.pairs(k, 0));
    const BodyId b = static_cast<BodyId>(r.pairs(k, 1));
    const Scalar truth = world.distance(exact, a, b).distance;
    EXPECT_LE(r.lower_bound(k), truth + 1e-9) << a << "-" << b;
    EXPECT_GE(r.distance(k), truth - 1e-9) << a << "-" << b;
    EXPECT_NEAR((r.point_b.row(k) - r.point_a.row(k)).norm(), r.distance(k), 1e-9);
    EXPECT_TRUE(r.certified(k));
  }
}

// Every query of `scene` against the oracle.
void expect_matches_oracle(Scene& scene, const World& world, const std::string& where) {
  SCOPED_TRACE(where);
  const Query q(scene.options().query);
  QueryOptions exact_options = scene.options().query;
  exact_options.method = Method::exact;
  const Query exact(exact_options);
  const std::vector<Pair> all = world.pairs();

  std::set<Pair> colliding;
  std::map<Pair, Scalar> distances;
  for (const Pair& p : all) {
    const DistanceResult r = exact.distance(world.bodies.at(p.first), world.poses.at(p.first),
                                            world.bodies.at(p.second), world.poses.at(p.second));
    distances[p] = r.distance;
    if (q.collision(world.bodies.at(p.first), world.poses.at(p.first), world.bodies.at(p.second),
                    world.poses.at(p.second))
            .colliding) {
      colliding.insert(p);
    }
  }

  const SceneResult contact = scene.colliding_pairs();
  EXPECT_EQ(pairs_of(contact), colliding);
  EXPECT_EQ(scene.stats().certified, scene.stats().candidates);
  for (Eigen::Index k = 0; k < contact.size(); ++k) EXPECT_TRUE(contact.certified(k));

  for (const Scalar d : {0.05, 0.3}) {
    std::set<Pair> within;
    for (const auto& [p, distance] : distances) {
      if (distance <= d) within.insert(p);
    }
    const SceneResult r = scene.pairs_within(d);
    EXPECT_EQ(pairs_of(r), within) << "d = " << d;
    expect_bounds(r, world, exact);
  }

  const SceneResult nearest_pair = scene.min_distance();
  if (distances.empty()) {
    EXPECT_EQ(nearest_pair.size(), 0);
  } else {
    Scalar smallest = std::numeric_limits<Scalar>::infinity();
    for (const auto& [p, distance] : distances) smallest = std::min(smallest, distance);
    ASSERT_EQ(nearest_pair.size(), 1);
    EXPECT_NEAR(nearest_pair.distance(0), smallest, 1e-8);
    expect_bounds(nearest_pair, world, exact);
  }

  if (world.bodies.size() >= 3) {
    const std::vector<BodyId> asked{world.bodies.begin()->first, world.bodies.rbegin()->first};
    const SceneResult near = scene.nearest(asked, 2);
    Eigen::Index row = 0;
    for (BodyId id : asked) {
      std::vector<std::pair<Scalar, BodyId>> ranked;
      for (const auto& [p, distance] : distances) {
        if (p.first == id) ranked.emplace_back(distance, p.second);
        if (p.second == id) ranked.emplace_back(distance, p.first);
      }
      std::sort(ranked.begin(), ranked.end());
      const std::size_t expected = std::min<std::size_t>(2, ranked.size());
      for (std::size_t k = 0; k < expected; ++k, ++row) {
        ASSERT_LT(row, near.size());
        EXPECT_EQ(near.pairs(row, 0), id);
        EXPECT_NEAR(near.distance(row), ranked[k].first, 1e-8);
        // The normal points from the asker to the other body.
        if (near.distance(row) > 1e-6) {
          EXPECT_GT(near.normal.row(row).dot(near.point_b.row(row) - near.point_a.row(row)), 0);
        }
      }
    }
    EXPECT_EQ(row, near.size());
  }

  const ContactResult touching = scene.contacts();
  EXPECT_EQ(pairs_of(touching), colliding);
  for (Eigen::Index k = 0; k < touching.size(); ++k) {
    EXPECT_GE(touching.counts(k), 1);
    EXPECT_LE(touching.counts(k), 4);
    EXPECT_NEAR(touching.normal.row(k).norm(), 1, 1e-12);
    EXPECT_TRUE(touching.certified(k));
  }
}

struct SceneCase {
  Broadphase broadphase;
  bool warm_start;
};

class SceneOracle : public ::testing::TestWithParam<SceneCase> {};

TEST_P(SceneOracle, EveryQueryEqualsTheOracleThroughMovesAddsAndRemoves) {
  std::mt19937_64 rng(7 + static_cast<int>(GetParam().broadphase));
  SceneOptions options;
  options.broadphase = GetParam().broadphase;
  options.warm_start = GetParam().warm_start;
  options.threads = 2;
  Scene scene(options);
  World world;
  constexpr Scalar kSide = 4;
  const auto add = [&](int count) {
    std::vector<ConvexPolyhedron> bodies;
    std::vector<Pose> poses;
    for (int i = 0; i < count; ++i) {
      bodies.push_back(random_body(rng));
      poses.push_back(random_pose(rng, kSide));
    }
    const std::vector<BodyId> ids = scene.add(bodies, poses);
    for (int i = 0; i < count; ++i) {
      world.bodies.emplace(ids[i], bodies[i]);
      world.poses[ids[i]] = poses[i];
      world.filters[ids[i]] = {};
    }
  };
  add(30);
  expect_matches_oracle(scene, world, "first frame");
  std::normal_distribution<Scalar> step(0, 0.05);
  for (int frame = 0; frame < 3; ++frame) {
    std::vector<BodyId> ids;
    std::vector<Pose> poses;
    for (auto& [id, pose] : world.poses) {
      pose.rotation = small_rotation(rng, 0.05) * pose.rotation;
      pose.translation += Vector3(step(rng), step(rng), step(rng));
      ids.push_back(id);
      poses.push_back(pose);
    }
    scene.set_poses(ids, poses);
    expect_matches_oracle(scene, world, "small moves, frame " + std::to_string(frame));
  }
  // Far moves, some bodies added and some removed.
  std::vector<BodyId> ids;
  std::vector<Pose> poses;
  for (auto& [id, pose] : world.poses) {
    if (id % 3 == 0) {
      pose = random_pose(rng, kSide);
      ids.push_back(id);
      poses.push_back(pose);
    }
  }
  scene.set_poses(ids, poses);
  const std::vector<BodyId> gone{2, 5, 11, 17};
  scene.remove(gone);
  for (BodyId id : gone) {
    world.bodies.erase(id);
    world.poses.erase(id);
    world.filters.erase(id);
  }
  add(6);
  expect_matches_oracle(scene, world, "after moves, adds and removes");
}

INSTANTIATE_TEST_SUITE_P(Broadphases, SceneOracle,
                         ::testing::Values(SceneCase{Broadphase::dynamic_aabb_tree, true},
                                           SceneCase{Broadphase::dynamic_aabb_tree, false},
                                           SceneCase{Broadphase::sap, true},
                                           SceneCase{Broadphase::ssap, true},
                                           SceneCase{Broadphase::interval_tree, true},
                                           SceneCase{Broadphase::spatial_hashing, true},
                                           SceneCase{Broadphase::brute_force, false}),
                         [](const ::testing::TestParamInfo<SceneCase>& info) {
                           return broadphase_name(info.param.broadphase) +
                                  (info.param.warm_start ? "_warm" : "_cold");
                         });

// Frames in which a few bodies move, most a little (inside the margins of their broadphase boxes)
// and some far, with bodies removed, added, filtered and excluded between them: the scene keeps
// its pair table and asks the broadphase again only about the bodies that left their boxes. Every
// frame's contacts equal the oracle's, and its candidates those of a scene made afresh.
class ScenePairTable : public ::testing::TestWithParam<Broadphase> {};

TEST_P(ScenePairTable, FewMovingBodiesGiveTheAnswersOfAFreshScene) {
  std::mt19937_64 rng(23 + static_cast<int>(GetParam()));
  SceneOptions options;
  options.broadphase = GetParam();
  options.threads = 2;
  Scene scene(options);
  World world;
  std::map<BodyId, Vector3> velocity;
  std::normal_distribution<Scalar> normal(0, 0.01);
  std::uniform_real_distribution<Scalar> chance(0, 1);
  const auto add = [&](int count) {
    std::vector<ConvexPolyhedron> bodies;
    std::vector<Pose> poses;
    for (int i = 0; i < count; ++i) {
      bodies.push_back(random_body(rng));
      poses.push_back(random_pose(rng, 4));
    }
    const std::vector<BodyId> ids = scene.add(bodies, poses);
    for (int i = 0; i < count; ++i) {
      world.bodies.emplace(ids[i], bodies[i]);
      world.poses[ids[i]] = poses[i];
      world.filters[ids[i]] = {};
      velocity[ids[i]] = Vector3(normal(rng), normal(rng), normal(rng));
    }
  };
  const auto forget = [&](const std::vector<BodyId>& ids) {
    scene.remove(ids);
    for (BodyId id : ids) {
      world.bodies.erase(id);
      world.poses.erase(id);
      world.filters.erase(id);
      velocity.erase(id);
    }
  };
  add(40);
  const Query q(options.query);
  const BodyFilter loners{2, ~2u};
  for (int frame = 0; frame < 24; ++frame) {
    if (frame == 8) forget({3, 17});
    if (frame == 12) add(3);
    if (frame == 16) {
      scene.set_filter({5, 6, 7}, loners);
      for (BodyId id : {5, 6, 7}) world.filters[id] = loners;
    }
    if (frame == 18) {
      scene.exclude({{0, 1}, {9, 4}, {10, 11}});
      world.excluded = {{0, 1}, {4, 9}, {10, 11}};
    }
    if (frame == 21) {
      scene.include({{1, 0}});
      world.excluded.erase({0, 1});
    }
    std::vector<BodyId> ids;
    std::vector<Pose> poses;
    for (auto& [id, pose] : world.poses) {
      if (chance(rng) > 0.15) continue;
      if (chance(rng) < 0.2) {
        pose = random_pose(rng, 4);
      } else {
        pose.rotation = small_rotation(rng, 0.02) * pose.rotation;
        pose.translation += velocity[id];
      }
      ids.push_back(id);
      poses.push_back(pose);
    }
    scene.set_poses(ids, poses);
    SCOPED_TRACE("frame " + std::to_string(frame));
    std::set<Pair> colliding;
    for (const Pair& p : world.pairs()) {
      if (q.collision(world.bodies.at(p.first), world.poses.at(p.first), world.bodies.at(p.second),
                      world.poses.at(p.second))
              .colliding) {
        colliding.insert(p);
      }
    }
    const SceneResult contact = scene.colliding_pairs();
    EXPECT_EQ(pairs_of(contact), colliding);
    EXPECT_EQ(scene.stats().certified, scene.stats().candidates);
    // The same world from nothing: its ids are the world's in order.
    Scene fresh(options);
    std::vector<ConvexPolyhedron> bodies;
    std::vector<Pose> poses_now;
    std::map<BodyId, BodyId> fresh_id;
    for (const auto& [id, body] : world.bodies) {
      fresh_id[id] = static_cast<BodyId>(bodies.size());
      bodies.push_back(body);
      poses_now.push_back(world.poses.at(id));
    }
    fresh.add(bodies, poses_now);
    for (const auto& [id, filter] : world.filters) fresh.set_filter({fresh_id[id]}, filter);
    for (const Pair& p : world.excluded) fresh.exclude({{fresh_id[p.first], fresh_id[p.second]}});
    const SceneResult again = fresh.colliding_pairs();
    EXPECT_EQ(scene.stats().candidates, fresh.stats().candidates);
    EXPECT_EQ(again.size(), contact.size());
    if (frame % 6 == 5) expect_matches_oracle(scene, world, "re-padded");
  }
}

INSTANTIATE_TEST_SUITE_P(Broadphases, ScenePairTable,
                         ::testing::Values(Broadphase::dynamic_aabb_tree, Broadphase::sap,
                                           Broadphase::ssap, Broadphase::interval_tree,
                                           Broadphase::spatial_hashing, Broadphase::brute_force),
                         [](const ::testing::TestParamInfo<Broadphase>& info) {
                           return broadphase_name(info.param);
                         });

TEST(Scene, FiltersAndExclusionsRemovePairs) {
  std::mt19937_64 rng(3);
  Scene scene;
  World world;
  std::vector<ConvexPolyhedron> bodies;
  std::vector<Pose> poses;
  for (int i = 0; i < 20; ++i) {
    bodies.push_back(random_body(rng));
    poses.push_back(random_pose(rng, 2));
  }
  const std::vector<BodyId> ids = scene.add(bodies, poses);
  for (int i = 0; i < 20; ++i) {
    world.bodies.emplace(ids[i], bodies[i]);
    world.poses[ids[i]] = poses[i];
    world.filters[ids[i]] = {};
  }
  // Bodies 0-4 form group 2, which ignores itself; pairs (6, 7), (8, 9) are excluded.
  const BodyFilter loners{2, ~2u};
  scene.set_filter({0, 1, 2, 3, 4}, loners);
  for (BodyId id = 0; id < 5; ++id) world.filters[id] = loners;
  scene.exclude({{6, 7}, {9, 8}});
  world.excluded = {{6, 7}, {8, 9}};
  expect_matches_oracle(scene, world, "filtered");
  const std::set<Pair> colliding = pairs_of(scene.colliding_pairs());
  for (const Pair& p : colliding) {
    EXPECT_FALSE(p.first < 5 && p.second < 5);
    EXPECT_FALSE(p == Pair(6, 7) || p == Pair(8, 9));
  }
  scene.include({{7, 6}});
  world.excluded = {{8, 9}};
  expect_matches_oracle(scene, world, "one exclusion lifted");
}

TEST(Scene, ExclusionsAndIdsCanBeReadAndIdsSkipped) {
  std::mt19937_64 rng(5);
  Scene scene;
  for (int i = 0; i < 6; ++i) scene.add(random_body(rng), random_pose(rng, 2));
  EXPECT_EQ(scene.next_id(), 6u);
  scene.exclude({{4, 1}, {0, 5}, {2, 3}});
  scene.include({{3, 2}});
  EXPECT_EQ(scene.excluded(), (std::vector<Pair>{{0, 5}, {1, 4}}));
  // Removing a body drops its exclusions, and its id is not given again.
  scene.remove({5});
  EXPECT_EQ(scene.excluded(), (std::vector<Pair>{{1, 4}}));
  EXPECT_EQ(scene.next_id(), 6u);
  scene.skip_ids(9);
  EXPECT_EQ(scene.add(random_body(rng)), 9u);
  EXPECT_FALSE(scene.contains(6) || scene.contains(7) || scene.contains(8));
  EXPECT_EQ(scene.ids(), (std::vector<BodyId>{0, 1, 2, 3, 4, 9}));
  EXPECT_THROW(scene.skip_ids(9), std::invalid_argument);
  EXPECT_THROW(scene.set_poses({7}, {Pose{}}), std::invalid_argument);
}

TEST(Scene, WithoutWarmStartsAnswersDoNotDependOnHistoryOrThreads) {
  std::mt19937_64 rng(11);
  std::vector<ConvexPolyhedron> bodies;
  std::vector<Pose> start;
  std::vector<Pose> end;
  for (int i = 0; i < 40; ++i) {
    bodies.push_back(random_body(rng));
    start.push_back(random_pose(rng, 4));
    end.push_back(random_pose(rng, 4));
  }
  std::vector<BodyId> ids(40);
  for (BodyId i = 0; i < 40; ++i) ids[i] = i;
  SceneOptions cold;
  cold.warm_start = false;
  cold.threads = 1;
  Scene travelled(cold);
  travelled.add(bodies, start);
  travelled.colliding_pairs();
  travelled.pairs_within(0.2);
  travelled.set_poses(ids, end);
  cold.threads = 2;
  cold.broadphase = Broadphase::sap;
  Scene fresh(cold);
  fresh.add(bodies, end);
  const SceneResult a = travelled.pairs_within(0.2);
  const SceneResult b = fresh.pairs_within(0.2);
  ASSERT_EQ(a.pairs, b.pairs);
  EXPECT_EQ(a.distance, b.distance);
  EXPECT_EQ(a.lower_bound, b.lower_bound);
  EXPECT_EQ(a.point_a, b.point_a);
  EXPECT_EQ(a.normal, b.normal);
  const ContactResult ca = travelled.contacts();
  const ContactResult cb = fresh.contacts();
  EXPECT_EQ(ca.points, cb.points);
}

// Bodies closing in on each other a little each frame, by turning and by translation, inside
// each other's boxes (so the pairs are candidates while still apart): the cached bounds less the
// motion since must never hide the frame where they meet.
TEST(Scene, CachedBoundsNeverHideAPairMovingIntoContact) {
  const ConvexPolyhedron rod = box(Vector3(-1, -0.05, -0.05), Vector3(1, 0.05, 0.05));
  const ConvexPolyhedron cube = box(Vector3(-0.2, -0.2, -0.2), Vector3(0.2, 0.2, 0.2));
  Scene scene;
  // A diagonal rod turning towards a cube in a corner of its box; another cube sliding towards
  // it from the opposite corner.
  const auto rod_pose = [](int frame) {
    return Pose{Eigen::AngleAxisd(M_PI / 4 - 0.004 * frame, Vector3::UnitZ()).toRotationMatrix(),
                Vector3::Zero()};
  };
  const auto slide_pose = [](int frame) {
    return Pose{Matrix3::Identity(), Vector3(-0.6 + 0.0015 * frame, 0.6 - 0.0015 * frame, 0)};
  };
  const Pose still{Matrix3::Identity(), Vector3(0.7, 0.05, 0)};
  const BodyId turning = scene.add(rod, rod_pose(0));
  const BodyId fixed = scene.add(cube, still);
  const BodyId sliding = scene.add(cube, slide_pose(0));
  const Query q;
  bool met_turning = false;
  bool met_sliding = false;
  std::size_t bounded = 0;
  for (int frame = 1; frame <= 250; ++frame) {
    scene.set_poses({turning, sliding}, {rod_pose(frame), slide_pose(frame)});
    const std::set<Pair> found = pairs_of(scene.colliding_pairs());
    bounded += scene.stats().warm_bounded;
    const bool touches_fixed = q.collide(rod, rod_pose(frame), cube, still);
    const bool touches_sliding = q.collide(rod, rod_pose(frame), cube, slide_pose(frame));
    EXPECT_EQ(found.count({turning, fixed}) == 1, touches_fixed) << "frame " << frame;
    EXPECT_EQ(found.count({turning, sliding}) == 1, touches_sliding) << "frame " << frame;
    met_turning = met_turning || touches_fixed;
    met_sliding = met_sliding || touches_sliding;
  }
  EXPECT_TRUE(met_turning);
  EXPECT_TRUE(met_sliding);
  EXPECT_GT(bounded, 0u);  // the bounds did settle frames on the way
}

TEST(Scene, WarmFramesSettleMostPairsFromTheCache) {
  std::mt19937_64 rng(5);
  Scene scene;
  std::vector<BodyId> ids;
  std::vector<Pose> poses;
  for (int i = 0; i < 60; ++i) {
    poses.push_back(random_pose(rng, 4));
    ids.push_back(scene.add(random_body(rng), poses.back()));
  }
  scene.colliding_pairs();
  const SceneStats cold = scene.stats();
  EXPECT_EQ(cold.warm_bounded + cold.warm_rejected + cold.warm_proven, 0u);
  EXPECT_GT(cold.cached_pairs, 0u);
  EXPECT_EQ(cold.cache_bytes / std::max<std::size_t>(cold.cached_pairs, 1) >= 48, true);
  for (Pose& p : poses) p.translation += Vector3(1e-3, -2e-3, 1e-3);
  scene.set_poses(ids, poses);
  scene.colliding_pairs();
  const SceneStats warm = scene.stats();
  EXPECT_EQ(warm.candidates, cold.candidates);
  EXPECT_GE(warm.warm_bounded + warm.warm_rejected + warm.warm_proven, warm.candidates * 8 / 10);
  EXPECT_GT(warm.warm_bounded, 0u);
  EXPECT_EQ(warm.certified, warm.candidates);
}

TEST(Scene, PosesEqualTransformedVertices) {
  std::mt19937_64 rng(13);
  const Query q;
  for (int trial = 0; trial < 20; ++trial) {
    const ConvexPolyhedron a = random_body(rng);
    const ConvexPolyhedron b = random_body(rng);
    const Pose pa = random_pose(rng, 1.5);
    const Pose pb = random_pose(rng, 1.5);
    const ConvexPolyhedron wa = transformed(a, pa);
    const ConvexPolyhedron wb = transformed(b, pb);
    const DistanceResult posed = q.distance(a, pa, b, pb);
    const DistanceResult moved = q.distance(wa, wb);
    EXPECT_NEAR(posed.distance, moved.distance, 1e-9);
    EXPECT_EQ(q.collide(a, pa, b, pb), q.collide(wa, wb));
    const DistanceResult signed_posed = q.signed_distance(a, pa, b, pb);
    const DistanceResult signed_moved = q.signed_distance(wa, wb);
    EXPECT_NEAR(signed_posed.distance, signed_moved.distance, 1e-9);
    // Witnesses in world coordinates: on the transformed bodies.
    EXPECT_NEAR((posed.point_b - posed.point_a).norm(), posed.distance, 1e-12);
    Vector3 from_weights = Vector3::Zero();
    const VectorX wts = posed.weights_a.dense();
    for (int i = 0; i < wa.size(); ++i) from_weights += wts(i) * wa.vertices().row(i).transpose();
    EXPECT_LT((from_weights - posed.point_a).norm(), 1e-12);
  }
}

TEST(Scene, BatchesTakePoses) {
  std::mt19937_64 rng(17);
  std::vector<ConvexPolyhedron> as;
  std::vector<ConvexPolyhedron> bs;
  BatchPoses poses;
  std::vector<ConvexPolyhedron> was;
  std::vector<ConvexPolyhedron> wbs;
  for (int i = 0; i < 12; ++i) {
    as.push_back(random_body(rng));
    bs.push_back(random_body(rng));
    poses.a.push_back(random_pose(rng, 1.5));
    poses.b.push_back(random_pose(rng, 1.5));
    was.push_back(transformed(as.back(), poses.a.back()));
    wbs.push_back(transformed(bs.back(), poses.b.back()));
  }
  const BatchResult posed = distance_many(as, bs, {}, {}, poses);
  const BatchResult moved = distance_many(was, wbs, {});
  for (int i = 0; i < 12; ++i) EXPECT_NEAR(posed.distance(i), moved.distance(i), 1e-9);
  const BatchResult collide_posed = collide_many(as, bs, {}, {}, poses);
  EXPECT_TRUE((collide_posed.colliding == collide_many(was, wbs, {}).colliding).all());
  poses.b.pop_back();
  EXPECT_THROW(distance_many(as, bs, {}, {}, poses), std::invalid_argument);
}

// Unit cube A; B placed by `pose` on top of it. Returns the contacts of the pair both ways.
std::pair<ContactResult, ContactResult> contacts_of(const ConvexPolyhedron& b, const Pose& pose) {
  const ConvexPolyhedron a = box(Vector3::Zero(), Vector3::Ones());
  ContactResult forward;
  ContactResult backward;
  {
    Scene scene;
    scene.add(a);
    scene.add(b, pose);
    forward = scene.contacts();
  }
  {
    Scene scene;
    scene.add(b, pose);
    scene.add(a);
    backward = scene.contacts();
  }
  return {forward, backward};
}

// The same points, in any order.
void expect_same_points(const VertexMatrix& p, const VertexMatrix& q) {
  ASSERT_EQ(p.rows(), q.rows());
  for (Eigen::Index i = 0; i < p.rows(); ++i) {
    Scalar nearest = std::numeric_limits<Scalar>::infinity();
    for (Eigen::Index j = 0; j < q.rows(); ++j)
      nearest = std::min(nearest, (p.row(i) - q.row(j)).norm());
    EXPECT_LT(nearest, 1e-9);
  }
}

TEST(SceneContacts, BoxRestingOnBoxGivesTheFourCornersOfTheOverlap) {
  const ConvexPolyhedron b = box(Vector3(0.25, 0.5, 0), Vector3(1.75, 2, 0.5));
  const Pose on_top{Matrix3::Identity(), Vector3(0, 0, 1)};
  const auto [forward, backward] = contacts_of(b, on_top);
  ASSERT_EQ(forward.size(), 1);
  EXPECT_EQ(forward.counts(0), 4);
  EXPECT_NEAR(forward.distance(0), 0, 1e-12);
  EXPECT_LT((forward.normal.row(0) - Eigen::RowVector3d(0, 0, 1)).norm(), 1e-9);
  VertexMatrix corners(4, 3);
  corners << 0.25, 0.5, 1, 1, 0.5, 1, 1, 1, 1, 0.25, 1, 1;
  expect_same_points(forward.points, corners);
  // Swapped: the same points, the normal reversed.
  ASSERT_EQ(backward.size(), 1);
  EXPECT_LT((backward.normal.row(0) + forward.normal.row(0)).norm(), 1e-9);
  expect_same_points(backward.points, forward.points);
}

TEST(SceneContacts, OverlappingBoxesGiveTheOverlapPolygonHalfwayBetweenTheFaces) {
  const ConvexPolyhedron b = box(Vector3(0.25, 0.25, 0), Vector3(0.75, 0.75, 1));
  const Pose sunk{Matrix3::Identity(), Vector3(0, 0, 0.9)};  // 0.1 deep
  const auto [forward, backward] = contacts_of(b, sunk);
  ASSERT_EQ(forward.size(), 1);
  EXPECT_NEAR(forward.distance(0), -0.1, 1e-9);
  EXPECT_TRUE(forward.certified(0));
  EXPECT_EQ(forward.counts(0), 4);
  for (Eigen::Index i = 0; i < forward.points.rows(); ++i) {
    EXPECT_NEAR(forward.points(i, 2), 0.95, 1e-9);
  }
  expect_same_points(backward.points, forward.points);
}

TEST(SceneContacts, EdgeOnFaceGivesTwoPoints) {
  // A unit cube turned 45 degrees about x, its lowest edge resting on A's top face.
  const ConvexPolyhedron b = box(Vector3(-0.5, -0.5, -0.5), Vector3(0.5, 0.5, 0.5));
  const Matrix3 turn = Eigen::AngleAxisd(M_PI / 4, Vector3::UnitX()).toRotationMatrix();
  const Pose on_edge{turn, Vector3(0.5, 0.5, 1 + std::sqrt(0.5))};
  const auto [forward, backward] = contacts_of(b, on_edge);
  ASSERT_EQ(forward.size(), 1);
  EXPECT_EQ(forward.counts(0), 2);
  VertexMatrix ends(2, 3);
  ends << 0, 0.5, 1, 1, 0.5, 1;
  expect_same_points(forward.points, ends);
  EXPECT_LT((forward.normal.row(0) - Eigen::RowVector3d(0, 0, 1)).norm(), 1e-9);
  EXPECT_EQ(backward.counts(0), 2);
  expect_same_points(backward.points, forward.points);
  EXPECT_LT((backward.normal.row(0) + forward.normal.row(0)).norm(), 1e-9);
}

TEST(SceneContacts, VertexOnFaceGivesOnePoint) {
  // A cube balanced on a corner: its body diagonal vertical.
  const ConvexPolyhedron b = box(Vector3(-0.5, -0.5, -0.5), Vector3(0.5, 0.5, 0.5));
  const Matrix3 turn =
      Eigen::Quaterniond::FromTwoVectors(Vector3(-1, -1, -1).normalized(), -Vector3::UnitZ())
          .toRotationMatrix();
  const Pose on_corner{turn, Vector3(0.5, 0.5, 1 + std::sqrt(0.75))};
  const auto [forward, backward] = contacts_of(b, on_corner);
  ASSERT_EQ(forward.size(), 1);
  EXPECT_EQ(forward.counts(0), 1);
  EXPECT_LT((forward.points.row(0) - Eigen::RowVector3d(0.5, 0.5, 1)).norm(), 1e-9);
  EXPECT_EQ(backward.counts(0), 1);
  expect_same_points(backward.points, forward.points);
}

TEST(SceneContacts, MaxPointsKeepsTheCornersSpanningTheMostArea) {
  // Two squares, one turned 45 degrees: their overlap is an octagon.
  const ConvexPolyhedron b = box(Vector3(-0.5, -0.5, 0), Vector3(0.5, 0.5, 1));
  const Matrix3 turn = Eigen::AngleAxisd(M_PI / 4, Vector3::UnitZ()).toRotationMatrix();
  const ConvexPolyhedron a = box(Vector3(-0.5, -0.5, -1), Vector3(0.5, 0.5, 0));
  Scene scene;
  scene.add(a);
  scene.add(b, {turn, Vector3::Zero()});
  for (int max_points : {1, 2, 3, 4, 8}) {
    const ContactResult r = scene.contacts(max_points);
    ASSERT_EQ(r.size(), 1);
    EXPECT_EQ(r.counts(0), max_points);
  }
  EXPECT_THROW(scene.contacts(0), std::invalid_argument);
}

TEST(Scene, SearchesEndWhenNoPairCanBeFound) {
  // Two copies of one point that may not pair, and a third body far away that pairs with none.
  VertexMatrix point(1, 3);
  point << 1, 2, 3;
  Scene scene;
  const BodyFilter loner{2, 0};
  scene.add({ConvexPolyhedron(point), ConvexPolyhedron(point)}, {}, loner);
  EXPECT_EQ(scene.min_distance().size(), 0);
  EXPECT_EQ(scene.nearest({0, 1}, 3).size(), 0);
  scene.add(box(Vector3::Constant(1e6), Vector3::Constant(1e6 + 1)), {}, loner);
  EXPECT_EQ(scene.min_distance().size(), 0);
  scene.set_filter({2}, {});
  scene.set_filter({0}, {});
  const SceneResult nearest = scene.nearest({0}, 2);
  ASSERT_EQ(nearest.size(), 1);
  EXPECT_EQ(nearest.pairs(0, 1), 2);
}

// The search's end is the extent of the bodies as they are now: two cubes that moved 99 apart
// since the last query are still a pair.
TEST(Scene, MinDistanceSearchesAsFarAsBodiesMovedSinceTheLastQuery) {
  const ConvexPolyhedron cube = box(Vector3::Zero(), Vector3::Ones());
  Scene scene;
  scene.add({cube, cube}, {Pose{}, Pose{Matrix3::Identity(), Vector3(2, 0, 0)}});
  scene.colliding_pairs();
  scene.set_poses({1}, {Pose{Matrix3::Identity(), Vector3(100, 0, 0)}});
  const SceneResult nearest = scene.min_distance();
  ASSERT_EQ(nearest.size(), 1);
  EXPECT_NEAR(nearest.distance(0), 99, 1e-6);
}

TEST(Scene, RejectsWhatItCannotAnswer) {
  Scene scene;
  const BodyId id = scene.add(box(Vector3::Zero(), Vector3::Ones()));
  EXPECT_THROW(scene.set_poses({id + 1}, {Pose{}}), std::invalid_argument);
  Pose scaled;
  scaled.rotation *= 2;
  EXPECT_THROW(scene.set_poses({id}, {scaled}), std::invalid_argument);
  EXPECT_THROW(scene.add({box(Vector3::Zero(), Vector3::Ones())}, {Pose{}, Pose{}}),
               std::invalid_argument);
  EXPECT_THROW(scene.remove({id, id}), std::invalid_argument);
  EXPECT_THROW(scene.set_poses({id, id}, {Pose{}, Pose{}}), std::invalid_argument);
  EXPECT_THROW(scene.pairs_within(-1), std::invalid_argument);
  EXPECT_THROW(scene.nearest({id}, 0), std::invalid_argument);
  EXPECT_THROW(scene.exclude({{id, id}}), std::invalid_argument);
  EXPECT_THROW(scene.include({{id, id + 1}}), std::invalid_argument);
  // Beyond 1e150 FCL's trees square box extents past the double range: refused, not crashed.
  Pose far;
  far.translation.x() = 1e155;
  const ConvexPolyhedron unit = box(Vector3::Zero(), Vector3::Ones());
  EXPECT_THROW(scene.add({unit, unit}, {Pose{}, far}), std::invalid_argument);
  EXPECT_THROW(scene.set_poses({id}, {far}), std::invalid_argument);
  EXPECT_THROW(scene.pairs_within(1e200), std::invalid_argument);
  EXPECT_EQ(scene.size(), 1u);
  EXPECT_EQ(scene.min_distance().size(), 0);
  EXPECT_EQ(scene.nearest({id}).size(), 0);
  SceneOptions loose;
  loose.query.tolerance = 0.5;
  EXPECT_THROW(Scene{loose}, std::invalid_argument);
  SceneOptions no_distance;
  no_distance.query.method = Method::libccd;
  Scene ccd(no_distance);
  EXPECT_THROW(ccd.pairs_within(1), std::invalid_argument);
  EXPECT_NO_THROW(ccd.colliding_pairs());
  EXPECT_THROW(broadphase_from_name("octree"), std::invalid_argument);
  EXPECT_EQ(broadphase_from_name("sap"), Broadphase::sap);
  try {
    broadphase_from_name("dynamic_aabb_tree_array");
    ADD_FAILURE() << "FCL's array tree is offered";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("use 'dynamic_aabb_tree'"), std::string::npos);
  }
}

}  // namespace
}  // namespace swarmcollide
