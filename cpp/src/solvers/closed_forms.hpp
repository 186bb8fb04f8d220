// Which closed form answers a pair, for the solvers that try them before their searches (dual,
// exact); private to the library's sources.
#pragma once

#include "../queries/rounded.hpp"
#include "core_closed_form.hpp"
#include "curved_point.hpp"

namespace swarmcollide::detail {

/// True when a closed form may answer `pair`: a ball against a cylinder, a cone or an ellipsoid
/// (point_against_curved), or balls and capsules against each other or a ball against a box
/// (core_closed_form). All are rounded or curved (FramedPair::adjusted), so two sharp polyhedra
/// pay one test for both.
inline bool closed_form_pair(const FramedPair& pair) {
  return rounded(pair) && (point_and_curved(pair) || small_cores(pair));
}

/// True, with `answer` (default-constructed by the caller), where the closed form for a
/// closed_form_pair settles `goal`; false where the caller's search must answer it.
inline bool answered_in_closed_form(const FramedPair& pair, Goal goal, int max_iterations,
                                    Answer& answer) {
  return point_and_curved(pair) ? point_against_curved(pair, goal, max_iterations, answer)
                                : core_closed_form(pair, goal, answer);
}

}  // namespace swarmcollide::detail
