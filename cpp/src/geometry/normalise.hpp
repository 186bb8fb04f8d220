// Moving point sets into a unit-sized frame; private to the library's sources.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstring>

#include "swarmcollide/types.hpp"

namespace swarmcollide::detail {

/// The unit roundoff of double precision: every basic operation is exact to a factor `1 + d`,
/// `|d| <= kRoundoff`. The rounding bounds of the exact paths are multiples of it.
inline constexpr Scalar kRoundoff = 0x1p-53;

/// 2^exponent for exponents of normal doubles, [-1022, 1023], built from its bits: std::ldexp
/// is a library call, and every query frames its pair with several of these.
inline Scalar power_of_two(int exponent) {
  const std::uint64_t bits = static_cast<std::uint64_t>(exponent + 1023) << 52;
  Scalar value;
  std::memcpy(&value, &bits, sizeof value);
  return value;
}

/// `x * 2^exponent`, exact whenever the result is a normal double: the factor is split in two
/// when 2^exponent alone would overflow or underflow.
inline Scalar times_power_of_two(Scalar x, int exponent) {
  if (exponent > 1000 || exponent < -1000) {
    const int half = exponent / 2;
    return x * power_of_two(half) * power_of_two(exponent - half);
  }
  return x * power_of_two(exponent);
}

/// times_power_of_two of each coordinate of `v`, the same values: one factor for the three where
/// 2^exponent is a normal double (every frame but the most extreme), without a test for each
/// (framing a pair places two offsets, and an answer turns two witnesses back).
inline Vector3 times_power_of_two(const Vector3& v, int exponent) {
  if (exponent >= -1000 && exponent <= 1000) return v * power_of_two(exponent);
  Vector3 scaled;
  for (int k = 0; k < 3; ++k) scaled(k) = times_power_of_two(v(k), exponent);
  return scaled;
}

/// The exponent e with 2^(e-1) <= length < 2^e (0 for a zero length): dividing by 2^e brings
/// `length` into [0.5, 1).
inline int exponent_above(Scalar length) {
  if (!(length > 0)) return 0;
  // A normal double's exponent field, read from its bits (frexp is a library call, and every
  // query frames its pair with this); subnormals and infinity take frexp.
  std::uint64_t bits = 0;
  std::memcpy(&bits, &length, sizeof bits);
  const int biased = static_cast<int>(bits >> 52) & 0x7ff;
  if (biased == 0 || biased == 0x7ff) {
    int exponent = 0;
    std::frexp(length, &exponent);
    return exponent;
  }
  return biased - 1022;
}

/// Points translated by `centre` and divided by 2^exponent, which puts them in the unit ball.
struct NormalisedPoints {
  VertexMatrix points;
  Vector3 centre;
  int exponent;
};

/// `points` moved so the centre of their bounding box is the origin and scaled by a power of two
/// (exactly) so they lie within the unit ball. Convex hulls and centroids are computed there, so
/// that coordinates anywhere in the double range neither overflow nor underflow in the cross
/// products; the only rounding is the translation's, relative to the points' own spread.
inline NormalisedPoints normalise(const VertexMatrix& points) {
  const Vector3 low = points.colwise().minCoeff().transpose();
  const Vector3 high = points.colwise().maxCoeff().transpose();
  const Vector3 centre = low / 2 + high / 2;
  const Vector3 half_extent = high / 2 - low / 2;
  const Scalar largest = half_extent.maxCoeff();
  const Scalar radius = largest > 0 ? largest * (half_extent / largest).norm() : 0;
  NormalisedPoints result{VertexMatrix(points.rows(), 3), centre, exponent_above(radius)};
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    for (int k = 0; k < 3; ++k) {
      result.points(i, k) = times_power_of_two(points(i, k) - centre(k), -result.exponent);
    }
  }
  return result;
}

}  // namespace swarmcollide::detail
