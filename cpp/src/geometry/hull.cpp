#include "swarmcollide/geometry/hull.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
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
  const Vector3 sigma = svd.singularValues();
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

Hull flat_hull(const VertexMatrix& points, const PrincipalAxes& frame) {
  std::vector<Eigen::Vector2d> projected(points.rows());
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    const Vector3 d = points.row(i).transpose() - frame.mean;
    projected[i] = {d.dot(frame.axes.col(0)), d.dot(frame.axes.col(1))};
  }
  const std::vector<int> ring = polygon_hull(projected);
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

// Up to this many points, trying every plane through three of them beats Qhull's set-up cost.
constexpr Eigen::Index kSmallHullLimit = 16;

// True when the triangles form a closed, consistently oriented surface: every directed edge is
// used once and its reverse once.
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
  if (triangles.size() < 4 || !closed_surface(triangles)) return false;
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

// The edge graph from the triangles (or the segment), deduplicated, in compressed rows.
void fill_adjacency(Hull& hull, Eigen::Index points) {
  std::vector<std::pair<int, int>> edges;
  if (hull.dimension == 1) {
    edges = {{hull.vertex_indices[0], hull.vertex_indices[1]},
             {hull.vertex_indices[1], hull.vertex_indices[0]}};
  }
  for (Eigen::Index f = 0; f < hull.faces.rows(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const int p = hull.faces(f, k);
      const int q = hull.faces(f, (k + 1) % 3);
      edges.emplace_back(p, q);
      edges.emplace_back(q, p);
    }
  }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  hull.neighbour_offsets.assign(static_cast<std::size_t>(points) + 1, 0);
  for (const auto& e : edges) ++hull.neighbour_offsets[e.first + 1];
  std::partial_sum(hull.neighbour_offsets.begin(), hull.neighbour_offsets.end(),
                   hull.neighbour_offsets.begin());
  hull.neighbours.resize(edges.size());
  for (std::size_t k = 0; k < edges.size(); ++k) hull.neighbours[k] = edges[k].second;
}

Hull hull_without_adjacency(const VertexMatrix& points) {
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
  Hull hull = hull_without_adjacency(points);
  fill_adjacency(hull, points.rows());
  return hull;
}

}  // namespace swarmcollide
