// The library's own exact solvers (method "exact"); private to the library's sources.
#pragma once

#include "../geometry/framed_body.hpp"
#include "answer.hpp"
#include "expanding_polytope.hpp"
#include "swarmcollide/queries/options.hpp"
#include "wolfe_min_norm.hpp"

namespace swarmcollide::detail {

/// The exact distance: Wolfe's nearest-point algorithm (1976) on B - A through the bodies'
/// support functions, from `start` (zero: from the centres' difference). Finite and exact to
/// rounding for every body, flat, collinear and single-point ones included; for overlapping
/// bodies a common point, with an intersection proof when Wolfe's corral encloses the origin.
Answer exact_distance(const FramedPair& pair, int max_iterations, const Vector3& start);

/// The exact distance continued from `corral`, another solver's last simplex of B - A (points
/// with the bodies' support indices, positive weights summing to one).
Answer exact_distance(const FramedPair& pair, int max_iterations, const MinNormPoint& corral);

/// exact_distance for a pair met again at nearby poses (a motion's samples): Wolfe's algorithm
/// starts from `corral`, its last corral for the pair, the points' support indices read again at
/// these poses (none: from the centres' difference), and its new last corral is written back
/// (emptied when it encloses the origin, a contact). Any start leaves the answer proven: its
/// bounds come from the supports along the direction the search ends with.
Answer exact_distance_again(const FramedPair& pair, int max_iterations, MinNormPoint& corral);

/// exact_distance for a caller that needs only the value proven to the tolerance, its direction
/// the witnesses' (a signed distance's contact normal): Wolfe's algorithm from `start` stops as
/// soon as a corral's new point separates the bodies, along the corral's point, by its norm less
/// the tolerance, instead of running on to its 1e-14 gap and its restarts, which curved bodies
/// reach only linearly (two ellipsoids apart: ~32,000 instructions). The answer is the corral's
/// (witnesses above, the separation along them below); exact_distance from `start` where that
/// does not prove the value, and for two polytopes (which reach that gap in a few steps).
Answer settled_distance(const FramedPair& pair, int max_iterations, const Vector3& start);

/// Whether `answer`, the answer of Wolfe's nearest point `corral` (no tetrahedron around the
/// origin), settles a signed distance, the bounds within the tolerance. Where its witnesses are
/// a few roundoffs apart (touching bodies) their direction is rounding noise and the separation
/// along it far short; the normal of the corral's triangle is then the contact normal (the
/// origin's nearest point lies on the triangle, whose plane supports B - A there), measured
/// with either sign. The separation along any direction bounds the signed distance below,
/// overlapping or not; the one that settles it becomes `answer`'s lower bound and direction,
/// and the expanding polytope is not needed. Polytopes only: where a surface is curved the
/// separation changes only to second order in the normal's angle, so a settled value leaves the
/// normal a square root of the tolerance off, which the expanding polytope (and its closed forms
/// on axes of symmetry) does not.
bool settles_signed_distance(const FramedPair& pair, const MinNormPoint& corral, Answer& answer);

/// The same for any pair, curved ones too, where only the value is asked (a distance): the lower
/// bound a plane of the corral proves is the separation along its normal, taken where the
/// witnesses stay within the tolerance of `upper` times that normal.
bool settles_value(const FramedPair& pair, const MinNormPoint& corral, Answer& answer);

/// The certified penetration depth of touching or overlapping bodies, from the direction `hint`
/// (which may be zero); `distance_upper`, any upper bound on their distance, also bounds the
/// signed distance. `nearest`, when not null, is the corral of Wolfe's algorithm on B - A run to
/// its stopping tests: the solver does not run it again, and the expanding polytope starts from
/// its tetrahedron if that encloses the origin (an intersection proof). `surface`, when not
/// null, is the pair's kept surface (penetration's).
Answer exact_penetration(const FramedPair& pair, int max_iterations, const Vector3& hint,
                         Scalar distance_upper, const MinNormPoint* nearest = nullptr,
                         KeptSurface* surface = nullptr);

/// The exact signed distance: `exact_distance` when a direction proves the bodies apart, the
/// certified penetration depth otherwise (starting from the direction `hint`, which may be zero).
Answer exact_signed_distance(const FramedPair& pair, int max_iterations, const Vector3& hint);

/// Method "exact".
Answer solve_exact(const FramedPair& pair, const QueryOptions& options, Goal goal);

}  // namespace swarmcollide::detail
