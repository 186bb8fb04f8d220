#include "swarmcollide/geometry/compound_body.hpp"

#include <algorithm>
#include <numeric>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "swarmcollide/geometry/placed_shape.hpp"

namespace swarmcollide {

namespace {

std::vector<ConvexPolyhedron> nonempty(std::vector<ConvexPolyhedron> parts) {
  if (parts.empty()) {
    throw std::invalid_argument("parts is empty: a compound body needs at least one convex part");
  }
  return parts;
}

// The parts placed by their poses.
std::vector<ConvexPolyhedron> placed_parts(const std::vector<ConvexPolyhedron>& parts,
                                           const std::vector<Pose>& poses) {
  if (poses.size() != parts.size()) {
    throw std::invalid_argument("poses has " + std::to_string(poses.size()) +
                                " poses for " + std::to_string(parts.size()) +
                                " parts: give one pose per part (the identity for a part in the "
                                "body's frame)");
  }
  std::vector<ConvexPolyhedron> result;
  result.reserve(parts.size());
  for (std::size_t i = 0; i < parts.size(); ++i) {
    validate_pose(poses[i], "poses", i);
    result.push_back(placed(parts[i], poses[i]));
  }
  return result;
}

// Points whose hull (grown by the part's rounding radius) holds the part: a polyhedron's own, a
// curved part's box corners (its points are only a few points on its surface).
VertexMatrix outer_points(const ConvexPolyhedron& part) {
  if (!part.curved()) return part.vertices();
  const Aabb& box = part.aabb();
  VertexMatrix corners(8, 3);
  for (int i = 0; i < 8; ++i) {
    for (int k = 0; k < 3; ++k) corners(i, k) = (i >> k) & 1 ? box.max(k) : box.min(k);
  }
  return corners;
}

// The convex hull of parts `order[begin, end)`: their outer points stacked. A polyhedron alone is
// its own envelope, and shares its hull; a curved part alone is enveloped by its box, so that
// the envelopes, which the searches read as polyhedra, are polyhedra.
ConvexPolyhedron envelope_of(const std::vector<ConvexPolyhedron>& parts,
                             const std::vector<int>& order, int begin, int end) {
  if (end - begin == 1 && !parts[order[begin]].curved()) return parts[order[begin]];
  Eigen::Index rows = 0;
  // The hull of rounded parts lies in the hull of their cores grown by their largest radius.
  Scalar radius = 0;
  std::vector<VertexMatrix> outer;
  outer.reserve(end - begin);
  for (int i = begin; i < end; ++i) {
    outer.push_back(outer_points(parts[order[i]]));
    rows += outer.back().rows();
    radius = std::max(radius, parts[order[i]].radius());
  }
  VertexMatrix points(rows, 3);
  Eigen::Index at = 0;
  for (const VertexMatrix& part : outer) {
    points.middleRows(at, part.rows()) = part;
    at += part.rows();
  }
  return ConvexPolyhedron(std::move(points), radius);
}

// Builds the subtree over parts `order[begin, end)` at index `at` of `tree`, splitting at the
// median of the parts' centres along the axis where they spread most: balanced, so a query
// descends log2(n) levels.
void build(const std::vector<ConvexPolyhedron>& parts, std::vector<int>& order, int begin, int end,
           std::vector<PartNode>& tree, std::vector<ConvexPolyhedron>& envelopes, int at) {
  envelopes[at] = envelope_of(parts, order, begin, end);
  PartNode& node = tree[at];
  node.box = parts[order[begin]].aabb();
  for (int i = begin + 1; i < end; ++i) {
    node.box.min = node.box.min.cwiseMin(parts[order[i]].aabb().min);
    node.box.max = node.box.max.cwiseMax(parts[order[i]].aabb().max);
  }
  node.centre = (node.box.min + node.box.max) / 2;
  // The ball around the box's centre through the farthest point: tighter than the box's half
  // diagonal for parts that do not fill their box's corners.
  Scalar radius = 0;
  for (int i = begin; i < end; ++i) {
    const ConvexPolyhedron& part = parts[order[i]];
    const VertexMatrix points = outer_points(part);
    // stableNorm: parts over 1e154 apart have squared distances beyond the double range.
    const Scalar reach =
        (points.rowwise() - node.centre.transpose()).rowwise().stableNorm().maxCoeff();
    radius = std::max(radius, part.radius() > 0 ? (reach + part.radius()) * (1 + 1e-15) : reach);
  }
  node.radius = radius;
  if (end - begin == 1) {
    node.part = order[begin];
    return;
  }
  Vector3 low = parts[order[begin]].bounds().centre;
  Vector3 high = low;
  for (int i = begin + 1; i < end; ++i) {
    low = low.cwiseMin(parts[order[i]].bounds().centre);
    high = high.cwiseMax(parts[order[i]].bounds().centre);
  }
  int axis = 0;
  (high - low).maxCoeff(&axis);
  const int middle = begin + (end - begin) / 2;
  std::nth_element(order.begin() + begin, order.begin() + middle, order.begin() + end,
                   [&](int x, int y) {
                     return parts[x].bounds().centre(axis) < parts[y].bounds().centre(axis);
                   });
  // A subtree over k parts takes 2k - 1 consecutive nodes: the left one right after its parent.
  const int left = at + 1;
  const int right = left + 2 * (middle - begin) - 1;
  tree[at].left = left;
  tree[at].right = right;
  build(parts, order, begin, middle, tree, envelopes, left);
  build(parts, order, middle, end, tree, envelopes, right);
}

}  // namespace

CompoundBody::CompoundBody(std::vector<ConvexPolyhedron> parts)
    : parts_(nonempty(std::move(parts))) {
  std::vector<int> order(parts_.size());
  std::iota(order.begin(), order.end(), 0);
  tree_.resize(2 * parts_.size() - 1);
  // Placeholders, each replaced by its node's envelope as the tree is built.
  node_envelopes_.assign(tree_.size(), parts_.front());
  build(parts_, order, 0, size(), tree_, node_envelopes_, 0);
  // Each part's own span is checked where it is made; together they may span more, and the
  // queries' tolerances (relative to the body's size) were then infinite: bodies 1e308 apart
  // were answered colliding.
  const Aabb& box = tree_.front().box;
  if (!(box.max - box.min).allFinite()) {
    throw std::invalid_argument(
        "parts span more than the largest double (1.8e308): the compound body's size is not "
        "representable; use a unit of length in which the coordinates are smaller");
  }
  for (int i = 0; i < size() && curved_part_ < 0; ++i) {
    if (parts_[i].curved()) curved_part_ = i;
  }
}

CompoundBody::CompoundBody(std::vector<ConvexPolyhedron> parts, const std::vector<Pose>& poses)
    : CompoundBody(placed_parts(nonempty(parts), poses)) {
  given_parts_ = std::move(parts);
  poses_ = poses;
}

CompoundBody::CompoundBody(ConvexPolyhedron part)
    : CompoundBody(std::vector<ConvexPolyhedron>{std::move(part)}) {}

std::vector<Pose> CompoundBody::part_poses() const {
  return poses_.empty() ? std::vector<Pose>(parts_.size()) : poses_;
}

int CompoundBody::point_count() const {
  int count = 0;
  for (const ConvexPolyhedron& part : parts_) count += part.size();
  return count;
}

}  // namespace swarmcollide
