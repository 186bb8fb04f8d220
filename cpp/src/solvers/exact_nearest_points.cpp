#include "swarmcollide/solvers/exact_nearest_points.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "exact_internal.hpp"
#include "swarmcollide/problem/certificate.hpp"
#include "wolfe_min_norm.hpp"

namespace swarmcollide {

namespace exact_internal {

namespace {

Scalar diagonal(const ConvexPolyhedron& body) {
  const Aabb box = body.aabb();
  return (box.max - box.min).norm();
}

Vector3 box_centre(const ConvexPolyhedron& body) {
  const Aabb box = body.aabb();
  return (box.max + box.min) / 2;
}

}  // namespace

Vector3 minimum_overlap_normal(const ConvexPolyhedron& a, const ConvexPolyhedron& b) {
  std::vector<Vector3> faces;
  std::vector<Vector3> edges_a;
  std::vector<Vector3> edges_b;
  for (const auto& [body, edges] : {std::pair{&a, &edges_a}, std::pair{&b, &edges_b}}) {
    const Hull& h = body->hull();
    const auto row = [&](int i) -> Vector3 { return body->vertices().row(i).transpose(); };
    if (h.dimension == 1) edges->push_back(row(h.vertex_indices[1]) - row(h.vertex_indices[0]));
    for (Eigen::Index f = 0; f < h.faces.rows(); ++f) {
      const Vector3 p = row(h.faces(f, 0)), q = row(h.faces(f, 1)), r = row(h.faces(f, 2));
      faces.push_back((q - p).cross(r - p));
      edges->insert(edges->end(), {q - p, r - q, p - r});
    }
  }
  std::vector<Vector3> axes = faces;
  axes.insert(axes.end(), {Vector3::UnitX(), Vector3::UnitY(), Vector3::UnitZ()});
  for (const Vector3& e : edges_a) {
    for (const Vector3& g : edges_b) axes.push_back(e.cross(g));
  }
  Vector3 best = Vector3::UnitX();
  Scalar best_separation = -std::numeric_limits<Scalar>::infinity();
  for (const Vector3& axis : axes) {
    if (!(axis.norm() > 0)) continue;
    for (const Vector3& n : {Vector3(axis.normalized()), Vector3(-axis.normalized())}) {
      const Scalar s = separation(a, b, n);
      if (s > best_separation) {
        best_separation = s;
        best = n;
      }
    }
  }
  return best;
}

Scalar pair_scale(const ConvexPolyhedron& a, const ConvexPolyhedron& b) {
  return diagonal(a) + diagonal(b) + (box_centre(b) - box_centre(a)).norm();
}

std::vector<int> supporting_feature(const ConvexPolyhedron& body, const Vector3& normal,
                                    Scalar slack) {
  const VectorX heights = body.vertices() * normal.normalized();
  const Scalar top = heights.maxCoeff();
  std::vector<int> feature;
  for (int i = 0; i < body.size(); ++i) {
    if (heights(i) >= top - slack) feature.push_back(i);
  }
  return feature;
}

VectorX weights_of_nearest(const ConvexPolyhedron& body, const std::vector<int>& candidates,
                           const Vector3& target) {
  const VertexMatrix& v = body.vertices();
  const auto oracle = [&](const Vector3& d) {
    OraclePoint best;
    Scalar lowest = 0;
    for (int k : candidates) {
      const Vector3 p = v.row(k).transpose() - target;
      const Scalar h = d.dot(p);
      if (best.ia < 0 || h < lowest) {
        lowest = h;
        best = {p, k, -1};
      }
    }
    return best;
  };
  Vector3 mean = Vector3::Zero();
  for (int k : candidates) mean += v.row(k).transpose();
  mean /= static_cast<Scalar>(candidates.size());
  const Scalar scale = diagonal(body) + (mean - target).norm();
  const MinNormPoint nearest = wolfe_min_norm(oracle, mean - target, scale, 100);
  VectorX weights = VectorX::Zero(body.size());
  for (int k = 0; k < nearest.size; ++k) weights(nearest.corral[k].ia) += nearest.weights[k];
  return weights / weights.sum();
}

DistanceResult result_from_weights(const ConvexPolyhedron& a, const ConvexPolyhedron& b,
                                   VectorX weights_a, VectorX weights_b, const std::string& method,
                                   Scalar tolerance) {
  DistanceResult r;
  const Vector3 origin = a.vertices().row(0).transpose();
  const Vector3 local_a = (a.vertices().rowwise() - origin.transpose()).transpose() * weights_a;
  const Vector3 local_b = (b.vertices().rowwise() - origin.transpose()).transpose() * weights_b;
  r.point_a = origin + local_a;
  r.point_b = origin + local_b;
  r.weights_a = std::move(weights_a);
  r.weights_b = std::move(weights_b);
  r.distance = (local_b - local_a).norm();
  if (r.distance > 0) {
    const Scalar s = separation(a, b, local_b - local_a);
    if (s > 0) {
      r.lower_bound = s;
      r.direction = (local_b - local_a) / r.distance;
    }
  }
  r.colliding = r.distance <= tolerance;
  r.certified = r.colliding || r.lower_bound > tolerance;
  r.method = method;
  r.status = SolverStatus::exact;
  return r;
}

DistanceResult result_from_witnesses(const ConvexPolyhedron& a, const ConvexPolyhedron& b,
                                     const Vector3& point_a, const Vector3& point_b,
                                     const std::string& method, Scalar tolerance) {
  const Vector3 n = point_b - point_a;
  std::vector<int> feature_a;
  std::vector<int> feature_b;
  if (n.norm() > 0) {
    // A generous slack: projecting onto a slightly larger face of the body costs nothing, while
    // a too small one could cut the true feature.
    const Scalar slack = 1e-6 * pair_scale(a, b);
    feature_a = supporting_feature(a, n, slack);
    feature_b = supporting_feature(b, -n, slack);
  } else {
    for (int i = 0; i < a.size(); ++i) feature_a.push_back(i);
    for (int j = 0; j < b.size(); ++j) feature_b.push_back(j);
  }
  return result_from_weights(a, b, weights_of_nearest(a, feature_a, point_a),
                             weights_of_nearest(b, feature_b, point_b), method, tolerance);
}

DistanceResult nearest_points(const ConvexPolyhedron& a, const ConvexPolyhedron& b,
                              const ExactOptions& options, const std::string& method) {
  const VertexMatrix& x = a.vertices();
  const VertexMatrix& y = b.vertices();
  const auto oracle = [&](const Vector3& d) {
    const int i = a.support_index(d);
    const int j = b.support_index(-d);
    return OraclePoint{(y.row(j) - x.row(i)).transpose(), i, j};
  };
  const Vector3 start = (y.colwise().mean() - x.colwise().mean()).transpose();
  const MinNormPoint nearest =
      wolfe_min_norm(oracle, start, pair_scale(a, b), options.max_iterations);
  VectorX weights_a = VectorX::Zero(a.size());
  VectorX weights_b = VectorX::Zero(b.size());
  for (int k = 0; k < nearest.size; ++k) {
    weights_a(nearest.corral[k].ia) += nearest.weights[k];
    weights_b(nearest.corral[k].ib) += nearest.weights[k];
  }
  weights_a /= weights_a.sum();
  weights_b /= weights_b.sum();
  DistanceResult r = result_from_weights(a, b, std::move(weights_a), std::move(weights_b), method,
                                         options.tolerance);
  r.iterations = nearest.iterations;
  return r;
}

bool is_certified_optimal(const ConvexPolyhedron& a, const ConvexPolyhedron& b,
                          const DistanceResult& result) {
  return result.colliding || result.distance - result.lower_bound <= 1e-10 * pair_scale(a, b);
}

DistanceResult penetration_result(const ConvexPolyhedron& a, const ConvexPolyhedron& b,
                                  const Vector3& normal, Scalar depth, const std::string& method,
                                  Scalar tolerance) {
  Vector3 n = normal.normalized();
  DistanceResult r;
  r.lower_bound = separation(a, b, n);
  // The overlap along any normal is a separating translation, so it bounds the depth from above;
  // when it exceeds the library's depth by more than rounding, the library missed the optimum
  // and the exact search over the Minkowski difference's facet normals takes over.
  if (r.lower_bound < -depth - 1e-9 * pair_scale(a, b)) {
    n = minimum_overlap_normal(a, b);
    r.lower_bound = separation(a, b, n);
  }
  r.distance = r.lower_bound;
  r.direction = n;
  // Witnesses: the nearest points of A's supporting feature along n and B's along -n once B is
  // translated by the overlap, which brings the two supporting planes together.
  const Scalar slack = 1e-9 * pair_scale(a, b);
  const std::vector<int> fa = supporting_feature(a, n, slack);
  const std::vector<int> fb = supporting_feature(b, -n, slack);
  VertexMatrix va(static_cast<Eigen::Index>(fa.size()), 3);
  VertexMatrix vb(static_cast<Eigen::Index>(fb.size()), 3);
  for (std::size_t k = 0; k < fa.size(); ++k) va.row(k) = a.vertices().row(fa[k]);
  for (std::size_t k = 0; k < fb.size(); ++k) {
    vb.row(k) = b.vertices().row(fb[k]) - r.lower_bound * n.transpose();
  }
  const DistanceResult faces =
      nearest_points(ConvexPolyhedron(va), ConvexPolyhedron(vb), ExactOptions{}, method);
  r.weights_a = VectorX::Zero(a.size());
  r.weights_b = VectorX::Zero(b.size());
  for (std::size_t k = 0; k < fa.size(); ++k) r.weights_a(fa[k]) = faces.weights_a(k);
  for (std::size_t k = 0; k < fb.size(); ++k) r.weights_b(fb[k]) = faces.weights_b(k);
  r.point_a = a.vertices().transpose() * r.weights_a;
  r.point_b = b.vertices().transpose() * r.weights_b;
  r.colliding = r.distance <= tolerance;
  r.certified = r.colliding || r.lower_bound > tolerance;
  r.method = method;
  r.status = SolverStatus::exact;
  return r;
}

}  // namespace exact_internal

DistanceResult exact_nearest_points(const ConvexPolyhedron& a, const ConvexPolyhedron& b,
                                    const ExactOptions& options) {
  options.validate();
  return exact_internal::nearest_points(a, b, options, "wolfe");
}

}  // namespace swarmcollide
