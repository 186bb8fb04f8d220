// Depths proven on a cylinder's side (solvers/cylinder_side.hpp): many overlapping pairs where
// the side holds the deepest point are proven by its section, and every depth claimed, the
// side's or the expanding polytope's, lies within the best separation a search of directions
// finds and the separation along the answer's own normal.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "geometry/framed_body.hpp"
#include "separation_search.hpp"
#include "shapes.hpp"
#include "solvers/minkowski.hpp"
#include "swarmcollide/geometry/shapes.hpp"

namespace swarmcollide::testing {
namespace {

// A cylinder against another cylinder, a cone, an ellipsoid and a box, the sizes and places as
// bench/curved_coal.py draws them, at the default tolerance and at 1e-12. Every depth claimed
// is below the bound a search of directions finds, and within the separation along the normal
// (with the slope of the side's bound out of the plane left unchecked, 6 of 3,000 such pairs
// had a depth claimed beyond that separation, lower above upper). At 1e-12 the expanding
// polytope leaves a few pairs unproven (3 of 3,000 here, 4 before the side's proof) and its
// witnesses off the normal on some (70; 220 before); the side's proofs hold at both.
TEST(CylinderSide, OverlapsOnASideAreProvenAndBracketTheDepth) {
  for (const Scalar tolerance : {1e-9, 1e-12}) {
    SCOPED_TRACE(::testing::Message() << "tolerance " << tolerance);
    const bool coarse = tolerance == 1e-9;
    Random rng(64);
    Random search(65);
    int pairs = 0;
    int sides = 0;
    int sides_off_normal = 0;
    for (int trial = 0; trial < 2000; ++trial) {
      const Cylinder a(rng.uniform(0.2, 1), rng.uniform(0.2, 1));
      const Scalar r = rng.uniform(0.2, 1);
      const Scalar h = rng.uniform(0.2, 1);
      const Cylinder cylinder(r, h);
      const Cone cone(r, h);
      const Ellipsoid ellipsoid(Vector3(r, h, rng.uniform(0.2, 1)));
      const Box box(Vector3(r, h, rng.uniform(0.2, 1)));
      const ConvexPolyhedron* kinds[] = {&cylinder, &cone, &ellipsoid, &box};
      const ConvexPolyhedron& b = *kinds[trial % 4];
      const bool swapped = trial % 8 >= 4;
      const Pose pa = at(rng.vector(0.2), rng.rotation());
      const Pose pb = at(rng.vector(0.8), rng.rotation());
      const detail::FramedPair pair = swapped ? detail::frame_pair(b, pb, a, pa, tolerance)
                                              : detail::frame_pair(a, pa, b, pb, tolerance);
      const detail::PenetrationBounds found = solve_penetration(pair);
      if (!(found.upper < 0)) continue;  // apart or touching
      ++pairs;
      SCOPED_TRACE(::testing::Message()
                   << "trial " << trial << " proof " << static_cast<int>(found.proof));
      EXPECT_LE(found.lower, found.upper);
      EXPECT_LE(best_separation_near(pair, found.normal, 0.3, 1e-8, search), found.upper + 1e-13);
      const bool side = found.proof == detail::PenetrationProof::cylinder_side;
      sides += side;
      if (side || coarse) {
        EXPECT_TRUE(found.proven);
        EXPECT_LE(found.upper - found.lower, pair.tolerance);
      }
      if (coarse) {
        EXPECT_TRUE(found.witnesses_along_normal);
      } else if (side && !found.witnesses_along_normal) {
        ++sides_off_normal;  // a box's face along the normal, say: Wolfe's search on features
      }
      if (found.witnesses_along_normal) {
        // At the separation along the normal to their residual, which is within the gap of the
        // upper bound.
        EXPECT_LE((found.point_b - found.point_a - found.upper * found.normal).norm(),
                  found.upper - found.lower + found.witness_residual + 1e-13);
      }
    }
    EXPECT_GT(pairs, 1500);
    // A side holds the deepest point of many pairs (a rim against a side, two sides, a box's
    // edge or an ellipsoid against a side): 1,120 of 2,704 in 3,000 trials drawn so.
    EXPECT_GT(sides, pairs / 3) << sides << " of " << pairs;
    EXPECT_LE(sides_off_normal, sides / 50) << sides_off_normal << " of " << sides;
  }
}

}  // namespace
}  // namespace swarmcollide::testing
