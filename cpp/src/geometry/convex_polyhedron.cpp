#include "swarmcollide/geometry/convex_polyhedron.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <mutex>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "normalise.hpp"
#include "support.hpp"

namespace swarmcollide {

namespace detail {
// The hull is guarded by double-checked locking rather than std::call_once: glibc's
// pthread_once wakes waiters with a futex system call every time it runs, a measurable cost for
// bodies that are built, queried once and dropped by the hundred thousand.
struct HullCache {
  // ConvexPolyhedron::outer_radius once found (negative before: a radius is not).
  std::atomic<Scalar> outer_radius{-1};
  std::atomic<bool> hull_ready{false};
  std::mutex hull_mutex;
  Hull hull;
  HullPoints hull_points;
  // The centred points by coordinate, for a body of at most kHillClimbingThreshold points (made
  // with the body: its scans are every query's inner loop).
  PointColumns columns;
  // Derived data: a list that only grows, newest first, read without a lock (every fcl query
  // asks for its shapes, and a mutex there made threads on one body wait on each other). Entries
  // are never changed once published, and live as long as the cache.
  struct Derived {
    std::type_index type;
    int key;
    std::shared_ptr<const void> data;
    std::unique_ptr<const Derived> next;
  };
  std::mutex derived_mutex;
  std::atomic<const Derived*> derived_head{nullptr};
  std::unique_ptr<const Derived> derived;

  const Derived* find(std::type_index type, int key) const {
    for (const Derived* d = derived_head.load(std::memory_order_acquire); d; d = d->next.get()) {
      if (d->key == key && d->type == type) return d;
    }
    return nullptr;
  }
};
}  // namespace detail

namespace {

// Twice the unit roundoff: the ball's radius is a sum and a norm of rounded terms, a few of these
// each.
constexpr Scalar kRoundoffBound = std::numeric_limits<Scalar>::epsilon();

void check_points(const VertexMatrix& points) {
  if (points.rows() == 0) {
    throw std::invalid_argument("points is empty: a polyhedron needs at least one point");
  }
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    if (!points.row(i).allFinite()) {
      throw std::invalid_argument("points has a NaN or infinite coordinate in row " +
                                  std::to_string(i));
    }
  }
}

void check_radius(Scalar radius) {
  if (!(radius >= 0) || !std::isfinite(radius)) {
    std::ostringstream message;
    message << "radius must be a finite number >= 0 (the rounding radius), got " << radius;
    throw std::invalid_argument(message.str());
  }
}

// Halves are taken before differences and sums, so coordinates up to the largest double give a
// finite centre and half-extent. The rounding grows the box by `radius` on every side and the
// ball by as much; both are rounded outward, so they still hold the body.
BodyBounds bounds_of(const VertexMatrix& points, Scalar radius) {
  BodyBounds bounds;
  bounds.box = {points.colwise().minCoeff().transpose(), points.colwise().maxCoeff().transpose()};
  bounds.centre = bounds.box.min / 2 + bounds.box.max / 2;
  const Vector3 half_extent = bounds.box.max / 2 - bounds.box.min / 2;
  const Scalar largest = half_extent.maxCoeff();
  bounds.radius = largest > 0 ? largest * (half_extent / largest).norm() : 0;
  if (radius > 0) {
    const Scalar huge = std::numeric_limits<Scalar>::infinity();
    for (int k = 0; k < 3; ++k) {
      bounds.box.min(k) = std::nextafter(bounds.box.min(k) - radius, -huge);
      bounds.box.max(k) = std::nextafter(bounds.box.max(k) + radius, huge);
    }
    bounds.radius = std::nextafter((bounds.radius + radius) * (1 + 4 * kRoundoffBound), huge);
  }
  if (!std::isfinite(bounds.radius) || !bounds.box.min.allFinite() || !bounds.box.max.allFinite()) {
    throw std::invalid_argument(
        "points (with the radius) span more than the largest double (1.8e308): the body's size "
        "is not representable; use a unit of length in which the coordinates are smaller");
  }
  return bounds;
}

// The largest distance of `centred`'s points from their origin, rounded up: in the unit ball
// (exactly, by a power of two), where no square underflows. Each norm is within a few roundoffs
// of the exact distance of its point from the box centre (the centred points are themselves
// rounded relative to it); 2^-40 is far more. One square root, of the largest sum of squares:
// the square root is monotone, so it is the largest of the norms, bit for bit.
Scalar largest_distance(const VertexMatrix& centred) {
  const int exponent = detail::exponent_above(centred.cwiseAbs().maxCoeff());
  Scalar largest = 0;
  for (Eigen::Index i = 0; i < centred.rows(); ++i) {
    Vector3 unit;
    for (int k = 0; k < 3; ++k) unit(k) = detail::times_power_of_two(centred(i, k), -exponent);
    largest = std::max(largest, unit.squaredNorm());
  }
  return detail::times_power_of_two(std::sqrt(largest) * (1 + 0x1p-40), exponent);
}

// A core's outer radius `core` grown by the rounding radius, rounded up.
Scalar rounded_outer_radius(Scalar core, Scalar radius) {
  return radius > 0 ? (core + radius) * (1 + 0x1p-40) : core;
}

// Centre of mass of a closed, outward-oriented triangle mesh, from the signed tetrahedra it forms
// with a reference point inside the hull.
Vector3 solid_centroid(const VertexMatrix& points, const FaceMatrix& faces, const Vector3& origin) {
  Scalar volume = 0;
  Vector3 moment = Vector3::Zero();
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    const Vector3 p = points.row(faces(f, 0)).transpose() - origin;
    const Vector3 q = points.row(faces(f, 1)).transpose() - origin;
    const Vector3 r = points.row(faces(f, 2)).transpose() - origin;
    const Scalar v = p.dot(q.cross(r));
    volume += v;
    moment += v * (p + q + r) / 4;
  }
  return origin + moment / volume;
}

// Area centroid of a flat polygon given as a doubled fan of triangles (each listed twice).
Vector3 flat_centroid(const VertexMatrix& points, const FaceMatrix& faces) {
  Scalar area = 0;
  Vector3 moment = Vector3::Zero();
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    const Vector3 p = points.row(faces(f, 0));
    const Vector3 q = points.row(faces(f, 1));
    const Vector3 r = points.row(faces(f, 2));
    const Scalar a = (q - p).cross(r - p).norm();
    area += a;
    moment += a * (p + q + r) / 3;
  }
  return moment / area;
}

}  // namespace

ConvexPolyhedron::ConvexPolyhedron(VertexMatrix points, Scalar radius)
    : vertices_(std::move(points)),
      radius_(radius),
      hull_cache_(std::make_shared<detail::HullCache>()),
      outer_radius_(&hull_cache_->outer_radius) {
  check_points(vertices_);
  check_radius(radius_);
  bounds_ = bounds_of(vertices_, radius_);
  centred_ = vertices_.rowwise() - bounds_.centre.transpose();
  static_assert(kHillClimbingThreshold <= detail::PointColumns::kCapacity);
  if (centred_.rows() <= kHillClimbingThreshold) {
    hull_cache_->columns.assign(centred_);
    columns_ = &hull_cache_->columns;
  }
}

ConvexPolyhedron::ConvexPolyhedron(VertexMatrix points, Scalar radius,
                                   std::shared_ptr<const SupportFunction> shape)
    : ConvexPolyhedron(std::move(points), radius) {
  curved_ = std::move(shape);
  support_error_per_radius_ = curved_->support_error_roundoffs() * detail::kRoundoff;
  // The points' box is the shape's, but their ball is not: the shape's outer radius bounds it.
  const Scalar huge = std::numeric_limits<Scalar>::infinity();
  bounds_.radius =
      std::nextafter((curved_->outer_radius() + radius) * (1 + 4 * kRoundoffBound), huge);
  if (!std::isfinite(bounds_.radius)) {
    throw std::invalid_argument(
        "the shape (with the radius) spans more than the largest double (1.8e308): its size is "
        "not representable; use a unit of length in which its dimensions are smaller");
  }
}

ConvexPolyhedron::ConvexPolyhedron(const VertexMatrix& centred,
                                   std::shared_ptr<const SupportFunction> shape, const Aabb& box)
    : ConvexPolyhedron(centred.rowwise() + (box.min / 2 + box.max / 2).transpose(), 0,
                       std::move(shape)) {
  bounds_.box = box;
  bounds_.centre = box.min / 2 + box.max / 2;
  // The given points, not the rounded differences of the placed ones: the solvers read these as
  // points of the shape, which they are.
  centred_ = centred;
  if (centred_.rows() <= kHillClimbingThreshold) {
    hull_cache_->columns.assign(centred_);
    columns_ = &hull_cache_->columns;
  }
}

int ConvexPolyhedron::support_index(const Vector3& direction) const {
  const HullPoints& read = hull_points();
  // The columns hold small bodies' points only: a larger body whose every point is a vertex (a
  // sphere's 40 points) scans them all. (Since 19b4074 it scanned the empty columns, and
  // support(), libccd's supports and the motions' turn rates read a wrong point.)
  if (read.every_point) {
    return columns_ != nullptr ? columns_->scan(direction)
                               : detail::scan_support(centred_, direction);
  }
  return read.indices[detail::scan_support(read.centred, direction)];
}

int ConvexPolyhedron::support_index(const Vector3& direction, int start) const {
  if (size() <= kHillClimbingThreshold) return support_index(direction);
  const HullPoints& read = hull_points();
  if (read.every_point) return detail::climb_support(centred_, hull(), direction, start);
  if (read.centred.rows() <= kHillClimbingThreshold) return support_index(direction);
  const auto found = std::lower_bound(read.indices.begin(), read.indices.end(), start);
  const int from = found != read.indices.end() && *found == start
                       ? static_cast<int>(found - read.indices.begin())
                       : -1;
  return read.indices[detail::climb_support(read.centred, read.hull, direction, from)];
}

Vector3 ConvexPolyhedron::centroid() const {
  if (curved_) return curved_->centroid() + bounds_.centre;
  const Hull& h = hull();
  // Volumes and areas are computed in the unit ball, where their cubes and squares of the
  // coordinates can neither overflow nor underflow.
  const detail::NormalisedPoints unit = detail::normalise(vertices_);
  Vector3 centre = Vector3::Zero();
  if (h.dimension == 3) {
    Vector3 inside = Vector3::Zero();
    for (int i : h.vertex_indices) inside += unit.points.row(i).transpose();
    inside /= static_cast<Scalar>(h.vertex_indices.size());
    centre = solid_centroid(unit.points, h.faces, inside);
  } else if (h.dimension == 2) {
    centre = flat_centroid(unit.points, h.faces);
  } else {
    for (int i : h.vertex_indices) centre += unit.points.row(i).transpose();
    centre /= static_cast<Scalar>(h.vertex_indices.size());
  }
  for (int k = 0; k < 3; ++k) centre(k) = detail::times_power_of_two(centre(k), unit.exponent);
  return unit.centre + centre;
}

const void* ConvexPolyhedron::find_derived(std::type_index type, int key) const {
  const detail::HullCache::Derived* found = hull_cache_->find(type, key);
  return found ? found->data.get() : nullptr;
}

const void* ConvexPolyhedron::add_derived(
    std::type_index type, int key, const std::function<std::shared_ptr<const void>()>& make) const {
  detail::HullCache& cache = *hull_cache_;
  const std::lock_guard<std::mutex> lock(cache.derived_mutex);
  if (const detail::HullCache::Derived* found = cache.find(type, key)) return found->data.get();
  cache.derived.reset(
      new detail::HullCache::Derived{type, key, make(), std::move(cache.derived)});
  cache.derived_head.store(cache.derived.get(), std::memory_order_release);
  return cache.derived->data.get();
}

const Hull& ConvexPolyhedron::hull() const {
  if (!hull_cache_->hull_ready.load(std::memory_order_acquire)) {
    const std::lock_guard<std::mutex> lock(hull_cache_->hull_mutex);
    if (!hull_cache_->hull_ready.load(std::memory_order_relaxed)) {
      hull_cache_->hull = compute_hull(vertices_);
      if (size() > kHillClimbingThreshold) {
        hull_cache_->hull_points = find_hull_points(centred_, hull_cache_->hull);
      }
      hull_cache_->hull_ready.store(true, std::memory_order_release);
    }
  }
  return hull_cache_->hull;
}

const HullPoints& ConvexPolyhedron::hull_points() const {
  // Small bodies are scanned whole: their hull is not needed for it.
  static const HullPoints kEveryPoint;
  if (size() <= kHillClimbingThreshold) return kEveryPoint;
  hull();
  return hull_cache_->hull_points;
}

Scalar ConvexPolyhedron::find_outer_radius() const {
  // A curved shape reaches beyond its points (a few on its surface); its own bound holds it.
  // Threads that find it at once store the same value.
  const Scalar radius = rounded_outer_radius(
      curved_ ? curved_->outer_radius() * (1 + 0x1p-40) : largest_distance(centred_), radius_);
  hull_cache_->outer_radius.store(radius, std::memory_order_relaxed);
  return radius;
}

int ConvexPolyhedron::read_point_count() const {
  if (size() <= kHillClimbingThreshold ||
      !hull_cache_->hull_ready.load(std::memory_order_acquire)) {
    return size();
  }
  const HullPoints& read = hull_cache_->hull_points;
  return read.every_point ? size() : static_cast<int>(read.indices.size());
}

}  // namespace swarmcollide
