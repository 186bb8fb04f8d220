#include "swarmcollide/geometry/placed_shape.hpp"

#include <cmath>
#include <limits>
#include <memory>
#include <utility>

#include "unit_direction.hpp"

namespace swarmcollide {

namespace {

constexpr Scalar kRoundoff = 0x1p-53;
// Support points are pulled towards the shape's centre by this factor after the rotation (as
// shapes.cpp's are after their own rounding), so the rotated point, rounded, stays in the shape.
constexpr Scalar kInward = 1 - 0x1p-50;
// A valid pose's rotation is orthogonal to 1e-9 (kRotationTolerance): it stretches no vector by
// more than this factor.
constexpr Scalar kStretch = 1 + 1e-8;

// A curved shape moved by a rotation R, its origin landing at `offset` in the placed body's frame
// (centred on its box). Its support point along d is `R s(R^T d) + offset`, s the shape's. The
// rounding adds to the shape's shortfall: R^T d is within 5.3u |d| of the exact direction, which
// costs twice that of the outer radius (10.6u); R s is within 5.3u |s|; the pull 8u; the sum with
// the offset u of the outer radius: under 25u of `outer_radius() |d|`, taken as 32.
class PlacedSupport final : public SupportFunction {
 public:
  PlacedSupport(std::shared_ptr<const SupportFunction> shape, const Pose& pose)
      : shape_(std::move(shape)),
        pose_(pose),
        offset_(Vector3::Zero()),
        // 3 max |R^T R - I| bounds its 2-norm e, and R^-1 - R^T and the stretch of R by about e.
        skew_(3 * (pose.rotation.transpose() * pose.rotation - Matrix3::Identity())
                      .cwiseAbs()
                      .maxCoeff() +
              16 * kRoundoff) {}

  /// Where the shape's origin lands relative to the placed body's box centre; set once that box
  /// is known (it is found from the support points relative to the origin).
  void set_offset(const Vector3& offset) { offset_ = offset; }
  /// The shape's support point along `direction`, rotated, before the offset.
  Vector3 turned_support(const Vector3& direction) const {
    const Vector3 local = pose_.rotation.transpose() * direction;
    return Vector3(pose_.rotation * shape_->support(local)) * kInward;
  }

  Vector3 support(const Vector3& direction) const override {
    return turned_support(direction) + offset_;
  }
  // The offset's length without its squares, which overflow for offsets above 1e154 (a shape
  // of that size, posed, was refused as spanning more than the largest double) and vanish below
  // 1e-162 (the ball then left the offset out).
  Scalar outer_radius() const override {
    return (detail::robust_length(offset_) + shape_->outer_radius() * kStretch) * kStretch;
  }
  Scalar support_error_roundoffs() const override { return shape_->support_error_roundoffs() + 32; }
  Vector3 centroid() const override { return pose_.rotation * shape_->centroid() + offset_; }
  // The shape's own bound at the point turned back (R^T for R^-1, off by the skew), shrunk by
  // the skew (R may stretch the ball by as much), less the rounding of the turn.
  Scalar depth_of(const Vector3& p, Vector3& outward) const override {
    const Vector3 from_origin = p - offset_;
    Vector3 local_outward;
    const Scalar depth = shape_->depth_of(pose_.rotation.transpose() * from_origin, local_outward);
    const Vector3 turned = pose_.rotation * local_outward;
    outward = turned / turned.norm();
    const Scalar margin = 2 * skew_ * (detail::robust_length(from_origin) + shape_->outer_radius());
    return depth * (1 - skew_) - margin;
  }
  const char* name() const override { return shape_->name(); }
  CurvedShapeParameters parameters() const override {
    CurvedShapeParameters shape = shape_->parameters();
    shape.pose = pose_;
    shape.placed = true;
    return shape;
  }

 private:
  std::shared_ptr<const SupportFunction> shape_;
  // The shape's rotation, and where its origin lands in the body's frame (its translation).
  Pose pose_;
  Vector3 offset_;
  Scalar skew_;
};

// A ConvexPolyhedron built from a placed curved shape (its constructor is for shapes only).
class PlacedCurved : public ConvexPolyhedron {
 public:
  PlacedCurved(const VertexMatrix& centred, std::shared_ptr<const SupportFunction> shape,
               const Aabb& box)
      : ConvexPolyhedron(centred, std::move(shape), box) {}
};

ConvexPolyhedron placed_curved(const ConvexPolyhedron& body, const Pose& pose) {
  // The shape's frame is centred on the body's box: its origin lands at R c + t.
  const Pose shape_pose{pose.rotation, pose.rotation * body.bounds().centre + pose.translation};
  auto shape = std::make_shared<PlacedSupport>(body.curved_shared(), shape_pose);
  // The box through the support points along the axes, grown by their shortfall and by the
  // rounding of the origin's coordinates.
  const Scalar huge = std::numeric_limits<Scalar>::infinity();
  const Scalar reach = body.curved()->outer_radius() * kStretch;
  const Scalar shortfall = shape->support_error_roundoffs() * kRoundoff * reach;
  Aabb box;
  for (int k = 0; k < 3; ++k) {
    const Vector3 axis = Vector3::Unit(k);
    const Scalar origin = shape_pose.translation(k);
    const Scalar margin = shortfall + 4 * kRoundoff * (std::abs(origin) + reach);
    box.max(k) = std::nextafter(origin + shape->turned_support(axis)(k) + margin, huge);
    box.min(k) = std::nextafter(origin + shape->turned_support(-axis)(k) - margin, -huge);
  }
  shape->set_offset(shape_pose.translation - (box.min / 2 + box.max / 2));
  // Its points: the support points along the body's axes, points of the shape.
  VertexMatrix centred(6, 3);
  for (int k = 0; k < 6; ++k) {
    const Vector3 axis = (k % 2 ? -1.0 : 1.0) * Vector3::Unit(k / 2);
    centred.row(k) = shape->support(axis).transpose();
  }
  return PlacedCurved(centred, std::move(shape), box);
}

}  // namespace

ConvexPolyhedron placed(const ConvexPolyhedron& body, const Pose& pose) {
  if (body.curved()) return placed_curved(body, pose);
  VertexMatrix points = body.vertices() * pose.rotation.transpose();
  points.rowwise() += pose.translation.transpose();
  return ConvexPolyhedron(std::move(points), body.radius());
}

}  // namespace swarmcollide
