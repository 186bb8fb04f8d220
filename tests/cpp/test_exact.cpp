#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "contract.hpp"
#include "hard_cases.hpp"
#include "paper_cases.hpp"
#include "swarmcollide/problem/certificate.hpp"
#include "swarmcollide/queries/collide.hpp"
#include "swarmcollide/queries/signed_distance.hpp"
#include "swarmcollide/solvers/exact_nearest_points.hpp"
#include "swarmcollide/solvers/fcl_distance.hpp"
#include "swarmcollide/solvers/libccd_penetration.hpp"

namespace swarmcollide {
namespace {

using testing::paper_a;
using testing::paper_b_colliding;
using testing::paper_b_separate;

// ---- Independent oracles ------------------------------------------------------------------

Scalar point_segment(const Vector3& p, const Vector3& a, const Vector3& b) {
  const Vector3 ab = b - a;
  const Scalar len2 = ab.squaredNorm();
  const Scalar t = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (a + t * ab - p).norm();
}

Scalar point_triangle(const Vector3& p, const Vector3& a, const Vector3& b, const Vector3& c) {
  const Vector3 n = (b - a).cross(c - a);
  Scalar best = std::min({point_segment(p, a, b), point_segment(p, b, c), point_segment(p, c, a)});
  if (n.squaredNorm() > 0) {
    const Vector3 q = p - n * n.dot(p - a) / n.squaredNorm();
    const bool inside = (b - a).cross(q - a).dot(n) >= 0 && (c - b).cross(q - b).dot(n) >= 0 &&
                        (a - c).cross(q - c).dot(n) >= 0;
    if (inside) best = std::min(best, (p - q).norm());
  }
  return best;
}

// Closest distance between segments by minimising over a fine search, refined exactly: the
// squared distance is a convex quadratic in (s, t); solve it on the square's interior and edges.
Scalar segment_segment(const Vector3& p0, const Vector3& p1, const Vector3& q0, const Vector3& q1) {
  Scalar best = std::min({point_segment(p0, q0, q1), point_segment(p1, q0, q1),
                          point_segment(q0, p0, p1), point_segment(q1, p0, p1)});
  const Vector3 d1 = p1 - p0;
  const Vector3 d2 = q1 - q0;
  const Vector3 r = p0 - q0;
  const Scalar a = d1.dot(d1), e = d2.dot(d2), b = d1.dot(d2), c = d1.dot(r), f = d2.dot(r);
  const Scalar denom = a * e - b * b;
  if (denom > 1e-14 * a * e) {
    const Scalar s = (b * f - c * e) / denom;
    const Scalar t = (a * f - b * c) / denom;
    if (s >= 0 && s <= 1 && t >= 0 && t <= 1) best = std::min(best, (r + s * d1 - t * d2).norm());
  }
  return best;
}

struct Features {
  std::vector<Vector3> points;
  std::vector<std::pair<Vector3, Vector3>> edges;
  std::vector<std::array<Vector3, 3>> triangles;
};

Features features(const ConvexPolyhedron& body) {
  const Hull& h = body.hull();
  Features f;
  const auto row = [&](int i) -> Vector3 { return body.vertices().row(i).transpose(); };
  for (int i : h.vertex_indices) f.points.push_back(row(i));
  if (h.dimension == 1) f.edges.push_back({row(h.vertex_indices[0]), row(h.vertex_indices[1])});
  for (Eigen::Index t = 0; t < h.faces.rows(); ++t) {
    const Vector3 a = row(h.faces(t, 0)), b = row(h.faces(t, 1)), c = row(h.faces(t, 2));
    f.triangles.push_back({a, b, c});
    f.edges.push_back({a, b});
    f.edges.push_back({b, c});
    f.edges.push_back({c, a});
  }
  return f;
}

// Distance of separated bodies by brute force over vertex/edge/face pairs of the two hulls.
Scalar oracle_distance(const ConvexPolyhedron& a, const ConvexPolyhedron& b) {
  const Features fa = features(a);
  const Features fb = features(b);
  Scalar best = std::numeric_limits<Scalar>::infinity();
  for (const Vector3& p : fa.points) {
    for (const Vector3& q : fb.points) best = std::min(best, (p - q).norm());
    for (const auto& e : fb.edges) best = std::min(best, point_segment(p, e.first, e.second));
    for (const auto& t : fb.triangles) best = std::min(best, point_triangle(p, t[0], t[1], t[2]));
  }
  for (const Vector3& q : fb.points) {
    for (const auto& e : fa.edges) best = std::min(best, point_segment(q, e.first, e.second));
    for (const auto& t : fa.triangles) best = std::min(best, point_triangle(q, t[0], t[1], t[2]));
  }
  for (const auto& e : fa.edges) {
    for (const auto& g : fb.edges) {
      best = std::min(best, segment_segment(e.first, e.second, g.first, g.second));
    }
  }
  return best;
}

// Penetration depth of overlapping solids by the separating-axis theorem: the facets of the
// Minkowski difference have face normals of either body or cross products of an edge of each.
Scalar oracle_depth(const ConvexPolyhedron& a, const ConvexPolyhedron& b) {
  const Features fa = features(a);
  const Features fb = features(b);
  std::vector<Vector3> axes;
  for (const Features* f : {&fa, &fb}) {
    for (const auto& t : f->triangles) axes.push_back((t[1] - t[0]).cross(t[2] - t[0]));
  }
  for (const auto& e : fa.edges) {
    for (const auto& g : fb.edges) axes.push_back((e.second - e.first).cross(g.second - g.first));
  }
  Scalar depth = std::numeric_limits<Scalar>::infinity();
  for (const Vector3& axis : axes) {
    if (axis.norm() < 1e-12) continue;
    for (const Vector3 n : {axis.normalized(), Vector3(-axis.normalized())}) {
      depth = std::min(depth, -separation(a, b, n));
    }
  }
  return depth;
}

// ---- Helpers --------------------------------------------------------------------------------

ConvexPolyhedron cube(const Vector3& lo, const Vector3& hi) {
  VertexMatrix v(8, 3);
  for (int k = 0; k < 8; ++k) {
    v.row(k) << (k & 1 ? hi.x() : lo.x()), (k & 2 ? hi.y() : lo.y()), (k & 4 ? hi.z() : lo.z());
  }
  return ConvexPolyhedron(v);
}

ConvexPolyhedron shifted(const ConvexPolyhedron& body, const Vector3& offset) {
  VertexMatrix v = body.vertices();
  v.rowwise() += offset.transpose();
  return ConvexPolyhedron(v);
}

ConvexPolyhedron random_body(std::mt19937_64& rng, const Vector3& centre, int n) {
  std::uniform_real_distribution<Scalar> u(-1, 1);
  VertexMatrix v(n, 3);
  for (int i = 0; i < n; ++i)
    v.row(i) << centre.x() + u(rng), centre.y() + u(rng), centre.z() + u(rng);
  return ConvexPolyhedron(v);
}

ConvexPolyhedron points(std::initializer_list<Vector3> list) {
  VertexMatrix v(static_cast<Eigen::Index>(list.size()), 3);
  Eigen::Index i = 0;
  for (const Vector3& p : list) v.row(i++) = p.transpose();
  return ConvexPolyhedron(v);
}

using testing::size_of;

DistanceOptions with(Method m) {
  DistanceOptions o;
  o.method = m;
  return o;
}

// The contract every distance result meets.
void expect_contract(const ConvexPolyhedron& a, const ConvexPolyhedron& b, const DistanceResult& r,
                     Scalar tolerance = 1e-9) {
  testing::expect_contract(a, b, r, 1e-12 * (size_of(a, b) + r.point_a.norm()));
  testing::expect_verdicts_from_bounds(r, tolerance);
  EXPECT_EQ(r.status, SolverStatus::exact);
}

const std::vector<Method> kDistanceMethods = {Method::fcl, Method::fcl_indep};

DistanceResult run(Method m, const ConvexPolyhedron& a, const ConvexPolyhedron& b) {
  return distance(a, b, with(m));
}

// ---- Method plumbing ----------------------------------------------------------------------

TEST(ExactMethods, NamesRoundTrip) {
  for (Method m : {Method::penalty, Method::fcl, Method::fcl_indep, Method::libccd}) {
    EXPECT_EQ(method_from_name(method_name(m)), m);
  }
  EXPECT_EQ(method_name(Method::fcl_indep), "fcl-indep");
  EXPECT_THROW(method_from_name("gjk"), std::invalid_argument);
}

TEST(ExactMethods, OptionsAreValidated) {
  ExactOptions o;
  EXPECT_NO_THROW(o.validate());
  o.distance_tolerance = 0;
  try {
    o.validate();
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("distance_tolerance"), std::string::npos);
  }
  o = {};
  o.max_iterations = 0;
  EXPECT_THROW(o.validate(), std::invalid_argument);
  o = {};
  o.tolerance = -1;
  EXPECT_THROW(fcl_distance(paper_a(), paper_b_separate(), FclGjk::libccd, o),
               std::invalid_argument);
}

TEST(ExactMethods, LibccdHasNoDistance) {
  try {
    distance(paper_a(), paper_b_separate(), with(Method::libccd));
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'fcl'"), std::string::npos);
  }
}

TEST(ExactMethods, SignedDistanceNeedsAnExactMethod) {
  EXPECT_THROW(signed_distance(paper_a(), paper_b_separate(), with(Method::ipso)),
               std::invalid_argument);
  EXPECT_THROW(signed_distance(paper_a(), paper_b_separate(), with(Method::penalty)),
               std::invalid_argument);
}

// ---- The paper's pairs --------------------------------------------------------------------

TEST(ExactMethods, PaperTouchingPairHasDistanceZero) {
  for (Method m : kDistanceMethods) {
    SCOPED_TRACE(method_name(m));
    const DistanceResult r = run(m, paper_a(), paper_b_colliding());
    expect_contract(paper_a(), paper_b_colliding(), r);
    EXPECT_LE(r.distance, 1e-12);
    EXPECT_TRUE(r.colliding);
    EXPECT_TRUE(r.certified);
    EXPECT_EQ(r.method, method_name(m));
    EXPECT_LE((r.point_a - Vector3(1, 0, 0)).norm(), 1e-12);
    EXPECT_TRUE(collide(paper_a(), paper_b_colliding(), with(m)));
  }
  EXPECT_TRUE(collide(paper_a(), paper_b_colliding(), with(Method::libccd)));
  EXPECT_LE(exact_nearest_points(paper_a(), paper_b_colliding()).distance, 1e-12);
}

TEST(ExactMethods, PaperSeparatePairHasDistanceOne) {
  for (Method m : kDistanceMethods) {
    SCOPED_TRACE(method_name(m));
    const DistanceResult r = run(m, paper_a(), paper_b_separate());
    expect_contract(paper_a(), paper_b_separate(), r);
    EXPECT_NEAR(r.distance, 1, 1e-12);
    EXPECT_NEAR(r.lower_bound, 1, 1e-12);
    EXPECT_LE((r.point_a - Vector3(1, 0, 0)).norm(), 1e-12);
    EXPECT_LE((r.point_b - Vector3(1, -1, 0)).norm(), 1e-12);
    EXPECT_NEAR(r.weights_a(1), 1, 1e-12);
    EXPECT_NEAR(r.weights_b(0), 1, 1e-12);
    EXPECT_LE((r.direction - Vector3(0, -1, 0)).norm(), 1e-12);
    EXPECT_FALSE(r.colliding);
    EXPECT_TRUE(r.certified);
    EXPECT_FALSE(collide(paper_a(), paper_b_separate(), with(m)));
  }
  EXPECT_FALSE(collide(paper_a(), paper_b_separate(), with(Method::libccd)));
}

// ---- Random pairs against the brute-force oracle -------------------------------------------

TEST(ExactMethods, RandomSeparatedPairsMatchOracle) {
  std::mt19937_64 rng(7);
  std::normal_distribution<Scalar> g;
  for (int trial = 0; trial < 60; ++trial) {
    SCOPED_TRACE("trial " + std::to_string(trial));
    const int na = 4 + trial % 9;
    const int nb = 4 + (trial * 5) % 11;
    // Boxes [-1, 1]^3 around centres 4 apart never overlap; 2.2 apart along x they are close.
    Vector3 offset = trial % 2 ? Vector3(g(rng), g(rng), g(rng)).normalized() * 4
                               : Vector3(2.2, 0.3 * g(rng), 0.3 * g(rng));
    const ConvexPolyhedron a = random_body(rng, Vector3::Zero(), na);
    const ConvexPolyhedron b = random_body(rng, offset, nb);
    const Scalar exact = oracle_distance(a, b);
    const Scalar tol = 1e-9 * size_of(a, b);
    for (Method m : kDistanceMethods) {
      SCOPED_TRACE(method_name(m));
      const DistanceResult ab = run(m, a, b);
      const DistanceResult ba = run(m, b, a);
      expect_contract(a, b, ab);
      expect_contract(b, a, ba);
      EXPECT_NEAR(ab.distance, exact, tol);
      EXPECT_NEAR(ba.distance, ab.distance, tol);
      EXPECT_LE(ab.lower_bound, exact + tol);
      EXPECT_NEAR(ab.lower_bound, exact, tol);
      EXPECT_FALSE(ab.colliding);
      EXPECT_TRUE(ab.certified);
      EXPECT_FALSE(collide(a, b, with(m)));
    }
    EXPECT_NEAR(exact_nearest_points(a, b).distance, exact, tol);
    EXPECT_FALSE(collide(a, b, with(Method::libccd)));
  }
}

TEST(ExactMethods, RandomOverlappingPairsCollide) {
  std::mt19937_64 rng(11);
  std::normal_distribution<Scalar> g;
  for (int trial = 0; trial < 30; ++trial) {
    const ConvexPolyhedron a = random_body(rng, Vector3::Zero(), 10);
    const ConvexPolyhedron b = random_body(rng, 0.3 * Vector3(g(rng), g(rng), g(rng)), 10);
    for (Method m : kDistanceMethods) {
      const DistanceResult r = run(m, a, b);
      expect_contract(a, b, r);
      EXPECT_LE(r.distance, 1e-12);
      EXPECT_TRUE(r.colliding);
    }
    EXPECT_TRUE(collide(a, b, with(Method::libccd)));
  }
}

// ---- Hard cases -------------------------------------------------------------------------------

TEST(ExactMethods, TouchingAndNearlyTouchingFaces) {
  const ConvexPolyhedron a = cube({0, 0, 0}, {1, 1, 1});
  const ConvexPolyhedron touching = cube({1, 0.2, 0.3}, {2, 1.2, 1.3});
  const ConvexPolyhedron close = cube({1 + 1e-12, 0.2, 0.3}, {2, 1.2, 1.3});
  const ConvexPolyhedron apart = cube({1 + 1e-6, 0.2, 0.3}, {2, 1.2, 1.3});
  for (Method m : kDistanceMethods) {
    SCOPED_TRACE(method_name(m));
    const DistanceResult t = run(m, a, touching);
    expect_contract(a, touching, t);
    EXPECT_LE(t.distance, 1e-14);
    EXPECT_TRUE(t.colliding);
    const DistanceResult c = run(m, a, close);
    expect_contract(a, close, c);
    EXPECT_NEAR(c.distance, 1e-12, 1e-15);
    EXPECT_TRUE(c.colliding);  // within the 1e-9 tolerance
    const DistanceResult f = run(m, a, apart);
    expect_contract(a, apart, f);
    EXPECT_NEAR(f.distance, 1e-6, 1e-15);
    EXPECT_FALSE(f.colliding);
    EXPECT_TRUE(f.certified);
  }
  EXPECT_TRUE(collide(a, touching, with(Method::libccd)));
  EXPECT_TRUE(collide(a, close, with(Method::libccd)));
  EXPECT_FALSE(collide(a, apart, with(Method::libccd)));
}

TEST(ExactMethods, StackedCubes) {
  const ConvexPolyhedron base = cube({0, 0, 0}, {1, 1, 1});
  for (int level = 1; level <= 4; ++level) {
    const ConvexPolyhedron top =
        cube({0.1 * level, 0, Scalar(level)}, {1 + 0.1 * level, 1, level + 1.0});
    for (Method m : kDistanceMethods) {
      const DistanceResult r = run(m, base, top);
      expect_contract(base, top, r);
      EXPECT_NEAR(r.distance, level - 1.0, 1e-12);
      EXPECT_EQ(r.colliding, level == 1);
    }
  }
}

TEST(ExactMethods, SizeRatioOneMillion) {
  const ConvexPolyhedron big = cube({0, 0, 0}, {1e6, 1e6, 1e6});
  const ConvexPolyhedron small = shifted(paper_a(), Vector3(1e6 + 1, 3e5, 2e5));
  for (Method m : kDistanceMethods) {
    SCOPED_TRACE(method_name(m));
    const DistanceResult r = run(m, big, small);
    expect_contract(big, small, r);
    EXPECT_NEAR(r.distance, 1, 1e-9 * 1e6);
    EXPECT_NEAR(r.distance, 1, 1e-8);  // far better than the relative promise
    const DistanceResult tiny =
        run(m, paper_a(), shifted(cube({0, 0, 0}, {1e-6, 1e-6, 1e-6}), Vector3(1 + 1e-6, 0, 0)));
    EXPECT_NEAR(tiny.distance, 1e-6, 1e-15);
  }
}

TEST(ExactMethods, CoordinatesOffsetByOneMillion) {
  const Vector3 offset(1e6, -1e6, 1e6);
  const ConvexPolyhedron a = shifted(paper_a(), offset);
  const ConvexPolyhedron b = shifted(paper_b_separate(), offset);
  const ConvexPolyhedron t = shifted(paper_b_colliding(), offset);
  for (Method m : kDistanceMethods) {
    SCOPED_TRACE(method_name(m));
    const DistanceResult r = run(m, a, b);
    expect_contract(a, b, r);
    EXPECT_NEAR(r.distance, 1, 1e-9);
    EXPECT_LE((r.point_a - (offset + Vector3(1, 0, 0))).norm(), 1e-9);
    const DistanceResult c = run(m, a, t);
    EXPECT_LE(c.distance, 1e-9);
    EXPECT_TRUE(c.colliding);
  }
  EXPECT_TRUE(collide(a, t, with(Method::libccd)));
  EXPECT_FALSE(collide(a, b, with(Method::libccd)));
}

TEST(ExactMethods, DegenerateBodies) {
  const ConvexPolyhedron a = paper_a();
  const ConvexPolyhedron point = points({{3, 3, 3}});
  const ConvexPolyhedron inside = points({{0.1, 0.1, 0.1}});
  const ConvexPolyhedron segment = points({{3, -1, 0}, {3, 1, 0}, {3, 0.5, 0}});
  const ConvexPolyhedron square = points({{-1, -1, 2}, {1, -1, 2}, {1, 1, 2}, {-1, 1, 2}});
  const ConvexPolyhedron crossing = points({{0.2, 0.2, -1}, {0.2, 0.2, 3}});
  const ConvexPolyhedron other_point = points({{3, 3, 4}});
  const ConvexPolyhedron skew = points({{-1, 0, 1}, {1, 0, 1}});
  const ConvexPolyhedron skew2 = points({{0, -1, 3}, {0, 1, 3}});
  struct Case {
    const ConvexPolyhedron* a;
    const ConvexPolyhedron* b;
    Scalar expected;
  };
  const std::vector<Case> cases = {
      {&a, &point, 8 / std::sqrt(3.0)},
      {&a, &inside, 0},
      {&a, &segment, 2},
      {&a, &square, 1},
      {&a, &crossing, 0},
      {&point, &other_point, 1},
      {&skew, &skew2, 2},
      {&square, &skew2, 1},
      {&segment, &square, 2 * std::sqrt(2.0)},
  };
  for (std::size_t k = 0; k < cases.size(); ++k) {
    SCOPED_TRACE("case " + std::to_string(k));
    for (Method m : kDistanceMethods) {
      SCOPED_TRACE(method_name(m));
      const DistanceResult ab = run(m, *cases[k].a, *cases[k].b);
      const DistanceResult ba = run(m, *cases[k].b, *cases[k].a);
      expect_contract(*cases[k].a, *cases[k].b, ab);
      expect_contract(*cases[k].b, *cases[k].a, ba);
      EXPECT_NEAR(ab.distance, cases[k].expected, 1e-12);
      EXPECT_NEAR(ba.distance, cases[k].expected, 1e-12);
      if (cases[k].expected > 0) {
        EXPECT_NEAR(oracle_distance(*cases[k].a, *cases[k].b), cases[k].expected, 1e-12);
      }
    }
    EXPECT_EQ(collide(*cases[k].a, *cases[k].b, with(Method::libccd)), cases[k].expected == 0);
  }
}

TEST(ExactMethods, DuplicateVertices) {
  VertexMatrix v(9, 3);
  v << 1, -1, 0, 2, -2, 0, 0, -2, 2, 0, -2, 0, 1, -1, 0, 1, -1, 0, 2, -2, 0, 0.5, -1.5, 0.2, 0, -2,
      0;
  const ConvexPolyhedron b(v);
  for (Method m : kDistanceMethods) {
    const DistanceResult r = run(m, paper_a(), b);
    expect_contract(paper_a(), b, r);
    EXPECT_NEAR(r.distance, 1, 1e-12);
  }
}

// The library's own solver solves its corral's affine subproblems in closed form, so the cases
// where they degenerate (flat nearest features, repeated points, far offsets) are checked too.
TEST(Wolfe, HardCases) {
  for (const testing::HardCase& c : testing::hard_cases()) {
    SCOPED_TRACE(c.name);
    for (const bool swapped : {false, true}) {
      const ConvexPolyhedron& a = swapped ? c.b : c.a;
      const ConvexPolyhedron& b = swapped ? c.a : c.b;
      const DistanceResult r = exact_nearest_points(a, b);
      expect_contract(a, b, r);
      EXPECT_NEAR(r.distance, c.distance, c.accuracy);
    }
  }
}

// ---- Signed distance ------------------------------------------------------------------------

std::vector<DistanceOptions> signed_methods() {
  DistanceOptions mpr = with(Method::libccd);
  mpr.exact.penetration = PenetrationAlgorithm::mpr;
  return {with(Method::fcl), with(Method::fcl_indep), with(Method::libccd), mpr};
}

void expect_signed_contract(const ConvexPolyhedron& a, const ConvexPolyhedron& b,
                            const DistanceResult& r) {
  const Scalar eps = 1e-9 * size_of(a, b);
  EXPECT_GE(r.weights_a.minCoeff(), 0);
  EXPECT_GE(r.weights_b.minCoeff(), 0);
  EXPECT_NEAR(r.weights_a.sum(), 1, 1e-12);
  EXPECT_NEAR(r.weights_b.sum(), 1, 1e-12);
  EXPECT_LE((a.vertices().transpose() * r.weights_a - r.point_a).norm(), 1e-12);
  EXPECT_LE((b.vertices().transpose() * r.weights_b - r.point_b).norm(), 1e-12);
  EXPECT_LE(r.lower_bound, r.distance + eps);
  EXPECT_EQ(r.status, SolverStatus::exact);
  if (r.direction.norm() > 0) {
    EXPECT_NEAR(r.direction.norm(), 1, 1e-12);
    EXPECT_LE((r.point_b - r.point_a - r.distance * r.direction).norm(), 1e-6 * size_of(a, b));
  }
}

TEST(SignedDistance, OverlappingCubesHaveKnownDepth) {
  const ConvexPolyhedron a = cube({0, 0, 0}, {1, 1, 1});
  const ConvexPolyhedron b = cube({0.8, 0.1, 0.05}, {1.8, 0.9, 0.95});
  for (const DistanceOptions& o : signed_methods()) {
    SCOPED_TRACE(method_name(o.method));
    const DistanceResult r = signed_distance(a, b, o);
    expect_signed_contract(a, b, r);
    EXPECT_NEAR(r.distance, -0.2, 1e-9);
    EXPECT_NEAR(r.lower_bound, -0.2, 1e-9);
    EXPECT_LE((r.direction - Vector3(1, 0, 0)).norm(), 1e-6);
    EXPECT_NEAR(r.point_a.x(), 1, 1e-9);
    EXPECT_NEAR(r.point_b.x(), 0.8, 1e-9);
    EXPECT_TRUE(r.colliding);
    EXPECT_TRUE(r.certified);
  }
}

TEST(SignedDistance, ApartAndTouchingPairs) {
  for (const DistanceOptions& o : signed_methods()) {
    SCOPED_TRACE(method_name(o.method));
    const DistanceResult apart = signed_distance(paper_a(), paper_b_separate(), o);
    expect_signed_contract(paper_a(), paper_b_separate(), apart);
    EXPECT_NEAR(apart.distance, 1, 1e-12);
    EXPECT_EQ(apart.method, method_name(o.method));
    const DistanceResult touching = signed_distance(paper_a(), paper_b_colliding(), o);
    expect_signed_contract(paper_a(), paper_b_colliding(), touching);
    EXPECT_NEAR(touching.distance, 0, 1e-9);
    EXPECT_TRUE(touching.colliding);
  }
}

TEST(SignedDistance, RandomOverlapsMatchSeparatingAxisOracle) {
  std::mt19937_64 rng(3);
  std::normal_distribution<Scalar> g;
  for (int trial = 0; trial < 25; ++trial) {
    SCOPED_TRACE("trial " + std::to_string(trial));
    const ConvexPolyhedron a = random_body(rng, Vector3::Zero(), 12);
    const ConvexPolyhedron b = random_body(rng, 0.5 * Vector3(g(rng), g(rng), g(rng)), 12);
    const Scalar depth = oracle_depth(a, b);
    ASSERT_GT(depth, 0);
    Scalar fcl_depth = 0;
    for (const DistanceOptions& o : signed_methods()) {
      SCOPED_TRACE(method_name(o.method) +
                   (o.exact.penetration == PenetrationAlgorithm::mpr ? " mpr" : ""));
      const DistanceResult r = signed_distance(a, b, o);
      expect_signed_contract(a, b, r);
      // The lower bound is a certificate: never above minus the true depth.
      EXPECT_LE(r.lower_bound, -depth + 1e-12);
      if (o.method == Method::fcl) fcl_depth = -r.distance;
      if (o.exact.penetration == PenetrationAlgorithm::epa) {
        EXPECT_NEAR(-r.distance, depth, 1e-6 * depth);
        EXPECT_NEAR(-r.distance, fcl_depth, 1e-6 * fcl_depth);
      } else {
        // MPR finds a penetration along its portal, an upper bound on the depth.
        EXPECT_GE(-r.distance, depth - 1e-9);
      }
    }
  }
}

}  // namespace
}  // namespace swarmcollide
