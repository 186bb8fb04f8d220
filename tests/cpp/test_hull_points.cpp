// The hull points: which given points the exact solvers read, and that answers over them are the
// answers over every given point.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

#include "contract.hpp"
#include "oracle.hpp"
#include "shapes.hpp"
#include "swarmcollide/geometry/convex_polyhedron.hpp"
#include "swarmcollide/queries/methods.hpp"
#include "swarmcollide/queries/query.hpp"

namespace swarmcollide::testing {
namespace {

// 45 points of a Fibonacci lattice on the unit sphere (each one a vertex of their hull) among
// 1,955 points strictly inside that hull and 10 exact repeats of vertices, shuffled.
struct DenseBody {
  VertexMatrix points;
  // Rows of the 45 vertices (their first copies), ascending.
  std::vector<int> hull_rows;
  VertexMatrix hull;
};

DenseBody dense_body(std::uint64_t seed) {
  constexpr int kVertices = 45;
  constexpr int kInside = 1955;
  constexpr int kRepeats = 10;
  VertexMatrix sphere(kVertices, 3);
  const Scalar golden = M_PI * (3 - std::sqrt(5.0));
  for (int i = 0; i < kVertices; ++i) {
    const Scalar z = 1 - 2 * (i + 0.5) / kVertices;
    const Scalar r = std::sqrt(1 - z * z);
    sphere.row(i) << r * std::cos(golden * i), r * std::sin(golden * i), z;
  }
  Random rng(seed);
  const int n = kVertices + kInside + kRepeats;
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  for (int i = n - 1; i > 0; --i) {
    std::swap(order[i], order[static_cast<int>(rng.uniform(0, i + 1)) % (i + 1)]);
  }
  DenseBody body{VertexMatrix(n, 3), {}, sphere};
  for (int k = 0; k < n; ++k) {
    Vector3 p;
    if (k < kVertices) {
      p = sphere.row(k);
    } else if (k < kVertices + kInside) {
      // A convex combination of four vertices pulled towards the centre, which is inside.
      Vector3 sum = Vector3::Zero();
      Scalar total = 0;
      for (int c = 0; c < 4; ++c) {
        const Scalar w = rng.uniform(0, 1);
        sum += w * sphere.row(static_cast<int>(rng.uniform(0, kVertices)) % kVertices).transpose();
        total += w;
      }
      p = 0.98 * sum / total;
    } else {
      p = sphere.row(k - kVertices - kInside);
    }
    body.points.row(order[k]) = p.transpose();
  }
  for (int k = 0; k < kVertices; ++k) {
    const int copy = std::min(order[k], order[k < kRepeats ? kVertices + kInside + k : k]);
    body.hull_rows.push_back(copy);
  }
  std::sort(body.hull_rows.begin(), body.hull_rows.end());
  return body;
}

Query query_of(Method method) {
  QueryOptions options;
  options.method = method;
  // The paper's swarms and the penalty method are not expected to converge here, only to keep
  // their contract (bounds, weights over every given point); a short budget keeps them quick.
  options.swarm.swarm_size = 10;
  options.swarm.max_iterations = 20;
  options.penalty.outer_iterations = 2;
  options.penalty.inner_iterations = 50;
  return Query(options);
}

bool over_hull(Method method) {
  return method == Method::dual || method == Method::exact || method == Method::fcl ||
         method == Method::libccd;
}

void expect_weights_over_given_points(const DistanceResult& r, const DenseBody& body,
                                      Method method) {
  ASSERT_EQ(r.weights_a.count(), body.points.rows());
  const VectorX w = r.weights_a.dense();
  EXPECT_NEAR(w.sum(), 1, 1e-12);
  EXPECT_TRUE((body.points.transpose() * w).isApprox(r.point_a, 1e-9));
  if (!over_hull(method)) return;
  for (int i = 0; i < w.size(); ++i) {
    if (!std::binary_search(body.hull_rows.begin(), body.hull_rows.end(), i)) EXPECT_EQ(w(i), 0);
  }
}

TEST(HullPoints, ADenseSamplingKeepsOnlyTheFirstCopiesOfTheHullVertices) {
  const DenseBody dense = dense_body(3);
  const ConvexPolyhedron body(dense.points);
  // Every given point until the hull is found (asking does not find it), its 45 vertices after.
  EXPECT_EQ(body.read_point_count(), body.size());
  EXPECT_EQ(body.read_point_count(), body.size());
  const HullPoints& read = body.hull_points();
  EXPECT_EQ(body.read_point_count(), 45);
  ASSERT_FALSE(read.every_point);
  EXPECT_EQ(read.indices, dense.hull_rows);
  EXPECT_EQ(read.hull.vertex_indices.size(), 45u);
  EXPECT_EQ(read.hull.faces.rows(), 86);
  for (std::size_t k = 0; k < read.indices.size(); ++k) {
    EXPECT_EQ(read.centred.row(k), body.centred_vertices().row(read.indices[k]));
  }
  // A support over the hull points is a support over every point.
  Random rng(4);
  for (int k = 0; k < 100; ++k) {
    const Vector3 d = rng.unit();
    EXPECT_EQ(dense.points.row(body.support_index(d)).dot(d), (dense.points * d).maxCoeff());
    EXPECT_EQ(dense.points.row(body.support_index(d, k)).dot(d), (dense.points * d).maxCoeff());
  }
}

TEST(HullPoints, EveryMethodAnswersAsTheHullWithWeightsOverTheGivenPoints) {
  const DenseBody dense = dense_body(5);
  const ConvexPolyhedron body(dense.points);
  const ConvexPolyhedron hull(dense.hull);
  Random rng(6);
  for (const Vector3& offset : {Vector3(2.5, 0.3, -0.2), Vector3(1.2, 1.1, 0.4),
                                Vector3(0.3, -0.2, 0.1), Vector3(1.9, 0, 0)}) {
    const ConvexPolyhedron other = moved(rng.body(12), offset);
    const Reference truth = reference(body, other);
    for (const MethodInfo& info : method_table()) {
      SCOPED_TRACE(std::string(info.name) + " at " + std::to_string(offset.x()));
      const Query query = query_of(info.method);
      const Scalar size = scale_of(body, other, query.options().tolerance).size;
      const Scalar slack = 1e-12 * size;
      if (info.capabilities & kDistance) {
        const DistanceResult d = query.distance(body, other);
        EXPECT_LE(d.lower_bound, truth.distance + slack);
        EXPECT_GE(d.distance, truth.distance - slack);
        expect_weights_over_given_points(d, dense, info.method);
        if (info.always_certified) {
          const DistanceResult h = query.distance(hull, other);
          EXPECT_TRUE(d.certified);
          EXPECT_NEAR(d.distance, h.distance, query.options().tolerance * size);
        }
      }
      if (info.capabilities & kSignedDistance) {
        const DistanceResult s = query.signed_distance(body, other);
        EXPECT_LE(s.lower_bound, truth.signed_distance + slack);
        EXPECT_GE(s.distance, truth.signed_distance - slack);
        EXPECT_TRUE(s.certified);
        expect_weights_over_given_points(s, dense, info.method);
        EXPECT_NEAR(s.distance, query.signed_distance(hull, other).distance,
                    query.options().tolerance * size);
      }
      EXPECT_EQ(query.collide(body, other), truth.distance == 0);
    }
  }
}

// A point over a face by 1e-15 of the size is within Qhull's tolerance, and Qhull leaves it off
// the vertices; it is extreme all the same, and stays among the hull points. One 1e-14 inside is
// proven inside, and left out.
TEST(HullPoints, AnExtremePointTheHullLeavesOutIsKept) {
  VertexMatrix points(45, 3);
  points.topRows(4) << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1;
  Random rng(7);
  for (int i = 5; i < points.rows(); ++i) {
    const Vector3 w(rng.uniform(0.05, 0.3), rng.uniform(0.05, 0.3), rng.uniform(0.05, 0.3));
    points.row(i) = w.transpose();
  }
  const Vector3 out = Vector3::Ones().normalized();
  for (const Scalar height : {1e-15, -1e-14}) {
    SCOPED_TRACE(height);
    points.row(4) = (Vector3::Constant(1.0 / 3) + height * out).transpose();
    const ConvexPolyhedron body(points);
    EXPECT_EQ(body.hull().vertex_indices, (std::vector<int>{0, 1, 2, 3}));
    ASSERT_EQ(points.row(4).dot(out) > points.row(1).dot(out), height > 0);
    const std::vector<int> expected =
        height > 0 ? std::vector<int>{0, 1, 2, 3, 4} : std::vector<int>{0, 1, 2, 3};
    EXPECT_EQ(body.hull_points().indices, expected);
    EXPECT_EQ(body.support_index(out) == 4, height > 0);
    EXPECT_EQ(body.support_index(out, 0) == 4, height > 0);
  }
}

// A cube's corners among points on its faces, a few ulps inside them and deep inside, and one
// point a few ulps outside a face (the only point beyond that face's plane: extreme, so it must
// be kept): whatever Qhull merges, no point left out is above the hull points along any
// direction, beyond the rounding of the heights.
TEST(HullPoints, NoPointLeftOutIsAboveTheKeptOnesNearCoplanarFaces) {
  Random rng(10);
  int left_off_by_qhull = 0;
  for (int trial = 0; trial < 20; ++trial) {
    SCOPED_TRACE(trial);
    VertexMatrix points(300, 3);
    for (int i = 0; i < 8; ++i) points.row(i) << (i & 1), (i >> 1 & 1), (i >> 2 & 1);
    const int outside = 8 + 7 * trial;
    for (int i = 8; i < points.rows(); ++i) {
      Vector3 p(rng.uniform(0, 1), rng.uniform(0, 1), rng.uniform(0, 1));
      const int axis = i % 3;
      const int kind = i % 3;
      if (kind < 2 || i == outside) p(axis) = rng.uniform() < 0 ? 0 : 1;  // on a face
      const Scalar nudge = std::ldexp(1.0, -52) * (1 + i % 5);
      const Scalar out = p(axis) == 1 ? nudge : -nudge;
      if (kind == 1 && i != outside) p(axis) -= out;  // inside by a few ulps
      if (i == outside) p(axis) += out;
      points.row(i) = p.transpose();
    }
    const ConvexPolyhedron body(points);
    const HullPoints& read = body.hull_points();
    ASSERT_FALSE(read.every_point);
    EXPECT_TRUE(std::binary_search(read.indices.begin(), read.indices.end(), outside));
    const std::vector<int>& vertices = body.hull().vertex_indices;
    left_off_by_qhull += !std::binary_search(vertices.begin(), vertices.end(), outside);
    VertexMatrix kept(read.indices.size(), 3);
    for (std::size_t k = 0; k < read.indices.size(); ++k) kept.row(k) = points.row(read.indices[k]);
    for (int k = 0; k < 50; ++k) {
      const Vector3 d = rng.unit();
      EXPECT_LE((points * d).maxCoeff(), (kept * d).maxCoeff() + 1e-15);
    }
  }
  EXPECT_GT(left_off_by_qhull, 0);  // the case this guards against does occur
}

TEST(HullPoints, DegenerateBodiesKeepEveryPointButRepeats) {
  Random rng(8);
  VertexMatrix flat(60, 3);
  VertexMatrix line(60, 3);
  for (int i = 0; i < 60; ++i) {
    flat.row(i) << rng.uniform(), rng.uniform(), 0.5;
    line.row(i) = (Vector3(1, 2, 3) * rng.uniform()).transpose();
  }
  flat.bottomRows(20) = flat.topRows(20);
  line.bottomRows(20) = line.topRows(20);
  std::vector<int> first_forty(40);
  std::iota(first_forty.begin(), first_forty.end(), 0);
  const VertexMatrix point = VertexMatrix::Constant(40, 3, 0.25);
  const ConvexPolyhedron bodies[] = {ConvexPolyhedron(flat), ConvexPolyhedron(line),
                                     ConvexPolyhedron(point)};
  const std::vector<int> kept[] = {first_forty, first_forty, {0}};
  const ConvexPolyhedron other = moved(unit_cube(), Vector3(1.5, 0.2, 0.1));
  for (int k = 0; k < 3; ++k) {
    SCOPED_TRACE(k);
    EXPECT_EQ(bodies[k].hull_points().indices, kept[k]);
    const Reference truth = reference(bodies[k], other);
    for (const Method method : {Method::dual, Method::exact, Method::fcl}) {
      const DistanceResult d = query_of(method).distance(bodies[k], other);
      EXPECT_TRUE(d.certified);
      EXPECT_LE(d.lower_bound, truth.distance + 1e-12);
      EXPECT_GE(d.distance, truth.distance - 1e-12);
      EXPECT_EQ(d.weights_a.count(), bodies[k].size());
    }
  }
}

// The hull points are decided on the centred points scaled by a power of two, so bodies scaled
// by powers of two and translated exactly (points on a grid of 2^-10, integer offsets) keep the
// same ones.
TEST(HullPoints, SameUnderPowerOfTwoScalesAndExactTranslations) {
  DenseBody dense = dense_body(9);
  for (Eigen::Index i = 0; i < dense.points.size(); ++i) {
    dense.points.data()[i] = std::round(dense.points.data()[i] * 1024) / 1024;
  }
  const ConvexPolyhedron body(dense.points);
  for (const Scalar scale : {0x1p-40, 0x1p30}) {
    for (const Vector3& offset : {Vector3(0, 0, 0), Vector3(3, -7, 1024)}) {
      const ConvexPolyhedron other = transformed(moved(body, offset), scale, Vector3::Zero());
      EXPECT_EQ(other.hull_points().indices, body.hull_points().indices);
    }
  }
}

}  // namespace
}  // namespace swarmcollide::testing
