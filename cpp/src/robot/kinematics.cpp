#include "swarmcollide/robot/kinematics.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "../detail/number_text.hpp"

namespace swarmcollide {

namespace {

constexpr Scalar kTwoPi = 6.283185307179586476925286766559;

// Joint values to the last digit that tells them apart: a limit missed by a roundoff must show.
std::string number(Scalar x) { return detail::shortest_number_text(x); }

// Where a value is, as the caller indexes what they gave: a table's row (its joint named), or a
// configuration given alone's own index (q[0] of a single configuration is its first value, not
// the row it was copied to).
struct Place {
  std::size_t row;
  int value;
};

std::string where(Place place, const Joint& joint) {
  const std::size_t index =
      place.row == kSingleConfiguration ? static_cast<std::size_t>(place.value) : place.row;
  return "q[" + std::to_string(index) + "], joint '" + joint.name + "'";
}

[[noreturn]] void outside(Place place, const Joint& joint, Scalar value, const char* fix) {
  throw std::invalid_argument(where(place, joint) + ": " + number(value) +
                              " is outside its limits [" + number(joint.lower) + ", " +
                              number(joint.upper) + "]; " + fix);
}

// `value` within the joint's limits as `mode` says.
Scalar admitted(Scalar value, const Joint& joint, LimitMode mode, Place row) {
  if (!std::isfinite(value)) {
    throw std::invalid_argument(where(row, joint) + ": " + number(value) +
                                " is not a finite number");
  }
  if (value >= joint.lower && value <= joint.upper) return value;
  switch (mode) {
    case LimitMode::raise:
      outside(row, joint, value, "pass limits='clamp' or limits='wrap' to bring it within");
    case LimitMode::clamp:
      return value < joint.lower ? joint.lower : joint.upper;
    case LimitMode::wrap:
      break;
  }
  if (joint.type != JointType::revolute) {
    outside(row, joint, value, "limits='wrap' applies to revolute joints only (this one slides)");
  }
  // The angle of the same pose nearest above the lower limit.
  const Scalar wrapped = joint.lower + std::fmod(std::fmod(value - joint.lower, kTwoPi) + kTwoPi,
                                                 kTwoPi);
  if (wrapped <= joint.upper) return wrapped;
  // Rounding can put an angle a hair above the lower limit's turn: the limit itself is the pose.
  if (kTwoPi - (wrapped - joint.lower) <= 1e-12 * kTwoPi) return joint.lower;
  outside(row, joint, value, "no turn by a multiple of 2 pi brings it within; use limits='clamp'");
}

// The child's pose relative to the joint frame at joint value `value`.
Pose motion(const Joint& joint, Scalar value) {
  Pose pose;
  const Scalar amount = value - joint.reference;
  if (joint.type == JointType::prismatic) {
    pose.translation = amount * joint.axis;
  } else {
    pose.rotation = Eigen::AngleAxis<Scalar>(amount, joint.axis).toRotationMatrix();
  }
  return pose;
}

// compose(placed, motion(joint, value)) for a turn by `amount` about sign e_k, bitwise: Eigen's
// AngleAxis matrix about sign e_k has c on the other two diagonal entries, (1 - c) + c on the
// k-th, +-s off the diagonal in the plane of the turn and exact zeros elsewhere, so each entry of
// the product is one or two nonzero products summed (a sum with exact zeros added, which is
// exact), and the translation is the placed one (a product with zeros added to it).
void turned_about_coordinate_axis(const Pose& placed, int k, Scalar sign, Scalar amount,
                                  Pose& pose) {
  const Scalar s = std::sin(amount) * sign;
  const Scalar c = std::cos(amount);
  const Scalar diagonal = (1 - c) + c;
  const int i = (k + 1) % 3;
  const int j = (k + 2) % 3;
  const Matrix3& r = placed.rotation;
  // The turn's matrix: M(i, i) = M(j, j) = c, M(j, i) = s, M(i, j) = -s, M(k, k) = diagonal.
  pose.rotation.col(i) = r.col(i) * c + r.col(j) * s;
  pose.rotation.col(j) = r.col(i) * -s + r.col(j) * c;
  pose.rotation.col(k) = r.col(k) * diagonal;
  pose.translation = placed.translation;
}

// compose(outer, inner) into `pose` (not aliasing either): the forward kinematics' step, made
// in place rather than through a call and a returned copy per joint.
inline void composed(const Pose& outer, const Pose& inner, Pose& pose) {
  pose.rotation.noalias() = outer.rotation * inner.rotation;
  pose.translation.noalias() = outer.rotation * inner.translation;
  pose.translation += outer.translation;
}

// compose(outer, origin) into `pose` for an origin that turns about e_k (OriginZeros) with at
// most two nonzero coordinates in its translation, with no product by its exact zeros: the same
// pose bit for bit wherever an entry is nonzero. Each entry of the product is a sum of three
// products, of which at most two are then not exact zeros (or times 1, exact), and two rounded
// products summed with exact zeros give the same rounded sum in any order.
template <int k>
void placed_by_turn(const Pose& outer, const Pose& origin, const OriginZeros& zeros, Pose& pose) {
  constexpr int i = (k + 1) % 3;
  constexpr int j = (k + 2) % 3;
  const Matrix3& r = outer.rotation;
  const Matrix3& o = origin.rotation;
  pose.rotation.col(k) = r.col(k);
  pose.rotation.col(i) = r.col(i) * o(i, i) + r.col(j) * o(j, i);
  pose.rotation.col(j) = r.col(i) * o(i, j) + r.col(j) * o(j, j);
  const Vector3& t = origin.translation;
  if (zeros.count == 0) {
    pose.translation = outer.translation;
  } else if (zeros.count == 1) {
    pose.translation = r.col(zeros.axes[0]) * t[zeros.axes[0]] + outer.translation;
  } else {
    pose.translation =
        (r.col(zeros.axes[0]) * t[zeros.axes[0]] + r.col(zeros.axes[1]) * t[zeros.axes[1]]) +
        outer.translation;
  }
}

// compose(outer, origin) into `pose` (not aliasing either), by placed_by_turn where the origin's
// zeros allow. (A Panda joint's origin turns about e_x or e_z with at most two nonzero
// coordinates: 15 products rather than 36.)
inline void placed_by(const Pose& outer, const Pose& origin, const OriginZeros& zeros,
                      Pose& pose) {
  if (zeros.count > 2) {
    composed(outer, origin, pose);
    return;
  }
  switch (zeros.turn_axis) {
    case 0:
      placed_by_turn<0>(outer, origin, zeros, pose);
      return;
    case 1:
      placed_by_turn<1>(outer, origin, zeros, pose);
      return;
    case 2:
      placed_by_turn<2>(outer, origin, zeros, pose);
      return;
    default:
      composed(outer, origin, pose);
  }
}

}  // namespace

Pose compose(const Pose& outer, const Pose& inner) {
  Pose pose;
  composed(outer, inner, pose);
  return pose;
}

namespace {

// The poses read dof values a row: a row of another length would be read past its end.
void require_dof_values(const RobotModel& model, Eigen::Index count) {
  if (count != model.dof()) {
    throw std::invalid_argument("q must have " + std::to_string(model.dof()) +
                                " values per configuration (one per moving joint), got " +
                                std::to_string(count));
  }
}

}  // namespace

void admit_configuration(const RobotModel& model, const Scalar* q, Eigen::Index count,
                         LimitMode mode, std::size_t row, Scalar* admitted_q) {
  require_dof_values(model, count);
  for (int d = 0; d < model.dof(); ++d) {
    const Joint& joint = model.joints()[model.moving_joints()[d]];
    admitted_q[d] = admitted(q[d], joint, mode, {row, d});
  }
}

Configurations admit_configurations(const RobotModel& model, const Configurations& q,
                                    LimitMode mode) {
  require_dof_values(model, q.cols());
  Configurations result(q.rows(), q.cols());
  for (Eigen::Index i = 0; i < q.rows(); ++i) {
    admit_configuration(model, q.row(i).data(), q.cols(), mode, static_cast<std::size_t>(i),
                        result.row(i).data());
  }
  return result;
}

void link_poses(const RobotModel& model, const Scalar* q, std::vector<Pose>& links) {
  links.assign(model.links().size(), Pose{});
  link_poses(model, q, model.joint_order(), links);
}

void link_poses(const RobotModel& model, const Scalar* q, const std::vector<int>& joints,
                std::vector<Pose>& links) {
  for (int j : joints) {
    const Joint& joint = model.joints()[j];
    const int dof = model.driving_dof(j);
    const OriginZeros& zeros = model.joint_origin_zeros(j);
    if (dof < 0) {
      placed_by(links[joint.parent], joint.origin, zeros, links[joint.child]);
      continue;
    }
    Pose placed;
    placed_by(links[joint.parent], joint.origin, zeros, placed);
    const Scalar value = model.joint_value(j, q[dof]);
    const int k = model.axis_coordinate(j);
    if (k < 0) {
      links[joint.child] = compose(placed, motion(joint, value));
    } else {
      turned_about_coordinate_axis(placed, k, joint.axis[k], value - joint.reference,
                                   links[joint.child]);
    }
  }
}

namespace {

// `pose` as a row-major homogeneous transform at `t`.
void write_transform(const Pose& pose, Scalar* t) {
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) t[4 * r + c] = pose.rotation(r, c);
    t[4 * r + 3] = pose.translation(r);
  }
  t[12] = t[13] = t[14] = 0;
  t[15] = 1;
}

}  // namespace

Pose geometry_pose(const RobotModel& model, const std::vector<Pose>& links, int g) {
  const Geometry& geometry = model.geometries()[static_cast<std::size_t>(g)];
  if (geometry.link < 0) return geometry.origin;
  Pose pose;
  placed_by(links[static_cast<std::size_t>(geometry.link)], geometry.origin,
            model.geometry_origin_zeros(g), pose);
  return pose;
}

void forward_kinematics(const RobotModel& model, const Configurations& q, Scalar* transforms) {
  require_dof_values(model, q.cols());
  std::vector<Pose> links;
  for (Eigen::Index i = 0; i < q.rows(); ++i) {
    link_poses(model, q.row(i).data(), links);
    for (const Pose& pose : links) {
      write_transform(pose, transforms);
      transforms += 16;
    }
  }
}

void geometry_poses(const RobotModel& model, const Configurations& q, Scalar* transforms) {
  require_dof_values(model, q.cols());
  std::vector<Pose> links;
  for (Eigen::Index i = 0; i < q.rows(); ++i) {
    link_poses(model, q.row(i).data(), links);
    for (std::size_t g = 0; g < model.geometries().size(); ++g) {
      write_transform(geometry_pose(model, links, static_cast<int>(g)), transforms);
      transforms += 16;
    }
  }
}

}  // namespace swarmcollide
