// The point of least norm of a simplex of up to four points, in closed form; private to the
// library's sources.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "swarmcollide/types.hpp"

namespace swarmcollide::detail {

/// The nearest point to the origin of the hull of `s[0], ..., s[m-1]` (m <= 4, each `s[k].p` a
/// point), as positive weights on the smallest face of the simplex that holds it: that face's
/// points, in their order, into `face` (another array than `s`), their weights (summing to one
/// up to rounding) into `w`, and their count into `size`.
///
/// Closed form, as GJK projects (Ericson, Real-Time Collision Detection, 5.1): the origin's
/// barycentric coordinates in the simplex's affine hull; when all are positive the nearest point
/// is inside, otherwise it lies on a face opposite a point whose coordinate is not positive (only
/// those faces face the origin), and the nearest of those faces' nearest points is taken. The
/// coordinates come from cross products of the edges from `s[0]`, which keeps them accurate for
/// long thin simplexes. For degenerate simplexes (duplicate, collinear or coplanar points, to
/// within a sine of 1e-8) all faces are tried: the answer is always a convex combination of the
/// points, and the nearest one whenever the coordinates are decided above rounding.
/// `bounded`: the caller knows every coordinate is at most 2^100 in magnitude (points of a frame,
/// framed_body.hpp), so only the last point's are read to rule out the scaling below whenever
/// one of them is at least 2^-100; the answer is the same bit for bit.
/// `point` and `norm2`: the nearest point, the combination of `face` with weights `w`, and its
/// squared norm, which Wolfe's algorithm takes as its corral's point instead of forming it again:
/// the weights times the points summed in order, as combination() below sums them onto a zero
/// vector, so the same values (only a zero coordinate's sign may differ, -0 where
/// combination's first sum makes +0).
template <class Point>
void nearest_simplex_point(const std::array<Point, 4>& s, int m, std::array<Point, 4>& face,
                           std::array<Scalar, 4>& w, int& size, bool bounded, Vector3& point,
                           Scalar& norm2);

/// The combination of the first `m` points of `s` with weights `w`, summed in order onto a zero
/// vector.
template <class Point>
Vector3 combination(const std::array<Point, 4>& s, const std::array<Scalar, 4>& w, int m) {
  Vector3 x = Vector3::Zero();
  for (int k = 0; k < m; ++k) x += w[k] * s[k].p;
  return x;
}

/// The same without the point.
template <class Point>
void nearest_simplex_point(const std::array<Point, 4>& s, int m, std::array<Point, 4>& face,
                           std::array<Scalar, 4>& w, int& size, bool bounded = false) {
  Vector3 point;
  Scalar norm2;
  nearest_simplex_point(s, m, face, w, size, bounded, point, norm2);
}

namespace nearest_simplex_detail {

// Below this sine of the angle between an edge and the rest of the simplex (the line of the
// other edge, the plane of the other two), the barycentric coordinates are left undecided by
// rounding: every face is tried.
constexpr Scalar kFlat = 1e-8;

// Dot and cross products of 3-vectors on their coordinates, for the triangle's coordinates:
// kept in scalar registers they take fewer instructions than Eigen's packets of two, which
// shuffle lanes (a triangle's projection about 15% fewer). The dot product sums as Eigen's
// packets of two sum a Vector3's, (x + y) + z, so the values are the same where Eigen
// vectorises (SSE2, NEON).
inline Scalar dot(const Vector3& u, const Vector3& v) {
  return (u.x() * v.x() + u.y() * v.y()) + u.z() * v.z();
}

inline Vector3 cross(const Vector3& u, const Vector3& v) {
  return {u.y() * v.z() - u.z() * v.y(), u.z() * v.x() - u.x() * v.z(),
          u.x() * v.y() - u.y() * v.x()};
}

// The nearest point found so far: a face of the simplex (`size` of the caller's points
// `simplex`, in their order, written straight into the caller's `face`) with weights on them
// (into the caller's `weight`), their combination `point` (the weights times the points as the
// offers were given them, summed in order; a tetrahedron's interior point is left to the caller)
// and its squared norm. Candidates are offered to it in place: returning faces by value, or
// keeping their indices to copy the points afterwards, costs more than the arithmetic here.
template <class Point>
struct Nearest {
  Nearest(const std::array<Point, 4>& points, std::array<Point, 4>& into,
          std::array<Scalar, 4>& weights)
      : simplex(points), face(into), weight(weights) {}

  const std::array<Point, 4>& simplex;
  std::array<Point, 4>& face;
  std::array<Scalar, 4>& weight;
  int size = 0;
  Scalar norm2 = std::numeric_limits<Scalar>::infinity();
  Vector3 point;
};

template <class Point>
inline void offer_vertex(const Vector3& p, int i, Nearest<Point>& best) {
  const Scalar norm2 = p.squaredNorm();
  if (!(norm2 < best.norm2)) return;
  best.face[0] = best.simplex[i];
  best.weight[0] = 1;
  best.size = 1;
  best.norm2 = norm2;
  best.point = p;
}

// The segment from a (index ia) to b (index ib). True when its nearest point lies inside it
// (both weights positive).
template <class Point>
inline bool offer_segment(const Vector3& a, const Vector3& b, int ia, int ib, Nearest<Point>& best) {
  const Vector3 ab = b - a;
  const Scalar along = -a.dot(ab);  // the origin's projection, times |ab|^2
  if (!(along > 0)) {
    offer_vertex(a, ia, best);
    return false;
  }
  const Scalar length2 = ab.squaredNorm();
  if (!(along < length2)) {
    offer_vertex(b, ib, best);
    return false;
  }
  const Scalar wb = along / length2;
  const Scalar wa = 1 - wb;
  if (!(wa > 0)) {
    offer_vertex(b, ib, best);
    return false;
  }
  const Vector3 point = wa * a + wb * b;
  const Scalar norm2 = point.squaredNorm();
  if (!(norm2 < best.norm2)) return true;
  best.face[0] = best.simplex[ia];
  best.face[1] = best.simplex[ib];
  best.weight[0] = wa;
  best.weight[1] = wb;
  best.size = 2;
  best.norm2 = norm2;
  best.point = point;
  return true;
}

// The triangle a, b, c (indices ia, ib, ic), whose edges `ab = b - a`, `ac = c - a` and normal
// `n = ab x ac` a tetrahedron has already computed. True when its nearest point lies inside it
// (three positive weights).
template <class Point>
inline bool offer_triangle(const Vector3& a, const Vector3& b, const Vector3& c, const Vector3& ab,
                           const Vector3& ac, const Vector3& n, int ia, int ib, int ic,
                           Nearest<Point>& best) {
  const Scalar nn = dot(n, n);
  // The barycentric coordinates times |n|^2, by Lagrange's identity: -n . (a x ac) and
  // -n . (ab x a), as triple products through the one cross product n x a.
  const Vector3 t = cross(n, a);
  const Scalar vb = -dot(ac, t);
  const Scalar vc = dot(ab, t);
  const Scalar va = nn - vb - vc;
  const Scalar ab2 = dot(ab, ab);
  const Scalar ac2 = dot(ac, ac);
  if (!(nn > kFlat * kFlat * ab2 * ac2)) {
    offer_segment(b, c, ib, ic, best);
    offer_segment(a, c, ia, ic, best);
    offer_segment(a, b, ia, ib, best);
    return false;
  }
  if (va > 0 && vb > 0 && vc > 0) {
    const Scalar wb = vb / nn;
    const Scalar wc = vc / nn;
    const Scalar wa = 1 - wb - wc;
    if (wa > 0 && wb > 0 && wc > 0) {
      const Scalar px = (wa * a.x() + wb * b.x()) + wc * c.x();
      const Scalar py = (wa * a.y() + wb * b.y()) + wc * c.y();
      const Scalar pz = (wa * a.z() + wb * b.z()) + wc * c.z();
      const Scalar norm2 = (px * px + py * py) + pz * pz;
      const Vector3 point(px, py, pz);
      if (norm2 < best.norm2) {
        best.face[0] = best.simplex[ia];
        best.face[1] = best.simplex[ib];
        best.face[2] = best.simplex[ic];
        best.weight[0] = wa;
        best.weight[1] = wb;
        best.weight[2] = wc;
        best.size = 3;
        best.norm2 = norm2;
        best.point = point;
      }
      return true;
    }
    // Coordinates positive yet a weight rounded to zero: every edge.
    offer_segment(b, c, ib, ic, best);
    offer_segment(a, c, ia, ic, best);
    offer_segment(a, b, ia, ib, best);
    return false;
  }
  // Outside: the edges opposite the coordinates that are not positive, whose lines separate the
  // origin's foot in the triangle's plane from the triangle. Where that foot's own foot on such an
  // edge lies inside the edge, it is the triangle's nearest point (every point of the triangle is
  // beyond the line, so at least as far from the origin): the other edges are not tried. The
  // nearest point is the same in exact arithmetic; rounding may choose another edge only where
  // two edges' points are equally near to within it.
  if (!(va > 0) && offer_segment(b, c, ib, ic, best)) return false;
  if (!(vb > 0) && offer_segment(a, c, ia, ic, best)) return false;
  if (!(vc > 0)) offer_segment(a, b, ia, ib, best);
  return false;
}

// The triangle a, b, c (indices ia, ib, ic). True when its nearest point lies inside it.
template <class Point>
inline bool offer_triangle(const Vector3& a, const Vector3& b, const Vector3& c, int ia, int ib,
                           int ic, Nearest<Point>& best) {
  const Vector3 ab = b - a;
  const Vector3 ac = c - a;
  return offer_triangle(a, b, c, ab, ac, ab.cross(ac), ia, ib, ic, best);
}

// The tetrahedron a, b, c, d (indices 0 to 3).
template <class Point>
inline void offer_tetrahedron(const Vector3& a, const Vector3& b, const Vector3& c,
                              const Vector3& d, Nearest<Point>& best) {
  const Vector3 e1 = b - a;
  const Vector3 e2 = c - a;
  const Vector3 e3 = d - a;
  // The normals of the faces through a (edges from a, crossed in order): the cofactors of the
  // origin's coordinates, and the normals the offers of those faces need. Their coordinates are
  // written one by one (scalar products), so they are read one by one too (dot, not Eigen's
  // packets of two): a packet read of two coordinates stored apart waits for both stores to
  // reach the cache (no store-to-load forwarding), some 4% of a 4-point overlapping distance.
  const Vector3 n_acd = cross(e2, e3);
  const Vector3 n_abd = cross(e1, e3);
  const Vector3 n_abc = cross(e1, e2);
  const Scalar volume = dot(e1, n_acd);
  // Flat: e1 nearly in the plane of e2 and e3, or those two nearly parallel.
  const Scalar area2 = dot(n_acd, n_acd);
  constexpr Scalar kFlat2 = kFlat * kFlat;
  if (!(volume * volume > kFlat2 * e1.squaredNorm() * area2 &&
        area2 > kFlat2 * e2.squaredNorm() * e3.squaredNorm())) {
    offer_triangle(b, c, d, 1, 2, 3, best);
    offer_triangle(a, c, d, e2, e3, n_acd, 0, 2, 3, best);
    offer_triangle(a, b, d, e1, e3, n_abd, 0, 1, 3, best);
    offer_triangle(a, b, c, e1, e2, n_abc, 0, 1, 2, best);
    return;
  }
  // Cramer's rule (the triple products e1 . (r x e3) and e1 . (e2 x r) read as r . (e3 x e1) and
  // r . (e1 x e2)); where the origin is inside, repeated once for its residual (iterative
  // refinement), the common point's distance from the origin: for a flat tetrahedron the first
  // solve's can be far above rounding.
  const Scalar inverse = 1 / volume;
  std::array<Scalar, 4> alpha{};
  Vector3 r = a;
  const auto interior = [&alpha] {
    alpha[0] = 1 - alpha[1] - alpha[2] - alpha[3];
    return alpha[0] > 0 && alpha[1] > 0 && alpha[2] > 0 && alpha[3] > 0;
  };
  bool inside = false;
  for (int pass = 0; pass < 2; ++pass) {
    alpha[1] -= dot(r, n_acd) * inverse;
    alpha[2] += dot(r, n_abd) * inverse;
    alpha[3] -= dot(r, n_abc) * inverse;
    inside = interior();
    if (!inside || pass == 1) break;
    r = a + alpha[1] * e1 + alpha[2] * e2 + alpha[3] * e3;
  }
  if (inside) {
    best.face = best.simplex;
    best.weight = alpha;
    best.size = 4;
    return;
  }
  // The faces opposite the coordinates that are not positive, whose planes separate the origin
  // from the tetrahedron. Where the origin's foot on such a face lies inside the face, it is the
  // tetrahedron's nearest point (every point of it is beyond the plane): the other faces are not
  // tried (as for a triangle's edges, rounding aside the same point). The face opposite the most
  // negative coordinate is tried first, the likeliest to hold it (on the curved benches, Wolfe's
  // tetrahedra outside the origin have two or three such faces, and the first in index order held
  // it in 39% of its tries). The order matters only where rounding does (two faces each taking
  // the foot as inside, or two different edges or vertices exactly as near): in exact arithmetic
  // only the face holding the nearest point is taken, and every face offers the same edges (each
  // from its lower index, the same values whichever face offers it) and vertices.
  const auto offer_face = [&](int k) {
    switch (k) {
      case 0:
        return offer_triangle(b, c, d, 1, 2, 3, best);
      case 1:
        return offer_triangle(a, c, d, e2, e3, n_acd, 0, 2, 3, best);
      case 2:
        return offer_triangle(a, b, d, e1, e3, n_abd, 0, 1, 3, best);
      default:
        return offer_triangle(a, b, c, e1, e2, n_abc, 0, 1, 2, best);
    }
  };
  int first = 0;
  for (int k = 1; k < 4; ++k) {
    if (alpha[k] < alpha[first]) first = k;
  }
  if (!(alpha[first] > 0) && offer_face(first)) return;
  for (int k = 0; k < 4; ++k) {
    if (k != first && !(alpha[k] > 0) && offer_face(k)) return;
  }
}

// The nearest point of the hull of the first m of a, b, c, d, offered to `best`.
template <class Point>
inline void offer_simplex(const Vector3& a, const Vector3& b, const Vector3& c, const Vector3& d,
                          int m, Nearest<Point>& best) {
  switch (m) {
    case 1:
      offer_vertex(a, 0, best);
      break;
    case 2:
      offer_segment(a, b, 0, 1, best);
      break;
    case 3:
      offer_triangle(a, b, c, 0, 1, 2, best);
      break;
    default:
      offer_tetrahedron(a, b, c, d, best);
      break;
  }
}

// nearest_simplex_point for points whose largest coordinate `reach` is far from one: the
// triangle's squared normal is of the fourth power of the coordinates, which overflows or
// underflows there, so the points are first scaled by a power of two (exactly), which leaves the
// weights as they are; the point is then the combination of the caller's points.
template <class Point>
[[gnu::noinline, gnu::cold]] void nearest_scaled_simplex_point(
    const std::array<Point, 4>& s, int m, Scalar reach, std::array<Point, 4>& face,
    std::array<Scalar, 4>& w, int& size, Vector3& point, Scalar& norm2) {
  const Scalar factor = std::ldexp(Scalar(1), -std::ilogb(reach));
  std::array<Vector3, 4> scaled;
  for (int k = 0; k < m; ++k) scaled[k] = factor * s[k].p;
  Nearest<Point> best{s, face, w};
  offer_simplex(scaled[0], scaled[1], scaled[2], scaled[3], m, best);
  size = best.size;
  point = combination(face, w, size);
  norm2 = point.squaredNorm();
}

}  // namespace nearest_simplex_detail

template <class Point>
void nearest_simplex_point(const std::array<Point, 4>& s, int m, std::array<Point, 4>& face,
                           std::array<Scalar, 4>& w, int& size, bool bounded, Vector3& point,
                           Scalar& norm2) {
  using namespace nearest_simplex_detail;
  constexpr Scalar kSmallest = 0x1p-100;
  constexpr Scalar kLargest = 0x1p100;
  // The largest coordinate (`reach`) in [2^-100, 2^100]: no scaling.
  const Vector3& last = s[m - 1].p;
  const bool in_range = bounded && (std::abs(last.x()) >= kSmallest ||
                                    std::abs(last.y()) >= kSmallest ||
                                    std::abs(last.z()) >= kSmallest);
  if (!in_range) {
    Vector3 largest = s[0].p.cwiseAbs();
    for (int k = 1; k < m; ++k) largest = largest.cwiseMax(s[k].p.cwiseAbs());
    const Scalar reach = largest.maxCoeff();
    if ((reach < kSmallest && reach > 0) || (reach > kLargest && std::isfinite(reach))) {
      nearest_scaled_simplex_point(s, m, reach, face, w, size, point, norm2);
      return;
    }
  }
  Nearest<Point> best{s, face, w};
  offer_simplex(s[0].p, s[1].p, s[2].p, s[3].p, m, best);
  size = best.size;
  // The offers' point is the combination of the caller's points, in the face's order; a
  // tetrahedron's interior point (Cramer's) is not.
  if (best.size > 0 && best.size < 4) {
    point = best.point;
    norm2 = best.norm2;
    return;
  }
  point = combination(face, w, size);
  norm2 = point.squaredNorm();
}

}  // namespace swarmcollide::detail
