#include "swarmcollide/geometry/pose.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace swarmcollide {

void validate_pose(const Pose& pose, const char* name) {
  if (!pose.rotation.allFinite() || !pose.translation.allFinite()) {
    throw std::invalid_argument(std::string(name) + " has a NaN or infinite entry");
  }
  if (pose.has_identity_rotation()) return;
  const Scalar orthogonality = (pose.rotation.transpose() * pose.rotation - Matrix3::Identity())
                                   .cwiseAbs()
                                   .maxCoeff();
  const Scalar determinant = pose.rotation.determinant();
  if (!(orthogonality <= kRotationTolerance) || !(std::abs(determinant - 1) <= kRotationTolerance)) {
    throw std::invalid_argument(
        std::string(name) + " is not a rigid motion: its rotation must satisfy R^T R = I and " +
        "det R = 1 to within 1e-9 (got |R^T R - I| = " + std::to_string(orthogonality) +
        ", det R = " + std::to_string(determinant) +
        "); scaling and reflection are not poses, scale the points instead");
  }
}

}  // namespace swarmcollide
