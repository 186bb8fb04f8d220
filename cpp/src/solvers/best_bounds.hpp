// The best bounds a search has found; private to the library's sources.
#pragma once

#include <limits>

#include "../queries/verdict.hpp"
#include "witness.hpp"

namespace swarmcollide::detail {

/// The best lower bound (a direction and its separation) and upper bound (a witness) found so
/// far, and whether they settle a goal (asked of verdict.hpp, the one home of that test).
class BestBounds {
 public:
  void offer_lower(const Vector3& n, Scalar s) {
    if (s > lower_) {
      lower_ = s;
      normal_ = n;
    }
  }
  void offer_upper(const Witness& w) {
    if (w.distance < upper_.distance || (w.encloses_origin && !upper_.encloses_origin)) {
      upper_ = w;
      points_pending_ = false;
    }
  }
  /// The witness of the single pair of points (x_ia, y_ib), `distance` apart (as vertex_witness
  /// computes it): its points are placed only if it is still the best when the answer is made
  /// (a search's first pair rarely is).
  void offer_upper_vertex(int ia, int ib, Scalar distance) {
    if (!(distance < upper_.distance)) return;
    upper_.ia = {ia, 0, 0, 0};
    upper_.ib = {ib, 0, 0, 0};
    upper_.weights = {1, 0, 0, 0};
    upper_.size = 1;
    upper_.distance = distance;
    upper_.encloses_origin = false;
    points_pending_ = true;
  }

  Scalar lower() const { return lower_; }
  /// The direction of the best lower bound (meaningful once one was offered).
  const Vector3& normal() const { return normal_; }
  /// The best upper bound (its points unset while an offered vertex pair's are pending: read its
  /// distance, or the answer).
  const Witness& upper() const { return upper_; }

  bool reached(const FramedPair& pair, Goal goal) const {
    return goal_reached(pair, goal, lower_, upper_.distance, upper_.encloses_origin);
  }
  /// A verdict is asked and no search can prove it (verdict_out_of_reach).
  bool out_of_reach(const FramedPair& pair, Goal goal) const {
    return goal == Goal::verdict && verdict_out_of_reach(pair, lower_, upper_.distance);
  }
  /// Contact is proven (the bodies are within the tolerance, or share a point).
  bool touching(const FramedPair& pair) const {
    return upper_.encloses_origin || upper_.distance + kFrameRounding <= pair.tolerance;
  }

  Answer answer(const FramedPair& pair) const {
    Answer a = answer_from_witness(pair, upper_);
    if (points_pending_) {
      a.point_a = pair.a.vertex(upper_.ia[0]);
      a.point_b = pair.b.vertex(upper_.ib[0]);
    }
    a.lower = lower_;
    a.direction = normal_;
    return a;
  }

 private:
  Scalar lower_ = -std::numeric_limits<Scalar>::infinity();
  Vector3 normal_ = Vector3::UnitX();
  Witness upper_;
  // upper_ is an offered vertex pair whose points are not yet placed.
  bool points_pending_ = false;
};

}  // namespace swarmcollide::detail
