// Witness points and the answers built from them; private to the library's sources.
#pragma once

#include <vector>

#include "../geometry/framed_body.hpp"
#include "answer.hpp"
#include "wolfe_min_norm.hpp"

namespace swarmcollide::detail {

/// The answer Wolfe's corral of Minkowski points gives: sparse weights over the corral's points,
/// witness points, the distance between them (`upper`), the separation along them (`lower`,
/// with its `direction`), and an intersection proof when the corral is a tetrahedron that
/// encloses the origin.
Answer answer_from_corral(const FramedPair& pair, const MinNormPoint& corral);

/// The answer dense weights on the simplexes give: the witness points they combine from the
/// bodies' frame points, the distance between them (`upper`) and the separation along them
/// (`lower`, with its `direction`).
Answer answer_from_weights(const FramedPair& pair, const VertexMatrix& points_a,
                           const VertexMatrix& points_b, VectorX lambda, VectorX delta);

/// Indices of the points of `body` within `slack` of its supporting plane along `normal` (the
/// supporting feature, padded by rounding), highest first, into `found`.
void supporting_feature(const FramedBody& body, const Vector3& normal, Scalar slack,
                        std::vector<int>& found);

/// Signed witnesses along the unit normal `n` (from A to B) with separation `s = s(n)`: the
/// nearest points of A's supporting feature along `n` and of B's along `-n` once B is moved by
/// `-s n`, which brings the two supporting planes together. Sets `point_a`, `point_b` (so that
/// `point_b - point_a = s n` to rounding), the weights and `direction` of `answer`.
void signed_witnesses(const FramedPair& pair, const Vector3& n, Scalar s, Answer& answer);

}  // namespace swarmcollide::detail
