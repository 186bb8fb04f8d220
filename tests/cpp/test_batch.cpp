// Batches: each pair is the single query with its own seed, whatever the threads and however the
// batch is split; errors name the lowest failing pair.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "paper_cases.hpp"
#include "queries/ball_screen.hpp"
#include "shapes.hpp"
#include "swarmcollide/geometry/shapes.hpp"
#include "swarmcollide/queries/batch.hpp"
#include "swarmcollide/queries/methods.hpp"
#include "swarmcollide/queries/query.hpp"

namespace swarmcollide::testing {
namespace {

// `count` pairs of random 6-point bodies, B's centres spread from overlapping to well apart.
struct Pairs {
  std::vector<ConvexPolyhedron> as;
  std::vector<ConvexPolyhedron> bs;
};

Pairs random_pairs(int count, std::uint64_t seed) {
  Random rng(seed);
  Pairs pairs;
  for (int i = 0; i < count; ++i) {
    pairs.as.push_back(rng.body(6));
    pairs.bs.push_back(rng.body(6, rng.vector(2.5)));
  }
  return pairs;
}

void expect_same(const BatchResult& x, const BatchResult& y) {
  EXPECT_EQ(x.distance, y.distance);
  EXPECT_EQ(x.lower_bound, y.lower_bound);
  EXPECT_EQ(x.point_a, y.point_a);
  EXPECT_EQ(x.point_b, y.point_b);
  EXPECT_EQ(x.direction, y.direction);
  EXPECT_TRUE((x.colliding == y.colliding).all());
  EXPECT_TRUE((x.certified == y.certified).all());
  EXPECT_TRUE((x.iterations == y.iterations).all());
  EXPECT_TRUE((x.escalated == y.escalated).all());
}

// The rows of `whole` from `first` on.
void expect_rows(const BatchResult& part, const BatchResult& whole, Eigen::Index first) {
  const Eigen::Index n = part.distance.size();
  EXPECT_EQ(part.distance, whole.distance.segment(first, n));
  EXPECT_EQ(part.point_a, whole.point_a.middleRows(first, n));
  EXPECT_TRUE((part.colliding == whole.colliding.segment(first, n)).all());
  EXPECT_TRUE((part.iterations == whole.iterations.segment(first, n)).all());
}

QueryOptions seeded(Method method) {
  QueryOptions options;
  options.method = method;
  options.seed = 5;
  options.swarm.max_iterations = 20;
  return options;
}

TEST(Batch, EachPairIsTheSingleQueryWithItsDerivedSeed) {
  const Pairs p = random_pairs(70, 3);
  for (Method m : {Method::ipso, Method::dual, Method::fcl}) {
    SCOPED_TRACE(method_name(m));
    const QueryOptions options = seeded(m);
    const BatchResult batch = distance_many(p.as, p.bs, options, {2});
    for (std::size_t i : {0u, 17u, 64u, 69u}) {
      QueryOptions single = options;
      single.seed = pair_seed(options.seed, i);
      const DistanceResult r = Query(single).distance(p.as[i], p.bs[i]);
      const auto row = static_cast<Eigen::Index>(i);
      EXPECT_EQ(batch.distance(row), r.distance);
      EXPECT_EQ(batch.lower_bound(row), r.lower_bound);
      EXPECT_EQ(batch.point_b.row(row), r.point_b.transpose());
      EXPECT_EQ(batch.direction.row(row), r.direction.transpose());
      EXPECT_EQ(batch.certified(row), r.certified);
      EXPECT_EQ(batch.iterations(row), r.iterations);
    }
    const BatchResult verdicts = collide_many(p.as, p.bs, options, {2});
    const BatchResult depths = signed_distance_many(p.as, p.bs, seeded(Method::dual), {2});
    for (std::size_t i : {5u, 66u}) {
      QueryOptions single = options;
      single.seed = pair_seed(options.seed, i);
      const DistanceResult decided = Query(single).collision(p.as[i], p.bs[i]);
      EXPECT_EQ(verdicts.colliding(i), decided.colliding);
      EXPECT_EQ(verdicts.escalated(i), decided.escalated_from.has_value());
      single.method = Method::dual;
      EXPECT_EQ(depths.distance(i), Query(single).signed_distance(p.as[i], p.bs[i]).distance);
    }
  }
}

TEST(Batch, AnswersDoNotDependOnTheThreadCount) {
  const Pairs p = random_pairs(150, 4);
  for (Method m : {Method::ipso, Method::dual}) {
    const BatchResult one = distance_many(p.as, p.bs, seeded(m), {1});
    for (int threads : {2, 3, 0}) expect_same(one, distance_many(p.as, p.bs, seeded(m), {threads}));
  }
}

// A batch split into parts, each told its first global index, answers as the whole.
TEST(Batch, PartsWithTheirFirstIndexAnswerAsTheWhole) {
  const Pairs p = random_pairs(100, 5);
  const QueryOptions options = seeded(Method::ipso);
  const BatchResult whole = distance_many(p.as, p.bs, options, {2});
  for (std::size_t cut : {1u, 37u, 64u}) {
    const std::vector<ConvexPolyhedron> head_a(p.as.begin(), p.as.begin() + cut);
    const std::vector<ConvexPolyhedron> head_b(p.bs.begin(), p.bs.begin() + cut);
    const std::vector<ConvexPolyhedron> tail_a(p.as.begin() + cut, p.as.end());
    const std::vector<ConvexPolyhedron> tail_b(p.bs.begin() + cut, p.bs.end());
    BatchSettings settings;
    settings.threads = 2;
    expect_rows(distance_many(head_a, head_b, options, settings), whole, 0);
    settings.first_index = cut;
    expect_rows(distance_many(tail_a, tail_b, options, settings), whole,
                static_cast<Eigen::Index>(cut));
  }
}

TEST(Batch, VertexStacksGiveTheAnswersOfTheBodiesTheyHold) {
  Random rng(6);
  const int pairs = 80, vertices = 7;
  std::vector<double> points_a(pairs * vertices * 3), points_b(points_a.size());
  for (double& x : points_a) x = rng.uniform();
  for (double& x : points_b) x = rng.uniform() + 1.5;
  std::vector<ConvexPolyhedron> as, bs;
  for (int i = 0; i < pairs; ++i) {
    as.emplace_back(Eigen::Map<const VertexMatrix>(&points_a[i * vertices * 3], vertices, 3));
    bs.emplace_back(Eigen::Map<const VertexMatrix>(&points_b[i * vertices * 3], vertices, 3));
  }
  const VertexStack stack_a{points_a.data(), pairs, vertices, "As"};
  const VertexStack stack_b{points_b.data(), pairs, vertices, "Bs"};
  const QueryOptions options = seeded(Method::ipso);
  expect_same(distance_many(stack_a, stack_b, options, {2}), distance_many(as, bs, options, {1}));
  // Bodies built row by row have no hull for the face screens: the same verdicts, whose bounds may
  // come from another screen or the solver but bracket the same distances.
  const BatchResult stacked = collide_many(stack_a, stack_b, options, {2});
  const BatchResult built = collide_many(as, bs, options, {1});
  EXPECT_TRUE((stacked.colliding == built.colliding).all());
  EXPECT_TRUE((stacked.certified == built.certified).all());
  EXPECT_TRUE((stacked.lower_bound.array() <= built.distance.array()).all());
  EXPECT_TRUE((built.lower_bound.array() <= stacked.distance.array()).all());
  const QueryOptions dual = seeded(Method::dual);
  expect_same(signed_distance_many(stack_a, stack_b, dual, {2}),
              signed_distance_many(as, bs, dual, {1}));
}

TEST(Batch, CollideManyEscalatesOnlyWhenAsked) {
  // 1e-10 apart (within the tolerance): a swarm without iterations cannot prove either verdict.
  VertexMatrix near(4, 3);
  near << 1, -1e-10, 0, 2, -2, 0, 0, -2, 2, 0, -2, 0;
  const std::vector<ConvexPolyhedron> as{paper_a()};
  const std::vector<ConvexPolyhedron> bs{ConvexPolyhedron(near)};
  QueryOptions options = seeded(Method::ipso);
  options.swarm.max_iterations = 0;
  const BatchResult decided = collide_many(as, bs, options);
  EXPECT_TRUE(decided.escalated(0));
  EXPECT_TRUE(decided.certified(0));
  EXPECT_TRUE(decided.colliding(0));
  BatchSettings raw;
  raw.escalate = false;
  const BatchResult own = collide_many(as, bs, options, raw);
  EXPECT_FALSE(own.escalated(0));
  EXPECT_FALSE(own.certified(0));
}

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

// Pairs 5 and 40 fail (bodies whose distance exceeds the double range); whatever thread meets
// which first, the error is pair 5's, named by its global index.
TEST(Batch, TheLowestFailingPairIsReported) {
  Pairs p = random_pairs(120, 7);
  for (std::size_t bad : {5u, 40u}) {
    p.as[bad] = point_set({{1.5e308, 0, 0}});
    p.bs[bad] = point_set({{-1.5e308, 0, 0}});
  }
  for (int threads : {1, 2, 4}) {
    BatchSettings settings;
    settings.threads = threads;
    const std::string message =
        error_of([&] { distance_many(p.as, p.bs, seeded(Method::dual), settings); });
    EXPECT_EQ(message.rfind("pair 5: ", 0), 0u) << message;
    settings.first_index = 1000;
    const std::string offset =
        error_of([&] { collide_many(p.as, p.bs, seeded(Method::dual), settings); });
    EXPECT_EQ(offset.rfind("pair 1005: ", 0), 0u) << offset;
  }
}

TEST(Batch, AStackBodyThatCannotBeBuiltIsNamedByItsGlobalIndex) {
  std::vector<double> points = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
  points.insert(points.end(), points.begin(), points.end());
  std::vector<double> broken = points;
  broken[4 * 3 + 5] = std::numeric_limits<double>::quiet_NaN();  // body 1, point 1
  const VertexStack good{points.data(), 2, 4, "As"};
  const VertexStack bad{broken.data(), 2, 4, "Bs"};
  BatchSettings settings;
  settings.first_index = 10;
  const std::string message = error_of([&] { distance_many(good, bad, {}, settings); });
  EXPECT_EQ(message.rfind("Bs[11]: ", 0), 0u) << message;
}

TEST(Batch, SettingsAndLengthsAreChecked) {
  const std::vector<ConvexPolyhedron> one{paper_a()};
  const std::vector<ConvexPolyhedron> two{paper_a(), paper_b_separate()};
  EXPECT_NE(error_of([&] { distance_many(one, two, {}); }).find("same length, got 1 and 2"),
            std::string::npos);
  for (int threads : {-1, kMaxThreads + 1}) {
    BatchSettings settings;
    settings.threads = threads;
    EXPECT_NE(error_of([&] { distance_many(two, two, {}, settings); }).find("threads must be in"),
              std::string::npos)
        << threads;
  }
  BatchSettings most;
  most.threads = kMaxThreads;  // no more threads than pairs are started
  EXPECT_EQ(distance_many(two, two, {}, most).distance.size(), 2);
  QueryOptions invalid;
  invalid.dual.swarm_size = 1;
  EXPECT_NE(error_of([&] { distance_many(two, two, invalid); }).find("swarm_size"),
            std::string::npos);
  const std::vector<ConvexPolyhedron> none;
  EXPECT_EQ(distance_many(none, none, {}).distance.size(), 0);
}

// Random rigid poses, B's centres from overlapping A to well apart.
std::vector<Pose> random_poses(int count, Random& rng, Scalar spread) {
  std::vector<Pose> poses(static_cast<std::size_t>(count));
  for (Pose& pose : poses) {
    pose.rotation = rng.rotation();
    pose.translation = rng.vector(spread);
  }
  return poses;
}

// One body on a side serves every row: the answers are those of the body repeated in a sequence,
// and of the single queries, row by row, for every kind of batch.
TEST(Batch, ASingleBodyServesEveryRow) {
  Random rng(8);
  const ConvexPolyhedron a = rng.body(40);
  const ConvexPolyhedron b = rng.body(9);
  BatchPoses poses;
  poses.a = random_poses(90, rng, 0.5);
  poses.b = random_poses(90, rng, 2.5);
  const std::vector<ConvexPolyhedron> as(90, a), bs(90, b);
  const QueryOptions options = seeded(Method::dual);
  const BatchSettings two{2};
  expect_same(distance_many(a, b, options, two, poses), distance_many(as, bs, options, two, poses));
  expect_same(collide_many(a, bs, options, two, poses), collide_many(as, b, options, two, poses));
  expect_same(signed_distance_many(as, b, options, two, poses),
              signed_distance_many(as, bs, options, two, poses));
  const BatchResult distances = distance_many(a, b, options, two, poses);
  for (std::size_t i : {0u, 31u, 89u}) {
    QueryOptions single = options;
    single.seed = pair_seed(options.seed, i);
    const DistanceResult r = Query(single).distance(a, poses.a[i], b, poses.b[i]);
    EXPECT_EQ(distances.distance(static_cast<Eigen::Index>(i)), r.distance);
    EXPECT_EQ(distances.point_a.row(static_cast<Eigen::Index>(i)), r.point_a.transpose());
  }
  // Single bodies on both sides: the poses count the rows, and without poses there is one.
  BatchPoses only_b;
  only_b.b = poses.b;
  EXPECT_EQ(distance_many(a, b, options, two, only_b).distance.size(), 90);
  EXPECT_EQ(distance_many(a, b, options).distance.size(), 1);
  const std::vector<CompoundBody> compounds(90, CompoundBody({a}));
  expect_same(distance_many(CompoundBody({a}), CompoundBody({b}), options, two, poses),
              distance_many(compounds, std::vector<CompoundBody>(90, CompoundBody({b})), options,
                            two, poses));
}

// Every row of a collision batch keeps valid bounds, whether its bodies' balls settled it or a
// solver did: the lower bound is at most, and the distance at least, the exact distance.
TEST(Batch, CollisionsSettledByBallsKeepValidBounds) {
  Random rng(9);
  const ConvexPolyhedron a = rng.body(30);
  const ConvexPolyhedron b = rng.body(12);
  BatchPoses poses;
  poses.b = random_poses(300, rng, 4);
  QueryOptions options;
  const BatchResult verdicts = collide_many(a, b, options, {2}, poses);
  QueryOptions exact;
  exact.method = Method::exact;
  exact.tolerance = 0;
  int settled_by_balls = 0;
  for (std::size_t i = 0; i < 300; ++i) {
    const auto row = static_cast<Eigen::Index>(i);
    const DistanceResult truth = Query(exact).distance(a, {}, b, poses.b[i]);
    const Scalar rounding = 1e-12;
    EXPECT_LE(verdicts.lower_bound(row), truth.distance + rounding) << i;
    EXPECT_GE(verdicts.distance(row), truth.lower_bound - rounding) << i;
    EXPECT_TRUE(verdicts.certified(row)) << i;
    EXPECT_EQ(verdicts.colliding(row), truth.colliding) << i;
    // The witnesses are the bodies' first points, placed; the direction is a unit vector.
    const Vector3 first_b = poses.b[i].rotation * b.vertices().row(0).transpose() +
                            poses.b[i].translation;
    if (verdicts.iterations(row) == 0 && !verdicts.colliding(row) &&
        (verdicts.point_b.row(row).transpose() - first_b).norm() < 1e-12) {
      ++settled_by_balls;
      EXPECT_NEAR(verdicts.direction.row(row).norm(), 1, 1e-12);
    }
  }
  EXPECT_GT(settled_by_balls, 30);  // the spread puts many pairs beyond their balls
}

// Answers are bitwise the same whatever the threads, and whatever the batch is cut into.
TEST(Batch, PosedBatchesAnswerAlikeOnAnyThreadsAndCuts) {
  Random rng(10);
  const ConvexPolyhedron a = rng.body(50);
  const ConvexPolyhedron b = rng.body(8);
  BatchPoses poses;
  poses.b = random_poses(200, rng, 3);
  const QueryOptions options = seeded(Method::dual);
  const BatchResult one = collide_many(a, b, options, {1}, poses);
  for (int threads : {2, 3, 7}) expect_same(one, collide_many(a, b, options, {threads}, poses));
  const BatchResult whole = distance_many(a, b, options, {1}, poses);
  for (int threads : {2, 5}) expect_same(whole, distance_many(a, b, options, {threads}, poses));
  for (std::size_t cut : {1u, 63u, 130u}) {
    BatchPoses tail;
    tail.b.assign(poses.b.begin() + static_cast<std::ptrdiff_t>(cut), poses.b.end());
    BatchSettings settings;
    settings.threads = 2;
    settings.first_index = cut;
    expect_rows(distance_many(a, b, options, settings, tail), whole,
                static_cast<Eigen::Index>(cut));
  }
}

// The smallest of `h(n) - n . centre` over the hull's facet normals n, h the support function:
// the radius of the largest ball about `centre` inside the body (up to rounding).
Scalar largest_inner_radius(const ConvexPolyhedron& body, const Vector3& centre) {
  const Hull& hull = body.hull();
  Scalar radius = std::numeric_limits<Scalar>::infinity();
  for (Eigen::Index f = 0; f < hull.faces.rows(); ++f) {
    const Vector3 p = body.vertices().row(hull.faces(f, 0)).transpose();
    const Vector3 n = (body.vertices().row(hull.faces(f, 1)).transpose() - p)
                          .cross(body.vertices().row(hull.faces(f, 2)).transpose() - p)
                          .normalized();
    radius = std::min(radius, n.dot(body.support(n)) - n.dot(centre));
  }
  return radius;
}

// Query::collide settles a pair whose outer balls are proven apart before framing it. Spheres are
// their balls, so pairs of them (and of capsules and cylinders, whose balls they nearly fill) at
// gaps across the balls' border, far from the origin and at every scale, with turned, unturned and
// shared poses, test the screen's rounding: a pair it calls apart is apart beyond the tolerance,
// and away from the tolerance's band every verdict is the exact one.
TEST(BallScreen, CollideAnswersPairsAcrossTheBallsBorderAsTheExactMethod) {
  Random rng(61);
  QueryOptions exact;
  exact.method = Method::exact;
  const Query ours{QueryOptions{}};
  const Query exact_query(exact);
  int apart = 0;
  int colliding = 0;
  for (const Scalar scale : {1e-150, 1e-3, 1.0, 1e150}) {
    for (int trial = 0; trial < 120; ++trial) {
      const Scalar ra = rng.uniform(0.2, 1) * scale;
      const Scalar rb = rng.uniform(0.2, 1) * scale;
      const ConvexPolyhedron a = trial % 3 == 0 ? ConvexPolyhedron(Cylinder(ra, ra / 2))
                                                : ConvexPolyhedron(Sphere(ra));
      ConvexPolyhedron b = trial % 3 == 1 ? ConvexPolyhedron(Capsule(rb, rb / 3))
                                          : ConvexPolyhedron(Sphere(rb));
      const Scalar size = a.outer_radius() + b.outer_radius() +
                          2 * std::max(a.bounds().radius, b.bounds().radius);
      const Scalar gap = rng.uniform(-4, 4) * kDefaultTolerance * size;
      const Vector3 offset = (a.outer_radius() + b.outer_radius() + gap) * rng.unit();
      // Both turned alike, turned apart, neither turned, or one pose shared by both (B's points
      // offset instead): each is a path of its own through the poses' identity tests.
      const int poses_case = trial % 4;
      Pose pose_a;
      pose_a.translation = rng.vector(1000 * scale);
      if (poses_case < 2 || trial % 8 == 3) pose_a.rotation = rng.rotation();
      Pose pose_b = pose_a;
      if (poses_case == 3) {
        b = ConvexPolyhedron(b.vertices().rowwise() + offset.transpose(), b.radius());
      } else {
        pose_b.translation += offset;
        if (poses_case == 1) pose_b.rotation = rng.rotation();
      }
      const bool verdict = ours.collide(a, pose_a, b, pose_b);
      const DistanceResult truth = exact_query.collision(a, pose_a, b, pose_b);
      ASSERT_TRUE(truth.certified) << scale << " " << trial;
      if (!verdict) {
        ++apart;
        EXPECT_GT(truth.distance, 0) << scale << " " << trial;
        EXPECT_FALSE(truth.colliding) << scale << " " << trial;
      } else {
        ++colliding;
      }
      const Scalar tolerance = kDefaultTolerance * size_of(a, pose_a, b, pose_b);
      if (truth.lower_bound > 2 * tolerance || truth.distance <= 0) {
        EXPECT_EQ(verdict, truth.colliding) << scale << " " << trial;
      }
      // The overload without poses, on the bodies placed, where neither is turned.
      if (poses_case == 2 && a.curved() == nullptr) {
        const ConvexPolyhedron placed_a(a.vertices().rowwise() + pose_a.translation.transpose(),
                                        a.radius());
        const ConvexPolyhedron placed_b(b.vertices().rowwise() + pose_b.translation.transpose(),
                                        b.radius());
        EXPECT_EQ(ours.collide(placed_a, placed_b), exact_query.collide(placed_a, placed_b))
            << scale << " " << trial;
      }
    }
  }
  EXPECT_GT(apart, 100);
  EXPECT_GT(colliding, 100);
}

// Query::collide raises the pair's errors whether or not its balls are apart: a pose that is not
// rigid or not finite, and a curved body asked of a method that cannot answer it.
TEST(BallScreen, CollideRaisesThePairsErrorsBeforeReadingItsBalls) {
  const ConvexPolyhedron a = Sphere(1);
  const ConvexPolyhedron b = Sphere(1);
  Pose far;
  far.translation = Vector3(100, 0, 0);
  Pose stretched = far;
  stretched.rotation(0, 0) = 1.5;
  Pose lost = far;
  lost.translation(1) = std::numeric_limits<Scalar>::quiet_NaN();
  const Query query{QueryOptions{}};
  EXPECT_FALSE(query.collide(a, {}, b, far));
  EXPECT_THROW(query.collide(a, {}, b, stretched), std::invalid_argument);
  EXPECT_THROW(query.collide(a, stretched, b, far), std::invalid_argument);
  EXPECT_THROW(query.collide(a, {}, b, lost), std::invalid_argument);
  QueryOptions swarm;
  swarm.method = Method::ipso;
  const Cylinder cylinder(1, 1);
  EXPECT_THROW(Query(swarm).collide(cylinder, {}, b, far), std::invalid_argument);
  EXPECT_THROW(Query(swarm).collide(cylinder, moved(b, far.translation)), std::invalid_argument);
}

// The inner ball about a body's box centre lies inside the body and is nearly the largest there:
// a cube's is its half-width; a corner tetrahedron, whose box centre lies outside it, and a flat
// square have none.
TEST(BallScreen, InnerBallsLieInsideTheirBodies) {
  VertexMatrix cube(8, 3);
  for (int i = 0; i < 8; ++i) {
    cube.row(i) << (i & 1 ? 7 : 3), (i & 2 ? -1 : -5), (i & 4 ? 3 : -1);
  }
  const detail::BodyBalls cube_balls = detail::body_balls(ConvexPolyhedron(cube), true);
  EXPECT_LE(cube_balls.inner, 2);
  EXPECT_GT(cube_balls.inner, 2 * (1 - 1e-12));
  EXPECT_GE(cube_balls.outer, 2 * std::sqrt(3.0));
  EXPECT_EQ(detail::body_balls(point_set({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}), true).inner,
            0);
  EXPECT_EQ(detail::body_balls(point_set({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}}), true).inner,
            0);
  EXPECT_EQ(detail::body_balls(ConvexPolyhedron(cube), false).inner, 0);  // not asked for
  Random rng(12);
  int found = 0;
  for (int trial = 0; trial < 30; ++trial) {
    const ConvexPolyhedron body = rng.body(12 + trial);
    const Scalar inner = detail::body_balls(body, true).inner;
    const Scalar largest = largest_inner_radius(body, body.bounds().centre);
    EXPECT_LE(inner, std::max(largest, 0.0) + 1e-14) << trial;
    if (largest > 0) {
      EXPECT_GT(inner, largest * (1 - 1e-9)) << trial;
      ++found;
    }
  }
  EXPECT_GT(found, 20);
}

// Rows whose bodies' inner balls overlap are settled as colliding without a solver, at a point
// common to both balls (so to both bodies); every verdict is the exact one.
TEST(Batch, InnerBallsProveContact) {
  Random rng(13);
  const ConvexPolyhedron a = rng.body(40);
  const ConvexPolyhedron b = rng.body(25, Vector3(4, -2, 1));
  BatchPoses poses;
  poses.a = random_poses(200, rng, 1);
  poses.b = random_poses(200, rng, 1.5);
  for (Pose& pose : poses.b) pose.translation -= pose.rotation * Vector3(4, -2, 1);
  const BatchResult verdicts = collide_many(a, b, {}, {2}, poses);
  const detail::BodyBalls balls_a = detail::body_balls(a, true);
  const detail::BodyBalls balls_b = detail::body_balls(b, true);
  QueryOptions exact;
  exact.method = Method::exact;
  exact.tolerance = 0;
  int settled_by_balls = 0;
  for (std::size_t i = 0; i < 200; ++i) {
    const auto row = static_cast<Eigen::Index>(i);
    const Pose& pa = poses.a[i];
    const Pose& pb = poses.b[i];
    EXPECT_EQ(verdicts.colliding(row), Query(exact).collide(a, pa, b, pb)) << i;
    EXPECT_TRUE(verdicts.certified(row)) << i;
    const Vector3 centre_a = pa.rotation * a.bounds().centre + pa.translation;
    const Vector3 centre_b = pb.rotation * b.bounds().centre + pb.translation;
    const Vector3 common =
        centre_a + balls_a.inner / (balls_a.inner + balls_b.inner) * (centre_b - centre_a);
    if (verdicts.colliding(row) && verdicts.iterations(row) == 0 &&
        (verdicts.point_a.row(row).transpose() - common).norm() < 1e-12) {
      ++settled_by_balls;
      EXPECT_EQ(verdicts.point_a.row(row), verdicts.point_b.row(row));
      EXPECT_EQ(verdicts.distance(row), 0);
      const ConvexPolyhedron point = point_set({common});
      EXPECT_LT(Query(exact).distance(point, {}, a, pa).distance, 1e-12) << i;
      EXPECT_LT(Query(exact).distance(point, {}, b, pb).distance, 1e-12) << i;
    }
  }
  EXPECT_GT(settled_by_balls, 20);
}

// A thin tetrahedron's box centre lies outside it, so it has no inner ball (radius 0). A small
// cube about that centre, apart from the tetrahedron, has an inner ball holding the centre: the
// balls must not prove contact (they did, with a common point outside the tetrahedron).
TEST(Batch, AThinBodyWithoutAnInnerBallIsNotProvenInContact) {
  const ConvexPolyhedron thin =
      point_set({Vector3(0, 0, 0), Vector3(1, 0, 0), Vector3(0, 1, 0), Vector3(0, 0, 0.01)});
  const Vector3 centre(0.5, 0.5, 0.005);
  ASSERT_EQ(thin.bounds().centre, centre);
  const auto corner = [&centre](int k) {
    return Vector3(centre + 0.002 * Vector3(k & 1 ? 1 : -1, k & 2 ? 1 : -1, k & 4 ? 1 : -1));
  };
  const ConvexPolyhedron cube = point_set({corner(0), corner(1), corner(2), corner(3), corner(4),
                                           corner(5), corner(6), corner(7)});
  EXPECT_EQ(detail::body_balls(thin, true).inner, 0);
  EXPECT_GT(detail::body_balls(cube, true).inner, 0);
  QueryOptions exact;
  exact.method = Method::exact;
  ASSERT_FALSE(Query(exact).collide(cube, {}, thin, {}));
  for (const auto& [a, b] : {std::pair{&cube, &thin}, std::pair{&thin, &cube}}) {
    EXPECT_FALSE(detail::collision_by_balls(*a, {}, detail::body_balls(*a, true), *b, {},
                                            detail::body_balls(*b, true), 1e-9));
    BatchPoses poses;
    poses.b = {Pose{}};
    const BatchResult verdicts = collide_many(*a, *b, {}, {1}, poses);
    EXPECT_FALSE(verdicts.colliding(0));
    EXPECT_TRUE(verdicts.certified(0));
  }
}

// The screens' lengths neither underflow nor overflow: bodies 1e-200 across, placed a billion
// times their size from the origin and rotated about it, get the exact verdicts, as do bodies
// 1e200 across.
TEST(Batch, BallScreensHoldAtAnyScale) {
  for (const Scalar scale : {1e-200, 1e200}) {
    Random rng(14);
    const ConvexPolyhedron unit_a = rng.body(20);
    const ConvexPolyhedron unit_b = rng.body(30);
    const Vector3 far(3e9, -1e9, 2e9);
    const ConvexPolyhedron a((unit_a.vertices().rowwise() + far.transpose()) * scale);
    const ConvexPolyhedron b((unit_b.vertices().rowwise() + far.transpose()) * scale);
    BatchPoses poses;
    poses.b = random_poses(60, rng, 2);
    for (Pose& pose : poses.b) pose.translation *= scale;
    poses.b[0].rotation.setIdentity();  // the bodies overlap where they were given
    const BatchResult verdicts = collide_many(a, b, {}, {2}, poses);
    QueryOptions exact;
    exact.method = Method::exact;
    exact.tolerance = 0;
    for (std::size_t i = 0; i < 60; ++i) {
      const auto row = static_cast<Eigen::Index>(i);
      const DistanceResult truth = Query(exact).distance(a, {}, b, poses.b[i]);
      EXPECT_EQ(verdicts.colliding(row), truth.colliding) << scale << " " << i;
      EXPECT_LE(verdicts.lower_bound(row), truth.distance * (1 + 1e-12)) << scale << " " << i;
      EXPECT_GE(verdicts.distance(row), truth.lower_bound * (1 - 1e-12)) << scale << " " << i;
    }
  }
}

// Pairs of small bodies (scanned whole by the solvers) near each other: most are apart though
// their bounding balls overlap. `count` rows, B's centre 1.6 to 2.2 from A's.
BatchPoses near_poses(int count, Random& rng) {
  BatchPoses poses;
  poses.b = random_poses(count, rng, 1);
  for (Pose& pose : poses.b) {
    pose.translation = rng.unit() * rng.uniform(1.6, 2.2);
  }
  return poses;
}

// The unit sphere's points: small bodies whose balls are nearly their own.
ConvexPolyhedron sphere_body(int count, Random& rng) {
  VertexMatrix points(count, 3);
  for (int i = 0; i < count; ++i) points.row(i) = rng.unit().transpose();
  return ConvexPolyhedron(points);
}

// The axis through the boxes' centres proves only true separations: wherever it settles a pair,
// its lower bound is at most the exact distance (and above the tolerance), and its distance, that
// of two points of the bodies, at least it; it settles most pairs of small bodies near each other
// whose balls overlap, and leaves bodies of more than kHillClimbingThreshold points alone.
TEST(BallScreen, TheCentresAxisProvesOnlyTrueSeparations) {
  Random rng(16);
  QueryOptions exact;
  exact.method = Method::exact;
  exact.tolerance = 0;
  int settled = 0, balls_overlap = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const ConvexPolyhedron a = sphere_body(4 + trial % 29, rng);
    const ConvexPolyhedron b = sphere_body(4 + trial % 17, rng);
    const detail::BodyBalls balls_a = detail::body_balls(a, true);
    const detail::BodyBalls balls_b = detail::body_balls(b, true);
    const Pose pose_a{rng.rotation(), rng.vector(0.1)};
    const Pose pose_b = near_poses(1, rng).b[0];
    const DistanceResult truth = Query(exact).distance(a, pose_a, b, pose_b);
    const std::optional<detail::ScreenVerdict> verdict =
        detail::apart_along_centres(a, pose_a, balls_a, b, pose_b, balls_b, 1e-9);
    if (!detail::collision_by_balls(a, pose_a, balls_a, b, pose_b, balls_b, 1e-9)) ++balls_overlap;
    if (!verdict) continue;
    ++settled;
    EXPECT_FALSE(verdict->colliding) << trial;
    EXPECT_GT(verdict->lower_bound, 0) << trial;
    EXPECT_LE(verdict->lower_bound, truth.lower_bound) << trial;
    EXPECT_GE(verdict->distance, truth.distance * (1 - 1e-14)) << trial;
    EXPECT_NEAR(verdict->direction.norm(), 1, 1e-15) << trial;
    EXPECT_NEAR((verdict->point_b - verdict->point_a).norm(), verdict->distance, 1e-15) << trial;
  }
  EXPECT_GT(settled, 200);
  EXPECT_GT(balls_overlap, 300);
  const ConvexPolyhedron large = sphere_body(kHillClimbingThreshold + 1, rng);
  const ConvexPolyhedron small = sphere_body(8, rng);
  const Pose far{Matrix3::Identity(), Vector3(2.2, 0, 0)};
  const detail::BodyBalls large_balls = detail::body_balls(large, true);
  const detail::BodyBalls small_balls = detail::body_balls(small, true);
  EXPECT_TRUE(detail::apart_along_centres(small, {}, small_balls, small, far, small_balls, 1e-9));
  EXPECT_FALSE(detail::apart_along_centres(large, {}, large_balls, small, far, small_balls, 1e-9));
}

// A collision batch of small bodies near each other settles most rows by the centres' axis (its
// verdict is the row's), gets every verdict right with valid bounds, and answers alike on any
// number of threads and however the batch is cut.
// Where the centres' axis proves nothing, the face normals nearest it prove most separations that
// exist, and only those: every lower bound stays below the exact distance.
TEST(BallScreen, TheFaceAxesProveOnlyTrueSeparations) {
  Random rng(18);
  QueryOptions exact;
  exact.method = Method::exact;
  exact.tolerance = 0;
  int by_faces = 0, apart_unsettled_by_axis = 0;
  for (int trial = 0; trial < 600; ++trial) {
    const ConvexPolyhedron a = sphere_body(4 + trial % 29, rng);
    const ConvexPolyhedron b = sphere_body(4 + trial % 17, rng);
    const detail::BodyBalls balls_a = detail::body_balls(a, true);
    const detail::BodyBalls balls_b = detail::body_balls(b, true);
    ASSERT_NE(balls_a.face_normals, nullptr);
    const Pose pose_a{rng.rotation(), rng.vector(0.1)};
    const Pose pose_b = near_poses(1, rng).b[0];
    if (detail::apart_along_centres(a, pose_a, balls_a, b, pose_b, balls_b, 1e-9)) continue;
    const DistanceResult truth = Query(exact).distance(a, pose_a, b, pose_b);
    if (!truth.colliding) ++apart_unsettled_by_axis;
    const std::optional<detail::ScreenVerdict> verdict =
        detail::apart_across_faces(a, pose_a, balls_a, b, pose_b, balls_b, 1e-9);
    if (!verdict) continue;
    ++by_faces;
    EXPECT_FALSE(truth.colliding) << trial;
    EXPECT_FALSE(verdict->colliding) << trial;
    EXPECT_GT(verdict->lower_bound, 0) << trial;
    EXPECT_LE(verdict->lower_bound, truth.lower_bound) << trial;
    EXPECT_GE(verdict->distance, truth.distance * (1 - 1e-14)) << trial;
    EXPECT_NEAR(verdict->direction.norm(), 1, 1e-15) << trial;
    EXPECT_NEAR((verdict->point_b - verdict->point_a).norm(), verdict->distance, 1e-15) << trial;
  }
  EXPECT_GT(apart_unsettled_by_axis, 50);
  EXPECT_GT(by_faces, apart_unsettled_by_axis / 2);
  // Without face normals (a batch over vertex stacks) the screen proves nothing.
  const ConvexPolyhedron small = sphere_body(8, rng);
  const Pose far{Matrix3::Identity(), Vector3(2.2, 0, 0)};
  const detail::BodyBalls outer_only = detail::body_balls(small, false);
  EXPECT_EQ(outer_only.face_normals, nullptr);
  EXPECT_FALSE(detail::apart_across_faces(small, {}, outer_only, small, far, outer_only, 1e-9));
  const detail::BodyBalls with_faces = detail::body_balls(small, true);
  EXPECT_TRUE(detail::apart_across_faces(small, {}, with_faces, small, far, with_faces, 1e-9));
}

TEST(Batch, NearApartRowsAreSettledByTheCentresAxis) {
  Random rng(17);
  const ConvexPolyhedron a = sphere_body(8, rng);
  const ConvexPolyhedron b = sphere_body(12, rng);
  const BatchPoses poses = near_poses(300, rng);
  const QueryOptions options;
  const BatchResult verdicts = collide_many(a, b, options, {1}, poses);
  const detail::BodyBalls balls_a = detail::body_balls(a, true);
  const detail::BodyBalls balls_b = detail::body_balls(b, true);
  QueryOptions exact;
  exact.method = Method::exact;
  exact.tolerance = 0;
  int by_axis = 0;
  for (std::size_t i = 0; i < 300; ++i) {
    const auto row = static_cast<Eigen::Index>(i);
    const DistanceResult truth = Query(exact).distance(a, {}, b, poses.b[i]);
    EXPECT_TRUE(verdicts.certified(row)) << i;
    EXPECT_EQ(verdicts.colliding(row), truth.colliding) << i;
    EXPECT_LE(verdicts.lower_bound(row), truth.distance + 1e-12) << i;
    EXPECT_GE(verdicts.distance(row), truth.lower_bound - 1e-12) << i;
    const std::optional<detail::ScreenVerdict> axis =
        detail::apart_along_centres(a, {}, balls_a, b, poses.b[i], balls_b, options.tolerance);
    if (axis && !detail::collision_by_balls(a, {}, balls_a, b, poses.b[i], balls_b,
                                            options.tolerance)) {
      ++by_axis;
      EXPECT_EQ(verdicts.lower_bound(row), axis->lower_bound) << i;
      EXPECT_EQ(verdicts.distance(row), axis->distance) << i;
      EXPECT_EQ(verdicts.direction.row(row), axis->direction.transpose()) << i;
      EXPECT_EQ(verdicts.iterations(row), 0) << i;
    }
  }
  EXPECT_GT(by_axis, 100);
  for (int threads : {2, 3}) expect_same(verdicts, collide_many(a, b, options, {threads}, poses));
  for (std::size_t cut : {1u, 64u, 201u}) {
    BatchPoses tail;
    tail.b.assign(poses.b.begin() + static_cast<std::ptrdiff_t>(cut), poses.b.end());
    BatchSettings settings;
    settings.threads = 2;
    settings.first_index = cut;
    expect_rows(collide_many(a, b, options, settings, tail), verdicts,
                static_cast<Eigen::Index>(cut));
  }
}

// Identity poses given explicitly, as a list or as an array, answer as no poses at all.
TEST(Batch, IdentityPosesAnswerAsNoPoses) {
  Random rng(18);
  const ConvexPolyhedron a = rng.body(9);
  const std::vector<ConvexPolyhedron> bs = {rng.body(7, Vector3(2, 0, 0)),
                                            rng.body(7, Vector3(0.5, 0, 0)),
                                            rng.body(40, Vector3(0, 1.5, 0))};
  const QueryOptions options = seeded(Method::dual);
  BatchPoses listed;
  listed.a.assign(3, Pose{});
  listed.b.assign(3, Pose{});
  std::vector<Scalar> transforms(3 * 12, 0);
  for (int i = 0; i < 3; ++i) {
    for (int k = 0; k < 3; ++k) transforms[12 * i + 4 * k + k] = 1;
  }
  BatchPoses arrays;
  arrays.array_b = {transforms.data(), transforms.data() + 3, 3, 12, 4, 12, 4};
  for (const BatchPoses& poses : {listed, arrays}) {
    expect_same(distance_many(a, bs, options, {2}, poses), distance_many(a, bs, options, {2}));
    expect_same(collide_many(a, bs, options, {2}, poses), collide_many(a, bs, options, {2}));
    expect_same(signed_distance_many(a, bs, options, {2}, poses),
                signed_distance_many(a, bs, options, {2}));
  }
}

// Poses read in place from arrays, as (m, 4, 4) transforms or as (m, 3, 3) rotations beside (m, 3)
// translations, answer as the same poses listed.
TEST(Batch, PoseArraysAnswerAsPoseLists) {
  Random rng(15);
  const ConvexPolyhedron a = rng.body(20);
  const ConvexPolyhedron b = rng.body(9);
  BatchPoses listed;
  listed.a = random_poses(70, rng, 1);
  listed.b = random_poses(70, rng, 2.5);
  std::vector<Scalar> transforms(70 * 16), rotations(70 * 9), translations(70 * 3);
  for (std::size_t i = 0; i < 70; ++i) {
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) {
        transforms[16 * i + 4 * r + c] = listed.a[i].rotation(r, c);
        rotations[9 * i + 3 * r + c] = listed.b[i].rotation(r, c);
      }
      transforms[16 * i + 4 * r + 3] = listed.a[i].translation(r);
      translations[3 * i + r] = listed.b[i].translation(r);
    }
  }
  BatchPoses arrays;
  arrays.array_a = {transforms.data(), transforms.data() + 3, 70, 16, 4, 16, 4};
  arrays.array_b = {rotations.data(), translations.data(), 70, 9, 3, 3, 1};
  const QueryOptions options = seeded(Method::dual);
  expect_same(distance_many(a, b, options, {2}, arrays), distance_many(a, b, options, {2}, listed));
  expect_same(collide_many(a, b, options, {2}, arrays), collide_many(a, b, options, {2}, listed));
  arrays.a = listed.a;
  EXPECT_NE(error_of([&] { distance_many(a, b, options, {}, arrays); })
                .find("poses_a: give the poses as a list or as an array, not both"),
            std::string::npos);
}

TEST(Batch, PosesAreCheckedOnceNamingTheRow) {
  Random rng(11);
  const ConvexPolyhedron a = rng.body(6);
  BatchPoses poses;
  poses.b = random_poses(5, rng, 2);
  poses.b[3].rotation(0, 0) *= 1.5;
  BatchSettings settings;
  settings.first_index = 20;
  const std::string message = error_of([&] { distance_many(a, a, {}, settings, poses); });
  EXPECT_EQ(message.rfind("poses_b[23] is not a rigid motion", 0), 0u) << message;
  poses.b[3].rotation(0, 0) = std::numeric_limits<double>::quiet_NaN();
  const std::string not_finite = error_of([&] { collide_many(a, a, {}, settings, poses); });
  EXPECT_NE(not_finite.find("poses_b[23] has a NaN"), std::string::npos) << not_finite;
  poses.a = random_poses(4, rng, 1);
  EXPECT_NE(error_of([&] { distance_many(a, a, {}, {}, poses); })
                .find("poses_b must have one pose per pair, got 5 for 4 pairs"),
            std::string::npos);
}

// A row whose bodies share a pose checks it once, with the verdicts of checking both: a pose B
// that differs from A is checked itself.
TEST(Batch, ASharedPoseIsCheckedOnce) {
  Random rng(12);
  const ConvexPolyhedron a = rng.body(6);
  BatchPoses poses;
  poses.a = random_poses(5, rng, 2);
  poses.b = poses.a;
  BatchSettings settings;
  settings.first_index = 20;
  EXPECT_EQ(error_of([&] { distance_many(a, a, {}, settings, poses); }), "");
  poses.b[3].translation(2) = std::numeric_limits<double>::quiet_NaN();
  const std::string not_finite = error_of([&] { collide_many(a, a, {}, settings, poses); });
  EXPECT_EQ(not_finite.rfind("poses_b[23] has a NaN", 0), 0u) << not_finite;
  poses.b = poses.a;
  poses.b[3].rotation(2, 2) *= 1.5;
  const std::string scaled = error_of([&] { distance_many(a, a, {}, settings, poses); });
  EXPECT_EQ(scaled.rfind("poses_b[23] is not a rigid motion", 0), 0u) << scaled;
  poses.a[3] = poses.b[3];
  const std::string both = error_of([&] { distance_many(a, a, {}, settings, poses); });
  EXPECT_EQ(both.rfind("poses_a[23] is not a rigid motion", 0), 0u) << both;
}

// A result's arrays are views of one block: each starts on a cache line (so that chunks of 64
// rows share none), a large block on a huge page's boundary; copies are deep and a moved-from
// result is empty.
TEST(BatchResultBlock, ArraysStartOnCacheLinesAndCopiesAreDeep) {
  const auto line = [](const void* data) { return reinterpret_cast<std::uintptr_t>(data) % 64; };
  for (std::size_t rows : {1u, 3u, 65u, 30000u}) {
    SCOPED_TRACE(rows);
    BatchResult r(rows);
    EXPECT_EQ(r.rows(), rows);
    for (const void* data : {static_cast<const void*>(r.distance.data()),
                             static_cast<const void*>(r.lower_bound.data()),
                             static_cast<const void*>(r.point_a.data()),
                             static_cast<const void*>(r.point_b.data()),
                             static_cast<const void*>(r.direction.data()),
                             static_cast<const void*>(r.colliding.data()),
                             static_cast<const void*>(r.certified.data()),
                             static_cast<const void*>(r.iterations.data()),
                             static_cast<const void*>(r.escalated.data()),
                             static_cast<const void*>(r.part_a.data()),
                             static_cast<const void*>(r.part_b.data())}) {
      EXPECT_EQ(line(data), 0u);
    }
    EXPECT_EQ(r.point_a.rows(), static_cast<Eigen::Index>(rows));
    EXPECT_EQ(r.part_b.size(), static_cast<Eigen::Index>(rows));
    // The arrays do not overlap: writing each leaves the others as written.
    r.distance.setConstant(1);
    r.lower_bound.setConstant(2);
    r.point_a.setConstant(3);
    r.point_b.setConstant(4);
    r.direction.setConstant(5);
    r.iterations.setConstant(6);
    r.part_a.setConstant(7);
    r.part_b.setConstant(8);
    r.colliding.setConstant(true);
    r.certified.setConstant(false);
    r.escalated.setConstant(true);
    const BatchResult copy = r;
    EXPECT_NE(copy.distance.data(), r.distance.data());
    r.point_b(rows - 1, 2) = -1;
    EXPECT_EQ(copy.point_b(rows - 1, 2), 4);
    EXPECT_TRUE((copy.distance.array() == 1).all() && (copy.lower_bound.array() == 2).all());
    EXPECT_TRUE((copy.point_a.array() == 3).all() && (copy.direction.array() == 5).all());
    EXPECT_TRUE((copy.iterations == 6).all() && (copy.part_a == 7).all() &&
                (copy.part_b == 8).all());
    EXPECT_TRUE(copy.colliding.all() && !copy.certified.any() && copy.escalated.all());
    BatchResult moved = std::move(r);
    EXPECT_EQ(moved.point_b(rows - 1, 2), -1);
    EXPECT_EQ(r.rows(), 0u);  // NOLINT(bugprone-use-after-move): a moved-from result is empty
    EXPECT_EQ(r.distance.size(), 0);
    r = copy;
    EXPECT_EQ(r.point_b(rows - 1, 2), 4);
  }
  EXPECT_EQ(reinterpret_cast<std::uintptr_t>(BatchResult(30000).distance.data()) % (2 << 20), 0u);
}

// The block of a large result, once freed, serves the next result of its size (and only of its
// size), whose rows are written as any others.
TEST(BatchResultBlock, AFreedLargeBlockServesTheNextResultOfItsSize) {
  const void* freed = nullptr;
  {
    BatchResult first(30000);
    first.distance.setConstant(1);
    freed = first.distance.data();
  }
  {
    BatchResult next(30000);
    EXPECT_EQ(static_cast<const void*>(next.distance.data()), freed);
    next.distance.setConstant(2);
    EXPECT_TRUE((next.distance.array() == 2).all());
  }
  const BatchResult larger(60000);
  EXPECT_NE(static_cast<const void*>(larger.distance.data()), freed);
  const BatchResult small(100);
  EXPECT_NE(static_cast<const void*>(small.distance.data()), freed);
  const BatchResult again(30000);
  EXPECT_EQ(static_cast<const void*>(again.distance.data()), freed);
}

// Tens of thousands of rows go to the threads in large chunks: the answers are still those of one
// thread, bit for bit, and an error is still the lowest failing row's, wherever the chunks fall.
TEST(Batch, LargeBatchesAnswerAlikeOnAnyThreads) {
  Random rng(12);
  const ConvexPolyhedron a = rng.body(8);
  const ConvexPolyhedron b = rng.body(8);
  BatchPoses poses;
  poses.b = random_poses(30000, rng, 2.5);
  const QueryOptions options = seeded(Method::dual);
  const BatchResult one = collide_many(a, b, options, {1}, poses);
  for (int threads : {2, 3}) expect_same(one, collide_many(a, b, options, {threads}, poses));
  BatchPoses fewer;
  fewer.b.assign(poses.b.begin(), poses.b.begin() + 3000);
  const BatchResult distances = distance_many(a, b, options, {1}, fewer);
  for (int threads : {2, 3}) expect_same(distances, distance_many(a, b, options, {threads}, fewer));
  for (std::size_t bad : {29990u, 17000u, 130u}) {
    poses.b[bad].rotation(1, 1) = std::numeric_limits<double>::quiet_NaN();
    for (int threads : {1, 2, 3}) {
      const std::string message =
          error_of([&] { collide_many(a, b, options, {threads}, poses); });
      EXPECT_EQ(message.rfind("poses_b[" + std::to_string(bad) + "] has a NaN", 0), 0u)
          << message;
    }
  }
}

// Each thread starts on a range of its own (the rows split evenly, on cache lines): a thread whose
// range comes later meets its failing row first, and the rows before it in the earlier ranges are
// still answered, so that the error is still the lowest failing row's.
TEST(Batch, AFailureInALaterRangeDoesNotHideAnEarlierOne) {
  Random rng(13);
  const ConvexPolyhedron a = rng.body(8);
  BatchPoses poses;
  poses.b = random_poses(30000, rng, 2.5);
  // With 2 threads the second range begins at row 14976, with 3 at 9984 and 19968: row 20000 is
  // among the first rows of the last range, row 14000 near the end of an earlier one.
  for (std::size_t bad : {20000u, 14000u}) {
    poses.b[bad].rotation(2, 0) = std::numeric_limits<double>::quiet_NaN();
  }
  for (int threads : {1, 2, 3}) {
    const std::string message = error_of([&] { collide_many(a, a, {}, {threads}, poses); });
    EXPECT_EQ(message.rfind("poses_b[14000] has a NaN", 0), 0u) << threads << ": " << message;
  }
}

TEST(Batch, PairSeedsDiffer) {
  EXPECT_NE(pair_seed(0, 0), pair_seed(0, 1));
  EXPECT_NE(pair_seed(0, 1), pair_seed(1, 0));
  EXPECT_NE(pair_seed(7, 3), pair_seed(7, 4));
}

}  // namespace
}  // namespace swarmcollide::testing
