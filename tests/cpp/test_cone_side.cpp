// Depths proven on a cone's side (solvers/cone_side.hpp): many overlapping pairs where the side
// holds the deepest point are proven by its section, and no depth claimed goes beyond the best
// separation a search of directions finds.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <initializer_list>

#include "geometry/framed_body.hpp"
#include "separation_search.hpp"
#include "shapes.hpp"
#include "solvers/minkowski.hpp"
#include "swarmcollide/geometry/shapes.hpp"

namespace swarmcollide::testing {
namespace {

constexpr Scalar kHalfPi = 1.5707963267948966;

// A cone against another cone, a cylinder and an ellipsoid, the sizes and places as
// bench/curved_coal.py draws them, the cone first or second, at the default tolerance and at
// 1e-12. Every depth claimed is below the bound a search of directions finds near the answer's
// normal; a depth the side claims, below the one it finds from the best of random directions
// too (a wedge wider than its bound holds in would claim a depth beyond the true one there).
// Every answer at the default tolerance is proven.
TEST(ConeSide, OverlapsOnASideAreProvenAndBracketTheDepth) {
  for (const Scalar tolerance : {1e-9, 1e-12}) {
    SCOPED_TRACE(::testing::Message() << "tolerance " << tolerance);
    const bool coarse = tolerance == 1e-9;
    Random rng(66);
    Random search(67);
    int pairs = 0;
    int sides = 0;
    int unproven = 0;
    for (int trial = 0; trial < 1500; ++trial) {
      const Cone a(rng.uniform(0.2, 1), rng.uniform(0.2, 1));
      const Scalar r = rng.uniform(0.2, 1);
      const Scalar h = rng.uniform(0.2, 1);
      const Cone cone(r, h);
      const Cylinder cylinder(r, h);
      const Ellipsoid ellipsoid(Vector3(r, h, rng.uniform(0.2, 1)));
      const ConvexPolyhedron* kinds[] = {&cone, &cylinder, &ellipsoid};
      const ConvexPolyhedron& b = *kinds[trial % 3];
      const bool swapped = trial % 6 >= 3;
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
      const bool side = found.proof == detail::PenetrationProof::cone_side;
      sides += side;
      if (coarse) {
        EXPECT_TRUE(found.proven);
        EXPECT_LE(found.upper - found.lower, pair.tolerance);
      } else {
        unproven += !found.proven || !(found.upper - found.lower <= pair.tolerance);
      }
      if (side) {
        EXPECT_TRUE(found.witnesses_along_normal || !coarse);
        // Nor anywhere else: the best of 200 random directions, searched from as above.
        Vector3 start = found.normal;
        Scalar best = detail::exact_separation(pair.a, pair.b, start);
        for (int k = 0; k < 200; ++k) {
          const Vector3 n = search.unit();
          const Scalar s = detail::exact_separation(pair.a, pair.b, n);
          if (s > best) {
            best = s;
            start = n;
          }
        }
        EXPECT_LE(best_separation_near(pair, start, 0.3, 1e-8, search), found.upper + 1e-13);
      }
      if (found.witnesses_along_normal) {
        EXPECT_LE((found.point_b - found.point_a - found.upper * found.normal).norm(),
                  found.upper - found.lower + found.witness_residual + 1e-13);
      }
    }
    EXPECT_GT(pairs, 1000);
    // At 1e-12, rounding's floor: the expanding polytope alone left 4 pairs here unproven, with
    // the side's proof 2 (one a side's, its gap 9.3e-12 narrowed to 5.3e-12).
    EXPECT_LE(unproven, 3);
    // A cone's side holds the deepest point of about half the overlapping pairs (a rim, an
    // ellipsoid or another side against it), most of which its chain proves.
    EXPECT_GT(sides, pairs / 5) << sides << " of " << pairs;
  }
}

// Of the answers expect_no_claim_beyond checked: those the cone's side proved, and those proven
// to the tolerance (by any proof).
struct Proofs {
  int sides = 0;
  int proven = 0;
};

// The pair of `cone` and `small` (in that order, or turned over where `swapped`), at the
// default tolerance: overlapping, and no depth claimed beyond the separation along any of the
// cone's outward `normals` (in the world; the opposite ones where the cone is B); `proofs`
// counts the answer.
void expect_no_claim_beyond(const Cone& cone, const Pose& pose_cone, const Cylinder& small,
                            const Pose& pose_small, bool swapped,
                            std::initializer_list<Vector3> normals, Proofs& proofs) {
  const detail::FramedPair pair =
      swapped ? detail::frame_pair(small, pose_small, cone, pose_cone, 1e-9)
              : detail::frame_pair(cone, pose_cone, small, pose_small, 1e-9);
  const detail::PenetrationBounds found = solve_penetration(pair);
  SCOPED_TRACE(::testing::Message() << "proof " << static_cast<int>(found.proof));
  ASSERT_LT(found.upper, 0);
  proofs.sides += found.proof == detail::PenetrationProof::cone_side;
  proofs.proven += found.proven;
  const Scalar toward = swapped ? -1 : 1;
  for (const Vector3& normal : normals) {
    EXPECT_LE(detail::exact_separation(pair.a, pair.b, toward * normal), found.upper + 1e-13);
  }
}

// A small cylinder inside a cone near its rim, almost as deep below the side as below the base:
// the expansion to 2^-12 cannot tell which is the deeper, and where its best normal is the
// side's while the base is nearer by up to 1e-6, the side's chain would claim the side's depth.
// The polytope's faces across the base are nearer than that and outside the side's wedge, so
// the chain's bound is refused there: no depth claimed lies beyond the separation along the
// base's normal or the side's.
TEST(ConeSide, ANearerBaseRefusesTheSidesBound) {
  const Scalar r = 0.5;
  const Scalar h = 0.5;
  const Cone cone(r, h);
  const Vector3 side_normal = Vector3(2 * h, 0, r).normalized();
  const Scalar side_plane = side_normal.dot(Vector3(0, 0, h));
  const Scalar radius = 0.04;
  const Scalar half_length = 0.03;
  const Cylinder small(radius, half_length);
  Random rng(68);
  Proofs proofs;
  for (int trial = 0; trial < 400; ++trial) {
    const Matrix3 turn = rng.rotation();
    const Matrix3 turn_small = rng.rotation();  // in the cone's axes
    const Vector3 axis = turn_small.col(2);
    const auto support = [&](const Vector3& d) {  // the small cylinder's, about its centre
      const Scalar along = axis.dot(d);
      return half_length * std::abs(along) + radius * std::sqrt(std::max(0.0, 1 - along * along));
    };
    // The centre 0.1 above the base, where the support of A - B along the side's normal exceeds
    // the one along the base's by `gap` (a positive gap: the base is the nearer).
    const Scalar gap = (trial % 2 == 0 ? 1 : -1) * 1e-7 * (1 + trial / 2 % 10);
    const Scalar z = -h + 0.1;
    const Scalar base_depth = h + z + support(Vector3::UnitZ());
    const Scalar x = (side_plane - side_normal.z() * z + support(-side_normal) - base_depth - gap) /
                     side_normal.x();
    const Vector3 shift = rng.vector(0.2);
    const Pose pose_cone = at(shift, turn);
    const Pose pose_small = at(shift + turn * Vector3(x, 0, z), turn * turn_small);
    SCOPED_TRACE(::testing::Message() << "trial " << trial << " gap " << gap);
    // The base's and the side's normals.
    expect_no_claim_beyond(cone, pose_cone, small, pose_small, trial % 4 >= 2,
                           {Vector3(turn * -Vector3::UnitZ()), Vector3(turn * side_normal)},
                           proofs);
  }
  // The side's proof still proves pairs whose side is the nearer.
  EXPECT_GT(proofs.sides, 0);
}

// A small cylinder on one of a cone's points (`point`: the apex or a rim point at azimuth 0), the
// point just inside its cap, its axis at `elevation` (rad) in the plane of azimuth 0: the point's
// contact, along the cap's normal, is a tolerance-sized step from being as deep as the side's.
// Where that normal lies above the elevations the side's wedge reaches (the apex's), or below
// them (a rim point's), only the wedge's upper or lower limit keeps the faces about it out: no
// depth claimed lies beyond the separation along the cap's normal or the side's. 400 poses drawn
// from `seed`; returns how they were proven.
Proofs expect_point_contact_refused(const Vector3& point, Scalar elevation, std::uint64_t seed) {
  const Scalar r = 0.5;
  const Scalar h = 0.5;
  const Cone cone(r, h);
  const Vector3 side_normal = Vector3(2 * h, 0, r).normalized();
  const Scalar radius = 0.04;
  const Scalar half_length = 0.03;
  const Cylinder small(radius, half_length);
  const Vector3 axis(std::cos(elevation), 0, std::sin(elevation));
  // Turns z onto the axis, about y.
  const Matrix3 onto_axis =
      Eigen::AngleAxis<Scalar>(kHalfPi - elevation, Vector3::UnitY()).toRotationMatrix();
  const Vector3 across(-std::sin(elevation), 0, std::cos(elevation));
  const Scalar along = axis.dot(side_normal);
  const Scalar small_support =  // the small cylinder's along -side_normal, about its centre
      half_length * std::abs(along) + radius * std::sqrt(1 - along * along);
  Random rng(seed);
  Proofs proofs;
  for (int trial = 0; trial < 400; ++trial) {
    // The point 0.01 below the cap: the support of A - B along the axis is 2 half-lengths less
    // that; the centre moved across the axis until the side's support exceeds it by `gap`.
    const Scalar gap = (trial % 2 == 0 ? 1 : -1) * 1e-7 * (1 + trial / 2 % 10);
    const Vector3 start = point - (half_length - 0.01) * axis;
    const Scalar point_depth = 2 * half_length - 0.01;
    const Scalar side_depth = side_normal.dot(point - start) + small_support;
    const Vector3 centre =
        start + (side_depth - point_depth - gap) / side_normal.dot(across) * across;
    const Matrix3 turn = rng.rotation();
    const Vector3 shift = rng.vector(0.2);
    const Pose pose_cone = at(shift, turn);
    const Pose pose_small = at(shift + turn * centre, turn * onto_axis);
    SCOPED_TRACE(::testing::Message() << "trial " << trial << " gap " << gap);
    // The cap's and the side's normals.
    expect_no_claim_beyond(cone, pose_cone, small, pose_small, trial % 4 >= 2,
                           {Vector3(turn * axis), Vector3(turn * side_normal)}, proofs);
  }
  return proofs;
}

// Over the apex, the cap's normal at 1 rad, above the side's (0.46): the wedge's upper limit.
// The side's proof still proves pairs whose side is the nearer.
TEST(ConeSide, ANearerApexRefusesTheSidesBound) {
  const Proofs proofs = expect_point_contact_refused(Vector3(0, 0, 0.5), 1.0, 69);
  EXPECT_GT(proofs.sides, 0);
}

// On the rim, the cap's normal at -0.2 rad, between the base's and the side's: the wedge's lower
// limit (without it, 183 of the 400 answers claim a depth beyond the separation along the cap's
// normal). The cap's edge point is the small cylinder's support both along the side's normal and
// along the cap's, so the wedge's lower limit lies at the cap's normal (to within the step): the
// faces about it straddle it, and the other proofs prove every pair.
TEST(ConeSide, ANearerRimRefusesTheSidesBound) {
  const Proofs proofs = expect_point_contact_refused(Vector3(0.5, 0, -0.5), -0.2, 70);
  EXPECT_EQ(proofs.proven, 400);
}

}  // namespace
}  // namespace swarmcollide::testing
