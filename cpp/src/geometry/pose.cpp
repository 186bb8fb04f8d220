#include "swarmcollide/geometry/pose.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

namespace swarmcollide {

namespace {

// A number as printf's %g writes it with `digits` significant digits: std::to_string's fixed six
// decimals print a deviation of 3e-9 as 0.000000.
std::string general(Scalar x, int digits) {
  char text[40];
  std::snprintf(text, sizeof text, "%.*g", digits, x);
  return text;
}

// What is wrong with the pose, after its name; empty when nothing is. Messages are built only
// for invalid poses: scenes validate thousands of poses a frame.
std::string problem(const Pose& pose) {
  if (!pose.rotation.allFinite() || !pose.translation.allFinite()) {
    return " has a NaN or infinite entry";
  }
  if (pose.has_identity_rotation()) return {};
  // R^T R - I is symmetric: its six distinct entries, the columns' dot products.
  const Matrix3& r = pose.rotation;
  Scalar orthogonality = 0;
  for (int i = 0; i < 3; ++i) {
    for (int j = i; j < 3; ++j) {
      const Scalar entry = r.col(i).dot(r.col(j)) - (i == j ? 1 : 0);
      orthogonality = std::max(orthogonality, std::abs(entry));
    }
  }
  const Scalar determinant = pose.rotation.determinant();
  if (!(orthogonality <= kRotationTolerance) ||
      !(std::abs(determinant - 1) <= kRotationTolerance)) {
    return " is not a rigid motion: its rotation must satisfy R^T R = I and det R = 1 to within "
           "1e-9 (got |R^T R - I| = " +
           general(orthogonality, 3) + ", det R = " + general(determinant, 12) +
           "); scaling and reflection are not poses, scale the points instead";
  }
  return {};
}

}  // namespace

void validate_pose(const Pose& pose, const char* name) {
  const std::string what = problem(pose);
  if (!what.empty()) throw std::invalid_argument(std::string(name) + what);
}

void validate_pose(const Pose& pose, const char* name, std::size_t index) {
  const std::string what = problem(pose);
  if (!what.empty()) {
    throw std::invalid_argument(std::string(name) + "[" + std::to_string(index) + "]" + what);
  }
}

}  // namespace swarmcollide
