// FramedBody's support points of curved bodies, defined inline for the files that include this
// header: framed_body.cpp (its out-of-line curved_support) and the curved pairs' searches
// (curved_search.cpp, secant_search.cpp, through solvers/inline_minkowski.hpp); private to the
// library's sources. Inlined into every
// solver through framed_body.hpp, the support made 64-vertex polytope rows up to 287
// instructions longer.
#pragma once

#include "curved_supports.hpp"
#include "framed_body.hpp"

namespace swarmcollide::detail {

// `use` of the curved body's support point along `local`, in its own frame (centred on its box).
// The use sits in each case: applied to the switch's result, the add of curved_support made the
// curved rows 0.2-0.5% longer (callgrind_query.py --curved). `kFinite`: `local` is known to be
// finite, which the cylinder's support need not test.
template <bool kFinite, typename Use>
[[gnu::always_inline]] inline auto FramedBody::use_curved_support(const Vector3& local,
                                                                  const Use& use) const {
  // The shapes of shapes.hpp are called by their exact (final) type: the same function, inlined
  // here.
  switch (curved_kind_) {
    case CurvedKind::cylinder: {
      const auto* cylinder = static_cast<const CylinderSupport*>(curved_);
      return use(kFinite ? cylinder->finite_support(local)
                         : cylinder->CylinderSupport::support(local));
    }
    case CurvedKind::ellipsoid:
      return use(static_cast<const EllipsoidSupport*>(curved_)->EllipsoidSupport::support(local));
    case CurvedKind::cone:
      return use(static_cast<const ConeSupport*>(curved_)->ConeSupport::support(local));
    default:
      return use(curved_->support(local));
  }
}

[[gnu::always_inline]] inline int FramedBody::inline_curved_support(const Vector3& local) const {
  return use_curved_support(local,
                            [this](const Vector3& point) { return add_support_point(point); });
}

[[gnu::always_inline]] inline Vector3 FramedBody::inline_support(const Vector3& d,
                                                                 int& index) const {
  if (curved_) {
    // A search's directions are finite (a unit start, its corrals' points, secant directions
    // tested finite). The point is placed as the body's points hold it (-0 as +0, as add()
    // keeps it), so vertex(index) would read back the same coordinates. The add and the
    // placement follow the switch: in each case (as inline_curved_support's add), they made
    // two ellipsoids' searches longer (callgrind_curved, apart: 14,051 -> 14,859).
    const Vector3 kept = use_curved_support<true>(
        local_direction(d), [](const Vector3& point) { return Vector3(point + Vector3::Zero()); });
    index = add_support_point_without_negative_zeros(kept);
    return placed(kept);
  }
  index = columns_ ? columns_->inline_scan(local_direction(d)) : support_index(d, index);
  return vertex(index);
}

inline bool FramedBody::add_support_curvature(const Vector3& d, const Vector3& u,
                                              const Vector3& v, Vector3& form) const {
  if (!curved_) return true;
  const Vector3 m = local_direction(d);
  const Vector3 lu = local_direction(u);
  const Vector3 lv = local_direction(v);
  const Scalar scale = scale_high_ * scale_low_;
  // A rim's point (r t, z), t the unit vector along m's part in the plane, turns with m about
  // the axis: its derivative is r / |m_xy| times the projection on the rim's tangent. The frame's
  // directions have unit length, so the squares neither overflow nor lose the rim's tangent.
  const auto rim = [&](Scalar radius) {
    const Scalar across = std::sqrt(m.x() * m.x() + m.y() * m.y());
    if (!(across > 0)) return false;
    const Scalar tu = (m.x() * lu.y() - m.y() * lu.x()) / across;
    const Scalar tv = (m.x() * lv.y() - m.y() * lv.x()) / across;
    form += (scale * radius / across) * Vector3(tu * tu, tu * tv, tv * tv);
    return true;
  };
  switch (curved_kind_) {
    case CurvedKind::cylinder:
      return rim(static_cast<const CylinderSupport*>(curved_)->radius());
    case CurvedKind::cone: {
      const auto* cone = static_cast<const ConeSupport*>(curved_);
      const Scalar apex = cone->half_length() * m.z();
      const Scalar base =
          cone->radius() * std::sqrt(m.x() * m.x() + m.y() * m.y()) - cone->half_length() * m.z();
      if (apex >= base) return true;
      return rim(cone->radius());
    }
    case CurvedKind::ellipsoid: {
      // s = R^2 m / |R m| (R the radii): ds/dm = (R^2 - s s^T) / |R m|.
      const Vector3& radii = static_cast<const EllipsoidSupport*>(curved_)->radii();
      const Vector3 squares = radii.cwiseProduct(radii);
      const Scalar length = m.cwiseProduct(radii).norm();
      if (!(length > 0)) return false;
      const Vector3 point = squares.cwiseProduct(m) / length;
      const Scalar su = point.dot(lu);
      const Scalar sv = point.dot(lv);
      const Vector3 squares_u = squares.cwiseProduct(lu);
      form += (scale / length) * Vector3(squares_u.dot(lu) - su * su,
                                         squares_u.dot(lv) - su * sv,
                                         squares.cwiseProduct(lv).dot(lv) - sv * sv);
      return true;
    }
    default:
      return false;
  }
}

inline bool FramedBody::crease_shape(CreaseShape& out) const {
  if (curved_kind_ != CurvedKind::cylinder && curved_kind_ != CurvedKind::cone) return false;
  const Scalar scale = scale_high_ * scale_low_;
  out.axis = rotated_ ? Vector3(rotation_.col(2)) : Vector3::UnitZ();
  if (curved_kind_ == CurvedKind::cylinder) {
    const auto* cylinder = static_cast<const CylinderSupport*>(curved_);
    out.radius = scale * cylinder->radius();
    out.half_length = scale * cylinder->half_length();
    return true;
  }
  const auto* cone = static_cast<const ConeSupport*>(curved_);
  out.cone = true;
  out.radius = scale * cone->radius();
  out.half_length = scale * cone->half_length();
  out.apex = placed(Vector3(0, 0, cone->half_length()));
  return true;
}

}  // namespace swarmcollide::detail
