#include "swarmcollide/solvers/libccd_penetration.hpp"

#include <ccd/ccd.h>

#include "exact_internal.hpp"

namespace swarmcollide {

namespace {

// What libccd's callbacks receive: the body and the shift that brings the pair near the origin.
struct CcdShape {
  const ConvexPolyhedron* body;
  Vector3 origin;
};

void to_ccd(const Vector3& v, ccd_vec3_t* out) {
  for (int k = 0; k < 3; ++k) out->v[k] = v(k);
}

void support(const void* object, const ccd_vec3_t* direction, ccd_vec3_t* out) {
  const auto* shape = static_cast<const CcdShape*>(object);
  const Vector3 d(direction->v[0], direction->v[1], direction->v[2]);
  to_ccd(shape->body->support(d) - shape->origin, out);
}

void centre(const void* object, ccd_vec3_t* out) {
  const auto* shape = static_cast<const CcdShape*>(object);
  to_ccd(shape->body->vertices().colwise().mean().transpose() - shape->origin, out);
}

struct CcdPair {
  CcdShape a;
  CcdShape b;
  ccd_t ccd;
};

CcdPair make_pair(const ConvexPolyhedron& a, const ConvexPolyhedron& b,
                  const ExactOptions& options) {
  const Aabb box = a.aabb();
  const Vector3 origin = (box.min + box.max) / 2;
  CcdPair pair{{&a, origin}, {&b, origin}, {}};
  CCD_INIT(&pair.ccd);
  pair.ccd.support1 = support;
  pair.ccd.support2 = support;
  pair.ccd.center1 = centre;
  pair.ccd.center2 = centre;
  pair.ccd.max_iterations = static_cast<unsigned long>(options.max_iterations);
  pair.ccd.epa_tolerance = options.penetration_tolerance;
  pair.ccd.mpr_tolerance = options.penetration_tolerance;
  return pair;
}

}  // namespace

bool libccd_intersect(const ConvexPolyhedron& a, const ConvexPolyhedron& b,
                      const ExactOptions& options) {
  options.validate();
  const CcdPair pair = make_pair(a, b, options);
  if (ccdGJKIntersect(&pair.a, &pair.b, &pair.ccd)) return true;
  return exact_internal::nearest_points(a, b, options, "libccd").colliding;
}

DistanceResult libccd_signed_distance(const ConvexPolyhedron& a, const ConvexPolyhedron& b,
                                      const ExactOptions& options) {
  options.validate();
  DistanceResult apart = exact_internal::nearest_points(a, b, options, "libccd");
  if (!apart.colliding) return apart;
  const CcdPair pair = make_pair(a, b, options);
  ccd_real_t depth = 0;
  ccd_vec3_t direction;
  ccd_vec3_t position;
  const int status =
      options.penetration == PenetrationAlgorithm::epa
          ? ccdGJKPenetration(&pair.a, &pair.b, &pair.ccd, &depth, &direction, &position)
          : ccdMPRPenetration(&pair.a, &pair.b, &pair.ccd, &depth, &direction, &position);
  // libccd: translating B by depth * direction brings the bodies into touching contact. Its
  // contact position is not needed: the witnesses follow from the normal.
  const Vector3 normal(direction.v[0], direction.v[1], direction.v[2]);
  if (status != 0 || !(depth > 0) || !(normal.norm() > 0) || !normal.allFinite()) return apart;
  return exact_internal::penetration_result(a, b, normal, depth, "libccd", options.tolerance);
}

}  // namespace swarmcollide
