// libccd checked by the certificate (method "libccd"); private to the library's sources.
#pragma once

#include "../geometry/framed_body.hpp"
#include "answer.hpp"
#include "swarmcollide/queries/options.hpp"

namespace swarmcollide::detail {

/// Method "libccd": libccd's GJK intersection test (ccdGJKIntersect) and GJK + EPA penetration
/// depth (ccdGJKPenetration) through the bodies' support functions in the frame. libccd's EPA
/// loops until its tolerance is met, which on some inputs is never; the support functions
/// therefore count their calls and, past a budget of 4 x max_iterations, return the origin for
/// both bodies, which ends EPA at once (its next support point then fails the expansion test),
/// and the answer goes to method "exact". libccd's answers are checked: a "no" by the separation
/// along the direction that proved it, a "yes" by a tetrahedron of its support points that
/// encloses the origin, a depth by the exact penetration solver's proof. Unproven verdicts and
/// depths are answered by "exact", which the answer names. No distances: libccd has none.
Answer solve_libccd(const FramedPair& pair, const QueryOptions& options, Goal goal);

}  // namespace swarmcollide::detail
