// Support points of a point set, the scan and the hill climb that ConvexPolyhedron and
// FramedBody share; private to the library's sources.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>

#include "column_scan.hpp"
#include "swarmcollide/geometry/hull.hpp"
#include "swarmcollide/types.hpp"

namespace swarmcollide::detail {

/// `d . x_i`, from the row-major storage: the inner product of every support loop.
inline Scalar point_height(const VertexMatrix& points, int i, const Vector3& d) {
  const Scalar* x = points.data() + 3 * static_cast<std::ptrdiff_t>(i);
  return x[0] * d.x() + x[1] * d.y() + x[2] * d.z();
}

/// The first index in [0, count) maximising `height(i)`.
template <class Height>
int first_highest(int count, const Height& height) {
  int best = 0;
  Scalar highest = height(0);
  for (int i = 1; i < count; ++i) {
    const Scalar h = height(i);
    if (h > highest) {
      highest = h;
      best = i;
    }
  }
  return best;
}

/// Index of a point maximising `d . x` (the first one on ties), by scanning every point: each
/// height is one rounded inner product, so the answer is the maximum to that rounding.
inline int scan_support(const VertexMatrix& points, const Vector3& d) {
  return first_highest(static_cast<int>(points.rows()),
                       [&](int i) { return point_height(points, i, d); });
}

/// The points of a small body by coordinate, for scans that compute several heights at once
/// (column_scan.hpp): the x of every point, then the y, then the z, each column padded by
/// repeating its last entry. The scans' answers are scan_support's, bit for bit.
class PointColumns {
 public:
  /// The most points held: the bodies scanned whole (kHillClimbingThreshold points).
  static constexpr int kCapacity = kColumnCapacity;

  PointColumns() = default;
  /// Holds `points` (at most kCapacity rows, at least one).
  void assign(const VertexMatrix& points) {
    count_ = static_cast<int>(points.rows());
    const int padded = (count_ + kColumnPadding - 1) / kColumnPadding * kColumnPadding;
    const Scalar* row = points.data();
    for (int i = 0; i < padded; ++i) {
      const Scalar* point = row + 3 * std::min(i, count_ - 1);
      for (int k = 0; k < 3; ++k) columns_[k * kCapacity + i] = point[k];
    }
  }
  /// True once points are held.
  bool held() const { return count_ > 0; }

  /// scan_support of the points held: the first index maximising `d . x`, each height rounded as
  /// point_height rounds it, `(x d_x + y d_y) + z d_z`.
  int scan(const Vector3& d) const { return inline_scan(d); }
  /// The same, always inline (the baseline's steps, or the call of a wider set's scan): for the
  /// searches' oracles on small pairs (FramedBody::scanned_support_index), which ask two per
  /// step. Everywhere else the compiler chooses (inlined everywhere, the penetration solver's
  /// signed distances took 1% more).
  [[gnu::always_inline]] int inline_scan(const Vector3& d) const {
    return scan_columns(columns_.data(), count_, d.x(), d.y(), d.z());
  }
  /// The same, in two registers (scan_few_columns) where the caller knows that at most
  /// kRegisterColumns points are held (`few`), else inline_scan's: the small pairs' search tests
  /// the count once rather than in every scan (tested in every scan, it made 8-32-point searches
  /// 30-54 instructions longer and the penetration solver's walks 120-160).
  template <bool few>
  [[gnu::always_inline]] int sized_scan(const Vector3& d) const {
    if constexpr (few) return scan_few_columns(columns_.data(), count_, d.x(), d.y(), d.z());
    return scan_columns(columns_.data(), count_, d.x(), d.y(), d.z());
  }
  /// The same by `kernel`, one instruction set's scan (column_scan_for).
  int scan_with(ColumnScan kernel, const Vector3& d) const {
    return kernel(columns_.data(), count_, d.x(), d.y(), d.z());
  }

 private:
  int count_ = 0;
  std::array<Scalar, 3 * kCapacity> columns_;
};

/// Cells along each edge of a face of the cube map of climb starts (Hull::climb_starts): six faces
/// of kClimbStartCells^2 cells, each about 11 degrees wide.
constexpr int kClimbStartCells = 8;
constexpr int kClimbStartCount = 6 * kClimbStartCells * kClimbStartCells;

/// The direction through the centre of cube-map cell `cell` (face `cell / kClimbStartCells^2`,
/// whose axis is face / 2, negative for odd faces).
inline Vector3 climb_cell_centre(int cell) {
  const int face = cell / (kClimbStartCells * kClimbStartCells);
  const int u = cell / kClimbStartCells % kClimbStartCells;
  const int v = cell % kClimbStartCells;
  const int axis = face / 2;
  Vector3 d;
  d(axis) = face % 2 ? -1 : 1;
  d((axis + 1) % 3) = (2 * u + 1) / Scalar(kClimbStartCells) - 1;
  d((axis + 2) % 3) = (2 * v + 1) / Scalar(kClimbStartCells) - 1;
  return d;
}

/// The cube-map cell that the direction `d` falls in; 0 for a zero or non-finite `d`.
inline int climb_cell(const Vector3& d) {
  int axis = 0;
  for (int k = 1; k < 3; ++k) {
    if (std::abs(d(k)) > std::abs(d(axis))) axis = k;
  }
  const Scalar major = std::abs(d(axis));
  if (!(major > 0) || !d.allFinite()) return 0;
  const int face = 2 * axis + (d(axis) < 0 ? 1 : 0);
  const auto cell = [major](Scalar t) {
    const auto i = static_cast<int>((t / major + 1) * (kClimbStartCells / Scalar(2)));
    return std::clamp(i, 0, kClimbStartCells - 1);
  };
  return (face * kClimbStartCells + cell(d((axis + 1) % 3))) * kClimbStartCells +
         cell(d((axis + 2) % 3));
}

/// Index of a point maximising `d . x`, by steepest ascent over `hull`'s edge graph, as FCL and
/// coal do, from `start`: a search passes the previous answer, which is best for a nearby
/// direction. Without one (a point with no neighbours, or out of range, is none), as after a
/// jump, the climb starts from the hull's climb start for the cube-map cell of `d` (coal keeps
/// such a table too), a step or two from the answer whatever the direction.
/// On a convex polytope a vertex with no higher neighbour maximises a linear function;
/// with rounded heights the climb can stop short of the maximum, so its answers serve search and
/// upper bounds (any point of the body does), never a proven lower bound on their own. Every
/// step strictly raises the height, so the climb ends.
inline int climb_support(const VertexMatrix& points, const Hull& hull, const Vector3& d,
                         int start) {
  const int* offsets = hull.neighbour_offsets.data();
  const int* neighbours = hull.neighbours.data();
  const bool given =
      start >= 0 && start < static_cast<int>(points.rows()) && offsets[start + 1] > offsets[start];
  // A search's previous answer can be far from the new one (Wolfe's algorithm turns its direction
  // by up to half a turn): the cell's start, a step or two from any support, is taken when higher.
  int current = hull.climb_starts[static_cast<std::size_t>(climb_cell(d))];
  Scalar highest = point_height(points, current, d);
  if (given) {
    const Scalar h = point_height(points, start, d);
    if (h >= highest) {
      current = start;
      highest = h;
    }
  }
  for (;;) {
    int next = current;
    for (int e = offsets[current]; e < offsets[current + 1]; ++e) {
      const Scalar h = point_height(points, neighbours[e], d);
      if (h > highest) {
        highest = h;
        next = neighbours[e];
      }
    }
    if (next == current) return current;
    current = next;
  }
}

}  // namespace swarmcollide::detail
