// Contact points of two bodies in contact; private to the library's sources.
#pragma once

#include <vector>

#include "../geometry/framed_body.hpp"

namespace swarmcollide::detail {

/// Slack, relative to the pair's size, within which a point counts as lying on a supporting
/// plane when contact features are collected: far above rounding, far below any visible tilt,
/// so that a box resting on a face gives four corners and one tilted by a degree gives an edge.
inline constexpr Scalar kContactFeatureTolerance = 1e-6;

/// The supporting features contact_points clipped: the indices of A's points within the slack of
/// its supporting plane along the normal, and of B's along its opposite.
struct ContactFeatures {
  std::vector<int> a;
  std::vector<int> b;
};

/// Up to `max_points` points where A and B touch along the unit normal `n` (frame coordinates,
/// from A to B), in the frame, appended to `out` (at least one): A's supporting feature along
/// `n` and B's along `-n` (their points within `slack` of the supporting planes: a face, an edge
/// or a vertex) are projected onto the plane perpendicular to `n`, clipped against each other,
/// and lifted halfway between the two supporting planes. Face on face gives the corners of the
/// overlap polygon, reduced to the `max_points` that span the largest area; edge on face the
/// ends of the edge's part over the face; a vertex (or crossing edges) one point. A curved body's
/// feature is its numbered points within the slack (its support points so far) and the points
/// its support function gives along directions near the normal within the slack: its extremes
/// are there whatever points a solver happened to find.
/// The features' numbered points are left in `features` (buffers reused from call to call).
void contact_points(const FramedPair& pair, const Vector3& n, Scalar slack, int max_points,
                    std::vector<Vector3>& out, ContactFeatures& features);

}  // namespace swarmcollide::detail
