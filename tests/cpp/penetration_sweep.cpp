// Timing and robustness sweep of the penetration solver (not a ctest test; run by hand):
//   swarmcollide_penetration_sweep timing [pairs]   per-call times by size
//   swarmcollide_penetration_sweep sweep [cases]    random cases of sizes 4-4096 against the oracle
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <random>
#include <string>
#include <vector>

#include "penetration_oracle.hpp"
#include "solvers/penetration.hpp"
#include "swarmcollide/geometry/hull.hpp"

namespace sc = swarmcollide;
using sc::Scalar;
using sc::Vector3;
using sc::VertexMatrix;

namespace {

using Clock = std::chrono::steady_clock;  // wall time, for the sweep's total

struct Body {
  VertexMatrix points;
  sc::Hull hull;
};

Body make(VertexMatrix points) {
  sc::Hull hull = sc::compute_hull(points);
  return {std::move(points), std::move(hull)};
}

VertexMatrix gaussian(std::mt19937_64& rng, int n, Scalar radius) {
  std::normal_distribution<Scalar> g;
  VertexMatrix v(n, 3);
  for (int i = 0; i < n; ++i) v.row(i) << g(rng), g(rng), g(rng);
  return v * (radius / 2);
}

VertexMatrix sphere(std::mt19937_64& rng, int n, Scalar radius) {
  VertexMatrix v = gaussian(rng, n, 1);
  v.rowwise().normalize();
  return v * radius;
}

Eigen::Matrix3d random_rotation(std::mt19937_64& rng) {
  std::normal_distribution<Scalar> g;
  return Eigen::Quaterniond(g(rng), g(rng), g(rng), g(rng)).normalized().toRotationMatrix();
}

Scalar percentile(std::vector<Scalar> v, Scalar p) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v[static_cast<std::size_t>(p * (v.size() - 1))];
}

// The thread's CPU time, which other processes sharing the cores do not inflate.
Scalar cpu_microseconds() {
  timespec t;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return t.tv_sec * 1e6 + t.tv_nsec * 1e-3;
}

// One call's CPU time: after a warm-up call, the mean of a batch of at least `repeats` calls
// lasting at least 200 microseconds in all (the clock costs a system call).
Scalar timed(const Body& a, const Body& b, const Vector3& hint, Scalar tolerance, int repeats,
             sc::detail::PenetrationBounds& out) {
  out = sc::detail::penetration(a.points, a.hull, b.points, b.hull, hint, tolerance, 1000);
  int calls = 0;
  const Scalar start = cpu_microseconds();
  Scalar elapsed = 0;
  while (calls < repeats || elapsed < 200) {
    out = sc::detail::penetration(a.points, a.hull, b.points, b.hull, hint, tolerance, 1000);
    ++calls;
    elapsed = cpu_microseconds() - start;
  }
  return elapsed / calls;
}

// A hint as the dual swarm gives it: the optimal normal turned by about a degree.
Vector3 near_hint(std::mt19937_64& rng, const Vector3& normal) {
  std::normal_distribution<Scalar> g;
  return (normal + 0.02 * Vector3(g(rng), g(rng), g(rng))).normalized();
}

void timing(int pairs) {
  std::mt19937_64 rng(2026);
  std::printf("%-26s %6s %9s %9s %9s %9s %8s %7s\n", "pairs (overlapping)", "count", "median",
              "p90", "max", "it max", "proven", "hint");
  struct Config {
    const char* name;
    int n;
    bool on_sphere;
  };
  for (const Config& c :
       {Config{"8-point random", 8, false}, Config{"64-point random", 64, false},
        Config{"512-point sphere", 512, true}, Config{"4096-point sphere", 4096, true}}) {
    const int count = c.n >= 4096  ? std::max(1, pairs / 10)
                      : c.n >= 512 ? std::max(1, pairs / 4)
                                   : pairs;
    std::vector<Body> as, bs;
    std::vector<Vector3> normals;
    for (int k = 0; k < count; ++k) {
      std::normal_distribution<Scalar> g;
      VertexMatrix a = c.on_sphere ? sphere(rng, c.n, 1) : gaussian(rng, c.n, 1);
      VertexMatrix b = c.on_sphere ? sphere(rng, c.n, 1) : gaussian(rng, c.n, 1);
      b.rowwise() += (0.6 * Vector3(g(rng), g(rng), g(rng))).transpose();
      as.push_back(make(std::move(a)));
      bs.push_back(make(std::move(b)));
      normals.push_back(sc::detail::penetration(as.back().points, as.back().hull, bs.back().points,
                                                bs.back().hull, Vector3::Zero(), 1e-9, 1000)
                            .normal);
    }
    for (const bool with_hint : {false, true}) {
      std::vector<Scalar> times;
      int proven = 0;
      int iterations = 0;
      for (int k = 0; k < count; ++k) {
        const Vector3 hint = with_hint ? near_hint(rng, normals[k]) : Vector3::Zero();
        sc::detail::PenetrationBounds r;
        times.push_back(timed(as[k], bs[k], hint, 1e-9, 3, r));
        proven += r.proven;
        iterations = std::max(iterations, r.iterations);
      }
      std::printf("%-26s %6d %8.2fus %8.2fus %8.2fus %9d %7.1f%% %7s\n", c.name, count,
                  percentile(times, 0.5), percentile(times, 0.9), percentile(times, 1), iterations,
                  100.0 * proven / count, with_hint ? "near" : "none");
    }
  }
}

// Random cases of many kinds, sizes 4-4096; sizes whose differences Qhull takes quickly are
// checked against the oracle.
void sweep(int cases) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<Scalar> unit(0, 1);
  std::normal_distribution<Scalar> g;
  const int sizes[] = {4, 5, 6, 8, 12, 16, 24, 32, 48, 64, 128, 256, 512, 1024, 2048, 4096};
  Scalar worst_violation = 0;
  Scalar worst_discrepancy = 0;
  Scalar worst_gap_proven = 0;
  Scalar worst_residual = 0;
  int checked = 0, proven = 0, proven_zero = 0, tight_zero = 0, overlapping = 0, max_iterations = 0;
  std::vector<Scalar> times;
  std::vector<Scalar> large_times;
  int unproven_reported = 0;
  int proofs[4] = {0, 0, 0, 0};
  int axes_cases = 0;
  int axes_proven = 0;
  std::vector<Scalar> axes_times;
  std::vector<std::vector<Scalar>> kind_times(9);
  const auto start_all = Clock::now();
  for (int c = 0; c < cases; ++c) {
    const int kind = c % 9;
    const bool large = kind == 4 || kind == 5 || kind == 8;
    const int na = sizes[static_cast<int>(unit(rng) * (large ? 16 : 10))];
    const int nb = kind == 5 ? 4 + static_cast<int>(unit(rng) * 12)
                             : sizes[static_cast<int>(unit(rng) * (large ? 16 : 10))];
    VertexMatrix a, b;
    switch (kind) {
      case 0:  // clouds
        a = gaussian(rng, na, 1);
        b = gaussian(rng, nb, 0.2 + unit(rng));
        break;
      case 1: {  // anisotropic: needles and slivers
        const Eigen::Vector3d stretch(1, std::pow(10, -6 * unit(rng)),
                                      std::pow(10, -6 * unit(rng)));
        a = (gaussian(rng, na, 1) * stretch.asDiagonal()) * random_rotation(rng);
        b = gaussian(rng, nb, 0.5) * random_rotation(rng);
        break;
      }
      case 2: {  // boxes, some turned, some face-aligned
        VertexMatrix box(8, 3);
        for (int k = 0; k < 8; ++k)
          box.row(k) << (k & 1 ? 0.5 : -0.5), (k & 2 ? 0.5 : -0.5), (k & 4 ? 0.5 : -0.5);
        a = box;
        b = unit(rng) < 0.5 ? VertexMatrix(box * random_rotation(rng)) : VertexMatrix(box * 0.7);
        break;
      }
      case 3: {  // flat and collinear bodies against clouds
        a = gaussian(rng, na, 1);
        a.col(2) *= unit(rng) < 0.5 ? 0 : 1;
        if (unit(rng) < 0.3) a.col(1).setZero();
        a = a * random_rotation(rng);
        b = gaussian(rng, nb, 0.7);
        break;
      }
      case 4:  // sphere points, large
        a = sphere(rng, na, 1);
        b = sphere(rng, nb, 0.3 + unit(rng));
        break;
      case 5:  // large size ratio
        a = sphere(rng, na, 1);
        b = gaussian(rng, nb, std::pow(10, -6 * unit(rng)));
        break;
      case 6:  // clouds, made to touch below
        a = gaussian(rng, na, 1);
        b = gaussian(rng, nb, 0.5);
        break;
      case 8: {  // large flat discs against spheres or coplanar discs
        const Eigen::Matrix3d turn = random_rotation(rng);
        a = sphere(rng, na, 1);
        a.col(2).setZero();
        a = a * turn;
        b = sphere(rng, nb, 0.5);
        if (unit(rng) < 0.5) {
          b.col(2).setZero();
          b = b * turn;
        }
        break;
      }
      default: {  // flat bodies in one plane or in planes 1e-16 apart
        const Eigen::Matrix3d turn = random_rotation(rng);
        a = gaussian(rng, na, 1);
        b = gaussian(rng, nb, 0.5);
        a.col(2).setZero();
        b.col(2).setConstant(unit(rng) < 0.5 ? 0 : 1e-16);
        a = a * turn;
        b = b * turn;
        b.rowwise() += (Vector3(g(rng), g(rng), 0) * 0.4).transpose() * turn;
        break;
      }
    }
    if (kind != 7 && kind != 8) b.rowwise() += (Vector3(g(rng), g(rng), g(rng)) * 0.4).transpose();
    if (kind == 6 || (kind == 8 && unit(rng) < 0.5)) {
      const sc::detail::PenetrationBounds r = sc::detail::penetration(
          a, sc::compute_hull(a), b, sc::compute_hull(b), Vector3::Zero(), 1e-9, 1000);
      b.rowwise() -= (r.separation * r.normal).transpose();
    }
    const Body ba = make(std::move(a));
    const Body bb = make(std::move(b));
    const int hint_kind = c / 9 % 3;
    const Vector3 hint = hint_kind == 0 ? Vector3::Zero() : Vector3(g(rng), g(rng), g(rng));
    sc::detail::PenetrationBounds r;
    const Scalar t = timed(ba, bb, hint, 1e-9, 1, r);
    (na + nb >= 1024 ? large_times : times).push_back(t);
    kind_times[kind].push_back(t);
    max_iterations = std::max(max_iterations, r.iterations);
    const sc::detail::PenetrationBounds zero =
        sc::detail::penetration(ba.points, ba.hull, bb.points, bb.hull, hint, 0, 1000);
    proven_zero += zero.proven;
    tight_zero += zero.upper - zero.lower <= 1e-12;
    if (static_cast<long long>(na) * nb <= 20000) {
      const sc::testing::OracleValue exact = sc::testing::oracle(ba.points, bb.points);
      ++checked;
      overlapping += exact.value < 0;
      // One iteration stops Wolfe and the polytope at once: the candidate axes alone.
      const sc::detail::PenetrationBounds axes =
          sc::detail::penetration(ba.points, ba.hull, bb.points, bb.hull, hint, 1e-9, 1);
      // Above 1024 points the faces-by-points check alone exceeds the axes' work cap.
      if (exact.value < -1e-12 && std::max(na, nb) <= 1024) {
        ++axes_cases;
        axes_proven += axes.proven;
      }
      for (const sc::detail::PenetrationBounds& bound : {r, zero, axes}) {
        // The oracle errs on one side only: there it bounds the true value rigorously.
        const Scalar rigorous =
            exact.is_lower_bound ? exact.value - bound.upper : bound.lower - exact.value;
        const Scalar other =
            exact.is_lower_bound ? bound.lower - exact.value : exact.value - bound.upper;
        worst_violation = std::max(worst_violation, rigorous);
        worst_discrepancy = std::max(worst_discrepancy, other);
        if (rigorous > 1e-15) {
          std::printf(
              "VIOLATION case %d kind %d sizes %d %d: lower %.17g oracle %.17g upper %.17g\n", c,
              kind, na, nb, bound.lower, exact.value, bound.upper);
        }
      }
    }
    proven += r.proven;
    ++proofs[static_cast<int>(r.proof)];
    if (r.proof == sc::detail::PenetrationProof::candidate_axes) axes_times.push_back(t);
    if (r.proven) {
      worst_gap_proven = std::max(worst_gap_proven, r.upper - r.lower);
      worst_residual = std::max(worst_residual, r.witness_residual);
    } else if (r.upper <= 0 && unproven_reported++ < 10) {
      std::printf(
          "unproven overlap: case %d kind %d sizes %d %d dims %d %d: lower %.17g upper %.17g\n", c,
          kind, na, nb, ba.hull.dimension, bb.hull.dimension, r.lower, r.upper);
    }
  }
  std::printf("cases %d (%d checked against the oracle, %d of those overlapping), %.1f s\n", cases,
              checked, overlapping,
              std::chrono::duration<Scalar>(Clock::now() - start_all).count());
  std::printf(
      "largest violation of the oracle's rigorous side: %.3g; largest excess on its "
      "approximate side: %.3g (tolerance 1e-9, 0 and axes-only runs)\n",
      worst_violation, worst_discrepancy);
  std::printf("proven at tolerance 1e-9: %d / %d (%.2f%%); largest proven gap %.3g\n", proven,
              cases, 100.0 * proven / cases, worst_gap_proven);
  std::printf(
      "candidate axes alone (one iteration), overlaps beyond 1e-12, sizes <= 1024: proven %d / "
      "%d\n",
      axes_proven, axes_cases);
  std::printf("at tolerance 0: proven %d, gap <= 1e-12 in %d / %d\n", proven_zero, tight_zero,
              cases);
  std::printf("largest witness residual when proven: %.3g; most iterations: %d\n", worst_residual,
              max_iterations);
  const char* kinds[] = {"clouds 4-64",          "needles, slivers 4-64", "boxes",
                         "flat/collinear 4-64",  "spheres 4-4096",        "size ratio 4-4096",
                         "touching clouds 4-64", "coplanar flat 4-64",    "discs 4-4096"};
  for (int k = 0; k < 9; ++k) {
    std::printf("  %-22s %4zu cases: p50 %8.2fus p90 %8.2fus max %8.2fus\n", kinds[k],
                kind_times[k].size(), percentile(kind_times[k], 0.5),
                percentile(kind_times[k], 0.9), percentile(kind_times[k], 1));
  }
  std::printf(
      "upper proven by: nothing %d, nearest point %d, polytope %d, candidate axes %d "
      "(median %.2fus, max %.2fus)\n",
      proofs[0], proofs[1], proofs[2], proofs[3], percentile(axes_times, 0.5),
      percentile(axes_times, 1));
  std::printf(
      "time per call, sizes na + nb < 1024 (%zu): p50 %.2fus p90 %.2fus p99 %.2fus max %.2fus\n",
      times.size(), percentile(times, 0.5), percentile(times, 0.9), percentile(times, 0.99),
      percentile(times, 1));
  std::printf("time per call, na + nb >= 1024 (%zu): p50 %.2fus p90 %.2fus p99 %.2fus max %.2fus\n",
              large_times.size(), percentile(large_times, 0.5), percentile(large_times, 0.9),
              percentile(large_times, 0.99), percentile(large_times, 1));
}

}  // namespace

int main(int argc, char** argv) {
  const std::string mode = argc > 1 ? argv[1] : "timing";
  const int count = argc > 2 ? std::atoi(argv[2]) : 0;
  if (mode == "sweep") {
    sweep(count > 0 ? count : 3000);
  } else {
    timing(count > 0 ? count : 200);
  }
  return 0;
}
