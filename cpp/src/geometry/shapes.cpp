#include "swarmcollide/geometry/shapes.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <sstream>
#include <stdexcept>

#include "curved_supports.hpp"
#include "normalise.hpp"

namespace swarmcollide {

namespace {

Scalar positive(Scalar value, const char* name) {
  if (!(value > 0) || !std::isfinite(value)) {
    std::ostringstream message;
    message << name << " must be a finite number > 0, got " << value;
    throw std::invalid_argument(message.str());
  }
  return value;
}

VertexMatrix one_point() { return VertexMatrix::Zero(1, 3); }

VertexMatrix segment_along_z(Scalar half_length) {
  VertexMatrix ends = VertexMatrix::Zero(2, 3);
  ends(0, 2) = -positive(half_length, "half_length");
  ends(1, 2) = half_length;
  return ends;
}

VertexMatrix corners(const Vector3& half_extents) {
  static const char* const kNames[3] = {"half_extents[0]", "half_extents[1]", "half_extents[2]"};
  for (int k = 0; k < 3; ++k) positive(half_extents(k), kNames[k]);
  VertexMatrix points(8, 3);
  for (int i = 0; i < 8; ++i) {
    for (int k = 0; k < 3; ++k) points(i, k) = (i >> k) & 1 ? half_extents(k) : -half_extents(k);
  }
  return points;
}

// Points on a shape's surface whose box is the shape's: its inner polytope.
VertexMatrix rims(Scalar radius, Scalar bottom, Scalar top, bool apex) {
  VertexMatrix points(apex ? 5 : 8, 3);
  int row = 0;
  for (Scalar z : {bottom, top}) {
    if (apex && z == top) break;
    points.row(row++) << radius, 0, z;
    points.row(row++) << -radius, 0, z;
    points.row(row++) << 0, radius, z;
    points.row(row++) << 0, -radius, z;
  }
  if (apex) points.row(row) << 0, 0, top;
  return points;
}

VertexMatrix cylinder_points(Scalar radius, Scalar half_length) {
  positive(radius, "radius");
  positive(half_length, "half_length");
  return rims(radius, -half_length, half_length, false);
}

VertexMatrix cone_points(Scalar radius, Scalar half_length) {
  positive(radius, "radius");
  positive(half_length, "half_length");
  return rims(radius, -half_length, half_length, true);
}

VertexMatrix axis_points(const Vector3& radii) {
  static const char* const kNames[3] = {"radii[0]", "radii[1]", "radii[2]"};
  VertexMatrix points = VertexMatrix::Zero(6, 3);
  for (int k = 0; k < 3; ++k) {
    points(2 * k, k) = positive(radii(k), kNames[k]);
    points(2 * k + 1, k) = -radii(k);
  }
  return points;
}

}  // namespace

Sphere::Sphere(Scalar radius) : ConvexPolyhedron(one_point(), positive(radius, "radius")) {}

Capsule::Capsule(Scalar radius, Scalar half_length)
    : ConvexPolyhedron(segment_along_z(half_length), positive(radius, "radius")),
      half_length_(half_length) {}

Box::Box(const Vector3& half_extents, Scalar radius)
    : ConvexPolyhedron(corners(half_extents), radius), half_extents_(half_extents) {}

Cylinder::Cylinder(Scalar radius, Scalar half_length)
    : ConvexPolyhedron(cylinder_points(radius, half_length), 0,
                       std::make_shared<const detail::CylinderSupport>(radius, half_length)),
      cylinder_radius_(radius),
      half_length_(half_length) {}

Cone::Cone(Scalar radius, Scalar half_length)
    : ConvexPolyhedron(cone_points(radius, half_length), 0,
                       std::make_shared<const detail::ConeSupport>(radius, half_length)),
      base_radius_(radius),
      half_length_(half_length) {}

Ellipsoid::Ellipsoid(const Vector3& radii)
    : ConvexPolyhedron(axis_points(radii), 0, std::make_shared<const detail::EllipsoidSupport>(radii)),
      radii_(radii) {}

}  // namespace swarmcollide
