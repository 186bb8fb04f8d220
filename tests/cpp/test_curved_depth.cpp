// Depths that the expanding polytope cannot prove: a point (or a segment) on a cylinder's or a
// cone's axis, or on the axis of an ellipsoid with two equal radii, is deepest along a whole
// circle of directions, as are two bodies of revolution on one axis. The closed form of the
// shape's interior proves them (curved_depth.hpp), or the meridian sections (meridian_depth.hpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "geometry/curved_depth.hpp"
#include "geometry/framed_body.hpp"
#include "shapes.hpp"
#include "swarmcollide/geometry/shapes.hpp"
#include "swarmcollide/queries/methods.hpp"
#include "swarmcollide/queries/query.hpp"

namespace swarmcollide::testing {
namespace {

Query query_of(Method method, Scalar tolerance) {
  QueryOptions options;
  options.method = method;
  options.tolerance = tolerance;
  return Query(options);
}

// A point, at `local` in the shape's frame, with its depth there; the shape turned anyhow.
struct Case {
  ConvexPolyhedron shape;
  ConvexPolyhedron inner;
  Vector3 local;
  Scalar depth;
};

// The depth of (0, 0, z) on the long axis of the ellipsoid (a, a, c), c > a, near its centre
// (|z| < c - a^2 / c): its nearest points lie on a circle, at sin t = c z / (c^2 - a^2) of the
// meridian ellipse (a cos t, c sin t).
Scalar prolate_axis_depth(Scalar a, Scalar c, Scalar z) {
  const Scalar s = c * z / (c * c - a * a);
  return std::hypot(a * std::sqrt(1 - s * s), c * s - z);
}

std::vector<Case> cases() {
  const ConvexPolyhedron point = point_set({Vector3::Zero()});
  const ConvexPolyhedron segment = point_set({Vector3(0, 0, -0.3), Vector3(0, 0, 0.3)});
  return {
      {Cylinder(0.5, 2), point, Vector3::Zero(), 0.5},           // the centre
      {Cylinder(0.5, 2), point, Vector3(0, 0, 1.2), 0.5},        // on the axis
      {Cylinder(0.5, 2), segment, Vector3(0, 0, 0.4), 0.5},      // a segment along it
      {Cylinder(0.5, 2), Sphere(0.2), Vector3::Zero(), 0.7},     // a ball: its core, plus 0.2
      // On a cone's axis the side is nearest: r (h - z) / |(r, 2h)| (base radius 1, h = 1.5).
      {Cone(1, 1.5), point, Vector3(0, 0, 0), 1 * 1.5 / std::hypot(1.0, 3.0)},
      {Cone(1, 1.5), point, Vector3(0, 0, -1), 0.5},             // the base is nearer
      {Ellipsoid(Vector3(0.6, 0.6, 1.5)), point, Vector3::Zero(), 0.6},
      {Ellipsoid(Vector3(0.6, 0.6, 1.5)), Sphere(0.1), Vector3::Zero(), 0.7},
      // Two bodies on one axis, and a point off an ellipsoid's centre, where no closed form of
      // the shape alone holds: the meridian sections' polygon (meridian_depth.hpp).
      {Cylinder(0.5, 2), Cone(0.2, 0.5), Vector3(0, 0, 0.4), 0.7},  // a cone in a bore
      {Ellipsoid(Vector3(0.6, 0.6, 1.5)), point, Vector3(0, 0, 0.3),
       prolate_axis_depth(0.6, 1.5, 0.3)},
      {Ellipsoid(Vector3(0.6, 0.6, 1.5)), Sphere(0.1), Vector3(0, 0, -0.5),
       prolate_axis_depth(0.6, 1.5, -0.5) + 0.1},
  };
}

TEST(CurvedDepth, PointsOnAnAxisOfSymmetryGetCertifiedDepths) {
  Random rng(17);
  for (Scalar tolerance : {1e-12}) {
    for (Method method : {Method::dual, Method::exact, Method::libccd}) {
      SCOPED_TRACE(method_name(method));
      const Query query = query_of(method, tolerance);
      int index = 0;
      for (const Case& c : cases()) {
        SCOPED_TRACE(index++);
        for (int trial = 0; trial < 3; ++trial) {
          const Pose pose_shape = trial == 0 ? Pose{} : at(rng.vector(3), rng.rotation());
          const Pose pose_inner = at(pose_shape.rotation * c.local + pose_shape.translation,
                                     pose_shape.rotation);
          const DistanceResult r = query.signed_distance(c.shape, pose_shape, c.inner, pose_inner);
          const Scalar size = size_of(c.shape, pose_shape, c.inner, pose_inner);
          EXPECT_TRUE(r.certified) << trial;
          EXPECT_LE(r.lower_bound, -c.depth + 1e-13 * size) << trial;
          EXPECT_NEAR(r.distance, -c.depth, tolerance * size + 1e-13 * size) << trial;
          EXPECT_TRUE(r.colliding);
          // The witnesses are the depth apart.
          EXPECT_NEAR((r.point_b - r.point_a).norm(), c.depth, tolerance * size + 1e-12 * size);
          // Either way round.
          const DistanceResult back = query.signed_distance(c.inner, pose_inner, c.shape, pose_shape);
          EXPECT_TRUE(back.certified) << trial;
          EXPECT_NEAR(back.distance, -c.depth, tolerance * size + 1e-13 * size) << trial;
        }
      }
    }
  }
}

TEST(CurvedDepth, TheClosedFormIsALowerBoundOnTheDepth) {
  // For random points in and around each shape, the bound is at most the point's true depth (a dense
  // scan of directions gives an upper bound on it: min over n of h(n) - n.p).
  Random rng(19);
  const std::vector<ConvexPolyhedron> shapes = {Cylinder(0.4, 0.9), Cone(0.7, 0.5),
                                                Ellipsoid(Vector3(0.3, 0.8, 0.5))};
  for (const ConvexPolyhedron& shape : shapes) {
    SCOPED_TRACE(shape.curved()->name());
    int inside = 0;
    for (int trial = 0; trial < 200; ++trial) {
      const Vector3 p = rng.vector(0.9);
      Vector3 outward;
      const Scalar bound = shape.curved()->depth_of(p, outward);
      EXPECT_NEAR(outward.norm(), 1, 1e-12);
      Scalar scanned = std::numeric_limits<Scalar>::infinity();
      for (int k = 0; k < 4000; ++k) {
        const Vector3 n = rng.unit();
        scanned = std::min(scanned, n.dot(shape.support(n)) - n.dot(p));
      }
      scanned = std::min(scanned, outward.dot(shape.support(outward)) - outward.dot(p));
      // A bound > 0 is a proof; outside the shape the bound claims nothing but must say so.
      EXPECT_LE(std::max(bound, Scalar(0)), std::max(scanned, Scalar(0)) + 1e-12) << p.transpose();
      inside += bound > 0;
    }
    EXPECT_GT(inside, 10);
  }
}

}  // namespace
}  // namespace swarmcollide::testing
