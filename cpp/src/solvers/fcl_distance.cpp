#include "swarmcollide/solvers/fcl_distance.hpp"

#include <fcl/narrowphase/distance.h>

#include <cmath>
#include <memory>
#include <vector>

#include "exact_internal.hpp"

namespace swarmcollide {

namespace {

std::string name_of(FclGjk gjk) { return gjk == FclGjk::libccd ? "fcl" : "fcl-indep"; }

// FCL's Convex finds support points by scanning the vertices up to this count and by walking
// the edges above it (fcl::Convex::kMinVertCountForEdgeWalking, private in FCL 0.7).
constexpr std::size_t kFclEdgeWalkingAbove = 32;

// The hull as an fcl::Convexd, translated by -origin. Faces are given only when FCL walks them:
// below that size GJK and EPA use nothing but the vertices, and the faces would only cost FCL's
// constructor its adjacency build and topology check (std::set and std::map per body).
std::shared_ptr<fcl::Convexd> to_fcl(const ConvexPolyhedron& body, const Vector3& origin) {
  const Hull& hull = body.hull();
  auto vertices = std::make_shared<std::vector<fcl::Vector3d>>();
  vertices->reserve(hull.vertex_indices.size());
  for (int i : hull.vertex_indices)
    vertices->push_back(body.vertices().row(i).transpose() - origin);
  auto faces = std::make_shared<std::vector<int>>();
  int face_count = 0;
  if (vertices->size() > kFclEdgeWalkingAbove) {
    std::vector<int> local(body.size(), -1);
    for (std::size_t k = 0; k < hull.vertex_indices.size(); ++k) {
      local[hull.vertex_indices[k]] = static_cast<int>(k);
    }
    face_count = static_cast<int>(hull.faces.rows());
    faces->reserve(4 * static_cast<std::size_t>(face_count));
    for (Eigen::Index f = 0; f < hull.faces.rows(); ++f) {
      faces->insert(faces->end(),
                    {3, local[hull.faces(f, 0)], local[hull.faces(f, 1)], local[hull.faces(f, 2)]});
    }
  }
  return std::make_shared<fcl::Convexd>(vertices, face_count, faces);
}

// A body's FCL shape in a frame centred on its bounding box, built once per body: coordinates near
// zero keep their precision whatever the bodies' offset.
struct FclShape {
  Vector3 origin;
  std::shared_ptr<fcl::Convexd> shape;
};

const FclShape& shape_of(const ConvexPolyhedron& body, std::shared_ptr<const FclShape>& keep) {
  keep = body.derived<FclShape>([&body] {
    const Aabb box = body.aabb();
    const Vector3 origin = (box.min + box.max) / 2;
    return FclShape{origin, to_fcl(body, origin)};
  });
  return *keep;
}

// The pair in A's frame: B is placed by the difference of the two origins.
struct FclPair {
  Vector3 origin;
  std::shared_ptr<const FclShape> a;
  std::shared_ptr<const FclShape> b;
};

FclPair make_pair(const ConvexPolyhedron& a, const ConvexPolyhedron& b) {
  FclPair pair;
  pair.origin = shape_of(a, pair.a).origin;
  shape_of(b, pair.b);
  return pair;
}

// One FCL distance query; a fresh fcl::DistanceResult each time, since it keeps the smallest
// distance it has seen. Its witnesses are in A's frame.
fcl::DistanceResultd query(const FclPair& pair, bool signed_distance, fcl::GJKSolverType solver,
                           Scalar tolerance) {
  const fcl::DistanceRequestd request(true, signed_distance, 0, 0, tolerance, solver);
  fcl::DistanceResultd result;
  fcl::Transform3d place_b = fcl::Transform3d::Identity();
  place_b.translation() = pair.b->origin - pair.a->origin;
  fcl::distance(pair.a->shape.get(), fcl::Transform3d::Identity(), pair.b->shape.get(), place_b,
                request, result);
  return result;
}

}  // namespace

DistanceResult fcl_distance(const ConvexPolyhedron& a, const ConvexPolyhedron& b, FclGjk gjk,
                            const ExactOptions& options) {
  options.validate();
  const std::string method = name_of(gjk);
  const FclPair pair = make_pair(a, b);
  const fcl::DistanceResultd raw =
      query(pair, false, gjk == FclGjk::libccd ? fcl::GST_LIBCCD : fcl::GST_INDEP,
            options.distance_tolerance);
  if (std::isfinite(raw.min_distance) && raw.min_distance > 0) {
    DistanceResult r = exact_internal::result_from_witnesses(
        a, b, raw.nearest_points[0] + pair.origin, raw.nearest_points[1] + pair.origin, method,
        options.tolerance);
    if (exact_internal::is_certified_optimal(a, b, r)) return r;
  }
  return exact_internal::nearest_points(a, b, options, method);
}

DistanceResult fcl_signed_distance(const ConvexPolyhedron& a, const ConvexPolyhedron& b, FclGjk gjk,
                                   const ExactOptions& options) {
  DistanceResult apart = fcl_distance(a, b, gjk, options);
  if (!apart.colliding) return apart;
  const FclPair pair = make_pair(a, b);
  const fcl::DistanceResultd raw = query(pair, true, fcl::GST_LIBCCD, options.distance_tolerance);
  // FCL's witnesses: point_a deepest in B, point_b deepest in A; point_a - point_b is the
  // translation of B that separates the bodies (the contact normal, from A to B).
  const Vector3 point_a = raw.nearest_points[0] + pair.origin;
  const Vector3 point_b = raw.nearest_points[1] + pair.origin;
  const Vector3 normal = point_a - point_b;
  if (!(raw.min_distance < 0) || !(normal.norm() > 0) || !normal.allFinite()) return apart;
  return exact_internal::penetration_result(a, b, normal, -raw.min_distance, apart.method,
                                            options.tolerance);
}

}  // namespace swarmcollide
