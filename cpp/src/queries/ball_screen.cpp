#include "ball_screen.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "../geometry/framed_body.hpp"
#include "../geometry/hull_graph.hpp"
#include "../geometry/normalise.hpp"

namespace swarmcollide::detail {

namespace {

// Shewchuk's bound on the rounding of orient3d's determinant computed from rounded differences,
// relative to its permanent (o3derrboundA = (7 + 56 u) u, rounded up to 8 u), as hull_points.cpp
// uses it; the absolute term covers products that underflow.
constexpr Scalar kOrientationBound = 8 * kRoundoff;

// |v|, without the squares of tiny or huge components underflowing or overflowing: for bodies
// 1e-200 across, the plain norm is 0. Where the sum of squares is far from both ends of the
// double range, the largest square is a normal number and the plain norm is as close (a squared
// component that underflows there is below 2^-1000 of the sum); it saves a division on the
// path of every row the screens settle.
Scalar length(const Vector3& v) {
  const Scalar squares = v.squaredNorm();
  if (squares > 0x1p-1000 && squares < 0x1p1000) return std::sqrt(squares);
  const Scalar largest = v.cwiseAbs().maxCoeff();
  return largest > 0 ? largest * (v / largest).norm() : 0;
}

// The inner radius and the face normals, kept together: one lookup among the body's derived data
// for a batch row whose body changed, not two.
struct ScreenData {
  Scalar inner;
  std::vector<Vector3> normals;
  PointColumns normal_columns;  // held when there are normals, at most kCapacity of them
};

// `normals` by coordinate (see BodyBalls::normal_columns); none held when there are none or more
// than PointColumns::kCapacity.
PointColumns normal_columns(const std::vector<Vector3>& normals) {
  PointColumns columns;
  const auto count = static_cast<Eigen::Index>(normals.size());
  if (count == 0 || count > PointColumns::kCapacity) return columns;
  VertexMatrix rows(count, 3);
  for (Eigen::Index i = 0; i < count; ++i) rows.row(i) = normals[static_cast<std::size_t>(i)];
  columns.assign(rows);
  return columns;
}

// The unit outward normals of the hull's triangles (none for a flat or lower-dimensional hull, or
// where a triangle's normal does not come out finite and nonzero). Any axis serves a separation
// test, which bounds its own rounding: these need no more precision than a good guess.
std::vector<Vector3> face_normals(const ConvexPolyhedron& body) {
  const Hull& hull = body.hull();
  if (hull.dimension != 3) return {};
  const VertexMatrix& centred = body.centred_vertices();
  std::vector<Vector3> normals;
  normals.reserve(static_cast<std::size_t>(hull.faces.rows()));
  for (Eigen::Index f = 0; f < hull.faces.rows(); ++f) {
    const Vector3 p = centred.row(hull.faces(f, 0)).transpose();
    const Vector3 normal = (centred.row(hull.faces(f, 1)).transpose() - p)
                               .cross(centred.row(hull.faces(f, 2)).transpose() - p);
    const Scalar size = length(normal);
    if (!(size > 0) || !std::isfinite(size)) return {};
    normals.push_back(normal / size);
  }
  return normals;
}

// The radius of a ball about the box centre (the origin of the centred points) inside the hull of
// the centred points, as the solvers read them; 0 when none is proven. The hull's triangles must
// form a closed, consistently oriented surface with the centre strictly behind every triangle's
// plane, beyond rounding: then the surface winds around the centre (as hull_points.cpp argues for
// the points it leaves out), and so around every point of a ball about it that meets no plane,
// which therefore lies in the hull of the triangles' corners. A ball meets no plane when its
// radius is below each plane's distance, bounded here from below: the determinant less
// Shewchuk's bound, over an upper bound of the exact normal's length.
Scalar inner_radius(const ConvexPolyhedron& body) {
  const Hull& hull = body.hull();
  if (hull.dimension != 3) return 0;
  std::vector<Eigen::RowVector3i> triangles;
  triangles.reserve(static_cast<std::size_t>(hull.faces.rows()));
  for (Eigen::Index f = 0; f < hull.faces.rows(); ++f) triangles.emplace_back(hull.faces.row(f));
  if (!closed_surface(triangles)) return 0;
  const VertexMatrix& centred = body.centred_vertices();
  // In the unit ball (exactly, by a power of two), where nothing overflows.
  const int exponent = exponent_above(centred.cwiseAbs().maxCoeff());
  const auto unit = [&](int i) -> Vector3 {
    Vector3 p;
    for (int k = 0; k < 3; ++k) p(k) = times_power_of_two(centred(i, k), -exponent);
    return p;
  };
  Scalar nearest = std::numeric_limits<Scalar>::infinity();
  for (const Eigen::RowVector3i& t : triangles) {
    const Vector3 a = unit(t(0));
    const Vector3 u = unit(t(1)) - a;
    const Vector3 v = unit(t(2)) - a;
    Vector3 minor, magnitude;
    for (int k = 0; k < 3; ++k) {
      const int i = (k + 1) % 3;
      const int j = (k + 2) % 3;
      minor(k) = u(i) * v(j) - u(j) * v(i);
      magnitude(k) = std::abs(u(i) * v(j)) + std::abs(u(j) * v(i));
    }
    // The centre's orientation determinant (0 - a) . (u x v), negative behind the plane.
    const Scalar behind = a.dot(minor) - (kOrientationBound * a.cwiseAbs().dot(magnitude) +
                                          kUnderflow);
    if (!(behind > 0)) return 0;
    // Each computed minor is within 4.1 u of its terms' magnitudes of the exact one.
    const Scalar normal = minor.norm() * (1 + 4 * kRoundoff) +
                          8 * kRoundoff * magnitude.norm() + kUnderflow;
    nearest = std::min(nearest, behind / normal);
  }
  return times_power_of_two(nearest * (1 - 4 * kRoundoff), exponent);
}

}  // namespace

BodyBalls body_balls(const ConvexPolyhedron& body, bool with_inner) {
  BodyBalls balls;
  balls.columns = body.centred_columns();
  balls.outer = body.outer_radius();
  if (with_inner) {
    const ScreenData& data = body.derived<ScreenData>([&body] {
      std::vector<Vector3> normals = face_normals(body);
      PointColumns columns = normal_columns(normals);
      return ScreenData{inner_radius(body), std::move(normals), columns};
    });
    balls.inner = data.inner;
    balls.face_normals = &data.normals;
    if (data.normal_columns.held()) balls.normal_columns = &data.normal_columns;
  }
  // A rounded body's inner ball grows by its radius (its outer one has: outer_radius), and is the
  // radius alone when its core is one point or a segment, whose box centre is on it (the point,
  // the segment's midpoint).
  const Scalar r = body.radius();
  if (r > 0) {
    if (balls.inner > 0) {
      balls.inner = (balls.inner + r) * (1 - 0x1p-40);
    } else if (with_inner && body.size() <= 2) {
      balls.inner = r * (1 - 0x1p-40);
    }
  }
  return balls;
}

namespace {

// Apart, proven `lower` apart along `direction`, with the placed points a[i] and b[j] as
// witnesses (moved out by the radii of rounded bodies, towards each other: the lower bound keeps
// them apart); nothing when their distance overflows.
std::optional<ScreenVerdict> apart(Scalar lower, const Vector3& direction,
                                   const ConvexPolyhedron& a, const Pose& pose_a, int i,
                                   const ConvexPolyhedron& b, const Pose& pose_b, int j) {
  ScreenVerdict verdict;
  verdict.lower_bound = lower;
  verdict.direction = direction;
  verdict.point_a = pose_a.rotation * a.vertices().row(i).transpose() + pose_a.translation;
  verdict.point_b = pose_b.rotation * b.vertices().row(j).transpose() + pose_b.translation;
  if (a.radius() > 0 || b.radius() > 0) {
    const Vector3 between = verdict.point_b - verdict.point_a;
    const Vector3 n = between / length(between);
    verdict.point_a += a.radius() * n;
    verdict.point_b -= b.radius() * n;
  }
  verdict.distance = length(verdict.point_b - verdict.point_a);
  if (!std::isfinite(verdict.distance)) return std::nullopt;
  return verdict;
}

// Where the centres of the bodies' boxes land, as both screens read them, and the first terms of
// their margins' sums, |c_a|_1 + |t_a|_1 + |c_b|_1 + |t_b|_1 (c a box centre, t a translation),
// added in that order as the margins add them (a margin's sum then goes on from it).
struct Centres {
  Vector3 a;
  Vector3 b;
  Vector3 between;
  Scalar length;
  Scalar reach;
};

Centres centres_of(const ConvexPolyhedron& a, const Pose& pose_a, const ConvexPolyhedron& b,
                   const Pose& pose_b) {
  Centres c;
  c.a = pose_a.rotation * a.bounds().centre + pose_a.translation;
  c.b = pose_b.rotation * b.bounds().centre + pose_b.translation;
  c.between = c.b - c.a;
  c.length = length(c.between);
  c.reach = a.bounds().centre.lpNorm<1>() + pose_a.translation.lpNorm<1>() +
            b.bounds().centre.lpNorm<1>() + pose_b.translation.lpNorm<1>();
  return c;
}

std::optional<ScreenVerdict> by_balls(const ConvexPolyhedron& a, const Pose& pose_a,
                                      const BodyBalls& balls_a, const ConvexPolyhedron& b,
                                      const Pose& pose_b, const BodyBalls& balls_b,
                                      const Centres& at, Scalar relative_tolerance) {
  const Vector3& centre_a = at.a;
  const Vector3& between = at.between;
  const Scalar centres = at.length;
  const BallsGap gap = balls_gap(balls_a.outer, balls_b.outer, at.reach, at.length);
  if (!std::isfinite(gap.margin)) return std::nullopt;
  const Scalar margin = gap.margin;
  if (gap.lower > world_tolerance(a, b, centres, relative_tolerance)) {
    return apart(gap.lower, between / centres, a, pose_a, 0, b, pose_b, 0);
  }
  const Scalar inner_a = balls_a.inner * (1 - kStretch);
  const Scalar inner_b = balls_b.inner * (1 - kStretch);
  // A radius of 0 proves nothing, not even the centre: a thin body's box centre may lie outside
  // it, and taking the centre for a point of the body proved thin bodies in contact that were not.
  if (!(inner_a > 0 && inner_b > 0)) return std::nullopt;
  if (!(centres + margin < (inner_a + inner_b) * (1 - 4 * kRoundoff))) return std::nullopt;
  // The point splitting the centres' segment in the inner radii's ratio is within each inner ball.
  ScreenVerdict verdict;
  verdict.colliding = true;
  verdict.point_a = centre_a + (inner_a / (inner_a + inner_b)) * between;
  verdict.point_b = verdict.point_a;
  return verdict;
}

// A computed unit vector `world` (of length 1 to 5 u) pointing from A towards B, and where it
// points in each body's own frame: `up_a = R_a^T world`, `down_b = -(R_b^T world)`. A placed
// point is R (c + x) + t, x a centred point, so its height along the axis is
// world . (R c + t) + (R^T world) . x: the heights are compared in each body's own frame, where
// they are rounded relative to the body's size, as the solvers compare them. The centres' axis
// is turned once per row: the face normals are chosen by the same turned vectors.
struct Axis {
  Vector3 world;
  Vector3 up_a;
  Vector3 down_b;
};

Axis turned(const Vector3& world, const Pose& pose_a, const Pose& pose_b) {
  return {world, pose_a.rotation.transpose() * world, -(pose_b.rotation.transpose() * world)};
}

// The bodies proven apart along `axis`: the separation of their supporting points along it, less
// a bound on its rounding, exceeds the tolerance.
std::optional<ScreenVerdict> apart_along(const Axis& turned_axis, const ConvexPolyhedron& a,
                                         const Pose& pose_a, const BodyBalls& balls_a,
                                         const ConvexPolyhedron& b, const Pose& pose_b,
                                         const BodyBalls& balls_b, const Centres& at,
                                         Scalar relative_tolerance) {
  const Vector3& axis = turned_axis.world;
  const Vector3& up_a = turned_axis.up_a;
  const Vector3& down_b = turned_axis.down_b;
  const Vector3& between = at.between;
  const Scalar centres = at.length;
  const VertexMatrix& points_a = a.centred_vertices();
  const VertexMatrix& points_b = b.centred_vertices();
  const PointColumns* columns_a = balls_a.columns;
  const PointColumns* columns_b = balls_b.columns;
  const int top_a = columns_a ? columns_a->scan(up_a) : scan_support(points_a, up_a);
  const int bottom_b = columns_b ? columns_b->scan(down_b) : scan_support(points_b, down_b);
  const Scalar separation = axis.dot(between) - point_height(points_b, bottom_b, down_b) -
                            point_height(points_a, top_a, up_a);
  // The bound below takes nonnegative margins and radii off the separation, so it cannot exceed
  // a nonnegative tolerance unless the separation is positive: the overlapping pairs of a batch
  // fail every axis, and skip the margin here.
  if (!(separation > 0)) return std::nullopt;
  // The rounding, against the exact separation of the placed bodies along the computed axis: the
  // centres' coordinates are within 7 u of |c| + |t| (1-norms), which moves axis . between by
  // that and 4 u of |between|; a rotated axis is within 5.3 u of R^T axis (|axis| = 1 to 5 u),
  // which with the centring's rounding (u of each centred point) and the inner products' moves
  // each height by at most 9.4 u of the body's outer radius (which bounds its centred points);
  // the last two sums add 2 u of their terms. 32 u of it all is more than twice that (the last
  // term covers products that underflow).
  const Scalar margin =
      32 * kRoundoff * (at.reach + centres + balls_a.outer + balls_b.outer) + 16 * kUnderflow;
  // Dividing by |axis| <= 1 + 5 u turns the separation along the axis into a distance; a rounded
  // body's radius is then taken off (rounded up), and the difference's rounding (down).
  const Scalar radii = (a.radius() + b.radius()) * (1 + 4 * kRoundoff);
  const Scalar lower = ((separation - margin) * (1 - 8 * kRoundoff) - radii) * (1 - 4 * kRoundoff);
  if (!std::isfinite(lower) || !(lower > world_tolerance(a, b, centres, relative_tolerance))) {
    return std::nullopt;
  }
  return apart(lower, axis, a, pose_a, top_a, b, pose_b, bottom_b);
}

// True when the screens that scan the bodies' points may: bodies of at most
// kHillClimbingThreshold points (scanned whole, as the solvers scan them) whose centres are apart.
// A curved shape's points are a few on its surface, not the body: its supports are not theirs.
bool scannable(const ConvexPolyhedron& a, const ConvexPolyhedron& b, const Centres& at) {
  return !a.curved() && !b.curved() && a.size() <= kHillClimbingThreshold &&
         b.size() <= kHillClimbingThreshold &&
         at.length > 0 && std::isfinite(at.length);
}

// The centres' axis, from A's centre towards B's (only for scannable bodies).
Axis centres_axis(const Pose& pose_a, const Pose& pose_b, const Centres& at) {
  return turned(at.between / at.length, pose_a, pose_b);
}

// The normal of `normals` nearest `direction` (the first of the largest inner products), from
// their columns when held (the same inner products, two at a time).
const Vector3& nearest_normal(const std::vector<Vector3>& normals, const PointColumns* columns,
                              const Vector3& direction) {
  if (columns != nullptr) return normals[static_cast<std::size_t>(columns->scan(direction))];
  std::size_t best = 0;
  Scalar best_height = normals[0].dot(direction);
  for (std::size_t i = 1; i < normals.size(); ++i) {
    const Scalar height = normals[i].dot(direction);
    if (height > best_height) {
      best_height = height;
      best = i;
    }
  }
  return normals[best];
}

// `direction` over its length: a unit vector to within 5 u.
Vector3 unit(const Vector3& direction) { return direction / length(direction); }

// `centres` is the centres' axis (centres_axis): A's normal nearest it, B's nearest its opposite.
std::optional<ScreenVerdict> across_faces(const ConvexPolyhedron& a, const Pose& pose_a,
                                          const BodyBalls& balls_a, const ConvexPolyhedron& b,
                                          const Pose& pose_b, const BodyBalls& balls_b,
                                          const Centres& at, const Axis& centres,
                                          Scalar relative_tolerance) {
  if (balls_a.face_normals == nullptr || balls_b.face_normals == nullptr ||
      balls_a.face_normals->empty() || balls_b.face_normals->empty()) {
    return std::nullopt;
  }
  const Vector3& normal_a =
      nearest_normal(*balls_a.face_normals, balls_a.normal_columns, centres.up_a);
  std::optional<ScreenVerdict> settled =
      apart_along(turned(unit(pose_a.rotation * normal_a), pose_a, pose_b), a, pose_a, balls_a,
                  b, pose_b, balls_b, at, relative_tolerance);
  if (settled) return settled;
  const Vector3& normal_b =
      nearest_normal(*balls_b.face_normals, balls_b.normal_columns, centres.down_b);
  return apart_along(turned(unit(-(pose_b.rotation * normal_b)), pose_a, pose_b), a, pose_a,
                     balls_a, b, pose_b, balls_b, at, relative_tolerance);
}

}  // namespace

std::optional<ScreenVerdict> collision_by_balls(const ConvexPolyhedron& a, const Pose& pose_a,
                                              const BodyBalls& balls_a, const ConvexPolyhedron& b,
                                              const Pose& pose_b, const BodyBalls& balls_b,
                                              Scalar relative_tolerance) {
  return by_balls(a, pose_a, balls_a, b, pose_b, balls_b, centres_of(a, pose_a, b, pose_b),
                  relative_tolerance);
}

std::optional<ScreenVerdict> apart_along_centres(const ConvexPolyhedron& a, const Pose& pose_a,
                                                 const BodyBalls& balls_a,
                                                 const ConvexPolyhedron& b, const Pose& pose_b,
                                                 const BodyBalls& balls_b,
                                                 Scalar relative_tolerance) {
  const Centres at = centres_of(a, pose_a, b, pose_b);
  if (!scannable(a, b, at)) return std::nullopt;
  return apart_along(centres_axis(pose_a, pose_b, at), a, pose_a, balls_a, b, pose_b, balls_b, at,
                     relative_tolerance);
}

std::optional<ScreenVerdict> apart_across_faces(const ConvexPolyhedron& a, const Pose& pose_a,
                                                const BodyBalls& balls_a,
                                                const ConvexPolyhedron& b, const Pose& pose_b,
                                                const BodyBalls& balls_b,
                                                Scalar relative_tolerance) {
  const Centres at = centres_of(a, pose_a, b, pose_b);
  if (!scannable(a, b, at)) return std::nullopt;
  return across_faces(a, pose_a, balls_a, b, pose_b, balls_b, at,
                      centres_axis(pose_a, pose_b, at), relative_tolerance);
}

// Flattened: every screen and every scan inlined into the row's one call. With the normals'
// scans beside the points', PointColumns::scan was kept out of line (up to eight calls a row) and
// collide_many's rows were 1,863 instructions (8 vertices, overlapping), 1,708 flattened;
// forcing the scan inline everywhere instead lengthened distance_many's rows (+77 apart, +125
// overlapping).
[[gnu::flatten]] std::optional<ScreenVerdict> collision_by_screens(
    const ConvexPolyhedron& a, const Pose& pose_a, const BodyBalls& balls_a,
    const ConvexPolyhedron& b, const Pose& pose_b, const BodyBalls& balls_b,
    Scalar relative_tolerance) {
  const Centres at = centres_of(a, pose_a, b, pose_b);
  std::optional<ScreenVerdict> settled =
      by_balls(a, pose_a, balls_a, b, pose_b, balls_b, at, relative_tolerance);
  if (settled || !scannable(a, b, at)) return settled;
  const Axis centres = centres_axis(pose_a, pose_b, at);
  settled = apart_along(centres, a, pose_a, balls_a, b, pose_b, balls_b, at, relative_tolerance);
  if (!settled) {
    settled =
        across_faces(a, pose_a, balls_a, b, pose_b, balls_b, at, centres, relative_tolerance);
  }
  return settled;
}

}  // namespace swarmcollide::detail
