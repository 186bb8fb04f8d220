// DistanceFinish's Wolfe searches for curved pairs (but two ellipsoids, secant_search.cpp): from
// a point (whole_curved) and from a corral a Wolfe walk left (walk_from_corral, overlap_first on
// curved pairs). In a file of their own, with the curved supports inline
// (framed_curved_support.hpp): whole()'s search from a single point, which every polytope query
// runs, compiles as it does alone. One search taking either start, or whole()'s oracle shared as
// a function object or a template, cost polytope queries 1-4% more instructions, and the curved
// supports inlined into every solver up to 287 instructions more a 64-vertex polytope query; the
// oracle and measure are therefore whole()'s, written again.
#include "distance_finish.hpp"
#include "inline_minkowski.hpp"
#include "nesterov_direction.hpp"
#include "newton_direction.hpp"
#include "whole_search.hpp"

namespace swarmcollide::detail {

namespace {

// The frame's tolerance from which two cylinders' or cones' searches ask along their creases no
// more: the steps' bookkeeping costs more than the support calls they save where few digits are
// asked. Instructions a search apart with and without the steps (callgrind_query.py --curved,
// 100 pairs of each kind, the relative tolerance times the frame's size of 1 to 2 is the frame's):
// at a relative 1e-9 -14% (two cylinders), -13% (a cylinder and a cone), -10% (two cones); at 3e-8
// -3%, -2%, -1%; at 1e-7 -2%, +2%, +2%; at 1e-6 +4%, +7%, +9%.
constexpr Scalar kCreaseStepsBelow = 1e-7;

// Whether a pair's searches ask along Newton's steps (NewtonDirection says where they paid): a
// pair with an ellipsoid, or two cylinders or cones at a fine tolerance; and whether the steps
// follow a polyhedron's edges too (an ellipsoid beside one, NewtonDirection<true>).
enum class Steps : unsigned char { wolfe, newton, newton_on_edges };

Steps newton_steps(const FramedPair& pair) {
  const CurvedKind a = pair.a.curved_kind();
  const CurvedKind b = pair.b.curved_kind();
  const auto creased = [](CurvedKind kind) {
    return kind == CurvedKind::cylinder || kind == CurvedKind::cone;
  };
  if (a == CurvedKind::ellipsoid || b == CurvedKind::ellipsoid) {
    return pair.a.curved() && pair.b.curved() ? Steps::newton : Steps::newton_on_edges;
  }
  return creased(a) && creased(b) && pair.tolerance < kCreaseStepsBelow ? Steps::newton
                                                                          : Steps::wolfe;
}

// `search` run with the directions newton_steps names for the pair.
template <typename Search>
bool with_directions(const FramedPair& pair, const Search& search) {
  switch (newton_steps(pair)) {
    case Steps::newton:
      return search(NewtonDirection<false>(pair));
    case Steps::newton_on_edges:
      return search(NewtonDirection<true>(pair));
    case Steps::wolfe:
      break;
  }
  return search(AlongCorral());
}

}  // namespace

bool DistanceFinish::whole_curved(const Vector3& start, int& hint_a, int& hint_b,
                                  BestBounds& bounds, Goal goal, bool enclosure,
                                  const OraclePoint* first_point) {
  // A large polyhedron beside a curved body climbs from its previous support, unless the
  // direction turned by more than about 25 degrees (as whole()'s climbing search).
  const bool climbs =
      pair_.a.size() > kHillClimbingThreshold || pair_.b.size() > kHillClimbingThreshold;
  Vector3 previous = start;
  const auto search = [&](auto directions) SWARMCOLLIDE_FLATTEN {
    const auto support = [&](const Vector3& d) __attribute__((always_inline)) {
      ++evaluations_;
      if (climbs) drop_hints_after_turn(d, previous, hint_a, hint_b);
      return inline_minkowski_support(pair_, d, hint_a, hint_b);
    };
    const auto oracle = [&](const Vector3& x) __attribute__((always_inline)) {
      return directions.ask(x, support);
    };
    const auto along = [&](const MinNormPoint& current, const OraclePoint& q,
                           Scalar inverse_norm) {
      return directions.measured(current, q, inverse_norm);
    };
    return whole_search(pair_, start, first_point, hint_a, hint_b, bounds, goal, enclosure,
                        max_iterations_, evaluations_, oracle, along, PlacedByBodies{pair_});
  };
  // The pairs newton_steps names ask along Newton's steps; the others compile as the search did
  // without them. (The oracle and measure above are walk_from_corral's too: made by one helper
  // returning both lambdas, they cost the searched rows 40 to 166 more instructions.)
  return with_directions(pair_, search);
}

bool DistanceFinish::walk_from_corral(const Vector3& start, const MinNormPoint& corral,
                                      int& hint_a, int& hint_b, BestBounds& bounds, Goal goal,
                                      bool enclosure) {
  // A curved body's supports are its support function's. A large polytope beside it climbs from
  // the hints without whole()'s reset after a turn, which only chooses where a climb starts: it
  // ends at the support from any start, within the margins whole()'s bounds already take.
  const auto search = [&](auto directions) SWARMCOLLIDE_FLATTEN {
    const auto support = [&](const Vector3& d) __attribute__((always_inline)) {
      ++evaluations_;
      return inline_minkowski_support(pair_, d, hint_a, hint_b);
    };
    const auto oracle = [&](const Vector3& x) __attribute__((always_inline)) {
      return directions.ask(x, support);
    };
    const auto along = [&](const MinNormPoint& current, const OraclePoint& q,
                           Scalar inverse_norm) {
      return directions.measured(current, q, inverse_norm);
    };
    return whole_search(pair_, start, &corral, hint_a, hint_b, bounds, goal, enclosure,
                        max_iterations_, evaluations_, oracle, along, PlacedByBodies{pair_});
  };
  return with_directions(pair_, search);
}

}  // namespace swarmcollide::detail
