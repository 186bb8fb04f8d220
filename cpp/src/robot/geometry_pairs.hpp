// How the queries over configurations answer one pair of a robot's geometries; private to the
// library's sources.
#pragma once

#include <vector>

#include "swarmcollide/geometry/pose.hpp"
#include "swarmcollide/queries/batch.hpp"
#include "swarmcollide/queries/distance_result.hpp"
#include "swarmcollide/queries/options.hpp"
#include "swarmcollide/queries/query.hpp"
#include "swarmcollide/robot/pair_filter.hpp"
#include "swarmcollide/robot/robot_model.hpp"

namespace swarmcollide::detail {

/// Throws std::invalid_argument naming the first curved geometry (Cylinder, Ellipsoid, ...) of a
/// pair when `method` cannot answer curved shapes, and the methods that can: before any
/// configuration, so the error names the geometry rather than a configuration.
void require_geometry_shapes(const RobotModel& model, const std::vector<GeometryPair>& pairs,
                             Method method);

/// The signed distance of `pair` with its geometries at `pose_a` and `pose_b`: the convex query
/// for two convex geometries (curved shapes among them), the compound query when one is compound,
/// and for a compound geometry against a curved one (which compound bodies do not take as parts)
/// the least of the convex query over the compound's parts, reduced as the compound query reduces
/// them (the least distance, the first part on ties; the least lower bound; colliding when any
/// part is; certified when every part is).
DistanceResult signed_distance_of(const Query& query, const RobotModel& model,
                                  const GeometryPair& pair, const Pose& pose_a,
                                  const Pose& pose_b);

/// The distance of `pair` (Query::distance), whole or part by part as signed_distance_of
/// answers it.
DistanceResult distance_of(const Query& query, const RobotModel& model, const GeometryPair& pair,
                           const Pose& pose_a, const Pose& pose_b);

/// The collision verdict of `pair` at `pose_a` and `pose_b` (Query::collision), whole or part by
/// part as signed_distance_of answers it (colliding when any part is).
DistanceResult collision_of(const Query& query, const RobotModel& model, const GeometryPair& pair,
                            const Pose& pose_a, const Pose& pose_b);

/// The signed distances of `pair` over the configurations whose geometry poses `poses` holds, as
/// signed_distance_many answers them (row i seeded by pair_seed(options.seed, i)): row i is
/// signed_distance_of at those poses with the options seeded for row i. For a compound geometry
/// against a curved one, the rows hold the least over the parts (reduced as signed_distance_of
/// reduces them; witnesses, directions and parts are those of the nearest part).
BatchResult signed_distances_of(const RobotModel& model, const GeometryPair& pair,
                                const QueryOptions& options, const BatchSettings& settings,
                                const BatchPoses& poses);

}  // namespace swarmcollide::detail
