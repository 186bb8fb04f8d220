// The chain of a section's support points that the side depths of cylinders and cones close on
// (cylinder_side.cpp, cone_side.cpp), and the wedge test their bounds share; private to the
// library's sources.
#pragma once

#include <array>
#include <cmath>
#include <limits>

#include "../geometry/curved_depth.hpp"
#include "../geometry/framed_body.hpp"
#include "expanding_polytope.hpp"
#include "swarmcollide/types.hpp"

namespace swarmcollide::detail {

/// What a side depth (cylinder_side_depth, cone_side_depth) proved.
struct SideDepth {
  /// Proven: the origin lies at least this deep in `A - B` (frame units); -infinity where
  /// nothing was proven.
  Scalar lower = -std::numeric_limits<Scalar>::infinity();
  /// The unit direction normal to the side along which `A - B`'s support was least in the
  /// section (the penetration's normal, from A to B).
  Vector3 normal = Vector3::UnitX();
  /// The support points of the other body it asked for.
  int steps = 0;
};

namespace side_chain {

using Vector2 = Eigen::Matrix<Scalar, 2, 1>;

// The chain's first corners lie this far (rad) either side of the best normal's azimuth: far,
// for the wedge (the faces nearer than the bound of a polytope expanded to 2^-12 reach a few
// hundredths of a radian from it), and near, where the expansion so far puts the deepest
// azimuth, which spares the chain the steps down to it.
inline constexpr Scalar kHalfSpread = 0.35;
inline constexpr Scalar kNearSpread = 0x1p-5;
inline constexpr int kMostCorners = 48;
// How far inside the wedge (as a sine) a near face's corners must lie: room for the rotation's
// rounding (a few roundoffs; a valid pose's skew is under 1e-9 and comes off the bound anyway).
inline constexpr Scalar kWedgeMargin = 0x1p-26;
// The steps of the secant search for the deepest azimuth (each a support point of the other
// body), which settles a smooth boundary in three or four.
inline constexpr int kMostSecantSteps = 8;

inline Scalar cross(const Vector2& p, const Vector2& q) { return p.x() * q.y() - p.y() * q.x(); }

/// The plane direction `middle` turned counterclockwise by `angle`.
inline Vector2 turned(const Vector2& middle, Scalar angle) {
  const Scalar c = std::cos(angle);
  const Scalar s = std::sin(angle);
  return Vector2(c * middle.x() - s * middle.y(), c * middle.y() + s * middle.x());
}

/// An edge of the chain, from corner k to k + 1.
struct Edge {
  Vector2 normal = Vector2::Zero();  // outward, unit to rounding
  Scalar distance = 0;               // from the origin to its line
  Scalar bound = 0;                  // at most `normal . corner` at both ends (rounding taken off)
  bool settled = false;
};

inline Edge measure(const Vector2& from, const Vector2& to) {
  Edge edge;
  const Vector2 along = to - from;
  const Scalar length = along.norm();
  if (!(length > 0)) {
    edge.distance = edge.bound = std::numeric_limits<Scalar>::infinity();
    return edge;
  }
  const Scalar inverse = 1 / length;
  edge.normal = Vector2(along.y() * inverse, -along.x() * inverse);
  edge.distance = cross(from, along) * inverse;
  // The normal is perpendicular to the rounded difference within some 4u, so its products with
  // the two ends differ from the distance by 16u of their lengths (section_depth's analysis
  // gives 12u for the quotient).
  const Scalar rounding = 24 * kRoundoff * (from.norm() + to.norm() + length);
  edge.bound = std::min(edge.normal.dot(from), edge.normal.dot(to));
  edge.bound = std::min(edge.bound, edge.distance) - rounding;
  return edge;
}

/// The chain of `count` corners (each with a `point` of the section's plane, counterclockwise)
/// grown where its nearest edge is, by the section's support point along that edge's normal,
/// until that point lies within `gap` of it (or kMostCorners); returns the nearest edge.
/// `support(w)` is the section's corner along the plane direction w.
template <class Corner, class Support>
int close_chain(std::array<Corner, kMostCorners>& corners, std::array<Edge, kMostCorners>& edges,
                int& count, Scalar gap, const Support& support) {
  for (int k = 0; k + 1 < count; ++k) edges[k] = measure(corners[k].point, corners[k + 1].point);
  int nearest = 0;
  for (;;) {
    nearest = 0;
    for (int k = 1; k + 1 < count; ++k) {
      if (edges[k].distance < edges[nearest].distance) nearest = k;
    }
    Edge& edge = edges[nearest];
    if (!std::isfinite(edge.distance) || edge.settled || count == kMostCorners) break;
    const Corner farther = support(edge.normal);
    if (!(edge.normal.dot(farther.point - corners[nearest].point) > gap)) {
      edge.settled = true;
      continue;
    }
    for (int k = count; k > nearest + 1; --k) {
      corners[k] = corners[k - 1];
      edges[k] = edges[k - 1];
    }
    corners[nearest + 1] = farther;
    ++count;
    edges[nearest] = measure(corners[nearest].point, corners[nearest + 1].point);
    edges[nearest + 1] = measure(corners[nearest + 1].point, corners[nearest + 2].point);
  }
  return nearest;
}

/// The chain around the plane direction `middle` (the expansion's best normal's), closed as
/// close_chain closes it; its nearest edge, or -1 where `on_side(corner)` refuses the corner
/// along `middle` or one near it. It starts at `middle` and either side of it, near (where the
/// expansion so far puts the deepest direction: the first steps are the chain's nearest) and far
/// (the wedge its bound may cover); the other body's support along the best normal lies off
/// the side where the deepest point is a rim's or a cap's, and no run of corners would be found.
template <class Corner, class Support, class OnSide>
int open_chain(const Vector2& middle, Scalar gap, const Support& support, const OnSide& on_side,
               std::array<Corner, kMostCorners>& corners, std::array<Edge, kMostCorners>& edges,
               int& count) {
  corners[2] = support(middle);
  if (!on_side(corners[2])) return -1;
  corners[1] = support(turned(middle, -kNearSpread));
  corners[3] = support(turned(middle, kNearSpread));
  if (!on_side(corners[1]) || !on_side(corners[3])) return -1;
  corners[0] = support(turned(middle, -kHalfSpread));
  corners[4] = support(turned(middle, kHalfSpread));
  count = 5;
  const int nearest = close_chain(corners, edges, count, gap, support);
  return std::isfinite(edges[nearest].distance) ? nearest : -1;
}

/// The plane direction along which the section is least deep, between the directions `from`
/// and `to` (counterclockwise, less than a half-turn apart): where the support point's offset
/// across the direction, `s(w) . t(w)` for the counterclockwise tangent t, changes sign
/// (meridian_depth.cpp's deepest_direction), found by the Illinois variant of the secant method
/// on the chord between them, which settles a smooth boundary in three or four steps. Where it
/// does not settle in kMostSecantSteps the offset jumps through zero (a flat edge of the
/// section, where the support point jumps from one end to the other, as along two cylinders'
/// sides), and the nearest edge's normal, `otherwise`, is that edge's (to the chain's gap); so
/// too where the two do not bracket it. `support(w)` is the section's corner along w, whose
/// point's offset is zero to `rounding`.
template <class Support>
Vector2 deepest_azimuth(const Support& support, Scalar rounding, const Vector2& from,
                        const Vector2& to, const Vector2& otherwise) {
  const auto at = [&](Scalar s) {
    const Vector2 w = from + s * (to - from);
    return Vector2(w.normalized());
  };
  // The offset, and whether it is zero to its rounding.
  bool settled = false;
  const auto across = [&](const Vector2& w) {
    const Vector2 point = support(w).point;
    const Scalar offset = point.dot(Vector2(-w.y(), w.x()));
    settled = std::abs(offset) <= rounding;
    return offset;
  };
  Scalar low = 0;
  Scalar high = 1;
  Scalar f_low = across(from);
  Scalar f_high = across(to);
  if (!(f_low <= 0 && f_high >= 0)) return otherwise;
  int kept_side = 0;
  for (int step = 0; step < kMostSecantSteps; ++step) {
    Scalar s = high - f_high * (high - low) / (f_high - f_low);
    if (!(s > low && s < high)) s = (low + high) / 2;
    const Vector2 w = at(s);
    const Scalar f = across(w);
    if (settled) return w;
    if (f < 0) {
      low = s;
      f_low = f;
      if (kept_side == -1) f_high /= 2;
      kept_side = -1;
    } else {
      high = s;
      f_high = f;
      if (kept_side == 1) f_low /= 2;
      kept_side = 1;
    }
  }
  return otherwise;
}

/// The run of edges' normals, from `first` to `last - 1`, each within a quarter-turn of
/// `middle` (so that the arc between any two is under a half-turn): false where one is not;
/// else `clockwise` and `counterclockwise` are the normals most clockwise and most
/// counterclockwise from the middle, and `bound` the least of their bounds.
inline bool run_arc(const std::array<Edge, kMostCorners>& edges, int first, int last,
                    const Vector2& middle, Vector2& clockwise, Vector2& counterclockwise,
                    Scalar& bound) {
  bound = std::numeric_limits<Scalar>::infinity();
  clockwise = edges[first].normal;
  counterclockwise = edges[first].normal;
  for (int k = first; k < last; ++k) {
    const Edge& edge = edges[k];
    if (!(edge.normal.dot(middle) > 0)) return false;
    bound = std::min(bound, edge.bound);
    if (cross(edge.normal, clockwise) > 0) clockwise = edge.normal;
    if (cross(counterclockwise, edge.normal) > 0) counterclockwise = edge.normal;
  }
  return true;
}

/// Whether the bound `lower` holds along every direction of A - B that the polytope's faces
/// nearer than it leave to the wedge: the directions `body`'s own frame sees on the inner side
/// of each of `walls` (inward unit normals, in the body's axes). A face passes where every
/// direction through it along which the face itself bounds the depth by less (those within
/// `acos(low / lower)` of its normal) lies in the wedge, or where its corners do (then every
/// direction through it does).
template <std::size_t Walls>
bool faces_in_wedge(const ExpandingPolytope& polytope, const FramedBody& body,
                    const std::array<Vector3, Walls>& walls, int wall_count, Scalar lower) {
  const Scalar margin = kWedgeMargin + rotation_skew(body);
  const auto inside = [&](const Vector3& w, Scalar room) {
    const Vector3 local = body.local_direction(w);
    for (int k = 0; k < wall_count; ++k) {
      if (!(walls[k].dot(local) > room * local.norm())) return false;
    }
    return true;
  };
  const auto face_passes = [&](const Vector3& normal, Scalar low, const Vector3& w0,
                               const Vector3& w1, const Vector3& w2) {
    const Scalar c = low / lower;
    if (c > 0 && inside(normal, std::sqrt(std::max(Scalar(0), 1 - c * c)) + margin)) return true;
    return inside(w0, margin) && inside(w1, margin) && inside(w2, margin);
  };
  return polytope.nearer_faces_pass(lower, face_passes);
}

}  // namespace side_chain

}  // namespace swarmcollide::detail
