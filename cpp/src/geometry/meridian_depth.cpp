#include "meridian_depth.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "curved_supports.hpp"
#include "normalise.hpp"

namespace swarmcollide::detail {

namespace {

using Vector2 = Eigen::Matrix<Scalar, 2, 1>;

// The gaps (frame units, where the pair's size is 1 to 2) below which an edge's own support
// point settles the edge: first some 6e-11, a sixteenth of the default tolerance, then some
// 1e-14, so that a curved section's bound is proven to a hundredth of the finest tolerance worth
// asking (1e-12). And the most corners of the polygon: most sections settle with a few dozen,
// but a point near a curvature centre of the boundary (the deepest directions crowding together,
// the minimum flat to the fourth order) needs hundreds of short edges. A ball 1e-5 below the
// tip's curvature centre on the axis of the ellipsoid (0.4, 0.4, 0.9): with 96 corners its
// bounds stayed 1.9e-8 apart (uncertified, the expanding polytope's 1,005 iterations, 0.7 ms);
// with 256, 1.2e-9 (certified at the default tolerance, 73 us); 512 gave 1.8e-11 in 210 us.
constexpr Scalar kCoarseGap = 0x1p-34;
constexpr Scalar kSettledGap = 0x1p-46;
constexpr int kMostCorners = 256;

Scalar sign_of(Scalar x) { return static_cast<Scalar>((x > 0) - (x < 0)); }

// A body symmetric about its own z axis, or about every axis through its centre, by its meridian
// section in the plane of x and z, in frame units: a body of revolution's support along (x, 0, z)
// is its section's along (x, z).
struct Revolution {
  enum class Shape : unsigned char { none, point, segment, cylinder, cone, ellipsoid };
  Shape shape = Shape::none;
  Scalar radius = 0;       // across the axis
  Scalar half_length = 0;  // along it
  bool any_axis = false;   // a point or a ball
  // How far the section's support points may lie outside the body.
  Scalar error = 0;

  Scalar reach() const { return std::hypot(radius, half_length); }

  // A point of the section farthest along `u`: a corner of a cylinder's rectangle, the apex or a
  // base corner of a cone's triangle (shapes.hpp's Cone: the apex at +half_length), an end of a
  // segment; on an ellipse within a few roundoffs (`error`).
  Vector2 support(const Vector2& u) const {
    switch (shape) {
      case Shape::segment:
        return {0, sign_of(u.y()) * half_length};
      case Shape::cylinder:
        return {sign_of(u.x()) * radius, sign_of(u.y()) * half_length};
      case Shape::cone:
        if (half_length * u.y() >= radius * std::abs(u.x()) - half_length * u.y()) {
          return {0, half_length};
        }
        return {sign_of(u.x()) * radius, -half_length};
      case Shape::ellipsoid: {
        const Scalar x = radius * u.x();
        const Scalar z = half_length * u.y();
        const Scalar length = std::hypot(x, z);
        if (!(length > 0)) return {0, 0};
        return {radius * (x / length), half_length * (z / length)};
      }
      default:
        return {0, 0};
    }
  }
};

Revolution revolution_of(const FramedBody& body) {
  Revolution found;
  const auto framed = [&body](Scalar length) {
    return times_power_of_two(length, -body.exponent());
  };
  switch (body.curved_kind()) {
    case CurvedKind::cylinder: {
      const auto& shape = static_cast<const CylinderSupport&>(*body.body().curved());
      found.shape = Revolution::Shape::cylinder;
      found.radius = framed(shape.radius());
      found.half_length = framed(shape.half_length());
      return found;
    }
    case CurvedKind::cone: {
      const auto& shape = static_cast<const ConeSupport&>(*body.body().curved());
      found.shape = Revolution::Shape::cone;
      found.radius = framed(shape.radius());
      found.half_length = framed(shape.half_length());
      return found;
    }
    case CurvedKind::ellipsoid: {
      const Vector3& radii = static_cast<const EllipsoidSupport&>(*body.body().curved()).radii();
      if (radii.x() != radii.y()) return found;
      found.shape = Revolution::Shape::ellipsoid;
      found.radius = framed(radii.x());
      found.half_length = framed(radii.z());
      found.any_axis = radii.x() == radii.z();
      // The unit vector's rounding (3u) and the products' (u).
      found.error = 4 * kRoundoff * std::max(found.radius, found.half_length);
      return found;
    }
    case CurvedKind::other:
      break;
  }
  if (body.curved()) return found;
  // A ball's core (one point, at the centre of its own box) or a capsule's (two points on the z
  // axis, about that centre: their heights may differ by their box centre's rounding).
  const VertexMatrix& points = body.body().centred_vertices();
  for (int i = 0; i < points.rows(); ++i) {
    if (points(i, 0) != 0 || points(i, 1) != 0) return found;
  }
  if (points.rows() == 1 && points(0, 2) == 0) {
    found.shape = Revolution::Shape::point;
    found.any_axis = true;
  } else if (points.rows() == 2) {
    const Scalar low = std::abs(points(0, 2));
    const Scalar high = std::abs(points(1, 2));
    found.shape = Revolution::Shape::segment;
    found.half_length = framed(std::max(low, high));
    found.error = framed(std::abs(high - low));
  }
  return found;
}

// The direction along which `q` is least deep in a convex set of the plane, between `from` and
// `to` (unit, less than a half-turn apart counterclockwise), or `otherwise` where the two do not
// bracket it. Where the set is curved the polygon's nearest edge gives its normal only to the
// edge's turn (some 1e-5 rad), which holds the depth to its square but not the witnesses: the
// support points along that normal lie off the line from q by as much. Along the deepest
// direction u the support point lies on the line from q along u, and its offset across u,
// `(s(u) - q) . t(u)` for the counterclockwise tangent t, grows through zero there (its slope is
// the boundary's radius of curvature less the depth, positive at a minimum): bisecting its sign
// finds u to the rounding of the offset.
template <typename Support>
Vector2 deepest_direction(const Support& support, const Vector2& q, Vector2 from, Vector2 to,
                          const Vector2& otherwise) {
  const auto across = [&](const Vector2& u) {
    return (support(u) - q).dot(Vector2(-u.y(), u.x()));
  };
  if (!(across(from) <= 0 && across(to) >= 0)) return otherwise;
  for (int step = 0; step < 64; ++step) {
    const Vector2 sum = from + to;
    const Vector2 middle = sum / std::hypot(sum.x(), sum.y());
    if (middle == from || middle == to) break;
    (across(middle) <= 0 ? from : to) = middle;
  }
  return to;
}

// A lower bound on the depth of a point in a convex set of the plane, and the outward normal of
// the nearest edge of the polygon that proves it.
struct SectionDepth {
  Scalar lower = -std::numeric_limits<Scalar>::infinity();
  Vector2 normal = Vector2::Zero();
};

// The depth of `q` (q.x >= 0) in a convex set symmetric about the z axis whose support points
// `support` gives (each within `error` of the set; along (0, +-1) on the axis), by the expanding
// polygon. Its corners are support points along directions from (0, -1) through (1, 0) to
// (0, 1), in that order, and their mirror images across the axis (support points along the
// mirrored directions): the polygon lies in the set (to `error`), and where `q` lies on the inner
// side of every edge the distance from `q` to the nearest edge's line bounds its depth below. A
// mirrored edge lies no nearer to `q` than its image (its line is the image's mirrored, and `q`
// lies on the image's side), so the chain's edges alone are measured: with the whole circle,
// a point on the axis had every edge refined twice, and a flat minimum ran out of corners. The
// nearest edge grows by the support point along its normal until that point adds less than
// kSettledGap.
template <typename Support>
SectionDepth section_depth(const Support& support, const Vector2& q, Scalar error) {
  // Corner i and the edge from it to the next corner (none from the last, whose edge fields
  // keep these values: it is copied as the corners shift).
  struct Corner {
    Vector2 direction;  // the one the point is the support point along
    Vector2 point;
    Vector2 normal = Vector2::Zero();  // the edge's outward unit normal
    // From q to the edge's line, positive inside; infinite for no edge.
    Scalar distance = std::numeric_limits<Scalar>::infinity();
    Scalar rounding = 0;  // a bound on the rounding of `distance`
    bool settled = false;
  };
  std::array<Corner, kMostCorners> corners;
  int count = 0;
  const Scalar diagonal = std::sqrt(Scalar(0.5));
  const Vector2 starts[] = {{0, -1}, {diagonal, -diagonal}, {1, 0}, {diagonal, diagonal}, {0, 1}};
  for (const Vector2& u : starts) {
    corners[count].direction = u;
    corners[count++].point = support(u);
  }
  const auto measure = [&](int i) {
    Corner& corner = corners[i];
    const Vector2& next = corners[i + 1].point;
    corner.settled = false;
    const Vector2 edge = next - corner.point;
    const Scalar length = std::hypot(edge.x(), edge.y());
    if (!(length > 0)) {
      corner.distance = std::numeric_limits<Scalar>::infinity();
      return;
    }
    const Vector2 from = corner.point - q;
    corner.normal = Vector2(edge.y(), -edge.x()) / length;
    // The edge's cross product with the corner seen from q, over its length. The edge is taken
    // between the corners themselves, within a roundoff of its own length (from q, as the
    // difference of the corners' vectors from q, it was within a roundoff of their lengths, and
    // the bound of a corner a millionth of the size from the next some 1e-10 short): the
    // differences, the products and the quotient round by some 7u of |from|.
    corner.distance = (from.x() * edge.y() - from.y() * edge.x()) / length;
    corner.rounding = 12 * kRoundoff * from.norm();
  };
  for (int i = 0; i + 1 < count; ++i) measure(i);
  const auto nearest = [&] {
    int least = 0;
    for (int i = 1; i + 1 < count; ++i) {
      if (corners[i].distance < corners[least].distance) least = i;
    }
    return least;
  };
  // First to a gap the default tolerance needs, then finer: where the section's minimum is
  // flat (the point near a curvature centre of its boundary, the deepest directions crowding
  // together), the finer gap alone spent every corner on the few nearest edges and left the
  // others as far below as the corners ran out.
  Scalar gap = kCoarseGap;
  for (;;) {
    const int least = nearest();
    Corner& edge = corners[least];
    if (!std::isfinite(edge.distance)) break;
    if (edge.settled) {
      if (gap == kSettledGap || count == kMostCorners) break;
      gap = kSettledGap;
      for (int i = 0; i + 1 < count; ++i) corners[i].settled = false;
      continue;
    }
    const Vector2 farther = support(edge.normal);
    if (!(edge.normal.dot(farther - edge.point) > gap) || count == kMostCorners) {
      edge.settled = true;
      continue;
    }
    for (int i = count; i > least + 1; --i) corners[i] = corners[i - 1];
    corners[least + 1].direction = edge.normal;
    corners[least + 1].point = farther;
    ++count;
    measure(least);
    measure(least + 1);
  }
  SectionDepth found;
  const int least = nearest();
  if (!std::isfinite(corners[least].distance)) return found;
  // The edges joining the chain's ends to their images, across the axis (of no length where the
  // ends lie on it: their lines then support the set there, which holds the polygon).
  Scalar lower = std::min(corners[count - 1].point.y() - q.y(), q.y() - corners[0].point.y());
  for (int i = 0; i + 1 < count; ++i) {
    if (std::isfinite(corners[i].distance)) {
      lower = std::min(lower, corners[i].distance - corners[i].rounding);
    }
  }
  // The corners' own rounding (each a difference of two support points) and their distance from
  // the set; a point within that of q has its depth within that of q's.
  found.lower = lower - error - 8 * kRoundoff * q.norm();
  const Corner& edge = corners[least];
  found.normal = deepest_direction(support, q, edge.direction, corners[least + 1].direction,
                                   edge.normal);
  return found;
}

}  // namespace

ClosedFormDepth meridian_depth(const FramedBody& a, const FramedBody& b) {
  ClosedFormDepth none;
  if (!a.curved() && !b.curved()) return none;
  const Revolution ra = revolution_of(a);
  if (ra.shape == Revolution::Shape::none) return none;
  const Revolution rb = revolution_of(b);
  if (rb.shape == Revolution::Shape::none || (ra.any_axis && rb.any_axis)) return none;
  // The axis: a body's own (a ball has none to give).
  const FramedBody& axial = ra.any_axis ? b : a;
  const Vector3 axis = frame_axis(axial);
  // Each body's axis along the frame's (+1) or against it (-1), and how far turning each onto it
  // moves their points.
  Scalar turned = 0;
  const auto along = [&](const FramedBody& body, const Revolution& shape, Scalar& flip) {
    flip = 1;
    if (&body == &axial || shape.any_axis) return true;
    const Vector3 own = frame_axis(body);
    if (own.dot(axis) < 0) flip = -1;
    const Scalar chord = (own - flip * axis).norm();
    if (!(chord <= kMostAxisTilt)) return false;
    turned += chord * (1 + 8 * kRoundoff) * shape.reach();
    return true;
  };
  Scalar flip_a = 1;
  Scalar flip_b = 1;
  if (!along(a, ra, flip_a) || !along(b, rb, flip_b)) return none;
  // B - A is the section's body of revolution about the axis through the centres' difference;
  // the origin lies at `q` from there, in the axial body's axes.
  const Vector3 from_centre = a.offset() - b.offset();
  const Vector3 q = axial.local_direction(from_centre);
  const auto section = [](const Revolution& shape, Scalar flip, const Vector2& u) {
    const Vector2 p = shape.support({u.x(), flip * u.y()});
    return Vector2(p.x(), flip * p.y());
  };
  const SectionDepth found = section_depth(
      [&](const Vector2& u) { return Vector2(section(rb, flip_b, u) - section(ra, flip_a, -u)); },
      Vector2(std::hypot(q.x(), q.y()), q.z()), ra.error + rb.error);
  const Scalar skew = std::max(rotation_skew(a), rotation_skew(b));
  const Scalar farthest = from_centre.norm() + ra.reach() + rb.reach();
  ClosedFormDepth least;
  least.depth = depth_in_frame(found.lower - turned, skew, farthest,
                               a.scan_shortfall() + b.scan_shortfall());
  if (!(least.depth > 0)) return none;
  // The section's normal turned about the axis to the origin's side (any side on the axis).
  const Vector3 across = radial(q.x(), q.y());
  const Vector3 away(found.normal.x() * across.x(), found.normal.x() * across.y(),
                     found.normal.y());
  // The origin leaves B - A along `away`, so B leaves A the other way.
  least.normal = -(axial.rotated() ? Vector3(axial.rotation() * away) : away).normalized();
  least.curved_a = a.curved();
  least.surface = a.curved() ? a.support(least.normal) : b.support(-least.normal);
  // Where sides of the sections face each other (segments in space: a cylinder's between its
  // rims, a cone's from its apex to its rim, a cap's diameter), each support along the normal is
  // one end of its side. Both ends of each, asked a little off the normal within the section's
  // plane, let the witnesses find a point both sides share. (Along a
  // curved part they lie below the supporting plane, out of the witnesses' features.)
  const Vector2 tangent(-found.normal.y(), found.normal.x());
  const Vector3 local(tangent.x() * across.x(), tangent.x() * across.y(), tangent.y());
  const Vector3 sideways = axial.rotated() ? Vector3(axial.rotation() * local) : local;
  for (const Scalar tilt : {Scalar(-1e-3), Scalar(1e-3)}) {
    a.support(least.normal + tilt * sideways);
    b.support(-least.normal + tilt * sideways);
  }
  return least;
}

}  // namespace swarmcollide::detail
