// minkowski_support with both supports inline, for the curved pairs' searches (curved_search.cpp,
// secant_search.cpp); private to the library. In a header of its own so that only they include
// the inline curved supports (framed_curved_support.hpp): inlined into every solver, those made
// 64-vertex polytope rows up to 287 instructions longer.
#pragma once

#include "../geometry/framed_curved_support.hpp"
#include "minkowski.hpp"

namespace swarmcollide::detail {

/// minkowski_support(pair.a, pair.b, d, hint_a, hint_b) for a finite `d` (a search's): the same
/// point. A curved body's support is its support function's, a small polyhedron's a scan,
/// whatever the hints; a large polyhedron climbs from its hint.
[[gnu::always_inline]] inline OraclePoint inline_minkowski_support(const FramedPair& pair,
                                                                   const Vector3& d, int& hint_a,
                                                                   int& hint_b) {
  const Vector3 point_a = pair.a.inline_support(d, hint_a);
  const Vector3 point_b = pair.b.inline_support(-d, hint_b);
  return {point_b - point_a, hint_a, hint_b};
}

}  // namespace swarmcollide::detail
