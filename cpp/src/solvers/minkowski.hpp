// Support queries on the Minkowski difference B - A of a framed pair; private to the library.
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include "../geometry/framed_body.hpp"
#include "wolfe_min_norm.hpp"

namespace swarmcollide::detail {

/// The support oracle of B - A: the point y_j - x_i that minimises `d . (y - x)`, with the
/// indices i (of A) and j (of B) that give it. `hint_a`/`hint_b` start the hill climbing of large
/// bodies and receive the answer, so nearby directions cost a few neighbour checks.
inline OraclePoint minkowski_support(const FramedBody& a, const FramedBody& b, const Vector3& d,
                                     int& hint_a, int& hint_b) {
  hint_a = a.support_index(d, hint_a);
  hint_b = b.support_index(-d, hint_b);
  return {b.vertex(hint_b) - a.vertex(hint_a), hint_a, hint_b};
}

/// Separation along the unit direction `n`: `min_j n.y_j - max_i n.x_i`, a lower bound on the
/// (signed) distance for every n. The support indices are started from, and returned in, the
/// hints.
inline Scalar separation(const FramedBody& a, const FramedBody& b, const Vector3& n, int& hint_a,
                         int& hint_b) {
  return n.dot(minkowski_support(a, b, n, hint_a, hint_b).p);
}

inline Scalar separation(const FramedBody& a, const FramedBody& b, const Vector3& n) {
  int hint_a = -1;
  int hint_b = -1;
  return separation(a, b, n, hint_a, hint_b);
}

/// Separation along `n` from exact scans of both bodies (FramedBody::exact_support_index):
/// `min_j n.y_j - max_i n.x_i` as computed in the frame, within `separation_margin` (of the
/// largest frame coordinate) of the exact separation along `n / |n|`, so a proven lower bound may
/// rest on it; `separation` may not, as its supports can fall short. The support indices are
/// returned in `ia` and `ib`.
inline Scalar exact_separation(const FramedBody& a, const FramedBody& b, const Vector3& n, int& ia,
                               int& ib) {
  ia = a.exact_support_index(n);
  ib = b.exact_support_index(-n);
  return b.height(ib, n) - a.height(ia, n);
}

inline Scalar exact_separation(const FramedBody& a, const FramedBody& b, const Vector3& n) {
  int ia = 0;
  int ib = 0;
  return exact_separation(a, b, n, ia, ib);
}

/// The points of `body` within `slack` below its supporting plane along `n`, whose highest point
/// is `top`, into `found`: a scan for small bodies (in index order), a flood over the hull's edge
/// graph from `top` for large ones (the points above a plane span a connected subgraph of a
/// polytope's graph). `visited` is all zero between calls, and grown to the body's size here.
void supporting_feature(const FramedBody& body, const Vector3& n, int top, Scalar slack,
                        std::vector<char>& visited, std::vector<int>& found);

/// The support oracle of `conv(b's points fb) - conv(a's points fa)`: the difference that
/// minimises `d . (y - x)` over the two features (the first one on ties), with its indices.
inline OraclePoint feature_support(const FramedBody& a, const std::vector<int>& fa,
                                   const FramedBody& b, const std::vector<int>& fb,
                                   const Vector3& d) {
  int i = fa[0];
  Scalar highest = a.height(i, d);
  for (std::size_t k = 1; k < fa.size(); ++k) {
    const Scalar h = a.height(fa[k], d);
    if (h > highest) {
      highest = h;
      i = fa[k];
    }
  }
  int j = fb[0];
  Scalar lowest = b.height(j, d);
  for (std::size_t k = 1; k < fb.size(); ++k) {
    const Scalar h = b.height(fb[k], d);
    if (h < lowest) {
      lowest = h;
      j = fb[k];
    }
  }
  return {b.vertex(j) - a.vertex(i), i, j};
}

/// True when the origin lies inside the tetrahedron of `points` (each of norm at most ~2) by
/// more than the rounding of the points and of the orientation tests: a proof that the bodies
/// whose difference they are share a point.
bool encloses_origin(const std::array<Vector3, 4>& points);
/// The same, with the origin's barycentric coordinates in the tetrahedron (positive, summing to
/// one up to rounding) in `weights` when it is enclosed.
bool encloses_origin(const std::array<Vector3, 4>& points, std::array<Scalar, 4>& weights);

}  // namespace swarmcollide::detail
