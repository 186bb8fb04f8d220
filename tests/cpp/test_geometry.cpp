#include <gtest/gtest.h>

#include <set>
#include <stdexcept>

#include "paper_cases.hpp"
#include "swarmcollide/geometry/convex_polyhedron.hpp"

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
  const std::shared_ptr<const int> first = cube.derived<int>(make);
  EXPECT_EQ(*copy.derived<int>(make), 1);
  EXPECT_EQ(copy.derived<int>(make), first);
  EXPECT_EQ(made, 1);
  // Another type is another slot; another body has its own.
  EXPECT_EQ(*cube.derived<double>([] { return 2.5; }), 2.5);
  EXPECT_EQ(*ConvexPolyhedron(unit_cube()).derived<int>(make), 2);
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

}  // namespace
}  // namespace swarmcollide
