#include "core_closed_form.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "../geometry/nearest_on_segments.hpp"
#include "../geometry/normalise.hpp"
#include "../queries/verdict.hpp"

namespace swarmcollide::detail {

namespace {

// A point of a core in the frame, as the combination `weight` of its points `index`.
struct CorePoint {
  Vector3 point = Vector3::Zero();
  std::array<int, ConvexWeights::kSparseCapacity> index{0, 0, 0, 0};
  std::array<Scalar, ConvexWeights::kSparseCapacity> weight{1, 0, 0, 0};
  int size = 1;
};

Scalar clamped(Scalar x) { return std::clamp(x, Scalar(0), Scalar(1)); }

// `c` the point `1 - s` of a segment's end `p0` and `s` of its end `p1` (one point when the core
// has one: `p1` is `p0`), its ends themselves at s = 0 and 1. Written in place: returned, the
// point and its weights were copied out (44 instructions of a ball's query).
void on_segment(int size, const Vector3& p0, const Vector3& p1, Scalar s, CorePoint& c) {
  if (size == 1 || s == 0) {
    c.point = p0;
  } else if (s == 1) {
    c.point = p1;
    c.index[0] = 1;
  } else {
    c.point = (1 - s) * p0 + s * p1;
    c.index = {0, 1, 0, 0};
    c.weight = {1 - s, s, 0, 0};
    c.size = 2;
  }
}

// The half extents of `body` when its eight points are the corners of a box in its own frame
// (centred on that box: a Box's, exactly), else false; `corner[c]` the point at the corner whose
// bit k is set when its coordinate k is positive.
bool box_extents(const FramedBody& body, Vector3& half, std::array<int, 8>& corner) {
  const VertexMatrix& x = body.local_points();
  half = x.row(0).cwiseAbs().transpose();
  if (!(half.minCoeff() > 0)) return false;
  unsigned corners = 0;
  for (int i = 0; i < 8; ++i) {
    unsigned bits = 0;
    for (int k = 0; k < 3; ++k) {
      if (std::abs(x(i, k)) != half(k)) return false;
      bits |= unsigned(x(i, k) > 0) << k;
    }
    corners |= 1u << bits;
    corner[bits] = i;
  }
  return corners == 0xFFu;
}

// The nearest point of the box `body` (half extents `half`, corners `corner`) to the frame point
// `p`, as the combination of the corners of the face, edge or corner it lies on: the point clamped
// to the extents in the box's own frame, each free coordinate the combination of the two faces
// across its axis. False for a point inside the box or on it.
bool nearest_on_box(const FramedBody& body, const Vector3& half, const std::array<int, 8>& corner,
                    const Vector3& p, CorePoint& nearest) {
  const Vector3 turned = body.local_direction(p - body.offset());
  Vector3 clamp;
  unsigned clamped_bits = 0;  // the clamped axes' side: bit k set at +half(k)
  std::array<int, 3> free_axes{};
  int free = 0;
  for (int k = 0; k < 3; ++k) {
    const Scalar local = times_power_of_two(turned(k), body.exponent());
    if (local > half(k)) {
      clamp(k) = half(k);
      clamped_bits |= 1u << k;
    } else if (local < -half(k)) {
      clamp(k) = -half(k);
    } else {
      clamp(k) = local;
      free_axes[free++] = k;
    }
  }
  if (free == 3) return false;
  nearest.point = body.placed_point(clamp);
  // Two free axes at most: four corners at most weigh, each the product of its sides' shares.
  nearest.size = 0;
  for (unsigned sides = 0; sides < (1u << free); ++sides) {
    unsigned bits = clamped_bits;
    Scalar weight = 1;
    for (int j = 0; j < free; ++j) {
      const int k = free_axes[j];
      const Scalar upper_share = clamped((1 + clamp(k) / half(k)) / 2);
      const bool upper = (sides >> j) & 1u;
      bits |= unsigned(upper) << k;
      weight *= upper ? upper_share : 1 - upper_share;
    }
    if (weight > 0) {
      nearest.index[nearest.size] = corner[bits];
      nearest.weight[nearest.size] = weight;
      ++nearest.size;
    }
  }
  return true;
}

// The points of two cores of one or two points each, placed in the frame once: the closed form
// and the separation read them both (placing them again was 20 instructions a point).
struct PlacedCores {
  std::array<Vector3, 2> a;
  std::array<Vector3, 2> b;
};

// The nearest points of the cores of `pair`, or false where no closed form here chooses them;
// `cores` holds the cores' placed points when neither is a box.
bool nearest_points(const FramedPair& pair, CorePoint& on_a, CorePoint& on_b,
                    PlacedCores& cores) {
  const int size_a = pair.a.size();
  const int size_b = pair.b.size();
  if (size_a == 8 || size_b == 8) {
    const bool box_a = size_a == 8;
    const FramedBody& box = box_a ? pair.a : pair.b;
    Vector3 half;
    std::array<int, 8> corner;
    if (!box_extents(box, half, corner)) return false;
    const Vector3 p = (box_a ? pair.b : pair.a).vertex(0);
    if (!nearest_on_box(box, half, corner, p, box_a ? on_a : on_b)) return false;
    (box_a ? on_b : on_a).point = p;
    return true;
  }
  const Vector3& p0 = cores.a[0] = pair.a.vertex(0);
  const Vector3& p1 = cores.a[1] = size_a == 2 ? pair.a.vertex(1) : p0;
  const Vector3& q0 = cores.b[0] = pair.b.vertex(0);
  const Vector3& q1 = cores.b[1] = size_b == 2 ? pair.b.vertex(1) : q0;
  // Two points are their own nearest points (the clamped form's s = t = 0, without its products).
  if (size_a == 1 && size_b == 1) {
    on_a.point = p0;
    on_b.point = q0;
    return true;
  }
  Scalar s;
  Scalar t;
  if (size_a == 1) {
    // A ball against a capsule: the clamped form's value for a first segment of length zero
    // (s = 0, t the clamped projection), without the products of that segment.
    const Vector3 d2 = q1 - q0;
    const Scalar e = d2.squaredNorm();
    const Scalar f = d2.dot(p0 - q0);
    on_a.point = p0;
    on_segment(size_b, q0, q1, e > 0 ? clamped(f / e) : 0, on_b);
    return true;
  }
  // Below sin^2 2^-40 of the angle between them, the lines' nearest points are ill-conditioned.
  nearest_on_segments(p0, p1, q0, q1, 0x1p-40, s, t);
  on_segment(size_a, p0, p1, s, on_a);
  on_segment(size_b, q0, q1, t, on_b);
  return true;
}

// exact_separation's value, `min_j n.y_j - max_i n.x_i` from the heights its scans compare, for
// bodies of eight points at most: every height, without a scan's call for each body (65
// instructions each for one point).
Scalar separation_of_all(const FramedPair& pair, const Vector3& n) {
  Scalar top_a = pair.a.height(0, n);
  for (int i = 1; i < pair.a.size(); ++i) top_a = std::max(top_a, pair.a.height(i, n));
  Scalar bottom_b = pair.b.height(0, n);
  for (int j = 1; j < pair.b.size(); ++j) bottom_b = std::min(bottom_b, pair.b.height(j, n));
  return bottom_b - top_a;
}

// separation_of_all for cores of one or two points each, from their points as `cores` placed
// them (FramedBody::height's value for a point already placed).
Scalar separation_of_cores(const FramedPair& pair, const PlacedCores& cores, const Vector3& n) {
  Scalar top_a = pair.a.height(0, cores.a[0], n);
  if (pair.a.size() == 2) top_a = std::max(top_a, pair.a.height(1, cores.a[1], n));
  Scalar bottom_b = pair.b.height(0, cores.b[0], n);
  if (pair.b.size() == 2) bottom_b = std::min(bottom_b, pair.b.height(1, cores.b[1], n));
  return bottom_b - top_a;
}

}  // namespace

bool core_closed_form(const FramedPair& pair, Goal goal, Answer& answer) {
  CorePoint on_a;
  CorePoint on_b;
  PlacedCores cores;
  if (!small_cores(pair) || !nearest_points(pair, on_a, on_b, cores)) return false;
  const Vector3 between = on_b.point - on_a.point;
  const Scalar distance = between.norm();
  // Cores that touch or overlap have no normal here: the search proves their overlap.
  if (!(distance > 0)) return false;
  const Vector3 normal = between / distance;
  const bool box = pair.a.size() == 8 || pair.b.size() == 8;
  const Scalar lower =
      box ? separation_of_all(pair, normal) : separation_of_cores(pair, cores, normal);
  // Polyhedra: no support error, so the radii alone shift the bounds.
  const RoundedBounds rounded = shifted_bounds(pair, lower, distance);
  if (!goal_reached(pair, goal, rounded, false)) return false;
  answer.upper = distance;
  answer.lower = lower;
  answer.rounded = rounded;
  answer.point_a = on_a.point;
  answer.point_b = on_b.point;
  answer.weights_a = ConvexWeights(pair.a.size(), on_a.index, on_a.weight, on_a.size);
  answer.weights_b = ConvexWeights(pair.b.size(), on_b.index, on_b.weight, on_b.size);
  answer.direction = normal;
  answer.iterations = 1;
  answer.evaluations = 1;
  return true;
}

}  // namespace swarmcollide::detail
