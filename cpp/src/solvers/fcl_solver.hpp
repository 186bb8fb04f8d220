// FCL's GJK checked by the certificate (method "fcl"); private to the library's sources.
#pragma once

#include "../geometry/framed_body.hpp"
#include "answer.hpp"
#include "swarmcollide/queries/options.hpp"

namespace swarmcollide::detail {

/// Method "fcl": FCL 0.7's own GJK (`fcl::detail::GJK`, the solver behind GST_INDEP) on the
/// bodies' hulls as `fcl::Convexd` (a rounded body's core: the radii are taken off after), or on
/// a curved shape as FCL's own `fcl::Cylinderd`, `fcl::Coned` or `fcl::Ellipsoidd`, built once
/// per body and scale in the frame's units. It is the one FCL routine used: its loop is bounded
/// by `max_iterations` and it has no assertions, whereas GST_LIBCCD's GJK and EPA abort the
/// process on some inputs (assertions in doSimplex2 and ComputeVisiblePatch). FCL's simplex is
/// turned into witness points and weights through the library's own support queries (a curved
/// shape's support function) and checked: a separation along the witnesses, or a simplex that
/// encloses the origin by more than rounding. What it does not prove (touching pairs, FCL's early
/// stops, every penetration depth) is answered by method "exact", which the answer names.
Answer solve_fcl(const FramedPair& pair, const QueryOptions& options, Goal goal);

}  // namespace swarmcollide::detail
