// The working frame of a query and the bodies placed in it; private to the library's sources.
#pragma once

#include <limits>
#include <memory>
#include <optional>

#include "normalise.hpp"
#include "support.hpp"
#include "support_cache.hpp"
#include "swarmcollide/geometry/convex_polyhedron.hpp"
#include "swarmcollide/geometry/pose.hpp"
#include "swarmcollide/problem/convex_weights.hpp"
#include "swarmcollide/types.hpp"

namespace swarmcollide::detail {

/// The exact type of a curved body's support function, where curved_supports.hpp has it.
enum class CurvedKind : unsigned char { other, cylinder, cone, ellipsoid };

/// A cylinder's or a cone's radius and half-length scaled into the frame, its axis (unit, from
/// the base towards the top or the apex) and the apex in the frame, for the creases of the
/// separation that NewtonDirection steps along: a cylinder's support point jumps between its
/// rims across the directions normal to its axis, a cone's between its apex and its base rim
/// across the directions normal to its slant lines.
struct CreaseShape {
  bool cone = false;
  Vector3 axis = Vector3::UnitZ();
  Vector3 apex = Vector3::Zero();
  Scalar radius = 0;
  Scalar half_length = 0;
};

/// Where a query computes: a world point `x` is `(x - centre) / 2^exponent` in the frame. The
/// frame is centred on the pair and scaled by a power of two (exactly) so that both bodies lie
/// in the unit ball. So an answer does not depend on the unit of length or on where the pair
/// is, nothing overflows or underflows, and rounding margins are absolute multiples of the
/// machine epsilon.
struct Frame {
  Vector3 centre = Vector3::Zero();
  int exponent = 0;
  /// The pair's size in frame units: the diameter of a ball around both bodies, in [1, 2) (0
  /// for two copies of one point). Tolerances are relative to it.
  Scalar size = 0;

  /// Inline: every answer turns its bounds and witnesses back with these (four calls out of line
  /// were 70 instructions of a batch row's distance).
  Scalar length_to_world(Scalar length) const { return times_power_of_two(length, exponent); }
  Vector3 point_to_world(const Vector3& p) const {
    return centre + times_power_of_two(p, exponent);
  }
};

/// Bound on the rounding error of a computed separation `min_j n.y_j - max_i n.x_i` along a
/// rounded unit vector `n` (`|n| = 1` to 4 roundoffs), as a separation along `n / |n|`, for
/// coordinates of magnitude at most `coordinate`: each dot product is within `3.01 u |n| |x|
/// <= 5.3 u coordinate` (|x| <= sqrt(3) coordinate), the difference adds `u |s| <= 3.5 u
/// coordinate` and dividing by `|n|` another `4 u |s| <= 14 u coordinate`; 28 u in all, doubled.
/// The coordinates are those the dot products are computed from, and the supports must be the
/// largest of those dot products (`FramedBody::exact_support_index`).
inline Scalar separation_margin(Scalar coordinate) { return 64 * kRoundoff * coordinate; }

/// A bound on the rounding of a separation `n . (y - x)` or of a distance `|y - x|` computed from
/// frame coordinates (each of magnitude at most 1), in frame units. Each coordinate carries a
/// few units of rounding from the translation, the scaling (exact) and the rotation, and a dot
/// product a few more; 128 roundoffs, twice `separation_margin(1)`, cover them with room to
/// spare.
inline constexpr Scalar kFrameRounding = 128 * kRoundoff;

/// A body under a pose, seen in a frame: point i is at `rotation * (x_i - c) / 2^e + offset`,
/// where c is the centre of the body's own bounding box. Support queries are answered in the
/// body's own frame (`rotation^T d`), so moving a body never touches its points or its hull.
/// Its points are the body's hull points (ConvexPolyhedron::hull_points), numbered among
/// themselves: the exact solvers read nothing else. The paper's methods, whose model (2) is over
/// every given point, read those through `given_points`, and `given_weights` turns weights over
/// the hull points into weights over the given points.
///
/// The exact paths ask their support points of it, of two kinds: `support_index` (a scan of small
/// bodies, a hill climb on large ones, comparing heights in the body's own coordinates centred on
/// its box, so rounded relative to the body's size) for searches and the separations of lower
/// bounds, and `exact_support_index` (a scan of the heights computed in the frame) for the
/// certified penetration solver, whose margins assume the very maximum of the frame heights.
///
/// A curved body (ConvexPolyhedron::curved) answers its support points from its support function:
/// each new one is appended to the body's points for this query (a cache that starts with the
/// body's points, all on its surface) and its index returned, so the solvers, which trade in
/// point indices, read it as any other point. Its points are points of the body (the support
/// function pulls them inside); the heights of its support points fall short of the support value
/// by at most its share of `FramedPair::support_error` beyond `scan_shortfall()`. It has no hull
/// the solvers may read: the parts that walk a hull or enumerate its faces check `curved()`.
class FramedBody {
 public:
  /// `world_centre` is where the centre of the body's box lands under the pose,
  /// `pose.rotation * body.bounds().centre + pose.translation`, as frame_pair computed it to
  /// centre the frame; `rotated` is `!pose.has_identity_rotation()`, which frame_pair knows too;
  /// `other` is the pair's other body (a curved body framed against a single point takes no
  /// cache of support points until it finds a new one). Defined inline in framed_body.cpp, where
  /// its caller (the framing of a pair) is.
  FramedBody(const ConvexPolyhedron& body, const Pose& pose, bool rotated,
             const Vector3& world_centre, const Frame& frame, const ConvexPolyhedron& other);
  /// Places the body as the constructor does with these arguments, for a new query: what depends
  /// on the body alone (its points, hull, columns, support function) is kept, and a curved body's
  /// support points start again from the body's own. Only for a body framed from a
  /// ConvexPolyhedron. A batch re-places the bodies of its last row when they are the next row's
  /// (KeptPair). Defined inline in framed_body.cpp, where its callers are.
  void place(const Pose& pose, bool rotated, const Vector3& world_centre, const Frame& frame,
             const ConvexPolyhedron& other);
  /// Points already in the frame, with their hull (`points` of a framed body, for a solver that
  /// reads every point many times): point i is row i as it is, and support queries compare these
  /// coordinates themselves. `body()` is not available; `points` and `hull` must outlive it.
  FramedBody(const VertexMatrix& points, const Hull& hull);
  /// A copy shares the curved body's support points with `body`: the points either finds are
  /// the other's too (a copy made before the first new point takes the cache both add to).
  FramedBody(const FramedBody& body);
  FramedBody(FramedBody&&) = default;
  FramedBody& operator=(const FramedBody&) = delete;
  FramedBody& operator=(FramedBody&&) = default;

  /// True for a curved body: its points are the support points found so far in this query.
  bool curved() const { return curved_ != nullptr; }
  /// Adds `frame_point`, a point of this curved body given in the frame, to its support points:
  /// the nearest surface point a closed-form depth names (curved_depth.hpp), which the witnesses
  /// then find on the supporting feature, or a rolling ball's witness (rolling_ball.hpp). Only for
  /// a curved body. Returns its number.
  int add_point(const Vector3& frame_point) const;
  /// The body framed; only for a body framed from a ConvexPolyhedron.
  const ConvexPolyhedron& body() const { return *body_; }
  /// Number of points (the hull points of a ConvexPolyhedron; a curved body's support points so
  /// far).
  int size() const { return curved_ ? found_->count() : static_cast<int>(vertices_->rows()); }
  /// The hull, with indices among the points.
  const Hull& hull() const { return hull_ ? *hull_ : body_->hull(); }
  /// The points in the body's own frame, centred on its box and not yet scaled (a curved body's
  /// first `size()` rows; the rows past them are unused).
  const VertexMatrix& local_points() const { return *vertices_; }
  /// Number of points the body was given (the `k` of model (2)).
  int given_size() const { return given_ ? body_->size() : size(); }
  /// Every given point in the frame, one per row, into `out` (resized): the paper's methods
  /// solve model (2) over these.
  void given_points(VertexMatrix& out) const;
  /// `weights` over the given points: weights over the points (`size()` of them) are spread to
  /// the given points they are (zero elsewhere); weights already over the given points pass.
  ConvexWeights given_weights(ConvexWeights weights) const;

  /// Point i of the body in the frame.
  Vector3 vertex(int i) const { return placed(vertices_->row(i).transpose()); }
  /// `vertex(0)` of a body of one point (a ball's core): the point is the centre of its own box,
  /// so its own-frame coordinates are zero and its place is the offset (its rotation and scaling
  /// make zeros; but for the sign of a zero coordinate, the same point), without the placement's
  /// products (some 40 instructions of a ball's closed form). A point whose box centre rounded
  /// off it (subnormal coordinates) is placed.
  Vector3 single_vertex() const {
    const VertexMatrix& x = *vertices_;
    return x(0, 0) == 0 && x(0, 1) == 0 && x(0, 2) == 0 ? offset_ : vertex(0);
  }
  /// `d . vertex(i)`, as `exact_support_index` compares it.
  Scalar height(int i, const Vector3& d) const {
    return in_frame_ ? point_height(*vertices_, i, d) : vertex(i).dot(d);
  }
  /// `height(i, d)` for a caller that has placed point i already (`placed` is `vertex(i)`): the
  /// same value, without placing the point a second time.
  Scalar height(int i, const Vector3& placed, const Vector3& d) const {
    return in_frame_ ? point_height(*vertices_, i, d) : placed.dot(d);
  }
  /// A frame direction in the body's own frame (support points do not depend on the scale).
  Vector3 local_direction(const Vector3& d) const {
    return rotated_ ? Vector3(rotation_.transpose() * d) : d;
  }
  /// Index of a point farthest along frame direction `d`, by scanning the points in the body's
  /// own frame (see ConvexPolyhedron::support_index).
  int support_index(const Vector3& d) const {
    if (curved_) return curved_support(local_direction(d));
    if (columns_) return columns_->scan(local_direction(d));
    return scan_support(*vertices_, local_direction(d));
  }
  /// The same for a direction already in the body's own frame.
  int local_support_index(const Vector3& local) const {
    if (curved_) return curved_support(local);
    if (columns_) return columns_->scan(local);
    return scan_support(*vertices_, local);
  }
  /// The same, climbing the hull from `start` on large bodies (as `support_index(d, start)`).
  int local_support_index(const Vector3& local, int start) const {
    if (curved_ || size() <= kHillClimbingThreshold) return local_support_index(local);
    return climb_support(*vertices_, hull(), local, start);
  }
  /// The point `local_points().row(local_support_index(local))` of a curved body (`local` a
  /// direction in its own frame), the same coordinates (-0 as +0), without numbering it among the
  /// body's points: for a closed form that reports no weights over the shape
  /// (point_against_curved).
  Vector3 curved_local_support(const Vector3& local) const;
  /// The exact type of a curved body's support function (CurvedKind::other for a polyhedron).
  CurvedKind curved_kind() const { return curved_kind_; }
  /// A point of the body's own frame, centred on its box, placed in the frame as `vertex()`
  /// places the body's points.
  Vector3 placed_point(const Vector3& centred) const { return placed(centred); }
  /// `vertex(support_index(d, index))` for a finite `d`, that index into `index` (a large body
  /// climbs from it): the same point, with a curved body's support and a small body's scan
  /// always inline, and a curved body's point placed as it is found rather than read back: for
  /// the curved pairs' searches (curved_search.cpp), whose oracles ask two per step (a curved
  /// support out of line cost 16 of its 117 instructions in the call and its dispatch). Defined
  /// in framed_curved_support.hpp, which its callers include.
  inline Vector3 inline_support(const Vector3& d, int& index) const;
  /// Adds to `form` the quadratic form of the derivative K of the body's support point (in the
  /// frame) with respect to the unit frame direction `d`, where the point moves smoothly with
  /// it, on the frame vectors `u` and `v`: (u^T K u, u^T K v, v^T K v). K is zero for a
  /// polyhedron (a vertex stays the support near most directions), a rim's or an ellipsoid's
  /// curvature for a curved body. False where no such model holds (another kind of support
  /// function, a direction along a cylinder's or a cone's axis). Defined in
  /// framed_curved_support.hpp.
  inline bool add_support_curvature(const Vector3& d, const Vector3& u, const Vector3& v,
                                    Vector3& form) const;
  /// The shape of the crease that a cylinder's or a cone's support point makes in the
  /// separation, where it jumps between two parts of the surface (CreaseShape), in the frame.
  /// False for other bodies. Defined in framed_curved_support.hpp.
  inline bool crease_shape(CreaseShape& out) const;
  /// True for a small polyhedron whose support points are scans of its points by coordinate
  /// (`support_index` takes them from any start): `scanned_support_index` answers it.
  bool scanned() const { return columns_ != nullptr; }
  /// Scans by rows from now on (`scanned()` false): the same support indices (the columns' scans
  /// are the rows' bit for bit), read from the one copy of the points that placing them reads.
  void scan_rows() { columns_ = nullptr; }
  /// `support_index(d)` of a `scanned()` body, the same index, always inline: a search's oracle
  /// on a small pair asks two per step, where the call out of line and its tests of the body's
  /// kind were a sixth of each scan (swarmcollide-thread-scaling count distance, 8 vertices).
  [[gnu::always_inline]] int scanned_support_index(const Vector3& d) const {
    return columns_->inline_scan(local_direction(d));
  }
  /// The same where the caller knows whether the body has at most kRegisterColumns points
  /// (PointColumns::sized_scan).
  template <bool few>
  [[gnu::always_inline]] int sized_support_index(const Vector3& d) const {
    return columns_->sized_scan<few>(local_direction(d));
  }
  /// `local_support_index(local)` of a `scanned()` body (`local` a direction in its own frame),
  /// the same index, always inline: the fcl method recovers the bodies' points of FCL's simplex
  /// by eight such scans, where the tests of the body's kind were a fifth of each.
  [[gnu::always_inline]] int scanned_local_support_index(const Vector3& local) const {
    return columns_->inline_scan(local);
  }
  /// The same, climbing the hull from `start` when the body has more than
  /// `kHillClimbingThreshold` points (see ConvexPolyhedron::support_index): for searches, whose
  /// successive directions are close.
  int support_index(const Vector3& d, int start) const {
    if (curved_ || size() <= kHillClimbingThreshold) return support_index(d);
    return climb_support(*vertices_, hull(), local_direction(d), start);
  }
  /// Index of a point maximising `height(i, d)` (the first one on ties), by scanning every point
  /// in the frame. `support_index` may fall short of it: a climb can stop early on heights that
  /// rounding made equal, and a scan in the body's own frame rounds the rotated direction and
  /// the heights differently (by a few roundoffs of the body's size).
  int exact_support_index(const Vector3& d) const {
    if (curved_) return curved_support(local_direction(d));
    if (in_frame_) return scan_support(*vertices_, d);
    return first_highest(size(), [&](int i) { return vertex(i).dot(d); });
  }
  /// How far `height(support_index(d), d)` may fall below the greatest `height(i, d)` for a
  /// direction `|d| <= 1 + 8u`: zero for points given in the frame (the scan compares those
  /// heights themselves); for a placed body, whose scan compares heights in its own frame, a
  /// multiple of the roundoff and of the reach `|offset| + 2^-e radius` (see framed_body.cpp).
  Scalar scan_shortfall() const;
  Vector3 support(const Vector3& d) const { return vertex(support_index(d)); }
  /// Every point in the frame, one per row, into `out` (resized), for solvers that read each
  /// point many times.
  void points(VertexMatrix& out) const;

  /// The body's rotation into the frame, and where the centre of its box lands in the frame.
  const Matrix3& rotation() const { return rotation_; }
  bool rotated() const { return rotated_; }
  const Vector3& offset() const { return offset_; }
  /// Local points `x` are `(x - box centre) / 2^exponent()` before the rotation.
  int exponent() const { return exponent_; }

 private:
  // `use(point)` of the curved body's support point along `local`, in its own frame
  // (framed_curved_support.hpp).
  template <bool kFinite = false, typename Use>
  auto use_curved_support(const Vector3& local, const Use& use) const;
  // The index of the curved body's support point along `local` (its own frame), appended to the
  // points unless it is one of them already.
  int curved_support(const Vector3& local) const;
  // The same, always inline (framed_curved_support.hpp).
  inline int inline_curved_support(const Vector3& local) const;
  // The pose's part of place (the rotation, the scale, the offset).
  void place_pose(const Pose& pose, bool rotated, const Vector3& world_centre,
                  const Frame& frame);
  // A curved body's support points for a new framing against `other`:
  // inline for a pair's framing, out of line for a kept pair's (restart_support_points).
  void start_support_points(const ConvexPolyhedron& other);
  void restart_support_points(const ConvexPolyhedron& other);
  // The number of `point` (in the body's own frame) among the curved body's support points,
  // added when it is new: to the body's own points (read until then) or to the cache this
  // framing took for its first new point (add_to_own_cache).
  int add_support_point(const Vector3& point) const {
    return found_->add(point, [this](const Vector3& p, std::size_t slot) {
      return add_to_own_cache(p, slot);
    });
  }
  // The same for a point without -0 coordinates (SupportCache::add_without_negative_zeros).
  int add_support_point_without_negative_zeros(const Vector3& point) const {
    return found_->add_without_negative_zeros(point, [this](const Vector3& p, std::size_t slot) {
      return add_to_own_cache(p, slot);
    });
  }
  // The first new support point `p` of a body that reads its body's own (sealed) points, `slot`
  // its empty slot there (SupportCache::add_new): a cache of the thread's pool started as those
  // takes it, and every later one (framed_body.cpp).
  int add_to_own_cache(const Vector3& p, std::size_t slot) const;
  // A cache of the thread's pool, started as the body's own (sealed) points, in their place.
  void own_support_points() const;
  // The support points, taken into a cache of their own first when they are the body's own (a
  // copy then shares that cache with this body).
  const VertexMatrix* shared_points() const;
  Vector3 scaled(const Vector3& v) const { return v * scale_high_ * scale_low_; }
  // A point of the body's own frame, centred on its box, in the frame.
  Vector3 placed(const Vector3& centred) const {
    const Vector3 local = scaled(centred);
    return rotated_ ? Vector3(rotation_ * local + offset_) : Vector3(local + offset_);
  }

  // vertices_: the points the supports read, in the body's own frame, centred on its box (the
  // body's centred_vertices, or its hull points' when some given points lie inside; given_ then
  // holds those hull points). hull_: the hull a large body's climbs read, held rather than asked
  // of the body at every climb; null for a small body, scanned whole (hull() then asks the body,
  // which builds it lazily).
  const ConvexPolyhedron* body_;
  // A curved body's until its first new support point: its body's own, then its cache's.
  mutable const VertexMatrix* vertices_;
  const Hull* hull_;
  const HullPoints* given_;
  // Points given in the frame: the placement below is the identity, which heights and exact
  // scans skip (they read every point). vertex() applies it all the same: a test there would slow
  // every framed query's loops for the few penetration calls it would spare.
  bool in_frame_;
  Matrix3 rotation_;
  bool rotated_;
  // The exact type of a curved body's support function when it is one of shapes.hpp's
  // (curved_supports.hpp), whose support curved_support calls without the virtual call. Beside
  // rotated_, in its padding: a member of its own made every polytope query 4 instructions
  // longer (its store, the larger pair).
  CurvedKind curved_kind_ = CurvedKind::other;
  Vector3 offset_;
  // No frame's exponent until the body is placed (place() keeps the scale of an unchanged one).
  int exponent_ = std::numeric_limits<int>::min();
  // 2^-exponent as two factors, each representable even for the most extreme exponents.
  Scalar scale_high_;
  Scalar scale_low_;
  // A curved body's support function and its support points so far in its own frame (centred on
  // its box; `vertices_` points to their rows); their support error is the pair's
  // (FramedPair::support_error), which pair_frame computes. Framed against a single
  // point, the body reads its body's own sealed cache until its first new point takes a cache of
  // the thread's pool (add_to_own_cache): a ball's closed form against a cylinder, which finds
  // none, takes none (taking, resetting and giving one back were 135 of its 2,283 instructions).
  const SupportFunction* curved_ = nullptr;
  mutable SharedSupportCache found_;
  // A small polyhedron's points (`vertices_`) by coordinate (ConvexPolyhedron::centred_columns),
  // for support_index's scans; null for larger bodies (climbed), curved bodies and points given in
  // the frame.
  const PointColumns* columns_ = nullptr;
};

/// A bound on the absolute coordinates of a placed body's points, without reading them: the
/// centre of its box in the frame plus its radius, rounded up (separation_margin's argument).
/// times_power_of_two is std::ldexp's value here, without the library call: it rounds once unless
/// its factor splits (|exponent| > 1000), where the partial product stays a normal double for
/// every radius whose scaled value is not zero either way.
inline Scalar coordinate_bound(const FramedBody& body) {
  const Scalar radius = times_power_of_two(body.body().bounds().radius, -body.exponent());
  return (body.offset().cwiseAbs().maxCoeff() + radius) * (1 + 16 * kRoundoff);
}

/// Two bodies in their common frame, with the query's tolerance in frame units.
struct FramedPair {
  Frame frame;
  FramedBody a;
  FramedBody b;
  /// Absolute tolerance in the frame: the relative tolerance times `frame.size`.
  Scalar tolerance;
  /// The bodies' rounding radii in the frame, A's and B's (0 for polyhedra): the solvers answer
  /// on the cores, and queries/rounded.hpp turns their bounds into the rounded bodies'.
  Scalar radius_a = 0;
  Scalar radius_b = 0;
  /// What the support points of curved bodies may fall short by along a unit frame direction,
  /// beyond `scan_shortfall()`, A's and B's added (0 for polyhedra): every lower bound of the
  /// pair loses it.
  Scalar support_error = 0;
  /// True when a radius or the support error is not zero: the solvers' bounds then go through
  /// queries/rounded.hpp (one test in every stop test, for two polyhedra).
  bool adjusted = false;
};

/// The frame of a pair and the bodies in it. Throws std::invalid_argument for an invalid pose
/// (see validate_pose), or when a posed body's position, or the pair's extent, is beyond the
/// double range (distances between such bodies are not representable).
FramedPair frame_pair(const ConvexPolyhedron& a, const Pose& pose_a, const ConvexPolyhedron& b,
                      const Pose& pose_b, Scalar relative_tolerance);

/// frame_pair for poses the caller has already validated: a scene validates each pose once, when
/// it is set, not once per candidate pair and frame. Still throws for positions or extents beyond
/// the double range.
FramedPair frame_validated_pair(const ConvexPolyhedron& a, const Pose& pose_a,
                                const ConvexPolyhedron& b, const Pose& pose_b,
                                Scalar relative_tolerance);

/// frame_validated_pair with the poses' identity tests made by the caller: `turned_a` is
/// `!pose_a.has_identity_rotation()`, and `turned_b` B's. A batch row knows them from validating
/// its poses (valid_pose), and a side without poses is the identity without a test.
FramedPair frame_turned_pair(const ConvexPolyhedron& a, const Pose& pose_a, bool turned_a,
                             const ConvexPolyhedron& b, const Pose& pose_b, bool turned_b,
                             Scalar relative_tolerance);

/// The framed pair of a batch's rows, kept from one row to the next (one per thread): a row of
/// the last row's bodies re-places them (FramedBody::place), which leaves the pair as
/// frame_turned_pair would make it without building one (a third of what framing an 8-vertex
/// pair cost); other bodies are framed anew.
class KeptPair {
 public:
  /// frame_turned_pair's pair of these bodies under these poses, until the next call. Throws as
  /// frame_turned_pair does.
  const FramedPair& frame(const ConvexPolyhedron& a, const Pose& pose_a, bool turned_a,
                          const ConvexPolyhedron& b, const Pose& pose_b, bool turned_b,
                          Scalar relative_tolerance);

 private:
  std::optional<FramedPair> pair_;
};

}  // namespace swarmcollide::detail
