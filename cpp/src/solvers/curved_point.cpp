#include "curved_point.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "../geometry/curved_depth.hpp"
#include "../geometry/curved_supports.hpp"
#include "../geometry/normalise.hpp"
#include "../queries/verdict.hpp"
#include "exact_solver.hpp"

namespace swarmcollide::detail {

namespace {

// How the support point along Nearest::second follows from the one along `first`, exactly, by a
// symmetry of the support function (curved_supports.hpp): none, or the same point with its x and
// y negated (rim points across a cone's base: unit_in_plane and unit_scaled see the same
// magnitudes, each quotient and product only changes sign, and the comparison of apex and rim
// reads the same numbers).
enum class Mirror { none, across };

// What the closed form chooses, in the shape's own frame: the outward normal at the nearest
// surface point, and that point either as `point` itself (`direct`: a cylinder's, in the closed
// form's units and pulled inside the shape) or as `weight` of the support point along `first`
// and `1 - weight` of the one along `second` (both points of the shape, with kInward's pull).
struct Nearest {
  bool inside = false;
  Vector3 normal = Vector3::Zero();
  bool direct = false;
  Vector3 point = Vector3::Zero();
  Vector3 first = Vector3::Zero();
  Vector3 second = Vector3::Zero();
  Mirror mirror = Mirror::none;
  Scalar weight = 1;
};

// The support point along `nearest.second` in the shape's own frame, `first` being the one along
// `nearest.first`: mirrored when a symmetry gives it (the same coordinates as the support's, with
// -0 as +0 as the shape's points store them: a support call fewer), else asked.
Vector3 second_support(const FramedBody& shape, const Nearest& nearest, const Vector3& first) {
  if (nearest.mirror == Mirror::across) return {-first.x() + 0, -first.y() + 0, first.z()};
  return shape.curved_local_support(nearest.second);
}

// The unit vector along (x, y) in the plane, or the x axis on the z axis (every azimuth is as
// near there). The length is the square root of the squares where none under- or overflows (the
// larger coordinate within 2^-500 and 2^500), a roundoff or two from std::hypot's, whose call was
// a fiftieth of a ball-cylinder query: it only chooses the witness and the normal, and the bounds
// are measured at the points chosen.
void azimuth(Scalar x, Scalar y, Scalar& ux, Scalar& uy, Scalar& rho) {
  const Scalar larger = std::max(std::abs(x), std::abs(y));
  rho = larger >= 0x1p-500 && larger <= 0x1p500 ? std::sqrt(x * x + y * y) : std::hypot(x, y);
  if (rho > 0) {
    ux = x / rho;
    uy = y / rho;
  } else {
    ux = 1;
    uy = 0;
  }
}

// The unit vector from `q` to `p`, or zero when they coincide (a point on the surface: no
// normal, and the search answers).
Vector3 away_from(const Vector3& p, const Vector3& q) {
  const Vector3 between = p - q;
  const Scalar length = between.norm();
  return length > 0 ? Vector3(between / length) : Vector3::Zero();
}

// A cylinder of radius r from z = -h to h: beside its side, the point at the same height on the
// generator; above or below a cap, the point straight above on it; past a rim, the rim point.
// Inside, the nearer of the generator's point and the cap's. The point is given directly, its
// distance from the axis pulled in by kInward (the unit azimuth is within 3 roundoffs of length 1,
// the rounded rho within two of the exact, so r |u| kInward and rho kInward stay below r; the
// height is p_z or +-h, on the cylinder's height): the combination of two support points placed
// in the frame that this replaced (the rim points above and below, or across the cap) is the same
// point in exact arithmetic, and cost a support call and two placements more.
Nearest cylinder_nearest(const Vector3& p, Scalar r, Scalar h) {
  Nearest n;
  Scalar ux, uy, rho;
  azimuth(p.x(), p.y(), ux, uy, rho);
  n.inside = !(rho > r) && !(std::abs(p.z()) > h);
  const bool side = n.inside ? r - rho <= h - std::abs(p.z()) : rho > r;
  const bool beyond_cap = n.inside ? !side : std::abs(p.z()) > h;
  const Scalar s = p.z() < 0 ? -1 : 1;
  n.direct = true;
  if (side && !beyond_cap) {
    n.normal = {ux, uy, 0};
    n.point = {r * ux * kInward, r * uy * kInward, p.z()};
  } else if (!side) {
    n.normal = {0, 0, s};
    n.point = {p.x() * kInward, p.y() * kInward, s * h};
  } else {
    n.normal = away_from(p, Vector3(r * ux, r * uy, s * h));
    n.point = {r * ux * kInward, r * uy * kInward, s * h};
  }
  return n;
}

// A cone of base radius r at z = -h, apex at (0, 0, h), in the half-plane of the point's azimuth
// (rho, z): the triangle (0, -h), (r, -h), (0, h). Below the base disk, the point straight under
// on it; else the nearest point of the slant (rim to apex): inside it, along the slant's normal;
// at its ends, the rim point or the apex.
Nearest cone_nearest(const Vector3& p, Scalar r, Scalar h) {
  Nearest n;
  Scalar ux, uy, rho;
  azimuth(p.x(), p.y(), ux, uy, rho);
  const Scalar z = p.z();
  const Vector3 rim_direction(ux, uy, -1);
  const Vector3 apex_direction(0, 0, 1);
  // The point straight under (or over) p on the base, between the rim points along and against
  // the azimuth.
  const auto on_base = [&] {
    n.normal = {0, 0, -1};
    n.first = rim_direction;
    n.second = {-ux, -uy, -1};
    n.mirror = Mirror::across;
    n.weight = std::clamp((1 + rho / r) / 2, Scalar(0), Scalar(1));
    return n;
  };
  if (z < -h && rho <= r) return on_base();
  // The slant from the rim (r, -h) along (-r, 2h) to the apex.
  const Scalar along = -r * (rho - r) + 2 * h * (z + h);
  const Scalar length_squared = r * r + 4 * h * h;
  // The foot of p on the slant, between the rim and the apex, along the slant's normal.
  const auto on_slant = [&](Scalar slant) {
    n.normal = Vector3(2 * h * ux, 2 * h * uy, r) / slant;
    n.first = rim_direction;
    n.second = apex_direction;
    n.weight = std::clamp(1 - along / length_squared, Scalar(0), Scalar(1));
    return n;
  };
  // Inside: above the base and below the slant's line, 2h rho < r (h - z). The nearer of the
  // point straight under on the base and the foot on the slant, which lies between the rim and
  // the apex (the triangle's angles there are acute).
  if (z > -h && 2 * h * rho < r * (h - z)) {
    n.inside = true;
    const Scalar slant = std::sqrt(length_squared);
    return z + h <= (r * (h - z) - 2 * h * rho) / slant ? on_base() : on_slant(slant);
  }
  if (along <= 0) {
    n.normal = away_from(p, Vector3(r * ux, r * uy, -h));
    n.first = rim_direction;
  } else if (along >= length_squared) {
    n.normal = away_from(p, Vector3(0, 0, h));
    n.first = apex_direction;
  } else {
    // 0 < along < length_squared: the clamp changes no weight here.
    return on_slant(std::sqrt(length_squared));
  }
  return n;
}

// An ellipsoid of semi-axes `radii`: the nearest point q of a point p outside has p - q along the
// surface's normal there, q_i = a_i^2 p_i / (a_i^2 + t) for the t > 0 at which q is on the
// surface, sum (a_i p_i / (a_i^2 + t))^2 = 1 (the function falls and is convex in t, so Newton's
// steps from below the root rise to it). The normal there is along p_i / (a_i^2 + t), and the
// support point along it is q: the witness is that one support point.
Nearest ellipsoid_nearest(const Vector3& p, const Vector3& a) {
  Nearest n;
  const Vector3 ap = a.cwiseProduct(p);
  const Vector3 aa = a.cwiseProduct(a);
  if (!(ap.cwiseQuotient(aa).squaredNorm() > 1)) {
    n.inside = true;  // or on the surface, or not finite: the penetration solver decides
    return n;
  }
  // The sum is at least |a p|^2 / (max a^2 + t)^2, so the root is at least |a p| - max a^2:
  // the start, from which far points need a few steps rather than dozens.
  Scalar t = std::max(Scalar(0), ap.norm() - aa.maxCoeff());
  for (int step = 0; step < 64; ++step) {
    Scalar value = -1;
    Scalar slope = 0;
    for (int k = 0; k < 3; ++k) {
      const Scalar over = ap(k) / (aa(k) + t);
      value += over * over;
      slope -= 2 * over * over / (aa(k) + t);
    }
    if (!(value > 0) || !(slope < 0)) break;
    const Scalar next = t - value / slope;
    if (!(next > t)) break;
    t = next;
  }
  Vector3 normal;
  for (int k = 0; k < 3; ++k) normal(k) = p(k) / (aa(k) + t);
  const Scalar length = normal.norm();
  if (!(length > 0) || !std::isfinite(length)) return n;
  n.normal = normal / length;
  n.first = n.normal;
  return n;
}

// The support value along `l`, a direction in the shape's own frame (unit to a few roundoffs),
// of the shape `kind` of radius `r` and half-length `h` (a cylinder, a cone) or semi-axes `radii`
// (an ellipsoid), each at most 1: a cylinder's rim over the cap the direction points to, `r |l_xy|
// + h |l_z|`; a cone's apex `h l_z` or its base's rim `r |l_xy| - h l_z`, the higher; an
// ellipsoid's `|diag(radii) l|`. The support is Lipschitz in l with the shape's outer radius, so
// l's rounding (3u a component) moves it by 5.3u of that radius, and computing it (a square root,
// a product, a sum or the cone's difference) under 6u more.
// Squares below the smallest normal double are off by less than it, far below the frame's
// rounding (kFrameRounding is absolute in the frame, where these sizes are at most 2).
Scalar support_value(CurvedShapeParameters::Kind kind, Scalar r, Scalar h, const Vector3& radii,
                     const Vector3& l) {
  switch (kind) {
    case CurvedShapeParameters::Kind::cylinder:
      return r * std::sqrt(l.x() * l.x() + l.y() * l.y()) + h * std::abs(l.z());
    case CurvedShapeParameters::Kind::cone: {
      const Scalar apex = h * l.z();
      return std::max(apex, r * std::sqrt(l.x() * l.x() + l.y() * l.y()) - apex);
    }
    case CurvedShapeParameters::Kind::ellipsoid:
      break;
  }
  return radii.cwiseProduct(l).norm();
}

// The kind and dimensions of a shape of curved_supports.hpp, read from its exact type (as
// CurvedShapeParameters holds them): the virtual parameters() built the whole struct, its pose
// too, some 20 instructions of a ball-cylinder query. False for any other support function (a
// shape placed in its body's frame), which the searches answer.
bool dimensions(const FramedBody& shape, CurvedShapeParameters& out) {
  const SupportFunction* support = shape.body().curved();
  switch (shape.curved_kind()) {
    case CurvedKind::cylinder: {
      const auto* cylinder = static_cast<const CylinderSupport*>(support);
      out.kind = CurvedShapeParameters::Kind::cylinder;
      out.radius = cylinder->radius();
      out.half_length = cylinder->half_length();
      return true;
    }
    case CurvedKind::cone: {
      const auto* cone = static_cast<const ConeSupport*>(support);
      out.kind = CurvedShapeParameters::Kind::cone;
      out.radius = cone->radius();
      out.half_length = cone->half_length();
      return true;
    }
    case CurvedKind::ellipsoid:
      out.kind = CurvedShapeParameters::Kind::ellipsoid;
      out.radii = static_cast<const EllipsoidSupport*>(support)->radii();
      return true;
    default:
      return false;
  }
}

}  // namespace

bool point_against_curved(const FramedPair& pair, Goal goal, int max_iterations, Answer& answer) {
  if (!point_and_curved(pair)) return false;
  const bool curved_a = pair.a.curved();
  const FramedBody& shape = curved_a ? pair.a : pair.b;
  const FramedBody& point = curved_a ? pair.b : pair.a;
  CurvedShapeParameters parameters;
  if (!dimensions(shape, parameters)) return false;
  // The point in the shape's own frame (centred on its box: the shape's origin for these), and
  // the shape, in units of its extent's power of two, so that no square in the closed forms
  // under- or overflows.
  const bool ellipsoid = parameters.kind == CurvedShapeParameters::Kind::ellipsoid;
  const int unit = exponent_above(ellipsoid ? parameters.radii.maxCoeff()
                                            : std::max(parameters.radius, parameters.half_length));
  const Vector3 p = point.single_vertex();
  const Vector3 local =
      times_power_of_two(shape.local_direction(p - shape.offset()), shape.exponent() - unit);
  const Scalar r = times_power_of_two(parameters.radius, -unit);
  const Scalar h = times_power_of_two(parameters.half_length, -unit);
  const Vector3 radii = ellipsoid ? times_power_of_two(parameters.radii, -unit) : Vector3::Zero();
  // Made in place (a Nearest default-made and assigned was stored twice).
  const Nearest nearest =
      parameters.kind == CurvedShapeParameters::Kind::cylinder ? cylinder_nearest(local, r, h)
      : parameters.kind == CurvedShapeParameters::Kind::cone   ? cone_nearest(local, r, h)
                                                               : ellipsoid_nearest(local, radii);
  // A point inside is answered for a signed distance only (the searches prove an overlap for the
  // other goals): by the penetration solver, where no closed form below settles it.
  if (nearest.inside && goal != Goal::signed_distance) return false;
  const auto penetration = [&] {
    answer = exact_penetration(pair, max_iterations, pair.b.offset() - pair.a.offset(),
                               std::numeric_limits<Scalar>::infinity());
    answer.intersection_proven = answer.upper + kFrameRounding < 0;
    return true;
  };
  if (!(nearest.normal.squaredNorm() > 0)) return nearest.inside && penetration();
  // The witness on the shape: the nearest point itself (a cylinder's: from the closed form's units
  // to the frame's at once, both powers of two, then turned and moved as FramedBody::placed_point
  // does), or the combination of its support points, found without numbering them among the
  // shape's points (weights over a curved body's points are never reported, so the shape's side
  // has none). The point's weights are those of each support point.
  std::array<Scalar, ConvexWeights::kSparseCapacity> weights{1, 0, 0, 0};
  int size = 1;
  Vector3 witness;
  if (nearest.direct) {
    const Vector3 scaled = times_power_of_two(nearest.point, unit - shape.exponent());
    witness = shape.rotated() ? Vector3(shape.rotation() * scaled + shape.offset())
                              : Vector3(scaled + shape.offset());
  } else {
    const Vector3 first_local = shape.curved_local_support(nearest.first);
    witness = shape.placed_point(first_local);
    if (nearest.weight < 1) {
      const Vector3 second = shape.placed_point(second_support(shape, nearest, first_local));
      if (second != witness) {
        weights = {nearest.weight, 1 - nearest.weight, 0, 0};
        size = 2;
        witness = nearest.weight * witness + (1 - nearest.weight) * second;
      }
    }
  }
  answer.point_a = curved_a ? witness : p;
  answer.point_b = curved_a ? p : witness;
  if (nearest.inside) {
    // The depth the shape's closed form proves (SupportFunction::depth_of, with the frame's
    // rounding: curved_depth.hpp) bounds the signed distance above, as the penetration solver's
    // proof; the separation along the nearest surface's normal below, as outside.
    const Scalar depth = closed_form_depth(pair.a, pair.b).depth;
    if (!(depth > 0)) return penetration();
    answer.upper = -depth;
    answer.intersection_proven = answer.upper + kFrameRounding < 0;
  } else {
    answer.upper = (answer.point_b - answer.point_a).norm();
  }
  (curved_a ? answer.weights_b : answer.weights_a) =
      ConvexWeights(point.size(), {0, 0, 0, 0}, weights, size);
  // The normal in the frame, from A to B.
  Vector3 normal = shape.rotated() ? Vector3(shape.rotation() * nearest.normal) : nearest.normal;
  normal.normalize();
  if (!curved_a) normal = -normal;
  // The separation along the normal: the point's height against the shape's support value along
  // it (outward from the shape), `m . o + 2^-e h(R^T m)` for the offset o and the support h of
  // the shape's own frame (support_value), exact for the placed shape whatever R. Its rounding,
  // a few roundoffs of the frame's sizes (l's, support_value's, the dot products'), is within
  // kFrameRounding, as a placed support point's height is; the pair's support error, which a
  // support point may fall short by, is taken off all the same (rounded_lower). A support point
  // placed and measured was some 130 instructions of a ball-cylinder query.
  const Vector3 outward = curved_a ? normal : Vector3(-normal);
  const Scalar top =
      outward.dot(shape.offset()) +
      times_power_of_two(
          support_value(parameters.kind, r, h, radii, shape.local_direction(outward)),
          unit - shape.exponent());
  answer.lower = curved_a ? normal.dot(p) - top : -top - normal.dot(p);
  answer.direction = normal;
  answer.iterations = 1;
  answer.evaluations = size + 1;
  const RoundedBounds rounded = rounded_bounds(pair, answer.lower, answer.upper);
  if (!goal_reached(pair, goal, rounded, false)) return nearest.inside && penetration();
  answer.rounded = rounded;
  return true;
}

}  // namespace swarmcollide::detail
