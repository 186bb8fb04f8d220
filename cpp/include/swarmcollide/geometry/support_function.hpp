#pragma once

#include "swarmcollide/geometry/pose.hpp"
#include "swarmcollide/types.hpp"

namespace swarmcollide {

/// What a curved shape is, in its own frame (shapes.hpp gives each kind's conventions): for the
/// adapters to libraries that have it as a primitive (FCL), and for drawing and saving it.
struct CurvedShapeParameters {
  enum class Kind { cylinder, cone, ellipsoid };
  Kind kind = Kind::cylinder;
  /// A cylinder's or a cone's base radius (0 for an ellipsoid).
  Scalar radius = 0;
  /// Half a cylinder's or a cone's length along z (0 for an ellipsoid).
  Scalar half_length = 0;
  /// An ellipsoid's semi-axes along x, y and z (zero for the others).
  Vector3 radii = Vector3::Zero();
  /// Where the shape sits in its body's frame (a compound body's part placed by a pose,
  /// placed_shape.hpp): its points `x` are at `pose.rotation * x + pose.translation`; the
  /// identity for a shape in its own frame.
  Pose pose;
  /// True when `pose` is not the identity.
  bool placed = false;
};

/// A curved convex shape given by its support function, in its own frame (centred on its box):
/// the one thing the support-function solvers ("dual", "exact") ask of a shape. Cylinder, Cone
/// and Ellipsoid (shapes.hpp) implement it; a ConvexPolyhedron built from one answers its
/// support points from it (ConvexPolyhedron::curved).
///
/// The contract every implementation keeps, which the certificates rest on: `support(d)` is a
/// point of the shape (inside or on it, rounding included: the computed point is pulled towards
/// the centre by a few roundoffs), and `d . support(d)` falls below the shape's support value
/// `max_x d . x` by at most `support_error_roundoffs()` roundoffs (2^-53) of `outer_radius() |d|`.
class SupportFunction {
 public:
  /// Roundoffs of `outer_radius() |d|` by which `d . support(d)` may fall short of the support
  /// value, for the shapes of shapes.hpp.
  static constexpr double kSupportErrorRoundoffs = 32;

  virtual ~SupportFunction() = default;
  /// Roundoffs of `outer_radius() |d|` by which this shape's `d . support(d)` may fall short of
  /// its support value: `kSupportErrorRoundoffs`, more for a shape placed by a pose.
  virtual Scalar support_error_roundoffs() const { return kSupportErrorRoundoffs; }
  /// A point of the shape farthest along `direction` (to within the bound above), in the shape's
  /// own frame. A direction along which a whole face or segment is farthest gets its centre (a
  /// cylinder's cap along +-z gets the cap's centre); the zero direction gets the origin.
  virtual Vector3 support(const Vector3& direction) const = 0;
  /// A bound on the distance of every point of the shape from the origin (its centre).
  virtual Scalar outer_radius() const = 0;
  /// The centre of mass of the solid.
  virtual Vector3 centroid() const = 0;
  /// A lower bound on how deep `point` (in the shape's own frame) lies inside the shape: the
  /// radius of a ball about it that the shape holds (rounding included; <= 0 outside or near
  /// the surface), and in `outward` a unit direction towards the nearest part of the surface.
  /// From the shape's closed form, for the depth proofs that a direction search cannot give
  /// (a point on a cylinder's axis is deepest along a whole circle of directions).
  virtual Scalar depth_of(const Vector3& point, Vector3& outward) const = 0;
  /// A radius r of a ball that rolls inside the shape: for every nonzero direction d, the ball of
  /// radius r about `s - r d / |d|` lies in the shape, s the exact support point along d, and the
  /// computed `support(d)` lies within `support_error_roundoffs()` roundoffs of `outer_radius()`
  /// of s (so the ball of radius r less that about `support(d) - r d / |d|` lies in the shape).
  /// Strictly convex smooth shapes have one (an ellipsoid's least radius of curvature); 0, the
  /// default, promises nothing. The depth proofs of curved pairs read it (rolling_ball.hpp).
  virtual Scalar rolling_radius() const { return 0; }
  /// The shape's name ("cylinder", ...), for messages.
  virtual const char* name() const = 0;
  /// The shape's kind and dimensions.
  virtual CurvedShapeParameters parameters() const = 0;
};

}  // namespace swarmcollide
