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
    }
  }

  Scalar lower() const { return lower_; }
  /// The direction of the best lower bound (meaningful once one was offered).
  const Vector3& normal() const { return normal_; }
  const Witness& upper() const { return upper_; }

  bool reached(const FramedPair& pair, Goal goal) const {
    return goal_reached(pair, goal, lower_, upper_.distance, upper_.encloses_origin);
  }
  /// Contact is proven (the bodies are within the tolerance, or share a point).
  bool touching(const FramedPair& pair) const {
    return upper_.encloses_origin || upper_.distance + kFrameRounding <= pair.tolerance;
  }

  Answer answer(const FramedPair& pair) const {
    Answer a = answer_from_witness(pair, upper_);
    a.lower = lower_;
    a.direction = normal_;
    return a;
  }

 private:
  Scalar lower_ = -std::numeric_limits<Scalar>::infinity();
  Vector3 normal_ = Vector3::UnitX();
  Witness upper_;
};

}  // namespace swarmcollide::detail
