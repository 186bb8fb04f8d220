#pragma once

#include <vector>

#include "swarmcollide/robot/robot_model.hpp"

namespace swarmcollide {

/// Two geometries of a model (indices into `RobotModel::geometries()`) whose distance is checked.
struct GeometryPair {
  int a = 0;
  int b = 0;
};

/// True when links `a` and `b` are adjacent: the same rigid group (links joined by fixed joints
/// move as one), or parent and child groups, where a group without geometry between them is
/// looked through (as MoveIt's setup assistant does): MJCF's links between the joints of one body,
/// or a URDF's frame-only links, do not make a body's child stop being its child. Their
/// geometries touch at the joint by design, so planners never check them.
bool adjacent_links(const RobotModel& model, int a, int b);

/// Every pair of geometries to check by default, in increasing (a, b) order: geometries on links
/// that are not adjacent, and each obstacle (`link` = -1) against each geometry on a link.
/// Geometries on one link, and two obstacles, are never paired.
std::vector<GeometryPair> default_pairs(const RobotModel& model);

/// Throws std::invalid_argument unless every pair names two different geometries of the model.
void validate_pairs(const RobotModel& model, const std::vector<GeometryPair>& pairs);

}  // namespace swarmcollide
