#include "swarmcollide/geometry/pose.hpp"

#include "../detail/number_text.hpp"
#include "pose_check.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace swarmcollide {

namespace {

using detail::finite_translation;
using detail::rigid;
using detail::rotation_deviation;

bool finite(const Pose& pose) {
  // x - x is 0 for a finite x and NaN otherwise, and a NaN stays in the sum.
  Scalar sum = 0;
  for (int k = 0; k < 9; ++k) sum += pose.rotation.data()[k] - pose.rotation.data()[k];
  for (int k = 0; k < 3; ++k) sum += pose.translation(k) - pose.translation(k);
  return sum == 0;
}

// True when the pose is valid. No message is built here: batches and scenes check thousands of
// poses a call, nearly all of them valid (detail::valid_pose says why the rotation's entries need
// no test of their own).
bool valid(const Pose& pose) {
  return finite_translation(pose) &&
         (pose.has_identity_rotation() || rigid(rotation_deviation(pose.rotation)));
}

// What is wrong with an invalid pose, after its name.
std::string problem(const Pose& pose) {
  if (!finite(pose)) return " has a NaN or infinite entry";
  const detail::RotationDeviation d = rotation_deviation(pose.rotation);
  return " is not a rigid motion: its rotation must satisfy R^T R = I and det R = 1 to within "
         "1e-9 (got |R^T R - I| = " +
         detail::number_text(d.orthogonality, 3) + ", det R = " + detail::number_text(d.determinant, 12) +
         "); scaling and reflection are not poses, scale the points instead";
}

}  // namespace

void validate_pose(const Pose& pose, const char* name) {
  if (!valid(pose)) throw std::invalid_argument(std::string(name) + problem(pose));
}

void validate_pose(const Pose& pose, const char* name, std::size_t index) {
  if (!valid(pose)) {
    throw std::invalid_argument(std::string(name) + "[" + std::to_string(index) + "]" +
                                problem(pose));
  }
}

}  // namespace swarmcollide
