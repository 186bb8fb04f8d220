// The random polytope pairs of the C++ benches that compare with FCL and coal: two hulls of
// points on the unit sphere, B moved until the pair's signed distance is a target. Shared by
// swarmcollide_bench.cpp and narrowphase_coal.cpp, so that both measure the same bodies.
#pragma once

#include <fcl/narrowphase/distance.h>

#include <algorithm>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <utility>
#include <vector>

#include "normals.hpp"
#include "swarmcollide/geometry/convex_polyhedron.hpp"

// The hull vertices of `n` random points on the unit sphere.
inline swarmcollide::VertexMatrix sphere_polytope(int n, Normals& normals) {
  swarmcollide::VertexMatrix points(n, 3);
  for (int i = 0; i < n; ++i) points.row(i) = normals.unit().transpose();
  const swarmcollide::ConvexPolyhedron body(points);
  const std::vector<int>& indices = body.hull().vertex_indices;
  swarmcollide::VertexMatrix vertices(static_cast<Eigen::Index>(indices.size()), 3);
  for (std::size_t k = 0; k < indices.size(); ++k) vertices.row(k) = points.row(indices[k]);
  return vertices;
}

// The body's hull as an fcl::Convexd translated by -origin, as an FCL user would build it.
inline std::shared_ptr<fcl::Convexd> to_fcl(const swarmcollide::ConvexPolyhedron& body,
                                            const swarmcollide::Vector3& origin) {
  const swarmcollide::Hull& hull = body.hull();
  std::vector<int> local(body.size(), -1);
  auto vertices = std::make_shared<std::vector<fcl::Vector3d>>();
  for (int i : hull.vertex_indices) {
    local[i] = static_cast<int>(vertices->size());
    vertices->push_back(body.vertices().row(i).transpose() - origin);
  }
  auto faces = std::make_shared<std::vector<int>>();
  for (Eigen::Index f = 0; f < hull.faces.rows(); ++f) {
    faces->insert(faces->end(),
                  {3, local[hull.faces(f, 0)], local[hull.faces(f, 1)], local[hull.faces(f, 2)]});
  }
  return std::make_shared<fcl::Convexd>(vertices, static_cast<int>(hull.faces.rows()), faces);
}

inline fcl::DistanceResultd fcl_distance_raw(const fcl::Convexd& a, const fcl::Convexd& b,
                                             const swarmcollide::Vector3& shift_b,
                                             bool signed_distance, fcl::GJKSolverType solver) {
  const fcl::DistanceRequestd request(true, signed_distance, 0, 0, 1e-10, solver);
  fcl::DistanceResultd result;
  fcl::Transform3d pose_b = fcl::Transform3d::Identity();
  pose_b.translation() = shift_b;
  fcl::distance(&a, fcl::Transform3d::Identity(), &b, pose_b, request, result);
  return result;
}

// Two random n-vertex polytopes, B moved along a random ray from A's centroid until FCL's
// distance (GST_LIBCCD; for overlaps its signed distance, EPA) is `target`, by bisection on the
// translation. Thin bodies cannot overlap by some targets: such draws are replaced by the next.
// Returns the points of A and of B.
inline std::pair<swarmcollide::VertexMatrix, swarmcollide::VertexMatrix> random_pair_points(
    int n, double target, std::uint64_t seed) {
  namespace sc = swarmcollide;
  Normals normals(seed);
  for (;;) {
    const sc::VertexMatrix a_points = sphere_polytope(n, normals);
    sc::VertexMatrix b0_points = sphere_polytope(n, normals);
    const sc::Vector3 u = normals.unit();
    b0_points.rowwise() += (a_points.colwise().mean() - b0_points.colwise().mean()).eval();
    const sc::ConvexPolyhedron a(a_points), b0(b0_points);
    const sc::Vector3 origin = a.aabb().min / 2 + a.aabb().max / 2;
    const auto fa = to_fcl(a, origin), fb = to_fcl(b0, origin);
    auto signed_distance = [&](double t) {
      return fcl_distance_raw(*fa, *fb, t * u, target < 0, fcl::GST_LIBCCD).min_distance;
    };
    // At t = 0 the centroids coincide; at t0 the separation along u is `target`, a lower bound
    // on the signed distance.
    double lo = 0;
    if (!(signed_distance(lo) < target)) continue;
    double hi = std::max(0.0, target + (a_points * u).maxCoeff() - (b0_points * u).minCoeff());
    for (int k = 0; signed_distance(hi) < target; ++k) {
      if (k == 100) throw std::runtime_error("random_pair: no upper bracket");
      hi += 0.5;
    }
    for (int step = 0; step < 64 && hi - lo > 1e-15; ++step) {
      const double mid = (lo + hi) / 2;
      (signed_distance(mid) < target ? lo : hi) = mid;
    }
    return {a_points, b0_points.rowwise() + hi * u.transpose()};
  }
}

// A proximity of the random workloads: its name and the pairs' signed distance.
struct BenchProximity {
  const char* name;
  double target;
};

// swarmcollide_bench.cpp's proximities, in its order: a proximity's index in this list seeds its
// pairs (random_pair_seed).
inline const std::vector<BenchProximity>& bench_proximities() {
  static const std::vector<BenchProximity> proximities = {
      {"apart", 1.0},          {"gap 1e-1", 1e-1},      {"gap 1e-2", 1e-2},
      {"gap 1e-3", 1e-3},      {"gap 1e-4", 1e-4},      {"overlap 1e-4", -1e-4},
      {"overlap 1e-3", -1e-3}, {"overlap 1e-2", -1e-2}, {"overlap 1e-1", -1e-1}};
  return proximities;
}

// The seed of pair `index` of a workload of `n`-vertex bodies at proximity number `proximity`
// (in swarmcollide_bench.cpp's full list): it depends on the size, proximity and index only.
inline std::uint64_t random_pair_seed(int n, int proximity, int index) {
  return 1000003ULL * static_cast<std::uint64_t>(n) + 1009ULL * proximity + index;
}
