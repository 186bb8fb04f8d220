// The tests' own reference is checked on cases with answers worked out by hand before it judges.
#include <gtest/gtest.h>

#include <cmath>

#include "hard_cases.hpp"
#include "oracle.hpp"
#include "paper_cases.hpp"
#include "shapes.hpp"

namespace swarmcollide::testing {
namespace {

TEST(Oracle, PaperPairs) {
  const Reference touching = reference(paper_a(), paper_b_colliding());
  EXPECT_EQ(touching.distance, 0);
  EXPECT_NEAR(touching.signed_distance, 0, 1e-15);
  const Reference separate = reference(paper_a(), paper_b_separate());
  EXPECT_NEAR(separate.distance, 1, 1e-15);
  EXPECT_NEAR(separate.signed_distance, 1, 1e-15);
}

TEST(Oracle, HardCasesInBothOrders) {
  for (const HardCase& c : hard_cases()) {
    SCOPED_TRACE(c.name);
    for (const Reference& r : {reference(c.a, c.b), reference(c.b, c.a)}) {
      EXPECT_NEAR(r.distance, c.distance, c.accuracy);
      EXPECT_NEAR(r.signed_distance, c.signed_distance, c.accuracy);
    }
  }
}

TEST(Oracle, CubePairs) {
  const ConvexPolyhedron cube = unit_cube();
  struct Expected {
    Vector3 offset;
    Scalar distance;
    Scalar signed_distance;
  };
  for (const Expected& e : {Expected{{3, 0, 0}, 2, 2},                            // face to face
                            Expected{{2, 2, 0}, std::sqrt(2.0), std::sqrt(2.0)},  // edge to edge
                            Expected{{2, 2, 2}, std::sqrt(3.0), std::sqrt(3.0)},  // corners
                            Expected{{0.5, 0.5, 0.5}, 0, -0.5},
                            Expected{{0.25, 0.125, 0.9}, 0, -0.1}, Expected{{0, 0, 0}, 0, -1}}) {
    SCOPED_TRACE(e.offset.transpose());
    const Reference r = reference(cube, moved(cube, e.offset));
    EXPECT_NEAR(r.distance, e.distance, 1e-15);
    EXPECT_NEAR(r.signed_distance, e.signed_distance, 1e-15);
  }
}

TEST(Oracle, PointAboveATriangleInterior) {
  const ConvexPolyhedron triangle = point_set({{-1, -1, 0}, {2, -1, 0}, {-1, 2, 0}});
  const Reference r = reference(triangle, point_set({{0, 0, 0.75}}));
  EXPECT_NEAR(r.distance, 0.75, 1e-15);
  EXPECT_NEAR(r.signed_distance, 0.75, 1e-15);
}

TEST(Oracle, SeparationIsTheGapBetweenSupportingPlanes) {
  const VertexMatrix d = differences(paper_a(), paper_b_separate());
  EXPECT_EQ(d.rows(), 16);
  EXPECT_EQ(separation_along(d, Vector3(0, -1, 0)), 1);
  EXPECT_LT(separation_along(d, Vector3(0, 1, 0)), 0);
}

}  // namespace
}  // namespace swarmcollide::testing
