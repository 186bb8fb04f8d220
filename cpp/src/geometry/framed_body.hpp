// The working frame of a query and the bodies placed in it; private to the library's sources.
#pragma once

#include <limits>

#include "swarmcollide/geometry/convex_polyhedron.hpp"
#include "swarmcollide/geometry/pose.hpp"
#include "swarmcollide/types.hpp"

namespace swarmcollide::detail {

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

  Scalar length_to_world(Scalar length) const;
  Vector3 point_to_world(const Vector3& p) const;
};

/// A bound on the rounding of a separation `n . (y - x)` or of a distance `|y - x|` computed from
/// frame coordinates (each of magnitude at most 1), in frame units. Each coordinate carries a
/// few units of rounding from the translation, the scaling (exact) and the rotation, and a dot
/// product a few more; 64 epsilons covers them with room to spare.
inline constexpr Scalar kFrameRounding = 64 * std::numeric_limits<Scalar>::epsilon();

/// A body under a pose, seen in a frame: point i is at `rotation * (x_i - c) / 2^e + offset`,
/// where c is the centre of the body's own bounding box. Support queries are answered in the
/// body's own frame (`rotation^T d`), so moving a body never touches its points or its hull.
class FramedBody {
 public:
  FramedBody(const ConvexPolyhedron& body, const Pose& pose, const Frame& frame);

  const ConvexPolyhedron& body() const { return *body_; }
  int size() const { return body_->size(); }
  const Hull& hull() const { return body_->hull(); }

  /// Point i of the body in the frame.
  Vector3 vertex(int i) const {
    const Vector3 local = scaled(body_->vertices().row(i).transpose() - body_centre_);
    return rotated_ ? Vector3(rotation_ * local + offset_) : Vector3(local + offset_);
  }
  /// A frame direction in the body's own frame (support points do not depend on the scale).
  Vector3 local_direction(const Vector3& d) const {
    return rotated_ ? Vector3(rotation_.transpose() * d) : d;
  }
  /// Index of a point farthest along frame direction `d` (see ConvexPolyhedron::support_index).
  int support_index(const Vector3& d) const { return body_->support_index(local_direction(d)); }
  int support_index(const Vector3& d, int start) const {
    return body_->support_index(local_direction(d), start);
  }
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
  Vector3 scaled(const Vector3& v) const { return v * scale_high_ * scale_low_; }

  const ConvexPolyhedron* body_;
  Matrix3 rotation_;
  bool rotated_;
  Vector3 body_centre_;
  Vector3 offset_;
  int exponent_;
  // 2^-exponent as two factors, each representable even for the most extreme exponents.
  Scalar scale_high_;
  Scalar scale_low_;
};

/// Two bodies in their common frame, with the query's tolerance in frame units.
struct FramedPair {
  Frame frame;
  FramedBody a;
  FramedBody b;
  /// Absolute tolerance in the frame: the relative tolerance times `frame.size`.
  Scalar tolerance;
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

}  // namespace swarmcollide::detail
