#include "swarmcollide/robot/robot_model.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <unordered_set>
#include <utility>

#include "../geometry/unit_direction.hpp"

namespace swarmcollide {

namespace {

std::string joint_label(const Joint& joint) { return "joint '" + joint.name + "'"; }

void check_link(int link, int links, const Joint& joint, const char* role) {
  if (link < 0 || link >= links) {
    throw std::invalid_argument(joint_label(joint) + ": " + role + " link index " +
                                std::to_string(link) + " is not in [0, " + std::to_string(links) +
                                ")");
  }
}

void check_joint(Joint& joint, int links) {
  check_link(joint.parent, links, joint, "parent");
  check_link(joint.child, links, joint, "child");
  validate_pose(joint.origin, (joint_label(joint) + " origin").c_str());
  // -1 alone means none: another negative index is a mistake, which was read as none.
  if (joint.mimic < -1) {
    throw std::invalid_argument(joint_label(joint) +
                                ": mimic must be a joint index, or -1 for none, got " +
                                std::to_string(joint.mimic));
  }
  if (joint.type == JointType::fixed) return;
  // Without overflow or underflow in the squares: axes of 1e300 or 1e-300 are finite and nonzero.
  const Scalar norm = detail::robust_length(joint.axis);
  if (!std::isfinite(norm) || norm == 0) {
    throw std::invalid_argument(joint_label(joint) + ": the axis must be finite and nonzero");
  }
  joint.axis /= norm;
  if (!std::isfinite(joint.reference)) {
    throw std::invalid_argument(joint_label(joint) + ": the reference value must be finite");
  }
  if (joint.type == JointType::continuous) {
    joint.lower = -INFINITY;
    joint.upper = INFINITY;
    return;
  }
  if (std::isnan(joint.lower) || std::isnan(joint.upper) || joint.lower > joint.upper) {
    throw std::invalid_argument(joint_label(joint) + ": limits must satisfy lower <= upper, got [" +
                                std::to_string(joint.lower) + ", " + std::to_string(joint.upper) +
                                "]");
  }
}

OriginZeros origin_zeros(const Pose& origin) {
  OriginZeros zeros;
  const Matrix3& r = origin.rotation;
  for (int k = 0; k < 3 && zeros.turn_axis < 0; ++k) {
    const int i = (k + 1) % 3;
    const int j = (k + 2) % 3;
    if (r(k, k) == 1 && r(k, i) == 0 && r(k, j) == 0 && r(i, k) == 0 && r(j, k) == 0) {
      zeros.turn_axis = k;
    }
  }
  int count = 0;
  for (int k = 0; k < 3; ++k) {
    if (origin.translation[k] == 0) continue;
    if (count < 2) zeros.axes[count] = k;
    ++count;
  }
  zeros.count = std::min(count, 3);
  return zeros;
}

// k when `axis` is the unit vector e_k or -e_k exactly, else -1.
int coordinate_axis(const Vector3& axis) {
  for (int k = 0; k < 3; ++k) {
    const int i = (k + 1) % 3;
    const int j = (k + 2) % 3;
    if (axis[i] == 0 && axis[j] == 0 && std::abs(axis[k]) == 1) return k;
  }
  return -1;
}

// Joint j's mimic (j mimics one) against its rules, each named when broken: a mimic joint moves,
// follows a moving joint that mimics none (its own degree of freedom, `dof_of_joint` >= 0), with
// a finite multiplier and offset.
void check_mimic(const std::vector<Joint>& joints, const std::vector<int>& dof_of_joint, int j) {
  const Joint& joint = joints[static_cast<std::size_t>(j)];
  const std::string label = joint_label(joint) + ": ";
  if (joint.type == JointType::fixed) {
    throw std::invalid_argument(label + "a fixed joint cannot mimic another (a mimic joint "
                                        "moves): make it revolute, continuous or prismatic, or "
                                        "drop its mimic");
  }
  if (joint.mimic >= static_cast<int>(joints.size())) {
    throw std::invalid_argument(label + "mimic must be a joint index, or -1 for none, got " +
                                std::to_string(joint.mimic) + " (the model has " +
                                std::to_string(joints.size()) + " joints)");
  }
  const Joint& followed = joints[static_cast<std::size_t>(joint.mimic)];
  if (joint.mimic == j) {
    throw std::invalid_argument(label + "it mimics itself; a mimic joint follows another, "
                                        "moving joint");
  }
  if (followed.type == JointType::fixed) {
    throw std::invalid_argument(label + "it mimics joint '" + followed.name +
                                "', which is fixed; a mimic joint follows a moving joint");
  }
  if (dof_of_joint[static_cast<std::size_t>(joint.mimic)] < 0) {
    // `followed` moves, so it mimics a joint itself.
    const int source = followed.mimic;
    const std::string& name = joints[static_cast<std::size_t>(source)].name;
    throw std::invalid_argument(
        label + "it mimics joint '" + followed.name + "', which mimics joint '" + name +
        "'; a mimic joint follows a joint that mimics none" +
        (source != j && dof_of_joint[static_cast<std::size_t>(source)] >= 0
             ? " (mimic '" + name + "', with the two multipliers and offsets composed)"
             : std::string()));
  }
  if (!std::isfinite(joint.multiplier)) {
    throw std::invalid_argument(label + "its mimic multiplier must be finite, got " +
                                std::to_string(joint.multiplier));
  }
  if (!std::isfinite(joint.offset)) {
    throw std::invalid_argument(label + "its mimic offset must be finite, got " +
                                std::to_string(joint.offset));
  }
}

void check_unique(const std::string& name, std::unordered_set<std::string>& seen,
                  const char* kind) {
  if (!seen.insert(name).second) {
    throw std::invalid_argument(std::string("two ") + kind + "s are named '" + name +
                                "': names must be unique");
  }
}

}  // namespace

RobotModel::RobotModel(std::vector<Link> links, std::vector<Joint> joints,
                       std::vector<Geometry> geometries)
    : links_(std::move(links)), joints_(std::move(joints)), geometries_(std::move(geometries)) {
  const int link_count = static_cast<int>(links_.size());
  if (link_count == 0) throw std::invalid_argument("a robot needs at least one link");
  std::unordered_set<std::string> names;
  for (const Link& link : links_) check_unique(link.name, names, "link");
  names.clear();
  parent_joint_.assign(links_.size(), -1);
  dof_of_joint_.assign(joints_.size(), -1);
  for (std::size_t j = 0; j < joints_.size(); ++j) {
    Joint& joint = joints_[j];
    check_unique(joint.name, names, "joint");
    check_joint(joint, link_count);
    int& parent = parent_joint_[static_cast<std::size_t>(joint.child)];
    if (parent >= 0) {
      throw std::invalid_argument(joint_label(joint) + ": link '" + links_[joint.child].name +
                                  "' is already the child of joint '" + joints_[parent].name +
                                  "'; each link has one parent joint");
    }
    parent = static_cast<int>(j);
    if (joint.type != JointType::fixed && joint.mimic < 0) {
      dof_of_joint_[j] = static_cast<int>(moving_.size());
      moving_.push_back(static_cast<int>(j));
    }
  }
  driving_dof_ = dof_of_joint_;
  for (std::size_t j = 0; j < joints_.size(); ++j) {
    const Joint& joint = joints_[j];
    if (joint.mimic < 0) continue;
    check_mimic(joints_, dof_of_joint_, static_cast<int>(j));
    driving_dof_[j] = dof_of_joint_[joint.mimic];
  }
  int root = -1;
  for (int l = 0; l < link_count; ++l) {
    if (parent_joint_[l] >= 0) continue;
    if (root >= 0) {
      throw std::invalid_argument("links '" + links_[root].name + "' and '" + links_[l].name +
                                  "' both have no parent joint: the links must form one tree");
    }
    root = l;
  }
  if (root < 0) throw std::invalid_argument("the joints form a cycle: no link is the root");
  // Joints from the root outwards: a link's pose is known before its children's.
  std::vector<std::vector<int>> children(links_.size());
  for (std::size_t j = 0; j < joints_.size(); ++j) {
    children[joints_[j].parent].push_back(static_cast<int>(j));
  }
  std::vector<int> frontier{root};
  while (!frontier.empty()) {
    const int link = frontier.back();
    frontier.pop_back();
    for (int j : children[link]) {
      order_.push_back(j);
      frontier.push_back(joints_[j].child);
    }
  }
  if (order_.size() != joints_.size()) {
    throw std::invalid_argument("the joints form a cycle: some links are not reached from '" +
                                links_[root].name + "'");
  }
  names.clear();
  bool compound = false;
  for (Geometry& geometry : geometries_) {
    if (geometry.parts) {
      geometry.body = geometry.parts->envelope();
      compound = true;
    }
  }
  if (compound) {
    for (const Geometry& geometry : geometries_) {
      if (geometry.parts) {
        compounds_.emplace_back(*geometry.parts);
      } else if (geometry.body.curved()) {
        compounds_.emplace_back();
      } else {
        compounds_.emplace_back(CompoundBody(geometry.body));
      }
    }
  }
  for (const Geometry& geometry : geometries_) {
    check_unique(geometry.name, names, "geometry");
    if (geometry.link < -1 || geometry.link >= link_count) {
      throw std::invalid_argument("geometry '" + geometry.name + "': link index " +
                                  std::to_string(geometry.link) + " is not in [-1, " +
                                  std::to_string(link_count) + ")");
    }
    validate_pose(geometry.origin, ("geometry '" + geometry.name + "' origin").c_str());
    geometry_zeros_.push_back(origin_zeros(geometry.origin));
  }
  for (const Joint& joint : joints_) {
    joint_zeros_.push_back(origin_zeros(joint.origin));
    axis_coordinate_.push_back(joint.type == JointType::prismatic ? -1
                                                                  : coordinate_axis(joint.axis));
  }
}

}  // namespace swarmcollide
