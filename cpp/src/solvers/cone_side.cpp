#include "cone_side.hpp"

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

using side_chain::kMostCorners;
using side_chain::Vector2;

// The most the best normal's elevation may lie off the side's (as a tangent) for the chain to be
// tried: a rim's or the apex's contact lies off it by tenths.
constexpr Scalar kMostTilt = 0.05;
// A corner's coordinates: the support point placed in the frame less the cone's offset, turned
// (within 16u of magnitudes up to 2, as the cylinder's), times the side's sine and cosine (each
// within a few roundoffs), plus the apex's height along a unit vector: within 32u each; twice
// that.
constexpr Scalar kCornerError = 64 * kRoundoff;
constexpr Scalar kQuarterTurn = 1.5707963267948966;

// A support point of the section, and the other body's point y it came from (the cone's axes,
// frame units, from the cone's centre).
struct Corner {
  Vector2 direction;
  Vector2 point;
  Vector3 other;
};

class Section {
 public:
  Section(const FramedBody& cone, const FramedBody& other) : cone_(cone), other_(other) {
    const auto& shape = static_cast<const ConeSupport&>(*cone.body().curved());
    radius_ = times_power_of_two(shape.radius(), -cone.exponent());
    half_length_ = times_power_of_two(shape.half_length(), -cone.exponent());
    const Scalar slant = std::hypot(radius_, 2 * half_length_);
    cosine_ = 2 * half_length_ / slant;
    sine_ = radius_ / slant;
  }

  Scalar cosine() const { return cosine_; }
  Scalar sine() const { return sine_; }
  int steps() const { return steps_; }

  // The frame direction of the side's normal at azimuth w.
  Vector3 frame_direction(const Vector2& w) const {
    const Vector3 local(cosine_ * w.x(), cosine_ * w.y(), sine_);
    return cone_.rotated() ? Vector3(cone_.rotation() * local) : local;
  }

  // The section's support point along w: the other body's least along the side's normal there.
  Corner support(const Vector2& w) {
    ++steps_;
    const Vector3 p = other_.inline_support(-frame_direction(w), hint_);
    const Vector3 y = cone_.local_direction(p - cone_.offset());
    const Scalar below_apex = half_length_ - y.z();
    return {w,
            {-cosine_ * y.x() + sine_ * below_apex * w.x(),
             -cosine_ * y.y() + sine_ * below_apex * w.y()},
            y};
  }

  // The distances along the side's line at azimuth w from the foot of the corner's point to the
  // apex and to the rim, where the corner's own `along`, `w . y_xy`, is `least` and `most`.
  Scalar to_apex(const Corner& c, Scalar least) const {
    return sine_ * least + cosine_ * (half_length_ - c.other.z());
  }
  Scalar to_rim(const Corner& c, Scalar most) const {
    return sine_ * (radius_ - most) + cosine_ * (half_length_ + c.other.z());
  }
  // Whether the corner's point lies between the apex and the rim along its own direction, and
  // no higher than the apex (its point then bounds the support along every azimuth).
  bool on_side(const Corner& c) const {
    const Scalar along = c.direction.dot(c.other.head<2>());
    return to_apex(c, along) > 2 * kCornerError && to_rim(c, along) > 2 * kCornerError &&
           c.other.z() <= half_length_;
  }

 private:
  const FramedBody& cone_;
  const FramedBody& other_;
  Scalar radius_ = 0;
  Scalar half_length_ = 0;
  Scalar cosine_ = 0;
  Scalar sine_ = 0;
  int hint_ = 0;
  int steps_ = 0;
};

// Whether the plane direction u lies on the arc from `clockwise` to `counterclockwise`
// (counterclockwise, under a half-turn).
bool on_arc(const Vector2& u, const Vector2& clockwise, const Vector2& counterclockwise) {
  return side_chain::cross(clockwise, u) >= 0 && side_chain::cross(u, counterclockwise) >= 0;
}

// The half-angle (rad) of a lift whose slope over the bound is `rise`, at most a quarter-turn
// (past it the cosine that multiplies the section's bound turns negative), shrunk for rounding.
Scalar lift(Scalar rise) { return std::min(2 * std::atan(rise), kQuarterTurn) * (1 - 0x1p-20); }

// `sign` turns A - B's directions into those of the cone less the other body (cone_side_depth).
SideDepth side_depth(Section& section, const FramedBody& a, const FramedBody& b,
                     const FramedBody& cone, const ExpandingPolytope& polytope, const Vector3& best,
                     Scalar sign, Scalar gap) {
  SideDepth none;
  // The best normal's elevation off the side's, as a tangent: `(z cos b - |xy| sin b)` over
  // `(z sin b + |xy| cos b)`.
  const Vector3 local_best = cone.local_direction(sign * best);
  const Scalar across_axis = std::hypot(local_best.x(), local_best.y());
  const Scalar tilt = local_best.z() * section.cosine() - across_axis * section.sine();
  const Scalar toward = local_best.z() * section.sine() + across_axis * section.cosine();
  if (!(across_axis > 0 && toward > 0 && std::abs(tilt) <= kMostTilt * toward)) return none;
  const Vector2 middle(local_best.x() / across_axis, local_best.y() / across_axis);
  const auto support = [&](const Vector2& w) { return section.support(w); };
  const auto on_side = [&](const Corner& c) { return section.on_side(c); };
  std::array<Corner, kMostCorners> corners;
  std::array<side_chain::Edge, kMostCorners> edges;
  int count = 0;
  const int nearest = side_chain::open_chain(middle, gap, support, on_side, corners, edges, count);
  if (nearest < 0) return none;
  // The run of corners around the nearest edge at least half as far from the apex and from the
  // rim as its corners are: the farther, the farther off the side's normals the bound holds.
  const auto along = [&](int k) { return corners[k].direction.dot(corners[k].other.head<2>()); };
  const auto apex_room = [&](int k) { return section.to_apex(corners[k], along(k)); };
  const auto rim_room = [&](int k) { return section.to_rim(corners[k], along(k)); };
  if (!section.on_side(corners[nearest]) || !section.on_side(corners[nearest + 1])) return none;
  const Scalar near_apex = std::min(apex_room(nearest), apex_room(nearest + 1)) / 2;
  const Scalar near_rim = std::min(rim_room(nearest), rim_room(nearest + 1)) / 2;
  const auto in_run = [&](int k) {
    return section.on_side(corners[k]) && apex_room(k) >= near_apex && rim_room(k) >= near_rim;
  };
  int first = nearest;
  int last = nearest + 1;
  while (first > 0 && in_run(first - 1)) --first;
  while (last + 1 < count && in_run(last + 1)) ++last;
  Scalar bound = 0;
  Vector2 clockwise;
  Vector2 counterclockwise;
  if (!side_chain::run_arc(edges, first, last, middle, clockwise, counterclockwise, bound)) {
    return none;
  }
  // The slopes over the wedge: `w . y_xy` is least and most at an end of the arc, unless the arc
  // holds the direction of -y_xy or of y_xy.
  Scalar apex_slope = std::numeric_limits<Scalar>::infinity();
  Scalar rim_slope = std::numeric_limits<Scalar>::infinity();
  for (int k = first; k <= last; ++k) {
    const Vector2 y = corners[k].other.head<2>();
    const Scalar at_ends_least = std::min(clockwise.dot(y), counterclockwise.dot(y));
    const Scalar at_ends_most = std::max(clockwise.dot(y), counterclockwise.dot(y));
    const Scalar least = on_arc(-y, clockwise, counterclockwise) ? -y.norm() : at_ends_least;
    const Scalar most = on_arc(y, clockwise, counterclockwise) ? y.norm() : at_ends_most;
    apex_slope = std::min(apex_slope, section.to_apex(corners[k], least));
    rim_slope = std::min(rim_slope, section.to_rim(corners[k], most));
  }
  // Each corner's point lies within kCornerError of its exact value, its slopes too. Along the
  // wedge's directions at elevation b + t the bound is `cos t d + |sin t| s`, at least d up to
  // `tan(|t| / 2) = s / d` (and the quarter-turn, past which the cosine turns negative).
  const Scalar d = bound - 2 * kCornerError;
  const Scalar rise_to_apex = (apex_slope - 2 * kCornerError) / d;
  const Scalar rise_to_rim = (rim_slope - 2 * kCornerError) / d;
  if (!(d > 0 && rise_to_apex > 0 && rise_to_rim > 0)) return none;
  const Scalar lower =
      depth_in_frame(d, rotation_skew(cone), 2, a.scan_shortfall() + b.scan_shortfall());
  if (!(lower > 0)) return none;
  // The wedge, in the cone's axes (inward normals): the planes through the axis along the run's
  // edge normals, and the elevations from `lowest` to `highest`, as planes through the
  // origin along the arc's middle direction c (a direction of the wedge has `c . u_xy` between
  // `cos(half arc) |u_xy|` and `|u_xy|`, so that each plane keeps a subset of its elevations).
  const Scalar side_elevation = std::atan2(section.sine(), section.cosine());
  const Scalar highest = side_elevation + lift(rise_to_apex);
  const Scalar lowest = side_elevation - lift(rise_to_rim);
  const Vector2 centre = (clockwise + counterclockwise).normalized();
  const Scalar half_arc_cosine = centre.dot(clockwise);
  std::array<Vector3, 4> walls = {Vector3(-clockwise.y(), clockwise.x(), 0),
                                  Vector3(counterclockwise.y(), -counterclockwise.x(), 0)};
  int wall_count = 2;
  if (highest < kQuarterTurn) {
    const Scalar slope = std::tan(highest);
    walls[wall_count++] = Vector3(slope * centre.x(), slope * centre.y(), -1);
  }
  if (lowest > -kQuarterTurn) {
    if (!(half_arc_cosine > 0)) return none;
    const Scalar slope = lowest < 0 ? std::tan(lowest) : std::tan(lowest) / half_arc_cosine;
    walls[wall_count++] = Vector3(-slope * centre.x(), -slope * centre.y(), 1);
  }
  // The polytope's faces and corners are A - B's: turned over with the walls.
  for (int k = 0; k < wall_count; ++k) walls[k] = sign * walls[k].normalized();
  if (!side_chain::faces_in_wedge(polytope, cone, walls, wall_count, lower)) return none;
  SideDepth found;
  found.lower = lower;
  // The witnesses need the azimuth where the support point lies on the line from the origin
  // (cylinder_side.cpp).
  const Vector2 azimuth =
      side_chain::deepest_azimuth(support, 2 * kCornerError, corners[nearest].direction,
                                  corners[nearest + 1].direction, edges[nearest].normal);
  found.normal = sign * section.frame_direction(azimuth).normalized();
  return found;
}

}  // namespace

SideDepth cone_side_depth(const FramedBody& a, const FramedBody& b, bool cone_is_a,
                          const ExpandingPolytope& polytope, const Vector3& best, Scalar gap) {
  // The cone less the other body's points: A - B where the cone is A, B - A where it is B,
  // whose normals are the opposite ones.
  const FramedBody& cone = cone_is_a ? a : b;
  const Scalar sign = cone_is_a ? 1 : -1;
  Section section(cone, cone_is_a ? b : a);
  SideDepth found = side_depth(section, a, b, cone, polytope, best, sign, gap);
  found.steps = section.steps();
  return found;
}

}  // namespace swarmcollide::detail
