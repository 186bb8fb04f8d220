// A warm start for the next frame's penetration of a pair in contact; private to the library.
#pragma once

#include <array>
#include <cstddef>

#include "../geometry/framed_body.hpp"
#include "contact_manifold.hpp"
#include "pair_cache.hpp"

namespace swarmcollide::detail {

/// Differences of feature points searched for a base triangle: the contacts of a frame are
/// mostly a vertex on a face (three or four) or an edge across an edge (four), and a face on a
/// face at most 4 x 4 (a box resting on a box).
inline constexpr std::size_t kMostBasePoints = 16;

/// The triangle of `points` (`count` of them, at most kMostBasePoints, in a plane's coordinates)
/// with `q` deepest inside, by its least barycentric coordinate, into `base` (indices in
/// increasing order); false when no triangle has `q` inside (every least coordinate <= 0).
/// Ties go to the first triangle in lexicographic order of its indices: exactly the triangle
/// that computing every triangle's coordinates in turn (cubic in `count`) picks.
bool deepest_triangle(const Eigen::Vector2d* points, std::size_t count, const Eigen::Vector2d& q,
                      std::array<std::size_t, 3>& base);

/// A tetrahedron of B - A enclosing the origin (beyond rounding) whose base lies on B - A's face
/// along the contact normal `n` (unit, frame coordinates, from A to B): three differences of the
/// contact's supporting `features`, around where the line from the apex (the point of B - A
/// farthest along `n`) through the origin meets that face. The expanding polytope started from
/// it meets the face it has to prove at once, where a tetrahedron of Wolfe's corral needs more
/// expansions to find it; after a small motion the same points usually still enclose the origin
/// and are still on the face. The climbs to the apex start from `out`'s fourth pair (-1: from
/// the hulls' cube maps of starts). Written to `out` only when found (false otherwise: a vertex
/// touching a vertex, features too large to search, or no triangle of them around the line).
bool contact_tetrahedron(const FramedPair& pair, const Vector3& n, const ContactFeatures& features,
                         PairProof::Enclosing& out);

}  // namespace swarmcollide::detail
