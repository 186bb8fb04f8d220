#include "contact_tetrahedron.hpp"

#include <array>
#include <cmath>
#include <cstdint>

#include "../solvers/minkowski.hpp"

namespace swarmcollide::detail {

namespace {

// Points up to which every triangle is looked at (four triangles at most).
constexpr std::size_t kFewBasePoints = 4;

}  // namespace

bool deepest_triangle(const Eigen::Vector2d* points, std::size_t count, const Eigen::Vector2d& q,
                      std::array<std::size_t, 3>& base) {
  const auto cross = [](const Eigen::Vector2d& x, const Eigen::Vector2d& y) {
    return x.x() * y.y() - x.y() * y.x();
  };
  // q's barycentric coordinates in the triangle (p, r, s), p < r < s, are w_p = cross(d_r, d_s)
  // / area and w_r = cross(d_s, d_p) / area, d_m the points' offsets from q: each cross(d_i,
  // d_j), i < j, is made once (cross(d_s, d_p) is minus cross(d_p, d_s) bit for bit, and so is
  // the quotient), and a triangle is looked at only if w_p and w_r can both be positive, i.e.
  // cross(d_r, d_s) and cross(d_p, d_s) have opposite signs (masks of the points s after i for
  // which cross(d_i, d_s) is positive or negative), as its least coordinate must be to beat any
  // triangle (best starts at 0). Dividing by the area keeps the sign of a nonzero quotient, and
  // a zero or negative w_p or w_r makes the least coordinate no larger than it (std::min over
  // {w_p, w_r, 1 - w_p - w_r} returns min(w_p, w_r) or less, even where the third is NaN), so
  // the triangles passed over are ones that could not have been picked; so is one whose w_p is
  // no more than the best least coordinate so far.
  std::array<Eigen::Vector2d, kMostBasePoints> d;
  for (std::size_t m = 0; m < count; ++m) d[m] = points[m] - q;
  Scalar best = 0;
  bool found = false;
  const auto offer = [&](std::size_t p, std::size_t r, std::size_t s, Scalar area, Scalar wp) {
    const Scalar wr = cross(d[s], d[p]) / area;
    const Scalar least = std::min({wp, wr, 1 - wp - wr});
    if (least > best) {
      best = least;
      base = {p, r, s};
      found = true;
    }
  };
  // A vertex on a face or an edge across an edge (most contacts of a drifting scene) has at most
  // four triangles: fewer than the masks' pairs.
  if (count <= kFewBasePoints) {
    for (std::size_t p = 0; p < count; ++p) {
      for (std::size_t r = p + 1; r < count; ++r) {
        for (std::size_t s = r + 1; s < count; ++s) {
          const Scalar area = cross(points[r] - points[p], points[s] - points[p]);
          if (!(std::abs(area) > 0)) continue;
          const Scalar wp = cross(d[r], d[s]) / area;
          if (wp > best) offer(p, r, s, area, wp);
        }
      }
    }
    return found;
  }
  std::array<std::array<Scalar, kMostBasePoints>, kMostBasePoints> c;
  // Bit j > i of positive[i] (negative[i]): cross(d_i, d_j) > 0 (< 0).
  std::array<std::uint32_t, kMostBasePoints> positive{};
  std::array<std::uint32_t, kMostBasePoints> negative{};
  for (std::size_t i = 0; i < count; ++i) {
    for (std::size_t j = i + 1; j < count; ++j) {
      const Scalar value = cross(d[i], d[j]);
      c[i][j] = value;
      positive[i] |= static_cast<std::uint32_t>(value > 0) << j;
      negative[i] |= static_cast<std::uint32_t>(value < 0) << j;
    }
  }
  for (std::size_t p = 0; p < count; ++p) {
    for (std::size_t r = p + 1; r < count; ++r) {
      // s after r with sign(c[r][s]) = -sign(c[p][s]).
      std::uint32_t candidates = ((positive[r] & negative[p]) | (negative[r] & positive[p])) &
                                 ~((2u << r) - 1);
      if (candidates == 0) continue;
      const Eigen::Vector2d side = points[r] - points[p];
      for (; candidates != 0; candidates &= candidates - 1) {
        const std::size_t s = static_cast<std::size_t>(__builtin_ctz(candidates));
        const Scalar area = cross(side, points[s] - points[p]);
        if (!(std::abs(area) > 0)) continue;
        const Scalar wp = c[r][s] / area;
        if (wp > best) offer(p, r, s, area, wp);
      }
    }
  }
  return found;
}

bool contact_tetrahedron(const FramedPair& pair, const Vector3& n, const ContactFeatures& features,
                         PairProof::Enclosing& out) {
  const std::size_t count = features.a.size() * features.b.size();
  if (count < 3 || count > kMostBasePoints) return false;
  int apex_a = out.a[3];
  int apex_b = out.b[3];
  const Vector3 apex = minkowski_support(pair.a, pair.b, -n, apex_a, apex_b).p;
  std::array<Vector3, kMostBasePoints> face;
  std::array<int, kMostBasePoints> face_a;
  std::array<int, kMostBasePoints> face_b;
  std::size_t k = 0;
  Scalar height = 0;
  for (int i : features.a) {
    for (int j : features.b) {
      face[k] = pair.b.vertex(j) - pair.a.vertex(i);
      face_a[k] = i;
      face_b[k] = j;
      height += n.dot(face[k]) / static_cast<Scalar>(count);
      ++k;
    }
  }
  const Scalar apex_height = n.dot(apex);
  if (!(apex_height > 0 && height < 0)) return false;
  // Where the line from the apex through the origin meets the face's plane, in coordinates of
  // that plane; the base is the triangle of face points around it with the largest least
  // barycentric coordinate (the one it is deepest inside).
  const Vector3 helper = std::abs(n.x()) < 0.6 ? Vector3::UnitX() : Vector3::UnitY();
  const Vector3 u = n.cross(helper).normalized();
  const Vector3 v = n.cross(u);
  const Vector3 meet = apex * (height / apex_height);
  const auto plane = [&](const Vector3& p) { return Eigen::Vector2d(u.dot(p), v.dot(p)); };
  const Eigen::Vector2d q = plane(meet);
  std::array<Eigen::Vector2d, kMostBasePoints> flat;
  for (std::size_t m = 0; m < count; ++m) flat[m] = plane(face[m]);
  std::array<std::size_t, 3> base{};
  if (!deepest_triangle(flat.data(), count, q, base)) return false;
  const std::array<Vector3, 4> corners{face[base[0]], face[base[1]], face[base[2]], apex};
  if (!encloses_origin(corners)) return false;
  for (int c = 0; c < 3; ++c) {
    out.a[c] = face_a[base[c]];
    out.b[c] = face_b[base[c]];
  }
  out.a[3] = apex_a;
  out.b[3] = apex_b;
  return true;
}

}  // namespace swarmcollide::detail
