#include "cylinder_side.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "../geometry/curved_depth.hpp"
#include "../geometry/curved_supports.hpp"
#include "../geometry/framed_curved_support.hpp"
#include "../geometry/normalise.hpp"
#include "side_chain.hpp"

namespace swarmcollide::detail {

namespace {

using side_chain::kMostCorners;
using side_chain::Vector2;

// The most the best normal may rise out of the cylinder's plane (as a sine) for the chain to be
// tried: a rim's contact lies off it by tenths.
constexpr Scalar kMostRise = 0.05;
// A corner's coordinates in the cylinder's axes: the support point placed in the frame less the
// cylinder's offset, turned (three products and sums of coordinates at most 2), and the disc's
// point (radius at most 1, along a unit vector within 2u): within 16u each; twice that.
constexpr Scalar kCornerError = 32 * kRoundoff;

// A support point of E's projection along z (the cylinder's axes, frame units) and its height.
struct Corner {
  Vector2 direction;
  Vector2 point;
  Scalar height = 0;
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

SideDepth side_depth(Section& section, const FramedBody& a, const FramedBody& b,
                     const FramedBody& cylinder, const ExpandingPolytope& polytope,
                     const Vector3& best, Scalar gap) {
  SideDepth none;
  const Vector3 local_best = cylinder.local_direction(best);
  const Scalar across_axis = std::hypot(local_best.x(), local_best.y());
  if (!(std::abs(local_best.z()) <= kMostRise * across_axis)) return none;
  const Vector2 middle(local_best.x() / across_axis, local_best.y() / across_axis);
  const auto support = [&](const Vector2& w) { return section.support(w); };
  // A corner on the side: below its rims.
  const auto on_side = [&](const Corner& c) {
    return std::abs(c.height) + 2 * kCornerError < section.half_length();
  };
  std::array<Corner, kMostCorners> corners;
  std::array<side_chain::Edge, kMostCorners> edges;
  int count = 0;
  const int nearest = side_chain::open_chain(middle, gap, support, on_side, corners, edges, count);
  if (nearest < 0) return none;
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
  Scalar bound = 0;
  Vector2 clockwise;
  Vector2 counterclockwise;
  if (!side_chain::run_arc(edges, first, last, middle, clockwise, counterclockwise, bound)) {
    return none;
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
  if (!side_chain::faces_in_wedge(polytope, cylinder, walls, wall_count, lower)) return none;
  SideDepth found;
  found.lower = lower;
  // The nearest edge's normal holds the depth to its gap but may turn a support point of a
  // curved boundary off the line from the origin by far more: the witnesses need the azimuth
  // where the support point lies on that line.
  const Vector2 azimuth =
      side_chain::deepest_azimuth(support, 2 * kCornerError, corners[nearest].direction,
                                  corners[nearest + 1].direction, edges[nearest].normal);
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
