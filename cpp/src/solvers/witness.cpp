#include "witness.hpp"

#include <utility>

#include "minkowski.hpp"

namespace swarmcollide::detail {

// A witness's weights become an answer's sparse weights as they are (answer_from_witness).
static_assert(Witness::kCapacity == ConvexWeights::kSparseCapacity);

Witness combined_witness(const FramedPair& pair, const MinNormPoint& corral) {
  return combined_witness(
      corral, [&](int i) { return pair.a.vertex(i); }, [&](int j) { return pair.b.vertex(j); });
}

bool corral_encloses_origin(const MinNormPoint& corral) {
  return corral.size == 4 && encloses_origin({corral.corral[0].p, corral.corral[1].p,
                                              corral.corral[2].p, corral.corral[3].p});
}

Witness witness_of(const FramedPair& pair, const MinNormPoint& corral) {
  Witness w = combined_witness(pair, corral);
  w.encloses_origin = corral_encloses_origin(corral);
  return w;
}

Witness contact_witness_of(const FramedPair& pair, const MinNormPoint& corral) {
  Witness w = combined_witness(pair, corral);
  if (!witnesses_prove_contact(pair, w)) w.encloses_origin = corral_encloses_origin(corral);
  return w;
}

Witness vertex_witness(const FramedPair& pair, int ia, int ib) {
  Witness w;
  w.ia[0] = ia;
  w.ib[0] = ib;
  w.weights[0] = 1;
  w.size = 1;
  w.point_a = pair.a.vertex(ia);
  w.point_b = pair.b.vertex(ib);
  w.distance = (w.point_b - w.point_a).norm();
  return w;
}

Answer answer_from_corral(const FramedPair& pair, const MinNormPoint& corral) {
  return answer_from_corral(pair, corral, witness_of(pair, corral));
}

Answer answer_from_corral(const FramedPair& pair, const MinNormPoint& corral,
                          const Witness& witness, bool separated) {
  Answer answer = answer_from_witness(pair, witness);
  if (answer.upper > 0) {
    answer.direction = (answer.point_b - answer.point_a) / answer.upper;
    if (separated) {
      // Started from the corral's points, hill climbing on large bodies is a few steps.
      int hint_a = corral.corral[0].ia;
      int hint_b = corral.corral[0].ib;
      answer.lower = separation(pair.a, pair.b, answer.direction, hint_a, hint_b);
    }
  }
  return answer;
}

Answer answer_from_weights(const FramedPair& pair, const VertexMatrix& points_a,
                           const VertexMatrix& points_b, VectorX lambda, VectorX delta) {
  Answer answer;
  answer.point_a = points_a.transpose() * lambda;
  answer.point_b = points_b.transpose() * delta;
  answer.weights_a = ConvexWeights(std::move(lambda));
  answer.weights_b = ConvexWeights(std::move(delta));
  const Vector3 between = answer.point_b - answer.point_a;
  answer.upper = between.norm();
  if (answer.upper > 0) {
    answer.direction = between / answer.upper;
    answer.lower = separation(pair.a, pair.b, answer.direction);
  }
  return answer;
}

}  // namespace swarmcollide::detail
