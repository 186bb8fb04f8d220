// An expanding polytope inside the Minkowski difference A - B that proves a depth; private.
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <optional>
#include <vector>

#include "../geometry/framed_body.hpp"
#include "swarmcollide/types.hpp"

namespace swarmcollide::detail {

/// A point of the Minkowski difference `A - B`: `x_ia - y_ib`, as computed.
struct DifferencePoint {
  Vector3 w = Vector3::Zero();
  int ia = -1;
  int ib = -1;
};

/// An expansion's last surface by the bodies' point indices, kept to start a later one at other
/// poses (a scene's pair in contact, frame after frame): each corner is placed again from its
/// indices and each face proven oriented again from them, so what was kept is only where the
/// expansion starts, never part of a proof. Empty when nothing is kept.
struct KeptSurface {
  /// (index in A, index in B) of each corner.
  std::vector<std::array<int, 2>> corners;
  /// Each face's corners (counter-clockwise seen from outside), the face across each edge k
  /// (corner k to k + 1) and which edge of that face it is.
  struct Face {
    std::array<std::uint8_t, 3> v;
    std::array<std::uint8_t, 3> adj;
    std::array<std::uint8_t, 3> adj_edge;
  };
  std::vector<Face> faces;
  void clear() {
    corners.clear();
    faces.clear();
  }
};

/// What the expansion proved and found.
struct ExpansionResult {
  /// The final surface, or one before a step that lowered the bound, passed `verify`:
  /// `depth_lower` is proven (sd <= -depth_lower), the best of theirs.
  bool verified = false;
  /// Proven `depth >= depth_lower >= 0` when `verified` (the origin is then in `A - B`).
  Scalar depth_lower = 0;
  /// The direction of least support `h(n) = max_i n.x_i - min_j n.y_j` met, i.e. of largest
  /// separation `s(n) = -h(n)`, from hill-climbed supports (not proven); minus infinity when the
  /// expansion met none (its start was too flat to make a face).
  Vector3 best_normal = Vector3::UnitX();
  Scalar best_separation = -std::numeric_limits<Scalar>::infinity();
  /// Support indices at `best_normal`, to warm-start later climbs.
  int best_ia = -1;
  int best_ib = -1;
  /// The corners of the face whose normal is `best_normal`: where the expansion converged, the
  /// origin's foot on it combines them into witnesses.
  std::array<DifferencePoint, 3> best_face;
  /// That face's index on the surface (replaced since, perhaps: see near_best_face).
  int best_face_index = -1;
  /// A live face of the final surface at that face: itself, or where the expansion replaced it,
  /// a face at the corner its support point became (-1 when there is none). The best normal's
  /// face is replaced where the expansion stopped on another face's gap (a fifth of a cylinder
  /// pair's runs): face_crossed and corners_around start here.
  int near_best_face = -1;
  /// That face's `distance` (the least of `best_normal . w` over its corners).
  Scalar best_face_distance = -std::numeric_limits<Scalar>::infinity();
  /// The gap between the least support met, `-best_separation`, and the nearest face's plane
  /// fell to the requested one.
  bool converged = false;
  int iterations = 0;
};

/// EPA (the expanding polytope algorithm) from a tetrahedron of points of `A - B` around the
/// origin, made safe by a verifier rather than by trusting each step.
///
/// The surface is kept as oriented triangles with their neighbours; each step takes the triangle
/// whose plane is nearest the origin, finds the support point of `A - B` along its normal, and
/// replaces the triangles that point sees by a cone from it, but only if every new triangle is
/// provably oriented with the origin inside (otherwise the expansion stops where it is). At the
/// end `verify` checks the surface's topology from scratch: every triangle's edges are matched by
/// reversed edges of its neighbours (a closed 2-cycle); every triangle had `det(v0, v1, v2)` above
/// its rounding bound when it was made (and a triangle never changes), so the radial projection
/// from the origin covers the sphere with a positive degree, every ray from the origin meets a
/// triangle, and the triangles' vertices being points of `A - B`, the ball of radius `min`
/// (triangle plane distance) lies in `A - B`. A step whose new triangles dip below the nearest
/// one (see expand) verifies the surface before it the same way, and the better of the two
/// bounds is the answer.
class ExpandingPolytope {
 public:
  /// Expands from the tetrahedron `start` until the least support met along a triangle's normal
  /// is within `stop_gap` of the nearest triangle's plane, the expansion cannot proceed safely,
  /// or after `max_iterations` steps; then verifies (unless `verify_end` is false, for a run to
  /// be resumed: it then proves only a bound a step that dipped kept). Returns verified = false
  /// when the tetrahedron does not enclose the origin provably.
  ExpansionResult run(const FramedBody& a, const FramedBody& b,
                      const std::array<DifferencePoint, 4>& start, Scalar stop_gap,
                      int max_iterations, bool verify_end = true);
  /// The same from the surface `kept` at the bodies' present poses: `started` is false (and
  /// nothing run) when a corner's indices are out of range or a face cannot be proven oriented
  /// with the origin inside there.
  ExpansionResult run(const FramedBody& a, const FramedBody& b, const KeptSurface& kept,
                      Scalar stop_gap, int max_iterations, bool& started);
  /// Goes on expanding the last run's surface, as it was left, until the gap falls to
  /// `stop_gap` (smaller than that run's), with what a run returns: a curved pair's polytope
  /// closes on the surface a chord at a time, and its best normal may be too far off the optimal
  /// one for the witnesses along it (Solver::witnesses in penetration.cpp). Where that run made
  /// no surface (a start too flat, or a kept surface not started), nothing: what a run that
  /// made no face returns.
  ExpansionResult resume(const FramedBody& a, const FramedBody& b, Scalar stop_gap,
                         int max_iterations);
  /// The last run's surface into `out` when it was verified and has at most `most_corners`
  /// corners; `out` emptied otherwise.
  void keep(const ExpansionResult& last, int most_corners, KeptSurface& out);
  /// The face of the last run's surface that the ray from the origin along `d` crosses, its
  /// corners into `corners`: found by walking from face `from` across the edge the ray passes
  /// beyond, for at most `kMostCrossingSteps` faces. A resting contact's facet of `A - B` is
  /// split into several faces, and the one its best normal came from need not hold the origin's
  /// foot on it, which another of them does. -1 when the walk meets a face that is not live or
  /// does not end; nothing here is proven (the caller checks what it makes of the corners).
  int face_crossed(int from, const Vector3& d, std::array<DifferencePoint, 3>& corners) const;
  /// The most corners corners_around gives: a face's three, one more for each of the three faces
  /// across its edges and for each of the six across theirs.
  static constexpr int kMostNearbyCorners = 12;
  /// The corners of face `from` of the last run's surface and of the live faces up to two edges
  /// away from it, each once, into `corners`; their number (0 when `from` is not a live face).
  /// On a curved pair's surface the faces where the expansion converged are a fine patch of
  /// slightly tilted faces, and the origin's foot may lie just beyond the one the best normal
  /// came from: a combination of these corners reaches it (nothing here is proven either).
  int corners_around(int from, std::array<DifferencePoint, kMostNearbyCorners>& corners) const;
  /// Whether the last run's surface, as it stands, is closed as `verify` proves it, and every
  /// live face whose proven plane distance `low` is below `depth` passes `test(normal, low, w0,
  /// w1, w2)` (its outward unit normal, that bound, its corners). Every ray from the origin
  /// crosses a face, whose points are points of `A - B` at least `low` along its normal: along a
  /// direction u through a face, `A - B` reaches at least `low / (u . normal)`; the directions
  /// where that is short of `depth` must be bounded otherwise (cylinder_side.hpp).
  template <typename Test>
  bool nearer_faces_pass(Scalar depth, const Test& test) const {
    Scalar closest = 0;
    if (!closed_) closed_ = verify(closest);
    if (!*closed_) return false;
    for (int i = 0; i < face_count_; ++i) {
      const Face& f = faces_[i];
      if (!f.alive || f.low * (1 - 8 * kRoundoff) >= depth) continue;
      if (!test(f.normal, f.low, vertices_[f.v[0]].w, vertices_[f.v[1]].w, vertices_[f.v[2]].w)) {
        return false;
      }
    }
    return true;
  }

 private:
  // The expansion from the surface in vertices_, faces_ and heap_.
  // `placed`: points_a_ and points_b_ already hold every vertex's points.
  ExpansionResult expand_surface(const FramedBody& a, const FramedBody& b, Scalar stop_gap,
                                 int max_iterations, bool placed, bool verify_end = true);
  struct Face {
    std::array<int, 3> v;         // vertices, counter-clockwise seen from outside
    std::array<int, 3> adj;       // the face across edge k (v[k] -> v[k + 1])
    std::array<int, 3> adj_edge;  // which edge of that face it is
    Vector3 normal;               // unit, outward
    Scalar distance;              // min_k normal . v[k]: a lower bound of the plane's distance
    Scalar top;                   // max_k normal . v[k]: a point beyond it sees the face
    Scalar low;                   // `distance` less its rounding: every point of it is farther
    bool alive;
  };

  bool make_face(int v0, int v1, int v2, Face& face) const;
  // make_face's normal is the cross product of the edges from the first corner, whose rounding
  // is about u |e1| |e2| whatever the area: on a sliver (next to the flat facets of curved
  // bodies, most) it tilts, the corners' heights along it spread far beyond rounding, the face
  // looks lower than it is, and a support point at its height cannot expand it: the expansion
  // stopped there, short of tight tolerances (8 of 11 cylinder, cone and box pairs that stayed
  // unproven at 1e-12). Where the corners spread more than rounding would, this takes the normal
  // from the edges at the corner opposite the longest one (the least product, the most accurate
  // normal) if the corners lie flatter along it, and the face's heights and bound with it
  // (`low` is a bound along any unit vector); true when it did. The face's orientation, proven
  // from its corners alone, does not change.
  bool flatten(int f);
  // Replaces the faces vertex `added` sees, from `closest`, by its cone. The new faces farther
  // than `ceiling` (the least support met, which bounds the depth from above) are left out of
  // the heap: the nearest face is never one of them while the expansion goes on (see
  // expand_surface), and on curved pairs more than half of the new faces are.
  bool expand(int closest, int added, Scalar ceiling);
  // The heap of every live face, for when the faces left out of it (see expand) may be the
  // nearest.
  void heap_live_faces();
  // The new faces from vertex `added` to the horizon of the faces in `visible_` (those marked
  // with stamp_ in seen_stamp_), made in faces_ after the first face_count_, with horizon_ and
  // start_face_: kConeMade; kConeBroken where the horizon is not one loop through distinct
  // vertices; else the face across a horizon edge whose new triangle could not be proven
  // oriented.
  int cone(int added);
  static constexpr int kConeMade = -1;
  static constexpr int kConeBroken = -2;
  // Faces that may join the visible ones in one expansion (see expand).
  static constexpr int kWidenings = 16;
  // Faces face_crossed walks across: a facet split by a few expansions has a few faces.
  static constexpr int kMostCrossingSteps = 8;
  // Whether live face i's neighbours across its edges are live faces that name it back across
  // the same edge, reversed: the closed surface verify proves and the expansion walks.
  bool linked(int i) const;
  bool verify(Scalar& depth_lower) const;

  std::vector<DifferencePoint> vertices_;
  std::vector<Scalar> norms_;  // |w| of each vertex, for the rounding bounds
  // Each vertex's points of A and of B in the frame (x_ia and y_ib), kept where a climbed body's
  // heights pick the climbs' starts (see run): placing a corner's point again at every step cost
  // more than the step's bookkeeping. Empty for a body that is not climbed or whose points were
  // given in the frame (its heights read them as given).
  std::vector<Vector3> points_a_;
  std::vector<Vector3> points_b_;
  // The surface's faces, replaced ones included, are the first face_count_; the rest is room for
  // the next cone, made in place.
  std::vector<Face> faces_;
  int face_count_ = 0;
  std::vector<std::pair<Scalar, int>> heap_;  // (distance, face), a min-heap with stale entries
  std::vector<int> stack_;
  std::vector<int> visible_;
  std::vector<std::pair<int, int>> horizon_;  // (face, edge) of visible faces on the horizon
  std::vector<int> seen_stamp_;
  std::vector<int> start_stamp_;  // per vertex: vertex_stamp_ of the cone whose horizon starts there
  std::vector<int> start_face_;   // per vertex: the new face whose horizon edge starts there
  int stamp_ = 0;
  int vertex_stamp_ = 0;
  // Whether the last run's surface as it stands passed `verify` (none: not verified yet), from
  // the run's end or the first nearer_faces_pass after it (the surface stands until the next run).
  mutable std::optional<bool> closed_;
  // The best depth bound of a surface verified before a step that dipped below it (see expand);
  // negative when none was.
  Scalar kept_depth_ = -1;
  // The surface the last run started from, when it was a kept one (keep() need not rewrite it
  // where the run added nothing).
  const KeptSurface* started_from_ = nullptr;
};

}  // namespace swarmcollide::detail
