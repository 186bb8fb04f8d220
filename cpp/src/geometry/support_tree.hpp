// A ball tree over a body's points for support points with a proven bound; private to the
// library's sources.
#pragma once

#include <vector>

#include "swarmcollide/types.hpp"

namespace swarmcollide::detail {

/// The points grouped into nested balls (a median split along the longest side of each box, down
/// to leaves of a few points), so that a support query proven as a scan's visits only the balls
/// that can rise above the best point found: near the top of a large body, a few dozen points
/// instead of all of them.
class SupportTree {
 public:
  /// The tree over the rows of `points`, which the queries must be given again.
  explicit SupportTree(const VertexMatrix& points);

  /// Index of a point of `points` whose computed height `point_height(points, i, d)` is at
  /// least every exact height `d . x_j` of the points the tree did not read, and at least the
  /// computed height of every point it read: the guarantee of `scan_support`, so margins derived
  /// for a scan hold. `start` (a climbed support, say) seeds the best point; -1 for none.
  int support_index(const VertexMatrix& points, const Vector3& d, int start) const;

 private:
  struct Node {
    Vector3 centre;
    // Added to |d| times itself, above d . centre as computed, it bounds the exact heights of
    // every point of the node: the ball's radius plus the rounding of that product and sum.
    Scalar reach;
    int begin;  // the node's points are order_[begin, end)
    int end;
    int first_child;  // -1 for a leaf; the children are first_child and first_child + 1
  };

  // Fills node `index` over order_[begin, end) and, below it, its subtree.
  void build(const VertexMatrix& points, int index, int begin, int end);

  std::vector<Node> nodes_;
  std::vector<int> order_;
};

}  // namespace swarmcollide::detail
