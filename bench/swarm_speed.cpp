// swarmcollide-swarm-speed: the swarm's time on the paper's separated pair (full budget and with
// the certified early stop) and its accuracy at the paper's budget on random sphere polytopes,
// against the exact "fcl" method. Built against any version of the library, it gives the
// before/after figures of bench/RESULTS.md; bench/results/swarm_speed_before.txt was made with
// the library at commit 50ffad6.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "swarmcollide/queries/distance.hpp"
using namespace swarmcollide;

VertexMatrix polytope(int n, std::mt19937_64& rng, double shift) {
  std::normal_distribution<double> N;
  VertexMatrix p(n, 3);
  for (int i = 0; i < n; ++i) {
    Vector3 v(N(rng), N(rng), N(rng));
    p.row(i) = v.normalized().transpose();
  }
  const ConvexPolyhedron body(p);
  const auto& idx = body.hull().vertex_indices;
  VertexMatrix v(idx.size(), 3);
  for (size_t k = 0; k < idx.size(); ++k) v.row(k) = p.row(idx[k]);
  v.col(0).array() += shift;
  return v;
}

// Times `distance(a, b, options)` over 3000 seeds and prints one line led by `label`.
void time_queries(const char* label, const ConvexPolyhedron& a, const ConvexPolyhedron& b,
                  DistanceOptions options) {
  std::vector<double> t;
  double sink = 0;
  for (int r = 0; r < 3000; ++r) {
    options.swarm.seed = r;
    const auto t0 = std::chrono::steady_clock::now();
    sink += distance(a, b, options).distance;
    t.push_back(
        std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count());
  }
  std::sort(t.begin(), t.end());
  std::printf("%s, tolerance %g: median %.1f us, p90 %.1f us (mean distance %.6f)\n", label,
              options.swarm.tolerance, t[t.size() / 2], t[t.size() * 9 / 10], sink / 3000);
}

int main() {
  VertexMatrix A(4, 3);
  A << 0, 1, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0;
  VertexMatrix B(4, 3);
  B << 1, -1, 0, 2, -2, 0, 0, -2, 2, 0, -2, 0;
  const ConvexPolyhedron a(A), b(B);
  VertexMatrix T(4, 3);
  T << 1, 0, 0, 2, -2, 0, 0, -2, 2, 0, -2, 0;
  const ConvexPolyhedron touching(T);
  for (double tol : {0.0, 1e-6}) {
    DistanceOptions o;
    o.swarm.tolerance = tol;
    time_queries("paper touching pair, ipso projection", a, touching, o);
  }
  for (auto mode : {ConstraintHandling::projection, ConstraintHandling::feasibility}) {
    for (double tol : {0.0, 1e-6}) {
      DistanceOptions o;
      o.swarm.tolerance = tol;
      o.swarm.constraint_handling = mode;
      time_queries(mode == ConstraintHandling::projection
                       ? "paper separated pair, ipso projection"
                       : "paper separated pair, ipso feasibility",
                   a, b, o);
    }
  }
  for (int n : {8, 16, 64}) {
    std::mt19937_64 rng(n);
    int within = 0, separated = 0;
    double worst = 0;
    std::vector<double> err;
    for (int k = 0; k < 100; ++k) {
      const double shift = 2 + (k % 2 ? 0.5 : 1e-2);
      const ConvexPolyhedron pa(polytope(n, rng, 0)), pb(polytope(n, rng, shift));
      DistanceOptions exact;
      exact.method = Method::fcl;
      const double truth = distance(pa, pb, exact).distance;
      DistanceOptions o;
      o.swarm.seed = k;
      const double d = distance(pa, pb, o).distance;
      if (truth > 1e-9) {
        ++separated;
        within += d - truth <= 1e-6;
        worst = std::max(worst, d - truth);
        err.push_back(d - truth);
      }
    }
    std::sort(err.begin(), err.end());
    std::printf(
        "%d-point sphere polytopes: %d/%d separated pairs within 1e-6, median error %.2e, worst "
        "%.2e\n",
        n, within, separated, err[err.size() / 2], worst);
  }
}
