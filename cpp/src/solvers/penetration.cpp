#include "penetration.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include "../geometry/curved_depth.hpp"
#include "../geometry/nearest_on_segments.hpp"
#include "../geometry/normalise.hpp"
#include "../geometry/support.hpp"
#include "../geometry/support_tree.hpp"
#include "../geometry/unit_direction.hpp"
#include "candidate_axes.hpp"
#include "cone_side.hpp"
#include "cylinder_side.hpp"
#include "expanding_polytope.hpp"
#include "minkowski.hpp"
#include "nearest_simplex_point.hpp"
#include "rolling_ball.hpp"
#include "wolfe_min_norm.hpp"

namespace swarmcollide::detail {

namespace {

constexpr Scalar kInfinity = std::numeric_limits<Scalar>::infinity();
// The scales of coordinates the margins hold for (squares of coordinates far from both limits).
constexpr Scalar kLargestCoordinate = 1e100;
constexpr Scalar kSmallestCoordinate = 1e-100;
// Work (edge pairs plus faces times points) up to which the candidate axes are the fallback when
// the polytope proves too little (tens of milliseconds); larger pairs keep the bounds they have,
// unproven.
constexpr long long kAxesFallbackWork = 1LL << 22;
// Times the witnesses' feature slack may grow 16-fold (from about 1e-12 to 1e-7 of the frame).
constexpr int kWitnessWidenings = 5;
// Iterations of Wolfe's algorithm on the witnesses' features (it stops at rounding long before).
constexpr int kWitnessIterations = 100;
// Times a curved pair's expansion goes on, each to a sixteenth of the gap, where no witnesses lie
// along its normal (Solver::resume_expansion).
constexpr int kWitnessResumes = 4;
// Corners of a surface kept for the next solve of the same pair (KeptSurface): an expansion
// adds one or two per frame to the one it started from, and a larger one costs more to place
// again than a few steps from a tetrahedron.
constexpr int kMostKeptCorners = 16;
// Steps from a tetrahedron from which its surface is kept: a resting contact's tetrahedron on
// its face takes one or two, fewer than placing a surface's faces again costs.
constexpr int kKeptFromSteps = 4;
// The gap (frame units, the pair's size 1 to 2) to which a pair with a cylinder or a cone
// expands before its side is tried (cylinder_side.hpp, cone_side.hpp), where the faces nearer
// than the side's bound lie within its wedge on most pairs whose side holds the deepest point.
// Overlapping cylinders took 65,242 instructions a query at 2^-10, 63,138 at 2^-12, 66,014 at
// 2^-14, 77,267 at 2^-8 (72,061 with the expansion alone; callgrind_query.py --curved --pairs
// 100, the chain as first built).
constexpr Scalar kSideGap = 0x1p-12;

// Buffers a solve reuses from the previous one on the same thread.
struct Workspace {
  ExpandingPolytope polytope;
  CandidateAxes axes;
  // The frame's points of placed bodies, for the candidate axes, which read each many times.
  VertexMatrix points_a;
  VertexMatrix points_b;
  std::vector<int> feature_a;
  std::vector<int> feature_b;
  std::vector<char> visited;  // all zero between uses
};

Workspace& thread_workspace() {
  thread_local Workspace workspace;
  return workspace;
}

long long edge_count(const Hull& hull) {
  if (hull.dimension <= 0) return 0;
  if (hull.dimension == 1) return 1;
  return static_cast<long long>(hull.neighbours.size()) / 2;
}

// What the candidate axes cost: every edge pair, and every face against every point (the check
// of how far the points stray from the hull's faces).
long long axes_work(const FramedBody& a, const FramedBody& b) {
  // A curved body has no faces or edges to enumerate.
  if (a.curved() || b.curved()) return std::numeric_limits<long long>::max();
  const auto faces_by_points = [](const FramedBody& body) {
    return body.hull().dimension == 3
               ? static_cast<long long>(body.hull().faces.rows()) * body.size()
               : 0;
  };
  return edge_count(a.hull()) * edge_count(b.hull()) + faces_by_points(a) + faces_by_points(b);
}

// Largest absolute coordinate of the pair: the rounding margins are multiples of it.
Scalar largest_coordinate(const VertexMatrix& a, const VertexMatrix& b) {
  return std::max(a.cwiseAbs().maxCoeff(), b.cwiseAbs().maxCoeff());
}

// Whether support_index scans every point of `body` (a small polyhedron), whatever its start: its
// support along a direction is then scanned_support's.
bool scanned_whole(const FramedBody& body) {
  return !body.curved() && body.size() <= kHillClimbingThreshold;
}

// A point of `body` highest along `n` as a scan of its points finds it (FramedBody::
// support_index, whose shortfall margin() covers): for large placed bodies by the branch and
// bound of their support tree (built once per body), seeded by a climb from `hint`, or by `hint`
// itself where it is a climb's answer along `n` already (`climbed`: a climb from a point none of
// whose neighbours is higher, and no lower than its cube-map cell's start, stays there).
// `shortfall` is the body's scan_shortfall(), which the solver keeps.
int scanned_support(const FramedBody& body, Scalar shortfall, const Vector3& n, int hint,
                    bool climbed) {
  if (body.curved() || body.size() <= kHillClimbingThreshold || shortfall == 0) {
    return body.support_index(n);
  }
  const VertexMatrix& points = body.local_points();
  const int key = &points == &body.body().centred_vertices() ? 0 : 1;
  const SupportTree& tree =
      body.body().derived<SupportTree>([&] { return SupportTree(points); }, key);
  return tree.support_index(points, body.local_direction(n),
                            climbed ? hint : body.support_index(n, hint));
}

class Solver {
 public:
  Solver(const FramedBody& a, const FramedBody& b, Scalar tolerance, int max_iterations,
         Scalar coordinate, KeptSurface* surface = nullptr)
      : surface_(surface),
        a_(a),
        b_(b),
        tolerance_(tolerance),
        max_iterations_(std::max(1, max_iterations)),
        ws_(thread_workspace()),
        coordinate_(coordinate),
        shortfall_a_(a.scan_shortfall()),
        shortfall_b_(b.scan_shortfall()) {}

  PenetrationBounds solve(const Vector3& hint, const MinNormPoint* nearest) {
    offer_flat_normals();
    if ((a_.curved() || b_.curved()) && use_closed_form()) return result();
    if ((a_.curved() || b_.curved()) && use_rolling_ball(hint)) return result();
    // An intersection proof's tetrahedron starts the polytope at once, whose faces' normals are
    // the directions to measure: the hint is tried only if they leave a gap. Otherwise Wolfe's
    // nearest point (the caller's, or found here from the hint) bounds the distance, and its
    // tetrahedron, if it encloses the origin, starts the polytope.
    const bool enclosed =
        (surface_ != nullptr && enclose_kept()) ||
        (nearest != nullptr && nearest->size == MinNormPoint::kCapacity && enclose(*nearest));
    if (!enclosed) {
      offer_hint(hint);
      if (nearest != nullptr) {
        use_nearest(*nearest);
      } else {
        nearest_then_polytope();
      }
    }
    finish();
    // A given corral that leaves a gap (touching pairs whose triangles missed the contact plane)
    // is followed by Wolfe's algorithm from the best direction, as when none is given.
    if (!done() && nearest != nullptr && !enclosed) {
      nearest_then_polytope();
      finish();
    }
    if (!done() && enclosed && offer_hint(hint)) finish();
    if (!done() && (a_.curved() || b_.curved()) && complete_tetrahedron()) finish();
    if (!done() && axes_work(a_, b_) <= kAxesFallbackWork) {
      enumerate_axes();
      finish();
    }
    if (surface_ != nullptr) {
      if (expanded_ && (expanded_from_kept_ || expansion_.iterations >= kKeptFromSteps)) {
        ws_.polytope.keep(expansion_, kMostKeptCorners, *surface_);
      } else {
        surface_->clear();
      }
    }
    return result();
  }

 private:
  Scalar margin() const {
    return separation_margin(coordinate_) + shortfall_a_ + shortfall_b_;
  }
  Scalar reach() const { return 2 * std::sqrt(Scalar(3)) * coordinate_; }
  Scalar lower() const { return separation_ - margin(); }
  // The gap below which the rounding margins leave nothing to gain.
  Scalar floor() const { return 16 * margin(); }
  bool done() const { return upper() - lower() <= std::max(tolerance_, floor()); }
  Scalar upper() const {
    return std::min(proven_upper_, nearest_length_ + 16 * kRoundoff * reach());
  }

  // The gap at which the expanding polytope stops. Its bound and the finish's separation along
  // its best normal (within margin() of a proven one) must end within the tolerance. Where a
  // support climbs (a large polytope), the finish's scan may find a higher point than the climb
  // did, so half the tolerance is left for that. Where every support is a scan or a curved
  // shape's support function, the finish measures along the polytope's best normal the very
  // points the polytope found (up to the rounding of the two ways of summing the heights), so
  // the polytope may close to the tolerance less twice the margin: a curved pair's polytope,
  // which gains a few digits per handful of steps, stops a step or two earlier.
  Scalar polytope_gap() const {
    const bool scanned_a = a_.curved() || a_.size() <= kHillClimbingThreshold;
    const bool scanned_b = b_.curved() || b_.size() <= kHillClimbingThreshold;
    if (!(a_.curved() || b_.curved()) || !scanned_a || !scanned_b) return tolerance_ / 2;
    return std::max(tolerance_ / 2, tolerance_ - 2 * margin() - 64 * kRoundoff * reach());
  }
  // Where an expansion stops: the polytope's gap, and no finer than a quarter of the floor.
  Scalar stop_gap() const { return std::max(polytope_gap(), floor() / 4); }

  // Flat bodies touch along their plane and two segments along their common normal, which the
  // polytope cannot find when A - B has no interior; trying these costs a few climbs.
  void offer_flat_normals() {
    Vector3 axis[2];
    int segments = 0;
    for (const FramedBody* body : {&a_, &b_}) {
      if (body->curved()) continue;  // never flat, and its points have no hull
      const Hull& h = body->hull();
      if (h.dimension == 2) {
        const Vector3 p = body->vertex(h.faces(0, 0));
        const Vector3 n = (body->vertex(h.faces(0, 1)) - p).cross(body->vertex(h.faces(0, 2)) - p);
        offer(n);
        offer(-n);
      } else if (h.dimension == 1) {
        axis[segments++] = body->vertex(h.vertex_indices[1]) - body->vertex(h.vertex_indices[0]);
      }
    }
    if (segments == 2) {
      offer(axis[0].cross(axis[1]));
      offer(-axis[0].cross(axis[1]));
    }
  }

  // A direction to try, of any length (none for the zero vector): its separation from climbed
  // supports ranks it; the best one is measured exactly by `finish`. True when it became the
  // candidate. The unit vector is made here (unit_direction), where every bound along it is
  // taken: normals of a body's tiny features, made unit by their callers, were not.
  bool offer(const Vector3& direction) {
    const std::optional<Vector3> unit = unit_direction(direction);
    if (!unit) return false;
    const Vector3& n = *unit;
    const Scalar estimate = separation(a_, b_, n, climb_a_, climb_b_);
    const bool taken = offer(n, estimate);
    climbs_along_candidate_ = taken;
    return taken;
  }
  bool offer(const Vector3& n, Scalar estimate) {
    if (!(estimate > estimate_)) return false;
    estimate_ = estimate;
    candidate_ = n;
    climbs_along_candidate_ = false;
    return true;
  }
  bool offer_hint(const Vector3& hint) {
    return offer(hint);
  }

  // The candidate's separation by scanning every point, which a proven lower bound needs (a climb
  // can stop a rounding error short of the maximum). The scans compare heights in each body's
  // own frame, within its `scan_shortfall` (in margin()) of the frame's highest.
  void finish() {
    if (!(estimate_ > -kInfinity)) offer(Vector3::UnitX());
    // Measured already (a cylinder's side measures its normal to know whether it settled the
    // answer, before solve's own finish).
    if (normal_ == candidate_ && separation_ > -kInfinity) return;
    normal_ = candidate_;
    // A polytope that support_index scans whole has its scan's support in the climb start
    // already when that start was found along the candidate (scanned_support would repeat it).
    const bool known_a = climbs_along_candidate_ && scanned_whole(a_);
    const bool known_b = climbs_along_candidate_ && scanned_whole(b_);
    top_a_ = known_a ? climb_a_
                     : scanned_support(a_, shortfall_a_, candidate_, climb_a_,
                                       climbs_along_candidate_);
    top_b_ = known_b ? climb_b_
                     : scanned_support(b_, shortfall_b_, -candidate_, climb_b_,
                                       climbs_along_candidate_);
    top_height_a_ = a_.height(top_a_, candidate_);
    top_height_b_ = b_.height(top_b_, candidate_);
    separation_ = top_height_b_ - top_height_a_;
  }

  void set_upper(Scalar value, PenetrationProof proof) {
    if (value < proven_upper_) {
      proven_upper_ = value;
      proof_ = proof;
    }
  }

  // Wolfe's nearest point of B - A to the origin: an upper bound |p| (p is a point of B - A, so
  // s(n) <= n.p <= |p| for every n) and, when the origin is inside, a tetrahedron around it for
  // the expanding polytope.
  void nearest_then_polytope() {
    int ia = climb_a_;
    int ib = climb_b_;
    const auto oracle = [&](const Vector3& d) { return minkowski_support(a_, b_, d, ia, ib); };
    // The first point is the one of B - A farthest along the best direction so far.
    Vector3 start =
        estimate_ > -kInfinity ? Vector3(-candidate_) : Vector3(b_.vertex(0) - a_.vertex(0));
    if (!(start.norm() > 0)) start = -Vector3::UnitX();
    const MinNormPoint m = wolfe_min_norm(oracle, start, reach(), max_iterations_);
    iterations_ += m.iterations;
    if (m.size == MinNormPoint::kCapacity && enclose(m)) return;
    use_nearest(m);
  }

  // Wolfe's nearest point `m` of B - A, whose tetrahedron (if any) does not start the polytope:
  // the upper bound |p| and the directions it suggests.
  void use_nearest(const MinNormPoint& m) {
    last_corral_ = m;
    // The exact convex combination of the corral (weights normalised) is a point of B - A; the
    // computed one is within 16 roundoffs of reach() of it (added in upper()).
    Scalar total = 0;
    for (int k = 0; k < m.size; ++k) total += m.weights[k];
    Vector3 p = Vector3::Zero();
    for (int k = 0; k < m.size; ++k) p += m.weights[k] / total * m.corral[k].p;
    if (p.norm() < nearest_length_) nearest_length_ = p.norm();
    offer(p);
    // Touching bodies: the origin is on the boundary of B - A and on the corral's triangles, which
    // then lie in the supporting plane there, so their normals are the contact normal.
    for (int k = 0; m.size >= 3 && k < m.size; ++k) {
      const Vector3& p0 = m.corral[k].p;
      const Vector3 n =
          (m.corral[(k + 1) % m.size].p - p0).cross(m.corral[(k + 2) % m.size].p - p0);
      offer(n);
      offer(-n);
      if (m.size == 3) break;
    }
  }

  // The expanding polytope, in A - B, from Wolfe's tetrahedron around the origin turned over;
  // true when it proved an upper bound.
  bool enclose(const MinNormPoint& m) {
    std::array<DifferencePoint, 4> start_tetrahedron;
    for (int k = 0; k < 4; ++k) {
      start_tetrahedron[k] = {-m.corral[k].p, m.corral[k].ia, m.corral[k].ib};
    }
    expanded_from_kept_ = false;
    if (has_side() && stop_gap() < kSideGap) {
      // Verified only where the side needs its faces (side_chain.hpp), or at the end.
      const bool dipped = use_expansion(
          ws_.polytope.run(a_, b_, start_tetrahedron, kSideGap, max_iterations_, false));
      if (use_side()) return true;
      return use_expansion(ws_.polytope.resume(a_, b_, stop_gap(), max_iterations_)) || dipped;
    }
    return use_expansion(
        ws_.polytope.run(a_, b_, start_tetrahedron, stop_gap(), max_iterations_));
  }

  // A cone's side is tried beside curved bodies only: beside a box, whose flat faces the
  // expansion closes on in few steps past 2^-12, its chain cost more than the steps it saved
  // (overlapping cone-box pairs 36,930 -> 40,320 instructions a query; a cylinder's side still
  // pays there, cylinder-box 46,759 -> 45,101).
  static bool has_side(const FramedBody& body, const FramedBody& other) {
    return body.curved_kind() == CurvedKind::cylinder ||
           (body.curved_kind() == CurvedKind::cone && other.curved());
  }
  bool has_side() const { return has_side(a_, b_) || has_side(b_, a_); }

  // Where a cylinder's or a cone's side holds the deepest point, its section proves the depth
  // (cylinder_side.hpp, cone_side.hpp) from the polytope expanded so far, to a gap that takes
  // it half the steps; the direction it gives is measured as any other. True when that settles
  // the answer.
  bool use_side() {
    if (!(expansion_.best_separation > -kInfinity)) return false;  // no face was made
    for (const bool side_of_a : {false, true}) {
      const FramedBody& body = side_of_a ? a_ : b_;
      if (!has_side(body, side_of_a ? b_ : a_)) continue;
      const bool cylinder = body.curved_kind() == CurvedKind::cylinder;
      const SideDepth side = cylinder ? cylinder_side_depth(a_, b_, side_of_a, ws_.polytope,
                                                            expansion_.best_normal, stop_gap())
                                      : cone_side_depth(a_, b_, side_of_a, ws_.polytope,
                                                        expansion_.best_normal, stop_gap());
      iterations_ += side.steps;
      if (!(side.lower > expansion_.depth_lower)) continue;
      set_upper(-side.lower,
                cylinder ? PenetrationProof::cylinder_side : PenetrationProof::cone_side);
      // The witnesses: along the normal a cylinder's or a cone's support may be a whole segment
      // of its side (the cylinder's is, the normal being across its axis), whose ends the
      // supports a little off the normal towards either end of the axis give.
      side_normal_ = side.normal;
      for (const FramedBody* body : {&a_, &b_}) {
        std::array<int, 2>& ends = body == &a_ ? side_ends_a_ : side_ends_b_;
        ends = {-1, -1};
        const CurvedKind kind = body->curved_kind();
        if (kind != CurvedKind::cylinder && kind != CurvedKind::cone) continue;
        const Vector3 along = body == &a_ ? side.normal : Vector3(-side.normal);
        ends[0] = body->support_index(along - Scalar(1e-3) * frame_axis(*body));
        ends[1] = body->support_index(along + Scalar(1e-3) * frame_axis(*body));
      }
      offer(side.normal);
      finish();
      return done();
    }
    return false;
  }

  // The expanding polytope from the surface this pair's last one ended with (surface_), its
  // corners placed at these poses: after a small motion most of its faces are still where the
  // new expansion would put them, and it needs a step or two instead of a few from a
  // tetrahedron. False when that surface does not enclose the origin provably any more (a face
  // cannot be proven oriented), or its expansion stopped short of the gap (a horizon that is not
  // one loop, on a surface the motion left a little concave), or proved no bound: the
  // tetrahedron's expansion then runs as if nothing were kept.
  bool enclose_kept() {
    bool started = false;
    face_index_ = -1;
    near_face_index_ = -1;
    const ExpansionResult e =
        ws_.polytope.run(a_, b_, *surface_, stop_gap(), max_iterations_, started);
    if (!started || !e.converged) return false;
    expanded_from_kept_ = true;
    return use_expansion(e);
  }

  // What an expansion found: its best normal is offered, and its bound proven if verified.
  bool use_expansion(const ExpansionResult& e) {
    expanded_ = true;
    expansion_ = e;
    iterations_ += e.iterations;
    // This run's surface replaced the one an earlier face was on.
    face_index_ = -1;
    near_face_index_ = -1;
    if (e.best_separation > -kInfinity && offer(e.best_normal, e.best_separation)) {
      // The supports there seed the scans that measure it, and the face may give the witnesses.
      climb_a_ = e.best_ia;
      climb_b_ = e.best_ib;
      // The expansion asked them of support_index along this very normal.
      climbs_along_candidate_ = true;
      face_ = e.best_face;
      face_index_ = e.best_face_index;
      near_face_index_ = e.near_best_face;
      face_normal_ = e.best_normal;
    }
    if (e.verified) set_upper(-e.depth_lower, PenetrationProof::polytope);
    return e.verified;
  }

  // A curved shape's closed form proves the depth of the other body's points in it, which the
  // polytope cannot where a circle of directions is deepest (curved_depth.hpp); the direction of
  // the nearest surface is measured as any other. True when that settles the answer.
  bool use_closed_form() {
    const ClosedFormDepth closed = closed_form_depth(a_, b_);
    if (!(closed.depth > 0)) return false;
    set_upper(-closed.depth, PenetrationProof::closed_form);
    (closed.curved_a ? a_ : b_).add_point(closed.surface);
    offer(closed.normal);
    finish();
    return done();
  }

  // Balls rolling inside curved bodies prove the depth from Wolfe's nearest point of the
  // difference of their centres (rolling_ball.hpp), a search that ends where the expanding
  // polytope would need dozens of steps; the separation along its direction is measured as any
  // other. True when that settles the answer.
  bool use_rolling_ball(const Vector3& hint) {
    if (!rolls(a_) && !rolls(b_)) return false;
    const Vector3 start =
        hint.allFinite() && hint.norm() > 0 ? hint : Vector3(b_.offset() - a_.offset());
    return roll(start, polytope_gap()) && done();
  }

  // The balls' search from the direction `start` to `gap`, its bound and normal taken as the
  // solver's: true when it proved a bound.
  bool roll(const Vector3& start, Scalar gap) {
    const RollingBallDepth& rolling =
        rolling_.emplace(rolling_ball_depth(a_, b_, start, gap, max_iterations_));
    iterations_ += rolling.iterations;
    if (!rolling.proven) return false;
    set_upper(-rolling.depth_lower, PenetrationProof::rolling_ball);
    offer(rolling.normal);
    finish();
    // A secant step's point, alone in the corral, may lie a little off the direction it was
    // asked along, whose separation met the search's gap: that direction is measured too.
    if (!done() && rolling.measured != rolling.normal) {
      offer(rolling.measured);
      finish();
    }
    return true;
  }

  // Curved bodies have no candidate axes to fall back on. Where Wolfe's corral stops short of a
  // tetrahedron around the origin (touching bodies, or coaxial ones whose supports along the
  // axis line up through it), points of B - A along the axes of the best direction's frame, their
  // diagonals and the corners of a regular tetrahedron around them, with the corral's, make
  // tetrahedra: the one that encloses the origin deepest (its least barycentric weight largest)
  // starts the expanding polytope. True when one did. (Without the corners, bodies sharing a
  // centre and an axis were never certified: with the origin at the centre of B - A, each point
  // along a direction has its opposite along the opposite one, and every tetrahedron of the axes
  // and diagonals held the origin on a face or an edge, not inside.)
  bool complete_tetrahedron() {
    constexpr int kDirections = 14;
    std::array<OraclePoint, MinNormPoint::kCapacity + kDirections> points;
    int count = 0;
    for (int k = 0; k < last_corral_.size; ++k) points[count++] = last_corral_.corral[k];
    const Vector3 w = unit_direction_or(candidate_, Vector3::UnitX());
    const Vector3 helper = std::abs(w.x()) < 0.6 ? Vector3::UnitX() : Vector3::UnitY();
    const Vector3 u = w.cross(helper).normalized();
    const Vector3 v = w.cross(u);
    const Vector3 directions[kDirections] = {w,         -w,        u,          -u,        v,
                                             -v,        u + v,     -u - v,     u - v,     v - u,
                                             w + u + v, w - u - v, -w + u - v, -w - u + v};
    for (const Vector3& d : directions) {
      int ia = -1;
      int ib = -1;
      points[count++] = minkowski_support(a_, b_, d, ia, ib);
    }
    MinNormPoint best;
    Scalar deepest = 0;
    std::array<Scalar, 4> weights;
    for (int i = 0; i < count; ++i) {
      for (int j = i + 1; j < count; ++j) {
        for (int k = j + 1; k < count; ++k) {
          for (int l = k + 1; l < count; ++l) {
            if (!encloses_origin({points[i].p, points[j].p, points[k].p, points[l].p}, weights)) {
              continue;
            }
            const Scalar least = *std::min_element(weights.begin(), weights.end());
            if (least > deepest) {
              deepest = least;
              best.corral = {points[i], points[j], points[k], points[l]};
              best.size = MinNormPoint::kCapacity;
            }
          }
        }
      }
    }
    return best.size == MinNormPoint::kCapacity && enclose(best);
  }

  // The axes read every point many times: a placed body's points are placed once, as the frame
  // computes them (the same values `vertex` gives).
  void enumerate_axes() {
    const FramedBody* a = &a_;
    const FramedBody* b = &b_;
    std::optional<FramedBody> placed_a;
    std::optional<FramedBody> placed_b;
    if (shortfall_a_ > 0) {
      a_.points(ws_.points_a);
      a = &placed_a.emplace(ws_.points_a, a_.hull());
    }
    if (shortfall_b_ > 0) {
      b_.points(ws_.points_b);
      b = &placed_b.emplace(ws_.points_b, b_.hull());
    }
    const AxesBound bound = ws_.axes.run(*a, *b, coordinate_);
    offer(bound.best_normal);
    // Below -flat_slack the difference is full-dimensional with the origin inside. Otherwise the
    // facets bound sd only if the origin is inside, |p| bounds it if not, and their maximum is
    // no better than |p| alone, which upper() already has.
    if (bound.upper < -bound.flat_slack) set_upper(bound.upper, PenetrationProof::candidate_axes);
  }

  // Witnesses: on A's supporting feature along the normal and B's along its opposite, the pair
  // whose difference is nearest to separation * normal (Wolfe's algorithm on the features'
  // difference shifted by it). At an optimal normal the foot of the origin on the facet of
  // A - B lies in that difference, and the residual is rounding.
  void witnesses(PenetrationBounds& r) {
    const Scalar gap = std::isfinite(upper()) ? std::max(Scalar(0), upper() - lower()) : 0;
    // A normal a gap's worth of angle off the optimal facet's tilts the optimal features by
    // more than the gap along long edges (a needle's, say): a feature cut to one of its vertices
    // leaves witnesses apart by far more than the tolerance. The slack widens until they agree.
    const Scalar target = witness_target();
    Scalar slack = 1024 * margin() + 2 * std::min(gap, Scalar(1e-9));
    if (normal_ == face_normal_ && witnesses_from_face(face_, slack, target, r)) return;
    // Its face rejected, most often because the foot lies on another face of the same facet (a
    // resting contact's): that face, if the surface is still the one it came from.
    if (normal_ == face_normal_ && near_face_index_ >= 0) {
      std::array<DifferencePoint, 3> crossed;
      const int f = ws_.polytope.face_crossed(near_face_index_, normal_, crossed);
      if (f >= 0 && f != face_index_ && witnesses_from_face(crossed, slack, target, r)) return;
      // A curved pair's surface converges on a patch of faces each a little tilted from the
      // next, and the foot may lie just beyond the best normal's face, on a face whose own
      // corners are off the separation along this normal by far more than the tolerance: the
      // point of the patch's corners nearest to it. (witnesses_within below finds one among
      // every support point near the supporting planes, which a fifth of the overlapping
      // cylinder and cone pairs went to: this made their rows 1-3% shorter.)
      if (witnesses_around_face(f >= 0 ? f : near_face_index_, slack, target, r)) return;
    }
    if (normal_ == side_normal_ && witnesses_from_side(target, r)) return;
    if (rolling_ && rolling_->proven && normal_ == rolling_->normal &&
        witnesses_from_rolling_ball(*rolling_, target, r)) {
      return;
    }
    for (int widening = 0; widening < kWitnessWidenings; ++widening, slack *= 16) {
      witnesses_within(slack, r);
      if (r.witness_residual <= target) return;
    }
  }

  // The witnesses a face of the expansion gives (its best normal's, or the face of the same
  // surface the ray from the origin along that normal crosses): where it converged, the face lies
  // in the facet of A - B along the normal, and the origin's nearest point on it (its foot on the
  // face's plane, inside the face) combines the face's corners into points of both supporting
  // features whose difference is the separation along the normal. Where it stopped early (a
  // loose tolerance), the corners lie below the supporting planes, by the feature slack reported
  // (at least `slack`), and the difference is the face's plane distance, the upper bound, along
  // the normal. False, leaving `r` alone, when the difference is off `separation * normal` by
  // more than `target` (a foot outside the face, among others) or off `upper * normal` by more
  // than the gap (an answer's witnesses lie along its normal at its upper bound, to within the
  // gap).
  bool witnesses_from_face(const std::array<DifferencePoint, 3>& face, Scalar slack,
                           Scalar target, PenetrationBounds& r) const {
    std::array<OraclePoint, MinNormPoint::kCapacity> corners;
    for (int k = 0; k < 3; ++k) corners[k] = {face[k].w, face[k].ia, face[k].ib};
    std::array<OraclePoint, MinNormPoint::kCapacity> nearest;
    std::array<Scalar, MinNormPoint::kCapacity> alpha{};
    int size = 0;
    nearest_simplex_point(corners, 3, nearest, alpha, size);
    return witnesses_from_corners(nearest, alpha, size, slack, target, r);
  }

  // The same from the combination of the corners of face `from` of the surface and of the faces
  // around it (ExpandingPolytope::corners_around) whose B - A point is nearest to separation *
  // normal, by Wolfe's algorithm on them (witnesses_within's, on these points alone).
  bool witnesses_around_face(int from, Scalar slack, Scalar target,
                             PenetrationBounds& r) const {
    std::array<DifferencePoint, ExpandingPolytope::kMostNearbyCorners> corners;
    const int count = ws_.polytope.corners_around(from, corners);
    if (count == 0) return false;
    // Points of B - A (minus the corners) less separation * normal, as witnesses_within's.
    const Vector3 shift = separation_ * normal_;
    const auto oracle = [&](const Vector3& d) {
      // The corner least along d in B - A: highest along d in A - B.
      const int least = first_highest(count, [&](int k) { return d.dot(corners[k].w); });
      return OraclePoint{Vector3(-corners[least].w - shift), corners[least].ia,
                         corners[least].ib};
    };
    const MinNormPoint m = wolfe_min_norm(oracle, normal_, reach(), kWitnessIterations);
    Scalar total = 0;
    for (int k = 0; k < m.size; ++k) total += m.weights[k];
    if (!(total > 0)) return false;
    std::array<Scalar, MinNormPoint::kCapacity> alpha{};
    for (int k = 0; k < m.size; ++k) alpha[k] = m.weights[k] / total;
    return witnesses_from_corners(m.corral, alpha, m.size, slack, target, r);
  }

  // The witnesses that the points `nearest` of A - B (the first `size`, with weights `alpha`)
  // combine: as witnesses_from_face's, with its checks.
  bool witnesses_from_corners(const std::array<OraclePoint, MinNormPoint::kCapacity>& nearest,
                              const std::array<Scalar, MinNormPoint::kCapacity>& alpha, int size,
                              Scalar slack, Scalar target, PenetrationBounds& r) const {
    const Vector3& n = normal_;
    const Scalar top_a = top_height_a_;
    const Scalar bottom_b = top_height_b_;
    std::array<int, MinNormPoint::kCapacity> ia{};
    std::array<int, MinNormPoint::kCapacity> ib{};
    std::array<Scalar, MinNormPoint::kCapacity> weights{};
    Vector3 point_a = Vector3::Zero();
    Vector3 point_b = Vector3::Zero();
    for (int k = 0; k < size; ++k) {
      const int i = nearest[k].ia;
      const int j = nearest[k].ib;
      // Each corner's points are placed once, for their heights and the witnesses.
      const Vector3 x = a_.vertex(i);
      const Vector3 y = b_.vertex(j);
      // How far the corners fall short of the supporting planes: the features they lie on.
      const Scalar short_of = std::max(top_a - a_.height(i, x, n), b_.height(j, y, n) - bottom_b);
      if (!std::isfinite(short_of)) return false;
      slack = std::max(slack, short_of);
      ia[k] = i;
      ib[k] = j;
      weights[k] = alpha[k];
      point_a += alpha[k] * x;
      point_b += alpha[k] * y;
    }
    const Scalar residual = (point_b - point_a - separation_ * n).norm();
    if (!(residual <= target)) return false;
    if (!((point_b - point_a - upper() * n).norm() <= upper() - lower())) return false;
    r.point_a = point_a;
    r.point_b = point_b;
    r.weights_a = ConvexWeights(a_.size(), ia, weights, size);
    r.weights_b = ConvexWeights(b_.size(), ib, weights, size);
    r.witness_residual = residual;
    r.feature_slack = slack;
    return true;
  }

  // The rolling balls' witnesses (rolling_ball.hpp), each within the search's gap of its
  // supporting plane, and `-depth_lower * normal` apart; false, leaving `r` alone, when they are
  // off `separation * normal` by more than `target`.
  bool witnesses_from_rolling_ball(const RollingBallDepth& rolling, Scalar target,
                                   PenetrationBounds& r) const {
    const Vector3& n = normal_;
    const Scalar residual = (rolling.point_b - rolling.point_a - separation_ * n).norm();
    if (!(residual <= target)) return false;
    r.point_a = rolling.point_a;
    r.point_b = rolling.point_b;
    r.weights_a = ConvexWeights(a_.size(), rolling.index_a, rolling.weight_a, rolling.size_a);
    r.weights_b = ConvexWeights(b_.size(), rolling.index_b, rolling.weight_b, rolling.size_b);
    r.witness_residual = residual;
    r.feature_slack = std::max(top_height_a_ - n.dot(r.point_a), n.dot(r.point_b) - top_height_b_);
    return true;
  }

  // The witnesses of a cylinder's or a cone's side (use_side): each body's support along the
  // normal, or for a cylinder or a cone the segment of its side between the supports a little
  // off the normal, and the nearest points of the two once one is moved by the separation along
  // the normal. False, leaving `r` alone, where they are off `separation * normal` by more than
  // `target` (a face of a box along the normal, say, whose support is one of its corners).
  bool witnesses_from_side(Scalar target, PenetrationBounds& r) const {
    const Vector3& n = normal_;
    const auto segment = [](const std::array<int, 2>& ends, int top) {
      return ends[0] >= 0 ? ends : std::array<int, 2>{top, top};
    };
    const std::array<int, 2> ia = segment(side_ends_a_, top_a_);
    const std::array<int, 2> ib = segment(side_ends_b_, top_b_);
    const Vector3 shift = separation_ * n;
    const Vector3 a0 = a_.vertex(ia[0]);
    const Vector3 a1 = a_.vertex(ia[1]);
    const Vector3 b0 = b_.vertex(ib[0]);
    const Vector3 b1 = b_.vertex(ib[1]);
    Scalar s = 0;
    Scalar t = 0;
    nearest_on_segments(Vector3(a0 + shift), Vector3(a1 + shift), b0, b1, Scalar(1e-24), s, t);
    const Vector3 point_a = a0 + s * (a1 - a0);
    const Vector3 point_b = b0 + t * (b1 - b0);
    const Scalar residual = (point_b - point_a - shift).norm();
    if (!(residual <= target)) return false;
    if (!((point_b - point_a - upper() * n).norm() <= upper() - lower())) return false;
    r.point_a = point_a;
    r.point_b = point_b;
    const auto weights = [](const FramedBody& body, const std::array<int, 2>& ends, Scalar along) {
      const std::array<int, 4> index{ends[0], ends[1], 0, 0};
      const bool point = ends[0] == ends[1];
      const std::array<Scalar, 4> weight{point ? 1 : 1 - along, along, 0, 0};
      return ConvexWeights(body.size(), index, weight, point ? 1 : 2);
    };
    r.weights_a = weights(a_, ia, s);
    r.weights_b = weights(b_, ib, t);
    r.witness_residual = residual;
    r.feature_slack = std::max(top_height_a_ - n.dot(point_a), n.dot(point_b) - top_height_b_);
    return true;
  }

  void witnesses_within(Scalar slack, PenetrationBounds& r) {
    const Vector3& n = normal_;
    supporting_feature(a_, n, top_a_, slack, ws_.visited, ws_.feature_a);
    supporting_feature(b_, -n, top_b_, slack, ws_.visited, ws_.feature_b);
    const Vector3 shift = separation_ * n;
    const auto oracle = [&](const Vector3& d) {
      OraclePoint point = feature_support(a_, ws_.feature_a, b_, ws_.feature_b, d);
      point.p -= shift;
      return point;
    };
    const MinNormPoint m = wolfe_min_norm(oracle, n, reach(), kWitnessIterations);
    Scalar total = 0;
    for (int k = 0; k < m.size; ++k) total += m.weights[k];
    std::array<int, MinNormPoint::kCapacity> ia{};
    std::array<int, MinNormPoint::kCapacity> ib{};
    std::array<Scalar, MinNormPoint::kCapacity> weights{};
    r.point_a.setZero();
    r.point_b.setZero();
    for (int k = 0; k < m.size; ++k) {
      ia[k] = m.corral[k].ia;
      ib[k] = m.corral[k].ib;
      weights[k] = m.weights[k] / total;
      r.point_a += weights[k] * a_.vertex(ia[k]);
      r.point_b += weights[k] * b_.vertex(ib[k]);
    }
    r.weights_a = ConvexWeights(a_.size(), ia, weights, m.size);
    r.weights_b = ConvexWeights(b_.size(), ib, weights, m.size);
    r.witness_residual = (r.point_b - r.point_a - shift).norm();
    r.feature_slack = slack;
  }

  PenetrationBounds result() {
    PenetrationBounds r = bounds();
    witnesses(r);
    for (int k = 0; k < kWitnessResumes && !(r.witness_residual <= witness_target()) &&
                    (resume_rolling() || resume_expansion());
         ++k) {
      r = bounds();
      witnesses(r);
    }
    r.witnesses_along_normal = r.witness_residual <= witness_target();
    return r;
  }

  // The distance within which the witnesses' difference must lie of separation * normal.
  Scalar witness_target() const { return std::max(tolerance_, 4 * margin()); }

  // Where no witnesses lie along a curved pair's best normal: its polytope closes on the
  // surface a chord at a time, and a normal within the gap of the optimal separation may be off
  // the optimal one by enough to move the supporting features' nearest points apart by more than
  // the tolerance across it (census case robots-1-3295, a box's edge against a cylinder's rim,
  // the features 3.8 tolerances apart at a gap of a tenth of the tolerance; at a tolerance of
  // 1e-12 a tenth of overlapping cylinder, cone and box pairs, by up to 1,000). The expansion goes
  // on from its surface to a sixteenth of the gap, its normal and bound are measured as before,
  // and the witnesses are sought again. False where it cannot (no expansion ran, a pair of
  // polytopes, whose facets the expansion finds exactly, or a gap at the rounding's floor).
  bool resume_expansion() {
    if (!expanded_ || !(a_.curved() || b_.curved())) return false;
    const Scalar gap = (upper() - lower()) / 16;
    if (!(gap > floor() / 4)) return false;
    use_expansion(ws_.polytope.resume(a_, b_, gap, max_iterations_));
    finish();
    return true;
  }

  // The same where rolling balls proved the depth: their search on the cores stops at the gap,
  // and its normal may be off the optimal one by enough to leave the witnesses apart across it
  // (curved census at 1e-9, seed 32 case 75: two ellipsoids overlapping by 0.1, the witnesses
  // 1.5 tolerances off the normal at a gap of 0.96). The search goes on from the best normal to a
  // sixteenth of the gap. False where the balls did not prove the bound, or the gap is at the
  // rounding's floor.
  bool resume_rolling() {
    if (!rolling_ || !rolling_->proven || proof_ != PenetrationProof::rolling_ball) return false;
    const Scalar gap = (upper() - lower()) / 16;
    return gap > floor() / 4 && roll(normal_, gap);
  }

  // The bounds and normal as they stand, without witnesses.
  PenetrationBounds bounds() const {
    PenetrationBounds r;
    r.normal = normal_;
    r.separation = separation_;
    r.margin = margin();
    r.scan_shortfall = shortfall_a_ + shortfall_b_;
    r.lower = lower();
    r.upper = upper();
    r.proof = proven_upper_ <= r.upper ? proof_ : PenetrationProof::nearest_point;
    if (!std::isfinite(r.upper)) r.proof = PenetrationProof::none;
    r.iterations = iterations_;
    r.proven = r.upper - r.lower <= tolerance_;
    return r;
  }

  // The surface kept for this pair (null: none), read before and written after the solve.
  KeptSurface* surface_;
  // Whether an expansion ran, and the last one's result (its surface is the workspace's).
  bool expanded_ = false;
  bool expanded_from_kept_ = false;
  ExpansionResult expansion_;
  const FramedBody& a_;
  const FramedBody& b_;
  Scalar tolerance_;
  int max_iterations_;
  Workspace& ws_;
  Scalar coordinate_;
  // The bodies' scan shortfalls, which margin() adds at every step (FramedBody computes them
  // when asked).
  Scalar shortfall_a_;
  Scalar shortfall_b_;
  // Climb starts shared by the directions offered.
  int climb_a_ = -1;
  int climb_b_ = -1;
  // The climb starts are support_index's supports along candidate_ (of A, and of B along minus
  // it), found when the candidate was offered.
  bool climbs_along_candidate_ = false;
  Vector3 candidate_ = Vector3::UnitX();
  Scalar estimate_ = -kInfinity;
  Vector3 normal_ = Vector3::UnitX();
  Scalar separation_ = -kInfinity;
  int top_a_ = 0;
  int top_b_ = 0;
  // Their heights along normal_ (finish computes them for the separation; the witnesses read
  // them again).
  Scalar top_height_a_ = 0;
  Scalar top_height_b_ = 0;
  Scalar proven_upper_ = kInfinity;
  PenetrationProof proof_ = PenetrationProof::none;
  Scalar nearest_length_ = kInfinity;
  int iterations_ = 0;
  // Wolfe's last corral on B - A (none yet: size 0).
  MinNormPoint last_corral_;
  // The normal a side proved its bound along (use_side; NaN until then),
  // and the ends of each body's side segment along it (-1 for a body with no side).
  Vector3 side_normal_ = Vector3::Constant(std::numeric_limits<Scalar>::quiet_NaN());
  std::array<int, 2> side_ends_a_{-1, -1};
  std::array<int, 2> side_ends_b_{-1, -1};
  // The rolling balls' proof and witnesses, once use_rolling_ball looked for one.
  std::optional<RollingBallDepth> rolling_;
  // The expanding polytope's face along its best normal, `face_normal_` (NaN until it has one).
  std::array<DifferencePoint, 3> face_;
  Vector3 face_normal_ = Vector3::Constant(std::numeric_limits<Scalar>::quiet_NaN());
  // Its index on the workspace polytope's surface while that is the surface it is on (else -1),
  // and the live face there where the walks to the origin's foot start (near_best_face).
  int face_index_ = -1;
  int near_face_index_ = -1;
};

}  // namespace

PenetrationBounds penetration(const FramedBody& a, const FramedBody& b, const Vector3& hint,
                              const MinNormPoint* nearest, Scalar tolerance, int max_iterations,
                              KeptSurface* surface) {
  const Scalar coordinate = std::max(coordinate_bound(a), coordinate_bound(b));
  Solver solver(a, b, tolerance, max_iterations, coordinate, surface);
  return solver.solve(hint, nearest);
}

PenetrationBounds penetration(const VertexMatrix& a, const Hull& hull_a, const VertexMatrix& b,
                              const Hull& hull_b, const Vector3& hint, Scalar tolerance,
                              int max_iterations) {
  // Outside these scales products of coordinates overflow or underflow and the margins, which
  // assume neither, prove nothing; the caller normalises the frame first.
  const Scalar coordinate = largest_coordinate(a, b);
  if (coordinate > kLargestCoordinate || (coordinate > 0 && coordinate < kSmallestCoordinate)) {
    PenetrationBounds r;
    r.lower = -kInfinity;
    r.upper = kInfinity;
    r.weights_a = ConvexWeights(VectorX::Constant(a.rows(), Scalar(1) / a.rows()));
    r.weights_b = ConvexWeights(VectorX::Constant(b.rows(), Scalar(1) / b.rows()));
    r.point_a = a.transpose() * r.weights_a.dense();
    r.point_b = b.transpose() * r.weights_b.dense();
    return r;
  }
  const FramedBody framed_a(a, hull_a);
  const FramedBody framed_b(b, hull_b);
  Solver solver(framed_a, framed_b, tolerance, max_iterations, coordinate);
  return solver.solve(hint, nullptr);
}

}  // namespace swarmcollide::detail
