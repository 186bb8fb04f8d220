// Unit vectors along directions of any length; private to the library's sources.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "normalise.hpp"
#include "swarmcollide/types.hpp"

namespace swarmcollide::detail {

/// Squared lengths from here up are sums of squares that lost no digits: an entry small enough
/// for its square to be subnormal adds at most 2^-1074 to them, 1e-33 of their size.
inline constexpr Scalar kFullSquaredLength = 1e-290;

/// `v` scaled to unit length, or nothing for the zero vector or one with an entry not finite.
/// Eigen's normalized() squares the entries: for a vector whose entries are all below about
/// 1e-154 (an edge or a face of a body that much smaller than its pair, two centres that close in
/// world units) the squares lose their digits or vanish, and it returned a vector of length far
/// from 1, or the vector itself, along which a separation scaled by that length was taken as a
/// bound (a speck inside a unit cube: a certified depth of 6e-15 where it is 0.5). Such a vector
/// is scaled by its largest entry first.
inline std::optional<Vector3> unit_direction(const Vector3& v) {
  const Scalar squared = v.squaredNorm();
  // A unit vector already (one made by a division by its length) is kept as it is, bit for bit.
  if (std::abs(squared - 1) <= 4 * kRoundoff) return v;
  if (squared >= kFullSquaredLength && squared < std::numeric_limits<Scalar>::infinity()) {
    return Vector3(v / std::sqrt(squared));
  }
  if (!v.allFinite()) return std::nullopt;
  const Scalar largest = v.cwiseAbs().maxCoeff();
  if (!(largest > 0)) return std::nullopt;
  const Vector3 scaled = v / largest;
  return Vector3(scaled / scaled.norm());
}

/// unit_direction(v), or `otherwise` for the zero vector and one with an entry not finite.
inline Vector3 unit_direction_or(const Vector3& v, const Vector3& otherwise) {
  const std::optional<Vector3> unit = unit_direction(v);
  return unit ? *unit : otherwise;
}

/// The length of `v` without underflow or overflow in its squares (as unit_direction's).
inline Scalar robust_length(const Vector3& v) {
  const Scalar squared = v.squaredNorm();
  if (squared >= kFullSquaredLength && squared < std::numeric_limits<Scalar>::infinity()) {
    return std::sqrt(squared);
  }
  const Scalar largest = v.cwiseAbs().maxCoeff();
  if (!(largest > 0) || !std::isfinite(largest)) return largest;
  return largest * (v / largest).norm();
}

/// The largest length over the rows of `points`. The squares are summed directly, which is exact
/// to a few roundoffs while they stay in the normal range; where the largest square overflows or
/// falls below 2^-960 (bodies beyond about 1e154 or below 1e-144 in size, where squares lose
/// digits or vanish), every row's norm is taken scaled.
inline Scalar largest_row_length(const VertexMatrix& points) {
  Scalar largest_square = 0;
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    largest_square = std::max(largest_square, points.row(i).squaredNorm());
  }
  if (largest_square >= 0x1p-960 && largest_square <= std::numeric_limits<Scalar>::max()) {
    return std::sqrt(largest_square);
  }
  Scalar largest = 0;
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    largest = std::max(largest, points.row(i).stableNorm());
  }
  return largest;
}

}  // namespace swarmcollide::detail
