// The dual's exact finish for distances; private to the library's sources.
#pragma once

#include "../geometry/framed_body.hpp"
#include "best_bounds.hpp"
#include "wolfe_min_norm.hpp"

namespace swarmcollide::detail {

/// Exact subproblems on the supporting features, which turn a good direction into the exact
/// distance: the nearest points of the features' hulls (Wolfe's algorithm) give an upper bound
/// and a direction, whose separation gives a lower bound. Its buffers are thread-local.
class DistanceFinish {
 public:
  /// `slack` (frame units): how far below a supporting plane a point still counts as on the
  /// feature; `max_iterations`: the cap of each Wolfe solve.
  DistanceFinish(const FramedPair& pair, Scalar slack, int max_iterations);

  /// From direction `n` (support points climbing from, and returned in, the hints): solves the
  /// subproblem of the two supporting features; while the bounds still differ, the supports
  /// along the subproblem's direction lie outside the features (otherwise the subproblem's
  /// optimum would be separated by it), so the features grow by them and the subproblem is
  /// solved again, a few times before the caller's search takes over. Offers every bound found;
  /// returns whether the bounds settle `goal`.
  bool from(const Vector3& n, int& hint_a, int& hint_b, BestBounds& bounds, Goal goal);

  /// Wolfe's algorithm on the whole Minkowski difference B - A from the unit direction `start`
  /// (GJK with Wolfe's corrals), its supports climbing from, and returned in, the hints: the
  /// exact nearest points, or a common point (with an intersection proof when its corral encloses
  /// the origin) when the bodies overlap, which no direction can show. Stops as soon as its bounds
  /// settle `goal`, so a verdict stops at the first separating direction or common point. Offers
  /// the separation along `start` and the supporting points' distance, then the witnesses and
  /// the separation along them; returns whether the bounds settle `goal`. A distance, and a
  /// verdict without `enclosure`, skip the intersection proof where the witnesses already prove
  /// contact (contact_witness_of); a verdict with it keeps the enclosing tetrahedron for whoever
  /// reads `intersection_proven` (a scene caches it, a compound screen reads it). `first`, when
  /// given, is the oracle's point along `start` from the same hints, already asked by the caller
  /// (counted here as the oracle call it replaces).
  bool whole(const Vector3& start, int& hint_a, int& hint_b, BestBounds& bounds, Goal goal,
             bool enclosure = true, const OraclePoint* first = nullptr);
  /// whole() going on from `corral`, where a Wolfe walk on the same pair stopped (overlap_first on
  /// curved pairs): its last point is the oracle's along the unit direction `start`, asked
  /// already, and its nearest point is not yet found (x infinite). Two ellipsoids start again
  /// along `start` (their secant steps need their own samples).
  bool whole_from_corral(const Vector3& start, const MinNormPoint& corral, int& hint_a,
                         int& hint_b, BestBounds& bounds, Goal goal, bool enclosure);

  long evaluations() const { return evaluations_; }

 private:
  // whole() for two ellipsoids: Wolfe's steps along secant directions (secant_search.cpp).
  bool whole_secant(const Vector3& start, int& hint_a, int& hint_b, BestBounds& bounds,
                    Goal goal, bool enclosure);
  // whole() for curved pairs but two ellipsoids, in a file of its own (curved_search.cpp), with
  // their supports inline.
  bool whole_curved(const Vector3& start, int& hint_a, int& hint_b, BestBounds& bounds, Goal goal,
                    bool enclosure, const OraclePoint* first_point);
  // whole()'s search from a corral, the same way (curved_search.cpp).
  bool walk_from_corral(const Vector3& start, const MinNormPoint& corral, int& hint_a,
                        int& hint_b, BestBounds& bounds, Goal goal, bool enclosure);
  void feature(const FramedBody& body, const Vector3& n, int& hint, std::vector<int>& found);
  Witness nearest_between(const std::vector<int>& fa, const std::vector<int>& fb,
                          const Vector3& start);

  const FramedPair& pair_;
  const Scalar slack_;
  const int max_iterations_;
  long evaluations_ = 0;
};

}  // namespace swarmcollide::detail
