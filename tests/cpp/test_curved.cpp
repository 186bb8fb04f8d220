// Curved shapes (Cylinder, Cone, Ellipsoid: support-function bodies) against closed forms and
// against polytope brackets: an inner polytope of points on the surface, and that polytope grown
// by its Hausdorff distance to the shape, enclose the shape's distance.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <fcl/narrowphase/detail/convexity_based_algorithm/minkowski_diff.h>

#include "geometry/framed_body.hpp"
#include "geometry/framed_curved_support.hpp"
#include "compound_oracle.hpp"
#include "shapes.hpp"
#include "solvers/curved_point.hpp"
#include "solvers/direction_swarm.hpp"
#include "solvers/fcl_shape.hpp"
#include "solvers/inline_minkowski.hpp"
#include "solvers/minkowski.hpp"
#include "swarmcollide/geometry/compound_body.hpp"
#include "swarmcollide/geometry/shapes.hpp"
#include "swarmcollide/queries/batch.hpp"
#include "swarmcollide/queries/methods.hpp"
#include "swarmcollide/queries/query.hpp"
#include "swarmcollide/scene/scene.hpp"

namespace swarmcollide::testing {
namespace {

// The methods that answer distances of curved shapes ("libccd" answers verdicts and signed
// distances only, tested apart).
const std::vector<Method> kCurvedMethods = {Method::dual, Method::exact, Method::fcl};
constexpr Scalar kPi = 3.14159265358979323846;

Query query_of(Method method, Scalar tolerance = kDefaultTolerance) {
  QueryOptions options;
  options.method = method;
  options.tolerance = tolerance;
  return Query(options);
}

// The bounds enclose `expected` (to rounding) and the distance is within the tolerance of it,
// certified.
void expect_answer(const DistanceResult& r, Scalar expected, Scalar size,
                   Scalar tolerance = kDefaultTolerance) {
  const Scalar slack = 1e-13 * size;
  EXPECT_TRUE(r.certified);
  EXPECT_LE(r.lower_bound, expected + slack);
  EXPECT_GE(r.distance, expected - slack);
  EXPECT_NEAR(r.distance, expected, tolerance * size + slack);
}

// Signed distance from the point p to the cylinder of radius r and half length h along z.
Scalar point_to_cylinder(const Vector3& p, Scalar r, Scalar h) {
  const Scalar radial = std::hypot(p.x(), p.y()) - r;
  const Scalar axial = std::abs(p.z()) - h;
  if (radial <= 0 && axial <= 0) return std::max(radial, axial);
  return std::hypot(std::max(radial, 0.0), std::max(axial, 0.0));
}

Scalar point_to_segment_2d(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                           const Eigen::Vector2d& b) {
  const Eigen::Vector2d d = b - a;
  const Scalar t = std::clamp((p - a).dot(d) / d.squaredNorm(), 0.0, 1.0);
  return (p - (a + t * d)).norm();
}

// Signed distance from p to the cone of base radius r at z = -h and apex (0, 0, h): in the
// half-plane (rho, z) of p the cone is the triangle (0, -h), (r, -h), (0, h), whose boundary
// there is the base and the slant side (the axis is inside the solid).
Scalar point_to_cone(const Vector3& p, Scalar r, Scalar h) {
  const Eigen::Vector2d q(std::hypot(p.x(), p.y()), p.z());
  const Eigen::Vector2d base0(0, -h), rim(r, -h), apex(0, h);
  const Scalar to_base = point_to_segment_2d(q, base0, rim);
  const Scalar to_side = point_to_segment_2d(q, rim, apex);
  // Inside: above the base and below the slant line through the rim and the apex.
  const bool inside = q.y() >= -h && q.x() * (2 * h) + (q.y() - h) * r <= 0;
  const Scalar nearest = std::min(to_base, to_side);
  return inside ? -nearest : nearest;
}

// Support value of the ellipsoid of `radii`, turned by `turn`, along the unit vector n.
Scalar ellipsoid_support(const Vector3& radii, const Matrix3& turn, const Vector3& n) {
  return radii.cwiseProduct(turn.transpose() * n).norm();
}

TEST(Curved, BadParametersNameTheParameter) {
  const Scalar nan = std::numeric_limits<Scalar>::quiet_NaN();
  const Scalar inf = std::numeric_limits<Scalar>::infinity();
  for (Scalar bad : {0.0, -1.0, nan, inf}) {
    SCOPED_TRACE(bad);
    const auto names = [](const auto& build, const std::string& name) {
      try {
        build();
        ADD_FAILURE() << "no error for " << name;
      } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
      }
    };
    names([&] { Cylinder(bad, 1); }, "radius");
    names([&] { Cylinder(1, bad); }, "half_length");
    names([&] { Cone(bad, 1); }, "radius");
    names([&] { Cone(1, bad); }, "half_length");
    names([&] { Ellipsoid(Vector3(1, bad, 1)); }, "radii[1]");
    names([&] { Ellipsoid(Vector3(1, 1, bad)); }, "radii[2]");
  }
}

TEST(Curved, BoundsHoldTheShape) {
  const Cylinder cylinder(2, 3);
  EXPECT_EQ(cylinder.aabb().min, Vector3(-2, -2, -3));
  EXPECT_EQ(cylinder.aabb().max, Vector3(2, 2, 3));
  EXPECT_GE(cylinder.bounds().radius, std::hypot(2.0, 3.0));
  EXPECT_LE(cylinder.bounds().radius, std::hypot(2.0, 3.0) * (1 + 1e-12));
  EXPECT_EQ(cylinder.radius(), 0);
  const Cone cone(2, 3);
  EXPECT_EQ(cone.aabb().min, Vector3(-2, -2, -3));
  EXPECT_EQ(cone.aabb().max, Vector3(2, 2, 3));
  EXPECT_NEAR(cone.centroid().z(), -1.5, 1e-15);
  const Ellipsoid ellipsoid(Vector3(1, 2, 3));
  EXPECT_EQ(ellipsoid.aabb().max, Vector3(1, 2, 3));
  EXPECT_GE(ellipsoid.bounds().radius, 3);
  EXPECT_LE(ellipsoid.bounds().radius, 3 * (1 + 1e-12));
  EXPECT_NE(ellipsoid.curved(), nullptr);
  EXPECT_EQ(Box(Vector3(1, 1, 1)).curved(), nullptr);
}

// The support function's contract (SupportFunction): its points are inside the shape, and their
// heights within 32 roundoffs of the outer radius of the support value, computed in long double.
TEST(Curved, SupportPointsAreInsideAndHighest) {
  Random rng(11);
  const Scalar u = 0x1p-53;
  for (int trial = 0; trial < 2000; ++trial) {
    const Scalar r = std::exp(rng.uniform(-3, 3));
    const Scalar h = std::exp(rng.uniform(-3, 3));
    const Vector3 radii(std::exp(rng.uniform(-3, 3)), std::exp(rng.uniform(-3, 3)),
                        std::exp(rng.uniform(-3, 3)));
    Vector3 d = rng.unit();
    if (trial % 4 == 1) d.x() = d.y() = 0;  // along the axis: a cap's centre
    if (trial % 4 == 2) d.z() = 0;
    if (trial % 4 == 3) d *= std::exp(rng.uniform(-600, 600));  // any length
    const long double dxy = std::hypot(static_cast<long double>(d.x()), d.y());
    const long double dz = d.z();
    const long double length = d.stableNorm();
    {
      const Cylinder c(r, h);
      const Vector3 p = c.curved()->support(d);
      EXPECT_LE(std::hypot(p.x(), p.y()), r);
      EXPECT_LE(std::abs(p.z()), h);
      const long double value = r * dxy + h * std::abs(dz);
      const long double height = d.cast<long double>().dot(p.cast<long double>());
      EXPECT_LE(value - height, 32 * u * c.curved()->outer_radius() * length);
    }
    {
      const Cone c(r, h);
      const Vector3 p = c.curved()->support(d);
      EXPECT_LE(point_to_cone(p, r, h), 1e-300);
      const long double value = std::max<long double>(h * dz, r * dxy - h * dz);
      const long double height = d.cast<long double>().dot(p.cast<long double>());
      EXPECT_LE(value - height, 32 * u * c.curved()->outer_radius() * length);
    }
    {
      const Ellipsoid e(radii);
      const Vector3 p = e.curved()->support(d);
      const Eigen::Matrix<long double, 3, 1> q =
          p.cast<long double>().cwiseQuotient(radii.cast<long double>());
      EXPECT_LE(q.squaredNorm(), 1.0L);
      const long double value =
          radii.cast<long double>().cwiseProduct(d.cast<long double>()).norm();
      const long double height = d.cast<long double>().dot(p.cast<long double>());
      EXPECT_LE(value - height, 32 * u * e.curved()->outer_radius() * length);
    }
  }
}

// An ellipsoid's support point does not depend on the direction's length: a direction whose
// largest component is within [2^-100, 2^100] is used as it is, others are first scaled by a
// power of two (EllipsoidSupport::support), and the two must give the same point bit for bit,
// on either side of both limits, for radii of very different sizes.
TEST(Curved, EllipsoidSupportsDoNotDependOnThePowerOfTwoOfTheDirection) {
  Random rng(29);
  for (int trial = 0; trial < 400; ++trial) {
    const Vector3 radii(std::exp(rng.uniform(-5, 5)), std::exp(rng.uniform(-5, 5)),
                        std::exp(rng.uniform(-5, 5)));
    const Ellipsoid e(radii);
    Vector3 d = rng.unit();
    if (trial % 3 == 1) d.y() = 0;
    const Vector3 expected = e.curved()->support(d);
    for (int exponent : {-300, -102, -101, -100, -99, -40, 0, 40, 99, 100, 101, 102, 300}) {
      const Vector3 p = e.curved()->support(d * std::ldexp(1.0, exponent));
      EXPECT_EQ(p, expected) << "radii " << radii.transpose() << ", direction "
                             << d.transpose() << " times 2^" << exponent;
    }
  }
}

// The same for a cone (ConeSupport::support: a direction whose largest component is within
// [2^-100, 2^100] is used as it is, for a radius and a half-length within [2^-200, 2^200]), on
// directions near the tie between the apex and the rim too, where the comparison's roundings
// decide: were the products not scaled exactly, some point would differ here.
TEST(Curved, ConeSupportsDoNotDependOnThePowerOfTwoOfTheDirection) {
  Random rng(31);
  for (int trial = 0; trial < 600; ++trial) {
    const Scalar r = std::exp(rng.uniform(-5, 5));
    const Scalar h = std::exp(rng.uniform(-5, 5));
    const Cone cone(r, h);
    Vector3 d = rng.unit();
    if (trial % 3 == 1) d.y() = 0;
    if (trial % 2 == 0) {
      // The apex and the rim equally high along d: h d_z = r |d_xy| - h d_z, to a rounding.
      d.z() = std::hypot(d.x(), d.y()) * r / (2 * h) * (1 + rng.uniform(-4, 4) * 1e-16);
    }
    const Vector3 expected = cone.curved()->support(d);
    for (int exponent : {-300, -102, -101, -100, -99, -40, 0, 40, 99, 100, 101, 102, 300}) {
      const Vector3 p = cone.curved()->support(d * std::ldexp(1.0, exponent));
      EXPECT_EQ(p, expected) << "r " << r << ", h " << h << ", direction " << d.transpose()
                             << " times 2^" << exponent;
    }
  }
}

// A framed curved body calls shapes.hpp's support functions by their exact type
// (FramedBody::curved_support, curved_supports.hpp), not through the virtual call: its support
// points are the virtual call's, bit for bit, for every kind (a kind mapped to another shape's
// function, or a copy of one that drifted, differs here). Enough directions that the body's cache
// of points grows its table (SupportCache::add_growing), after which a direction asked again
// answers the point's first number.
TEST(Curved, FramedSupportsAreTheShapesOwn) {
  Random rng(23);
  const ConvexPolyhedron shapes[] = {Cylinder(0.7, 0.4), Cone(0.5, 0.9),
                                     Ellipsoid(Vector3(0.3, 0.8, 0.5))};
  for (const ConvexPolyhedron& shape : shapes) {
    SCOPED_TRACE(shape.curved()->name());
    const detail::FramedPair pair = detail::frame_pair(shape, at(rng.vector(1), rng.rotation()),
                                                       shape, at(rng.vector(1)), 1e-9);
    const detail::FramedBody& body = pair.a;
    std::vector<Vector3> directions;
    std::vector<int> numbers;
    for (int k = 0; k < 300; ++k) {
      const Vector3 d = k % 5 == 0 ? Vector3(0, 0, k % 2 ? 1.0 : -1.0) : rng.unit();
      const int i = body.support_index(d);
      // The cache keeps a zero coordinate as +0.
      const Vector3 expected =
          shape.curved()->support(body.local_direction(d)) + Vector3::Zero();
      const Vector3 found = body.local_points().row(i).transpose();
      EXPECT_EQ(found, expected) << "direction " << d.transpose();
      directions.push_back(d);
      numbers.push_back(i);
    }
    EXPECT_GT(body.size(), 128);  // the table (128 slots at first) grew
    for (std::size_t k = 0; k < directions.size(); ++k) {
      EXPECT_EQ(body.support_index(directions[k]), numbers[k]);
    }
  }
}

// A curved body's support points live in a cache that its thread reuses from query to query
// (SharedSupportCache), started by reading the body's own table (SupportCache::reset) until the
// first point added copies it. Framed again after queries that added points (a hundred: the table
// grew too) to its own table and to another body's, a body numbers its support points as it did
// the first time: a point written into the body's own table, or a table kept from the last
// query, would be found again under a number from that query.
TEST(Curved, ReusedSupportCachesNumberAsNewOnes) {
  Random rng(31);
  const Cylinder cylinder(0.7, 0.4);
  const Cone cone(0.5, 0.9);
  std::vector<Vector3> directions;
  for (int k = 0; k < 100; ++k) directions.push_back(rng.unit());
  const Pose pose = at(Vector3(0.1, 0.2, 0.3), rng.rotation());
  // The numbers of the support points along `directions`, the first `count` of them, in one
  // framing of `shape`.
  const auto numbers = [&](const ConvexPolyhedron& shape, std::size_t count) {
    const detail::FramedPair pair = detail::frame_pair(shape, pose, shape, at(Vector3(1, 0, 0)),
                                                       kDefaultTolerance);
    EXPECT_EQ(pair.a.size(), shape.size());
    std::vector<int> found;
    for (std::size_t k = 0; k < count; ++k) found.push_back(pair.a.support_index(directions[k]));
    return found;
  };
  const std::vector<int> first = numbers(cylinder, directions.size());
  EXPECT_GT(*std::max_element(first.begin(), first.end()), 64);
  EXPECT_EQ(numbers(cylinder, directions.size()), first);
  EXPECT_EQ(numbers(cylinder, 3), std::vector<int>(first.begin(), first.begin() + 3));
  numbers(cone, directions.size());
  EXPECT_EQ(numbers(cylinder, directions.size()), first);
}

// A framed curved body reads its body's own points until it finds a new support point: a ball's
// closed form against a cylinder (point_against_curved), which finds none, takes no cache from the
// thread's pool (SharedSupportCache), whose taking, resetting and giving back were 150-200
// instructions of such a query. A copy of a pair made before the first new point shares the cache
// it then takes, and a new framing reads the body's own points again (the body's own are never
// added to).
TEST(Curved, ClosedFormsTakeNoSupportCache) {
  const Cylinder cylinder(0.7, 0.4);
  const Sphere ball(0.3);
  Random rng(37);
  const Pose pose = at(Vector3(0.1, 0.2, 0.3), rng.rotation());
  const Pose away = at(Vector3(2, 0.5, 0));
  const Vector3 d = rng.unit();
  // A cylinder pair's search leaves caches in the pool.
  Query().signed_distance(cylinder, pose, cylinder, away);
  const std::size_t pooled = detail::SharedSupportCache::pooled();
  ASSERT_GT(pooled, 0u);
  const detail::FramedPair pair =
      detail::frame_pair(cylinder, pose, ball, away, kDefaultTolerance);
  detail::Answer answer;
  ASSERT_TRUE(detail::point_against_curved(pair, detail::Goal::signed_distance, 100, answer));
  EXPECT_EQ(detail::SharedSupportCache::pooled(), pooled);
  EXPECT_EQ(pair.a.size(), cylinder.size());
  const detail::FramedPair copy = pair;
  EXPECT_EQ(detail::SharedSupportCache::pooled(), pooled - 1);
  const int found = copy.a.support_index(d);
  EXPECT_EQ(found, cylinder.size());
  EXPECT_EQ(pair.a.size(), cylinder.size() + 1);
  EXPECT_EQ(pair.a.vertex(found), copy.a.vertex(found));
  EXPECT_EQ(pair.a.support_index(d), found);
  const detail::FramedPair again =
      detail::frame_pair(cylinder, pose, ball, away, kDefaultTolerance);
  EXPECT_EQ(again.a.size(), cylinder.size());
  EXPECT_EQ(again.a.support_index(d), found);
  EXPECT_EQ(again.a.vertex(found), pair.a.vertex(found));
  EXPECT_EQ(detail::SharedSupportCache::pooled(), pooled - 2);
}

// A support cache numbers each point once, in the order found, at every fill of its table: a
// point it holds (asked again as found, or with -0 for +0) keeps its number and adds no row, also
// when the table is the start's, borrowed (a reused cache before its first new point), or full
// (the next new point grows it). add() writes a new point's row before it searches the table, so
// a point found must leave every held row as it was.
TEST(Curved, SupportCachesNumberEachPointOnce) {
  VertexMatrix own(3, 3);
  own << 1, 0, 0, 0, 1, 0, 0, 0, -1;
  const detail::SupportCache start(own);
  Random rng(37);
  std::vector<Vector3> points;
  for (int k = 0; k < 3; ++k) points.push_back(own.row(k).transpose());
  for (int k = 0; k < 300; ++k) points.push_back(rng.unit());
  for (int use = 0; use < 2; ++use) {  // a new cache, then one taken back from the pool
    SCOPED_TRACE(use);
    const detail::SharedSupportCache cache(start);
    EXPECT_EQ(cache->add(Vector3(0, -0.0, -1)), 2);  // held by the borrowed table
    EXPECT_EQ(cache->count(), 3);
    for (int i = 3; i < static_cast<int>(points.size()); ++i) {
      EXPECT_EQ(cache->add(points[i]), i);
      EXPECT_EQ(cache->add(points[i]), i);
      EXPECT_EQ(cache->add(points[i / 2]), i / 2);
      EXPECT_EQ(cache->add(points[0]), 0);
      ASSERT_EQ(cache->count(), i + 1);
    }
    for (int i = 0; i < cache->count(); ++i) {
      EXPECT_EQ(Vector3(cache->points().row(i).transpose()), points[i]) << i;
    }
  }
}

// The curved pairs' searches ask their supports inline (inline_minkowski_support): a cylinder's
// without its finiteness test (CylinderSupport::finite_support), and a curved body's point placed
// as it is found (FramedBody::inline_support) rather than read back from the body's points. Both
// are minkowski_support's, bit for bit: the same numbers and the same point, for every kind beside
// every kind, along axes (zero components in the unrotated body's frame) and random directions,
// asked first inline or first out of line (a point new to the cache, or one it holds). A copy of a
// support that drifted, or a point placed otherwise than the body's own, differs here.
TEST(Curved, SearchSupportsAreTheBodiesOwn) {
  Random rng(29);
  const ConvexPolyhedron shapes[] = {Cylinder(0.7, 0.4), Cone(0.5, 0.9),
                                     Ellipsoid(Vector3(0.3, 0.8, 0.5)),
                                     Box(Vector3(0.2, 0.5, 0.3))};
  for (const ConvexPolyhedron& a : shapes) {
    for (const ConvexPolyhedron& b : shapes) {
      const detail::FramedPair pair =
          detail::frame_pair(a, at(rng.vector(1), rng.rotation()), b, at(rng.vector(1)), 1e-9);
      for (int k = 0; k < 200; ++k) {
        const Vector3 d =
            k % 4 == 0 ? Vector3(Vector3::Unit(k / 4 % 3) * (k % 8 == 0 ? 1.0 : -1.0)) : rng.unit();
        int inline_a = -1;
        int inline_b = -1;
        int a_index = -1;
        int b_index = -1;
        detail::OraclePoint asked_inline;
        detail::OraclePoint asked;
        if (k % 2 == 0) {
          asked_inline = detail::inline_minkowski_support(pair, d, inline_a, inline_b);
          asked = detail::minkowski_support(pair.a, pair.b, d, a_index, b_index);
        } else {
          asked = detail::minkowski_support(pair.a, pair.b, d, a_index, b_index);
          asked_inline = detail::inline_minkowski_support(pair, d, inline_a, inline_b);
        }
        EXPECT_EQ(inline_a, a_index) << "direction " << d.transpose();
        EXPECT_EQ(inline_b, b_index) << "direction " << d.transpose();
        EXPECT_EQ(asked_inline.ia, asked.ia);
        EXPECT_EQ(asked_inline.ib, asked.ib);
        for (int c = 0; c < 3; ++c) {
          EXPECT_EQ(std::signbit(asked_inline.p(c)), std::signbit(asked.p(c)));
          EXPECT_EQ(asked_inline.p(c), asked.p(c)) << "direction " << d.transpose();
        }
      }
    }
  }
}

// FramedBody::add_support_curvature, the curvature NewtonDirection's steps read, is the
// derivative of the framed support point on the vectors across the direction: turning a unit
// direction by a small angle along w moves the point by the derivative times the turn, to second
// order (the finite difference of two support points asked inline, as the searches ask them), so
// w and u across the direction read the motion as w^T K w and u^T K w. Directions near a
// cylinder's or a cone's axis, or near a rim's or the apex's switch, are left out: the model
// holds within one smooth part of the surface.
TEST(Curved, SupportCurvaturesAreTheSupportPointsMotion) {
  Random rng(41);
  const ConvexPolyhedron shapes[] = {Cylinder(0.7, 0.4), Cone(0.5, 0.9),
                                     Ellipsoid(Vector3(0.3, 0.8, 0.5)),
                                     Box(Vector3(0.2, 0.5, 0.3))};
  constexpr Scalar kTurn = 1e-6;
  int compared = 0;
  for (const ConvexPolyhedron& shape : shapes) {
    const Pose pose = at(rng.vector(1), rng.rotation());
    const detail::FramedPair pair = detail::frame_pair(shape, pose, shape, Pose{}, 1e-9);
    const detail::FramedBody& body = pair.a;
    for (int k = 0; k < 200; ++k) {
      const Vector3 d = rng.unit();
      const Vector3 w = d.cross(rng.unit()).normalized();
      const Vector3 u = d.cross(w);
      const Vector3 e = (d + kTurn * w).normalized();
      const Vector3 local_d = pose.rotation.transpose() * d;
      if (std::abs(local_d.z()) < 0.05 || std::hypot(local_d.x(), local_d.y()) < 0.05) continue;
      int index = -1;
      const Vector3 from = body.inline_support(d, index);
      const Vector3 to = body.inline_support(e, index);
      if (body.curved_kind() == detail::CurvedKind::cone && (from.z() > 0) != (to.z() > 0)) {
        continue;
      }
      if (body.curved_kind() == detail::CurvedKind::other && !(to - from).isZero()) continue;
      Vector3 form = Vector3::Zero();
      ASSERT_TRUE(body.add_support_curvature(d, w, u, form));
      // A point moves by about the radius times the turn; second order and rounding stay
      // far below a thousandth of that.
      EXPECT_NEAR(w.dot(to - from), kTurn * form(0), 1e-3 * kTurn) << shape.size() << " " << k;
      EXPECT_NEAR(u.dot(to - from), kTurn * form(1), 1e-3 * kTurn) << shape.size() << " " << k;
      EXPECT_GE(form(0), 0);
      EXPECT_GE(form(2), 0);
      EXPECT_LE(form(1) * form(1), form(0) * form(2) * (1 + 1e-12) + 1e-300);
      ++compared;
    }
  }
  EXPECT_GT(compared, 400);
}

// Cylinders and cones among themselves search with Newton's steps, along a crease where the
// nearest point lies on a mantle (NewtonDirection's Crease): two cylinders side by side with
// crossed axes (both nearest points on the mantles, the direction normal to both axes), a rim
// against a mantle, random poses, and cones beside cylinders and cones. Every answer is proven,
// encloses the exact method's at a tolerance far below the default, and is the closed form
// where there is one.
TEST(Curved, NewtonStepsAlongCreasesKeepCylinderAndConePairsProven) {
  Random rng(47);
  const Query dual = query_of(Method::dual, 1e-12);
  const Query exact = query_of(Method::exact, 1e-12);
  const auto check = [&](const ConvexPolyhedron& a, const Pose& pa, const ConvexPolyhedron& b,
                         const Pose& pb) {
    const DistanceResult d = dual.signed_distance(a, pa, b, pb);
    const DistanceResult e = exact.signed_distance(a, pa, b, pb);
    const Scalar size = size_of(a, pa, b, pb);
    // The steps search pairs apart; an overlapping pair's depth at this tolerance is the
    // expanding polytope's, which may stop short of it (uncertified, its bounds still proven).
    if (e.lower_bound > 0) EXPECT_TRUE(d.certified);
    EXPECT_LE(d.lower_bound, e.distance + 1e-14 * size);
    EXPECT_LE(e.lower_bound, d.distance + 1e-14 * size);
    return d;
  };
  for (int i = 0; i < 300; ++i) {
    SCOPED_TRACE(i);
    const Scalar ra = rng.uniform(0.1, 1);
    const Scalar rb = rng.uniform(0.1, 1);
    const Cylinder a(ra, rng.uniform(0.3, 1));
    const Cylinder b(rb, rng.uniform(0.3, 1));
    const Scalar gap = rng.uniform(1e-3, 0.5);
    if (i % 3 == 0) {
      // Axes along z and along a direction across x (turned by 0.5 to 2.6 from z), the mantles
      // facing each other across the gap along x: their lines cross within 0.15 of both
      // centres (inside the half-lengths), so the distance is the gap.
      const Scalar turn = rng.uniform(0.5, 2.6);
      const Pose pb = at(Vector3(ra + rb + gap, rng.uniform(-0.05, 0.05), rng.uniform(-0.05, 0.05)),
                         Eigen::AngleAxisd(turn, Vector3::UnitX()).toRotationMatrix());
      const DistanceResult d = check(a, Pose{}, b, pb);
      EXPECT_NEAR(d.distance, gap, 1e-11 * size_of(a, Pose{}, b, pb));
    } else if (i % 3 == 1) {
      // B's rim against A's mantle: B tilted, a rim point nearest A's side.
      const Pose pb = at(Vector3(ra + gap + rb, 0, rng.uniform(-0.2, 0.2)),
                         Eigen::AngleAxisd(rng.uniform(0.3, 1.2), Vector3::UnitY())
                             .toRotationMatrix());
      check(a, Pose{}, b, pb);
    } else {
      check(a, at(Vector3::Zero(), rng.rotation()), b, at(rng.vector(1.6), rng.rotation()));
    }
    // Cones beside cylinders and cones: their creases (apex against base rim) turn with the
    // direction's azimuth.
    const Cone cone(rng.uniform(0.1, 1), rng.uniform(0.1, 1));
    const Pose pa = at(Vector3::Zero(), rng.rotation());
    if (i % 2 == 0) {
      check(cone, pa, b, at(rng.vector(1.6), rng.rotation()));
    } else {
      check(a, pa, Cone(rng.uniform(0.1, 1), rng.uniform(0.1, 1)),
            at(rng.vector(1.6), rng.rotation()));
      check(cone, pa, Cone(rng.uniform(0.1, 1), rng.uniform(0.1, 1)),
            at(rng.vector(1.6), rng.rotation()));
    }
  }
}

// Cylinders and cones among themselves search along their creases only below a frame tolerance
// of 1e-7 (curved_search.cpp's kCreaseStepsBelow), and without the steps above it: at relative
// tolerances on both sides every answer apart is certified and encloses the exact method's at
// 1e-12.
TEST(Curved, CylinderAndConePairsStayProvenWithAndWithoutCreaseSteps) {
  Random rng(52);
  const Query exact = query_of(Method::exact, 1e-12);
  int apart = 0;
  for (const Scalar tolerance : {1e-9, 3e-8, 3e-7, 1e-6}) {
    SCOPED_TRACE(tolerance);
    const Query dual = query_of(Method::dual, tolerance);
    for (int i = 0; i < 60; ++i) {
      SCOPED_TRACE(i);
      const Cylinder cylinder(rng.uniform(0.1, 1), rng.uniform(0.1, 1));
      const Cone cone(rng.uniform(0.1, 1), rng.uniform(0.1, 1));
      const ConvexPolyhedron& a = i % 2 == 0 ? static_cast<const ConvexPolyhedron&>(cylinder)
                                             : static_cast<const ConvexPolyhedron&>(cone);
      const ConvexPolyhedron& b = i % 3 == 0 ? static_cast<const ConvexPolyhedron&>(cylinder)
                                             : static_cast<const ConvexPolyhedron&>(cone);
      const Pose pa = at(rng.vector(0.2), rng.rotation());
      const Pose pb = at(rng.vector(1.6), rng.rotation());
      const DistanceResult d = dual.signed_distance(a, pa, b, pb);
      const DistanceResult e = exact.signed_distance(a, pa, b, pb);
      const Scalar size = size_of(a, pa, b, pb);
      if (e.lower_bound > 0) {
        ++apart;
        EXPECT_TRUE(d.certified);
      }
      EXPECT_LE(d.lower_bound, e.distance + 1e-14 * size);
      EXPECT_LE(e.lower_bound, d.distance + 1e-14 * size);
    }
  }
  EXPECT_GT(apart, 60);
}

// Ellipsoids beside cylinders, cones and boxes search with Newton's steps on the separating
// direction (NewtonDirection): every answer apart is proven, and encloses the exact method's at
// a tolerance far below the default. An overlap's expanding polytope may reach the rounding's
// floor with its normal too far off the optimal one for witnesses along it (6 of 94 here, whose
// witnesses were 10 to 700 tolerances off before session 49): those are not certified, and every
// certified answer's witnesses lie along its direction to the tolerance.
TEST(Curved, NewtonStepsKeepEllipsoidPairsProven) {
  Random rng(43);
  constexpr Scalar kTolerance = 1e-12;
  const Query dual = query_of(Method::dual, kTolerance);
  const Query exact = query_of(Method::exact, kTolerance);
  int overlapping = 0;
  int unproven = 0;
  for (int i = 0; i < 400; ++i) {
    const ConvexPolyhedron ellipsoid(
        Ellipsoid(Vector3(rng.uniform(0.1, 1), rng.uniform(0.1, 1), rng.uniform(0.1, 1))));
    const Scalar r = rng.uniform(0.1, 1);
    const Scalar h = rng.uniform(0.1, 1);
    const ConvexPolyhedron other = i % 3 == 0   ? ConvexPolyhedron(Cylinder(r, h))
                                   : i % 3 == 1 ? ConvexPolyhedron(Cone(r, h))
                                                : ConvexPolyhedron(Box(Vector3(r, h, r)));
    const Pose pa = at(Vector3::Zero(), rng.rotation());
    const Pose pb = at(rng.vector(1.6), rng.rotation());
    const DistanceResult d = dual.signed_distance(ellipsoid, pa, other, pb);
    const DistanceResult e = exact.signed_distance(ellipsoid, pa, other, pb);
    const Scalar size = size_of(ellipsoid, pa, other, pb);
    SCOPED_TRACE(i);
    if (d.lower_bound > 0) EXPECT_TRUE(d.certified);
    overlapping += d.distance < 0;
    unproven += !d.certified;
    for (const DistanceResult* r : {&d, &e}) {
      if (r->certified) {
        EXPECT_LE((r->point_b - r->point_a - r->distance * r->direction).norm(),
                  kTolerance * size);
      }
    }
    EXPECT_LE(d.lower_bound, e.distance + 1e-14 * size);
    EXPECT_LE(e.lower_bound, d.distance + 1e-14 * size);
  }
  EXPECT_GT(overlapping, 80);
  EXPECT_LE(unproven, 10) << "of " << overlapping;
}

// An ellipsoid nearest a box's edge: the separation has a crease there (the box's support jumps
// between the edge's ends as the direction crosses the normals to it), which Newton's steps follow
// once the directions have crossed it and come back (NewtonDirection<true>'s edges). Boxes turned
// by 45 degrees about z face +x with an edge along z; ellipsoids turned anyhow stand off it along
// x. Every answer is certified at 1e-12 and encloses the exact method's, the nearest points lie
// inside the edge, and the searches ask fewer support points than they did without the steps
// (here 19.8 a pair -> 10.4; on random ellipsoid-box pairs nearest an edge, 20.1 -> 12.5).
TEST(Curved, NewtonStepsFollowABoxEdgeBesideAnEllipsoid) {
  Random rng(61);
  constexpr Scalar kTolerance = 1e-12;
  const Query dual = query_of(Method::dual, kTolerance);
  const Query exact = query_of(Method::exact, kTolerance);
  const Matrix3 turned = Eigen::AngleAxisd(kPi / 4, Vector3::UnitZ()).toRotationMatrix();
  long evaluations = 0;
  int on_edge = 0;
  constexpr int kPairs = 200;
  for (int i = 0; i < kPairs; ++i) {
    SCOPED_TRACE(i);
    const Vector3 half(rng.uniform(0.2, 0.6), rng.uniform(0.2, 0.6), rng.uniform(0.4, 0.8));
    const Box box(half);
    // The edge through the corner (x, -y) turned, along z.
    const Vector3 edge = turned * Vector3(half.x(), -half.y(), 0);
    const Ellipsoid ellipsoid(
        Vector3(rng.uniform(0.1, 0.5), rng.uniform(0.1, 0.5), rng.uniform(0.1, 0.5)));
    const Pose pa = at(edge + Vector3(0.6 + rng.uniform(0, 0.3), rng.uniform(-0.05, 0.05),
                                      rng.uniform(-0.2, 0.2)),
                       rng.rotation());
    const Pose pb = at(Vector3::Zero(), turned);
    const DistanceResult d = dual.signed_distance(ellipsoid, pa, box, pb);
    const DistanceResult e = exact.signed_distance(ellipsoid, pa, box, pb);
    const Scalar size = size_of(ellipsoid, pa, box, pb);
    ASSERT_GT(e.lower_bound, 0);
    EXPECT_TRUE(d.certified);
    EXPECT_LE(d.lower_bound, e.distance + 1e-14 * size);
    EXPECT_LE(e.lower_bound, d.distance + 1e-14 * size);
    evaluations += d.evaluations;
    // The box's witness on two of its faces at once, away from the corners: on the edge.
    const Vector3 local = turned.transpose() * d.point_b;
    const int faces = (std::abs(std::abs(local.x()) - half.x()) < 1e-9) +
                      (std::abs(std::abs(local.y()) - half.y()) < 1e-9) +
                      (std::abs(std::abs(local.z()) - half.z()) < 1e-9);
    on_edge += faces == 2;
  }
  EXPECT_GE(on_edge, kPairs * 9 / 10);
  EXPECT_LT(static_cast<double>(evaluations) / kPairs, 14);
}

// A box's edge against a cylinder's rim, overlapping (robots census case robots-1-3295): the
// expanding polytope closed to a tenth of the tolerance along a normal whose supporting features'
// nearest points lay 3.8 tolerances off it, and the answer was certified with them. The
// expansion now goes on until witnesses lie along its normal.
TEST(Curved, WitnessesOfABoxEdgeInACylinderRimLieAlongTheNormal) {
  Matrix3 rotation_a;
  rotation_a << -0.5402072765984005, 0.8410667042330601, -0.02798030272669577,
      0.5495674132411564, 0.3777704534432016, 0.7451611522407365, 0.6373003660861678,
      0.38716441408767976, -0.6662972008425224;
  Matrix3 rotation_b;
  rotation_b << 0.11840681389290009, -0.9026557936624895, -0.413753966254432,
      0.4482926517940512, -0.3232077487098259, 0.833408932950316, -0.8860098897705323,
      -0.28416415914303417, 0.36638395964799375;
  const Pose pa = at(Vector3(-0.352032723847248, -0.011389722804565072, -0.21061492195502896),
                     rotation_a);
  const Pose pb = at(Vector3(-0.2748651444512399, -0.11664247734294494, -0.21981545060020208),
                     rotation_b);
  const Box box(Vector3(0.04579934128043067, 0.09471072331471757, 0.10243019143010905));
  const Cylinder cylinder(0.1305779060912093, 0.13601317581951358);
  const Scalar size = size_of(box, pa, cylinder, pb);
  for (Method method : kCurvedMethods) {
    SCOPED_TRACE(method_name(method));
    const DistanceResult r = query_of(method).signed_distance(box, pa, cylinder, pb);
    EXPECT_TRUE(r.certified);
    // The depth as the dual method proves it at a tolerance of 1e-13.
    EXPECT_NEAR(r.distance, -0.10432369668968, kDefaultTolerance * size);
    EXPECT_LE((r.point_b - r.point_a - r.distance * r.direction).norm(),
              kDefaultTolerance * size);
  }
}

// The closed form of a ball against a cylinder or a cone (point_against_curved) takes the second
// rim point of a pair from the first by a symmetry of the support function rather than asking it:
// a cylinder's rim points along (x, y, 1) and (x, y, -1) differ only in the sign of their height,
// and a cylinder's along (x, y, s) and (-x, -y, s), and a cone's along (x, y, -1) and (-x, -y, -1),
// only in the signs of x and y, bit for bit (with -0 as +0, as the closed form mirrors them). A
// support function that lost the symmetry (a rounding that depends on a sign) fails here.
TEST(Curved, RimPointsAcrossAndAboveEachOtherAreMirrorImages) {
  Random rng(41);
  const Cylinder cylinder(0.7, 0.4);
  const Cone cone(0.5, 0.9);
  const auto mirrored = [](Vector3 p, bool height) {
    if (height) {
      p.z() = -p.z();
    } else {
      p.x() = -p.x();
      p.y() = -p.y();
    }
    return Vector3(p + Vector3::Zero());
  };
  const auto support = [](const ConvexPolyhedron& shape, const Vector3& d) {
    return Vector3(shape.curved()->support(d) + Vector3::Zero());
  };
  for (int k = 0; k < 2000; ++k) {
    // Unit azimuths as the closed form makes them, some on an axis, and directions of any length.
    Vector3 d = rng.unit();
    if (k % 7 == 0) d.x() = 0;
    if (k % 11 == 0) d.y() = 0;
    const Scalar length = std::hypot(d.x(), d.y());
    const Scalar ux = length > 0 ? d.x() / length : 1;
    const Scalar uy = length > 0 ? d.y() / length : 0;
    const Scalar s = k % 2 ? 1.0 : -1.0;
    const Scalar scale = std::ldexp(1.0, static_cast<int>(rng.uniform(-60, 60)));
    SCOPED_TRACE(::testing::Message() << "azimuth " << ux << " " << uy << " scale " << scale);
    EXPECT_EQ(support(cylinder, scale * Vector3(ux, uy, -1)),
              mirrored(support(cylinder, scale * Vector3(ux, uy, 1)), true));
    EXPECT_EQ(support(cylinder, scale * Vector3(-ux, -uy, s)),
              mirrored(support(cylinder, scale * Vector3(ux, uy, s)), false));
    EXPECT_EQ(support(cone, scale * Vector3(-ux, -uy, -1)),
              mirrored(support(cone, scale * Vector3(ux, uy, -1)), false));
  }
}

// A random ball near a random shape of radius `r` and half-length `h`: the ball's centre at
// `local` in the shape's frame.
struct BallNearShape {
  explicit BallNearShape(Random& rng)
      : r(rng.uniform(0.2, 2)),
        h(rng.uniform(0.2, 2)),
        ball(rng.uniform(0.05, 0.5)),
        turn(rng.rotation()),
        pose_shape(at(rng.vector(1), turn)),
        local(rng.vector(3)),
        pose_ball(at(turn * local + pose_shape.translation)) {}

  Scalar r;
  Scalar h;
  Sphere ball;
  Matrix3 turn;
  Pose pose_shape;
  Vector3 local;
  Pose pose_ball;
};

TEST(Curved, SpheresAgainstCylindersAndConesMatchThePointDistance) {
  Random rng(13);
  for (int trial = 0; trial < 30; ++trial) {
    const BallNearShape pair(rng);
    const Scalar r = pair.r;
    const Scalar h = pair.h;
    const Cylinder cylinder(r, h);
    const Cone cone(r, h);
    const Sphere& ball = pair.ball;
    const Pose& pose_shape = pair.pose_shape;
    const Vector3& local = pair.local;
    const Pose& pose_ball = pair.pose_ball;
    for (Method method : kCurvedMethods) {
      SCOPED_TRACE(method_name(method));
      const Query query = query_of(method);
      const Scalar to_cylinder = point_to_cylinder(local, r, h) - ball.radius();
      const Scalar size_c = size_of(cylinder, pose_shape, ball, pose_ball);
      expect_answer(query.signed_distance(cylinder, pose_shape, ball, pose_ball), to_cylinder,
                    size_c);
      expect_answer(query.distance(ball, pose_ball, cylinder, pose_shape),
                    std::max(to_cylinder, 0.0), size_c);
      const DistanceResult verdict = query.collision(cylinder, pose_shape, ball, pose_ball);
      EXPECT_TRUE(verdict.certified);
      EXPECT_EQ(verdict.colliding, to_cylinder <= kDefaultTolerance * size_c);
      const Scalar to_cone = point_to_cone(local, r, h) - ball.radius();
      const Scalar size_k = size_of(cone, pose_shape, ball, pose_ball);
      expect_answer(query.signed_distance(ball, pose_ball, cone, pose_shape), to_cone, size_k);
      expect_answer(query.distance(cone, pose_shape, ball, pose_ball), std::max(to_cone, 0.0),
                    size_k);
    }
  }
}

// The closed form of a point against a shape finds its witness on the shape from support points
// that it does not number among the shape's (curved_point.cpp): the witness is still a point of
// the cylinder, at the answer's distance from the ball's, and the ball's weights are its one
// point's (a curved body reports none).
TEST(Curved, ClosedFormWitnessesLieOnTheShapeAndTheBall) {
  Random rng(31);
  for (int trial = 0; trial < 30; ++trial) {
    const BallNearShape pair(rng);
    const Cylinder cylinder(pair.r, pair.h);
    const DistanceResult d =
        Query().signed_distance(cylinder, pair.pose_shape, pair.ball, pair.pose_ball);
    ASSERT_TRUE(d.certified);
    const Vector3 on_shape = pair.turn.transpose() * (d.point_a - pair.pose_shape.translation);
    const Scalar slack = 1e-12;
    EXPECT_LE(std::hypot(on_shape.x(), on_shape.y()), pair.r + slack);
    EXPECT_LE(std::abs(on_shape.z()), pair.h + slack);
    if (d.distance > 0) {
      EXPECT_NEAR((d.point_b - pair.pose_ball.translation).norm(), pair.ball.radius(), slack);
      EXPECT_NEAR((d.point_b - d.point_a).norm(), d.distance, slack);
    }
    EXPECT_EQ(d.weights_a.count(), 0);
    ASSERT_EQ(d.weights_b.count(), 1);
    EXPECT_NEAR(d.weights_b.dense()(0), 1, 1e-15);
  }
}

// A ball whose centre lies inside a cylinder or a cone: the closed form answers its signed
// distance (point_against_curved, one iteration) rather than the penetration solver, either way
// round, with the centre on the axis, at the shape's middle, and nearest the mantle, a cap, the
// base or the slant. The bounds enclose the point's depth less the radius, certified, and the
// witness on the shape lies on its surface, the ball's witness its surface point along the
// normal: `point_b - point_a = distance * direction`.
TEST(Curved, BallCentresInsideAreAnsweredByTheClosedForm) {
  Random rng(37);
  for (int trial = 0; trial < 40; ++trial) {
    const Scalar r = rng.uniform(0.2, 2);
    const Scalar h = rng.uniform(0.2, 2);
    const Sphere ball(rng.uniform(0.05, 0.5));
    const Matrix3 turn = rng.rotation();
    const Pose pose_shape = at(rng.vector(1), turn);
    // Points of the cylinder: on its axis, at its middle, or anywhere inside. The cone holds
    // those below its slant.
    Vector3 local(rng.uniform(-r, r), rng.uniform(-r, r), rng.uniform(-h, h));
    if (trial % 8 == 0) local.head<2>().setZero();
    if (trial % 16 == 8) local.setZero();
    if (local.head<2>().norm() >= r) local.head<2>() *= 0.5;
    const bool in_cone = 2 * h * local.head<2>().norm() < r * (h - local.z());
    const Pose pose_ball = at(turn * local + pose_shape.translation);
    const Cylinder cylinder(r, h);
    const Cone cone(r, h);
    for (const ConvexPolyhedron* shape : {static_cast<const ConvexPolyhedron*>(&cylinder),
                                          static_cast<const ConvexPolyhedron*>(&cone)}) {
      const bool is_cone = shape == &cone;
      if (is_cone && !in_cone) continue;
      SCOPED_TRACE(::testing::Message() << shape->curved()->name() << " trial " << trial);
      const Scalar expected =
          (is_cone ? point_to_cone(local, r, h) : point_to_cylinder(local, r, h)) - ball.radius();
      const Scalar size = size_of(*shape, pose_shape, ball, pose_ball);
      for (bool shape_first : {true, false}) {
        const DistanceResult d = shape_first
                                     ? Query().signed_distance(*shape, pose_shape, ball, pose_ball)
                                     : Query().signed_distance(ball, pose_ball, *shape, pose_shape);
        expect_answer(d, expected, size);
        EXPECT_EQ(d.iterations, 1);
        EXPECT_TRUE(d.colliding);
        const Vector3 on_shape = shape_first ? d.point_a : d.point_b;
        const Vector3 on_ball = shape_first ? d.point_b : d.point_a;
        const Vector3 in_frame = turn.transpose() * (on_shape - pose_shape.translation);
        EXPECT_NEAR(is_cone ? point_to_cone(in_frame, r, h) : point_to_cylinder(in_frame, r, h),
                    0, 1e-12 * size);
        EXPECT_NEAR((on_ball - pose_ball.translation).norm(), ball.radius(), 1e-12 * size);
        EXPECT_LT((d.point_b - d.point_a - d.distance * d.direction).norm(), 1e-12 * size);
      }
    }
  }
}

TEST(Curved, CoaxialAndSideBySideCylinders) {
  const Cylinder a(1, 2);
  const Cylinder b(0.5, 1);
  for (Method method : kCurvedMethods) {
    SCOPED_TRACE(method_name(method));
    const Query query = query_of(method);
    // Coaxial, the caps 0.25 apart, then overlapping by 0.25 (the depth along the axis: the
    // radial way out is 1.5).
    for (Scalar gap : {0.25, -0.25}) {
      const Pose pb = at(Vector3(0, 0, 3 + gap));
      const Scalar size = size_of(a, {}, b, pb);
      expect_answer(query.signed_distance(a, {}, b, pb), gap, size);
      expect_answer(query.distance(a, {}, b, pb), std::max(gap, 0.0), size);
      EXPECT_EQ(query.collide(a, {}, b, pb), gap < 0);
    }
    // Side by side, parallel axes 2 apart: 0.5 between the mantles.
    const Pose side = at(Vector3(2, 0, 0.5));
    expect_answer(query.signed_distance(a, {}, b, side), 0.5, size_of(a, {}, b, side));
    // Crossed: b lying along x above a's cap.
    Matrix3 lying;
    lying << 0, 0, 1, 0, 1, 0, -1, 0, 0;  // z onto x
    const Pose crossed = at(Vector3(0.3, 0.1, 2.75), lying);
    expect_answer(query.distance(a, {}, b, crossed), 0.25, size_of(a, {}, b, crossed));
  }
}

// Long cylinders lying side by side along x, staggered so that the direction between their
// centres does not separate them: the signed distance's Wolfe walk runs, finds a separating
// direction, and the distance search goes on from its corral (overlap_first). The mantles are
// 0.3 apart, at tolerances down to 1e-12.
TEST(Curved, StaggeredPairsApartAlongNoCentreDirection) {
  const Cylinder a(0.1, 2);
  const Cone b(0.1, 2);
  Matrix3 lying;
  lying << 0, 0, 1, 0, 1, 0, -1, 0, 0;  // z onto x
  const Pose pa = at(Vector3::Zero(), lying);
  for (Scalar tolerance : {1e-9, 1e-12}) {
    SCOPED_TRACE(tolerance);
    const Query query = query_of(Method::dual, tolerance);
    const Pose cylinder = at(Vector3(3.8, 0.5, 0), lying);
    expect_answer(query.signed_distance(a, pa, a, cylinder), 0.3, size_of(a, pa, a, cylinder),
                  tolerance);
    // The cone's base (x = 1.8) faces the cylinder's end: its rim is 0.3 from the mantle.
    const Pose cone = at(Vector3(3.8, 0.5, 0), lying);
    expect_answer(query.signed_distance(a, pa, b, cone), 0.3, size_of(a, pa, b, cone), tolerance);
  }
}

// An ellipsoid against a box face: the distance is the face's offset less the support value of
// the (turned) ellipsoid along the face normal.
TEST(Curved, EllipsoidAgainstABoxFace) {
  Random rng(17);
  const Box wall(Vector3(0.1, 3, 3));
  for (int trial = 0; trial < 20; ++trial) {
    const Vector3 radii(rng.uniform(0.2, 1), rng.uniform(0.2, 1), rng.uniform(0.2, 1));
    const Ellipsoid e(radii);
    const Matrix3 turn = rng.rotation();
    const Scalar face = rng.uniform(0.5, 1.5);
    const Pose pose_wall = at(Vector3(face + 0.1, 0, 0));
    const Scalar expected = face - ellipsoid_support(radii, turn, Vector3::UnitX());
    for (Method method : kCurvedMethods) {
      SCOPED_TRACE(method_name(method));
      const Query query = query_of(method);
      const Scalar size = size_of(e, at(Vector3::Zero(), turn), wall, pose_wall);
      expect_answer(query.signed_distance(e, at(Vector3::Zero(), turn), wall, pose_wall), expected,
                    size);
      expect_answer(query.distance(wall, pose_wall, e, at(Vector3::Zero(), turn)),
                    std::max(expected, 0.0), size);
    }
  }
}

// Two ellipsoids along x touching to within 1e-9 of their size, at tolerance 1e-12: apart or in
// contact as the gap says, and certified.
TEST(Curved, NearlyTouchingShapesGetTheRightVerdict) {
  const Ellipsoid a(Vector3(1, 0.5, 0.7));
  const Ellipsoid b(Vector3(0.6, 0.9, 0.4));
  const Cylinder c(0.6, 0.9);
  for (Scalar relative : {1e-9, -1e-9}) {
    const Scalar gap = relative * 4;
    const Pose pb = at(Vector3(1.6 + gap, 0, 0));
    Matrix3 lying;
    lying << 0, 0, 1, 0, 1, 0, -1, 0, 0;  // the cylinder's axis along x: its cap faces a
    const Pose pc = at(Vector3(1.9 + gap, 0, 0), lying);
    for (Method method : kCurvedMethods) {
      SCOPED_TRACE(method_name(method));
      const Query query = query_of(method, 1e-12);
      const DistanceResult ab = query.collision(a, {}, b, pb);
      EXPECT_TRUE(ab.certified);
      EXPECT_EQ(ab.colliding, gap < 0);
      const DistanceResult sd = query.signed_distance(a, {}, b, pb);
      expect_answer(sd, gap, size_of(a, {}, b, pb), 1e-12);
      const DistanceResult ac = query.collision(a, {}, c, pc);
      EXPECT_TRUE(ac.certified);
      EXPECT_EQ(ac.colliding, gap < 0);
      expect_answer(query.signed_distance(a, {}, c, pc), gap, size_of(a, {}, c, pc), 1e-12);
    }
  }
}

// The same pair in any unit: a cylinder and a cone (and an ellipsoid) scaled by 10^k answer the
// scaled distance.
TEST(Curved, TheAnswerDoesNotDependOnTheUnit) {
  const Matrix3 turn = Random(19).rotation();
  std::vector<Scalar> unit_answers;
  for (Scalar scale : {1e-100, 1e-50, 1.0, 3e7, 1e50, 1e100}) {
    SCOPED_TRACE(scale);
    const Cylinder cylinder(0.5 * scale, 1 * scale);
    const Cone cone(0.7 * scale, 0.4 * scale);
    const Ellipsoid ellipsoid(Vector3(0.3, 0.6, 0.9) * scale);
    const Pose pose_cone = at(Vector3(0.9, 0.4, 0.2) * scale, turn);
    const Pose pose_ellipsoid = at(Vector3(-0.2, 0.3, 1.3) * scale, turn.transpose());
    for (Method method : kCurvedMethods) {
      SCOPED_TRACE(method_name(method));
      const Query query = query_of(method);
      const DistanceResult one = query.signed_distance(cylinder, {}, cone, pose_cone);
      const DistanceResult two = query.signed_distance(cylinder, {}, ellipsoid, pose_ellipsoid);
      const DistanceResult three = query.distance(cone, pose_cone, ellipsoid, pose_ellipsoid);
      for (const DistanceResult* r : {&one, &two, &three}) {
        EXPECT_TRUE(r->certified);
        EXPECT_LE(r->lower_bound, r->distance);
      }
      if (scale == 1e-100 && method == Method::dual) {
        for (const DistanceResult* r : {&one, &two, &three}) {
          unit_answers.push_back(r->distance / scale);
        }
      } else {
        int k = 0;
        for (const DistanceResult* r : {&one, &two, &three}) {
          EXPECT_NEAR(r->distance / scale, unit_answers[k++], 2 * kDefaultTolerance * 4);
        }
      }
    }
  }
}

// Points on a cylinder's rims, n per rim: the inner polytope, within r (1 - cos(pi / n)) of the
// cylinder everywhere (the chord's sagitta).
ConvexPolyhedron cylinder_points(Scalar r, Scalar h, int n, Scalar& hausdorff) {
  VertexMatrix v(2 * n, 3);
  for (int i = 0; i < n; ++i) {
    const Scalar t = 2 * kPi * i / n;
    v.row(2 * i) << r * std::cos(t), r * std::sin(t), -h;
    v.row(2 * i + 1) << r * std::cos(t), r * std::sin(t), h;
  }
  hausdorff = r * (1 - std::cos(kPi / n)) * (1 + 1e-9) + 1e-14;
  return ConvexPolyhedron(v);
}

ConvexPolyhedron cone_points(Scalar r, Scalar h, int n, Scalar& hausdorff) {
  VertexMatrix v(n + 1, 3);
  for (int i = 0; i < n; ++i) {
    const Scalar t = 2 * kPi * i / n;
    v.row(i) << r * std::cos(t), r * std::sin(t), -h;
  }
  v.row(n) << 0, 0, h;
  hausdorff = r * (1 - std::cos(kPi / n)) * (1 + 1e-9) + 1e-14;
  return ConvexPolyhedron(v);
}

// An ellipsoid's points: the unit sphere's on a latitude-longitude grid, stretched. The sphere's
// polytope holds the ball of its least face distance, so the ellipsoid is within the largest
// radius times (1 - that) of the stretched polytope.
ConvexPolyhedron ellipsoid_points(const Vector3& radii, int n, Scalar& hausdorff) {
  std::vector<Vector3> sphere;
  sphere.emplace_back(0, 0, 1);
  sphere.emplace_back(0, 0, -1);
  for (int i = 1; i < n; ++i) {
    const Scalar polar = kPi * i / n;
    for (int j = 0; j < 2 * n; ++j) {
      const Scalar t = kPi * j / n;
      sphere.emplace_back(std::sin(polar) * std::cos(t), std::sin(polar) * std::sin(t),
                          std::cos(polar));
    }
  }
  VertexMatrix unit(static_cast<Eigen::Index>(sphere.size()), 3);
  for (std::size_t i = 0; i < sphere.size(); ++i) unit.row(i) = sphere[i].transpose();
  const ConvexPolyhedron ball(unit);
  const Hull& hull = ball.hull();
  Scalar inner = 1;
  for (Eigen::Index f = 0; f < hull.faces.rows(); ++f) {
    const Vector3 p = unit.row(hull.faces(f, 0));
    const Vector3 normal =
        (Vector3(unit.row(hull.faces(f, 1))) - p).cross(Vector3(unit.row(hull.faces(f, 2))) - p);
    inner = std::min(inner, std::abs(normal.normalized().dot(p)));
  }
  hausdorff = radii.maxCoeff() * (1 - inner) * (1 + 1e-6) + 1e-14;
  VertexMatrix v = unit;
  for (Eigen::Index i = 0; i < v.rows(); ++i) v.row(i) = v.row(i).cwiseProduct(radii.transpose());
  return ConvexPolyhedron(v);
}

// Random posed pairs of every curved kind (and curved against a rounded box): the signed distance
// lies between the inner polytopes' and that less both Hausdorff distances (sd can only grow as a
// body shrinks, and by no more than the distance it shrinks by).
TEST(Curved, RandomPosedPairsLieWithinTheirPolytopeBrackets) {
  Random rng(23);
  const Query polytopes = query_of(Method::exact);
  for (int trial = 0; trial < 12; ++trial) {
    const Scalar r = rng.uniform(0.2, 1);
    const Scalar h = rng.uniform(0.2, 1);
    const Vector3 radii(rng.uniform(0.2, 1), rng.uniform(0.2, 1), rng.uniform(0.2, 1));
    struct Made {
      ConvexPolyhedron shape;
      ConvexPolyhedron inner;
      Scalar hausdorff;
    };
    const auto make = [&](int kind) -> Made {
      Scalar e = 0;
      switch (kind) {
        case 0: {
          ConvexPolyhedron inner = cylinder_points(r, h, 256, e);
          return {Cylinder(r, h), inner, e};
        }
        case 1: {
          ConvexPolyhedron inner = cone_points(r, h, 256, e);
          return {Cone(r, h), inner, e};
        }
        case 2: {
          ConvexPolyhedron inner = ellipsoid_points(radii, 32, e);
          return {Ellipsoid(radii), inner, e};
        }
        default:
          return {Box(radii, 0.1), Box(radii, 0.1), 0};
      }
    };
    const Made a = make(trial % 3);
    const Made b = make((trial / 3) % 4);
    const Pose pa = at(rng.vector(0.5), rng.rotation());
    const Pose pb = at(rng.vector(1.5), rng.rotation());
    const DistanceResult in = polytopes.signed_distance(a.inner, pa, b.inner, pb);
    ASSERT_TRUE(in.certified);
    const Scalar size = size_of(a.shape, pa, b.shape, pb);
    const Scalar slack = 2 * kDefaultTolerance * size;
    for (Method method : kCurvedMethods) {
      SCOPED_TRACE(::testing::Message() << method_name(method) << " trial " << trial);
      const Query query = query_of(method);
      const DistanceResult s = query.signed_distance(a.shape, pa, b.shape, pb);
      EXPECT_TRUE(s.certified);
      EXPECT_LE(s.lower_bound, s.distance);
      EXPECT_LE(s.distance, in.distance + slack);
      EXPECT_GE(s.distance, in.lower_bound - a.hausdorff - b.hausdorff - slack);
      EXPECT_LE(s.lower_bound, in.distance + slack);
      // The witnesses are on the bodies' surfaces and along the normal.
      EXPECT_NEAR((s.point_b - s.point_a - s.distance * s.direction).norm(), 0, slack);
      const DistanceResult d = query.distance(b.shape, pb, a.shape, pa);
      EXPECT_TRUE(d.certified);
      EXPECT_NEAR(d.distance, std::max(s.distance, 0.0), slack);
      EXPECT_EQ(query.collide(a.shape, pa, b.shape, pb), s.distance <= kDefaultTolerance * size);
    }
  }
}

// A polytope 1.0001 tolerances from a cylinder (met by bisecting sc.collide to the verdict's
// border): the dual method's finish left the verdict unproven, its swarm's rounds then spent
// 0.5 s (their finishes merging and sorting the cylinder's thousands of support points) and
// still left it so, and its distance was uncertified, where the exact method's search from the
// centres' direction proves the pair apart. Both methods now answer it certified, apart.
TEST(Curved, APolytopeAHairBeyondTheToleranceFromACylinderIsProvenApart) {
  VertexMatrix points(35, 3);
  points << -0.24843479961133874, 0.04864533703299052, 0.8003229450894594,
    -0.326945711518409, -0.7315635242918435, 0.7970727317098779,
    0.14622220253669455, -0.32530709227075233, -0.12482496612978833,
    -0.45687553073669945, 0.46892192201205896, 0.3566695041295389,
    0.3142861787521375, 0.11010171385985881, -1.0250208221167694,
    -0.5934891976386595, 0.1422001535832363, -1.3274744571026202,
    -0.03962780733872192, -0.5126561837259104, 0.31664685021564454,
    -0.09830069021896037, 0.5294590571595419, 0.1688273347129178,
    0.05687437601215375, -0.4866697660001436, 0.313854310767962,
    1.1896413042970426, -0.8552222227378247, -0.5118671962040933,
    0.8320463416060688, 0.25589561584872345, -0.14796480971124987,
    0.3909892140119748, 0.16624605142506305, -0.32631097161114686,
    -0.3341454558841379, 0.4276376346906882, 0.17165235945051843,
    0.5388412405473293, 0.3268903737619455, -0.3069976561980845,
    0.7620580810675485, -0.46158145673031764, -0.22664753822029815,
    -0.39139108039952825, -0.7005900862471016, 0.3112968318029853,
    -0.5264266134770131, -0.34211242126863334, 0.4713864618473497,
    0.43260657490357457, -0.3107121068383425, -0.6540197180434605,
    -0.05212682509840581, -0.7989329438003068, -0.5052121042427482,
    -0.19388814916545666, -0.07906511177539793, -0.2776151058358035,
    -0.07267245072046866, 0.6910201602973974, 0.3135630809292049,
    0.6896131286771731, 0.4480146993256288, 0.11599083445970863,
    -0.6069201372016982, -0.6680435409168003, -0.010292639266626371,
    -0.2043038072563747, -0.467271548696428, 0.2048523064749682,
    0.6120395891326884, -0.034043742463844666, 0.04291777962051738,
    -0.2734824340080992, -0.34397045379835134, 0.9868265184233438,
    -0.6282055093137473, -0.08061233264777028, -0.2235700739731985,
    -0.0549458171771297, 0.5231666824909095, 0.49688131709069755,
    -0.07005599877832837, 0.5617478523605172, -0.3832735861503789,
    0.17783855610208804, 0.8897560128189866, -0.28879396965410953,
    0.10255870368563147, 0.7492899675052436, -0.42123877654323,
    0.03216257276997991, -0.15740018667199207, -0.5584715479039196,
    0.2021305548925699, -0.4220645295407369, 0.8278772251189269,
    0.01033059584121111, -0.10507477227673084, 0.020435898843298425,
    0.051393690754768226, -0.09961211249780173, 0.028614259687519492;
  const ConvexPolyhedron polytope(points);
  const Cylinder cylinder(0.1484458703352641, 0.25554530994112157);
  Matrix3 rotation;
  rotation << -0.6944473106191402, 0.4830224792594639, -0.5333218702658691,
      0.44288123063002455, -0.2972286366466019, -0.8458790416559789,
      -0.5670971242472305, -0.8236166718123444, -0.007511962678170622;
  const Pose pose =
      at(Vector3(0.08844963591027584, -0.4439062472788866, -1.1358499112399854), rotation);
  for (Method method : kCurvedMethods) {
    SCOPED_TRACE(method_name(method));
    const Query query = query_of(method);
    const DistanceResult r = query.distance(polytope, Pose{}, cylinder, pose);
    EXPECT_TRUE(r.certified);
    EXPECT_FALSE(r.colliding);
    EXPECT_NEAR(r.distance, 4.509067775e-9,
                kDefaultTolerance * size_of(polytope, Pose{}, cylinder, pose));
    EXPECT_FALSE(query.collide(polytope, Pose{}, cylinder, pose));
  }
}

// The dual method's swarm measures a curved body's support points without numbering them among
// the body's points: every particle's point numbered, a cone held 7,800 after the rounds of one
// sc.collide at a verdict's border, and every finish scanned them all (0.3 s a call). Its
// separations are those of the numbered points, and its global best's points are numbered when
// the finish asks for them.
TEST(Curved, TheDirectionSwarmLeavesACurvedBodysSupportPointsAlone) {
  Random rng(11);
  const Box box(Vector3(0.3, 0.2, 0.1));
  const Cone cone(0.3, 0.4);
  const detail::FramedPair pair = detail::frame_pair(
      box, at(Vector3::Zero(), rng.rotation()), cone, at(Vector3(1, 0.2, 0), rng.rotation()),
      kDefaultTolerance);
  const int points = pair.b.size();
  const DualOptions options;
  detail::DirectionSwarm swarm(pair, options, 7);
  swarm.seed(Vector3::UnitX(), kPi / 2, -1, -1);
  for (int iteration = 0; iteration < 30; ++iteration) swarm.step();
  EXPECT_EQ(swarm.evaluations(), 31 * options.swarm_size);
  EXPECT_EQ(pair.b.size(), points);  // every particle's numbered: 171 more
  const int best_b = swarm.best_support_b();
  EXPECT_LE(pair.b.size(), points + 1);
  int ia = -1;
  int ib = -1;
  EXPECT_EQ(swarm.best_value(), detail::separation(pair.a, pair.b, swarm.best_direction(), ia, ib));
  EXPECT_EQ(ib, best_b);
  EXPECT_EQ(ia, swarm.best_support_a());
}

// A polytope a few roundoffs of the frame beyond the tolerance's border with a cylinder (from a
// bisection of sc.collide to it): the dual method's Wolfe search, finish and exact fallback leave
// the verdict unproven, and its swarm's rounds prove it, once the finish's features keep only
// their highest points (with all of them, before 83b2c49, it stayed unproven). The verdict is
// checked on its own, against the separation along the answer's direction in long double.
TEST(Curved, TheDualRoundsProveAVerdictAHairFromTheBorderWithACylinder) {
  VertexMatrix points(21, 3);
  points << 0.4108090717505792, 0.16521853809169357, -0.6515786158021805,
    0.45267793333655887, 0.22318728618200565, -0.2684766176801426,
    0.29055905209817656, 0.18228619809303787, 0.147066248327763,
    0.014211120657898394, 0.27335649330622347, -0.36822704350083346,
    -0.08145497399652639, -0.24105965633998913, 0.2994231063173138,
    0.019861053740829495, -0.1462283754825443, -0.39095423117842104,
    -0.12859612030943535, 0.004071090259171754, -0.1378014526496852,
    0.6470319071991036, 0.5033621576528972, -1.3555812394829843,
    -0.9445066229838364, -0.08738604602758097, -0.21109520578817678,
    0.10682149874930555, 0.10866096551128179, 1.0589193775255241,
    -0.5560103813461407, -0.18880250356349904, 1.0213858037461652,
    0.32335149810092345, 0.33153168618813084, -0.25700318584373144,
    -0.8240375854278263, 0.08373237211137056, 0.05450704391077377,
    -0.6136760271222871, -0.3416133308902811, -0.036021839863613715,
    -0.4723758115303887, -0.049134983926108634, 0.04774151373472717,
    0.017793118527742856, -0.2531458291571574, 0.2968740358929114,
    0.4455834771411642, 0.16042415228328186, -0.4091151136951535,
    0.3658261418927204, -0.25072000923352616, 0.43958030914399265,
    -0.5358937084387221, 0.4572336015643906, -0.01003172730774021,
    -0.6243744451672077, -0.15694973598342388, 0.027051139385771944,
    0.13639566958222687, -0.49109406247048887, -0.5536865235825965;
  const ConvexPolyhedron polytope(points);
  const Cylinder cylinder(0.41657997301827887, 0.29021213494326614);
  Matrix3 rotation;
  rotation << -0.6040825743968432, -0.018468311341473614, 0.7967077034811931,
      0.7905631334139658, -0.13992611251073095, 0.596180019058276,
      0.10046977354794161, 0.989989699195819, 0.09912729235380505;
  const Pose pose =
      at(Vector3(-0.6525843611166336, 0.8641707276104478, -0.1258434198985211), rotation);
  const DistanceResult verdict =
      query_of(Method::dual).collision(polytope, Pose{}, cylinder, pose, /*escalate=*/false);
  EXPECT_TRUE(verdict.certified);
  EXPECT_FALSE(verdict.colliding);
  // The separation along the answer's direction from the polytope's points and the cylinder's
  // support function (r |u_xy| + h |u_z| along u in its frame), in long double, whose rounding is
  // some 1e-19 of the size.
  using Long = long double;
  const Vector3 n = verdict.direction;
  Long highest_a = -1e300L;
  for (int i = 0; i < points.rows(); ++i) {
    Long h = 0;
    for (int k = 0; k < 3; ++k) h += Long(n(k)) * Long(points(i, k));
    highest_a = std::max(highest_a, h);
  }
  Long u[3] = {0, 0, 0};  // -n in the cylinder's frame: R^T (-n)
  for (int k = 0; k < 3; ++k) {
    for (int j = 0; j < 3; ++j) u[k] -= Long(rotation(j, k)) * Long(n(j));
  }
  const Long support = Long(cylinder.radius()) * std::sqrt(u[0] * u[0] + u[1] * u[1]) +
                       Long(cylinder.half_length()) * std::abs(u[2]);
  Long lowest_b = -support;
  for (int k = 0; k < 3; ++k) lowest_b += Long(n(k)) * Long(pose.translation(k));
  const Long norm = std::sqrt(Long(n.squaredNorm()));
  const Scalar tolerance = kDefaultTolerance * size_of(polytope, Pose{}, cylinder, pose);
  EXPECT_GT((lowest_b - highest_a) / norm, Long(tolerance));
}

// A verdict whose bounds lie within rounding of the tolerance on both sides can be proven by no
// bound, however many rounds the swarm runs: bisecting polytopes towards the verdict's border
// with a cylinder and a cone meets such pairs, and the search stops on them before its rounds are
// spent (it ran all 20 rounds of 30 iterations, milliseconds a call, before). Every verdict
// proven is the exact method's where that one proves its own.
TEST(Curved, TheDualRoundsStopWhereNoBoundCanProveTheVerdict) {
  Random rng(57);
  const Query dual = query_of(Method::dual);
  const Query exact = query_of(Method::exact);
  const DualOptions rounds;
  const Scalar u = std::numeric_limits<Scalar>::epsilon() / 2;
  int out_of_reach = 0;
  for (int body = 0; body < 16; ++body) {
    VertexMatrix points(21, 3);
    for (int i = 0; i < points.rows(); ++i) points.row(i) = 0.5 * rng.unit().transpose();
    const ConvexPolyhedron polytope(points);
    const ConvexPolyhedron curved = body % 2 == 0 ? ConvexPolyhedron(Cylinder(0.4, 0.6))
                                                  : ConvexPolyhedron(Cone(0.4, 0.6));
    const Vector3 direction = rng.unit();
    Scalar near = 0;
    Scalar far = 3;
    for (int step = 0; step < 48; ++step) {
      const Pose pose = at(0.5 * (near + far) * direction, Matrix3::Identity());
      const DistanceResult verdict = dual.collision(polytope, Pose{}, curved, pose, false);
      (verdict.colliding ? near : far) = 0.5 * (near + far);
      if (verdict.certified) {
        const DistanceResult decided = exact.collision(polytope, Pose{}, curved, pose, false);
        if (decided.certified) EXPECT_EQ(verdict.colliding, decided.colliding) << body;
        continue;
      }
      // Within three quarters of the frame's rounding on either side of the tolerance (that
      // rounding is 128 u of a power of two above half the size, so at least 64 u of the size):
      // out of reach, however the world's bounds were rounded.
      const Scalar size = size_of(polytope, Pose{}, curved, pose);
      const Scalar tolerance = kDefaultTolerance * size;
      if (verdict.lower_bound > tolerance - 48 * u * size &&
          verdict.distance < tolerance + 48 * u * size) {
        ++out_of_reach;
        EXPECT_LT(verdict.iterations, rounds.max_rounds * rounds.max_iterations) << body;
      }
    }
  }
  EXPECT_GT(out_of_reach, 0);
}

TEST(Curved, MethodsThatReadPointsRefuseCurvedShapes) {
  const Cylinder cylinder(1, 1);
  const ConvexPolyhedron cube = unit_cube();
  for (Method method : {Method::ipso, Method::pso, Method::penalty}) {
    SCOPED_TRACE(method_name(method));
    try {
      query_of(method).collide(cylinder, {}, cube, at(Vector3(3, 0, 0)));
      ADD_FAILURE() << "no error";
    } catch (const std::invalid_argument& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find("cylinder"), std::string::npos) << message;
      EXPECT_NE(message.find("'dual', 'exact', 'fcl', 'libccd'"), std::string::npos) << message;
    }
  }
}

// FCL's primitives, as the method "fcl" builds them (in the frame's units), have our shapes'
// conventions: FCL's support point along a direction is ours, to rounding (a cone upside down,
// a cylinder of length h instead of 2h, would miss by the shape's size).
TEST(Curved, FclPrimitivesAreOurShapes) {
  Random rng(37);
  for (int trial = 0; trial < 60; ++trial) {
    const Scalar r = std::exp(rng.uniform(-2, 2));
    const Scalar h = std::exp(rng.uniform(-2, 2));
    const Vector3 radii(std::exp(rng.uniform(-2, 2)), std::exp(rng.uniform(-2, 2)),
                        std::exp(rng.uniform(-2, 2)));
    const Scalar scale = std::exp(rng.uniform(-100, 100));
    const ConvexPolyhedron shapes[] = {Cylinder(r * scale, h * scale), Cone(r * scale, h * scale),
                                       Ellipsoid(radii * scale)};
    for (const ConvexPolyhedron& shape : shapes) {
      SCOPED_TRACE(shape.curved()->name());
      const detail::FramedPair pair =
          detail::frame_pair(shape, at(rng.vector(scale), rng.rotation()), shape,
                             at(rng.vector(scale)), kDefaultTolerance);
      const fcl::ShapeBased& fcl_shape = detail::fcl_shape(pair.a);
      const Scalar unit = std::ldexp(1.0, -pair.a.exponent());
      for (int k = 0; k < 20; ++k) {
        const Vector3 d = rng.unit();
        const Vector3 theirs = fcl::detail::getSupport(&fcl_shape, d);
        const Vector3 ours = shape.curved()->support(d) * unit;
        EXPECT_NEAR((theirs - ours).norm(), 0, 1e-12 * shape.curved()->outer_radius() * unit)
            << "direction " << d.transpose();
      }
    }
  }
}

// Cylinders and cones whose cap meets the other's rim: where the expanding polytope's new faces
// dipped below its nearest one (the cap's flat facet of A - B beside the rim's curve), it stopped,
// a few 1e-12 short of a tolerance of 1e-12 (curved_census.py: 20 of 750 such pairs); it now
// verifies the surface before such a step, keeps its bound and goes on. The last two (cones) it
// left unproven on slivers, whose normals from the cross product at the wrong corner tilted by
// far more than rounding: a support point at the face's height could not expand it.
TEST(Curved, CapRimContactsAreProvenAtTightTolerance) {
  struct Case {
    bool cone_a;
    Scalar radius_a;
    Scalar half_length_a;
    bool cone_b;
    Scalar radius_b;
    Scalar half_length_b;
    Pose pose_a;
    Pose pose_b;
  };
  const auto placed = [](std::initializer_list<Scalar> rotation, const Vector3& translation) {
    Pose pose;
    auto entry = rotation.begin();
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) pose.rotation(i, j) = *entry++;
    }
    pose.translation = translation;
    return pose;
  };
  // Poses and sizes of curved_census.py's pairs (seed 26), written out to the last digit.
  const Case cases[] = {
      {false, 0.8932278090150577, 0.9613713228108935, false, 0.5304579567989778,
       0.13949430242853725,
       placed({0.880452657082996, 0.3815368462830449, -0.28148313193490043,
               0.13428924234560943, 0.3686988139085547, 0.9197975777379864,
               0.4547191639085982, -0.8476383778185206, 0.2733855563548527},
              {0.0, 0.0, 0.0}),
       placed({0.8346694044645926, -0.5345054027035743, -0.1327816242234305,
               0.13620364609175561, 0.4339321366238148, -0.890590516228644,
               0.5336436564244292, 0.7252633144491597, 0.4349914627578167},
              {1.298368917624614, 0.15988279998658994, 0.15226166210313496})},
      {false, 0.6307578195754501, 0.9805129851355954, false, 1.0037794463388128, 1.0613643961667085,
       placed({0.5030207119400159, 0.07859314988441016, -0.860693487921575,
               -0.7845424206486644, 0.45930249452782934, -0.41657461363271686,
               0.3625787549789611, 0.8847962111762008, 0.2926983278499323},
              {0.0, 0.0, 0.0}),
       placed({-0.35125421158400116, -0.45290764015990054, 0.8194480754320506,
               0.38797945930695477, -0.8669456993506032, -0.312853150109403,
               0.8521105667695856, 0.20803803465300214, 0.4802371894567638},
              {1.0683168114973798, 0.08250657462821431, -0.7568625061302993})},
      {false, 0.6022459132318345, 1.080826453526332, true, 0.6611421440890861, 0.7870924362556015,
       placed({-0.4330967867923867, -0.6551353363678559, 0.61905158453257,
               -0.8188016695805834, -0.0011629118382863704, -0.5740753204311306,
               0.37681693056729637, -0.7555106476273068, -0.535922253838753},
              {0.0, 0.0, 0.0}),
       placed({0.24163301856670505, 0.8148962809684066, -0.526837295189134,
               -0.8084208849434843, 0.4693510792669613, 0.3551974622349273,
               0.5367207440797649, 0.34007883741097267, 0.7721898906484498},
              {-1.0416996880650313, -0.4140198872816876, 0.8357444677404748})},
      {false, 0.4082496798546018, 0.5151142054148151, true, 0.9959843682239224, 1.048703043232522,
       placed({0.41737680392671805, -0.6572430245581912, -0.627557336196079,
               -0.2970291479906672, -0.7513214261069042, 0.5893129897742165,
               -0.8588191246053246, -0.059562751298847215, -0.5088044711574924},
              {0.0, 0.0, 0.0}),
       placed({0.7947092115645851, 0.19193223087789837, -0.575846583565995,
               0.5705561710544659, -0.5599388362095993, 0.6007779584637797,
               -0.20713021200699433, -0.8059965995303411, -0.5544966698001572},
              {0.3310639404045681, -0.05622878973814238, -0.9077136522012254})},
      {true, 0.6638806941283152, 1.0981329515675347, true, 0.8061815614239918,
       1.0002033400740975,
       placed({-0.992691239477419, 0.0341812410283382, 0.11573999233863815,
               -0.1157862163708396, -0.5401476801466522, -0.833567055329513,
               0.034024331930406465, -0.8408758091382775, 0.5401575866751633},
              {0.0, 0.0, 0.0}),
       placed({0.019262384660966747, -0.827232754409891, -0.5615291003755711,
               0.9320080525803667, -0.18845047265111817, 0.30959232755823,
               -0.36192533824329726, -0.5293131298097521, 0.7673575829745083},
              {-0.9217768661215864, 0.8097481521408727, -0.9800258825651427})},
      {true, 0.559952306197727, 1.0898687376313945, true, 0.8279392363602323,
       0.6858375563535913,
       placed({-0.33060500169115503, 0.9430165226385125, 0.03768515473709318,
               0.1594521400891683, 0.09516842801533971, -0.9826077474404897,
               -0.9302017780448365, -0.3188460574318845, -0.18182916097911248},
              {0.0, 0.0, 0.0}),
       placed({0.164191215776069, -0.9031901329868319, 0.396596556133819,
               -0.16807194185306013, 0.37055913793329465, 0.9134756415230102,
               -0.9720046640956607, -0.2166414294851346, -0.09095836413942077},
              {-0.42746725912907846, 0.23067304975753444, 0.43048092196227117})},
  };
  const Query query = query_of(Method::dual, 1e-12);
  for (const Case& c : cases) {
    const ConvexPolyhedron a = c.cone_a ? ConvexPolyhedron(Cone(c.radius_a, c.half_length_a))
                                        : ConvexPolyhedron(Cylinder(c.radius_a, c.half_length_a));
    const ConvexPolyhedron b = c.cone_b ? ConvexPolyhedron(Cone(c.radius_b, c.half_length_b))
                                        : ConvexPolyhedron(Cylinder(c.radius_b, c.half_length_b));
    const DistanceResult r = query.signed_distance(a, c.pose_a, b, c.pose_b);
    EXPECT_TRUE(r.certified) << "gap " << r.distance - r.lower_bound;
    EXPECT_LT(r.distance, 0);
  }
}

// The method "fcl" answers curved pairs through FCL's GJK on its primitives, checked by our own
// support points along FCL's directions: on separated pairs FCL's answer is proven as it stands
// (the answer names "fcl", not "exact") and agrees with "dual".
TEST(Curved, FclAnswersSeparatedCurvedPairsItself) {
  Random rng(41);
  const Query fcl = query_of(Method::fcl);
  const Query dual = query_of(Method::dual);
  int by_fcl = 0;
  int apart = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const auto make = [&rng](int kind) -> ConvexPolyhedron {
      const Scalar a = rng.uniform(0.2, 1);
      const Scalar b = rng.uniform(0.2, 1);
      switch (kind % 3) {
        case 0: return Cylinder(a, b);
        case 1: return Cone(a, b);
        default: return Ellipsoid(Vector3(a, b, rng.uniform(0.2, 1)));
      }
    };
    const ConvexPolyhedron a = make(trial);
    const ConvexPolyhedron b = make(trial / 3);
    const Pose pa = at(Vector3::Zero(), rng.rotation());
    const Pose pb = at(rng.unit() * rng.uniform(2.5, 4), rng.rotation());
    const DistanceResult ours = dual.distance(a, pa, b, pb);
    const DistanceResult theirs = fcl.distance(a, pa, b, pb);
    ASSERT_TRUE(ours.certified);
    EXPECT_TRUE(theirs.certified);
    const Scalar size = size_of(a, pa, b, pb);
    EXPECT_NEAR(theirs.distance, ours.distance, 2 * kDefaultTolerance * size);
    EXPECT_LE(theirs.lower_bound, ours.distance + 1e-15 * size);
    EXPECT_LE(ours.lower_bound, theirs.distance + 1e-15 * size);
    apart += ours.distance > 0;
    by_fcl += theirs.method == Method::fcl;
  }
  EXPECT_EQ(apart, 300);
  EXPECT_GE(by_fcl, 270) << "FCL's answers proven as they stand";
}

// The method "libccd" answers verdicts and signed distances of curved pairs through the shapes'
// support functions, checked as for polyhedra, and agrees with "dual".
TEST(Curved, LibccdAnswersCurvedVerdictsAndDepths) {
  Random rng(43);
  const Query libccd = query_of(Method::libccd);
  const Query dual = query_of(Method::dual);
  int colliding = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const auto make = [&rng](int kind) -> ConvexPolyhedron {
      const Scalar a = rng.uniform(0.2, 1);
      const Scalar b = rng.uniform(0.2, 1);
      switch (kind % 4) {
        case 0: return Cylinder(a, b);
        case 1: return Cone(a, b);
        case 2: return Ellipsoid(Vector3(a, b, rng.uniform(0.2, 1)));
        default: return Box(Vector3(a, b, a), 0.1);
      }
    };
    const ConvexPolyhedron a = make(trial);
    const ConvexPolyhedron b = make(trial / 4);
    const Pose pa = at(Vector3::Zero(), rng.rotation());
    const Pose pb = at(rng.vector(1.5), rng.rotation());
    const Scalar size = size_of(a, pa, b, pb);
    const DistanceResult ours = dual.signed_distance(a, pa, b, pb);
    const DistanceResult theirs = libccd.signed_distance(a, pa, b, pb);
    const DistanceResult verdict = libccd.collision(a, pa, b, pb);
    ASSERT_TRUE(ours.certified);
    EXPECT_TRUE(theirs.certified);
    EXPECT_NEAR(theirs.distance, ours.distance, 2 * kDefaultTolerance * size);
    EXPECT_TRUE(verdict.certified);
    EXPECT_EQ(verdict.colliding, ours.distance <= kDefaultTolerance * size);
    colliding += verdict.colliding;
  }
  EXPECT_GT(colliding, 50);
  EXPECT_LT(colliding, 250);
}

// A plus of a cylinder (axis z) and a bar across it (along x), and a rod of a capsule and a cone
// on it: compound bodies with curved parts, whose every answer is the best part pair's as Query
// answers the parts one by one; batches and scenes agree with the pair queries.
CompoundBody plus_shape() { return CompoundBody({Cylinder(0.3, 1), Box(Vector3(1, 0.15, 0.15))}); }
CompoundBody rod() {
  return CompoundBody({Capsule(0.1, 0.8), Cone(0.4, 0.3), Ellipsoid(Vector3(0.2, 0.5, 0.2))});
}

TEST(Curved, CompoundBodiesWithCurvedPartsAnswerAsTheirBestPartPair) {
  Random rng(47);
  const CompoundBody plus = plus_shape();
  const CompoundBody other = rod();
  ASSERT_NE(plus.curved_part(), nullptr);
  EXPECT_EQ(plus.curved_part(), &plus.parts()[0]);
  EXPECT_EQ(CompoundBody(unit_cube()).curved_part(), nullptr);
  // Every node's envelope and ball hold the curved parts below it: along any direction the
  // envelope's support value reaches the part's.
  for (const CompoundBody* body : {&plus, &other}) {
    for (std::size_t node = 0; node < body->tree().size(); ++node) {
      const ConvexPolyhedron& envelope = body->node_envelopes()[node];
      EXPECT_EQ(envelope.curved(), nullptr);
      for (const ConvexPolyhedron& part : body->parts()) {
        if (!part.curved()) continue;
        const PartNode& volume = body->tree()[node];
        const bool below = (volume.box.min.array() <= part.aabb().min.array()).all() &&
                           (part.aabb().max.array() <= volume.box.max.array()).all();
        if (!below) continue;
        EXPECT_LE(part.bounds().radius + (part.bounds().centre - volume.centre).norm(),
                  volume.radius * (1 + 1e-12));
        for (int k = 0; k < 50; ++k) {
          const Vector3 d = rng.unit();
          EXPECT_GE(d.dot(envelope.support(d)) + envelope.radius(),
                    d.dot(part.support(d)) - 1e-15);
        }
      }
    }
  }
  for (Method method : kCurvedMethods) {
    SCOPED_TRACE(method_name(method));
    const Query query = query_of(method);
    // Every part pair's own answer is certified too.
    const auto certified = [](const DistanceResult& r) { EXPECT_TRUE(r.certified); };
    int colliding = 0;
    for (int trial = 0; trial < 30; ++trial) {
      const Pose pa = at(Vector3::Zero(), rng.rotation());
      const Pose pb = at(rng.vector(1.6), rng.rotation());
      const Scalar size = size_of(plus.envelope(), pa, other.envelope(), pb);
      const Scalar slack = 2 * kDefaultTolerance * size;
      const CompoundResult d = query.distance(plus, pa, other, pb);
      const DistanceResult d_oracle = best_part_pair(query, plus, pa, other, pb, false, certified);
      EXPECT_TRUE(d.certified) << trial;
      EXPECT_NEAR(d.distance, d_oracle.distance, slack) << trial;
      EXPECT_LE(d.lower_bound, d_oracle.distance + slack);
      EXPECT_NEAR((d.point_b - d.point_a).norm(), d.distance, slack);
      const CompoundResult s = query.signed_distance(plus, pa, other, pb);
      const DistanceResult s_oracle = best_part_pair(query, plus, pa, other, pb, true, certified);
      EXPECT_TRUE(s.certified) << trial;
      EXPECT_NEAR(s.distance, s_oracle.distance, slack) << trial;
      const CompoundResult c = query.collision(plus, pa, other, pb);
      EXPECT_TRUE(c.certified);
      EXPECT_EQ(c.colliding, d_oracle.distance <= kDefaultTolerance * size) << trial;
      colliding += c.colliding;
    }
    EXPECT_GT(colliding, 3);
    EXPECT_LT(colliding, 27);
  }
}

TEST(Curved, CompoundBodiesWithCurvedPartsInBatchesAndScenes) {
  Random rng(53);
  const CompoundBody plus = plus_shape();
  const CompoundBody other = rod();
  BatchPoses poses;
  for (int row = 0; row < 40; ++row) {
    poses.a.push_back(at(Vector3::Zero(), rng.rotation()));
    poses.b.push_back(at(rng.vector(1.6), rng.rotation()));
  }
  const Query query = query_of(Method::dual);
  const BatchResult distances = distance_many(plus, other, QueryOptions{}, {}, poses);
  const BatchResult verdicts = collide_many(plus, other, QueryOptions{}, {}, poses);
  for (int row = 0; row < 40; ++row) {
    const CompoundResult one = query.distance(plus, poses.a[row], other, poses.b[row]);
    EXPECT_TRUE(distances.certified(row));
    EXPECT_NEAR(distances.distance(row), one.distance, 1e-8);
    EXPECT_EQ(verdicts.colliding(row), one.colliding) << row;
  }
  // In a scene, with a cylinder, a plus and a rod: the colliding pairs are the pair queries'.
  Scene scene{SceneOptions{}};
  std::vector<Pose> placed;
  for (int i = 0; i < 6; ++i) placed.push_back(at(rng.vector(1.2), rng.rotation()));
  const std::vector<BodyId> compounds =
      scene.add(std::vector<CompoundBody>{plus, other, plus, other}, {placed[0], placed[1],
                                                                       placed[2], placed[3]});
  const BodyId cylinder = scene.add(Cylinder(0.3, 0.4), placed[4]);
  const BodyId ellipsoid = scene.add(Ellipsoid(Vector3(0.5, 0.2, 0.3)), placed[5]);
  const std::vector<BodyId> ids = {compounds[0], compounds[1], compounds[2],
                                   compounds[3], cylinder,     ellipsoid};
  const std::vector<CompoundBody> bodies = {plus, other, plus, other,
                                            CompoundBody(Cylinder(0.3, 0.4)),
                                            CompoundBody(Ellipsoid(Vector3(0.5, 0.2, 0.3)))};
  const SceneResult hits = scene.colliding_pairs();
  std::vector<std::pair<BodyId, BodyId>> found;
  for (Eigen::Index k = 0; k < hits.size(); ++k) {
    EXPECT_TRUE(hits.certified(k));
    found.emplace_back(static_cast<BodyId>(std::min(hits.pairs(k, 0), hits.pairs(k, 1))),
                       static_cast<BodyId>(std::max(hits.pairs(k, 0), hits.pairs(k, 1))));
  }
  int colliding = 0;
  for (std::size_t i = 0; i < ids.size(); ++i) {
    for (std::size_t j = i + 1; j < ids.size(); ++j) {
      const CompoundResult r = query.collision(bodies[i], placed[i], bodies[j], placed[j]);
      ASSERT_TRUE(r.certified);
      const bool listed = std::find(found.begin(), found.end(),
                                    std::make_pair(std::min(ids[i], ids[j]),
                                                   std::max(ids[i], ids[j]))) != found.end();
      EXPECT_EQ(listed, r.colliding) << i << " " << j;
      colliding += r.colliding;
    }
  }
  EXPECT_GT(colliding, 0);
}

TEST(Curved, CompoundBodiesWithCurvedPartsRefuseMethodsThatReadPoints) {
  const CompoundBody plus = plus_shape();
  for (Method method : {Method::ipso, Method::pso, Method::penalty}) {
    SCOPED_TRACE(method_name(method));
    QueryOptions options;
    options.method = method;
    try {
      Query(options).collision(plus, {}, plus, at(Vector3(5, 0, 0)));
      ADD_FAILURE() << "no error";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("cylinder"), std::string::npos) << e.what();
    }
    SceneOptions scene_options;
    scene_options.query.method = method;
    Scene scene(scene_options);
    EXPECT_THROW(scene.add(plus), std::invalid_argument);
  }
}

// Overlapping pairs of shapes with flat facets (a cylinder's cap, a cone's base, a box's face) at
// tolerance 1e-12: near the optimum, the support point only just rises above the nearest face of
// the expanding polytope, beyond an edge whose other face is nearly coplanar and does not see it,
// so the triangle on that edge cannot be proven oriented. Before the expansion took in the face
// across such an edge, it stopped there with gaps of 4e-12 to 7e-11 of the frame: 91 of these 827
// overlapping pairs unproven, 46 since. Those stay unproven, and say so (their bounds hold).
TEST(Curved, DeepOverlapsOnFlatFacetsAreProvenAtTightTolerance) {
  Random rng(59);
  const Query query = query_of(Method::exact, 1e-12);
  int overlapping = 0;
  int unproven = 0;
  for (int trial = 0; trial < 1000; ++trial) {
    const auto make = [&rng](int kind) -> ConvexPolyhedron {
      const Vector3 s(rng.uniform(0.1, 1.1), rng.uniform(0.1, 1.1), rng.uniform(0.1, 1.1));
      switch (kind % 3) {
        case 0: return Cylinder(s.x(), s.y());
        case 1: return Cone(s.x(), s.y());
        default: return Box(s);
      }
    };
    const ConvexPolyhedron a = make(trial);
    const ConvexPolyhedron b = make(trial / 3 + 1);
    const Pose pa = at(Vector3::Zero(), rng.rotation());
    const Pose pb = at(rng.vector(0.8), rng.rotation());
    const DistanceResult s = query.signed_distance(a, pa, b, pb);
    if (s.distance >= 0) continue;
    ++overlapping;
    unproven += !s.certified;
    EXPECT_LE(s.lower_bound, s.distance);
  }
  EXPECT_GT(overlapping, 800);
  EXPECT_LE(unproven, 50) << "of " << overlapping;
}

// A scene of curved shapes answers as the pair queries do, warm and cold.
TEST(Curved, ScenesAnswerAsThePairQueries) {
  Random rng(29);
  std::vector<ConvexPolyhedron> bodies;
  std::vector<Pose> poses;
  for (int i = 0; i < 12; ++i) {
    switch (i % 4) {
      case 0: bodies.push_back(Cylinder(rng.uniform(0.2, 0.5), rng.uniform(0.2, 0.5))); break;
      case 1: bodies.push_back(Cone(rng.uniform(0.2, 0.5), rng.uniform(0.2, 0.5))); break;
      case 2: bodies.push_back(Ellipsoid(Vector3(0.3, 0.4, 0.5))); break;
      default: bodies.push_back(Sphere(0.3)); break;
    }
    poses.push_back(at(rng.vector(1.2), rng.rotation()));
  }
  SceneOptions options;
  Scene scene(options);
  const std::vector<BodyId> ids = scene.add(bodies, poses);
  const Query query = query_of(Method::dual);
  int colliding = 0;
  for (int frame = 0; frame < 3; ++frame) {
    const SceneResult pairs = scene.colliding_pairs();
    std::vector<std::pair<BodyId, BodyId>> found;
    for (Eigen::Index k = 0; k < pairs.size(); ++k) {
      EXPECT_TRUE(pairs.certified(k));
      found.emplace_back(static_cast<BodyId>(std::min(pairs.pairs(k, 0), pairs.pairs(k, 1))),
                         static_cast<BodyId>(std::max(pairs.pairs(k, 0), pairs.pairs(k, 1))));
    }
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      for (std::size_t j = i + 1; j < bodies.size(); ++j) {
        const DistanceResult r = query.collision(bodies[i], poses[i], bodies[j], poses[j]);
        ASSERT_TRUE(r.certified);
        const bool listed = std::find(found.begin(), found.end(),
                                      std::make_pair(ids[i], ids[j])) != found.end();
        EXPECT_EQ(listed, r.colliding) << i << " " << j;
        colliding += r.colliding;
      }
    }
    for (Pose& p : poses) p.translation += rng.vector(0.1);
    scene.set_poses(ids, poses);
  }
  EXPECT_GT(colliding, 3);
}

// Random posed pairs of every kind (curved, polyhedra, rounded): every distance and verdict
// certified at the default tolerance. On curved bodies Wolfe's algorithm stalls on rounding (the
// squared norm's decrease) before the separation proves the distance; "exact" restarts it from
// the best direction (before that, 2 in 3000 distances and 3 in 3000 signed distances stayed
// unproven). Signed distances of overlapping curved pairs can stay unproven where the expanding
// polytope stops on faces too thin to add to (a box's corner in a cone's rim: 1 in 3000 here),
// and say so.
TEST(Curved, RandomPairsOfEveryKindAreCertified) {
  Random rng(31);
  // By value: a shape's ConvexPolyhedron keeps its support function (and has no virtual
  // destructor to delete a derived shape through).
  const auto make = [&](int kind) -> ConvexPolyhedron {
    const Scalar a = rng.uniform(0.1, 1.1);
    const Scalar b = rng.uniform(0.1, 1.1);
    const Scalar c = rng.uniform(0.1, 1.1);
    switch (kind % 5) {
      case 0: return Cylinder(a, b);
      case 1: return Cone(a, b);
      case 2: return Ellipsoid(Vector3(a, b, c));
      case 3: return Box(Vector3(a, b, c), kind % 2 ? 0.0 : 0.1);
      default: return Sphere(a);
    }
  };
  for (Method method : kCurvedMethods) {
    SCOPED_TRACE(method_name(method));
    const Query query = query_of(method);
    int unproven = 0;
    int unproven_signed = 0;
    for (int i = 0; i < 3000; ++i) {
      const ConvexPolyhedron a = make(i);
      const ConvexPolyhedron b = make(i / 5);
      const Pose pa = at(Vector3::Zero(), rng.rotation());
      const Pose pb = at(rng.vector(1.5), rng.rotation());
      const DistanceResult d = query.distance(a, pa, b, pb);
      const DistanceResult s = query.signed_distance(a, pa, b, pb);
      const DistanceResult c = query.collision(a, pa, b, pb);
      unproven += !d.certified + !c.certified;
      unproven_signed += !s.certified;
      const Scalar size = size_of(a, pa, b, pb);
      EXPECT_LE(s.lower_bound, s.distance + 1e-15 * size);
      EXPECT_LE(d.lower_bound, d.distance + 1e-15 * size);
      EXPECT_EQ(c.colliding, d.distance <= kDefaultTolerance * size);
    }
    EXPECT_EQ(unproven, 0);
    EXPECT_LE(unproven_signed, 1);
  }
}

}  // namespace
}  // namespace swarmcollide::testing
