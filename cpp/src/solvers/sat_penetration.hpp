// Certified penetration depth by exhaustive separating-axis enumeration; private to the library.
#pragma once

#include "../geometry/framed_body.hpp"
#include "answer.hpp"

namespace swarmcollide::detail {

/// The signed distance of a touching or overlapping pair, from the facet normals of the
/// Minkowski difference B - A, which contain the direction of least overlap: face normals of
/// either hull and cross products of an edge of each (all pairs). `lower` is the largest
/// separation found (with its direction and signed witnesses); `upper` is the smaller of
/// `distance_upper` (any distance bounds the signed distance) and the largest separation over
/// the candidates plus each candidate's rounding and the bodies' deviation from their hulls'
/// dimension. Skips the enumeration (leaving `upper` at `distance_upper`) when the bodies have
/// more than `max_edge_pairs` pairs of edges. `hint` may be zero.
Answer sat_penetration(const FramedPair& pair, const Vector3& hint, Scalar distance_upper,
                       long max_edge_pairs);

}  // namespace swarmcollide::detail
