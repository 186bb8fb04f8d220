#include "cylinder_side.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "../geometry/curved_depth.hpp"
#include "../geometry/curved_supports.hpp"
#include "../geometry/framed_curved_support.hpp"
#include "../geometry/normalise.hpp"

namespace swarmcollide::detail {

namespace {

using Vector2 = Eigen::Matrix<Scalar, 2, 1>;

// The chain's first corners lie this far (rad) either side of the best normal's azimuth: far,
// for the wedge (the faces nearer than the bound of a polytope expanded to 2^-12 reach a few
// hundredths of a radian from it), and near, where the expansion so far puts the deepest
// azimuth, which spares the chain the steps down to it.
constexpr Scalar kHalfSpread = 0.35;
constexpr Scalar kNearSpread = 0x1p-5;
// The most the best normal may rise out of the cylinder's plane (as a sine) for the chain to be
// tried: a rim's contact lies off it by tenths.
constexpr Scalar kMostRise = 0.05;
constexpr int kMostCorners = 48;
// How far inside the wedge (as a sine) a near face's corners must lie: room for the rotation's
// rounding (a few roundoffs; a valid pose's skew is under 1e-9 and comes off the bound anyway).
constexpr Scalar kWedgeMargin = 0x1p-26;
// A corner's coordinates in the cylinder's axes: the support point placed in the frame less the
// cylinder's offset, turned (three products and sums of coordinates at most 2), and the disc's
// point (radius at most 1, along a unit vector within 2u): within 16u each; twice that.
constexpr Scalar kCornerError = 32 * kRoundoff;
// The steps of the secant search for the deepest azimuth (each a support point of the other
// body), which settles a smooth boundary in three or four.
constexpr int kMostSecantSteps = 8;

Scalar cross(const Vector2& p, const Vector2& q) { return p.x() * q.y() - p.y() * q.x(); }

// A support point of E's projection along z (the cylinder's axes, frame units) and its height.
struct Corner {
  Vector2 direction;
  Vector2 point;
  Scalar height = 0;
};

// An edge of the chain, from corner k to k + 1.
struct Edge {
  Vector2 normal = Vector2::Zero();  // outward, unit to rounding
  Scalar distance = 0;               // from the origin's projection to its line
  Scalar bound = 0;                  // at most `normal . corner` at both ends (rounding taken off)
  bool settled = false;
};

class Section {
 public:
  Section(const FramedBody& cylinder, const FramedBody& other, Scalar sign)
      : cylinder_(cylinder), other_(other), sign_(sign) {
    const auto& shape = static_cast<const CylinderSupport&>(*cylinder.body().curved());
    radius_ = times_power_of_two(shape.radius(), -cylinder.exponent());
    half_length_ = times_power_of_two(shape.half_length(), -cylinder.exponent());
  }

  Scalar half_length() const { return half_length_; }
  int steps() const { return steps_; }

  // The frame direction of the cylinder's plane direction w.
  Vector3 frame_direction(const Vector2& w) const {
    const Vector3 local(w.x(), w.y(), 0);
    return cylinder_.rotated() ? Vector3(cylinder_.rotation() * local) : local;
  }

  // E's support point along w: the other body's along sign w (A's support for a cylinder B,
  // B's along -w for a cylinder A), from the cylinder's centre, plus the disc's.
  Corner support(const Vector2& w) {
    ++steps_;
    const Vector3 p = other_.inline_support(sign_ * frame_direction(w), hint_);
    const Vector3 e = sign_ * cylinder_.local_direction(p - cylinder_.offset()) +
                      radius_ * Vector3(w.x(), w.y(), 0);
    return {w, {e.x(), e.y()}, e.z()};
  }

 private:
  const FramedBody& cylinder_;
  const FramedBody& other_;
  Scalar sign_;
  Scalar radius_ = 0;
  Scalar half_length_ = 0;
  int hint_ = 0;
  int steps_ = 0;
};

Edge measure(const Corner& from, const Corner& to) {
  Edge edge;
  const Vector2 along = to.point - from.point;
  const Scalar length = along.norm();
  if (!(length > 0)) {
    edge.distance = edge.bound = std::numeric_limits<Scalar>::infinity();
    return edge;
  }
  const Scalar inverse = 1 / length;
  edge.normal = Vector2(along.y() * inverse, -along.x() * inverse);
  edge.distance = cross(from.point, along) * inverse;
  // The normal is perpendicular to the rounded difference within some 4u, so its products with
  // the two ends differ from the distance by 16u of their lengths (section_depth's analysis
  // gives 12u for the quotient).
  const Scalar rounding = 24 * kRoundoff * (from.point.norm() + to.point.norm() + length);
  edge.bound = std::min(edge.normal.dot(from.point), edge.normal.dot(to.point));
  edge.bound = std::min(edge.bound, edge.distance) - rounding;
  return edge;
}

// The azimuth of the plane along which E's projection is least deep, between the directions
// `from` and `to` (counterclockwise, less than a half-turn apart): where the support point's
// offset across the direction, `s(w) . t(w)` for the counterclockwise tangent t, changes sign
// (meridian_depth.cpp's deepest_direction), found by the Illinois variant of the secant method
// on the chord between them, which settles a smooth boundary in three or four steps. Where it
// does not settle in kMostSecantSteps the offset jumps through zero (a flat edge of the
// projection, where the support point jumps from one end to the other, as along two
// cylinders' sides), and the nearest edge's normal, `otherwise`, is that edge's (to the
// chain's gap); so too where the two do not bracket it.
Vector2 deepest_azimuth(Section& section, const Vector2& from, const Vector2& to,
                        const Vector2& otherwise) {
  const auto at = [&](Scalar s) {
    const Vector2 w = from + s * (to - from);
    return Vector2(w.normalized());
  };
  // The offset, and whether it is zero to its rounding (the point's coordinates' kCornerError).
  bool settled = false;
  const auto across = [&](const Vector2& w) {
    const Vector2 point = section.support(w).point;
    const Scalar offset = point.dot(Vector2(-w.y(), w.x()));
    settled = std::abs(offset) <= 2 * kCornerError;
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

SideDepth side_depth(Section& section, const FramedBody& a, const FramedBody& b,
                     const FramedBody& cylinder, const ExpandingPolytope& polytope,
                     const Vector3& best, Scalar gap) {
  SideDepth none;
  const Vector3 local_best = cylinder.local_direction(best);
  const Scalar across_axis = std::hypot(local_best.x(), local_best.y());
  if (!(std::abs(local_best.z()) <= kMostRise * across_axis)) return none;
  const Vector2 middle(local_best.x() / across_axis, local_best.y() / across_axis);
  // The chain starts at the best normal's azimuth and either side of it, near (where the
  // expansion so far puts the deepest one: the first steps are the chain's nearest) and far
  // (the wedge its bound may cover).
  const auto turned = [&](Scalar angle) {
    const Scalar c = std::cos(angle);
    const Scalar s = std::sin(angle);
    return Vector2(c * middle.x() - s * middle.y(), c * middle.y() + s * middle.x());
  };
  std::array<Corner, kMostCorners> corners;
  std::array<Edge, kMostCorners> edges;
  corners[2] = section.support(middle);
  // The other body's support along the best normal lies off the side (a rim's or a cap's
  // contact): no run of corners will be found.
  if (!(std::abs(corners[2].height) + 2 * kCornerError < section.half_length())) return none;
  corners[1] = section.support(turned(-kNearSpread));
  corners[3] = section.support(turned(kNearSpread));
  // Nor where the near corners leave it, as they do where the deepest point is a rim's.
  for (const int k : {1, 3}) {
    if (!(std::abs(corners[k].height) + 2 * kCornerError < section.half_length())) return none;
  }
  corners[0] = section.support(turned(-kHalfSpread));
  corners[4] = section.support(turned(kHalfSpread));
  int count = 5;
  for (int k = 0; k + 1 < count; ++k) edges[k] = measure(corners[k], corners[k + 1]);
  // The expanding chain: the nearest edge grows by the support point along its normal until
  // that point lies within `gap` of it.
  int nearest = 0;
  for (;;) {
    nearest = 0;
    for (int k = 1; k + 1 < count; ++k) {
      if (edges[k].distance < edges[nearest].distance) nearest = k;
    }
    Edge& edge = edges[nearest];
    if (!std::isfinite(edge.distance) || edge.settled || count == kMostCorners) break;
    const Corner farther = section.support(edge.normal);
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
    edges[nearest] = measure(corners[nearest], corners[nearest + 1]);
    edges[nearest + 1] = measure(corners[nearest + 1], corners[nearest + 2]);
  }
  if (!std::isfinite(edges[nearest].distance)) return none;
  // The run of corners around the nearest edge no higher than halfway from its corners to the
  // rims: the lower its corners, the farther out of the plane the run's bound holds.
  const Scalar h = section.half_length();
  const Scalar near =
      std::max(std::abs(corners[nearest].height), std::abs(corners[nearest + 1].height));
  if (!(near + 2 * kCornerError < h)) return none;
  const Scalar most = (h + near) / 2;
  const auto in_run = [&](int k) { return std::abs(corners[k].height) <= most; };
  int first = nearest;
  int last = nearest + 1;
  while (first > 0 && in_run(first - 1)) --first;
  while (last + 1 < count && in_run(last + 1)) ++last;
  // The wedge: the run's edge normals, each within a quarter-turn of the middle (so that the
  // arc between any two is under a half-turn); its ends are the normals most clockwise and most
  // counterclockwise from the middle.
  Scalar bound = std::numeric_limits<Scalar>::infinity();
  Vector2 clockwise = edges[first].normal;
  Vector2 counterclockwise = edges[first].normal;
  for (int k = first; k < last; ++k) {
    const Edge& edge = edges[k];
    if (!(edge.normal.dot(middle) > 0)) return none;
    bound = std::min(bound, edge.bound);
    if (cross(edge.normal, clockwise) > 0) clockwise = edge.normal;
    if (cross(counterclockwise, edge.normal) > 0) counterclockwise = edge.normal;
  }
  // Each corner lies within kCornerError of a point of E (its height too). Along the wedge's
  // directions at elevation t the bound is `cos t d + |sin t| (h - most)`, concave in t on
  // either side of the plane: at least d up to where it falls back to d, at
  // `tan(t / 2) = (h - most) / d`, everywhere if `h - most >= d`. Then the cylinder's own frame
  // and the frame differ by the rotation's skew and the placements' rounding.
  const Scalar d = bound - 2 * kCornerError;
  const Scalar rise = (h - most - 2 * kCornerError) / d;
  if (!(d > 0 && rise > 0)) return none;
  const Scalar steepest = rise >= 1 ? std::numeric_limits<Scalar>::infinity()
                                    : 2 * rise / (1 - rise * rise) * (1 - 0x1p-20);
  const Scalar lower =
      depth_in_frame(d, rotation_skew(cylinder), 2, a.scan_shortfall() + b.scan_shortfall());
  if (!(lower > 0)) return none;
  // The directions the side's bound holds along contain the cone of the wedge's planes and the
  // planes at the slope `steepest` from the cylinder's plane (measured along the wedge's middle,
  // which is no longer than a direction's part in the plane): inward normals, in the
  // cylinder's axes.
  const Vector2 centre = (clockwise + counterclockwise).normalized();
  std::array<Vector3, 4> walls = {Vector3(-clockwise.y(), clockwise.x(), 0),
                                  Vector3(counterclockwise.y(), -counterclockwise.x(), 0),
                                  Vector3(steepest * centre.x(), steepest * centre.y(), -1),
                                  Vector3(steepest * centre.x(), steepest * centre.y(), 1)};
  const int wall_count = std::isfinite(steepest) ? 4 : 2;
  for (int k = 0; k < wall_count; ++k) walls[k].normalize();
  const Scalar margin = kWedgeMargin + rotation_skew(cylinder);
  // A face nearer than the bound passes where every direction through it along which the face
  // itself bounds the depth by less (those within `acos(low / lower)` of its normal) lies in
  // that cone, or where its corners do (then every direction through it does).
  const auto inside = [&](const Vector3& w, Scalar room) {
    const Vector3 local = cylinder.local_direction(w);
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
  if (!polytope.nearer_faces_pass(lower, face_passes)) return none;
  SideDepth found;
  found.lower = lower;
  // The nearest edge's normal holds the depth to its gap but may turn a support point of a
  // curved boundary off the line from the origin by far more: the witnesses need the azimuth
  // where the support point lies on that line.
  const Edge& edge = edges[nearest];
  const Vector2 azimuth = deepest_azimuth(section, corners[nearest].direction,
                                          corners[nearest + 1].direction, edge.normal);
  found.normal = section.frame_direction(azimuth).normalized();
  return found;
}

}  // namespace

SideDepth cylinder_side_depth(const FramedBody& a, const FramedBody& b, bool cylinder_is_a,
                              const ExpandingPolytope& polytope, const Vector3& best, Scalar gap) {
  const FramedBody& cylinder = cylinder_is_a ? a : b;
  Section section(cylinder, cylinder_is_a ? b : a, cylinder_is_a ? -1 : 1);
  SideDepth found = side_depth(section, a, b, cylinder, polytope, best, gap);
  found.steps = section.steps();
  return found;
}

}  // namespace swarmcollide::detail
