#include "scene_body.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "../geometry/support.hpp"
#include "../geometry/unit_direction.hpp"

namespace swarmcollide::detail {

namespace {

constexpr Scalar kEpsilon = std::numeric_limits<Scalar>::epsilon();

// The norm of R' - R, for rotations R and R' (to the 1e-9 that poses are validated to): from the
// angle theta of R'^T R, |R' - R|_2 = 2 sin(theta / 2) = sqrt(3 - trace(R'^T R)), with a margin
// for the rotations' own error; or the Frobenius norm, never smaller, when that is less (for a
// rotation that did not change, exactly zero).
Scalar turn(const Matrix3& from, const Matrix3& to) {
  const Scalar frobenius = (to - from).norm();
  // trace(R'^T R), the sum of the entries' products: no matrix product.
  const Scalar trace = to.cwiseProduct(from).sum();
  return std::min(frobenius, std::sqrt(std::max(Scalar(0), 3 - trace) + 1e-8));
}

constexpr Scalar kMarginSteps = 12;
constexpr Scalar kMarginOfRadius = 0.25;

}  // namespace

Scalar reach_about_centre(const ConvexPolyhedron& body) {
  // A curved shape's points are a few on its surface; its outer radius holds all of it.
  if (body.curved()) return body.curved()->outer_radius();
  // Not the rows' plain norms: their squares vanish for bodies below 1e-162, whose turns then
  // moved them nowhere.
  return largest_row_length(body.centred_vertices());
}

Scalar displacement(const ConvexPolyhedron& body, Scalar reach, const Pose& from, const Pose& to) {
  const Vector3& c = body.bounds().centre;
  const Vector3 old_centre = from.rotation * c + from.translation;
  const Vector3 new_centre = to.rotation * c + to.translation;
  const Scalar moved =
      robust_length(new_centre - old_centre) + turn(from.rotation, to.rotation) * reach;
  const Scalar magnitude = old_centre.cwiseAbs().maxCoeff() + new_centre.cwiseAbs().maxCoeff() +
                           c.cwiseAbs().maxCoeff() + reach;
  return moved * (1 + 1e-12) + 16 * kEpsilon * magnitude;
}

void update_box(SceneBody& b) {
  const Matrix3& r = b.pose.rotation;
  const Vector3& t = b.pose.translation;
  const VertexMatrix& points = b.body.vertices();
  Vector3 low;
  Vector3 high;
  Scalar shortfall = 0;
  if (const SupportFunction* shape = b.body.curved()) {
    // The support points along the world axes, in the shape's frame; their heights fall short of
    // the support values by at most the support function's error bound, added to the box.
    for (int k = 0; k < 3; ++k) {
      const Vector3 axis = r.row(k).transpose();
      const Vector3 centre = b.body.bounds().centre;
      high(k) = axis.dot(shape->support(axis) + centre) + t(k);
      low(k) = axis.dot(shape->support(-axis) + centre) + t(k);
    }
    shortfall = shape->support_error_roundoffs() * kEpsilon * shape->outer_radius();
  } else if (b.body.size() <= kHillClimbingThreshold) {
    low = r * points.row(0).transpose() + t;
    high = low;
    for (int i = 1; i < b.body.size(); ++i) {
      const Vector3 p = r * points.row(i).transpose() + t;
      low = low.cwiseMin(p);
      high = high.cwiseMax(p);
    }
  } else {
    // ConvexPolyhedron::support_index(d, start)'s climb where every point is a hull point, the hull
    // read once for the six: looked up at each call, it cost a third of a climb from a support
    // that has not moved.
    const Hull* hull = b.body.hull_points().every_point ? &b.body.hull() : nullptr;
    const auto climb = [&](const Vector3& d, int start) {
      return hull != nullptr ? climb_support(b.body.centred_vertices(), *hull, d, start)
                             : b.body.support_index(d, start);
    };
    for (int k = 0; k < 3; ++k) {
      const Vector3 axis = r.row(k).transpose();
      int& up = b.box_supports[2 * k];
      int& down = b.box_supports[2 * k + 1];
      up = climb(axis, up);
      down = climb(-axis, down);
      high(k) = axis.dot(points.row(up).transpose()) + t(k);
      low(k) = axis.dot(points.row(down).transpose()) + t(k);
    }
  }
  const Scalar reach = b.body.bounds().centre.cwiseAbs().maxCoeff() + b.body.bounds().radius +
                       t.cwiseAbs().maxCoeff();
  // A rounded body's box grows by its radius (the reach counts it, for the rounding).
  const Vector3 rounding = Vector3::Constant(16 * kEpsilon * reach + b.body.radius() + shortfall);
  b.box = {low - rounding, high + rounding};
}

void fatten(SceneBody& b) {
  const Scalar margin = std::min(kMarginSteps * b.step, kMarginOfRadius * b.body.bounds().radius);
  b.object.set_box(padded(b.padded, margin));
}

Scalar own_reach(const ConvexPolyhedron& body) {
  return body.bounds().centre.stableNorm() + body.bounds().radius;
}

[[noreturn]] void refuse_placement(const std::string& what, Scalar value) {
  std::ostringstream message;
  message << what << " " << value << "; a scene takes bodies within " << kMaxSceneCoordinate / 2
          << " of their own origin, moved by at most " << kMaxSceneCoordinate / 2
          << " along each axis, so that every coordinate stays within " << kMaxSceneCoordinate
          << " (its broadphase squares box extents): use a larger unit of length, or the pair "
             "queries (distance, collide), which take any finite coordinates";
  throw std::invalid_argument(message.str());
}

}  // namespace swarmcollide::detail
