#include "support_tree.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>

#include "framed_body.hpp"
#include "support.hpp"
#include "unit_direction.hpp"

namespace swarmcollide::detail {

namespace {

// Points per leaf: a leaf costs as many heights as its ball costs one, and small leaves keep the
// balls near the top of a body tight.
constexpr int kLeafSize = 8;

}  // namespace

SupportTree::SupportTree(const VertexMatrix& points) {
  order_.resize(static_cast<std::size_t>(points.rows()));
  std::iota(order_.begin(), order_.end(), 0);
  nodes_.reserve(4 * order_.size() / kLeafSize + 2);
  nodes_.emplace_back();
  build(points, 0, 0, static_cast<int>(order_.size()));
}

void SupportTree::build(const VertexMatrix& points, int index, int begin, int end) {
  Vector3 low = points.row(order_[begin]).transpose();
  Vector3 high = low;
  for (int k = begin + 1; k < end; ++k) {
    low = low.cwiseMin(points.row(order_[k]).transpose());
    high = high.cwiseMax(points.row(order_[k]).transpose());
  }
  const Vector3 centre = low / 2 + high / 2;
  // |x - centre| as computed is within 4 roundoffs of the exact distance (one rounding per
  // difference, then the norm); d . x <= d . centre + |d| |x - centre|, and d . centre as
  // computed is within 3.01u |d| |centre|, the final product and sum within 2u of their terms.
  // The lengths without their squares, which vanish for bodies below 1e-162 (whose balls then
  // shrank to their centres and cut off the supports) and overflow above 1e154.
  Scalar radius = 0;
  for (int k = begin; k < end; ++k) {
    radius = std::max(radius, robust_length(points.row(order_[k]).transpose() - centre));
  }
  radius *= 1 + 8 * kRoundoff;
  nodes_[index] = {centre, radius + 8 * kRoundoff * (robust_length(centre) + radius), begin, end,
                   -1};
  if (end - begin <= kLeafSize) return;
  int axis = 0;
  (high - low).maxCoeff(&axis);
  const int middle = begin + (end - begin) / 2;
  std::nth_element(order_.begin() + begin, order_.begin() + middle, order_.begin() + end,
                   [&](int i, int j) { return points(i, axis) < points(j, axis); });
  const int first = static_cast<int>(nodes_.size());
  nodes_[index].first_child = first;
  nodes_.resize(nodes_.size() + 2);
  build(points, first, begin, middle);
  build(points, first + 1, middle, end);
}

int SupportTree::support_index(const VertexMatrix& points, const Vector3& d, int start) const {
  const int count = static_cast<int>(points.rows());
  int best = start >= 0 && start < count ? start : order_.front();
  Scalar highest = point_height(points, best, d);
  // An upper bound on |d|: the norm is within 2u of the exact one.
  const Scalar length = d.norm() * (1 + 4 * kRoundoff);
  const auto bound = [&](const Node& node) { return node.centre.dot(d) + length * node.reach; };
  // Depth-first, the child of larger bound first; the stack holds at most one sibling per level.
  std::array<int, 128> stack;
  int size = 0;
  stack[size++] = 0;
  while (size > 0) {
    const Node& node = nodes_[stack[--size]];
    if (!(bound(node) > highest)) continue;
    if (node.first_child < 0) {
      for (int k = node.begin; k < node.end; ++k) {
        const Scalar h = point_height(points, order_[k], d);
        if (h > highest) {
          highest = h;
          best = order_[k];
        }
      }
      continue;
    }
    const int near = node.first_child;
    const int far = near + 1;
    const bool swap = bound(nodes_[far]) > bound(nodes_[near]);
    stack[size++] = swap ? near : far;
    stack[size++] = swap ? far : near;
  }
  return best;
}

}  // namespace swarmcollide::detail
