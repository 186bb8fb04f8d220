// Witness points and the answers built from them; private to the library's sources.
#pragma once

#include <array>
#include <limits>

#include "../geometry/framed_body.hpp"
#include "answer.hpp"
#include "wolfe_min_norm.hpp"

namespace swarmcollide::detail {

/// An upper bound as a convex combination of at most four point pairs (x_ia, y_ib), as Wolfe's
/// corral gives it: sparse, so that recording a better bound costs nothing in the bodies' sizes.
struct Witness {
  static constexpr int kCapacity = MinNormPoint::kCapacity;
  std::array<int, kCapacity> ia{};
  std::array<int, kCapacity> ib{};
  std::array<Scalar, kCapacity> weights{};
  int size = 0;
  Vector3 point_a = Vector3::Zero();
  Vector3 point_b = Vector3::Zero();
  /// |point_b - point_a|.
  Scalar distance = std::numeric_limits<Scalar>::infinity();
  /// The corral it came from encloses the origin by more than rounding: the bodies share a point.
  bool encloses_origin = false;
};

/// The witness of Wolfe's corral of Minkowski points (whose indices are the bodies' own), with
/// the enclosure test when the corral is a tetrahedron.
Witness witness_of(const FramedPair& pair, const MinNormPoint& corral);

/// The enclosure test alone: the corral is a tetrahedron around the origin, beyond rounding.
bool corral_encloses_origin(const MinNormPoint& corral);

/// The witness alone, without the enclosure test (`encloses_origin` false).
Witness combined_witness(const FramedPair& pair, const MinNormPoint& corral);

/// The same with the corral's points of A and B given by `vertex_a(i)` and `vertex_b(j)`: the
/// bodies' own `vertex`, or the very points a search's oracle placed already (placing them again
/// was most of what a witness cost: DistanceFinish::whole). Always inline: called out of line
/// from combined_witness(pair, corral), it made each witness 20 instructions longer.
template <class VertexA, class VertexB>
[[gnu::always_inline]] inline Witness combined_witness(const MinNormPoint& corral,
                                                       const VertexA& vertex_a,
                                                       const VertexB& vertex_b) {
  Witness w;
  w.size = corral.size;
  Scalar total = 0;
  for (int k = 0; k < corral.size; ++k) total += corral.weights[k];
  // Summed in locals: the compiler cannot keep the witness's own fields in registers across the
  // vertex reads (they might alias), and the stores and reloads of each sum would stall.
  Vector3 point_a = Vector3::Zero();
  Vector3 point_b = Vector3::Zero();
  // A corral's neighbouring points often share a body's vertex (a vertex of A against an edge or
  // a face of B, an edge against an edge): placed once, it is read again.
  int placed_a = -1;
  int placed_b = -1;
  Vector3 point_of_a = Vector3::Zero();  // set at the first point (no index is -1), for GCC
  Vector3 point_of_b = Vector3::Zero();
  for (int k = 0; k < corral.size; ++k) {
    const OraclePoint& q = corral.corral[k];
    const Scalar weight = corral.weights[k] / total;
    w.ia[k] = q.ia;
    w.ib[k] = q.ib;
    w.weights[k] = weight;
    if (q.ia != placed_a) {
      placed_a = q.ia;
      point_of_a = vertex_a(q.ia);
    }
    if (q.ib != placed_b) {
      placed_b = q.ib;
      point_of_b = vertex_b(q.ib);
    }
    point_a += weight * point_of_a;
    point_b += weight * point_of_b;
  }
  w.point_a = point_a;
  w.point_b = point_b;
  w.distance = (point_b - point_a).norm();
  return w;
}

/// The same, with the enclosure test only where the witnesses do not already prove contact (their
/// distance within the pair's tolerance beyond rounding, `close_proven`): for a distance, which
/// either proof settles, and which reports no intersection proof, the test is a fifth of what an
/// overlapping pair's search costs.
Witness contact_witness_of(const FramedPair& pair, const MinNormPoint& corral);

/// The witnesses' distance is within the pair's tolerance beyond rounding: they prove contact.
inline bool witnesses_prove_contact(const FramedPair& pair, const Witness& witness) {
  return witness.distance + kFrameRounding <= pair.tolerance;
}

/// `w`, the corral's combined witness, with the enclosure test where `enclose` (witness_of), else
/// only where the witnesses do not prove contact (contact_witness_of).
inline Witness tested_witness(const FramedPair& pair, const MinNormPoint& corral, Witness w,
                              bool enclose) {
  if (enclose || !witnesses_prove_contact(pair, w)) {
    w.encloses_origin = corral_encloses_origin(corral);
  }
  return w;
}

/// The witness of the single pair of points (x_ia, y_ib).
Witness vertex_witness(const FramedPair& pair, int ia, int ib);

/// An answer holding `witness` as its upper bound, with its sparse weights. Inline: every
/// answer of the dual and exact paths is made by it, and its call was some 10 instructions of
/// each query.
inline Answer answer_from_witness(const FramedPair& pair, const Witness& witness) {
  Answer answer;
  answer.upper = witness.distance;
  answer.point_a = witness.point_a;
  answer.point_b = witness.point_b;
  answer.weights_a = ConvexWeights(pair.a.size(), witness.ia, witness.weights, witness.size);
  answer.weights_b = ConvexWeights(pair.b.size(), witness.ib, witness.weights, witness.size);
  answer.intersection_proven = witness.encloses_origin;
  return answer;
}

/// The answer Wolfe's corral of Minkowski points gives: sparse weights over the corral's points,
/// witness points, the distance between them (`upper`), the separation along them (`lower`,
/// with its `direction`), and an intersection proof when the corral is a tetrahedron that
/// encloses the origin.
Answer answer_from_corral(const FramedPair& pair, const MinNormPoint& corral);

/// The same from the corral's witness, already computed. Without `separated`, no separation is
/// measured (`lower` stays 0): a caller whose goal a proven intersection settles skips its scans.
Answer answer_from_corral(const FramedPair& pair, const MinNormPoint& corral,
                          const Witness& witness, bool separated = true);

/// The answer dense weights on the simplexes give: the witness points they combine from the
/// bodies' frame points, the distance between them (`upper`) and the separation along them
/// (`lower`, with its `direction`).
Answer answer_from_weights(const FramedPair& pair, const VertexMatrix& points_a,
                           const VertexMatrix& points_b, VectorX lambda, VectorX delta);

}  // namespace swarmcollide::detail
