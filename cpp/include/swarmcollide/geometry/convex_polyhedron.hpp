#pragma once

#include <atomic>
#include <functional>
#include <memory>
#include <typeindex>

#include "swarmcollide/geometry/aabb.hpp"
#include "swarmcollide/geometry/hull.hpp"
#include "swarmcollide/geometry/hull_points.hpp"
#include "swarmcollide/geometry/support_function.hpp"
#include "swarmcollide/types.hpp"

namespace swarmcollide {

namespace detail {
struct HullCache;
class PointColumns;
}

/// Number of points above which `support_index(direction, start)` climbs the hull instead of
/// scanning the points, and above which a body finds its hull points (`hull_points()`): smaller
/// bodies are scanned whole.
inline constexpr int kHillClimbingThreshold = 32;

/// A body's extent, computed once when it is built: every query needs it. For a rounded body
/// (`ConvexPolyhedron::radius() > 0`) it is the extent of the rounded body, rounding included.
struct BodyBounds {
  /// Smallest axis-aligned box containing the body (its points, grown by the rounding radius).
  Aabb box;
  /// The box's centre (the centre of the points' box: the rounding grows it evenly).
  Vector3 centre = Vector3::Zero();
  /// A bound on the distance from `centre` of every point of the body: half the points' box
  /// diagonal plus the rounding radius, rounded up.
  Scalar radius = 0;
};

/// A convex polyhedron: the convex hull of a finite point set (the paper's Definition 3), or,
/// with a rounding radius r > 0, the rounded body: that hull (the core) grown by a ball of
/// radius r (their Minkowski sum), which makes a sphere of one point, a capsule of a segment and
/// a rounded box of a box's corners (shapes.hpp).
///
/// The queries answer a pair of rounded bodies on their cores and subtract both radii: the signed
/// distance of A + B(r) and B + B(s) is exactly that of A and B less r + s, for convex A and B
/// (rounded.hpp).
///
/// The points are kept as given; they are the `x_i` of model (2), so a point inside the hull is a
/// legitimate (if redundant) vertex of the model. The exact solvers and support queries read only
/// the hull points (`hull_points()`), found with the hull. Flat, collinear and single-point sets
/// are valid bodies. Copies share the lazily computed hull; the class is safe to read from many
/// threads.
///
/// A curved shape (Cylinder, Cone, Ellipsoid) is a ConvexPolyhedron whose `curved()` support
/// function defines it: its points are a few points on its surface (an inner polytope, whose box
/// is the shape's), which the support-function solvers never read as the body; they ask `curved()`
/// for support points ("fcl" hands FCL its own primitive). Methods that read the points as the
/// body (the paper's swarms, the penalty method) refuse curved shapes.
class ConvexPolyhedron {
 public:
  /// Throws std::invalid_argument if `points` is empty, has a NaN or infinite coordinate, or
  /// spans so far that the body's size is not representable in double precision, or if `radius`
  /// (the rounding radius) is negative, NaN or infinite.
  explicit ConvexPolyhedron(VertexMatrix points, Scalar radius = 0);

  /// The points the body was built from, one per row.
  const VertexMatrix& vertices() const { return vertices_; }
  /// Number of points (the `k` of model (2)).
  int size() const { return static_cast<int>(vertices_.rows()); }
  /// The rounding radius: the body is the hull of the points grown by a ball of this radius (0
  /// for a plain polyhedron). Support points, hulls and centroids are those of the core.
  Scalar radius() const { return radius_; }

  /// The points less the centre of their box (`bounds().centre`), as support queries compare
  /// them. Each difference is rounded relative to itself, so heights `d . x` are rounded relative
  /// to the body's size, not to its distance from the origin, which may be many orders larger
  /// (supports chosen among points 1e8 from the origin fell 6e-9 short); and they are the same
  /// numbers, scaled, for a body scaled by a power of two or translated exactly, so such bodies
  /// break ties alike and get the same answers.
  const VertexMatrix& centred_vertices() const { return centred_; }
  /// `centred_vertices()` by coordinate, made with the body when it has at most
  /// `kHillClimbingThreshold` points (null otherwise): the library's scans read them two at a
  /// time, with the same answers as a scan of the rows. Inline: every query frames its bodies
  /// with it.
  const detail::PointColumns* centred_columns() const { return columns_; }

  /// The support function of a curved shape (shapes.hpp), null for a polyhedron: the body is
  /// then that shape (rounded by `radius()`), not the hull of its points.
  const SupportFunction* curved() const { return curved_.get(); }
  /// The same support function, shared: for a body made from this one (placed_shape.hpp).
  const std::shared_ptr<const SupportFunction>& curved_shared() const { return curved_; }
  /// `curved()->support_error_roundoffs()` roundoffs (2^-53 each, so the product is exact), 0 for
  /// a polyhedron: how far, relative to `bounds().radius` and a unit direction, the support points
  /// may fall short of the support value. Kept with the body: the framing of every query reads
  /// it, where the virtual call was some 10 instructions a curved body.
  Scalar support_error_per_radius() const { return support_error_per_radius_; }

  /// Index of a point that maximises `direction . x` (the first of the hull points on ties),
  /// comparing `centred_vertices()` of the hull points.
  int support_index(const Vector3& direction) const;
  /// Index of a point that maximises `direction . x`, found by hill climbing over the hull's
  /// vertex adjacency from the point `start` (any index; a point that is not a hull vertex starts
  /// from the first one) when the body has more than `kHillClimbingThreshold` hull points, as FCL
  /// and coal do, and by scanning them otherwise. Passing the previous answer as `start` for a
  /// nearby direction makes a query cost a few neighbour checks. On ties any maximiser is returned.
  int support_index(const Vector3& direction, int start) const;
  /// A point of the core (the points' hull, or the curved shape) farthest along `direction`; the
  /// rounded body's is this plus `radius()` times the unit direction.
  Vector3 support(const Vector3& direction) const {
    if (curved_) return curved_->support(direction) + bounds_.centre;
    return vertices_.row(support_index(direction));
  }

  /// Smallest axis-aligned box containing the body (the rounded body when `radius() > 0`).
  const Aabb& aabb() const { return bounds_.box; }
  /// The box, its centre and the radius of the ball around that centre holding the body.
  const BodyBounds& bounds() const { return bounds_; }
  /// The radius of a ball about `bounds().centre` holding the body, rounded up: the largest
  /// distance of a point from the centre (a curved shape's own outer radius) plus `radius()`.
  /// Tighter than `bounds().radius`, which the box's diagonal gives: a collision verdict between
  /// bodies whose balls are apart needs nothing else (Query::collide). Computed on first use and
  /// shared by the body's copies (a body built for one distance query never pays for it).
  Scalar outer_radius() const {
    const Scalar found = outer_radius_->load(std::memory_order_relaxed);
    return found >= 0 ? found : find_outer_radius();
  }
  /// Centre of mass of the solid (a curved shape's own); for flat, collinear and single-point
  /// bodies, of the polygon, segment or point they are.
  Vector3 centroid() const;
  /// Convex hull, computed on first use (of the points: for a curved shape, an inner polytope).
  const Hull& hull() const;
  /// The points the exact solvers read: the hull's vertices and any point not proven inside their
  /// hull (see HullPoints), found with the hull for bodies of more than `kHillClimbingThreshold`
  /// points; smaller bodies read every point.
  const HullPoints& hull_points() const;
  /// How many points the exact solvers read (`hull_points()`'s) once the hull is found, and
  /// `size()` until then: what a query on the body costs grows with it, and asking it never
  /// finds the hull.
  int read_point_count() const;

  /// Data a solver derives from the body (an FCL shape at some scale, say): made by `make()` on
  /// the first call for type `T` and `key`, then shared by every copy of the body, and kept as
  /// long as one of them lives. Safe to call from many threads; once made, finding it takes no
  /// lock (a solver asks for it on every query).
  template <typename T, typename Make>
  const T& derived(const Make& make, int key = 0) const {
    const void* found = find_derived(typeid(T), key);
    if (!found) {
      found = add_derived(typeid(T), key, [&make] {
        return std::shared_ptr<const void>(std::make_shared<const T>(make()));
      });
    }
    return *static_cast<const T*>(found);
  }

 protected:
  /// A curved shape: `points` on its surface (whose box must be the shape's), rounded by
  /// `radius`, answering its support points from `shape`; the bounds' ball is the shape's outer
  /// radius (plus `radius`).
  ConvexPolyhedron(VertexMatrix points, Scalar radius,
                   std::shared_ptr<const SupportFunction> shape);
  /// A curved shape whose points' box is not the shape's (a shape placed by a pose,
  /// placed_shape.hpp): `box` holds the shape, and its centre (`min / 2 + max / 2`) is the origin
  /// of `shape`'s frame, in which `centred` gives points of the shape (`centred_vertices()`).
  ConvexPolyhedron(const VertexMatrix& centred, std::shared_ptr<const SupportFunction> shape,
                   const Aabb& box);

 private:
  // outer_radius() the first time, kept where outer_radius_ points.
  Scalar find_outer_radius() const;
  // The data kept for (type, key), null when there is none yet.
  const void* find_derived(std::type_index type, int key) const;
  // The data for (type, key), made by `make` unless another thread made it first.
  const void* add_derived(std::type_index type, int key,
                          const std::function<std::shared_ptr<const void>()>& make) const;

  VertexMatrix vertices_;
  Scalar radius_;
  BodyBounds bounds_;
  VertexMatrix centred_;
  std::shared_ptr<detail::HullCache> hull_cache_;
  std::shared_ptr<const SupportFunction> curved_;
  Scalar support_error_per_radius_ = 0;
  // outer_radius() where hull_cache_ (which every copy shares) keeps it, negative until found.
  const std::atomic<Scalar>* outer_radius_ = nullptr;
  // The columns held in hull_cache_ (which every copy shares), null for a large body.
  const detail::PointColumns* columns_ = nullptr;
};

}  // namespace swarmcollide
