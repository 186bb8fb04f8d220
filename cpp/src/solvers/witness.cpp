#include "witness.hpp"

#include <algorithm>
#include <array>
#include <utility>

#include "minkowski.hpp"

namespace swarmcollide::detail {

namespace {

using Indices = std::array<int, ConvexWeights::kSparseCapacity>;
using Weights = std::array<Scalar, ConvexWeights::kSparseCapacity>;
static_assert(Witness::kCapacity == ConvexWeights::kSparseCapacity);

}  // namespace

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

void supporting_feature(const FramedBody& body, const Vector3& normal, Scalar slack,
                        std::vector<int>& found) {
  found.clear();
  const Vector3 top = body.support(normal);
  const Scalar floor = normal.dot(top) - slack;
  for (int i = 0; i < body.size(); ++i) {
    if (normal.dot(body.vertex(i)) >= floor) found.push_back(i);
  }
  std::sort(found.begin(), found.end(),
            [&](int i, int j) { return normal.dot(body.vertex(i)) > normal.dot(body.vertex(j)); });
}

void signed_witnesses(const FramedPair& pair, const Vector3& n, Scalar s, Answer& answer) {
  // Rounding puts points of the true feature up to kFrameRounding below the plane; a generous
  // slack costs only a slightly larger subproblem, while a too small one could cut the feature.
  constexpr Scalar kSlack = 1e3 * kFrameRounding;
  thread_local std::vector<int> feature_a;
  thread_local std::vector<int> feature_b;
  supporting_feature(pair.a, n, kSlack, feature_a);
  supporting_feature(pair.b, -n, kSlack, feature_b);
  const Vector3 shift = -s * n;
  const auto oracle = [&](const Vector3& d) {
    int i = feature_a[0];
    Scalar highest = d.dot(pair.a.vertex(i));
    for (int k : feature_a) {
      const Scalar h = d.dot(pair.a.vertex(k));
      if (h > highest) {
        highest = h;
        i = k;
      }
    }
    int j = feature_b[0];
    Scalar lowest = d.dot(pair.b.vertex(j));
    for (int k : feature_b) {
      const Scalar h = d.dot(pair.b.vertex(k));
      if (h < lowest) {
        lowest = h;
        j = k;
      }
    }
    return OraclePoint{pair.b.vertex(j) + shift - pair.a.vertex(i), i, j};
  };
  const MinNormPoint nearest = wolfe_min_norm(oracle, n, 2, 100);
  Indices ia{};
  Indices ib{};
  Weights w{};
  Scalar total = 0;
  for (int k = 0; k < nearest.size; ++k) total += nearest.weights[k];
  answer.point_a.setZero();
  answer.point_b.setZero();
  for (int k = 0; k < nearest.size; ++k) {
    ia[k] = nearest.corral[k].ia;
    ib[k] = nearest.corral[k].ib;
    w[k] = nearest.weights[k] / total;
    answer.point_a += w[k] * pair.a.vertex(ia[k]);
    answer.point_b += w[k] * pair.b.vertex(ib[k]);
  }
  answer.weights_a = ConvexWeights(pair.a.size(), ia, w, nearest.size);
  answer.weights_b = ConvexWeights(pair.b.size(), ib, w, nearest.size);
  answer.direction = n;
}

}  // namespace swarmcollide::detail
