#include "swarmcollide/geometry/hull.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <numeric>
#include <stdexcept>
#include <string>
#include <utility>

extern "C" {
#include <libqhull_r/qhull_ra.h>
}

#include "swarmcollide/geometry/convex_polyhedron.hpp"
#include "hull_graph.hpp"
#include "normalise.hpp"
#include "support.hpp"

namespace swarmcollide {

namespace {

struct PrincipalAxes {
  Vector3 mean;
  Eigen::Matrix3d axes;  // columns, largest spread first
  int dimension;
};

PrincipalAxes principal_axes(const VertexMatrix& points) {
  PrincipalAxes result;
  result.mean = points.colwise().mean().transpose();
  const VertexMatrix centred = points.rowwise() - result.mean.transpose();
  Eigen::JacobiSVD<Eigen::Matrix<Scalar, Eigen::Dynamic, 3>> svd(centred, Eigen::ComputeFullV);
  // Fewer than three points have fewer singular values; the missing ones are zero.
  Vector3 sigma = Vector3::Zero();
  sigma.head(svd.singularValues().size()) = svd.singularValues();
  result.axes = svd.matrixV();
  result.dimension = 0;
  if (sigma(0) > 0) {
    for (int k = 0; k < 3; ++k) result.dimension += sigma(k) > kFlatnessTolerance * sigma(0);
  }
  return result;
}

Scalar cross2(const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return (a - o).x() * (b - o).y() - (a - o).y() * (b - o).x();
}

// Andrew's monotone chain; returns the hull's indices counter-clockwise, without collinear points.
std::vector<int> polygon_hull(const std::vector<Eigen::Vector2d>& p) {
  if (p.size() < 3) {
    std::vector<int> all(p.size());
    std::iota(all.begin(), all.end(), 0);
    return all;
  }
  std::vector<int> order(p.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int i, int j) {
    return p[i].x() < p[j].x() || (p[i].x() == p[j].x() && p[i].y() < p[j].y());
  });
  std::vector<int> hull(2 * order.size());
  std::size_t k = 0;
  for (int i : order) {
    while (k >= 2 && cross2(p[hull[k - 2]], p[hull[k - 1]], p[i]) <= 0) --k;
    hull[k++] = i;
  }
  const std::size_t lower = k + 1;
  for (auto it = order.rbegin() + 1; it != order.rend(); ++it) {
    while (k >= lower && cross2(p[hull[k - 2]], p[hull[k - 1]], p[*it]) <= 0) --k;
    hull[k++] = *it;
  }
  hull.resize(k - 1);
  return hull;
}

Hull segment_hull(const VertexMatrix& points, const PrincipalAxes& frame) {
  Eigen::Index lo = 0;
  Eigen::Index hi = 0;
  const VectorX t = (points.rowwise() - frame.mean.transpose()) * frame.axes.col(0);
  t.minCoeff(&lo);
  t.maxCoeff(&hi);
  Hull hull;
  hull.dimension = 1;
  hull.vertex_indices = {static_cast<int>(std::min(lo, hi)), static_cast<int>(std::max(lo, hi))};
  return hull;
}

Hull flat_hull(const VertexMatrix& points, const PrincipalAxes& frame) {
  std::vector<Eigen::Vector2d> projected(points.rows());
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    const Vector3 d = points.row(i).transpose() - frame.mean;
    projected[i] = {d.dot(frame.axes.col(0)), d.dot(frame.axes.col(1))};
  }
  const std::vector<int> ring = polygon_hull(projected);
  // Far from the origin the rounded mean can give collinear points (even two) a sliver of a
  // second singular value; in the plane they are still a segment.
  if (ring.size() < 3) return segment_hull(points, frame);
  Hull hull;
  hull.dimension = 2;
  hull.vertex_indices = ring;
  const int triangles = static_cast<int>(ring.size()) - 2;
  hull.faces.resize(2 * triangles, 3);
  // Counter-clockwise in the (axis0, axis1) plane faces +axis0 x axis1; the reversed copy faces
  // the other side.
  for (int t = 0; t < triangles; ++t) {
    hull.faces.row(t) << ring[0], ring[t + 1], ring[t + 2];
    hull.faces.row(triangles + t) << ring[0], ring[t + 2], ring[t + 1];
  }
  std::sort(hull.vertex_indices.begin(), hull.vertex_indices.end());
  return hull;
}

// Up to this many points, trying every plane through three of them beats Qhull's set-up cost.
constexpr Eigen::Index kSmallHullLimit = 16;

// The fast path for small solids takes only points in clear general position: a first
// tetrahedron with heights of at least kFatTetrahedron times its longest edge L (so the smallest
// singular value of the centred points is orders of magnitude above kFlatnessTolerance times the
// largest, and principal_axes would call the set solid), faces of area at least
// kGeneralPositionMargin L^2 / 2, and every point at least kGeneralPositionMargin L away from the
// plane of every face it is not a corner of. Both are hundreds of times small_solid_hull's
// tolerances, so that path would find the same triangles, and no orientation test is decided by
// rounding.
constexpr Scalar kFatTetrahedron = 1e-2;
constexpr Scalar kGeneralPositionMargin = 1e-9;
constexpr int kMaxSmallHullFaces = 2 * kSmallHullLimit - 4;

struct Triangle {
  std::array<int, 3> corners;  // counter-clockwise seen from outside
  Vector3 normal;              // unit, outward
};

// The row small_solid_hull writes for the triangle `face`, whose corners ascending are `sorted`:
// it meets the face at that triple, takes the triple's unit normal, and starts the triangle at the
// corner that comes first in (u, v) order, u = normal.unitOrthogonal(), v = normal x u (where
// Andrew's monotone chain starts). Computed the same way, so both paths give identical hulls.
Eigen::RowVector3i small_solid_hull_row(const VertexMatrix& points, const Triangle& face,
                                        const std::array<int, 3>& sorted) {
  const Vector3 p = points.row(sorted[0]);
  Vector3 normal =
      (points.row(sorted[1]).transpose() - p).cross(points.row(sorted[2]).transpose() - p);
  normal /= normal.norm();
  if (normal.dot(face.normal) < 0) normal = -normal;
  const Vector3 u = normal.unitOrthogonal();
  const Vector3 v = normal.cross(u);
  int first = 0;  // the corner sorted[0], which projects to (0, 0)
  Eigen::Vector2d lowest(0, 0);
  for (int k = 1; k < 3; ++k) {
    const Vector3 d = points.row(sorted[k]).transpose() - p;
    const Eigen::Vector2d q(d.dot(u), d.dot(v));
    if (q.x() < lowest.x() || (q.x() == lowest.x() && q.y() < lowest.y())) {
      lowest = q;
      first = k;
    }
  }
  const int start = static_cast<int>(
      std::find(face.corners.begin(), face.corners.end(), sorted[first]) - face.corners.begin());
  return {face.corners[start], face.corners[(start + 1) % 3], face.corners[(start + 2) % 3]};
}

// Incremental (beneath-beyond) hull of a small solid point set in general position, without heap
// allocation: a fat first tetrahedron, then each point replaces the faces it sees by a cone to
// their horizon. Returns false (and small_solid_hull decides) unless the points are in the clear
// general position described above; what it returns then is small_solid_hull's hull, row for row.
bool general_position_hull(const VertexMatrix& points, Hull& hull) {
  const int n = static_cast<int>(points.rows());
  if (n < 4 || n > kSmallHullLimit) return false;
  const auto point = [&points](int i) -> Vector3 { return points.row(i).transpose(); };

  // The first tetrahedron: the leftmost point, the point farthest from it, the point farthest
  // from their line, the point farthest from their plane.
  Eigen::Index leftmost = 0;
  points.col(0).minCoeff(&leftmost);
  const int a = static_cast<int>(leftmost);
  Eigen::Index farthest = 0;
  const Scalar longest =
      std::sqrt((points.rowwise() - points.row(a)).rowwise().squaredNorm().maxCoeff(&farthest));
  int b = static_cast<int>(farthest);
  if (!(longest > 0)) return false;
  const Vector3 axis = (point(b) - point(a)) / longest;
  int c = a;
  Scalar widest = 0;
  for (int i = 0; i < n; ++i) {
    const Scalar w = (point(i) - point(a)).cross(axis).squaredNorm();
    if (w > widest) {
      widest = w;
      c = i;
    }
  }
  if (std::sqrt(widest) < kFatTetrahedron * longest) return false;
  const Vector3 base = (point(b) - point(a)).cross(point(c) - point(a)).normalized();
  int d = a;
  Scalar tallest = 0;
  for (int i = 0; i < n; ++i) {
    const Scalar h = std::abs(base.dot(point(i) - point(a)));
    if (h > tallest) {
      tallest = h;
      d = i;
    }
  }
  if (tallest < kFatTetrahedron * longest) return false;
  const Scalar margin = kGeneralPositionMargin * longest;

  std::array<Triangle, kMaxSmallHullFaces> faces;
  int face_count = 0;
  // edge_face[p][q]: the face with the directed edge p -> q. Every edge of the current surface
  // has its reverse in the neighbouring face, so a visible face's neighbours are two lookups away.
  std::array<std::array<std::uint8_t, kSmallHullLimit>, kSmallHullLimit> edge_face;
  const auto add_face = [&](int p, int q, int r) {
    Vector3 normal = (point(q) - point(p)).cross(point(r) - point(p));
    const Scalar length = normal.norm();
    if (!(length > margin * longest) || face_count == kMaxSmallHullFaces) return false;
    faces[face_count] = {{p, q, r}, normal / length};
    edge_face[p][q] = edge_face[q][r] = edge_face[r][p] = static_cast<std::uint8_t>(face_count);
    ++face_count;
    return true;
  };
  // With d behind the triangle (a, b, c), these four face away from the opposite corner.
  if (base.dot(point(d) - point(a)) > 0) std::swap(b, c);
  if (!add_face(a, b, c) || !add_face(a, d, b) || !add_face(b, d, c) || !add_face(c, d, a)) {
    return false;
  }

  std::array<bool, kMaxSmallHullFaces> visible{};
  std::array<std::pair<int, int>, 3 * kMaxSmallHullFaces> horizon;
  for (int q = 0; q < n; ++q) {
    if (q == a || q == b || q == c || q == d) continue;
    bool outside = false;
    for (int f = 0; f < face_count; ++f) {
      const Scalar height = faces[f].normal.dot(point(q) - point(faces[f].corners[0]));
      if (std::abs(height) <= margin) return false;
      visible[f] = height > 0;
      outside = outside || visible[f];
    }
    if (!outside) continue;
    int horizon_size = 0;
    for (int f = 0; f < face_count; ++f) {
      if (!visible[f]) continue;
      for (int k = 0; k < 3; ++k) {
        const int p = faces[f].corners[k];
        const int r = faces[f].corners[(k + 1) % 3];
        if (!visible[edge_face[r][p]]) horizon[horizon_size++] = {p, r};
      }
    }
    int kept = 0;
    for (int f = 0; f < face_count; ++f) {
      if (visible[f]) continue;
      if (kept != f) {
        faces[kept] = faces[f];
        const auto& k = faces[kept].corners;
        edge_face[k[0]][k[1]] = edge_face[k[1]][k[2]] = edge_face[k[2]][k[0]] =
            static_cast<std::uint8_t>(kept);
      }
      ++kept;
    }
    face_count = kept;
    for (int e = 0; e < horizon_size; ++e) {
      if (!add_face(horizon[e].first, horizon[e].second, q)) return false;
    }
  }

  // Every face must have every other point clearly behind it (which also proves the surface
  // convex and outward), and a closed triangulated sphere has 2V - 4 faces.
  std::uint32_t corners = 0;
  for (int f = 0; f < face_count; ++f) {
    const Triangle& face = faces[f];
    for (int i = 0; i < n; ++i) {
      if (i == face.corners[0] || i == face.corners[1] || i == face.corners[2]) continue;
      if (face.normal.dot(point(i) - point(face.corners[0])) > -margin) return false;
    }
    for (int corner : face.corners) corners |= std::uint32_t{1} << corner;
  }
  std::vector<int> vertex_indices;
  for (int i = 0; i < n; ++i) {
    if (corners >> i & 1) vertex_indices.push_back(i);
  }
  if (face_count != 2 * static_cast<int>(vertex_indices.size()) - 4) return false;

  // small_solid_hull lists the faces in the order of their sorted corner triples; with at most
  // 16 points a triple packs into one sortable int, 4 bits a corner, the face's slot below.
  static_assert(kSmallHullLimit <= 16 && kMaxSmallHullFaces <= 32);
  std::array<int, kMaxSmallHullFaces> keys;
  for (int f = 0; f < face_count; ++f) {
    const auto [low, high] =
        std::minmax({faces[f].corners[0], faces[f].corners[1], faces[f].corners[2]});
    const int middle = faces[f].corners[0] + faces[f].corners[1] + faces[f].corners[2] - low - high;
    keys[f] = low << 13 | middle << 9 | high << 5 | f;
  }
  std::sort(keys.begin(), keys.begin() + face_count);
  hull.dimension = 3;
  hull.vertex_indices = std::move(vertex_indices);
  hull.faces.resize(face_count, 3);
  for (int f = 0; f < face_count; ++f) {
    const int key = keys[f];
    hull.faces.row(f) =
        small_solid_hull_row(points, faces[key & 31], {key >> 13, key >> 9 & 15, key >> 5 & 15});
  }
  return true;
}

}  // namespace

namespace detail {

bool closed_surface(const std::vector<Eigen::RowVector3i>& triangles) {
  std::vector<std::pair<int, int>> edges;
  for (const auto& t : triangles) {
    for (int k = 0; k < 3; ++k) edges.emplace_back(t(k), t((k + 1) % 3));
  }
  std::sort(edges.begin(), edges.end());
  if (std::adjacent_find(edges.begin(), edges.end()) != edges.end()) return false;
  return std::all_of(edges.begin(), edges.end(), [&](const std::pair<int, int>& e) {
    return std::binary_search(edges.begin(), edges.end(), std::make_pair(e.second, e.first));
  });
}

}  // namespace detail

namespace {

// Exact hull of a small solid point set: every plane through three points with all points on one
// side is a face; the points on it form a convex polygon, triangulated as a fan. Returns false
// (and the caller asks Qhull) if rounding leaves the faces inconsistent.
bool small_solid_hull(const VertexMatrix& points, Hull& hull) {
  const Eigen::Index n = points.rows();
  const Vector3 centre = points.colwise().mean().transpose();
  const Scalar scale = (points.rowwise() - centre.transpose()).rowwise().norm().maxCoeff();
  const Scalar tolerance = 1e-12 * scale;
  std::vector<std::uint64_t> seen;
  std::vector<Eigen::RowVector3i> triangles;
  std::vector<int> members;
  std::vector<Eigen::Vector2d> projected;
  for (Eigen::Index i = 0; i < n; ++i) {
    for (Eigen::Index j = i + 1; j < n; ++j) {
      for (Eigen::Index k = j + 1; k < n; ++k) {
        const Vector3 p = points.row(i);
        Vector3 normal = (points.row(j).transpose() - p).cross(points.row(k).transpose() - p);
        const Scalar length = normal.norm();
        if (length <= tolerance * scale) continue;
        normal /= length;
        Scalar highest = -1;
        Scalar lowest = 1;
        for (Eigen::Index m = 0; m < n; ++m) {
          const Scalar offset = normal.dot(points.row(m).transpose() - p);
          highest = std::max(highest, offset);
          lowest = std::min(lowest, offset);
        }
        if (highest > tolerance && lowest < -tolerance) continue;
        if (highest > tolerance) normal = -normal;
        std::uint64_t on_face = 0;
        for (Eigen::Index m = 0; m < n; ++m) {
          if (std::abs(normal.dot(points.row(m).transpose() - p)) <= tolerance) {
            on_face |= std::uint64_t{1} << m;
          }
        }
        if (std::find(seen.begin(), seen.end(), on_face) != seen.end()) continue;
        seen.push_back(on_face);
        // (u, v, normal) is right-handed, so counter-clockwise in (u, v) faces outward.
        const Vector3 u = normal.unitOrthogonal();
        const Vector3 v = normal.cross(u);
        members.clear();
        projected.clear();
        for (Eigen::Index m = 0; m < n; ++m) {
          if (on_face >> m & 1) {
            members.push_back(static_cast<int>(m));
            const Vector3 d = points.row(m).transpose() - p;
            projected.emplace_back(d.dot(u), d.dot(v));
          }
        }
        const std::vector<int> ring = polygon_hull(projected);
        for (std::size_t t = 1; t + 1 < ring.size(); ++t) {
          triangles.emplace_back(members[ring[0]], members[ring[t]], members[ring[t + 1]]);
        }
      }
    }
  }
  if (triangles.size() < 4 || !detail::closed_surface(triangles)) return false;
  hull.dimension = 3;
  hull.faces.resize(static_cast<Eigen::Index>(triangles.size()), 3);
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    hull.faces.row(static_cast<Eigen::Index>(t)) = triangles[t];
  }
  hull.vertex_indices.assign(hull.faces.data(), hull.faces.data() + hull.faces.size());
  std::sort(hull.vertex_indices.begin(), hull.vertex_indices.end());
  hull.vertex_indices.erase(std::unique(hull.vertex_indices.begin(), hull.vertex_indices.end()),
                            hull.vertex_indices.end());
  return true;
}

// Qhull's reentrant C API, with its messages captured rather than printed.
bool qhull_solid(const VertexMatrix& points, Hull& hull) {
  std::vector<coordT> coords(points.data(), points.data() + points.size());
  char* message = nullptr;
  std::size_t message_size = 0;
  FILE* errfile = open_memstream(&message, &message_size);
  qhT qh_storage;
  qhT* qh = &qh_storage;
  qh_zero(qh, errfile);
  char flags[] = "qhull Qt";
  const int exitcode = qh_new_qhull(qh, 3, static_cast<int>(points.rows()), coords.data(), False,
                                    flags, nullptr, errfile);
  bool ok = exitcode == 0;
  if (ok) {
    std::vector<Eigen::RowVector3i> faces;
    facetT* facet;
    vertexT* vertex;
    vertexT** vertexp;
    FORALLfacets {
      if (qh_setsize(qh, facet->vertices) != 3) {
        ok = false;
        break;
      }
      Eigen::RowVector3i ids;
      int k = 0;
      FOREACHvertex_(facet->vertices) { ids(k++) = qh_pointid(qh, vertex->point); }
      const Vector3 p = points.row(ids(0));
      const Vector3 normal(facet->normal[0], facet->normal[1], facet->normal[2]);
      if ((points.row(ids(1)).transpose() - p)
              .cross(points.row(ids(2)).transpose() - p)
              .dot(normal) < 0) {
        std::swap(ids(1), ids(2));
      }
      faces.push_back(ids);
    }
    FORALLvertices { hull.vertex_indices.push_back(qh_pointid(qh, vertex->point)); }
    hull.faces.resize(static_cast<Eigen::Index>(faces.size()), 3);
    for (std::size_t f = 0; f < faces.size(); ++f) hull.faces.row(f) = faces[f];
  }
  qh_freeqhull(qh, !qh_ALL);
  int still_long = 0;
  int total_long = 0;
  qh_memfreeshort(qh, &still_long, &total_long);
  std::fclose(errfile);
  std::free(message);
  std::sort(hull.vertex_indices.begin(), hull.vertex_indices.end());
  hull.dimension = 3;
  return ok;
}

}  // namespace

namespace detail {

// The edge graph from the triangles (or the segment) in compressed rows, each point's neighbours
// ascending. Every edge of a closed surface (a doubled polygon too) is listed in both directions,
// so bucketing the directed edges by their first point finds all neighbours; a point's bucket
// repeats a neighbour only on a doubled polygon.
void fill_adjacency(Hull& hull, const VertexMatrix& vertices) {
  const Eigen::Index points = vertices.rows();
  const auto for_each_edge = [&hull](const auto& visit) {
    if (hull.dimension == 1) {
      visit(hull.vertex_indices[0], hull.vertex_indices[1]);
      visit(hull.vertex_indices[1], hull.vertex_indices[0]);
    }
    for (Eigen::Index f = 0; f < hull.faces.rows(); ++f) {
      for (int k = 0; k < 3; ++k) visit(hull.faces(f, k), hull.faces(f, (k + 1) % 3));
    }
  };
  std::vector<int>& offsets = hull.neighbour_offsets;
  std::vector<int>& neighbours = hull.neighbours;
  offsets.assign(static_cast<std::size_t>(points) + 1, 0);
  for_each_edge([&offsets](int p, int) { ++offsets[p + 1]; });
  std::partial_sum(offsets.begin(), offsets.end(), offsets.begin());
  neighbours.resize(static_cast<std::size_t>(offsets.back()));
  std::vector<int> next(offsets.begin(), offsets.end() - 1);
  for_each_edge([&](int p, int q) { neighbours[next[p]++] = q; });
  int written = 0;
  for (Eigen::Index i = 0; i < points; ++i) {
    const auto begin = neighbours.begin() + offsets[i];
    const auto end = neighbours.begin() + offsets[i + 1];
    std::sort(begin, end);
    const auto last = std::unique(begin, end);
    offsets[i] = written;
    for (auto it = begin; it != last; ++it) neighbours[written++] = *it;
  }
  offsets[points] = written;
  neighbours.resize(static_cast<std::size_t>(written));
  // Each cell's start by a climb from the previous cell's (the first by a scan), as the
  // adjacency is now in place; a climb stopped short by rounding only makes a start worse.
  // A set of at most kHillClimbingThreshold points is scanned, never climbed: its cells keep the
  // first vertex (a valid start), as the 384 climbs were half the time of answering a fresh
  // 8-point pair by the fcl method (distance_many on point arrays, 39 us a pair).
  hull.climb_starts.assign(kClimbStartCount, hull.vertex_indices.front());
  if (points <= kHillClimbingThreshold) return;
  int last = hull.vertex_indices.front();
  const Vector3 first = climb_cell_centre(0);
  for (int v : hull.vertex_indices) {
    if (point_height(vertices, v, first) > point_height(vertices, last, first)) last = v;
  }
  for (int cell = 0; cell < kClimbStartCount; ++cell) {
    last = climb_support(vertices, hull, climb_cell_centre(cell), last);
    hull.climb_starts[static_cast<std::size_t>(cell)] = last;
  }
}

}  // namespace detail

namespace {

Hull hull_without_adjacency(const VertexMatrix& points) {
  {
    Hull hull;
    if (general_position_hull(points, hull)) return hull;
  }
  const PrincipalAxes frame = principal_axes(points);
  if (frame.dimension == 0) {
    Hull hull;
    hull.vertex_indices = {0};
    return hull;
  }
  if (frame.dimension == 1) return segment_hull(points, frame);
  if (frame.dimension == 3) {
    Hull hull;
    if (points.rows() <= kSmallHullLimit && small_solid_hull(points, hull)) return hull;
    hull = Hull();
    // Qhull refuses sets too thin for its own precision test; they are flat to within rounding.
    if (qhull_solid(points, hull)) return hull;
  }
  return flat_hull(points, frame);
}

}  // namespace

Hull compute_hull(const VertexMatrix& points) {
  if (points.rows() == 0) throw std::invalid_argument("points is empty: the hull needs a point");
  if (!points.allFinite()) {
    throw std::invalid_argument("points has a NaN or infinite coordinate");
  }
  // The hull's combinatorics do not change under translation and scaling; in the unit ball the
  // cross products of coordinates near 1e300 (or 1e-300) neither overflow nor underflow.
  const VertexMatrix unit = detail::normalise(points).points;
  Hull hull = hull_without_adjacency(unit);
  detail::fill_adjacency(hull, unit);
  return hull;
}

}  // namespace swarmcollide
