#include "geometry_pairs.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>

#include "swarmcollide/geometry/support_function.hpp"
#include "swarmcollide/queries/methods.hpp"

namespace swarmcollide::detail {

namespace {

// The compound side of a pair that is answered part by part (a compound geometry against a
// curved one): 0 for a, 1 for b, -1 when the pair is answered whole.
int parts_side(const RobotModel& model, const GeometryPair& pair) {
  const Geometry& a = model.geometries()[pair.a];
  const Geometry& b = model.geometries()[pair.b];
  if (a.parts && b.body.curved()) return 0;
  if (b.parts && a.body.curved()) return 1;
  return -1;
}

// `into` becomes the better of itself and `part` (the least distance, `into` on ties), with the
// least lower bound, colliding when either is and certified when both are.
void keep_nearest(DistanceResult& into, DistanceResult part) {
  const bool colliding = into.colliding || part.colliding;
  const bool certified = into.certified && part.certified;
  const Scalar lower = std::min(into.lower_bound, part.lower_bound);
  if (part.distance < into.distance) into = std::move(part);
  into.colliding = colliding;
  into.certified = certified;
  into.lower_bound = lower;
}

}  // namespace

void require_geometry_shapes(const RobotModel& model, const std::vector<GeometryPair>& pairs,
                             Method method) {
  if (method_info(method).capabilities & kCurvedShapes) return;
  for (const GeometryPair& pair : pairs) {
    for (const int g : {pair.a, pair.b}) {
      const Geometry& geometry = model.geometries()[g];
      if (!geometry.body.curved()) continue;
      std::string able;
      for (const MethodInfo& info : method_table()) {
        if (info.capabilities & kCurvedShapes) {
          able += std::string(able.empty() ? "'" : ", '") + info.name + "'";
        }
      }
      throw std::invalid_argument("geometry '" + geometry.name + "' is a " +
                                  geometry.body.curved()->name() + ", which method '" +
                                  method_name(method) +
                                  "' cannot answer (it reads a body's points): use method " +
                                  able);
    }
  }
}

namespace {

// `ask(a, pose_a, b, pose_b)` (a Query goal) on `pair`: whole, or part by part for a compound
// geometry against a curved one, reduced by keep_nearest.
template <typename Ask>
DistanceResult pair_answer(const RobotModel& model, const GeometryPair& pair, const Pose& pose_a,
                           const Pose& pose_b, const Ask& ask) {
  const Geometry& a = model.geometries()[pair.a];
  const Geometry& b = model.geometries()[pair.b];
  const int side = parts_side(model, pair);
  if (side < 0) {
    if (a.parts || b.parts) {
      return ask(model.compound(pair.a), pose_a, model.compound(pair.b), pose_b);
    }
    return ask(a.body, pose_a, b.body, pose_b);
  }
  const std::vector<ConvexPolyhedron>& parts = (side == 0 ? a : b).parts->parts();
  DistanceResult nearest;
  for (std::size_t k = 0; k < parts.size(); ++k) {
    DistanceResult part = side == 0 ? ask(parts[k], pose_a, b.body, pose_b)
                                    : ask(a.body, pose_a, parts[k], pose_b);
    if (k == 0) {
      nearest = std::move(part);
    } else {
      keep_nearest(nearest, std::move(part));
    }
  }
  return nearest;
}

}  // namespace

DistanceResult signed_distance_of(const Query& query, const RobotModel& model,
                                  const GeometryPair& pair, const Pose& pose_a,
                                  const Pose& pose_b) {
  return pair_answer(model, pair, pose_a, pose_b,
                     [&](const auto& a, const Pose& pa, const auto& b, const Pose& pb) {
                       return query.signed_distance(a, pa, b, pb);
                     });
}

DistanceResult distance_of(const Query& query, const RobotModel& model, const GeometryPair& pair,
                           const Pose& pose_a, const Pose& pose_b) {
  return pair_answer(model, pair, pose_a, pose_b,
                     [&](const auto& a, const Pose& pa, const auto& b, const Pose& pb) {
                       return query.distance(a, pa, b, pb);
                     });
}

DistanceResult collision_of(const Query& query, const RobotModel& model, const GeometryPair& pair,
                            const Pose& pose_a, const Pose& pose_b) {
  return pair_answer(model, pair, pose_a, pose_b,
                     [&](const auto& a, const Pose& pa, const auto& b, const Pose& pb) {
                       return query.collision(a, pa, b, pb);
                     });
}

BatchResult signed_distances_of(const RobotModel& model, const GeometryPair& pair,
                                const QueryOptions& options, const BatchSettings& settings,
                                const BatchPoses& poses) {
  const Geometry& a = model.geometries()[pair.a];
  const Geometry& b = model.geometries()[pair.b];
  const int side = parts_side(model, pair);
  if (side < 0) {
    if (a.parts || b.parts) {
      return signed_distance_many(model.compound(pair.a), model.compound(pair.b), options,
                                  settings, poses);
    }
    return signed_distance_many(a.body, b.body, options, settings, poses);
  }
  const std::vector<ConvexPolyhedron>& parts = (side == 0 ? a : b).parts->parts();
  BatchResult nearest;
  for (std::size_t k = 0; k < parts.size(); ++k) {
    BatchResult part = side == 0 ? signed_distance_many(parts[k], b.body, options, settings, poses)
                                 : signed_distance_many(a.body, parts[k], options, settings, poses);
    if (k == 0) {
      nearest = std::move(part);
      nearest.part_a.setZero();
      nearest.part_b.setZero();
      continue;
    }
    for (std::size_t i = 0; i < nearest.rows(); ++i) {
      const auto r = static_cast<Eigen::Index>(i);
      nearest.colliding(r) = nearest.colliding(r) || part.colliding(r);
      nearest.certified(r) = nearest.certified(r) && part.certified(r);
      nearest.lower_bound(r) = std::min(nearest.lower_bound(r), part.lower_bound(r));
      if (part.distance(r) < nearest.distance(r)) {
        nearest.distance(r) = part.distance(r);
        nearest.point_a.row(r) = part.point_a.row(r);
        nearest.point_b.row(r) = part.point_b.row(r);
        nearest.direction.row(r) = part.direction.row(r);
        nearest.iterations(r) = part.iterations(r);
        nearest.escalated(r) = part.escalated(r);
        (side == 0 ? nearest.part_a : nearest.part_b)(r) = static_cast<int>(k);
      }
    }
  }
  return nearest;
}

}  // namespace swarmcollide::detail
