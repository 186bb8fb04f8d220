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
// curved rows 0.2-0.5% longer (callgrind_query.py --curved).
template <typename Use>
[[gnu::always_inline]] inline auto FramedBody::use_curved_support(const Vector3& local,
                                                                  const Use& use) const {
  // The shapes of shapes.hpp are called by their exact (final) type: the same function, inlined
  // here.
  switch (curved_kind_) {
    case CurvedKind::cylinder:
      return use(static_cast<const CylinderSupport*>(curved_)->CylinderSupport::support(local));
    case CurvedKind::ellipsoid:
      return use(static_cast<const EllipsoidSupport*>(curved_)->EllipsoidSupport::support(local));
    case CurvedKind::cone:
      return use(static_cast<const ConeSupport*>(curved_)->ConeSupport::support(local));
    default:
      return use(curved_->support(local));
  }
}

[[gnu::always_inline]] inline int FramedBody::inline_curved_support(const Vector3& local) const {
  return use_curved_support(local, [this](const Vector3& point) { return found_->add(point); });
}

[[gnu::always_inline]] inline int FramedBody::inline_support_index(const Vector3& d,
                                                                  int start) const {
  if (curved_) return inline_curved_support(local_direction(d));
  if (columns_) return columns_->inline_scan(local_direction(d));
  return support_index(d, start);
}

}  // namespace swarmcollide::detail
