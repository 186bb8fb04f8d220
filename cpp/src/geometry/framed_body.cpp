#include "framed_body.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <typeinfo>
#include <utility>
#include <vector>

#include "curved_supports.hpp"
#include "framed_curved_support.hpp"
#include "normalise.hpp"
#include "pose_check.hpp"

namespace swarmcollide::detail {

namespace {

// Largest component first, so vectors with components near the largest double have a norm.
Scalar robust_norm(const Vector3& v) {
  const Scalar largest = v.cwiseAbs().maxCoeff();
  return largest > 0 ? largest * (v / largest).norm() : 0;
}

[[noreturn]] void refuse_placement(const char* name) {
  throw std::invalid_argument(std::string(name) +
                              " is placed beyond the double range (1.8e308): its position is "
                              "not representable");
}

// Where the centre of the body's box lands under the pose (`turned`: its rotation is not the
// identity, whose product is skipped). Inline, its error out of line: a batch row's distance
// takes 19 instructions fewer than with the two calls out of line.
inline Vector3 world_centre(const ConvexPolyhedron& body, const Pose& pose, bool turned,
                            const char* name) {
  const Vector3 centre = turned ? Vector3(pose.rotation * body.bounds().centre + pose.translation)
                                : Vector3(body.bounds().centre + pose.translation);
  if (!finite_entries(centre)) refuse_placement(name);
  return centre;
}

// A curved body's support error in a frame of exponent `exponent` (its share of
// FramedPair::support_error), for unit directions: SupportFunction's bound on the outer radius,
// which bounds.radius holds (0 for a polyhedron, whose factor is 0 and radius finite).
Scalar curved_support_error(const ConvexPolyhedron& body, int exponent) {
  return body.support_error_per_radius() * times_power_of_two(body.bounds().radius, -exponent) *
         (1 + 16 * kRoundoff);
}

// The exact type of `shape` among curved_supports.hpp's, once per framed body. The type_info
// objects are compared by address first: a shape made in the library has its type's one object,
// and where the addresses differ, type_info's == compares the names as strings (two string
// comparisons before a cone's match, 73 instructions a cone's framing, one before an
// ellipsoid's); a type none of them matches by address is compared by name after all.
CurvedKind exact_kind(const SupportFunction& shape) {
  const std::type_info& type = typeid(shape);
  if (&type == &typeid(CylinderSupport)) return CurvedKind::cylinder;
  if (&type == &typeid(EllipsoidSupport)) return CurvedKind::ellipsoid;
  if (&type == &typeid(ConeSupport)) return CurvedKind::cone;
  if (type == typeid(CylinderSupport)) return CurvedKind::cylinder;
  if (type == typeid(EllipsoidSupport)) return CurvedKind::ellipsoid;
  if (type == typeid(ConeSupport)) return CurvedKind::cone;
  return CurvedKind::other;
}

}  // namespace

// Inline in a pair's framing (the FramedBody constructor): called, it made the curved searches'
// queries 17-23 instructions longer.
[[gnu::always_inline]] inline void FramedBody::start_support_points(
    const ConvexPolyhedron& other) {
  // The cache of the body's own points is made once per body and copied: hashing them again
  // was most of what framing a curved body cost. Against a single point (a ball's core) a
  // closed form answers from the support function alone (point_against_curved): the body
  // reads its own points, and takes a copy at its first new support point only
  // (add_to_own_cache). Against any other body a search finds new points at once, and the
  // copy is taken here, where taking it cost the searches 30-50 instructions fewer a body.
  const ConvexPolyhedron& body = *body_;
  const SupportCache& start = body.derived<SupportCache>(
      [&body] { return SupportCache::sealed(body.centred_vertices()); });
  found_ = other.size() == 1 ? SharedSupportCache::reading(start) : SharedSupportCache(start);
  vertices_ = &found_->points();
}

// start_support_points for KeptPair::frame, out of line: inlined into it (as place is), its
// branches made every polytope row 9 instructions longer (swarmcollide-thread-scaling count).
[[gnu::noinline]] void FramedBody::restart_support_points(const ConvexPolyhedron& other) {
  start_support_points(other);
}

// Inlined into its two callers here, the constructor (every single query frames its pair through
// it) and KeptPair::frame (place): called out of line it made every query 46 instructions longer
// (callgrind_query.py).
[[gnu::always_inline]] inline void FramedBody::place_pose(const Pose& pose, bool rotated,
                                                          const Vector3& world_centre,
                                                          const Frame& frame) {
  rotation_ = pose.rotation;
  rotated_ = rotated;
  // A batch's rows mostly share their frame's exponent: its scale is kept then.
  if (frame.exponent != exponent_) {
    exponent_ = frame.exponent;
    const int half = -exponent_ / 2;
    scale_high_ = power_of_two(half);
    scale_low_ = power_of_two(-exponent_ - half);
  }
  offset_ = times_power_of_two(Vector3(world_centre - frame.centre), -exponent_);
}

[[gnu::always_inline]] inline void FramedBody::place(const Pose& pose, bool rotated,
                                                     const Vector3& world_centre,
                                                     const Frame& frame,
                                                     const ConvexPolyhedron& other) {
  place_pose(pose, rotated, world_centre, frame);
  if (curved_) restart_support_points(other);
}

// Inlined into frame_turned_pair's framing, its only caller: called out of line it made every
// query 40 instructions longer (callgrind_query.py).
[[gnu::always_inline]] inline FramedBody::FramedBody(const ConvexPolyhedron& body,
                                                     const Pose& pose, bool rotated,
                                                     const Vector3& world_centre,
                                                     const Frame& frame,
                                                     const ConvexPolyhedron& other)
    : body_(&body),
      vertices_(&body.centred_vertices()),
      hull_(nullptr),
      given_(nullptr),
      in_frame_(false) {
  // Small bodies are scanned whole: their hull points are every point (hull_points).
  if (body.size() > kHillClimbingThreshold) {
    const HullPoints& read = body.hull_points();
    if (!read.every_point) {
      vertices_ = &read.centred;
      hull_ = &read.hull;
      given_ = &read;
    } else {
      // The body's own hull, held here: each climb asked the body for it (a call and an atomic
      // load, 8 to 9 times a distance row of 260-vertex bodies).
      hull_ = &body.hull();
    }
  }
  if (const SupportFunction* shape = body.curved()) {
    curved_ = shape;
    curved_kind_ = exact_kind(*shape);
    hull_ = nullptr;
    given_ = nullptr;
  } else if (vertices_ == &body.centred_vertices()) {
    columns_ = body.centred_columns();
  }
  place_pose(pose, rotated, world_centre, frame);
  if (curved_) start_support_points(other);
}

int FramedBody::curved_support(const Vector3& local) const { return inline_curved_support(local); }

Vector3 FramedBody::curved_local_support(const Vector3& local) const {
  // The coordinates the cache would store (-0 + 0 = +0).
  return use_curved_support(local,
                            [](const Vector3& point) { return Vector3(point + Vector3::Zero()); });
}

int FramedBody::add_point(const Vector3& frame_point) const {
  const Vector3 turned = local_direction(frame_point - offset_);
  Vector3 local;
  for (int k = 0; k < 3; ++k) local(k) = times_power_of_two(turned(k), exponent_);
  return add_support_point(local);
}

void FramedBody::own_support_points() const {
  found_.own();
  vertices_ = &found_->points();
}

int FramedBody::add_to_own_cache(const Vector3& p, std::size_t slot) const {
  own_support_points();
  return found_->add_new(p, slot);
}

const VertexMatrix* FramedBody::shared_points() const {
  if (curved_ && found_->is_sealed()) own_support_points();
  return vertices_;
}

// `vertices_` is declared before `found_`: shared_points() has given `body` its own cache before
// `found_` copies the handle to it.
FramedBody::FramedBody(const FramedBody& body)
    : body_(body.body_),
      vertices_(body.shared_points()),
      hull_(body.hull_),
      given_(body.given_),
      in_frame_(body.in_frame_),
      rotation_(body.rotation_),
      rotated_(body.rotated_),
      curved_kind_(body.curved_kind_),
      offset_(body.offset_),
      exponent_(body.exponent_),
      scale_high_(body.scale_high_),
      scale_low_(body.scale_low_),
      curved_(body.curved_),
      found_(body.found_),
      columns_(body.columns_) {}

FramedBody::FramedBody(const VertexMatrix& points, const Hull& hull)
    : body_(nullptr),
      vertices_(&points),
      hull_(&hull),
      given_(nullptr),
      in_frame_(true),
      rotation_(Matrix3::Identity()),
      rotated_(false),
      offset_(Vector3::Zero()),
      exponent_(0),
      scale_high_(1),
      scale_low_(1) {}

// A placed point is p_i = fl(R q_i + o), q_i = 2^-e x_i, and the scan compares g_i =
// fl(fl(R^T d) . x_i). With the reach r >= |o| + |q_i| (the frame holds the body, so r <= 1
// up to rounding): |p_i - (R q_i + o)| <= 5.2u |q_i| + 1.8u r (a 3-term product per
// coordinate, then the sum); fl(R^T d) is within 5.2u |d| of R^T d, which moves d . R q_i by
// 5.2u |q_i|; and 2^-e g_i is within 3.1u |q_i| of 2^-e fl(R^T d) . x_i. So every d . p_i is
// 2^-e g_i + d . o to within 15.3u r, and the scan's point is within 30.6u r of the highest;
// the computed heights add what separation_margin covers. 64u r, with r rounded up, doubles it.
// Computed when asked (the penetration solver's margins), not when a body is framed: most queries
// never ask.
Scalar FramedBody::scan_shortfall() const {
  if (in_frame_) return 0;
  const Scalar radius = times_power_of_two(body_->bounds().radius, -exponent_);
  const Scalar reach = offset_.norm() + radius * (1 + 16 * kRoundoff);
  return 64 * kRoundoff * reach * (1 + 16 * kRoundoff);
}

void FramedBody::points(VertexMatrix& out) const {
  out.resize(size(), 3);
  for (int i = 0; i < size(); ++i) out.row(i) = vertex(i).transpose();
}

void FramedBody::given_points(VertexMatrix& out) const {
  if (!given_) return points(out);
  const VertexMatrix& all = body_->centred_vertices();
  out.resize(all.rows(), 3);
  for (Eigen::Index i = 0; i < all.rows(); ++i) out.row(i) = placed(all.row(i).transpose());
}

ConvexWeights FramedBody::given_weights(ConvexWeights weights) const {
  // A curved body's points are this query's support points: weights over them mean nothing to
  // the caller.
  if (curved_) return ConvexWeights();
  if (!given_ || weights.count() == body_->size()) return weights;
  const std::vector<int>& given = given_->indices;
  std::array<int, ConvexWeights::kSparseCapacity> index{};
  std::array<Scalar, ConvexWeights::kSparseCapacity> weight{};
  int stored = 0;
  weights.for_each([&](int, Scalar) { ++stored; });
  if (stored <= ConvexWeights::kSparseCapacity) {
    int k = 0;
    weights.for_each([&](int i, Scalar w) {
      index[k] = given[i];
      weight[k++] = w;
    });
    return ConvexWeights(body_->size(), index, weight, stored);
  }
  VectorX dense = VectorX::Zero(body_->size());
  weights.for_each([&](int i, Scalar w) { dense(given[i]) += w; });
  return ConvexWeights(std::move(dense));
}

namespace {

// Everything of a FramedPair but its bodies, for bodies whose boxes' centres land at `centre_a`
// and `centre_b` (world_centre).
struct PairFrame {
  Frame frame;
  Scalar tolerance;
  Scalar radius_a;
  Scalar radius_b;
  Scalar support_error;
};

[[gnu::always_inline]] inline PairFrame pair_frame(const ConvexPolyhedron& a,
                                                  const Vector3& centre_a,
                                                  const ConvexPolyhedron& b,
                                                  const Vector3& centre_b,
                                                  Scalar relative_tolerance) {
  Frame frame;
  // Halves first: the sum and difference of two coordinates near the largest double overflow.
  frame.centre = centre_a / 2 + centre_b / 2;
  const Scalar extent =
      robust_norm(centre_b / 2 - centre_a / 2) + std::max(a.bounds().radius, b.bounds().radius);
  if (!std::isfinite(extent)) {
    throw std::invalid_argument(
        "the bodies are farther apart than the double range allows (their extent exceeds "
        "1.8e308): distances between them are not representable; use a larger unit of length");
  }
  frame.exponent = exponent_above(extent);
  frame.size = 2 * times_power_of_two(extent, -frame.exponent);
  // The extent counts the rounding (it is in the bounds' radius), so the frame holds the rounded
  // bodies and the tolerance is relative to their size.
  const Scalar support_error =
      a.curved() || b.curved() ? (curved_support_error(a, frame.exponent) +
                                  curved_support_error(b, frame.exponent)) *
                                     (1 + 4 * kRoundoff)
                               : 0;
  return {frame, relative_tolerance * frame.size,
          times_power_of_two(a.radius(), -frame.exponent),
          times_power_of_two(b.radius(), -frame.exponent), support_error};
}

// frame_turned_pair, inlined into frame_pair too: the call between them, with its arguments and
// its return, was 25 instructions of every query.
[[gnu::always_inline]] inline FramedPair framed_pair(const ConvexPolyhedron& a,
                                                     const Pose& pose_a, bool turned_a,
                                                     const ConvexPolyhedron& b,
                                                     const Pose& pose_b, bool turned_b,
                                                     Scalar relative_tolerance) {
  const Vector3 centre_a = world_centre(a, pose_a, turned_a, "a");
  const Vector3 centre_b = world_centre(b, pose_b, turned_b, "b");
  const PairFrame f = pair_frame(a, centre_a, b, centre_b, relative_tolerance);
  return {f.frame,
          FramedBody(a, pose_a, turned_a, centre_a, f.frame, b),
          FramedBody(b, pose_b, turned_b, centre_b, f.frame, a),
          f.tolerance,
          f.radius_a,
          f.radius_b,
          f.support_error,
          f.radius_a > 0 || f.radius_b > 0 || f.support_error > 0};
}

}  // namespace

FramedPair frame_turned_pair(const ConvexPolyhedron& a, const Pose& pose_a, bool turned_a,
                             const ConvexPolyhedron& b, const Pose& pose_b, bool turned_b,
                             Scalar relative_tolerance) {
  return framed_pair(a, pose_a, turned_a, b, pose_b, turned_b, relative_tolerance);
}

const FramedPair& KeptPair::frame(const ConvexPolyhedron& a, const Pose& pose_a, bool turned_a,
                                  const ConvexPolyhedron& b, const Pose& pose_b, bool turned_b,
                                  Scalar relative_tolerance) {
  if (!pair_ || &pair_->a.body() != &a || &pair_->b.body() != &b) {
    pair_.emplace(frame_turned_pair(a, pose_a, turned_a, b, pose_b, turned_b, relative_tolerance));
    return *pair_;
  }
  // Every field that the poses decide is written, once nothing more can throw.
  const Vector3 centre_a = world_centre(a, pose_a, turned_a, "a");
  const Vector3 centre_b = world_centre(b, pose_b, turned_b, "b");
  const PairFrame f = pair_frame(a, centre_a, b, centre_b, relative_tolerance);
  FramedPair& pair = *pair_;
  pair.frame = f.frame;
  pair.a.place(pose_a, turned_a, centre_a, f.frame, b);
  pair.b.place(pose_b, turned_b, centre_b, f.frame, a);
  pair.tolerance = f.tolerance;
  pair.radius_a = f.radius_a;
  pair.radius_b = f.radius_b;
  pair.support_error = f.support_error;
  pair.adjusted = f.radius_a > 0 || f.radius_b > 0 || f.support_error > 0;
  return pair;
}

FramedPair frame_pair(const ConvexPolyhedron& a, const Pose& pose_a, const ConvexPolyhedron& b,
                      const Pose& pose_b, Scalar relative_tolerance) {
  const PoseTurns turned = validated_turns(pose_a, pose_b);
  return framed_pair(a, pose_a, turned.a, b, pose_b, turned.b, relative_tolerance);
}

FramedPair frame_validated_pair(const ConvexPolyhedron& a, const Pose& pose_a,
                                const ConvexPolyhedron& b, const Pose& pose_b,
                                Scalar relative_tolerance) {
  return frame_turned_pair(a, pose_a, !pose_a.has_identity_rotation(), b, pose_b,
                           !pose_b.has_identity_rotation(), relative_tolerance);
}

}  // namespace swarmcollide::detail
