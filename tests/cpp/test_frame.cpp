// The pair's frame and poses: answers do not depend on the unit of length or on where the pair
// is, and a posed body is answered as its moved points would be.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "contract.hpp"
#include "geometry/framed_body.hpp"
#include "oracle.hpp"
#include "paper_cases.hpp"
#include "shapes.hpp"
#include "swarmcollide/geometry/shapes.hpp"

namespace swarmcollide::testing {
namespace {

struct Pair {
  std::string name;
  ConvexPolyhedron a;
  ConvexPolyhedron b;
};

// Pairs apart, touching, within the tolerance and overlapping, with coordinates that are exact
// binary fractions, so that scaling by a power of two and translating by a multiple of one
// change no bit of their frame coordinates.
std::vector<Pair> dyadic_pairs() {
  return {
      {"paper, touching", paper_a(), paper_b_colliding()},
      {"paper, separate", paper_a(), paper_b_separate()},
      {"cubes overlapping by half", unit_cube(), moved(unit_cube(), {0.5, 0.25, 0.125})},
      {"cubes 2^-30 apart", unit_cube(), box({1 + 0x1p-30, 0.25, 0.5}, {2, 1.25, 1.5})},
      {"cubes 2^-10 apart", unit_cube(), box({1 + 0x1p-10, 0.25, 0.5}, {2, 1.25, 1.5})},
  };
}

// Every method with every query it answers.
struct MethodQuery {
  Method method;
  QueryKind kind;
};

std::vector<MethodQuery> method_queries() {
  std::vector<MethodQuery> all;
  for (const MethodInfo& info : method_table()) {
    for (QueryKind kind : {QueryKind::distance, QueryKind::collide, QueryKind::signed_distance}) {
      if (info.capabilities & capability_of(kind)) all.push_back({info.method, kind});
    }
  }
  return all;
}

Query query_of(Method method) {
  QueryOptions options;
  options.method = method;
  return Query(options);
}

std::string scientific(Scalar x) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", x);
  return text;
}

std::string label(const MethodQuery& m, const Pair& pair) {
  return std::string(method_name(m.method)) + " " + kind_name(m.kind) + ", " + pair.name;
}

TEST(Frame, PutsBothBodiesInTheUnitBallAndKeepsTheToleranceRelative) {
  for (Scalar scale : {1e-300, 1e-5, 1.0, 3e7, 1e300}) {
    for (const Pair& p : dyadic_pairs()) {
      SCOPED_TRACE(p.name + ", scale " + scientific(scale));
      const ConvexPolyhedron a = transformed(p.a, scale, Vector3::Zero());
      const ConvexPolyhedron b = transformed(p.b, scale, Vector3::Zero());
      const detail::FramedPair pair = detail::frame_pair(a, Pose{}, b, Pose{}, 1e-9);
      EXPECT_GE(pair.frame.size, 1);
      EXPECT_LT(pair.frame.size, 2);
      EXPECT_EQ(pair.tolerance, 1e-9 * pair.frame.size);
      for (const detail::FramedBody* body : {&pair.a, &pair.b}) {
        for (int i = 0; i < body->size(); ++i) EXPECT_LE(body->vertex(i).norm(), 1);
      }
      // The world size is the distance across both bodies' boxes, give or take a factor 2.
      const Scalar across = (a.bounds().centre / 2 - b.bounds().centre / 2).stableNorm() * 2;
      const Scalar size = pair.frame.length_to_world(pair.frame.size);
      EXPECT_GE(size, across);
      EXPECT_LE(size, 2 * (across + a.bounds().radius + b.bounds().radius));
    }
  }
}

// A power-of-two scale moves every frame coordinate by nothing: the answers are the same bits,
// scaled.
TEST(Frame, PowerOfTwoScalesGiveTheSameAnswersScaled) {
  for (const MethodQuery& m : method_queries()) {
    const Query query = query_of(m.method);
    for (const Pair& p : dyadic_pairs()) {
      SCOPED_TRACE(label(m, p));
      const DistanceResult unit = ask(query, m.kind, p.a, p.b);
      for (int exponent : {-900, -330, 330, 900}) {
        const Scalar s = std::ldexp(1.0, exponent);
        const DistanceResult r = ask(query, m.kind, transformed(p.a, s, Vector3::Zero()),
                                     transformed(p.b, s, Vector3::Zero()));
        EXPECT_EQ(r.distance, std::ldexp(unit.distance, exponent));
        EXPECT_EQ(r.lower_bound, std::ldexp(unit.lower_bound, exponent));
        EXPECT_EQ(r.point_a, unit.point_a * s);
        EXPECT_EQ(r.weights_a.dense(), unit.weights_a.dense());
        EXPECT_EQ(r.direction, unit.direction);
        EXPECT_EQ(r.colliding, unit.colliding);
        EXPECT_EQ(r.certified, unit.certified);
        EXPECT_EQ(r.method, unit.method);
        EXPECT_EQ(r.status, unit.status);
        EXPECT_EQ(r.iterations, unit.iterations);
      }
    }
  }
}

// Any scale in [1e-100, 1e100] rounds the points differently, by an epsilon of their size: no
// verdict or certificate changes, and every answer scales, to the tolerance (the certified
// methods) or within its own bounds (the others).
TEST(Frame, AnyScaleChangesNoVerdictAndScalesEveryAnswer) {
  for (const MethodQuery& m : method_queries()) {
    const Query query = query_of(m.method);
    for (const Pair& p : dyadic_pairs()) {
      SCOPED_TRACE(label(m, p));
      const DistanceResult unit = ask(query, m.kind, p.a, p.b);
      const PairScale unit_scale = scale_of(p.a, p.b, kDefaultTolerance);
      for (Scalar s : {1e-100, 1e-30, 1e-3, 7.0, 1e30, 1e100}) {
        SCOPED_TRACE("scale " + scientific(s));
        const ConvexPolyhedron a = transformed(p.a, s, Vector3::Zero());
        const ConvexPolyhedron b = transformed(p.b, s, Vector3::Zero());
        const DistanceResult r = ask(query, m.kind, a, b);
        // Which method answers may change ("fcl" settles or hands over to "exact" by rounding);
        // the answer may not.
        EXPECT_EQ(r.colliding, unit.colliding);
        EXPECT_EQ(r.certified, unit.certified);
        const PairScale scale = scale_of(a, b, kDefaultTolerance);
        expect_contract(a, b, m.kind, m.method, r, reference(a, b), scale);
        // A collide answer's distance is only the bound that settled the verdict.
        if (method_info(m.method).always_certified && m.kind != QueryKind::collide) {
          EXPECT_NEAR(r.distance / s, unit.distance, unit_scale.tolerance + unit_scale.rounding);
        } else {
          EXPECT_LE(r.lower_bound / s, unit.distance + unit_scale.rounding);
          EXPECT_LE(unit.lower_bound, r.distance / s + unit_scale.rounding);
        }
      }
    }
  }
}

// Translating a pair by up to a million times its size changes its points by an epsilon of
// their magnitude, which the pairs here absorb: none is within 1e-9 of the tolerance.
TEST(Frame, TranslationsFarFromTheOriginChangeNoVerdict) {
  Random rng(8);
  for (const MethodQuery& m : method_queries()) {
    const Query query = query_of(m.method);
    for (const Pair& p : dyadic_pairs()) {
      SCOPED_TRACE(label(m, p));
      const DistanceResult home = ask(query, m.kind, p.a, p.b);
      const PairScale scale = scale_of(p.a, p.b, kDefaultTolerance);
      for (Scalar times : {1e3, 1e6}) {
        const Vector3 offset = times * scale.size * rng.unit();
        const ConvexPolyhedron a = moved(p.a, offset);
        const ConvexPolyhedron b = moved(p.b, offset);
        const DistanceResult r = ask(query, m.kind, a, b);
        EXPECT_EQ(r.colliding, home.colliding);
        EXPECT_EQ(r.certified, home.certified);
        expect_contract(a, b, m.kind, m.method, r, reference(a, b),
                        scale_of(a, b, kDefaultTolerance));
        // A collide answer's distance is only the bound that settled the verdict.
        if (method_info(m.method).always_certified && m.kind != QueryKind::collide) {
          EXPECT_NEAR(r.distance, home.distance, scale.tolerance + 1e-9 * scale.size);
        }
      }
    }
  }
}

// Translating dyadic bodies by a multiple of a power of two keeps their frame coordinates:
// distances are the same bits, and the witnesses move by the translation.
TEST(Frame, ExactTranslationsGiveTheSameAnswersMoved) {
  // About 3e5 times the pairs' size; the sums with the coordinates take at most 53 bits.
  const Vector3 offset(0x1p20, -0x1p20, 0x1p19);
  for (const MethodQuery& m : method_queries()) {
    const Query query = query_of(m.method);
    for (const Pair& p : dyadic_pairs()) {
      SCOPED_TRACE(label(m, p));
      const DistanceResult home = ask(query, m.kind, p.a, p.b);
      const DistanceResult r = ask(query, m.kind, moved(p.a, offset), moved(p.b, offset));
      EXPECT_EQ(r.distance, home.distance);
      EXPECT_EQ(r.lower_bound, home.lower_bound);
      EXPECT_EQ(r.weights_b.dense(), home.weights_b.dense());
      EXPECT_LE((r.point_a - home.point_a - offset).norm(), 1e-9);
      EXPECT_EQ(r.colliding, home.colliding);
      EXPECT_EQ(r.certified, home.certified);
    }
  }
}

TEST(Frame, PairsBeyondTheDoubleRangeAreRefusedAndPairsWithinItAnswered) {
  const ConvexPolyhedron far = point_set({{1e300, 1e300, 1e300}});
  const ConvexPolyhedron origin = point_set({{0, 0, 0}});
  for (const MethodQuery& m : method_queries()) {
    SCOPED_TRACE(std::string(method_name(m.method)) + " " + kind_name(m.kind));
    const DistanceResult r = ask(query_of(m.method), m.kind, far, origin);
    EXPECT_NEAR(r.distance, std::sqrt(3.0) * 1e300, 1e286);
    EXPECT_FALSE(r.colliding);
    EXPECT_TRUE(r.certified);
    const ConvexPolyhedron huge = point_set({{1.5e308, 0, 0}});
    const ConvexPolyhedron opposite = point_set({{-1.5e308, 0, 0}});
    EXPECT_THROW(ask(query_of(m.method), m.kind, huge, opposite), std::invalid_argument);
  }
}

// Posed bodies are answered in world coordinates as their moved points would be: the contract
// holds against the moved points, the certified methods give their distances, and identity
// poses change nothing.
TEST(Poses, AnswerAsTheTransformedPoints) {
  Random rng(21);
  const std::vector<Pair> pairs = {
      {"paper, separate", paper_a(), paper_b_separate()},
      {"cubes overlapping", unit_cube(), moved(unit_cube(), {0.5, 0.25, 0.1})},
      {"random", rng.body(8), rng.body(7, {1.5, 0.5, 0})},
  };
  for (const MethodQuery& m : method_queries()) {
    const Query query = query_of(m.method);
    for (const Pair& p : pairs) {
      SCOPED_TRACE(label(m, p));
      const Pose pose_a{rng.rotation(), rng.vector(10)};
      const Pose pose_b{rng.rotation(), pose_a.translation + rng.vector()};
      const auto place = [](const ConvexPolyhedron& body, const Pose& pose) {
        VertexMatrix v = body.vertices() * pose.rotation.transpose();
        v.rowwise() += pose.translation.transpose();
        return ConvexPolyhedron(v);
      };
      const ConvexPolyhedron a = place(p.a, pose_a);
      const ConvexPolyhedron b = place(p.b, pose_b);
      DistanceResult posed;
      switch (m.kind) {
        case QueryKind::distance:
          posed = query.distance(p.a, pose_a, p.b, pose_b);
          break;
        case QueryKind::collide:
          posed = query.collision(p.a, pose_a, p.b, pose_b);
          EXPECT_EQ(query.collide(p.a, pose_a, p.b, pose_b), posed.colliding);
          break;
        case QueryKind::signed_distance:
          posed = query.signed_distance(p.a, pose_a, p.b, pose_b);
          break;
      }
      const Reference truth = reference(a, b);
      const PairScale scale = scale_of(a, b, kDefaultTolerance);
      expect_contract(a, b, m.kind, m.method, posed, truth, scale);
      const DistanceResult moved_points = ask(query, m.kind, a, b);
      EXPECT_EQ(posed.colliding, moved_points.colliding);
      // A verdict's bounds are only its proof, which may come from the frame's own directions
      // (the centres' line); values are the same in every frame.
      if (method_info(m.method).always_certified && m.kind != QueryKind::collide) {
        EXPECT_NEAR(posed.distance, moved_points.distance, scale.tolerance + scale.rounding);
      }
      DistanceResult identity;
      switch (m.kind) {
        case QueryKind::distance:
          identity = query.distance(p.a, Pose{}, p.b, Pose{});
          break;
        case QueryKind::collide:
          identity = query.collision(p.a, Pose{}, p.b, Pose{});
          break;
        case QueryKind::signed_distance:
          identity = query.signed_distance(p.a, Pose{}, p.b, Pose{});
          break;
      }
      expect_identical(identity, ask(query, m.kind, p.a, p.b));
    }
  }
}

TEST(Poses, OnlyFiniteProperRotationsAreRigidMotions) {
  Random rng(4);
  Pose pose{rng.rotation(), rng.vector()};
  EXPECT_NO_THROW(validate_pose(pose, "pose_a"));
  // Rotations built from rounded trigonometry are an epsilon off; within 1e-9 is accepted.
  pose.rotation(0, 0) += 1e-12;
  EXPECT_NO_THROW(validate_pose(pose, "pose_a"));
  const auto error = [](const Pose& p) {
    try {
      validate_pose(p, "pose_b");
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  Pose scaled{2 * Matrix3::Identity(), Vector3::Zero()};
  EXPECT_NE(error(scaled).find("pose_b is not a rigid motion"), std::string::npos);
  Pose reflection{Matrix3::Identity(), Vector3::Zero()};
  reflection.rotation(2, 2) = -1;
  EXPECT_NE(error(reflection).find("not a rigid motion"), std::string::npos);
  Pose nan{Matrix3::Identity(), Vector3(0, std::nan(""), 0)};
  EXPECT_NE(error(nan).find("pose_b has a NaN or infinite entry"), std::string::npos);
  Pose infinite{Matrix3::Identity(), Vector3::Zero()};
  infinite.rotation(1, 0) = std::numeric_limits<Scalar>::infinity();
  EXPECT_NE(error(infinite).find("NaN or infinite"), std::string::npos);
  // Every entry of the identity and of a rotation, in turn NaN or infinite (validation tests
  // only the translation's finiteness itself; the rotation's falls to the rigidity test).
  for (const Matrix3& rotation : {Matrix3(Matrix3::Identity()), Matrix3(rng.rotation())}) {
    for (int k = 0; k < 9; ++k) {
      for (const Scalar bad : {std::numeric_limits<Scalar>::quiet_NaN(),
                               std::numeric_limits<Scalar>::infinity(),
                               -std::numeric_limits<Scalar>::infinity()}) {
        Pose broken{rotation, rng.vector()};
        broken.rotation.data()[k] = bad;
        EXPECT_NE(error(broken).find("NaN or infinite"), std::string::npos) << k << " " << bad;
      }
    }
  }
}

// A query whose bodies share a pose (the same object, or a copy) checks it once: the verdicts are
// those of checking each pose, and a pose B that differs from A in any one of its twelve entries
// is checked itself, naming B.
TEST(Poses, ASharedPoseIsCheckedOnceWithTheSameVerdicts) {
  Random rng(9);
  const ConvexPolyhedron a = rng.body(6);
  const ConvexPolyhedron b = rng.body(6);
  const Query query;
  const auto error = [&](const Pose& pose_a, const Pose& pose_b) {
    try {
      query.distance(a, pose_a, b, pose_b);
      query.collide(a, pose_a, b, pose_b);
      query.signed_distance(a, pose_a, b, pose_b);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  const Pose pose{rng.rotation(), rng.vector()};
  const Pose copy = pose;
  EXPECT_EQ(error(pose, pose), "");
  EXPECT_EQ(error(pose, copy), "");
  expect_identical(query.distance(a, pose, b, pose), query.distance(a, pose, b, copy));
  Pose scaled = pose;
  scaled.rotation *= 1.5;
  EXPECT_EQ(error(scaled, scaled).rfind("pose_a is not a rigid motion", 0), 0u);
  for (int k = 0; k < 12; ++k) {
    for (const Scalar bad : {std::numeric_limits<Scalar>::quiet_NaN(), Scalar(7)}) {
      Pose other = copy;
      (k < 9 ? other.rotation.data()[k] : other.translation(k - 9)) = bad;
      const std::string message = error(pose, other);
      if (k >= 9 && !std::isnan(bad)) {  // a finite translation is valid
        EXPECT_EQ(message, "") << k;
      } else {
        EXPECT_EQ(message.rfind("pose_b ", 0), 0u) << k << " " << bad << ": " << message;
      }
    }
  }
}

// A large body climbs a hull held in its frame: the hull points' own when some given points lie
// inside, the body's own when every point is a hull point (not asked of the body at every climb).
TEST(FramedBodies, ClimbAHullTheyHold) {
  Random rng(7);
  VertexMatrix sphere(100, 3);
  for (int i = 0; i < 100; ++i) sphere.row(i) = rng.vector().normalized().transpose();
  const ConvexPolyhedron round(sphere);
  const ConvexPolyhedron cloud = rng.body(100);
  ASSERT_TRUE(round.hull_points().every_point);
  ASSERT_FALSE(cloud.hull_points().every_point);
  const detail::FramedPair pair =
      detail::frame_pair(round, Pose{rng.rotation(), rng.vector()}, cloud, Pose{}, 1e-9);
  EXPECT_EQ(&pair.a.hull(), &round.hull());
  EXPECT_EQ(&pair.b.hull(), &cloud.hull_points().hull);
}

// The exact support is the largest height computed in the frame, whatever the body's own
// coordinates (here 1e8 from the body, where they round a hundred million times coarser than
// its frame coordinates); points given in the frame are answered as they are.
TEST(FramedBodies, ExactSupportIsTheLargestHeightInTheFrame) {
  Random rng(5);
  const ConvexPolyhedron far = moved(rng.body(40), Vector3(1e8, -1e8, 1e8));
  const ConvexPolyhedron near = rng.body(12, {1.5, 0, 0});
  const Pose home{rng.rotation(), Vector3(-1e8, 1e8, -1e8)};
  const detail::FramedPair pair = detail::frame_pair(far, home, near, Pose{}, 1e-9);
  VertexMatrix points;
  pair.a.points(points);
  const detail::FramedBody in_frame(points, far.hull());
  for (int k = 0; k < 200; ++k) {
    const Vector3 d = rng.unit();
    for (const detail::FramedBody* body : {&pair.a, &pair.b, &in_frame}) {
      int top = 0;
      for (int i = 1; i < body->size(); ++i) {
        if (body->height(i, d) > body->height(top, d)) top = i;
      }
      EXPECT_EQ(body->exact_support_index(d), top);
    }
    EXPECT_EQ(in_frame.support_index(d), in_frame.exact_support_index(d));
    EXPECT_EQ(in_frame.exact_support_index(d), pair.a.exact_support_index(d));
  }
  for (int i = 0; i < in_frame.size(); ++i) {
    EXPECT_EQ(in_frame.vertex(i), pair.a.vertex(i));
    EXPECT_EQ(in_frame.height(i, Vector3(0.3, -0.2, 0.9)),
              in_frame.vertex(i).dot(Vector3(0.3, -0.2, 0.9)));
  }
  // A height from the point placed already is height()'s, bit for bit, placed or given in the
  // frame (the penetration solver's witnesses read their corners' heights so).
  const Vector3 d(0.3, -0.2, 0.9);
  for (const detail::FramedBody* body : {&pair.a, &pair.b, &in_frame}) {
    for (int i = 0; i < body->size(); ++i) {
      EXPECT_EQ(body->height(i, body->vertex(i), d), body->height(i, d));
    }
  }
}

// A small body's inline scan in its own frame (the fcl method's recovery of FCL's simplex) is its
// support scan: the same index along any direction, ties (a cube's faces and edges along the
// axes and diagonals) included.
TEST(FramedBodies, ASmallBodysInlineLocalScanIsItsSupportScan) {
  Random rng(13);
  const ConvexPolyhedron cube = unit_cube();
  const ConvexPolyhedron four = rng.body(4);
  const ConvexPolyhedron many = rng.body(32);
  const detail::FramedPair pair =
      detail::frame_pair(cube, Pose{rng.rotation(), rng.vector()}, four, Pose{}, 1e-9);
  const detail::FramedPair other = detail::frame_pair(many, Pose{}, cube, Pose{}, 1e-9);
  std::vector<Vector3> directions;
  for (int k = 0; k < 3; ++k) {
    directions.push_back(Vector3::Unit(k));
    directions.push_back(-Vector3::Unit(k));
  }
  directions.push_back(Vector3(1, 1, 0));
  directions.push_back(Vector3(-1, 1, 1));
  for (int n = 0; n < 200; ++n) directions.push_back(rng.unit());
  for (const detail::FramedBody* body : {&pair.a, &pair.b, &other.a, &other.b}) {
    ASSERT_TRUE(body->scanned());
    for (const Vector3& local : directions) {
      EXPECT_EQ(body->scanned_local_support_index(local), body->local_support_index(local, -1));
    }
  }
}

// A body of one point (a ball's core) lies at the centre of its own box: single_vertex() reads it
// at the body's offset, and it is vertex(0) under any pose and at any scale. A point whose box
// centre rounds off it (odd multiples of the smallest subnormal: x / 2 rounds to even), in a pair
// so small that its frame scales it up by 2^1064, is not at its offset: it is placed, as vertex(0)
// places it.
TEST(FramedBodies, ABallsCoreIsItsPlacedPoint) {
  Random rng(17);
  for (Scalar scale : {1e-300, 1.0, 1e300}) {
    const Sphere ball(0.5 * scale);
    const Sphere other(0.25 * scale);
    for (int trial = 0; trial < 20; ++trial) {
      const detail::FramedPair pair =
          detail::frame_pair(ball, Pose{rng.rotation(), rng.vector(2) * scale}, other,
                             Pose{rng.rotation(), rng.vector(2) * scale}, 1e-9);
      for (const detail::FramedBody* body : {&pair.a, &pair.b}) {
        EXPECT_EQ(body->single_vertex(), body->offset());
        EXPECT_EQ(body->single_vertex(), body->vertex(0));
      }
    }
  }
  const Scalar tiny = std::numeric_limits<Scalar>::denorm_min();
  const auto one_point = [](const Vector3& p) {
    VertexMatrix points(1, 3);
    points.row(0) = p.transpose();
    return ConvexPolyhedron(points);
  };
  const ConvexPolyhedron odd = one_point(Vector3(3 * tiny, -5 * tiny, 7 * tiny));
  const ConvexPolyhedron far = one_point(Vector3(1001 * tiny, 0, 0));
  ASSERT_NE(odd.centred_vertices()(0, 0), 0);
  const detail::FramedPair pair =
      detail::frame_pair(odd, Pose{rng.rotation(), Vector3::Zero()}, far, Pose{}, 1e-9);
  EXPECT_NE(pair.a.single_vertex(), pair.a.offset());
  EXPECT_EQ(pair.a.single_vertex(), pair.a.vertex(0));
}

// times_power_of_two of a vector is that of each coordinate, bit for bit, for every exponent of
// a frame: those with a normal power of two (one factor) and the extreme ones past +-1000 (split).
TEST(FramedBodies, AVectorScalesAsItsCoordinates) {
  Random rng(19);
  const Scalar tiny = std::numeric_limits<Scalar>::denorm_min();
  const std::vector<Vector3> vectors{rng.vector(), Vector3(tiny, -3 * tiny, 0x1p-1000),
                                     Vector3(1e300, -1e-300, 0.75), Vector3(-0.0, 0.0, 1)};
  for (int exponent : {-1100, -1074, -1001, -1000, -999, -3, 0, 5, 999, 1000, 1001, 1100}) {
    for (const Vector3& v : vectors) {
      const Vector3 scaled = detail::times_power_of_two(v, exponent);
      for (int k = 0; k < 3; ++k) {
        const Scalar each = detail::times_power_of_two(v(k), exponent);
        EXPECT_TRUE(scaled(k) == each && std::signbit(scaled(k)) == std::signbit(each))
            << "exponent " << exponent << " coordinate " << v(k);
      }
    }
  }
}

// Two framings of a pair agree field by field: a pair re-placed by KeptPair must be the pair
// frame_turned_pair makes, so that a batch's answers are the same bit for bit.
void expect_same_framing(const detail::FramedPair& kept, const detail::FramedPair& fresh) {
  EXPECT_EQ(kept.frame.centre, fresh.frame.centre);
  EXPECT_EQ(kept.frame.exponent, fresh.frame.exponent);
  EXPECT_EQ(kept.frame.size, fresh.frame.size);
  EXPECT_EQ(kept.tolerance, fresh.tolerance);
  EXPECT_EQ(kept.radius_a, fresh.radius_a);
  EXPECT_EQ(kept.radius_b, fresh.radius_b);
  EXPECT_EQ(kept.support_error, fresh.support_error);
  EXPECT_EQ(kept.adjusted, fresh.adjusted);
  Random rng(11);
  for (const auto& [k, f] : {std::pair{&kept.a, &fresh.a}, std::pair{&kept.b, &fresh.b}}) {
    EXPECT_EQ(&k->body(), &f->body());
    EXPECT_EQ(k->rotation(), f->rotation());
    EXPECT_EQ(k->rotated(), f->rotated());
    EXPECT_EQ(k->offset(), f->offset());
    EXPECT_EQ(k->exponent(), f->exponent());
    EXPECT_EQ(k->curved_kind(), f->curved_kind());
    EXPECT_EQ(k->scan_shortfall(), f->scan_shortfall());
    ASSERT_EQ(k->size(), f->size());
    for (int i = 0; i < k->size(); ++i) EXPECT_EQ(k->vertex(i), f->vertex(i));
    for (int n = 0; n < 20; ++n) {
      const Vector3 d = rng.unit();
      EXPECT_EQ(k->support_index(d), f->support_index(d));
      EXPECT_EQ(k->support_index(d, 0), f->support_index(d, 0));
    }
  }
}

// A batch keeps its pair from row to row: re-placed under each row's poses it is the pair framed
// anew (small, large, rounded and curved bodies, turned or not, far apart or near), a curved
// body's support points start again from its own, and other bodies are framed anew.
TEST(FramedBodies, AKeptPairReplacedIsThePairFramedAnew) {
  Random rng(13);
  const ConvexPolyhedron small = rng.body(8);
  const ConvexPolyhedron large = rng.body(100);
  const ConvexPolyhedron rounded(rng.body(6).vertices(), 0.25);
  const Ellipsoid curved(Vector3(0.5, 1, 1.5));
  const std::vector<std::pair<const ConvexPolyhedron*, const ConvexPolyhedron*>> bodies = {
      {&small, &large}, {&rounded, &small}, {&curved, &small}, {&small, &curved}};
  detail::KeptPair kept;
  for (const auto& [a, b] : bodies) {
    for (int row = 0; row < 6; ++row) {
      const Pose pose_a = row % 3 == 0 ? Pose{} : Pose{rng.rotation(), rng.vector()};
      const Pose pose_b{row % 2 == 0 ? Matrix3::Identity() : rng.rotation(),
                        rng.vector() * std::pow(10.0, row - 2)};
      const bool turned_a = !pose_a.has_identity_rotation();
      const bool turned_b = !pose_b.has_identity_rotation();
      const detail::FramedPair& pair = kept.frame(*a, pose_a, turned_a, *b, pose_b, turned_b, 1e-6);
      const detail::FramedPair fresh =
          detail::frame_turned_pair(*a, pose_a, turned_a, *b, pose_b, turned_b, 1e-6);
      expect_same_framing(pair, fresh);
      // A query's support points of a curved body are its own: the next row does not see them.
      if (pair.a.curved()) pair.a.support_index(rng.unit());
      if (pair.b.curved()) pair.b.support_index(rng.unit());
    }
  }
}

// A row that cannot be framed throws as frame_turned_pair does, and the pair kept answers the
// next row as a pair framed anew.
TEST(FramedBodies, AKeptPairRefusesWhatFramingRefuses) {
  Random rng(17);
  const ConvexPolyhedron a = rng.body(8);
  const ConvexPolyhedron b = moved(rng.body(8), Vector3(1e308, 0, 0));
  detail::KeptPair kept;
  kept.frame(a, Pose{}, false, b, Pose{}, false, 1e-9);
  // B's box centre lands beyond the double range.
  const Pose beyond{Matrix3::Identity(), Vector3(1e308, 0, 0)};
  EXPECT_THROW(kept.frame(a, Pose{}, false, b, beyond, false, 1e-9), std::invalid_argument);
  EXPECT_THROW(detail::frame_turned_pair(a, Pose{}, false, b, beyond, false, 1e-9),
               std::invalid_argument);
  const Pose next{rng.rotation(), Vector3(0, 3, 0)};
  expect_same_framing(kept.frame(a, Pose{}, false, b, next, true, 1e-9),
                      detail::frame_turned_pair(a, Pose{}, false, b, next, true, 1e-9));
}

}  // namespace
}  // namespace swarmcollide::testing
