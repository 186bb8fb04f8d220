#include "link_motion_bound.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "../geometry/unit_direction.hpp"
#include "swarmcollide/robot/kinematics.hpp"

namespace swarmcollide::detail {

namespace {

constexpr Scalar kUnit = 0x1p-53;
// Every bound below is a short sum of products of rounded numbers: 16 roundoffs of it cover them.
constexpr Scalar kRoundUp = 1 + 16 * kUnit;

// A bound on the spectral norm of R^T R - I: its largest absolute row sum (the matrix is
// symmetric), rounded up.
Scalar rigid_deviation(const Matrix3& rotation) {
  const Matrix3 gram = rotation.transpose() * rotation - Matrix3::Identity();
  return gram.cwiseAbs().rowwise().sum().maxCoeff() * kRoundUp + 8 * kUnit;
}

// A bound on the spectral norm of a rotation R with R^T R - I of norm at most `deviation`.
Scalar rotation_norm(Scalar deviation) { return std::sqrt(1 + deviation) * kRoundUp; }

// The distance of `p` from the line through the origin along the unit `axis`. Lengths here are
// robust_length's: the squares of a robot's coordinates vanish below 1e-162 (a link of that size
// then reached nowhere, and a colliding motion was certified free) and overflow above 1e154.
Scalar off_axis(const Vector3& p, const Vector3& axis) {
  return robust_length(p - p.dot(axis) * axis);
}

// Raises `about_origin` and `about_axis` to bounds on the distance of the core points of `body`,
// placed by `origin`, from the origin and from the line along `axis`. A rounded body's ball turns
// into itself, so it moves no farther than its core: its radius is left out.
void core_reach(const ConvexPolyhedron& body, const Pose& origin, const Vector3& axis,
                Scalar& about_origin, Scalar& about_axis) {
  if (const SupportFunction* shape = body.curved()) {
    // The shape lies within its outer radius of its centre, the body's box centre.
    const Vector3 centre = origin.rotation * body.bounds().centre + origin.translation;
    const Scalar radius = shape->outer_radius() * rotation_norm(rigid_deviation(origin.rotation));
    about_origin = std::max(about_origin, robust_length(centre) + radius);
    about_axis = std::max(about_axis, off_axis(centre, axis) + radius);
    return;
  }
  for (int i = 0; i < body.size(); ++i) {
    const Vector3 p = origin.rotation * body.vertices().row(i).transpose() + origin.translation;
    about_origin = std::max(about_origin, robust_length(p));
    about_axis = std::max(about_axis, off_axis(p, axis));
  }
}

}  // namespace

LinkMotionBound::BoxCorners LinkMotionBound::BoxCorners::of(const Aabb& box) {
  BoxCorners corners;
  for (int c = 0; c < 8; ++c) {
    corners.x[c] = (c & 1) ? box.max.x() : box.min.x();
    corners.y[c] = (c & 2) ? box.max.y() : box.min.y();
    corners.z[c] = (c & 4) ? box.max.z() : box.min.z();
  }
  return corners;
}

LinkMotionBound::BoxCorners LinkMotionBound::BoxCorners::placed(const Pose& pose) const {
  // Each coordinate as the product's: its 3 products summed from the first, then the
  // translation added.
  const Matrix3& r = pose.rotation;
  const Vector3& t = pose.translation;
  return {r(0, 0) * x + r(0, 1) * y + r(0, 2) * z + t.x(),
          r(1, 0) * x + r(1, 1) * y + r(1, 2) * z + t.y(),
          r(2, 0) * x + r(2, 1) * y + r(2, 2) * z + t.z()};
}

Scalar LinkMotionBound::BoxCorners::farthest_off_axis(const Vector3& origin,
                                                      const Vector3& axis) const {
  // Each corner's expressions are off_axis's on corner - origin, in its order (its dot product
  // and squared norm sum their 3 products from the first), and a rounded square root is
  // nondecreasing: the root of the largest square is the largest root.
  using Corners = Eigen::Array<Scalar, 8, 1>;
  const Corners px = x - origin.x();
  const Corners py = y - origin.y();
  const Corners pz = z - origin.z();
  const Corners along = px * axis.x() + py * axis.y() + pz * axis.z();
  const Corners qx = px - along * axis.x();
  const Corners qy = py - along * axis.y();
  const Corners qz = pz - along * axis.z();
  const Scalar largest_square = (qx * qx + qy * qy + qz * qz).maxCoeff();
  if (std::isnan(largest_square) || (largest_square >= kFullSquaredLength &&
                                      largest_square < std::numeric_limits<Scalar>::infinity())) {
    return std::sqrt(largest_square);
  }
  // Squares that lost their digits or overflowed: each corner's length as off_axis takes it.
  Scalar farthest = 0;
  for (int c = 0; c < 8; ++c) {
    farthest = std::max(farthest, robust_length(Vector3(qx[c], qy[c], qz[c])));
  }
  return farthest;
}

LinkMotionBound::LinkMotionBound(const RobotModel& model) : model_(model) {
  const std::vector<Joint>& joints = model.joints();
  origin_sigma_.resize(joints.size());
  chain_sigma_.resize(joints.size());
  for (std::size_t j = 0; j < joints.size(); ++j) {
    origin_sigma_[j] = rigid_deviation(joints[j].origin.rotation);
  }
  chains_.resize(model.links().size());
  for (std::size_t l = 0; l < chains_.size(); ++l) {
    for (int link = static_cast<int>(l); model.parent_joint(link) >= 0;) {
      const int j = model.parent_joint(link);
      chains_[l].push_back(j);
      link = joints[j].parent;
    }
    std::reverse(chains_[l].begin(), chains_[l].end());
  }
  // The product of the origins from the root to each joint (the turns between them are exact
  // rotations): its Gram matrix is within prod (1 + sigma_k) - 1 of the identity.
  for (int j : model.joint_order()) {
    const int above = model.parent_joint(joints[j].parent);
    const Scalar before = above < 0 ? 0 : chain_sigma_[above];
    chain_sigma_[j] = ((1 + before) * (1 + origin_sigma_[j]) - 1) * kRoundUp;
  }
  const std::vector<Geometry>& geometries = model.geometries();
  origin_reach_.assign(geometries.size(), 0);
  axis_reach_.assign(geometries.size(), 0);
  for (std::size_t g = 0; g < geometries.size(); ++g) {
    const Geometry& geometry = geometries[g];
    const int parent = geometry.link < 0 ? -1 : model.parent_joint(geometry.link);
    const Vector3 axis = parent < 0 ? Vector3::UnitZ() : joints[parent].axis.normalized();
    if (geometry.parts) {
      for (const ConvexPolyhedron& part : geometry.parts->parts()) {
        core_reach(part, geometry.origin, axis, origin_reach_[g], axis_reach_[g]);
      }
    } else {
      core_reach(geometry.body, geometry.origin, axis, origin_reach_[g], axis_reach_[g]);
    }
    origin_reach_[g] *= kRoundUp;
    axis_reach_[g] *= kRoundUp;
  }
  // The model's constants of set_motion's chain bounds, per joint.
  origin_norm_.assign(joints.size(), 0);
  chain_norm_.assign(joints.size(), 0);
  origin_length_.assign(joints.size(), 0);
  origin_off_axis_.assign(joints.size(), 0);
  for (std::size_t j = 0; j < joints.size(); ++j) {
    origin_norm_[j] = rotation_norm(origin_sigma_[j]);
    chain_norm_[j] = rotation_norm(chain_sigma_[j]);
    origin_length_[j] = robust_length(joints[j].origin.translation);
    const int above = model.parent_joint(joints[j].parent);
    if (above >= 0) {
      origin_off_axis_[j] = off_axis(joints[j].origin.translation, joints[above].axis.normalized());
    }
  }
  start_axes_.assign(joints.size(), Vector3::Zero());
  end_axes_.assign(joints.size(), Vector3::Zero());
  change_.resize(joints.size());
  velocity_.resize(joints.size());
  slide_.resize(joints.size());
  value_error_.resize(joints.size());
  geometries_.resize(geometries.size());
  box_corners_.reserve(geometries.size());
  for (const Geometry& geometry : geometries) {
    box_corners_.push_back(BoxCorners::of(geometry.body.bounds().box));
  }
  const std::size_t links = chains_.size();
  shared_.assign(links * links, 0);
  for (std::size_t a = 0; a < links; ++a) {
    for (std::size_t b = 0; b < links; ++b) {
      const std::vector<int>& x = chains_[a];
      const std::vector<int>& y = chains_[b];
      std::size_t k = 0;
      while (k < x.size() && k < y.size() && x[k] == y[k]) ++k;
      shared_[a * links + b] = k;
    }
  }
}

std::size_t LinkMotionBound::shared_joints(int a, int b) const {
  if (a < 0 || b < 0) return 0;
  return shared_[static_cast<std::size_t>(a) * chains_.size() + static_cast<std::size_t>(b)];
}

void LinkMotionBound::set_motion(const Scalar* q0, const Scalar* q1) {
  link_poses(model_, q0, start_links_);
  link_poses(model_, q1, end_links_);
  set_motion(q0, q1, start_links_, end_links_);
}

void LinkMotionBound::set_motion(const Scalar* q0, const Scalar* q1,
                                 const std::vector<Pose>& start_links,
                                 const std::vector<Pose>& end_links) {
  const std::vector<Joint>& joints = model_.joints();
  for (std::size_t j = 0; j < joints.size(); ++j) {
    const Joint& joint = joints[j];
    const int dof = model_.driving_dof(static_cast<int>(j));
    change_[j] = slide_[j] = value_error_[j] = velocity_[j] = 0;
    if (dof < 0) continue;
    const Scalar rate = std::abs(joint.mimic < 0 ? 1 : joint.multiplier);
    const Scalar v0 = model_.joint_value(static_cast<int>(j), q0[dof]);
    const Scalar v1 = model_.joint_value(static_cast<int>(j), q1[dof]);
    change_[j] = rate * std::abs(q1[dof] - q0[dof]) * kRoundUp;
    velocity_[j] = (joint.mimic < 0 ? 1 : joint.multiplier) * (q1[dof] - q0[dof]);
    // q(t) = q0 + t (q1 - q0), the mimic's multiple and offset, and the motion's `value -
    // reference` are each a few roundoffs of these magnitudes away from the exact values.
    value_error_[j] = 8 * kUnit *
                      (rate * 2 * (std::abs(q0[dof]) + std::abs(q1[dof])) + std::abs(v0) +
                       std::abs(v1) + std::abs(joint.reference) + std::abs(joint.offset));
    if (joint.type == JointType::prismatic) {
      slide_[j] = std::max(std::abs(v0 - joint.reference), std::abs(v1 - joint.reference)) *
                      kRoundUp +
                  value_error_[j];
    } else {
      start_axes_[j] = (start_links[static_cast<std::size_t>(joint.child)].rotation * joint.axis)
                           .normalized();
      end_axes_[j] =
          (end_links[static_cast<std::size_t>(joint.child)].rotation * joint.axis).normalized();
    }
  }
  const std::vector<Geometry>& geometries = model_.geometries();
  for (std::size_t g = 0; g < geometries.size(); ++g) {
    GeometryMotion& motion = geometries_[g];
    const int link = geometries[g].link;
    motion.rounding = 0;
    if (link < 0) {
      motion.speed.clear();
      motion.speed_below.clear();
      motion.extent = origin_reach_[g];
      continue;
    }
    const std::vector<int>& chain = chains_[static_cast<std::size_t>(link)];
    const std::size_t n = chain.size();
    // Sized on the first motion (a geometry's chain is the same on every one); every entry is
    // written below.
    motion.speed.resize(n);
    motion.speed_below.resize(n);
    turns_.resize(n);
    // z: the points' distance from the frame of chain[k]'s child; turn: from chain[k]'s axis.
    Scalar z = origin_reach_[g];
    Scalar turn = axis_reach_[g];
    // Per joint, the bound on the points' distance from its axis from the chain.
    for (std::size_t k = n; k-- > 0;) {
      if (k + 1 < n) {
        const int after = chain[k + 1];
        const Scalar inner = origin_norm_[after] * (slide_[after] + z);
        z = (origin_length_[after] + inner) * kRoundUp;
        turn = (origin_off_axis_[after] + inner) * kRoundUp;
      }
      turns_[k] = turn;
      const int j = chain[k];
      if (model_.driving_dof(j) < 0) continue;
      const Scalar reach = joints[j].type == JointType::prismatic ? 1 : turn;
      motion.rounding += chain_norm_[j] * reach * kRoundUp * value_error_[j];
    }
    motion.extent = z;
    if (n > 0) {
      motion.extent =
          (origin_length_[chain[0]] + origin_norm_[chain[0]] * (slide_[chain[0]] + z)) * kRoundUp;
    }
    motion.rounding *= kRoundUp;
    // The box's corners placed at both ends, and the rounding of their distances from the axes:
    // the frames' (as pair_margin's), the corners' placing and off_axis's few products.
    const Geometry& geometry = geometries[g];
    const BoxCorners start_corners =
        box_corners_[g].placed(geometry_pose(model_, start_links, static_cast<int>(g)));
    const BoxCorners end_corners =
        box_corners_[g].placed(geometry_pose(model_, end_links, static_cast<int>(g)));
    const Scalar slack =
        64 * kUnit * static_cast<Scalar>(n + 2) * (motion.extent + 2 * geometry.body.bounds().radius);
    // From the bottom of the chain up: `below` bounds how far the joints below chain[k] move the
    // points over the whole motion, in chain[k]'s child frame.
    Scalar below = 0;
    for (std::size_t k = n; k-- > 0;) {
      const int j = chain[k];
      motion.speed[k] = 0;
      if (model_.driving_dof(j) < 0) continue;
      Scalar reach = 1;
      if (joints[j].type != JointType::prismatic) {
        // The points' distance from the axis (at most the box corners' d0 at the start and d1
        // at the end) changes only through the joints below, by at most `below` (the header).
        // The frames are rigid to within sigma: distances in them and in the world differ by
        // at most that factor, as in local_speed.
        const auto child = static_cast<std::size_t>(joints[j].child);
        const Scalar measured =
            ((start_corners.farthest_off_axis(start_links[child].translation, start_axes_[j]) +
              end_corners.farthest_off_axis(end_links[child].translation, end_axes_[j]) +
              below) /
                 2 * (1 + 4 * chain_sigma_[j]) +
             slack) *
            kRoundUp;
        reach = std::min(turns_[k], measured);
      }
      const Scalar coefficient = chain_norm_[j] * reach * kRoundUp;
      motion.speed[k] = coefficient * change_[j];
      below = (below + motion.speed[k]) * kRoundUp;
    }
    motion.total = 0;
    for (Scalar speed : motion.speed) motion.total += speed;
    motion.total *= kRoundUp;
    for (std::size_t k = 0; k < n; ++k) {
      Scalar below_k = 0;
      for (std::size_t m = k + 1; m < n; ++m) below_k += motion.speed[m];
      motion.speed_below[k] = below_k * kRoundUp;
    }
    motion.terms.clear();
    for (std::size_t k = 0; k < n; ++k) {
      const int j = chain[k];
      if (model_.driving_dof(j) < 0) continue;
      motion.terms.push_back({k, joints[j].type != JointType::prismatic, change_[j],
                              1 + 4 * chain_sigma_[j], motion.speed_below[k], velocity_[j]});
    }
  }
}

void LinkMotionBound::add_shared_turns(Scalar& speed, int link, std::size_t shared,
                                       Scalar extents) const {
  for (std::size_t k = 0; k < shared; ++k) {
    const int j = chains_[static_cast<std::size_t>(link)][k];
    if (model_.joints()[j].type == JointType::prismatic) continue;
    speed += 1.01 * chain_sigma_[j] * change_[j] * extents;
  }
}

Scalar LinkMotionBound::pair_speed(const GeometryPair& pair) const {
  const int la = model_.geometries()[pair.a].link;
  const int lb = model_.geometries()[pair.b].link;
  const std::size_t shared = shared_joints(la, lb);
  const GeometryMotion& a = geometries_[pair.a];
  const GeometryMotion& b = geometries_[pair.b];
  Scalar speed = 0;
  for (std::size_t k = shared; k < a.speed.size(); ++k) speed += a.speed[k];
  for (std::size_t k = shared; k < b.speed.size(); ++k) speed += b.speed[k];
  add_shared_turns(speed, la, shared, a.extent + b.extent);
  return speed * kRoundUp;
}

void LinkMotionBound::place_chain(int g, const std::vector<Pose>& links, const Pose& pose,
                                  PlacedChain& placed, std::size_t first) const {
  place_chain_from(g, links, pose, placed, first, nullptr);
}

void LinkMotionBound::place_end_chain(int g, int end, const std::vector<Pose>& links,
                                      const Pose& pose, PlacedChain& placed) const {
  place_chain_from(g, links, pose, placed, 0, end == 0 ? &start_axes_ : &end_axes_);
}

void LinkMotionBound::place_chain_from(int g, const std::vector<Pose>& links, const Pose& pose,
                                       PlacedChain& placed, std::size_t first,
                                       const std::vector<Vector3>* turn_axes) const {
  const int link = model_.geometries()[static_cast<std::size_t>(g)].link;
  if (link < 0) return;
  const std::vector<int>& chain = chains_[static_cast<std::size_t>(link)];
  const GeometryMotion& motion = geometries_[static_cast<std::size_t>(g)];
  const BodyBounds& bounds = model_.geometries()[static_cast<std::size_t>(g)].body.bounds();
  const Vector3 centre = pose.rotation * bounds.centre + pose.translation;
  // The rounding of the placed frames (as pair_margin's), and the ball's radius.
  const Scalar slack = 64 * kUnit * static_cast<Scalar>(chain.size() + 1) * motion.extent;
  // Grown to the longest chain placed in it (a sampled pair's chains change from pair to pair,
  // a third of the samples'), the entries past this chain left as they were.
  if (placed.axis.size() < chain.size()) {
    placed.axis.resize(chain.size(), Vector3::Zero());
    placed.reach.resize(chain.size(), 0);
    placed.origin.resize(chain.size(), Vector3::Zero());
  }
  placed.centre = centre;
  placed.radius = bounds.radius + slack;
  for (std::size_t k = first; k < chain.size(); ++k) {
    const int j = chain[k];
    if (model_.driving_dof(j) < 0) {
      placed.axis[k].setZero();
      placed.reach[k] = 0;
      continue;
    }
    const Joint& joint = model_.joints()[j];
    const Pose& frame = links[static_cast<std::size_t>(joint.child)];
    const bool turn = joint.type != JointType::prismatic;
    const Vector3 axis = turn && turn_axes ? (*turn_axes)[static_cast<std::size_t>(j)]
                                           : (frame.rotation * joint.axis).normalized();
    placed.axis[k] = axis;
    placed.origin[k] = frame.translation;
    placed.reach[k] = turn ? off_axis(centre - frame.translation, axis) + bounds.radius + slack
                           : 0;
  }
}

LinkMotionBound::LocalSpeed LinkMotionBound::local_speed(const GeometryPair& pair,
                                                         const std::vector<Pose>& links,
                                                         const Pose& pose_a,
                                                         const Pose& pose_b) const {
  PlacedChain a;
  PlacedChain b;
  place_chain(pair.a, links, pose_a, a);
  place_chain(pair.b, links, pose_b, b);
  return local_speed(pair, a, b);
}

LinkMotionBound::LocalSpeed LinkMotionBound::local_speed(const GeometryPair& pair,
                                                         const PlacedChain& placed_a,
                                                         const PlacedChain& placed_b) const {
  const int la = model_.geometries()[pair.a].link;
  const int lb = model_.geometries()[pair.b].link;
  const std::size_t shared = shared_joints(la, lb);
  LocalSpeed local{0, 0};
  const auto add = [&](int g, int link, const PlacedChain& placed) {
    if (link < 0) return;
    for (const GeometryMotion::Term& term : geometries_[static_cast<std::size_t>(g)].terms) {
      if (term.k < shared) continue;
      // A slide moves the points by its change; a turn by its change times their distance from
      // its axis (the child's frame turns about the axis through its origin). The frames are
      // rigid to within sigma: distances in them and in the world differ by at most that factor.
      const Scalar reach = term.turn ? placed.reach[term.k] : 1;
      local.at += term.change * reach * term.rigid;
      local.growth += term.change * term.rigid * term.below;
    }
  };
  add(pair.a, la, placed_a);
  add(pair.b, lb, placed_b);
  add_shared_turns(local.at, la, shared, geometries_[pair.a].extent + geometries_[pair.b].extent);
  local.at *= kRoundUp;
  local.growth *= kRoundUp;
  return local;
}

LinkMotionBound::DirectionalSpeed LinkMotionBound::directional_speed(
    const GeometryPair& pair, const Vector3& direction, const std::vector<Pose>& links,
    const Pose& pose_a, const Pose& pose_b) const {
  PlacedChain a;
  PlacedChain b;
  place_chain(pair.a, links, pose_a, a);
  place_chain(pair.b, links, pose_b, b);
  return directional_speed(pair, direction, a, b);
}

LinkMotionBound::DirectionalSpeed LinkMotionBound::directional_speed(
    const GeometryPair& pair, const Vector3& direction, const PlacedChain& placed_a,
    const PlacedChain& placed_b) const {
  const int la = model_.geometries()[pair.a].link;
  const int lb = model_.geometries()[pair.b].link;
  // The joints above the frame C the pair is measured in, and C's deviation from rigid (the
  // header): none and 0 in the world's frame.
  const std::size_t shared = shared_joints(la, lb);
  const Scalar sigma = sigma_after(la, shared);
  const Scalar in_common = (1 + 4 * sigma) * kRoundUp;
  DirectionalSpeed speed{0, 0, 0, 2 * sigma};
  const auto add = [&](int g, const PlacedChain& placed) {
    if (model_.geometries()[static_cast<std::size_t>(g)].link < 0) return;
    // The angular speed of the frames above the joint in C (the turns taken so far below C).
    Scalar turning = 0;
    for (const GeometryMotion::Term& term : geometries_[static_cast<std::size_t>(g)].terms) {
      if (term.k < shared) continue;
      // The joints below alone change the points' distance from the axis.
      const Scalar below = term.below;
      const Vector3& axis = placed.axis[term.k];
      const Scalar change = term.change * (term.rigid * in_common);
      if (!term.turn) {
        speed.linear += change * (std::abs(direction.dot(axis)) + 8 * kUnit + 4.01 * sigma);
        speed.quadratic += change * turning;
        continue;
      }
      const Scalar across = direction.cross(axis).norm() + 8 * kUnit + 4.01 * sigma;
      const Scalar reach = placed.reach[term.k];
      speed.linear += change * across * reach;
      speed.quadratic += change * (across * below + reach * turning);
      speed.cubic += change * turning * below;
      turning += change;
    }
  };
  add(pair.a, placed_a);
  add(pair.b, placed_b);
  // The rate at a time s away is at most linear + quadratic s + cubic s^2: its integral over h
  // is the bound.
  speed.linear *= kRoundUp;
  speed.quadratic *= kRoundUp;
  speed.cubic *= kRoundUp;
  return speed;
}

LinkMotionBound::TwistSpeed LinkMotionBound::twist_speed(const GeometryPair& pair,
                                                         const Vector3& n,
                                                         const PlacedChain& placed_a,
                                                         const PlacedChain& placed_b) const {
  // As directional_speed: measured in the frame C where the chains part.
  const std::size_t shared = shared_count(pair);
  const Scalar sigma = sigma_after(model_.geometries()[pair.a].link, shared);
  const Scalar in_common = (1 + 4 * sigma) * kRoundUp;
  // The separation's rate at the sample is within [low, high], to `error`.
  Scalar low = 0;
  Scalar high = 0;
  Scalar error = 0;
  TwistSpeed speed{0, 0, 0, 0, 0};
  const auto add = [&](int g, const PlacedChain& placed, Scalar side) {
    if (model_.geometries()[static_cast<std::size_t>(g)].link < 0) return;
    const std::vector<GeometryMotion::Term>& terms =
        geometries_[static_cast<std::size_t>(g)].terms;
    Vector3 w = Vector3::Zero();
    Scalar along = 0;
    Scalar spread_error = 0;
    // The sums from each joint down of the joints' speeds at the sample (S_k) and of their
    // growth, made by taking each joint's term off the whole: each step rounds by at most a
    // roundoff of the whole, which `slack` adds back.
    Scalar p0 = 0;
    Scalar p1 = 0;
    for (std::size_t i = terms.size(); i-- > 0;) {
      const GeometryMotion::Term& term = terms[i];
      if (term.k < shared) break;
      const Scalar m = term.change * (term.rigid * in_common);
      p0 += m * (term.turn ? placed.reach[term.k] : 1);
      if (term.turn) p1 += m * term.below;
    }
    const Scalar slack = 4 * static_cast<Scalar>(terms.size() + 1) * kUnit;
    const Scalar slack0 = slack * p0;
    const Scalar slack1 = slack * p1;
    Scalar omega = 0;
    for (const GeometryMotion::Term& term : terms) {
      if (term.k < shared) continue;
      const Vector3& axis = placed.axis[term.k];
      const Scalar m = term.change * (term.rigid * in_common);
      const Scalar s0 = m * (term.turn ? placed.reach[term.k] : 1);
      const Scalar s1 = term.turn ? m * term.below : 0;
      speed.a0 += omega * s0;
      speed.a1 += omega * s1;
      if (!term.turn) {
        along += term.velocity * n.dot(axis);
        error += m * (16 * kUnit + 4.01 * sigma);
      } else {
        const Vector3 offset = placed.centre - placed.origin[term.k];
        along += term.velocity * n.dot(axis.cross(offset));
        w += term.velocity * axis;
        error += m * ((64 * kUnit + 8 * sigma) * robust_length(offset) +
                      (8 * kUnit + 4.01 * sigma) * placed.reach[term.k]);
        spread_error += m;
        const Scalar across = n.cross(axis).norm() + 8 * kUnit + 4.01 * sigma;
        const Scalar from0 = p0 + slack0;
        const Scalar from1 = p1 + slack1;
        speed.a0 += m * across * from0;
        speed.a1 += m * (across * from1 + omega * from0);
        speed.a2 += m * omega * from1;
        omega += m;
      }
      p0 = std::max<Scalar>(p0 - s0, 0);
      p1 = std::max<Scalar>(p1 - s1, 0);
    }
    // The ball's points: its centre's rate along n, give or take r |n x W|.
    const Scalar spread =
        placed.radius * (n.cross(w).norm() + spread_error * (16 * kUnit + 8 * sigma));
    if (side > 0) {
      low += along - spread;
      high += along + spread;
    } else {
      low -= along + spread;
      high -= along - spread;
    }
  };
  add(pair.a, placed_a, -1);
  add(pair.b, placed_b, 1);
  error = error * kRoundUp + 16 * kUnit * (std::abs(low) + std::abs(high));
  speed.forward = -low + error;
  speed.backward = high + error;
  speed.a0 *= kRoundUp;
  speed.a1 *= kRoundUp;
  speed.a2 *= kRoundUp;
  return speed;
}

std::size_t LinkMotionBound::shared_count(const GeometryPair& pair) const {
  return shared_joints(model_.geometries()[pair.a].link, model_.geometries()[pair.b].link);
}

int LinkMotionBound::common_link(const GeometryPair& pair) const {
  const int la = model_.geometries()[pair.a].link;
  const std::size_t shared = shared_count(pair);
  if (shared == 0) return -1;
  return model_.joints()[chains_[static_cast<std::size_t>(la)][shared - 1]].child;
}

Scalar LinkMotionBound::common_sigma(const GeometryPair& pair) const {
  return sigma_after(model_.geometries()[pair.a].link, shared_count(pair));
}

Scalar LinkMotionBound::sigma_after(int link, std::size_t shared) const {
  return shared == 0 ? 0 : chain_sigma_[chains_[static_cast<std::size_t>(link)][shared - 1]];
}

Scalar LinkMotionBound::pair_margin(const GeometryPair& pair) const {
  const auto chain_length = [this](int link) {
    return link < 0 ? Scalar{0} : static_cast<Scalar>(chains_[static_cast<std::size_t>(link)].size());
  };
  const GeometryMotion& a = geometries_[pair.a];
  const GeometryMotion& b = geometries_[pair.b];
  const Scalar na = chain_length(model_.geometries()[pair.a].link);
  const Scalar nb = chain_length(model_.geometries()[pair.b].link);
  return (a.rounding + b.rounding +
          kUnit * (64 * (na + 1) * a.extent + 64 * (nb + 1) * b.extent +
                   256 * (a.extent + b.extent))) *
         kRoundUp;
}

}  // namespace swarmcollide::detail
