// The separating-axis bound: every facet normal of the Minkowski difference, enumerated; private.
#pragma once

#include <vector>

#include "../geometry/framed_body.hpp"
#include "swarmcollide/types.hpp"

namespace swarmcollide::detail {

/// What the enumeration of candidate axes proved and found.
struct AxesBound {
  /// Proven: `s(n) <= upper` at every facet normal `n` of `A - B`, and at the extra axes.
  Scalar upper = -1e300;
  /// When `upper < -flat_slack` the difference `A - B` is full-dimensional and contains the
  /// origin, so `sd <= upper`; otherwise only `sd <= max(upper, distance)` holds.
  Scalar flat_slack = 0;
  /// The candidate of largest bound: its separation is the best lower bound found.
  Vector3 best_normal = Vector3::UnitX();
  /// Edge pairs tested.
  long long pairs = 0;
};

/// The overlay of the Gauss maps of A and -B: its vertices (face normals of either body, crossings
/// of an edge arc of each) are the facet normals of `A - B`, so for overlapping bodies the largest
/// separation over them is the signed distance. Crossing tests are inclusive (an extra axis never
/// hurts a bound), each candidate's bound is `n'.(y - x)` for points x, y of the features that
/// span it plus the rounding of `n'` times `|y - x|`, and nearly parallel edge pairs are bounded
/// over the arc their facet normal can lie on. The bound holds for the polytopes the hulls
/// describe; how far the points stray from them (Qhull's rounding, the flattening of nearly flat,
/// collinear or coincident sets) is measured and added, since moving the bodies by a Hausdorff
/// distance h moves every separation by at most h. Costs O(faces * (points + climb) +
/// edges_a * edges_b).
class CandidateAxes {
 public:
  /// The bound for A and B, whose coordinates are at most `coordinate` in magnitude.
  AxesBound run(const FramedBody& a, const FramedBody& b, Scalar coordinate);

 private:
  /// An edge's Gauss arc: the unit normals from `u` to `v`, rotating positively about `t`; on the
  /// great circle orthogonal to `t`, a point `x` is on it iff `x.P >= 0`, `x.Q >= 0` and
  /// `x.M >= 0` (the last excludes the antipode of a short arc), each up to `tau`.
  struct Arc {
    Vector3 t;
    Vector3 u;
    Vector3 v;
    Vector3 P;
    Vector3 Q;
    Vector3 M;
    Scalar tau;
    int p;
    int q;
    bool full;  // a segment's edge: the whole great circle
  };
  struct Facet {
    Vector3 normal;
    Scalar error;  // bound on the angle between `normal` and the true plane's normal
    int vertex;
  };

  static void collect(const FramedBody& body, bool negate, std::vector<Arc>& arcs,
                      std::vector<Facet>& facets, std::vector<int>& slot_face,
                      std::vector<int>& ring, Scalar& hull_error);
  /// Records a candidate: `estimate` is n.(y - x) for the features spanning it, `error` what
  /// rounding (and the direction's uncertainty) may add to the true facet's separation.
  void offer(AxesBound& bound, const Vector3& n, Scalar estimate, Scalar error);

  std::vector<Arc> arcs_a_;
  std::vector<Arc> arcs_b_;
  std::vector<Facet> facets_a_;
  std::vector<Facet> facets_b_;
  std::vector<int> slot_face_;
  std::vector<int> ring_;
  Scalar best_estimate_ = 0;
};

}  // namespace swarmcollide::detail
