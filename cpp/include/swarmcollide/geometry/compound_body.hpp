#pragma once

#include <vector>

#include "swarmcollide/geometry/aabb.hpp"
#include "swarmcollide/geometry/convex_polyhedron.hpp"
#include "swarmcollide/geometry/pose.hpp"
#include "swarmcollide/types.hpp"

namespace swarmcollide {

/// A node of a compound body's bounding-volume tree, in the body's own frame: a box and a ball
/// that hold every part below it.
struct PartNode {
  /// Smallest axis-aligned box holding the parts below.
  Aabb box;
  /// A ball holding the parts below: every point of them lies within `radius` of `centre`.
  Vector3 centre = Vector3::Zero();
  Scalar radius = 0;
  /// Children (indices into `CompoundBody::tree()`), -1 for a leaf.
  int left = -1;
  int right = -1;
  /// The part a leaf holds, -1 for an inner node.
  int part = -1;

  bool leaf() const { return part >= 0; }
};

/// A body that is the union of convex parts (a non-convex object, say, decomposed into convex
/// pieces), each part a ConvexPolyhedron in the body's own frame. The paper expresses objects by
/// "convex Bounding Volume Hierarchies": the body keeps a binary tree over its parts, built once,
/// whose every node holds a box, a ball and the convex hull of the parts below it, so that
/// queries between compound bodies visit only the part pairs that the volumes' certified lower
/// bounds cannot rule out.
///
/// A part may be a curved shape (Cylinder, Cone, Ellipsoid): the envelopes hold its box, and its
/// part pairs are answered as Query answers a convex pair, by the methods that answer curved
/// shapes (the others refuse the body). Each part may have a pose in the body's frame: the body
/// keeps the part placed by it (placed_shape.hpp), which the queries read as any part.
///
/// Copies share the parts (and their hulls); the class is safe to read from many threads.
class CompoundBody {
 public:
  /// Throws std::invalid_argument if `parts` is empty.
  explicit CompoundBody(std::vector<ConvexPolyhedron> parts);
  /// Parts each placed by its pose in the body's frame: part i's points `x` are at
  /// `poses[i].rotation * x + poses[i].translation`. Throws std::invalid_argument if `parts` is
  /// empty, if there is not one pose per part, or for an invalid pose (see validate_pose).
  CompoundBody(std::vector<ConvexPolyhedron> parts, const std::vector<Pose>& poses);
  /// A body of one part.
  explicit CompoundBody(ConvexPolyhedron part);

  /// The convex parts in the body's frame (placed by their poses), in the order given.
  const std::vector<ConvexPolyhedron>& parts() const { return parts_; }
  /// The parts as given, each in its own frame (`parts()` for a body built without poses).
  const std::vector<ConvexPolyhedron>& given_parts() const {
    return given_parts_.empty() ? parts_ : given_parts_;
  }
  /// Where each part sits in the body's frame (identity poses for a body built without poses).
  std::vector<Pose> part_poses() const;
  /// Number of parts.
  int size() const { return static_cast<int>(parts_.size()); }
  /// The bounding-volume tree over the parts: node 0 is the root, each inner node has two
  /// children and each leaf one part (a body of n parts has 2n - 1 nodes).
  const std::vector<PartNode>& tree() const { return tree_; }
  /// The convex hull of every part's points: a convex body holding the compound one, which
  /// scenes box and screen with (its distance to another body bounds the compound's from below).
  const ConvexPolyhedron& envelope() const { return node_envelopes_.front(); }
  /// The convex hull of the parts below each node of `tree()` (a leaf's is its part, the root's
  /// the envelope): a separation between two nodes' envelopes bounds every part pair below them.
  const std::vector<ConvexPolyhedron>& node_envelopes() const { return node_envelopes_; }
  /// The envelope's box, its centre and radius.
  const BodyBounds& bounds() const { return envelope().bounds(); }
  /// Total number of points of the parts.
  int point_count() const;
  /// The first curved part (ConvexPolyhedron::curved), null when every part is a polyhedron.
  const ConvexPolyhedron* curved_part() const {
    return curved_part_ < 0 ? nullptr : &parts_[curved_part_];
  }

 private:
  std::vector<ConvexPolyhedron> parts_;
  // The parts as given and their poses, kept only for a body built with poses.
  std::vector<ConvexPolyhedron> given_parts_;
  std::vector<Pose> poses_;
  std::vector<PartNode> tree_;
  std::vector<ConvexPolyhedron> node_envelopes_;
  // The index of the first curved part, -1 for none.
  int curved_part_ = -1;
};

}  // namespace swarmcollide
