#include "core_closed_form.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "../detail/flatten.hpp"
#include "../geometry/curved_depth.hpp"
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

// The half extents of a body whose eight points `x` (in its own frame, centred on its box) are
// the corners of a box (centred on that box: a Box's, exactly), else false; `corner[c]` the point
// at the corner whose bit k is set when its coordinate k is positive.
bool box_extents(const VertexMatrix& x, Vector3& half, std::array<int, 8>& corner) {
  // A Box's points are its corners in that order (shapes.cpp): point i has coordinate k positive
  // when bit k of i is set. 24 comparisons confirm it without sorting the corners out (a third of
  // the instructions of the general reading below).
  half = x.row(7).transpose();
  if (half.minCoeff() > 0) {
    bool in_order = true;
    for (int i = 0; i < 7 && in_order; ++i) {
      for (int k = 0; k < 3; ++k) in_order &= x(i, k) == ((i >> k) & 1 ? half(k) : -half(k));
    }
    if (in_order) {
      corner = {0, 1, 2, 3, 4, 5, 6, 7};
      return true;
    }
  }
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

// A body's points read as a box's corners (box_extents).
struct BoxCorners {
  bool box = false;
  Vector3 half = Vector3::Zero();
  std::array<int, 8> corner{};
};

// box_extents of the points of `body` (eight, so its own: ConvexPolyhedron::centred_vertices),
// read once per body and kept with it (ConvexPolyhedron::derived): confirming the corners' order
// was some 94 instructions of every ball-box query, the look-up is about 25.
const BoxCorners& box_corners(const FramedBody& body) {
  return body.body().derived<BoxCorners>([&body] {
    BoxCorners read;
    read.box = box_extents(body.local_points(), read.half, read.corner);
    return read;
  });
}

// The point of the box `body` (half extents `half`, corners `corner`) at own-frame coordinates
// `clamp` on its boundary, as the combination of the corners of the face, edge or corner it lies
// on: the clamped axes at the sides `clamped_bits` (bit k set at +half(k)), each of the `free`
// axes `free_axes` the combination of the two faces across it.
void on_box(const FramedBody& body, const Vector3& half, const std::array<int, 8>& corner,
            const Vector3& clamp, unsigned clamped_bits, const std::array<int, 3>& free_axes,
            int free, CorePoint& nearest) {
  nearest.point = body.placed_point(clamp);
  // Two free axes at most: four corners at most weigh, each the product of its sides' shares
  // (each axis' computed once: per corner, the divisions were a tenth of a ball-box query's
  // closed form).
  std::array<Scalar, 3> upper_share{};
  for (int j = 0; j < free; ++j) {
    const int k = free_axes[j];
    upper_share[j] = clamped((1 + clamp(k) / half(k)) / 2);
  }
  nearest.size = 0;
  for (unsigned sides = 0; sides < (1u << free); ++sides) {
    unsigned bits = clamped_bits;
    Scalar weight = 1;
    for (int j = 0; j < free; ++j) {
      const bool upper = (sides >> j) & 1u;
      bits |= unsigned(upper) << free_axes[j];
      weight *= upper ? upper_share[j] : 1 - upper_share[j];
    }
    if (weight > 0) {
      nearest.index[nearest.size] = corner[bits];
      nearest.weight[nearest.size] = weight;
      ++nearest.size;
    }
  }
}

// The nearest point of the box `body` (half extents `half`, corners `corner`) to the point at
// `local` in its own frame (in_own_frame): the point clamped to the extents, on the face, edge or
// corner it lies on (on_box). False for a point inside the box or on it.
bool nearest_on_box(const FramedBody& body, const Vector3& half, const std::array<int, 8>& corner,
                    const Vector3& local, CorePoint& nearest) {
  Vector3 clamp;
  unsigned clamped_bits = 0;  // the clamped axes' side: bit k set at +half(k)
  std::array<int, 3> free_axes{};
  int free = 0;
  for (int k = 0; k < 3; ++k) {
    if (local(k) > half(k)) {
      clamp(k) = half(k);
      clamped_bits |= 1u << k;
    } else if (local(k) < -half(k)) {
      clamp(k) = -half(k);
    } else {
      clamp(k) = local(k);
      free_axes[free++] = k;
    }
  }
  if (free == 3) return false;
  on_box(body, half, corner, clamp, clamped_bits, free_axes, free, nearest);
  return true;
}

// The points of two cores of one or two points each, placed in the frame once: the closed form
// and the separation read them both (placing them again was 20 instructions a point).
struct PlacedCores {
  std::array<Vector3, 2> a;
  std::array<Vector3, 2> b;
};

// The nearest points of two cores of one or two points each (points and segments); `cores` holds
// their placed points.
void nearest_on_cores(const FramedPair& pair, CorePoint& on_a, CorePoint& on_b,
                      PlacedCores& cores) {
  const int size_a = pair.a.size();
  const int size_b = pair.b.size();
  const Vector3& p0 = cores.a[0] = size_a == 1 ? pair.a.single_vertex() : pair.a.vertex(0);
  const Vector3& p1 = cores.a[1] = size_a == 2 ? pair.a.vertex(1) : p0;
  const Vector3& q0 = cores.b[0] = size_b == 1 ? pair.b.single_vertex() : pair.b.vertex(0);
  const Vector3& q1 = cores.b[1] = size_b == 2 ? pair.b.vertex(1) : q0;
  // Two points are their own nearest points (the clamped form's s = t = 0, without its products).
  if (size_a == 1 && size_b == 1) {
    on_a.point = p0;
    on_b.point = q0;
    return;
  }
  if (size_a == 1) {
    // A ball against a capsule: the clamped form's value for a first segment of length zero
    // (s = 0, t the clamped projection), without the products of that segment.
    const Vector3 d2 = q1 - q0;
    const Scalar e = d2.squaredNorm();
    const Scalar f = d2.dot(p0 - q0);
    on_a.point = p0;
    on_segment(size_b, q0, q1, e > 0 ? clamped(f / e) : 0, on_b);
    return;
  }
  Scalar s;
  Scalar t;
  // Below sin^2 2^-40 of the angle between them, the lines' nearest points are ill-conditioned.
  nearest_on_segments(p0, p1, q0, q1, 0x1p-40, s, t);
  on_segment(size_a, p0, p1, s, on_a);
  on_segment(size_b, q0, q1, t, on_b);
}

// exact_separation's value, `min_j n.y_j - max_i n.x_i` from the heights its scans compare, for
// cores of one or two points each: every height, from the points as `cores` placed them
// (FramedBody::height's value for a point already placed), without a scan's call for each body
// (65 instructions each for one point).
Scalar separation_of_cores(const FramedPair& pair, const PlacedCores& cores, const Vector3& n) {
  Scalar top_a = pair.a.height(0, cores.a[0], n);
  if (pair.a.size() == 2) top_a = std::max(top_a, pair.a.height(1, cores.a[1], n));
  Scalar bottom_b = pair.b.height(0, cores.b[0], n);
  if (pair.b.size() == 2) bottom_b = std::min(bottom_b, pair.b.height(1, cores.b[1], n));
  return bottom_b - top_a;
}

// The greatest height along the unit frame direction `n` of the box `box` (half extents `half`)
// when `top`, else the least: its support value, `n . o +- sum_k 2^-e h_k |l_k|` for its offset o
// and `l = R^T n` (local_direction), which is exact for the placed box `R q + o`, q its scaled
// corners, whatever R. Computed, it is within 9.5u of the reach |o| + 2^-e |h| of that value: l_k
// is within 3.02u of (R^T n)_k (a 3-term dot product of a unit row), which moves the sum by 3.02u
// sum_k 2^-e h_k <= 5.3u 2^-e |h|; the sum of three products rounds by 3.02u 2^-e |h|, n . o by
// 3.02u |o|, the last addition by u of the reach. That is the rounding a scan of the placed
// corners' heights carries (each corner placed to 5.2u of its size plus 1.8u of the reach, its
// dot product 3u more; framed_body.cpp), inside kFrameRounding and separation_margin (64u of the
// coordinate bound). The heights of the corners that may hold the extreme, placed one by one,
// were 270 of a ball-box query's 2,040 instructions.
Scalar box_extreme_height(const FramedBody& box, const Vector3& half, const Vector3& n, bool top) {
  const Vector3 l = box.local_direction(n);
  const Scalar reach = times_power_of_two(
      half(0) * std::abs(l(0)) + half(1) * std::abs(l(1)) + half(2) * std::abs(l(2)),
      -box.exponent());
  const Scalar centre = box.offset().dot(n);
  return top ? centre + reach : centre - reach;
}

// The separation along the unit frame direction `n` of a point `p` (a ball's core, B when
// `box_a`) and a box (its half extents `half`): the point's height against the box's extreme one
// (box_extreme_height).
Scalar box_separation(const FramedPair& pair, bool box_a, const Vector3& half, const Vector3& p,
                      const Vector3& n) {
  const FramedBody& point = box_a ? pair.b : pair.a;
  const Scalar at_point = point.height(0, p, n);
  return box_a ? at_point - box_extreme_height(pair.a, half, n, true)
               : box_extreme_height(pair.b, half, n, false) - at_point;
}

// The answer from the nearest points `on_a` and `on_b` of cores that are apart, or false when
// they touch or its bounds leave `goal` unmet: the upper bound is their distance, the lower one
// `separation(normal)`, the separation along the normal between them. Inline in both callers
// (segments, a point and a box): its call cost the segments' queries 38 instructions.
template <typename Separation>
[[gnu::always_inline]] inline bool apart_answer(const FramedPair& pair, Goal goal,
                                                const CorePoint& on_a, const CorePoint& on_b,
                                                const Separation& separation, Answer& answer) {
  const Vector3 between = on_b.point - on_a.point;
  const Scalar distance = between.norm();
  // Cores that touch or overlap have no normal here: the search proves their overlap.
  if (!(distance > 0)) return false;
  const Vector3 normal = between / distance;
  const Scalar lower = separation(normal);
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

// A signed distance for a point (a ball's core) `centre` inside the box (`local` its own-frame
// coordinates, in_own_frame of `from_offset`, its difference from the box's offset; half extents
// `half`, corners `corner`), the box A when `box_a`: the point's depth is its least distance to a
// face, `min_k half(k) - |local(k)|`, along that face's normal. The upper bound is minus the depth
// that the frame's rounding leaves proven (depth_in_frame, as the curved shapes' closed forms
// prove theirs), the lower one the separation along the face's normal over every point less its
// rounding. False where the point is on the boundary to rounding, or the bounds are further apart
// than the tolerance: the search answers then.
bool inside_box_answer(const FramedPair& pair, bool box_a, const Vector3& half,
                       const std::array<int, 8>& corner, const Vector3& centre,
                       const Vector3& local, const Vector3& from_offset, Answer& answer) {
  const FramedBody& box = box_a ? pair.a : pair.b;
  int face = 0;
  Scalar least = half(0) - std::abs(local(0));
  for (int k = 1; k < 3; ++k) {
    const Scalar depth = half(k) - std::abs(local(k));
    if (depth < least) {
      least = depth;
      face = k;
    }
  }
  // The difference rounds by u of half(face) at most, and taking this bound off by u again.
  const Scalar framed = times_power_of_two(least - 4 * kRoundoff * half(face), -box.exponent());
  if (!(framed > 0)) return false;
  const Scalar depth =
      depth_in_frame(framed, rotation_skew(box), from_offset.norm(), box.scan_shortfall());
  if (!(depth > 0)) return false;
  Vector3 outward = box.rotated() ? Vector3(box.rotation().col(face)) : Vector3::Unit(face);
  outward.normalize();
  const bool upper_side = local(face) >= 0;
  if (!upper_side) outward = -outward;
  // From A to B: out of the box when it is A, into it when it is B.
  const Vector3 normal = box_a ? outward : Vector3(-outward);
  // The separation from the box's support value, less its rounding (separation_margin, as the
  // penetration solver's, which box_extreme_height's rounding and the centre's height are well
  // within: the box, and the centre in it, lie within the box's coordinate_bound).
  const Scalar lower = box_separation(pair, box_a, half, centre, normal) -
                       separation_margin(coordinate_bound(box));
  const RoundedBounds rounded = shifted_bounds(pair, lower, -depth);
  if (!goal_reached(pair, Goal::signed_distance, rounded, false)) return false;
  // The witness on the box: the point of the face straight out from the centre.
  Vector3 clamp = local;
  clamp(face) = upper_side ? half(face) : -half(face);
  CorePoint on_face;
  on_box(box, half, corner, clamp, unsigned(upper_side) << face,
         {(face + 1) % 3, (face + 2) % 3, 0}, 2, on_face);
  const ConvexWeights on_box_weights(box.size(), on_face.index, on_face.weight, on_face.size);
  const ConvexWeights at_centre(1, {0, 0, 0, 0}, {1, 0, 0, 0}, 1);
  answer.upper = -depth;
  answer.lower = lower;
  answer.rounded = rounded;
  answer.point_a = box_a ? on_face.point : centre;
  answer.point_b = box_a ? centre : on_face.point;
  answer.weights_a = box_a ? on_box_weights : at_centre;
  answer.weights_b = box_a ? at_centre : on_box_weights;
  answer.direction = normal;
  answer.intersection_proven = answer.upper + kFrameRounding < 0;
  answer.iterations = 1;
  answer.evaluations = 1;
  return true;
}

// A point (a ball's core) against a box: apart, from the nearest point on the box; inside, for a
// signed distance, from the nearest face (inside_box_answer).
bool ball_against_box(const FramedPair& pair, Goal goal, Answer& answer) {
  const bool box_a = pair.a.size() == 8;
  const FramedBody& box = box_a ? pair.a : pair.b;
  const BoxCorners& corners = box_corners(box);
  if (!corners.box) return false;
  const Vector3& half = corners.half;
  const std::array<int, 8>& corner = corners.corner;
  const Vector3 p = (box_a ? pair.b : pair.a).single_vertex();
  const Vector3 from_offset = p - box.offset();
  const Vector3 local = in_own_frame(box, from_offset);
  CorePoint on_a;
  CorePoint on_b;
  if (nearest_on_box(box, half, corner, local, box_a ? on_a : on_b)) {
    (box_a ? on_b : on_a).point = p;
    const auto separation = [&](const Vector3& n) {
      return box_separation(pair, box_a, half, p, n);
    };
    return apart_answer(pair, goal, on_a, on_b, separation, answer);
  }
  // The searches prove the other goals' overlaps.
  return goal == Goal::signed_distance &&
         inside_box_answer(pair, box_a, half, corner, p, local, from_offset, answer);
}

}  // namespace

// Flattened: FramedBody's placements and turns (the cores' points, the box's witness), called out
// of line, reload the pose at every call; inlined, a ball-box query took 150-170 instructions
// fewer when it still placed the box's corners one by one, the balls' and capsules' 8-21.
SWARMCOLLIDE_FLATTEN bool core_closed_form(const FramedPair& pair, Goal goal, Answer& answer) {
  if (!small_cores(pair)) return false;
  if (pair.a.size() == 8 || pair.b.size() == 8) return ball_against_box(pair, goal, answer);
  CorePoint on_a;
  CorePoint on_b;
  PlacedCores cores;
  nearest_on_cores(pair, on_a, on_b, cores);
  const auto separation = [&](const Vector3& n) { return separation_of_cores(pair, cores, n); };
  return apart_answer(pair, goal, on_a, on_b, separation, answer);
}

}  // namespace swarmcollide::detail
