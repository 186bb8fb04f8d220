#include "distance_finish.hpp"

#include <algorithm>
#include <array>
#include <type_traits>
#include <vector>

#include "../queries/verdict.hpp"
#include "minkowski.hpp"
#include "nesterov_direction.hpp"
#include "whole_search.hpp"

namespace swarmcollide::detail {

namespace {

// Exact subproblems the finish solves from one direction before the caller's search takes over
// again. From the first generation's best direction, 512-vertex pairs need up to 10; with fewer,
// a quarter of them wait a dozen swarm iterations for the next finish.
constexpr int kFinishSteps = 10;

// Pairs of polytopes whose larger body has more points than this ask their search's points with
// Nesterov's momentum (NesterovDirection). Smaller pairs' Wolfe walks end in about as few steps
// without it: with it, the point the momentum asks in vain before it turns off made their steps
// more (narrowphase_coal.cpp's pairs, 4 points overlapping: 4.7 -> 5.45 oracle calls a distance;
// 8 points: 5.55 -> 5.9), and natively their queries longer.
constexpr int kMomentumSize = 8;

// A curved body's feature keeps its highest points, up to this many. Its points are the support
// points asked so far, hundreds near one plane once a swarm's rounds have run, and a subset of
// them still bounds the distance above. Fewer points made the finishes cheaper and, for reasons
// not looked into, settled more verdicts: of 94 sc.collide calls at a verdict's border (C++, one
// run each, the proven counts deterministic), all kept 60 proven in 0.94 s; the highest 16: 51,
// 0.70 s; 32: 69, 0.75 s; 64: 71, 0.71 s; 128: 69, 1.08 s; 256: 71, 1.20 s.
constexpr std::size_t kCurvedFeaturePoints = 64;

struct Buffers {
  std::vector<char> visited;  // all zero between uses
  std::vector<int> feature_a;
  std::vector<int> feature_b;
  std::vector<int> grown;
  std::vector<std::pair<Scalar, int>> ranked;  // (height, point) of a feature being sorted
};

Buffers& buffers() {
  thread_local Buffers b;
  return b;
}

// Adds the points of `more` missing from `into`, both numbers among a body's `points`; returns
// whether any was. `marks` (all zero between uses) holds a mark per point of the body: a curved
// body's features are its support points near the plane, hundreds once a swarm's rounds have
// run, where a search of `into` for each point made every merge quadratic (a polytope 1.1
// tolerances from a cylinder: sc.collide spent 0.5 s, 59% of it here).
bool merge(std::vector<int>& into, const std::vector<int>& more, int points,
           std::vector<char>& marks) {
  if (marks.size() < static_cast<std::size_t>(points)) marks.resize(points, 0);
  for (int i : into) marks[i] = 1;
  const std::size_t before = into.size();
  for (int i : more) {
    if (!marks[i]) {
      marks[i] = 1;
      into.push_back(i);
    }
  }
  for (int i : into) marks[i] = 0;
  return into.size() > before;
}

// The points of a scanned body that a small pair's search has placed in the frame: each support
// point once the oracle has found it (scanned in the body's own frame), or the caller's first
// point.
class PlacedSupports {
 public:
  explicit PlacedSupports(const FramedBody&) {}
  [[gnu::always_inline]] static int support(const FramedBody& body, const Vector3& d) {
    return body.sized_support_index<false>(d);
  }
  const Vector3& place(const FramedBody& body, int i) { return points_[i] = body.vertex(i); }
  const Vector3& point(int i) const { return points_[i]; }

 private:
  std::array<Vector3, kHillClimbingThreshold> points_;
};

// The same for a body of at most kRegisterColumns points, placed whole at the start and held by
// coordinate too (for scan_few_columns, padded by its last point): its supports scan the frame
// directions themselves, not turned into the body's own frame, and are placed already. A search
// on two such bodies asks about five points, each of which turned two directions and placed two
// points; placing the eight points first costs about half of that.
//
// Its scans compare the heights in the frame, as exact_support_index does: the highest computed
// height, which any lower bound may take (a local scan's point may fall short of it by
// scan_shortfall, framed_body.cpp). On ties and near-ties it may choose another point than a
// local scan would: any point of B - A is one the search may ask.
class PlacedFew {
 public:
  explicit PlacedFew(const FramedBody& body) : count_(body.size()) {
    for (int i = 0; i < kRegisterColumns; ++i) {
      points_[i] = body.vertex(std::min(i, count_ - 1));
      for (int c = 0; c < 3; ++c) columns_[c * kColumnCapacity + i] = points_[i][c];
    }
  }
  [[gnu::always_inline]] int support(const FramedBody&, const Vector3& d) const {
    return scan_few_columns(columns_.data(), count_, d.x(), d.y(), d.z());
  }
  const Vector3& place(const FramedBody&, int i) const { return points_[i]; }
  const Vector3& point(int i) const { return points_[i]; }

 private:
  int count_;
  std::array<Vector3, kRegisterColumns> points_;
  // The x at 0, the y at kColumnCapacity, the z at twice that, as scan_few_columns reads them.
  alignas(16) std::array<Scalar, 2 * kColumnCapacity + kRegisterColumns> columns_;
};

// True for an ellipsoid (a curved body whose support map is smooth).
bool smooth(const FramedBody& body) {
  return body.curved() &&
         body.body().curved()->parameters().kind == CurvedShapeParameters::Kind::ellipsoid;
}

}  // namespace

DistanceFinish::DistanceFinish(const FramedPair& pair, Scalar slack, int max_iterations)
    : pair_(pair), slack_(slack), max_iterations_(max_iterations) {}

// Points of `body` within the slack of its supporting plane along `n` (its support point climbing
// from, and returned in, `hint`), highest first, into `found`.
void DistanceFinish::feature(const FramedBody& body, const Vector3& n, int& hint,
                             std::vector<int>& found) {
  hint = body.support_index(n, hint);
  Buffers& buf = buffers();
  supporting_feature(body, n, hint, slack_, buf.visited, found);
  // Each height computed once: a curved body's features hold hundreds of its support points
  // once a swarm has asked for them, each placed again at every comparison.
  std::vector<std::pair<Scalar, int>>& ranked = buf.ranked;
  ranked.clear();
  for (int i : found) ranked.emplace_back(body.height(i, n), i);
  // Highest first; equal heights in the order found, as the comparison of heights alone kept
  // them (a stable sort). Past kCurvedFeaturePoints, a curved body's highest are selected first
  // (ties by number: supporting_feature finds a curved body's points in their order), and the
  // sort then keeps the selection's order of equal heights.
  const auto higher = [](const auto& p, const auto& q) { return p.first > q.first; };
  if (body.curved() && ranked.size() > kCurvedFeaturePoints) {
    const auto higher_first = [](const auto& p, const auto& q) {
      return p.first > q.first || (p.first == q.first && p.second < q.second);
    };
    std::nth_element(ranked.begin(), ranked.begin() + kCurvedFeaturePoints, ranked.end(),
                     higher_first);
    ranked.resize(kCurvedFeaturePoints);
    found.resize(kCurvedFeaturePoints);
  }
  std::stable_sort(ranked.begin(), ranked.end(), higher);
  for (std::size_t k = 0; k < ranked.size(); ++k) found[k] = ranked[k].second;
}

// The exact nearest points of the hulls of two features: Wolfe's algorithm on their Minkowski
// difference from `start`, with support points by scanning the features.
Witness DistanceFinish::nearest_between(const std::vector<int>& fa, const std::vector<int>& fb,
                                        const Vector3& start) {
  const auto oracle = [&](const Vector3& d) {
    ++evaluations_;
    return feature_support(pair_.a, fa, pair_.b, fb, d);
  };
  // In the frame every point lies in the unit ball, so 2 bounds every difference.
  return witness_of(pair_, wolfe_min_norm(oracle, start, 2, max_iterations_));
}

bool DistanceFinish::from(const Vector3& n, int& hint_a, int& hint_b, BestBounds& bounds,
                          Goal goal) {
  Buffers& buf = buffers();
  std::vector<int>& fa = buf.feature_a;
  std::vector<int>& fb = buf.feature_b;
  feature(pair_.a, n, hint_a, fa);
  feature(pair_.b, -n, hint_b, fb);
  // Each subproblem grows around the previous one's nearest points, so Wolfe starts there.
  Vector3 start = n;
  for (int step = 0; step < kFinishSteps; ++step) {
    const Witness sub = nearest_between(fa, fb, start);
    bounds.offer_upper(sub);
    if (bounds.reached(pair_, goal)) return true;
    if (!(sub.distance > 0)) return false;
    const Vector3 next = (sub.point_b - sub.point_a) / sub.distance;
    start = next;
    int ia = hint_a;
    int ib = hint_b;
    ++evaluations_;
    bounds.offer_lower(next, separation(pair_.a, pair_.b, next, ia, ib));
    if (bounds.reached(pair_, goal)) return true;
    feature(pair_.a, next, ia, buf.grown);
    const bool grew_a = merge(fa, buf.grown, pair_.a.size(), buf.visited);
    feature(pair_.b, -next, ib, buf.grown);
    const bool grew_b = merge(fb, buf.grown, pair_.b.size(), buf.visited);
    if (!grew_a && !grew_b) return false;  // rounding: nothing left to add
  }
  return false;
}

bool DistanceFinish::whole(const Vector3& start, int& hint_a, int& hint_b, BestBounds& bounds,
                           Goal goal, bool enclosure, const OraclePoint* first_point) {
  // Curved pairs have searches of their own, which take the curved supports inline
  // (curved_search.cpp): inlined into this function's searches, the supports made 64-vertex
  // polytope rows up to 287 instructions longer. Two ellipsoids (smooth, strictly convex) ask
  // along secant directions (secant_search.cpp). The edges and flat faces of cylinders, cones and
  // boxes make the support map far from affine: secant steps there cost more support calls than
  // they save (cylinder-cylinder apart 29,380 -> 43,068 instructions per query), and a
  // polytope's Wolfe walk ends in a few exact steps. Its first point is asked again there
  // (`first_point` only saves a scan of a polytope). A curved pair is `adjusted` (its support
  // error): polyhedra without radii pass one test, as they passed smooth()'s. Secant steps asked
  // only at the end of a search (once the gap is within 1e-5 |x|) of an ellipsoid beside a
  // cylinder or a cone cut its oracle calls by 12-15% but not its instructions (callgrind_curved,
  // 100 pairs apart: cone-ellipsoid 19,675 -> 20,060, cylinder-ellipsoid 19,828 -> 19,714): the
  // model's solve and the second support of a refused secant point cost what the calls saved.
  if (pair_.adjusted && (pair_.a.curved() || pair_.b.curved())) {
    if (smooth(pair_.a) && smooth(pair_.b)) {
      return whole_secant(start, hint_a, hint_b, bounds, goal, enclosure);
    }
    return whole_curved(start, hint_a, hint_b, bounds, goal, enclosure, first_point);
  }
  // Each oracle point is asked with Nesterov's momentum or along the corral's point itself, and
  // bounds the distance by its separation along the direction it was asked for
  // (NesterovDirection, AlongCorral).
  // Two small polytopes, scanned whole whatever the hints, have a search of their own whose
  // oracle scans both bodies inline (minkowski_support's two calls out of line and their tests
  // of the bodies' kinds were a sixth of each scan); the other pairs' search compiles as it did
  // alone (one oracle testing for both, 64-vertex queries took 1% more). Each search is
  // flattened, everything it calls inlined into it: left to the inliner, the two competed for
  // this function's budget, and whichever lost ran its oracle out of line (with the support scans
  // dispatched to wider instruction sets, 260-vertex rows 6,204 -> 6,442 instructions; flattened,
  // swarmcollide-thread-scaling count distance: 8 vertices apart 3,388 -> 3,369, overlapping
  // 5,146 -> 4,984, 260 apart 6,442 -> 6,176).
  // The oracle keeps the points it placed, by index (a scanned body has at most
  // kHillClimbingThreshold), and the corrals' witnesses read them: placing them again was most of
  // what a witness cost (callgrind_query, 4 vertices overlapping: 505 of 5,529 instructions a
  // distance). Every corral point is an oracle point, or the given first one, placed here. Two
  // bodies of at most kRegisterColumns points are placed whole first and scanned in the frame
  // (PlacedFew): callgrind_query, 4 vertices, a verdict overlapping 4,399 -> 4,029 instructions,
  // 1e-2 apart 5,268 -> 4,641, a distance 4,359 -> 3,990 and 5,455 -> 4,790, but a verdict the
  // first point settles (apart) 1,014 -> 1,117.
  // Pairs with a body of more than kMomentumSize points search with the momentum, but where
  // their first point lies mostly along the start (NesterovDirection::mostly_along_start);
  // smaller pairs search as before. Each way is an instance of its own, holding its placed points
  // and oracle: those without momentum compile as the search did before it (the momentum's state
  // held and tested in every step made 4-point queries 40-220 instructions longer; the points and
  // oracle held by whole() and read through references, 13-54). Large bodies' first point is
  // asked here, unless given, to choose: tested in every step of one instance, the momentum's
  // state made 260-point batch rows apart 3% longer. Scanned pairs' instance with momentum tests
  // their first point itself: asked here, 16-point verdicts apart, settled by it, took 8% longer.
  const bool large = std::max(pair_.a.size(), pair_.b.size()) > kMomentumSize;
  if (pair_.a.scanned() && pair_.b.scanned()) {
    const auto small_search = [&](auto directions, auto few) SWARMCOLLIDE_FLATTEN {
      using Placed = std::conditional_t<decltype(few)::value, PlacedFew, PlacedSupports>;
      Placed placed_a(pair_.a);
      Placed placed_b(pair_.b);
      if (first_point != nullptr) {
        placed_a.place(pair_.a, first_point->ia);
        placed_b.place(pair_.b, first_point->ib);
      }
      const auto scan = [&](const Vector3& d) __attribute__((always_inline)) {
        ++evaluations_;
        hint_a = placed_a.support(pair_.a, d);
        hint_b = placed_b.support(pair_.b, -d);
        const Vector3& x = placed_a.place(pair_.a, hint_a);
        const Vector3& y = placed_b.place(pair_.b, hint_b);
        return OraclePoint{y - x, hint_a, hint_b};
      };
      const auto scans = [&](const Vector3& x) __attribute__((always_inline)) {
        return directions.ask(x, scan);
      };
      const auto measured = [&](const MinNormPoint& current, const OraclePoint& q,
                                Scalar inverse_norm) {
        return directions.measured(current, q, inverse_norm);
      };
      const auto kept = [&](const MinNormPoint& corral, bool enclose) {
        const auto point_a = [&](int i) -> const Vector3& { return placed_a.point(i); };
        const auto point_b = [&](int j) -> const Vector3& { return placed_b.point(j); };
        return tested_witness(pair_, corral, combined_witness(corral, point_a, point_b), enclose);
      };
      return whole_search(pair_, start, first_point, hint_a, hint_b, bounds, goal, enclosure,
                          max_iterations_, evaluations_, scans, measured, kept);
    };
    // Two bodies of up to kRegisterColumns points, scanned in registers, have an instance of
    // their own (PlacedFew), and the others scan on the chosen set (PointColumns::sized_scan).
    constexpr std::false_type on_set{};
    if (large) return small_search(NesterovDirection(start, first_point), on_set);
    if (pair_.a.size() <= kRegisterColumns && pair_.b.size() <= kRegisterColumns) {
      return small_search(AlongCorral(), std::true_type());
    }
    return small_search(AlongCorral(), on_set);
  }
  // The supports of large bodies climb from the previous ones, unless the direction turned by
  // more than about 25 degrees (as Wolfe's first steps do): the hull's climbing starts are then
  // nearer. Small bodies are scanned, whatever the hints.
  const bool climbs =
      pair_.a.size() > kHillClimbingThreshold || pair_.b.size() > kHillClimbingThreshold;
  OraclePoint along_start;
  const OraclePoint* first = first_point;
  if (large && first == nullptr) {
    // The search counts it, as the call it replaces.
    along_start = minkowski_support(pair_.a, pair_.b, start, hint_a, hint_b);
    first = &along_start;
  }
  const auto climbing_search = [&](auto directions) SWARMCOLLIDE_FLATTEN {
    Vector3 previous = start;
    const auto support = [&](const Vector3& d) __attribute__((always_inline)) {
      ++evaluations_;
      if (climbs) drop_hints_after_turn(d, previous, hint_a, hint_b);
      return minkowski_support(pair_.a, pair_.b, d, hint_a, hint_b);
    };
    const auto oracle = [&](const Vector3& x) __attribute__((always_inline)) {
      return directions.ask(x, support);
    };
    const auto measured = [&](const MinNormPoint& current, const OraclePoint& q,
                              Scalar inverse_norm) {
      return directions.measured(current, q, inverse_norm);
    };
    return whole_search(pair_, start, first, hint_a, hint_b, bounds, goal, enclosure,
                        max_iterations_, evaluations_, oracle, measured, PlacedByBodies{pair_});
  };
  if (large && !NesterovDirection::mostly_along_start(start, *first)) {
    return climbing_search(NesterovDirection(start, first));
  }
  return climbing_search(AlongCorral());
}

bool DistanceFinish::whole_from_corral(const Vector3& start, const MinNormPoint& corral,
                                       int& hint_a, int& hint_b, BestBounds& bounds, Goal goal,
                                       bool enclosure) {
  if (smooth(pair_.a) && smooth(pair_.b)) {
    return whole_secant(start, hint_a, hint_b, bounds, goal, enclosure);
  }
  return walk_from_corral(start, corral, hint_a, hint_b, bounds, goal, enclosure);
}

}  // namespace swarmcollide::detail
