#include "penetration.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "candidate_axes.hpp"
#include "expanding_polytope.hpp"
#include "penetration_support.hpp"
#include "wolfe_min_norm.hpp"

namespace swarmcollide::detail {

namespace {

constexpr Scalar kInfinity = std::numeric_limits<Scalar>::infinity();
// Edge pairs up to which the candidate axes are enumerated before anything else: below it the
// enumeration costs about as much as Wolfe plus the expanding polytope, and proves every case.
constexpr long long kAxesFirstPairs = 1024;
// Edge pairs up to which the enumeration is the fallback when the polytope proves too little
// (about 40 ms); larger pairs keep the polytope's bounds, unproven.
constexpr long long kAxesFallbackPairs = 1LL << 22;
// Iterations of Wolfe's algorithm on the features (at most four points leave the corral per
// iteration, and it stops at rounding long before).
constexpr int kWitnessIterations = 100;

// Buffers a solve reuses from the previous one on the same thread.
struct Workspace {
  ExpandingPolytope polytope;
  CandidateAxes axes;
  std::vector<int> feature_a;
  std::vector<int> feature_b;
};

Workspace& thread_workspace() {
  thread_local Workspace workspace;
  return workspace;
}

long long edge_count(const Hull& hull) {
  if (hull.dimension <= 0) return 0;
  if (hull.dimension == 1) return 1;
  return static_cast<long long>(hull.neighbours.size()) / 2;
}

class Solver {
 public:
  Solver(const VertexMatrix& a, const Hull& hull_a, const VertexMatrix& b, const Hull& hull_b,
         Scalar tolerance, int max_iterations)
      : a_{a, hull_a},
        b_{b, hull_b},
        coordinate_(largest_coordinate(a, b)),
        margin_(separation_margin(coordinate_)),
        reach_(2 * std::sqrt(Scalar(3)) * coordinate_),
        tolerance_(tolerance),
        max_iterations_(max_iterations),
        ws_(thread_workspace()) {}

  PenetrationBounds solve(const Vector3& hint) {
    if (hint.allFinite() && hint.norm() > 0) offer_direction(hint.normalized());
    const long long pairs = edge_count(a_.hull) * edge_count(b_.hull);
    if (pairs <= kAxesFirstPairs) {
      enumerate_axes();
      if (!done()) expand();
    } else {
      expand();
      if (!done() && pairs <= kAxesFallbackPairs) enumerate_axes();
    }
    return result();
  }

 private:
  // The separation along unit n by scanning both bodies: what a proven lower bound rests on.
  Scalar exact_separation(const Vector3& n) const {
    return b_.point(b_.scan_max(-n)).dot(n) - a_.point(a_.scan_max(n)).dot(n);
  }

  // Every direction gives a lower bound; the best one is kept, with its separation computed
  // exactly once, here.
  void offer_direction(const Vector3& n) {
    if (!n.allFinite()) return;
    const Scalar s = exact_separation(n);
    if (s > separation_) {
      separation_ = s;
      normal_ = n;
    }
  }

  Scalar lower() const { return separation_ - margin_; }
  bool done() const { return upper_ - lower() <= std::max(tolerance_, floor()); }
  // The gap below which the rounding margins leave nothing to gain.
  Scalar floor() const { return 16 * margin_; }

  // Wolfe's nearest point of A - B to the origin: an upper bound |p| (p is a point of A - B, so
  // s(n) <= -n.p <= |p| for every n) and, when the origin is inside, a tetrahedron around it.
  const exact_internal::MinNormPoint& nearest() {
    if (nearest_ready_) return nearest_;
    nearest_ready_ = true;
    int ia = -1;
    int ib = -1;
    const auto oracle = [&](const Vector3& d) {
      ia = a_.climb_max(-d, ia);
      ib = b_.climb_max(d, ib);
      return exact_internal::OraclePoint{a_.point(ia) - b_.point(ib), ia, ib};
    };
    Vector3 start = normal_;
    if (!(separation_ > -kInfinity)) start = a_.point(0) - b_.point(0);
    if (!(start.norm() > 0)) start = Vector3::UnitX();
    nearest_ = exact_internal::wolfe_min_norm(oracle, start, reach_, max_iterations_);
    iterations_ += nearest_.iterations;
    // The exact convex combination of the corral (weights normalised) is a point of A - B; the
    // computed one is within 16 roundoffs of reach_ of it.
    Scalar total = 0;
    for (int k = 0; k < nearest_.size; ++k) total += nearest_.weights[k];
    Vector3 p = Vector3::Zero();
    for (int k = 0; k < nearest_.size; ++k) p += nearest_.weights[k] / total * nearest_.corral[k].p;
    nearest_norm_ = p.norm() + 16 * kRoundoff * reach_;
    if (p.norm() > 0) offer_direction(-p.normalized());
    return nearest_;
  }

  void enumerate_axes() {
    const AxesBound bound = ws_.axes.run(a_, b_, coordinate_);
    offer_direction(bound.best_normal);
    if (bound.upper < -bound.flat_slack) {
      upper_ = std::min(upper_, bound.upper);
    } else {
      nearest();
      upper_ = std::min(upper_, std::max(bound.upper, nearest_norm_));
    }
  }

  void expand() {
    const exact_internal::MinNormPoint& m = nearest();
    upper_ = std::min(upper_, nearest_norm_);
    if (m.size != exact_internal::MinNormPoint::kCapacity || done()) return;
    std::array<DifferencePoint, 4> start;
    for (int k = 0; k < 4; ++k) start[k] = {m.corral[k].p, m.corral[k].ia, m.corral[k].ib};
    const Scalar stop_gap = std::max(tolerance_ / 2, floor() / 4);
    const ExpansionResult e = ws_.polytope.run(a_, b_, start, stop_gap, max_iterations_);
    iterations_ += e.iterations;
    if (e.best_separation > -kInfinity) offer_direction(e.best_normal);
    if (e.verified) upper_ = std::min(upper_, -e.depth_lower);
  }

  // Witnesses: on A's supporting feature along the normal and B's along its opposite, the pair
  // whose difference is nearest to separation * normal (Wolfe's algorithm on the features'
  // difference shifted by it). At an optimal normal the foot of the origin on the facet of
  // A - B lies in that difference, and the residual is rounding.
  void witnesses(PenetrationBounds& r) {
    const Vector3& n = normal_;
    const Scalar gap = std::isfinite(upper_) ? std::max(Scalar(0), upper_ - lower()) : 0;
    const Scalar slack = 1024 * margin_ + 2 * std::min(gap, Scalar(1e-9));
    const auto collect = [&](const BodyView& body, const Vector3& d, std::vector<int>& feature) {
      const Scalar top = body.point(body.scan_max(d)).dot(d);
      feature.clear();
      for (int i = 0; i < body.size(); ++i) {
        if (body.point(i).dot(d) >= top - slack) feature.push_back(i);
      }
    };
    collect(a_, n, ws_.feature_a);
    collect(b_, -n, ws_.feature_b);
    const Vector3 shift = separation_ * n;
    const auto oracle = [&](const Vector3& d) {
      int i = ws_.feature_a.front();
      for (int k : ws_.feature_a) {
        if (a_.point(k).dot(d) > a_.point(i).dot(d)) i = k;
      }
      int j = ws_.feature_b.front();
      for (int k : ws_.feature_b) {
        if (b_.point(k).dot(d) < b_.point(j).dot(d)) j = k;
      }
      return exact_internal::OraclePoint{b_.point(j) - a_.point(i) - shift, i, j};
    };
    const exact_internal::MinNormPoint m =
        exact_internal::wolfe_min_norm(oracle, n, reach_, kWitnessIterations);
    Scalar total = 0;
    for (int k = 0; k < m.size; ++k) total += m.weights[k];
    r.weights_a = VectorX::Zero(a_.size());
    r.weights_b = VectorX::Zero(b_.size());
    r.point_a.setZero();
    r.point_b.setZero();
    for (int k = 0; k < m.size; ++k) {
      const Scalar w = m.weights[k] / total;
      r.weights_a(m.corral[k].ia) += w;
      r.weights_b(m.corral[k].ib) += w;
      r.point_a += w * a_.point(m.corral[k].ia);
      r.point_b += w * b_.point(m.corral[k].ib);
    }
    r.witness_residual = (r.point_b - r.point_a - shift).norm();
    r.feature_slack = slack;
  }

  PenetrationBounds result() {
    if (!(separation_ > -kInfinity)) offer_direction(Vector3::UnitX());
    PenetrationBounds r;
    r.normal = normal_;
    r.separation = separation_;
    r.lower = lower();
    r.upper = upper_;
    r.iterations = iterations_;
    r.proven = upper_ - r.lower <= tolerance_;
    witnesses(r);
    return r;
  }

  BodyView a_;
  BodyView b_;
  Scalar coordinate_;
  Scalar margin_;
  Scalar reach_;
  Scalar tolerance_;
  int max_iterations_;
  Workspace& ws_;
  Vector3 normal_ = Vector3::UnitX();
  Scalar separation_ = -kInfinity;
  Scalar upper_ = kInfinity;
  exact_internal::MinNormPoint nearest_;
  Scalar nearest_norm_ = kInfinity;
  bool nearest_ready_ = false;
  int iterations_ = 0;
};

}  // namespace

PenetrationBounds penetration(const VertexMatrix& a, const Hull& hull_a, const VertexMatrix& b,
                              const Hull& hull_b, const Vector3& hint, Scalar tolerance,
                              int max_iterations) {
  Solver solver(a, hull_a, b, hull_b, tolerance, max_iterations);
  return solver.solve(hint);
}

}  // namespace swarmcollide::detail
