#include "swarmcollide/geometry/hull.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
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
