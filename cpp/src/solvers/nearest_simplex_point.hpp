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
/// the weights times the points summed in order, as combination() (wolfe_min_norm.hpp) sums them
/// onto a zero vector, so the same values (only a zero coordinate's sign may differ, -0 where
/// combination's first sum makes +0).
template <class Point>
void nearest_simplex_point(const std::array<Point, 4>& s, int m, std::array<Point, 4>& face,
                           std::array<Scalar, 4>& w, int& size, bool bounded, Vector3& point,
                           Scalar& norm2);

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

// The nearest point found so far: a face of the simplex (`size` of its points, by index,
// increasing) with weights on them, their combination `point` (the weights times the points,
// summed in order; a tetrahedron's interior point is left to the caller) and its squared norm.
// Candidates are offered to it in place: returning faces by value costs more than the
// arithmetic here.
struct Nearest {
  std::array<int, 4> index{};
  std::array<Scalar, 4> weight{};
  int size = 0;
  Scalar norm2 = std::numeric_limits<Scalar>::infinity();
  Vector3 point;
};

inline void offer_vertex(const Vector3& p, int i, Nearest& best) {
  const Scalar norm2 = p.squaredNorm();
  if (!(norm2 < best.norm2)) return;
  best.index[0] = i;
  best.weight[0] = 1;
  best.size = 1;
  best.norm2 = norm2;
  best.point = p;
}

// The segment from a (index ia) to b (index ib). True when its nearest point lies inside it
// (both weights positive).
inline bool offer_segment(const Vector3& a, const Vector3& b, int ia, int ib, Nearest& best) {
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
  best.index[0] = ia;
  best.index[1] = ib;
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
inline bool offer_triangle(const Vector3& a, const Vector3& b, const Vector3& c, const Vector3& ab,
                           const Vector3& ac, const Vector3& n, int ia, int ib, int ic,
                           Nearest& best) {
  const Scalar nn = n.squaredNorm();
  // The barycentric coordinates times |n|^2, by Lagrange's identity: -n . (a x ac) and
  // -n . (ab x a), as triple products through the one cross product n x a.
  const Vector3 t = n.cross(a);
  const Scalar vb = -ac.dot(t);
  const Scalar vc = ab.dot(t);
  const Scalar va = nn - vb - vc;
  if (!(nn > kFlat * kFlat * ab.squaredNorm() * ac.squaredNorm())) {
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
      const Vector3 point = wa * a + wb * b + wc * c;
      const Scalar norm2 = point.squaredNorm();
      if (norm2 < best.norm2) {
        best.index[0] = ia;
        best.index[1] = ib;
        best.index[2] = ic;
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
inline bool offer_triangle(const Vector3& a, const Vector3& b, const Vector3& c, int ia, int ib,
                           int ic, Nearest& best) {
  const Vector3 ab = b - a;
  const Vector3 ac = c - a;
  return offer_triangle(a, b, c, ab, ac, ab.cross(ac), ia, ib, ic, best);
}

// The tetrahedron a, b, c, d (indices 0 to 3).
inline void offer_tetrahedron(const Vector3& a, const Vector3& b, const Vector3& c,
                              const Vector3& d, Nearest& best) {
  const Vector3 e1 = b - a;
  const Vector3 e2 = c - a;
  const Vector3 e3 = d - a;
  // The normals of the faces through a (edges from a, crossed in order): the cofactors of the
  // origin's coordinates, and the normals the offers of those faces need.
  const Vector3 n_acd = e2.cross(e3);
  const Vector3 n_abd = e1.cross(e3);
  const Vector3 n_abc = e1.cross(e2);
  const Scalar volume = e1.dot(n_acd);
  // Flat: e1 nearly in the plane of e2 and e3, or those two nearly parallel.
  const Scalar area2 = n_acd.squaredNorm();
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
    alpha[1] -= r.dot(n_acd) * inverse;
    alpha[2] += r.dot(n_abd) * inverse;
    alpha[3] -= r.dot(n_abc) * inverse;
    r = a + alpha[1] * e1 + alpha[2] * e2 + alpha[3] * e3;
    inside = interior();
    if (!inside) break;
  }
  if (inside) {
    best.index = {0, 1, 2, 3};
    best.weight = alpha;
    best.size = 4;
    best.norm2 = r.squaredNorm();
    return;
  }
  // The faces opposite the coordinates that are not positive, whose planes separate the origin
  // from the tetrahedron. Where the origin's foot on such a face lies inside the face, it is the
  // tetrahedron's nearest point (every point of it is beyond the plane): the other faces are not
  // tried (as for a triangle's edges, rounding aside the same point).
  if (!(alpha[0] > 0) && offer_triangle(b, c, d, 1, 2, 3, best)) return;
  if (!(alpha[1] > 0) && offer_triangle(a, c, d, e2, e3, n_acd, 0, 2, 3, best)) return;
  if (!(alpha[2] > 0) && offer_triangle(a, b, d, e1, e3, n_abd, 0, 1, 3, best)) return;
  if (!(alpha[3] > 0)) offer_triangle(a, b, c, e1, e2, n_abc, 0, 1, 2, best);
}

}  // namespace nearest_simplex_detail

template <class Point>
void nearest_simplex_point(const std::array<Point, 4>& s, int m, std::array<Point, 4>& face,
                           std::array<Scalar, 4>& w, int& size, bool bounded, Vector3& point,
                           Scalar& norm2) {
  using namespace nearest_simplex_detail;
  std::array<Vector3, 4> scaled;
  std::array<const Vector3*, 4> p = {&s[0].p, &s[1].p, &s[2].p, &s[3].p};
  // The triangle's squared normal is of the fourth power of the coordinates, which overflows or
  // underflows for coordinates far from one: such points are first scaled by a power of two
  // (exactly), which leaves the weights as they are.
  constexpr Scalar kSmallest = 0x1p-100;
  constexpr Scalar kLargest = 0x1p100;
  // The largest coordinate (`reach`) is then in [2^-100, 2^100]: no scaling.
  const Vector3& last = s[m - 1].p;
  const bool in_range = bounded && (std::abs(last.x()) >= kSmallest ||
                                    std::abs(last.y()) >= kSmallest ||
                                    std::abs(last.z()) >= kSmallest);
  Scalar reach = 1;
  bool rescaled = false;
  if (!in_range) {
    Vector3 largest = s[0].p.cwiseAbs();
    for (int k = 1; k < m; ++k) largest = largest.cwiseMax(s[k].p.cwiseAbs());
    reach = largest.maxCoeff();
  }
  if ((reach < kSmallest && reach > 0) || (reach > kLargest && std::isfinite(reach))) {
    const Scalar factor = std::ldexp(Scalar(1), -std::ilogb(reach));
    for (int k = 0; k < m; ++k) {
      scaled[k] = factor * s[k].p;
      p[k] = &scaled[k];
    }
    rescaled = true;
  }
  Nearest f;
  switch (m) {
    case 1:
      offer_vertex(*p[0], 0, f);
      break;
    case 2:
      offer_segment(*p[0], *p[1], 0, 1, f);
      break;
    case 3:
      offer_triangle(*p[0], *p[1], *p[2], 0, 1, 2, f);
      break;
    default:
      offer_tetrahedron(*p[0], *p[1], *p[2], *p[3], f);
      break;
  }
  for (int k = 0; k < f.size; ++k) {
    face[k] = s[f.index[k]];
    w[k] = f.weight[k];
  }
  size = f.size;
  // The offers' point is the combination of the points they were given, in the face's order:
  // the caller's own unless they were scaled. A tetrahedron's interior point (Cramer's) is not.
  if (!rescaled && f.size > 0 && f.size < 4) {
    point = f.point;
    norm2 = f.norm2;
    return;
  }
  point = Vector3::Zero();
  for (int k = 0; k < f.size; ++k) point += w[k] * face[k].p;
  norm2 = point.squaredNorm();
}

}  // namespace swarmcollide::detail
