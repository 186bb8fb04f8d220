#pragma once

#include "swarmcollide/geometry/convex_polyhedron.hpp"
#include "swarmcollide/types.hpp"

namespace swarmcollide {

/// A ball of radius `radius()` about the origin: the rounded body of the one point (0, 0, 0).
/// URDF's `<sphere radius>` and MJCF's sphere geom (size = radius), centred on the body's frame.
class Sphere : public ConvexPolyhedron {
 public:
  /// Throws std::invalid_argument unless `radius` is finite and positive.
  explicit Sphere(Scalar radius);
};

/// A capsule along z, centred: the rounded body of the segment from (0, 0, -half_length) to
/// (0, 0, half_length) with radius `radius()`; its total length is 2 (half_length + radius).
/// MJCF's capsule geom (size = radius, half-length of the cylinder part), axis z, centred.
class Capsule : public ConvexPolyhedron {
 public:
  /// Throws std::invalid_argument unless `radius` and `half_length` are finite and positive.
  Capsule(Scalar radius, Scalar half_length);
  /// Half the length of the segment at the capsule's core.
  Scalar half_length() const { return half_length_; }

 private:
  Scalar half_length_;
};

/// An axis-aligned box centred on the origin, `2 half_extents` across: the hull of its 8 corners,
/// rounded by `radius` (0 for a sharp box; a rounded box then spans `half_extents + radius`).
/// URDF's `<box size>` is `2 half_extents`; MJCF's box geom size is `half_extents`.
class Box : public ConvexPolyhedron {
 public:
  /// Throws std::invalid_argument unless every half extent is finite and positive and `radius`
  /// finite and nonnegative.
  explicit Box(const Vector3& half_extents, Scalar radius = 0);
  const Vector3& half_extents() const { return half_extents_; }

 private:
  Vector3 half_extents_;
};

}  // namespace swarmcollide
