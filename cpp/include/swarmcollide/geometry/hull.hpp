#pragma once

#include <vector>

#include "swarmcollide/types.hpp"

namespace swarmcollide {

/// The convex hull of a point set, as indices into that set.
struct Hull {
  /// Affine dimension of the points: 0 (one point), 1 (segment), 2 (flat polygon) or 3 (solid).
  int dimension = 0;
  /// Indices of the points that are vertices of the hull, ascending.
  std::vector<int> vertex_indices;
  /// Triangles with outward normals by the right-hand rule. A flat polygon is listed twice, once
  /// facing each side, so the mesh stays closed; segments and single points have no faces.
  FaceMatrix faces;
  /// The hull's edge graph (edges of the triangles, of the polygon or of the segment) in
  /// compressed rows: the neighbours of point `i` are `neighbours[neighbour_offsets[i]]` up to
  /// `neighbours[neighbour_offsets[i + 1]]` (excluded). Points that are not hull vertices have
  /// none. `neighbour_offsets` has one entry per point plus one.
  std::vector<int> neighbour_offsets;
  std::vector<int> neighbours;
  /// Where hill climbs without a start begin: per cell of a cube map of directions (six faces of
  /// 8 x 8 cells, about 11 degrees wide), a vertex farthest along the cell's centre, so that a
  /// climb from the cell of its direction is a step or two. A set of at most
  /// kHillClimbingThreshold points, which the library scans rather than climbs, has its first
  /// vertex in every cell.
  std::vector<int> climb_starts;
};

/// Relative size below which a singular value of the centred points counts as zero when
/// deciding the hull's dimension.
inline constexpr Scalar kFlatnessTolerance = 1e-10;

/// Convex hull of `points` (Qhull for solids, an exact 2-D hull for flat input).
/// Throws std::invalid_argument for an empty or non-finite point set.
Hull compute_hull(const VertexMatrix& points);

}  // namespace swarmcollide
