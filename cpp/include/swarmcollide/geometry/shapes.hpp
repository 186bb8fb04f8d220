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

/// A solid circular cylinder along z, centred: radius `cylinder_radius()`, from z = -half_length
/// to z = half_length (FCL's and coal's convention). URDF's `<cylinder radius length>` has
/// length = 2 half_length; MJCF's cylinder geom has size = (radius, half_length). A curved shape:
/// answered from its support function (ConvexPolyhedron::curved) by the methods "dual" and
/// "exact".
class Cylinder : public ConvexPolyhedron {
 public:
  /// Throws std::invalid_argument unless `radius` and `half_length` are finite and positive.
  Cylinder(Scalar radius, Scalar half_length);
  /// The radius of the cylinder's circular section (`radius()` is the rounding radius, 0).
  Scalar cylinder_radius() const { return cylinder_radius_; }
  Scalar half_length() const { return half_length_; }

 private:
  Scalar cylinder_radius_;
  Scalar half_length_;
};

/// A solid right circular cone along z, centred on its axis' midpoint (FCL's and coal's
/// convention): its base, a disk of radius `base_radius()`, at z = -half_length, its apex at
/// (0, 0, half_length). Its centre of mass is at z = -half_length / 2. A curved shape, answered
/// by the methods "dual" and "exact".
class Cone : public ConvexPolyhedron {
 public:
  /// Throws std::invalid_argument unless `radius` and `half_length` are finite and positive.
  Cone(Scalar radius, Scalar half_length);
  /// The radius of the base disk.
  Scalar base_radius() const { return base_radius_; }
  Scalar half_length() const { return half_length_; }

 private:
  Scalar base_radius_;
  Scalar half_length_;
};

/// A solid ellipsoid centred on the origin with semi-axes `radii()` along x, y and z: the points
/// with (x/a)^2 + (y/b)^2 + (z/c)^2 <= 1. MJCF's ellipsoid geom has size = radii. A curved shape,
/// answered by the methods "dual" and "exact".
class Ellipsoid : public ConvexPolyhedron {
 public:
  /// Throws std::invalid_argument unless every radius is finite and positive.
  explicit Ellipsoid(const Vector3& radii);
  const Vector3& radii() const { return radii_; }

 private:
  Vector3 radii_;
};

}  // namespace swarmcollide
