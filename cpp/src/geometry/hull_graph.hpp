// The surface and edge graph of a hull, shared by hull.cpp and hull_points.cpp; private to the
// library's sources.
#pragma once

#include <vector>

#include "swarmcollide/geometry/hull.hpp"
#include "swarmcollide/types.hpp"

namespace swarmcollide::detail {

/// True when the triangles form a closed, consistently oriented surface: every directed edge is
/// used once and its reverse once.
bool closed_surface(const std::vector<Eigen::RowVector3i>& triangles);

/// Sets `hull.neighbour_offsets` and `hull.neighbours` from its faces (or its segment), and
/// `hull.climb_starts`, for the point set `points` whose hull it is (every cell starting at the
/// first vertex for a set of at most kHillClimbingThreshold points, which is scanned).
void fill_adjacency(Hull& hull, const VertexMatrix& points);

}  // namespace swarmcollide::detail
