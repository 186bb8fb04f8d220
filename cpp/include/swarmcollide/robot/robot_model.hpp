#pragma once

#include <optional>
#include <string>
#include <vector>

#include "swarmcollide/geometry/compound_body.hpp"
#include "swarmcollide/geometry/convex_polyhedron.hpp"
#include "swarmcollide/geometry/pose.hpp"
#include "swarmcollide/types.hpp"

namespace swarmcollide {

/// How a joint moves its child link: URDF's joint types (MJCF's hinge is revolute, or continuous
/// when unlimited; its slide is prismatic; a body without joints is fixed to its parent).
enum class JointType { revolute, continuous, prismatic, fixed };

/// A link: a rigid frame of the kinematic tree.
struct Link {
  std::string name;
};

/// A joint from its parent link to its child link: the child's frame is
/// `parent * origin * motion(q - reference)`, where the motion turns about `axis` (revolute,
/// continuous) or slides along it (prismatic) through the joint frame's origin.
struct Joint {
  std::string name;
  JointType type = JointType::fixed;
  /// Link indices.
  int parent = 0;
  int child = 0;
  /// The joint frame in the parent link's frame.
  Pose origin;
  /// The axis in the joint frame; normalised by the model (any nonzero length is accepted).
  Vector3 axis = Vector3::UnitZ();
  /// The joint's limits; -inf and inf when it has none (continuous joints).
  Scalar lower = 0;
  Scalar upper = 0;
  /// The joint value at which the child sits at `origin` (MJCF's `ref`; 0 for URDF).
  Scalar reference = 0;
  /// The index of the joint this one mimics (URDF's `<mimic>`), -1 for none: its value is then
  /// `multiplier * value(mimicked) + offset`, and it is no degree of freedom of its own.
  int mimic = -1;
  Scalar multiplier = 1;
  Scalar offset = 0;
};

/// A body fixed to a link (or to the world, for an obstacle: `link` = -1) at `origin`: the convex
/// `body`, or when `parts` is set the compound body `parts` (non-convex: a mesh's convex parts),
/// whose envelope the model then puts in `body`.
struct Geometry {
  std::string name;
  int link = -1;
  Pose origin;
  ConvexPolyhedron body;
  std::optional<CompoundBody> parts;
};

/// Which entries of an origin (a joint's or a geometry's pose in its link's frame) are exact
/// zeros, found once so that the forward kinematics multiplies by none of them.
struct OriginZeros {
  /// k when the rotation's k-th row and column are e_k exactly (a turn about e_k; the identity
  /// too), else -1.
  int turn_axis = -1;
  /// The translation's nonzero coordinates, `axes[0..count)`, when at most two are; else 3.
  int count = 3;
  int axes[2] = {0, 0};
};

/// A robot as a plain table of links, joints and geometries: immutable once built, so one model
/// is shared by every thread and every call (the per-call data lives in the calls, and no call
/// leaves anything behind that could change the next answer, unlike a solver state carried from
/// call to call).
///
/// The links form one tree: every link but one (the root, which sits at the identity) is the
/// child of exactly one joint. The moving joints (all but the fixed ones) are the degrees of
/// freedom, numbered in the order the joints are given.
class RobotModel {
 public:
  /// Throws std::invalid_argument naming the joint, link or geometry at fault: a link index out
  /// of range, a link with two parent joints, links that are not one tree (a cycle or two roots),
  /// a zero or non-finite axis, limits with lower > upper or NaN on a limited joint, an invalid
  /// origin (not a rigid motion), a mimic index below -1, a mimic of a fixed, mimic or missing
  /// joint, a non-finite multiplier or offset, or duplicate names.
  RobotModel(std::vector<Link> links, std::vector<Joint> joints, std::vector<Geometry> geometries);

  const std::vector<Link>& links() const { return links_; }
  const std::vector<Joint>& joints() const { return joints_; }
  const std::vector<Geometry>& geometries() const { return geometries_; }
  /// The number of degrees of freedom (moving joints).
  int dof() const { return static_cast<int>(moving_.size()); }
  /// The joint index of degree of freedom `i`.
  const std::vector<int>& moving_joints() const { return moving_; }
  /// The degree of freedom of joint `j`, -1 for a fixed or mimic joint.
  int dof_of_joint(int j) const { return dof_of_joint_[static_cast<std::size_t>(j)]; }
  /// The degree of freedom that moves joint `j`: its own, its mimicked joint's, or -1 (fixed).
  int driving_dof(int j) const { return driving_dof_[static_cast<std::size_t>(j)]; }
  /// Joint `j`'s value when its driving degree of freedom has the value `value`.
  Scalar joint_value(int j, Scalar value) const {
    const Joint& joint = joints_[static_cast<std::size_t>(j)];
    return joint.mimic < 0 ? value : joint.multiplier * value + joint.offset;
  }
  /// The exact zeros of joint `j`'s origin, and of geometry `g`'s.
  const OriginZeros& joint_origin_zeros(int j) const {
    return joint_zeros_[static_cast<std::size_t>(j)];
  }
  const OriginZeros& geometry_origin_zeros(int g) const {
    return geometry_zeros_[static_cast<std::size_t>(g)];
  }
  /// k when joint `j` turns about e_k or -e_k exactly, else -1 (and for a slide).
  int axis_coordinate(int j) const { return axis_coordinate_[static_cast<std::size_t>(j)]; }
  /// The joint whose child is link `l`, -1 for the root.
  int parent_joint(int l) const { return parent_joint_[static_cast<std::size_t>(l)]; }
  /// The joints in an order where each joint's parent link is placed before it (root first).
  const std::vector<int>& joint_order() const { return order_; }
  /// True when some pair needs the compound queries: a geometry has `parts`.
  bool has_compound() const { return !compounds_.empty(); }
  /// Geometry g as a compound body (its parts, or its convex body as one part), when
  /// `has_compound()` and g is no curved shape (compound bodies take polyhedra only: a pair of a
  /// compound geometry and a curved one is answered part by part).
  const CompoundBody& compound(int g) const { return *compounds_[static_cast<std::size_t>(g)]; }

 private:
  std::vector<Link> links_;
  std::vector<Joint> joints_;
  std::vector<Geometry> geometries_;
  std::vector<int> moving_;
  std::vector<int> dof_of_joint_;
  std::vector<int> driving_dof_;
  std::vector<int> parent_joint_;
  std::vector<int> order_;
  std::vector<OriginZeros> joint_zeros_;
  std::vector<OriginZeros> geometry_zeros_;
  std::vector<int> axis_coordinate_;
  std::vector<std::optional<CompoundBody>> compounds_;
};

}  // namespace swarmcollide
