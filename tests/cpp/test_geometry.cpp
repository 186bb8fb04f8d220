#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <limits>
#include <random>
#include <set>
#include <stdexcept>
#include <thread>
#include <utility>

#include "geometry/support.hpp"
#include "geometry/support_tree.hpp"
#include "paper_cases.hpp"
#include "swarmcollide/geometry/convex_polyhedron.hpp"
#include "swarmcollide/geometry/shapes.hpp"

namespace swarmcollide {
namespace {

VertexMatrix unit_cube() {
  VertexMatrix v(8, 3);
  int row = 0;
  for (int x = 0; x < 2; ++x)
    for (int y = 0; y < 2; ++y)
      for (int z = 0; z < 2; ++z) v.row(row++) << x, y, z;
  return v;
}

using OrientedTriangle = std::array<int, 3>;

// The triangle with its smallest index first, the orientation kept.
OrientedTriangle rotated_to_smallest(int p, int q, int r) {
  if (q < p && q < r) return {q, r, p};
  if (r < p && r < q) return {r, p, q};
  return {p, q, r};
}

// Brute-force oracle for points in general position: the faces are the triangles whose plane has
// every other point strictly on one side, oriented so that side is behind them.
std::set<OrientedTriangle> hull_triangles_by_brute_force(const VertexMatrix& points) {
  std::set<OrientedTriangle> faces;
  const int n = static_cast<int>(points.rows());
  for (int i = 0; i < n; ++i) {
    for (int j = i + 1; j < n; ++j) {
      for (int k = j + 1; k < n; ++k) {
        const Vector3 p = points.row(i);
        const Vector3 normal = (points.row(j).transpose() - p).cross(points.row(k).transpose() - p);
        int above = 0;
        int below = 0;
        for (int m = 0; m < n; ++m) {
          if (m == i || m == j || m == k) continue;
          const Scalar height = normal.dot(points.row(m).transpose() - p);
          above += height > 0;
          below += height < 0;
        }
        if (above == 0) faces.insert(rotated_to_smallest(i, j, k));
        if (below == 0) faces.insert(rotated_to_smallest(i, k, j));
      }
    }
  }
  return faces;
}

std::set<OrientedTriangle> triangles_of(const Hull& hull) {
  std::set<OrientedTriangle> faces;
  for (Eigen::Index f = 0; f < hull.faces.rows(); ++f) {
    faces.insert(rotated_to_smallest(hull.faces(f, 0), hull.faces(f, 1), hull.faces(f, 2)));
  }
  return faces;
}

// Every face normal points away from every hull vertex not on the face.
void expect_outward(const ConvexPolyhedron& body) {
  const Hull& hull = body.hull();
  for (Eigen::Index f = 0; f < hull.faces.rows(); ++f) {
    const Vector3 p = body.vertices().row(hull.faces(f, 0));
    const Vector3 q = body.vertices().row(hull.faces(f, 1));
    const Vector3 r = body.vertices().row(hull.faces(f, 2));
    const Vector3 normal = (q - p).cross(r - p);
    for (int i : hull.vertex_indices) {
      EXPECT_LE(normal.dot(body.vertices().row(i).transpose() - p), 1e-12);
    }
  }
}

TEST(ConvexPolyhedron, RejectsEmptyAndNonFinitePoints) {
  EXPECT_THROW(ConvexPolyhedron(VertexMatrix(0, 3)), std::invalid_argument);
  VertexMatrix bad = unit_cube();
  bad(3, 1) = std::numeric_limits<Scalar>::quiet_NaN();
  EXPECT_THROW(ConvexPolyhedron{bad}, std::invalid_argument);
  bad(3, 1) = std::numeric_limits<Scalar>::infinity();
  EXPECT_THROW(ConvexPolyhedron{bad}, std::invalid_argument);
}

TEST(ConvexPolyhedron, RejectsPointsSpanningBeyondTheDoubleRange) {
  // The radius (half the box's diagonal) is what every query scales by: 2.6e308 is too large.
  VertexMatrix span(2, 3);
  span << 1.5e308, 1.5e308, 1.5e308, -1.5e308, -1.5e308, -1.5e308;
  EXPECT_THROW(ConvexPolyhedron{span}, std::invalid_argument);
  span.col(1).setZero();
  span.col(2).setZero();  // along one axis the radius is 1.5e308
  EXPECT_NO_THROW(ConvexPolyhedron{span});
}

TEST(ConvexPolyhedron, BoundsAreTheBoxItsCentreAndHalfDiagonal) {
  VertexMatrix points(3, 3);
  points << 1, 2, 3, -1, 0, 5, 3, 2, 4;
  const ConvexPolyhedron body(points);
  const BodyBounds& bounds = body.bounds();
  EXPECT_EQ(bounds.box.min, Vector3(-1, 0, 3));
  EXPECT_EQ(bounds.box.max, Vector3(3, 2, 5));
  EXPECT_EQ(bounds.centre, Vector3(1, 1, 4));
  EXPECT_DOUBLE_EQ(bounds.radius, std::sqrt(4.0 + 1 + 1));
  EXPECT_EQ(&body.aabb(), &bounds.box);
  // Coordinates near the largest double still give a finite centre and radius.
  const BodyBounds huge = ConvexPolyhedron(points * 3e307).bounds();
  EXPECT_TRUE(huge.centre.isApprox(Vector3(3e307, 3e307, 1.2e308), 1e-15));
  EXPECT_DOUBLE_EQ(huge.radius, 3e307 * std::sqrt(6.0));
}

// The outer ball (Query::collide's screen) holds every point of the body, rounding radius
// included, at every scale, and is the points' own ball (tighter than the box's), not a looser
// bound; a curved shape's is its own outer radius, which holds its support points.
TEST(ConvexPolyhedron, OuterRadiusHoldsTheBodyAboutItsBoxCentre) {
  std::mt19937_64 rng(41);
  std::uniform_real_distribution<Scalar> uniform(-1, 1);
  for (const Scalar scale : {1e-200, 1e-8, 1.0, 3e5, 1e200}) {
    for (const Scalar rounding : {0.0, 0.3}) {
      VertexMatrix points(12, 3);
      for (Eigen::Index i = 0; i < points.rows(); ++i) {
        for (int k = 0; k < 3; ++k) points(i, k) = (uniform(rng) + 5) * scale;
      }
      const ConvexPolyhedron body(points, rounding * scale);
      long double farthest = 0;
      for (Eigen::Index i = 0; i < points.rows(); ++i) {
        long double squares = 0;
        for (int k = 0; k < 3; ++k) {
          const long double d = static_cast<long double>(points(i, k)) /
                                    static_cast<long double>(scale) -
                                static_cast<long double>(body.bounds().centre(k)) /
                                    static_cast<long double>(scale);
          squares += d * d;
        }
        farthest = std::max(farthest, std::sqrt(squares));
      }
      const long double reach = (farthest + rounding) * static_cast<long double>(scale);
      EXPECT_GE(static_cast<long double>(body.outer_radius()), reach) << scale << " " << rounding;
      EXPECT_LE(static_cast<long double>(body.outer_radius()), reach * (1 + 1e-11L))
          << scale << " " << rounding;
      EXPECT_LE(body.outer_radius(), body.bounds().radius) << scale << " " << rounding;
    }
  }
  const Cylinder cylinder(0.5, 2);
  EXPECT_GE(cylinder.outer_radius(), std::hypot(0.5, 2.0));
  EXPECT_LE(cylinder.outer_radius(), std::hypot(0.5, 2.0) * (1 + 1e-11));
  const Sphere sphere(0.7);
  EXPECT_GE(sphere.outer_radius(), 0.7);
  EXPECT_LE(sphere.outer_radius(), 0.7 * (1 + 1e-11));
  const Ellipsoid ellipsoid(Vector3(0.2, 3, 1));
  for (int i = 0; i < 200; ++i) {
    const Vector3 d(uniform(rng), uniform(rng), uniform(rng));
    EXPECT_LE((ellipsoid.support(d) - ellipsoid.bounds().centre).norm(),
              ellipsoid.outer_radius());
  }
  EXPECT_LE(ellipsoid.outer_radius(), 3 * (1 + 1e-11));
}

TEST(ConvexPolyhedron, SupportIsTheFarthestPoint) {
  const ConvexPolyhedron cube(unit_cube());
  EXPECT_EQ(cube.support(Vector3(1, 1, 1)), Vector3(1, 1, 1));
  EXPECT_EQ(cube.support(Vector3(-1, -2, -3)), Vector3(0, 0, 0));
  EXPECT_EQ(cube.support(Vector3(1, -1, 1)), Vector3(1, 0, 1));
}

TEST(ConvexPolyhedron, BoxAndCentroid) {
  const ConvexPolyhedron cube(unit_cube());
  EXPECT_EQ(cube.aabb().min, Vector3::Zero());
  EXPECT_EQ(cube.aabb().max, Vector3::Ones());
  EXPECT_TRUE(cube.centroid().isApprox(Vector3(0.5, 0.5, 0.5), 1e-14));
  // The solid's centroid, not the mean of the points: an extra point inside the cube moves the
  // mean but not the body.
  VertexMatrix with_inner(9, 3);
  with_inner << unit_cube(), 0.1, 0.1, 0.1;
  EXPECT_TRUE(ConvexPolyhedron(with_inner).centroid().isApprox(Vector3(0.5, 0.5, 0.5), 1e-14));
  EXPECT_TRUE(testing::paper_a().centroid().isApprox(Vector3(0.25, 0.25, 0.25), 1e-14));
}

TEST(ConvexPolyhedron, DerivedDataIsMadeOncePerBodyAndSharedByCopies) {
  const ConvexPolyhedron cube(unit_cube());
  const ConvexPolyhedron copy = cube;
  int made = 0;
  const auto make = [&made] { return ++made; };
  const int& first = cube.derived<int>(make);
  EXPECT_EQ(copy.derived<int>(make), 1);
  EXPECT_EQ(&copy.derived<int>(make), &first);
  EXPECT_EQ(made, 1);
  // Another type is another slot, and so is another key; another body has its own.
  EXPECT_EQ(cube.derived<double>([] { return 2.5; }), 2.5);
  EXPECT_EQ(cube.derived<int>(make, 7), 2);
  EXPECT_EQ(&cube.derived<int>(make), &first);
  EXPECT_EQ(ConvexPolyhedron(unit_cube()).derived<int>(make), 3);
}

TEST(ConvexPolyhedron, ThreadsAskingForDerivedDataAtOnceShareOne) {
  // Each thread asks for several keys, so that threads read the list while others add to it.
  for (int trial = 0; trial < 20; ++trial) {
    const ConvexPolyhedron cube(unit_cube());
    std::atomic<int> made{0};
    std::vector<std::vector<const int*>> seen(4, std::vector<const int*>(8, nullptr));
    std::vector<std::thread> threads;
    for (std::size_t t = 0; t < seen.size(); ++t) {
      threads.emplace_back([&cube, &seen, &made, t] {
        for (int key = 0; key < 8; ++key) {
          const int k = (key + static_cast<int>(t)) % 8;
          seen[t][k] = &cube.derived<int>([&made, k] {
            ++made;
            return k;
          }, k);
        }
      });
    }
    for (std::thread& thread : threads) thread.join();
    EXPECT_EQ(made.load(), 8);
    for (int key = 0; key < 8; ++key) {
      EXPECT_EQ(*seen[0][key], key);
      for (std::size_t t = 1; t < seen.size(); ++t) EXPECT_EQ(seen[t][key], seen[0][key]);
    }
  }
}

TEST(ConvexPolyhedron, ThreadsAskingForTheHullAtOnceShareOne) {
  for (int trial = 0; trial < 20; ++trial) {
    const ConvexPolyhedron cube(unit_cube());
    std::vector<const Hull*> seen(4, nullptr);
    std::vector<std::thread> threads;
    for (std::size_t t = 0; t < seen.size(); ++t) {
      threads.emplace_back([&cube, &seen, t] { seen[t] = &cube.hull(); });
    }
    for (auto& thread : threads) thread.join();
    for (const Hull* hull : seen) {
      EXPECT_EQ(hull, &cube.hull());
      EXPECT_EQ(hull->faces.rows(), 12);
    }
  }
}

// The tree's support point is as high as a scan's, to the rounding of the heights: on random
// clouds, on a sphere, and on a grid whose faces tie (every point of a top face is a maximum).
TEST(SupportTree, FindsThePointAScanFinds) {
  std::mt19937_64 rng(7);
  std::normal_distribution<double> normal;
  std::uniform_int_distribution<int> pick(-1, 999);
  for (int shape = 0; shape < 3; ++shape) {
    VertexMatrix points(1000, 3);
    for (int i = 0; i < 1000; ++i) {
      Vector3 p(normal(rng), normal(rng), normal(rng));
      if (shape == 1) p.normalize();
      if (shape == 2) p = Vector3(i % 10, (i / 10) % 10, i / 100);
      points.row(i) = 3 * p.transpose();
    }
    const detail::SupportTree tree(points);
    for (int trial = 0; trial < 200; ++trial) {
      Vector3 d(normal(rng), normal(rng), normal(rng));
      if (trial % 4 == 0) d = Vector3::Unit(trial % 3);
      const int found = tree.support_index(points, d, pick(rng));
      const int scanned = detail::scan_support(points, d);
      const Scalar rounding = 1e-15 * points.norm() * d.norm();
      EXPECT_GE(detail::point_height(points, found, d),
                detail::point_height(points, scanned, d) - rounding)
          << "shape " << shape << " trial " << trial;
    }
  }
}

// The column scan (several heights at a time), on every instruction set this processor runs,
// answers the row scan's index, bit for bit: for every count up to its capacity (the columns are
// padded), on random clouds, on grids whose heights tie (the first maximiser wins), on heights of
// both signs of zero, and on directions that make heights infinite or NaN (the row scan keeps its
// first point against a NaN).
TEST(PointColumns, ScanFindsTheRowScansIndex) {
  constexpr std::array<detail::KernelIsa, 3> kIsas = {
      detail::KernelIsa::baseline, detail::KernelIsa::avx2, detail::KernelIsa::avx512};
  int sets = 0;
  for (const auto isa : kIsas) sets += detail::kernel_isa_available(isa) ? 1 : 0;
  std::mt19937_64 rng(11);
  std::normal_distribution<double> normal;
  const double inf = std::numeric_limits<double>::infinity();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  int checked = 0;
  for (int count = 1; count <= detail::PointColumns::kCapacity; ++count) {
    for (int shape = 0; shape < 4; ++shape) {
      VertexMatrix points(count, 3);
      for (int i = 0; i < count; ++i) {
        Vector3 p(normal(rng), normal(rng), normal(rng));
        if (shape == 1) p = Vector3(i % 2, (i / 2) % 2, 0);  // ties along z and across
        if (shape == 2) p = Vector3(i % 3 == 0 ? 0.0 : -0.0, 0.0, i % 2 ? 1e308 : -1e308);
        if (shape == 3) p *= 1e300;  // products overflow to infinities, sums to NaN
        points.row(i) = p.transpose();
      }
      detail::PointColumns columns;
      columns.assign(points);
      ASSERT_TRUE(columns.held());
      for (int trial = 0; trial < 40; ++trial) {
        Vector3 d(normal(rng), normal(rng), normal(rng));
        if (trial % 5 == 0) d = Vector3::Unit(trial % 3);
        if (trial % 5 == 1) d = -Vector3::Unit(trial % 3);
        if (trial == 2) d = Vector3(nan, 1, 0);
        if (trial == 3) d = Vector3(inf, -inf, 1);
        if (trial == 4) d = Vector3(1e10, 1e10, 1e10);
        const int expected = detail::scan_support(points, d);
        EXPECT_EQ(columns.scan(d), expected)
            << "count " << count << " shape " << shape << " trial " << trial;
        if (count <= detail::kRegisterColumns) {
          // The few points' register scan, which every set takes for them, on the columns as
          // PointColumns pads them (by the last point).
          constexpr int kCapacity = detail::PointColumns::kCapacity;
          std::array<double, 3 * kCapacity> held;
          for (int i = 0; i < kCapacity; ++i) {
            for (int k = 0; k < 3; ++k) held[k * kCapacity + i] = points(std::min(i, count - 1), k);
          }
          EXPECT_EQ(detail::scan_few_columns(held.data(), count, d.x(), d.y(), d.z()), expected)
              << "few, count " << count << " shape " << shape << " trial " << trial;
        }
        for (const auto isa : kIsas) {
          if (!detail::kernel_isa_available(isa)) continue;
          EXPECT_EQ(columns.scan_with(detail::column_scan_for(isa), d), expected)
              << detail::kernel_isa_name(isa) << ", count " << count << " shape " << shape
              << " trial " << trial;
          ++checked;
        }
      }
    }
  }
  EXPECT_EQ(checked, detail::PointColumns::kCapacity * 4 * 40 * sets);
}

TEST(Hull, CubeHasEightVerticesAndTwelveOutwardTriangles) {
  VertexMatrix points(9, 3);
  points << unit_cube(), 0.5, 0.5, 0.5;
  const ConvexPolyhedron cube(points);
  const Hull& hull = cube.hull();
  EXPECT_EQ(hull.dimension, 3);
  EXPECT_EQ(hull.vertex_indices, (std::vector<int>{0, 1, 2, 3, 4, 5, 6, 7}));
  EXPECT_EQ(hull.faces.rows(), 12);
  expect_outward(cube);
}

TEST(Hull, FlatPolygonIsListedFacingBothSides) {
  VertexMatrix square(5, 3);
  square << 0, 0, 2, 1, 0, 2, 1, 1, 2, 0, 1, 2, 0.5, 0.5, 2;
  const ConvexPolyhedron body(square);
  const Hull& hull = body.hull();
  EXPECT_EQ(hull.dimension, 2);
  EXPECT_EQ(hull.vertex_indices, (std::vector<int>{0, 1, 2, 3}));
  EXPECT_EQ(hull.faces.rows(), 4);
  std::set<int> normal_signs;
  for (Eigen::Index f = 0; f < hull.faces.rows(); ++f) {
    const Vector3 p = square.row(hull.faces(f, 0));
    const Vector3 n = (square.row(hull.faces(f, 1)).transpose() - p)
                          .cross(square.row(hull.faces(f, 2)).transpose() - p);
    normal_signs.insert(n.z() > 0 ? 1 : -1);
  }
  EXPECT_EQ(normal_signs, (std::set<int>{-1, 1}));
  EXPECT_TRUE(body.centroid().isApprox(Vector3(0.5, 0.5, 2), 1e-14));
}

TEST(Hull, SegmentAndPointHaveNoFaces) {
  VertexMatrix segment(3, 3);
  segment << 0, 0, 0, 2, 2, 2, 1, 1, 1;
  const ConvexPolyhedron line(segment);
  EXPECT_EQ(line.hull().dimension, 1);
  EXPECT_EQ(line.hull().vertex_indices, (std::vector<int>{0, 1}));
  EXPECT_EQ(line.hull().faces.rows(), 0);
  EXPECT_TRUE(line.centroid().isApprox(Vector3(1, 1, 1), 1e-14));

  VertexMatrix repeated(3, 3);
  repeated << 1, 2, 3, 1, 2, 3, 1, 2, 3;
  const ConvexPolyhedron point(repeated);
  EXPECT_EQ(point.hull().dimension, 0);
  EXPECT_EQ(point.hull().vertex_indices.size(), 1u);
  EXPECT_EQ(point.centroid(), Vector3(1, 2, 3));
}

TEST(Hull, FarFromTheOriginStillExact) {
  VertexMatrix points = unit_cube();
  points.rowwise() += Eigen::RowVector3d(1e6, -1e6, 1e6);
  const ConvexPolyhedron cube(points);
  EXPECT_EQ(cube.hull().dimension, 3);
  EXPECT_EQ(cube.hull().faces.rows(), 12);
  expect_outward(cube);
}

// Hulls are computed on points moved into the unit ball, so no coordinate in the double range
// overflows or underflows their orientation tests.
TEST(Hull, ExactAtAnyScale) {
  for (Scalar scale : {1e-300, 1e-100, 1e77, 1e100, 1e300}) {
    SCOPED_TRACE(scale);
    const ConvexPolyhedron cube(unit_cube() * scale);
    EXPECT_EQ(cube.hull().dimension, 3);
    EXPECT_EQ(cube.hull().faces.rows(), 12);
    EXPECT_TRUE(cube.centroid().isApprox(Vector3::Constant(0.5 * scale), 1e-14));
  }
}

TEST(Hull, RandomSmallSolidsMatchTheBruteForceOracle) {
  std::mt19937_64 rng(11);
  std::normal_distribution<Scalar> normal;
  for (int n : {4, 5, 6, 8, 12, 16, 17, 24}) {
    for (int trial = 0; trial < 50; ++trial) {
      SCOPED_TRACE(std::to_string(n) + " points, trial " + std::to_string(trial));
      VertexMatrix points(n, 3);
      for (Eigen::Index k = 0; k < points.size(); ++k) points.data()[k] = normal(rng);
      points.col(2) *= trial % 2 ? 1.0 : 1e-3;  // some thin bodies too
      const ConvexPolyhedron body(points);
      const Hull& hull = body.hull();
      const std::set<OrientedTriangle> expected = hull_triangles_by_brute_force(points);
      EXPECT_EQ(hull.dimension, 3);
      EXPECT_EQ(triangles_of(hull), expected);
      EXPECT_EQ(hull.faces.rows(), static_cast<Eigen::Index>(expected.size()));
      std::set<int> corners;
      for (const auto& t : expected) corners.insert(t.begin(), t.end());
      EXPECT_EQ(hull.vertex_indices, std::vector<int>(corners.begin(), corners.end()));
      // The neighbours of a point are the other corners of its triangles' edges, ascending.
      std::vector<std::set<int>> adjacent(n);
      for (const auto& t : expected) {
        for (int k = 0; k < 3; ++k) {
          adjacent[t[k]].insert(t[(k + 1) % 3]);
          adjacent[t[(k + 1) % 3]].insert(t[k]);
        }
      }
      ASSERT_EQ(hull.neighbour_offsets.size(), static_cast<std::size_t>(n) + 1);
      for (int i = 0; i < n; ++i) {
        EXPECT_EQ(std::vector<int>(hull.neighbours.begin() + hull.neighbour_offsets[i],
                                   hull.neighbours.begin() + hull.neighbour_offsets[i + 1]),
                  std::vector<int>(adjacent[i].begin(), adjacent[i].end()))
            << "point " << i;
      }
    }
  }
}

TEST(Hull, PointsWithinRoundingOfAFaceAreNotVertices) {
  // A tetrahedron with a fifth point over the centre of its slanted face: far enough out it is a
  // vertex; within the hull's tolerance (1e-12 of the size) of the face it is on the face.
  VertexMatrix points(5, 3);
  points << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0;
  const Vector3 centre(1.0 / 3, 1.0 / 3, 1.0 / 3);
  const Vector3 out = Vector3::Ones().normalized();
  for (const auto& [height, vertex] : {std::pair{1e-6, true}, std::pair{1e-14, false},
                                       std::pair{-1e-14, false}, std::pair{-1e-6, false}}) {
    SCOPED_TRACE(height);
    points.row(4) = (centre + height * out).transpose();
    const ConvexPolyhedron body(points);
    const Hull& hull = body.hull();
    EXPECT_EQ(hull.dimension, 3);
    const std::vector<int> expected =
        vertex ? std::vector<int>{0, 1, 2, 3, 4} : std::vector<int>{0, 1, 2, 3};
    EXPECT_EQ(hull.vertex_indices, expected);
    EXPECT_EQ(hull.faces.rows(), vertex ? 6 : 4);
  }
}

TEST(Hull, RepeatedPointsAppearOnce) {
  VertexMatrix points(6, 3);
  points << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 0, 0, 0.1, 0.1, 0.1;
  const ConvexPolyhedron body(points);
  const Hull& hull = body.hull();
  EXPECT_EQ(hull.dimension, 3);
  EXPECT_EQ(hull.faces.rows(), 4);
  ASSERT_EQ(hull.vertex_indices.size(), 4u);
  EXPECT_EQ(hull.vertex_indices[0], 0);
  EXPECT_TRUE(hull.vertex_indices[1] == 1 || hull.vertex_indices[1] == 4);
}

TEST(Hull, TwoPointsFarFromTheOriginAreASegment) {
  // The rounded mean of these two points leaves a sliver of a second singular value.
  VertexMatrix points(2, 3);
  points << 1000000.12573022, 999999.86789514, 1e6, 1000000.10490012, 999999.46433063, 1e6;
  const ConvexPolyhedron segment(points);
  EXPECT_EQ(segment.hull().dimension, 1);
  EXPECT_EQ(segment.hull().vertex_indices, (std::vector<int>{0, 1}));
  EXPECT_TRUE(segment.centroid().isApprox(points.colwise().mean().transpose(), 1e-15));
}

// Bodies of more than kHillClimbingThreshold points climb the hull's edge graph from a start
// point; the answer is a farthest point, as a scan finds it, from any start.
TEST(HillClimbing, SupportMatchesTheScan) {
  std::mt19937_64 rng(5);
  std::normal_distribution<Scalar> normal;
  VertexMatrix points(500, 3);
  for (int i = 0; i < points.rows(); ++i) {
    points.row(i) << normal(rng), normal(rng), normal(rng);  // many interior points
  }
  const ConvexPolyhedron body(points);
  int start = -1;
  for (int k = 0; k < 200; ++k) {
    const Vector3 d(normal(rng), normal(rng), normal(rng));
    start = body.support_index(d, k % 3 == 0 ? -1 : start);
    EXPECT_DOUBLE_EQ(points.row(start).dot(d), (points * d).maxCoeff());
  }
  const Hull& hull = body.hull();
  ASSERT_EQ(hull.neighbour_offsets.size(), static_cast<std::size_t>(body.size()) + 1);
  for (int i = 0; i < body.size(); ++i) {
    for (int k = hull.neighbour_offsets[i]; k < hull.neighbour_offsets[i + 1]; ++k) {
      const int j = hull.neighbours[k];
      const auto begin = hull.neighbours.begin() + hull.neighbour_offsets[j];
      const auto end = hull.neighbours.begin() + hull.neighbour_offsets[j + 1];
      EXPECT_NE(std::find(begin, end, i), end);  // symmetric
    }
  }
}

// A climb without a start begins at the hull's start for its direction's cube-map cell: each
// cell's start supports the body along the cell's centre, and every direction, the centres
// included, falls in the cell whose centre is nearest along its major axis.
TEST(HillClimbing, ClimbStartsSupportTheirCells) {
  std::mt19937_64 rng(11);
  std::normal_distribution<Scalar> normal;
  VertexMatrix points(300, 3);
  for (int i = 0; i < points.rows(); ++i) points.row(i) << normal(rng), normal(rng), normal(rng);
  const ConvexPolyhedron body(points);
  const std::vector<int>& starts = body.hull().climb_starts;
  ASSERT_EQ(starts.size(), static_cast<std::size_t>(detail::kClimbStartCount));
  for (int cell = 0; cell < detail::kClimbStartCount; ++cell) {
    const Vector3 d = detail::climb_cell_centre(cell);
    EXPECT_EQ(detail::climb_cell(d), cell);
    EXPECT_EQ(detail::climb_cell(3 * d), cell);
    EXPECT_NEAR(points.row(starts[cell]).dot(d), (points * d).maxCoeff(), 1e-12);
  }
  EXPECT_EQ(detail::climb_cell(Vector3::Zero()), 0);
  EXPECT_EQ(detail::climb_cell(Vector3(1, std::nan(""), 0)), 0);
}

}  // namespace
}  // namespace swarmcollide
