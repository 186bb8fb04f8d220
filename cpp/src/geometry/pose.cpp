#include "swarmcollide/geometry/pose.hpp"

#include "../detail/number_text.hpp"
#include "pose_check.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace swarmcollide {

namespace {

// |R^T R - I| (largest entry) and det R: how far a rotation is from a proper rotation.
struct Deviation {
  Scalar orthogonality;
  Scalar determinant;
};

// Inline: every query checks a pose with it, and its call was a tenth of the check.
[[gnu::always_inline]] inline Deviation deviation(const Matrix3& r) {
  // R^T R - I is symmetric: its six distinct entries, the columns' dot products (written out:
  // every row of a batch checks its poses).
  const auto dot = [&r](int i, int j) {
    return r(0, i) * r(0, j) + r(1, i) * r(1, j) + r(2, i) * r(2, j);
  };
  const Scalar orthogonality =
      std::max({std::abs(dot(0, 0) - 1), std::abs(dot(1, 1) - 1), std::abs(dot(2, 2) - 1),
                std::abs(dot(0, 1)), std::abs(dot(0, 2)), std::abs(dot(1, 2))});
  return {orthogonality, r.determinant()};
}

bool finite(const Pose& pose) {
  // x - x is 0 for a finite x and NaN otherwise, and a NaN stays in the sum.
  Scalar sum = 0;
  for (int k = 0; k < 9; ++k) sum += pose.rotation.data()[k] - pose.rotation.data()[k];
  for (int k = 0; k < 3; ++k) sum += pose.translation(k) - pose.translation(k);
  return sum == 0;
}

bool rigid(const Deviation& d) {
  return d.orthogonality <= kRotationTolerance &&
         std::abs(d.determinant - 1) <= kRotationTolerance;
}

bool finite_translation(const Pose& pose) {
  const Vector3& t = pose.translation;
  return (t.x() - t.x()) + (t.y() - t.y()) + (t.z() - t.z()) == 0;
}

// True when the pose is valid. No message is built here: batches and scenes check thousands of
// poses a call, nearly all of them valid. The rotation's entries need no test of their own: the
// identity is finite, and every entry is a factor of a product in the determinant, so one that is
// infinite or NaN makes it infinite or NaN, which rigid() rejects.
bool valid(const Pose& pose) {
  return finite_translation(pose) &&
         (pose.has_identity_rotation() || rigid(deviation(pose.rotation)));
}

}  // namespace

namespace detail {

bool valid_pose(const Pose& pose, bool turned) {
  return finite_translation(pose) && (!turned || rigid(deviation(pose.rotation)));
}

}  // namespace detail

namespace {

// What is wrong with an invalid pose, after its name.
std::string problem(const Pose& pose) {
  if (!finite(pose)) return " has a NaN or infinite entry";
  const Deviation d = deviation(pose.rotation);
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
