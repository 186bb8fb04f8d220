// Steady-state solves allocate nothing but their result's arrays (the exact methods' results,
// with sparse weights and no history, have none). This binary replaces malloc
// (glibc lets an executable interpose it) to count every heap allocation, Eigen's included.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstddef>

#include "solvers/penetration.hpp"
#include "swarmcollide/geometry/hull.hpp"
#include "swarmcollide/queries/batch.hpp"
#include "swarmcollide/queries/methods.hpp"
#include "swarmcollide/queries/query.hpp"

extern "C" void* __libc_malloc(std::size_t size);
extern "C" void* __libc_calloc(std::size_t count, std::size_t size);
extern "C" void* __libc_realloc(void* pointer, std::size_t size);
extern "C" void __libc_free(void* pointer);

namespace {
std::atomic<long> allocations{0};
// Every call of free(), free(nullptr) included: a call for nothing is a cost of its own.
std::atomic<long> frees{0};
}

extern "C" void* malloc(std::size_t size) {
  allocations.fetch_add(1, std::memory_order_relaxed);
  return __libc_malloc(size);
}
extern "C" void* calloc(std::size_t count, std::size_t size) {
  allocations.fetch_add(1, std::memory_order_relaxed);
  return __libc_calloc(count, size);
}
extern "C" void* realloc(void* pointer, std::size_t size) {
  allocations.fetch_add(1, std::memory_order_relaxed);
  return __libc_realloc(pointer, size);
}

extern "C" void free(void* pointer) {
  frees.fetch_add(1, std::memory_order_relaxed);
  __libc_free(pointer);
}

namespace swarmcollide {
namespace {

template <typename Work>
long allocations_during(Work&& work) {
  const long before = allocations.load();
  work();
  return allocations.load() - before;
}

template <typename Work>
long frees_during(Work&& work) {
  const long before = frees.load();
  work();
  return frees.load() - before;
}

// n points spread over the unit sphere (a golden-angle spiral), the hull's every vertex.
VertexMatrix sphere_points(int n) {
  VertexMatrix points(n, 3);
  for (int i = 0; i < n; ++i) {
    const double t = 2.399963 * i;
    const double z = 1 - (2.0 * i + 1) / n;
    const double r = std::sqrt(1 - z * z);
    points.row(i) << r * std::cos(t), r * std::sin(t), z;
  }
  return points;
}

TEST(AllocationCount, SeesEveryHeapAllocation) {
  EXPECT_EQ(allocations_during([] { VectorX(100).setZero(); }), 1);
}

struct AllocationCase {
  Method method;
  const char* name;
};

class SteadyState : public ::testing::TestWithParam<AllocationCase> {};

TEST_P(SteadyState, ASolveAllocatesNoMoreThanCopyingItsResult) {
  VertexMatrix A(4, 3);
  A << 0, 1, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0;
  VertexMatrix B(4, 3);
  B << 1, -1, 0, 2, -2, 0, 0, -2, 2, 0, -2, 0;
  const ConvexPolyhedron a(A), b(B);
  QueryOptions options;
  options.method = GetParam().method;
  options.tolerance = 0;  // the whole budget: every iteration runs
  DistanceResult warm_up = Query(options).distance(a, b);
  options.seed = 1;
  const Query query(options);

  DistanceResult result;
  const long solve = allocations_during([&] { result = query.distance(a, b); });
  DistanceResult copy;
  const long result_arrays = allocations_during([&] { copy = result; });
  EXPECT_LE(solve, result_arrays) << GetParam().name;
  // The free function builds (and validates) its query on the stack.
  const long through_function = allocations_during([&] { result = distance(a, b, options); });
  EXPECT_LE(through_function, result_arrays) << GetParam().name;
}

// A distance or verdict the dual settles with Wolfe's start (nearly every pair) allocates nothing:
// its answer's weights are sparse, and its history (one value) is held in place (History).
TEST(DualSteadyState, ADistanceSettledByItsStartAllocatesNothing) {
  for (const int n : {4, 8, 64}) {
    const VertexMatrix points = sphere_points(n);
    const ConvexPolyhedron a(points);
    for (const double offset : {3.0, 2.01, 1.5}) {  // apart, near, overlapping
      const ConvexPolyhedron b(points.rowwise() + Eigen::RowVector3d(offset, 0.1, -0.2));
      const Query query{QueryOptions{}};
      DistanceResult result = query.distance(a, b);
      ASSERT_TRUE(result.certified);
      ASSERT_EQ(result.history.size(), 1u);
      EXPECT_EQ(allocations_during([&] { result = query.distance(a, b); }), 0)
          << n << " points, offset " << offset;
      EXPECT_EQ(allocations_during([&] { result = query.collision(a, b); }), 0)
          << n << " points, offset " << offset;
    }
  }
}

// Nor does it call free(): a query makes and drops an answer's and a result's weights, which an
// empty Eigen vector, freed with free(nullptr), made a call each (ConvexWeights holds a dense
// vector only for dense weights), and a batch row an answer's.
TEST(DualSteadyState, ADistanceSettledByItsStartCallsNoFree) {
  const VertexMatrix points = sphere_points(8);
  const ConvexPolyhedron a(points);
  Pose pose;
  pose.translation << 0.1, 0.2, 0.3;
  for (const double offset : {3.0, 2.01, 1.5}) {  // apart, near, overlapping
    const ConvexPolyhedron b(points.rowwise() + Eigen::RowVector3d(offset, 0.1, -0.2));
    const Query query{QueryOptions{}};
    DistanceResult result = query.distance(a, pose, b, pose);
    bool colliding = query.collide(a, pose, b, pose);
    ASSERT_TRUE(result.certified);
    EXPECT_EQ(frees_during([&] { result = query.distance(a, pose, b, pose); }), 0) << offset;
    EXPECT_EQ(frees_during([&] { result = query.collision(a, pose, b, pose); }), 0) << offset;
    EXPECT_EQ(frees_during([&] { colliding = query.collide(a, pose, b, pose); }), 0) << offset;
    EXPECT_EQ(colliding, result.colliding);
  }
}

INSTANTIATE_TEST_SUITE_P(Methods, SteadyState,
                         ::testing::Values(AllocationCase{Method::ipso, "ipso"},
                                           AllocationCase{Method::pso, "pso"},
                                           AllocationCase{Method::dual, "dual"},
                                           AllocationCase{Method::exact, "exact"},
                                           AllocationCase{Method::fcl, "fcl"}),
                         [](const auto& info) { return std::string(info.param.name); });

TEST(PenetrationSteadyState, AllocatesNothing) {
  // Points on two overlapping spheres (or a sphere and a disc): small (scanned) and large
  // (climbed) bodies, through the polytope and, with one iteration, through the candidate axes.
  for (const int n : {12, 200}) {
    for (const bool flat : {false, true}) {
      VertexMatrix a(n, 3);
      VertexMatrix b(n, 3);
      for (int i = 0; i < n; ++i) {
        const double t = 2.399963 * i;
        const double z = 1 - (2.0 * i + 1) / n;
        const double r = std::sqrt(1 - z * z);
        a.row(i) << r * std::cos(t), r * std::sin(t), flat ? 0 : z;
        b.row(i) << r * std::cos(t + 1) + 0.7, r * std::sin(t + 1) + 0.2, -z;
      }
      const Hull ha = compute_hull(a);
      const Hull hb = compute_hull(b);
      for (const int iterations : {1000, 1}) {
        detail::PenetrationBounds r =
            detail::penetration(a, ha, b, hb, Vector3::Zero(), 1e-9, iterations);
        ASSERT_TRUE(r.proven) << n << " " << iterations;
        const long solve = allocations_during(
            [&] { r = detail::penetration(a, ha, b, hb, Vector3::Zero(), 1e-9, iterations); });
        // The witnesses' weights are sparse (at most four points each): nothing to allocate.
        EXPECT_EQ(solve, 0) << n << " points, " << iterations << " iterations, flat " << flat;
      }
    }
  }
}

// A signed distance of overlapping placed bodies works on the bodies where they are (no copy of
// their points in the frame) and answers with sparse weights: a warmed-up query allocates nothing.
TEST(PenetrationSteadyState, AnOverlappingSignedDistanceAllocatesNothing) {
  for (const int n : {12, 200}) {
    const VertexMatrix points = sphere_points(n);
    const ConvexPolyhedron a(points), b(points);
    const Pose pose_a{Eigen::AngleAxisd(0.3, Vector3(1, 2, 3).normalized()).toRotationMatrix(),
                      Vector3::Zero()};
    const Pose pose_b{Eigen::AngleAxisd(1.1, Vector3(-2, 1, 1).normalized()).toRotationMatrix(),
                      Vector3(0.9, 0.4, -0.2)};
    for (const Method method : {Method::dual, Method::exact}) {
      QueryOptions options;
      options.method = method;
      const Query query(options);
      DistanceResult result = query.signed_distance(a, pose_a, b, pose_b);
      ASSERT_TRUE(result.certified && result.distance < -0.1) << n;
      const long solve =
          allocations_during([&] { result = query.signed_distance(a, pose_a, b, pose_b); });
      EXPECT_EQ(solve, 0) << n << " points, method " << method_name(method);
    }
  }
}

// A batch allocates its result columns and its bookkeeping, and per row no more than the single
// query allocates for its own result's arrays (the dual's history, a penetration's weights): no
// body is copied, no query rebuilt, no pose list made (one thread, so no thread is started).
TEST(BatchSteadyState, RowsAllocateNoMoreThanTheirSingleQueries) {
  const VertexMatrix points = sphere_points(40);
  const ConvexPolyhedron a(points);
  const ConvexPolyhedron b(points.topRows(8).eval());
  BatchPoses few, many;
  for (int i = 0; i < 1000; ++i) {
    Pose pose;
    pose.rotation = Eigen::AngleAxisd(0.01 * i, Vector3(1, 2, 3).normalized()).toRotationMatrix();
    pose.translation = Vector3(0.5 + 0.003 * i, 0.2, -0.1);  // overlapping to well apart
    if (i % 100 == 0) few.b.push_back(pose);
    many.b.push_back(pose);
  }
  BatchSettings one_thread;
  one_thread.threads = 1;
  for (const Method method : {Method::dual, Method::exact}) {
    QueryOptions options;
    options.method = method;
    collide_many(a, b, options, one_thread, many);  // the bodies' hulls and balls, once
    const Query query(options);
    const long singles = allocations_during([&] {
      for (const Pose& pose : many.b) {
        query.distance(a, {}, b, pose);
        query.signed_distance(a, {}, b, pose);
      }
    });
    const long rows_10 =
        allocations_during([&] { distance_many(a, b, options, one_thread, few); }) +
        allocations_during([&] { collide_many(a, b, options, one_thread, few); }) +
        allocations_during([&] { signed_distance_many(a, b, options, one_thread, few); });
    const long rows_1000 =
        allocations_during([&] { distance_many(a, b, options, one_thread, many); }) +
        allocations_during([&] { collide_many(a, b, options, one_thread, many); }) +
        allocations_during([&] { signed_distance_many(a, b, options, one_thread, many); });
    EXPECT_LE(rows_1000 - rows_10, singles) << method_name(method);
    if (method == Method::exact) EXPECT_LT(rows_1000 - rows_10, 200);  // penetrations' weights
    // The dual's distances and verdicts allocate nothing per row: a batch keeps no history.
    const long verdicts_and_distances =
        allocations_during([&] { distance_many(a, b, options, one_thread, many); }) +
        allocations_during([&] { collide_many(a, b, options, one_thread, many); }) -
        allocations_during([&] { distance_many(a, b, options, one_thread, few); }) -
        allocations_during([&] { collide_many(a, b, options, one_thread, few); });
    if (method == Method::dual) EXPECT_EQ(verdicts_and_distances, 0);
  }
}

}  // namespace
}  // namespace swarmcollide
