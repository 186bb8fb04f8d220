// The support functions of the curved shapes (shapes.hpp's Cylinder, Cone and Ellipsoid), in a
// header so that FramedBody::curved_support calls them by their exact type, inlined, rather than
// through SupportFunction's virtual call (two per support-oracle call of a curved pair); private
// to the library's sources.
#pragma once

#include <algorithm>
#include <cmath>

#include "normalise.hpp"
#include "swarmcollide/geometry/support_function.hpp"
#include "swarmcollide/types.hpp"

namespace swarmcollide::detail {

// The support points of the curved shapes below are pulled towards the centre by this factor
// (1 - 8u, exact), after their last rounding: a computed point is within a few roundoffs of the
// surface, perhaps outside it, and scaled so it lies inside (each shape is star-shaped about its
// centre), as witnesses and the expanding polytope's corners must. It costs 8u of the support
// value, within SupportFunction::kSupportErrorRoundoffs.
inline constexpr Scalar kInward = 1 - 0x1p-50;

// `d` scaled by a power of two (exactly) so that its largest component is in [0.5, 1): support
// points do not depend on the length of the direction, and nothing below under- or overflows.
// Zero for a zero or non-finite direction (whose support point is then the centre, a point of
// the shape).
inline Vector3 unit_scaled(const Vector3& d) {
  const Scalar largest = d.cwiseAbs().maxCoeff();
  if (!(largest > 0) || !std::isfinite(largest)) return Vector3::Zero();
  const int exponent = exponent_above(largest);
  // One factor for the three components wherever 2^-exponent is a normal double (all but the most
  // extreme lengths): the very products times_power_of_two forms, without its tests per component
  // (a support call's directions come here once or twice, and searches make thousands of calls).
  if (exponent >= -1000 && exponent <= 1000) return d * power_of_two(-exponent);
  Vector3 scaled;
  for (int k = 0; k < 3; ++k) scaled(k) = times_power_of_two(d(k), -exponent);
  return scaled;
}

// Sizes within [2^-200, 2^200]: a shape whose support may take a direction of ordinary length
// as it is (unscaled_if_tame).
inline bool tame_sizes(Scalar smallest, Scalar largest) {
  return smallest >= 0x1p-200 && largest <= 0x1p200;
}

// `d` itself for a shape of tame sizes and a direction whose largest component is within
// [2^-100, 2^100], else unit_scaled(d): where the shape's support is proven to give the same point
// for both (each shape says why), the exponent, its power and the product are saved, a third of
// a support's instructions.
inline Vector3 unscaled_if_tame(const Vector3& d, bool tame) {
  const Scalar largest = d.cwiseAbs().maxCoeff();
  return tame && largest >= 0x1p-100 && largest <= 0x1p100 ? d : unit_scaled(d);
}

// The unit vector along (x, y), or zero: the components are divided by the larger first, so no
// square under- or overflows. Each coordinate is within 4 roundoffs of the exact one.
inline Eigen::Matrix<Scalar, 2, 1> unit_in_plane(Scalar x, Scalar y) {
  const Scalar larger = std::max(std::abs(x), std::abs(y));
  if (!(larger > 0)) return {0, 0};
  const Scalar sx = x / larger;
  const Scalar sy = y / larger;
  const Scalar length = std::sqrt(sx * sx + sy * sy);
  return {sx / length, sy / length};
}

inline CurvedShapeParameters shape_parameters(CurvedShapeParameters::Kind kind, Scalar radius,
                                       Scalar half_length, const Vector3& radii = Vector3::Zero()) {
  CurvedShapeParameters parameters;
  parameters.kind = kind;
  parameters.radius = radius;
  parameters.half_length = half_length;
  parameters.radii = radii;
  return parameters;
}

// The unit vector along (x, y, 0), or the x axis for a point on the z axis (every direction in
// the plane is as near there).
inline Vector3 radial(Scalar x, Scalar y) {
  const auto in_plane = unit_in_plane(x, y);
  if (in_plane.x() == 0 && in_plane.y() == 0) return Vector3::UnitX();
  return {in_plane.x(), in_plane.y(), 0};
}

// A cylinder's support: the rim point of the cap the direction points to. The height of the
// computed point falls short of the support value `r |d_xy| + h |d_z|` by the rounding of the
// unit vector in the plane (4u, first order in its length) and kInward's 8u, with the product's
// u: 13u of `r |d|`.
//
// The direction is not scaled (unit_scaled): the point reads only the sign of d_z and
// unit_in_plane's quotients by the larger of |d_x| and |d_y|, which are the same numbers for
// d and for d times a power of two (each quotient is rounded once from the same exact value):
// nothing under- or overflows, and the point is unit_scaled's without its exponent and product
// per call (searches make thousands). Only where unit_scaled's product itself rounded (a
// component below 2^-1021 beside one of at least 1) may a quotient differ, by its one rounding
// fewer. A non-finite direction still answers the centre.
class CylinderSupport final : public SupportFunction {
 public:
  CylinderSupport(Scalar radius, Scalar half_length) : r_(radius), h_(half_length) {}
  Vector3 support(const Vector3& d) const override {
    // NaN exactly when a component is infinite or NaN.
    const Scalar finite = (d.x() - d.x()) + (d.y() - d.y()) + (d.z() - d.z());
    if (finite != 0) return Vector3::Zero();
    return finite_support(d);
  }
  /// support(d) for a direction known to be finite (a search's), without the test: the same
  /// point. The test was a third of the support's instructions in a search's steps.
  Vector3 finite_support(const Vector3& d) const {
    const auto in_plane = unit_in_plane(d.x(), d.y());
    const Scalar z = d.z() > 0 ? h_ : d.z() < 0 ? -h_ : 0;
    return {r_ * in_plane.x() * kInward, r_ * in_plane.y() * kInward, z};
  }
  Scalar outer_radius() const override { return std::hypot(r_, h_); }
  Vector3 centroid() const override { return Vector3::Zero(); }
  // The nearer of the side (r - |p_xy|) and the caps (h - |p_z|), each within a few roundoffs
  // of the magnitudes: 8u of them is taken off.
  Scalar depth_of(const Vector3& p, Vector3& outward) const override {
    const Scalar side = r_ - std::hypot(p.x(), p.y());
    const Scalar cap = h_ - std::abs(p.z());
    const Scalar rounding = 8 * kRoundoff * (r_ + h_ + p.cwiseAbs().sum());
    if (side <= cap) {
      outward = radial(p.x(), p.y());
      return side - rounding;
    }
    outward = {0, 0, p.z() < 0 ? -1.0 : 1.0};
    return cap - rounding;
  }
  const char* name() const override { return "cylinder"; }
  CurvedShapeParameters parameters() const override {
    return shape_parameters(CurvedShapeParameters::Kind::cylinder, r_, h_);
  }
  /// parameters()'s radius and half-length, without building the whole CurvedShapeParameters (its
  /// pose too) through the virtual call: for the closed forms, which know the exact type.
  Scalar radius() const { return r_; }
  Scalar half_length() const { return h_; }

 private:
  Scalar r_;
  Scalar h_;
};

// A cone's support: its apex or the rim point of its base, whichever is higher; the comparison
// rounds by a few u of `h |d_z| + r |d_xy|` and the rim point as the cylinder's: under 20u of
// `outer_radius() |d|` in all.
//
// For a radius and a half-length within [2^-200, 2^200] (tame_) and a direction whose largest
// component is within [2^-100, 2^100], the direction itself rather than unit_scaled's d / 2^e:
// the point reads unit_in_plane's quotients, the same numbers for both (as the cylinder's), and
// the comparison of `h d_z` with `r (u . d_xy) - h d_z`, whose products and sums all scale by the
// power of two exactly while they are normal (they lie within [2^-300, 2^300] times a quotient):
// the same comparison, so the same point. (Only a component of at most 2^-700 of the largest might
// round otherwise, subnormal in one scaling: a term below half an ulp of the others either way.)
class ConeSupport final : public SupportFunction {
 public:
  ConeSupport(Scalar radius, Scalar half_length)
      : r_(radius),
        h_(half_length),
        tame_(tame_sizes(std::min(radius, half_length), std::max(radius, half_length))) {}
  Vector3 support(const Vector3& direction) const override {
    const Vector3 d = unscaled_if_tame(direction, tame_);
    const auto in_plane = unit_in_plane(d.x(), d.y());
    const Scalar apex = h_ * d.z();
    const Scalar rim = r_ * (in_plane.x() * d.x() + in_plane.y() * d.y()) - h_ * d.z();
    if (apex >= rim) return {0, 0, h_};
    return {r_ * in_plane.x() * kInward, r_ * in_plane.y() * kInward, -h_};
  }
  Scalar outer_radius() const override { return std::hypot(r_, h_); }
  Vector3 centroid() const override { return {0, 0, -h_ / 2}; }
  // The nearer of the base plane (p_z + h) and the side: the solid is the base's half-space
  // and the infinite solid cone, whose side is nearest along the tangent plane through the
  // point's generator, at (r (h - p_z) - 2h |p_xy|) / |(r, 2h)|. 16u of the magnitudes covers the
  // rounding.
  Scalar depth_of(const Vector3& p, Vector3& outward) const override {
    const Scalar slant = std::hypot(r_, 2 * h_);
    const Scalar base = p.z() + h_;
    const Scalar side = (r_ * (h_ - p.z()) - 2 * h_ * std::hypot(p.x(), p.y())) / slant;
    const Scalar rounding = 16 * kRoundoff * (r_ + h_ + p.cwiseAbs().sum());
    if (base <= side) {
      outward = -Vector3::UnitZ();
      return base - rounding;
    }
    const Vector3 across = radial(p.x(), p.y());
    outward = Vector3(2 * h_ * across.x(), 2 * h_ * across.y(), r_) / slant;
    return side - rounding;
  }
  const char* name() const override { return "cone"; }
  CurvedShapeParameters parameters() const override {
    return shape_parameters(CurvedShapeParameters::Kind::cone, r_, h_);
  }
  /// parameters()'s radius and half-length (as the cylinder's).
  Scalar radius() const { return r_; }
  Scalar half_length() const { return h_; }

 private:
  Scalar r_;
  Scalar h_;
  bool tame_;
};

// An ellipsoid's support `R^2 d / |R d|` (R = diag(radii)), as `R u` with u the unit vector along
// `R d`: u is within 4u of it, which moves the height `|R d| cos` by second order in the angle
// and first order in |u|; with R's products and kInward, under 16u of `|R d| <= max radius |d|`.
//
// R d is brought into [0.5, 1) again before its norm, against under- and overflow, except for
// radii within [2^-200, 2^200] (tame_), where it needs none: d's largest component is in [0.5, 1),
// so R d's is within [2^-201, 2^200] and the squares in [2^-402, 2^400], normal. A power of two
// then changes nothing: each square, their sum (a square below half an ulp of the largest
// vanishes either way), the square root and each quotient scale by it exactly, and the quotients
// are the same numbers. (Only a component of R d below 2^-822 would differ: scaled down by up to
// 2^-201 it would round as a subnormal; a direction with a component 2^-622 of its largest.)
class EllipsoidSupport final : public SupportFunction {
 public:
  explicit EllipsoidSupport(const Vector3& radii)
      : radii_(radii), tame_(tame_sizes(radii.minCoeff(), radii.maxCoeff())) {}
  Vector3 support(const Vector3& direction) const override {
    // For tame radii and a direction whose largest component is within [2^-100, 2^100], d itself
    // rather than unit_scaled's d / 2^e: R d's largest component is then within [2^-300, 2^300],
    // its square normal, and as above the power of two changes nothing (only a component of R d
    // subnormal in one of the two scalings, at most 2^-722 of the largest, might round
    // otherwise).
    const Vector3 raw = unscaled_if_tame(direction, tame_).cwiseProduct(radii_);
    const Vector3 stretched = tame_ ? raw : unit_scaled(raw);
    const Scalar length = stretched.norm();
    if (!(length > 0)) return Vector3::Zero();
    return radii_.cwiseProduct(stretched / length) * kInward;
  }
  Scalar outer_radius() const override { return radii_.maxCoeff(); }
  // rho = min radius^2 / max radius, the least radius of curvature, rolls inside. With M =
  // R^-2 and f(x) = x^T M x, a surface point p (f(p) = 1) has the outward normal v = M p / |M p|,
  // and a point y = p + rho (w - v) on the sphere of radius rho about p - rho v (|w| = 1) has
  //   f(y) = 1 + 2 rho |M p| v.(w - v) + rho^2 (w - v)^T M (w - v)
  //       <= 1 - rho |w - v|^2 (|M p| - rho / min radius^2)      (v.(w - v) = -|w - v|^2 / 2)
  // <= 1, as |M p| >= p^T M p / |p| >= 1 / max radius = rho / min radius^2; the ball is convex,
  // so inside too. The support point along d is the surface point of normal d / |d|, and a ball
  // of a smaller radius tangent there inside this one. rho is rounded down (its two roundings are
  // within 2.1u). The computed support point: d is scaled exactly, each component of R d and of
  // the unit vector along it rounds (u, then 3.5u with the norm's 2.5u), then R's product and
  // kInward's (u, u, and the pull 8u): within 15.5u of each component of the exact point, so
  // within 16u max radius of it, inside kSupportErrorRoundoffs = 32u of outer_radius().
  Scalar rolling_radius() const override {
    const Scalar least = radii_.minCoeff();
    return least * least / radii_.maxCoeff() * (1 - 4 * kRoundoff);
  }
  Vector3 centroid() const override { return Vector3::Zero(); }
  // The ball of radius `min radius (1 - |p / radii|)` about p lies inside (|(p + v) / radii| <=
  // |p / radii| + |v| / min radius): exact at the centre and everywhere on a sphere. The
  // outward direction is the gradient of |x / radii|^2 (the shortest axis at the centre).
  Scalar depth_of(const Vector3& p, Vector3& outward) const override {
    const Vector3 scaled = p.cwiseQuotient(radii_);
    Eigen::Index shortest = 0;
    const Scalar least = radii_.minCoeff(&shortest);
    const Vector3 gradient = scaled.cwiseQuotient(radii_);
    const Scalar length = gradient.norm();
    outward = length > 0 ? Vector3(gradient / length) : Vector3(Vector3::Unit(shortest));
    return least * (1 - scaled.norm()) - 16 * kRoundoff * radii_.maxCoeff() * (1 + scaled.norm());
  }
  const char* name() const override { return "ellipsoid"; }
  CurvedShapeParameters parameters() const override {
    return shape_parameters(CurvedShapeParameters::Kind::ellipsoid, 0, 0, radii_);
  }
  /// parameters()'s semi-axes (as the cylinder's radius).
  const Vector3& radii() const { return radii_; }

 private:
  Vector3 radii_;
  bool tame_;
};

}  // namespace swarmcollide::detail
