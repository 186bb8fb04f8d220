#include "fcl_shape.hpp"

#include <fcl/geometry/shape/cone.h>
#include <fcl/geometry/shape/convex.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/ellipsoid.h>

#include <memory>
#include <vector>

#include "../geometry/normalise.hpp"

namespace swarmcollide::detail {

namespace {

// What ConvexPolyhedron::derived keeps.
struct FclShape {
  std::shared_ptr<const fcl::ShapeBased> shape;
};

// A curved body as FCL's own primitive. FCL's cylinder and cone run along z, centred as ours
// (the cone's base at -lz/2, its apex at +lz/2), with length lz = 2 half_length. Their boxes, and
// the ellipsoid's, are centred on their origins, so the body's box-centred frame is the shape's.
std::shared_ptr<const fcl::ShapeBased> make_primitive(const SupportFunction& curved,
                                                      int exponent) {
  const CurvedShapeParameters shape = curved.parameters();
  const auto scaled = [exponent](Scalar length) { return times_power_of_two(length, -exponent); };
  switch (shape.kind) {
    case CurvedShapeParameters::Kind::cylinder:
      return std::make_shared<const fcl::Cylinderd>(scaled(shape.radius),
                                                    scaled(2 * shape.half_length));
    case CurvedShapeParameters::Kind::cone:
      return std::make_shared<const fcl::Coned>(scaled(shape.radius),
                                                scaled(2 * shape.half_length));
    case CurvedShapeParameters::Kind::ellipsoid:
      return std::make_shared<const fcl::Ellipsoidd>(
          scaled(shape.radii.x()), scaled(shape.radii.y()), scaled(shape.radii.z()));
  }
  return nullptr;
}

// A polyhedron's hull points (a rounded body's core: a sphere's one point, a capsule's segment)
// as an fcl::Convexd. FCL's own sphere and capsule supports are their cores' plus the radius
// along the direction, so its GJK on the cores walks as on those primitives, and answers the
// cores to double precision where the primitives' curved surfaces would stop it at its tolerance.
std::shared_ptr<const fcl::ShapeBased> make_convex(const FramedBody& framed) {
  const Hull& hull = framed.hull();
  auto vertices = std::make_shared<std::vector<fcl::Vector3d>>();
  vertices->reserve(hull.vertex_indices.size());
  for (int i : hull.vertex_indices) {
    fcl::Vector3d p;
    for (int k = 0; k < 3; ++k) {
      p(k) = times_power_of_two(framed.local_points()(i, k), -framed.exponent());
    }
    vertices->push_back(p);
  }
  // No faces: GJK_indep's supports (fcl::detail::MinkowskiDiff) scan the vertices whatever the
  // size, never walking the faces, which would only cost the constructor an adjacency build.
  return std::make_shared<const fcl::Convexd>(vertices, 0, std::make_shared<std::vector<int>>());
}

FclShape make_shape(const FramedBody& framed) {
  if (const SupportFunction* curved = framed.body().curved()) {
    return {make_primitive(*curved, framed.exponent())};
  }
  return {make_convex(framed)};
}

}  // namespace

const fcl::ShapeBased& fcl_shape(const FramedBody& body) {
  // Found without a lock or a reference count once made.
  return *body.body()
              .derived<FclShape>([&body] { return make_shape(body); }, body.exponent())
              .shape;
}

}  // namespace swarmcollide::detail
