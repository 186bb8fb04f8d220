#include "swarmcollide/geometry/shapes.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

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

}  // namespace

Sphere::Sphere(Scalar radius) : ConvexPolyhedron(one_point(), positive(radius, "radius")) {}

Capsule::Capsule(Scalar radius, Scalar half_length)
    : ConvexPolyhedron(segment_along_z(half_length), positive(radius, "radius")),
      half_length_(half_length) {}

Box::Box(const Vector3& half_extents, Scalar radius)
    : ConvexPolyhedron(corners(half_extents), radius), half_extents_(half_extents) {}

}  // namespace swarmcollide
