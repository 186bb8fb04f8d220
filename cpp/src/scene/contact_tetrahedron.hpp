// A warm start for the next frame's penetration of a pair in contact; private to the library.
#pragma once

#include "../geometry/framed_body.hpp"
#include "contact_manifold.hpp"
#include "pair_cache.hpp"

namespace swarmcollide::detail {

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
