// Support points and rounding margins shared by the parts of the penetration solver; private.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "swarmcollide/geometry/convex_polyhedron.hpp"
#include "swarmcollide/geometry/hull.hpp"
#include "swarmcollide/types.hpp"

namespace swarmcollide::detail {

/// The unit roundoff of double precision: every basic operation is exact to a factor `1 + d`,
/// `|d| <= kRoundoff`.
inline constexpr Scalar kRoundoff = 0x1p-53;

/// A body as the penetration solver sees it: its points and their hull.
struct BodyView {
  const VertexMatrix& points;
  const Hull& hull;

  Vector3 point(int i) const { return points.row(i).transpose(); }
  int size() const { return static_cast<int>(points.rows()); }
  /// `d . x_i`, from the row-major storage (the support loops' inner product).
  Scalar height(int i, const Vector3& d) const {
    const Scalar* x = points.data() + 3 * static_cast<std::ptrdiff_t>(i);
    return x[0] * d.x() + x[1] * d.y() + x[2] * d.z();
  }

  /// Index of a point maximising `d . x` over all points (a scan; exact to rounding, so it is
  /// what a proven lower bound uses).
  int scan_max(const Vector3& d) const {
    int best = 0;
    Scalar top = height(0, d);
    for (int i = 1; i < size(); ++i) {
      const Scalar h = height(i, d);
      if (h > top) {
        top = h;
        best = i;
      }
    }
    return best;
  }

  /// Index of a point maximising `d . x`: a scan for small bodies, steepest ascent over the hull's
  /// edge graph from `start` for large ones. In floating point the climb can stop a rounding
  /// error short of the maximum, so its answers serve upper bounds (any point of the body does)
  /// and search, never a lower bound on its own. At most `size()` steps: each one strictly raises
  /// the height.
  int climb_max(const Vector3& d, int start) const {
    if (size() <= kHillClimbingThreshold) return scan_max(d);
    const int* offsets = hull.neighbour_offsets.data();
    const int* neighbours = hull.neighbours.data();
    if (start < 0 || offsets[start] == offsets[start + 1]) start = hull.vertex_indices[0];
    Scalar top = height(start, d);
    for (int step = 0; step < size(); ++step) {
      int next = start;
      for (int e = offsets[start]; e < offsets[start + 1]; ++e) {
        const Scalar h = height(neighbours[e], d);
        if (h > top) {
          top = h;
          next = neighbours[e];
        }
      }
      if (next == start) break;
      start = next;
    }
    return start;
  }
};

/// Largest absolute coordinate of the pair: the rounding margins are multiples of it.
inline Scalar largest_coordinate(const VertexMatrix& a, const VertexMatrix& b) {
  return std::max(a.cwiseAbs().maxCoeff(), b.cwiseAbs().maxCoeff());
}

/// Bound on the rounding error of a computed separation `min_j n.y_j - max_i n.x_i` along a
/// rounded unit vector `n` (`|n| = 1` to 4 roundoffs), as a separation along `n / |n|`, for
/// coordinates of magnitude at most `coordinate`: each dot product is within `3.01 u |n| |x|
/// <= 5.3 u coordinate` (|x| <= sqrt(3) coordinate), the difference adds `u |s| <= 3.5 u
/// coordinate` and dividing by `|n|` another `4 u |s| <= 14 u coordinate`; 28 u in all, doubled.
inline Scalar separation_margin(Scalar coordinate) { return 64 * kRoundoff * coordinate; }

}  // namespace swarmcollide::detail
