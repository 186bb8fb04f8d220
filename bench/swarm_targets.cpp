// swarmcollide-swarm-targets: the swarm at the paper's budget (40 particles x 200 iterations)
// against plain_pso.cpp, the same method as a plain scalar loop built with -O3 -march=native.
//
//   swarmcollide-swarm-targets [--quick] [--json FILE]   accuracy and time, this process's kernels
//   swarmcollide-swarm-targets --sweep [--quick]         the velocity-limit sweep of docs/method.md
//   swarmcollide-swarm-targets --choices [--quick]       the other open choices, on the plain PSO
//
// The kernels are the widest the processor runs unless SWARMCOLLIDE_ISA=avx512|avx2|baseline
// forces one; bench/swarm_targets.py runs this binary once per instruction set. Times are ratios
// measured inside one run: batches of the two contenders alternate, and the median is reported.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <exception>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "plain_pso.hpp"
#include "sphere_polytope.hpp"
#include "swarmcollide/queries/methods.hpp"
#include "swarmcollide/queries/query.hpp"
#include "swarmcollide/solvers/swarm.hpp"

namespace sc = swarmcollide;

namespace {

struct Pair {
  sc::VertexMatrix a, b;  // row-major, so .data() is x y z per vertex, as plain_pso reads it
  double exact;
};

// `count` separated pairs of n-point sphere polytopes: B's centre 2.01 or 2.5 from A's along x,
// so the bodies (inside unit balls) are apart by at least 0.01 or 0.5.
std::vector<Pair> workload(int n, int count, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  sc::QueryOptions exact;
  exact.method = sc::Method::exact;
  std::vector<Pair> pairs;
  for (int k = 0; k < count; ++k) {
    Pair p{sphere_polytope(n, rng, 0), sphere_polytope(n, rng, k % 2 ? 2.5 : 2.01), 0};
    p.exact = sc::distance(sc::ConvexPolyhedron(p.a), sc::ConvexPolyhedron(p.b), exact).distance;
    pairs.push_back(std::move(p));
  }
  return pairs;
}

// ipso at the library's defaults (the paper's budget, the default tolerance), seeded with `seed`.
sc::QueryOptions ipso_options(std::uint64_t seed) {
  sc::QueryOptions options;
  options.method = sc::Method::ipso;
  options.seed = seed;
  return options;
}

double plain(const Pair& p, std::uint64_t seed) {
  return plain_pso(p.a.data(), static_cast<int>(p.a.rows()), p.b.data(),
                   static_cast<int>(p.b.rows()), PlainPsoOptions{}, seed);
}

struct Accuracy {
  int within = 0;
  int pairs = 0;
  double median_error = 0;
  double p90_error = 0;
};

template <typename Solve>
Accuracy accuracy(const std::vector<Pair>& pairs, Solve&& solve) {
  Accuracy a;
  std::vector<double> errors;
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    const double error = std::max(solve(pairs[k], k) - pairs[k].exact, 0.0);
    a.within += error <= 1e-6;
    errors.push_back(error);
  }
  a.pairs = static_cast<int>(pairs.size());
  std::sort(errors.begin(), errors.end());
  a.median_error = errors[errors.size() / 2];
  a.p90_error = errors[errors.size() * 9 / 10];
  return a;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

struct Timing {
  double ipso_us;
  double plain_us;
  double ratio;  // median over rounds of (ipso's time / plain's time) within the round
};

// Full budget (tolerance 0) on the first few pairs, one seed per solve. The contenders alternate
// solve by solve (which goes first alternates too), so that both see the same load on a shared
// machine; a round's ratio is the ratio of its sums, and the median round is reported.
Timing time_full_budget(const std::vector<Pair>& pairs, int rounds) {
  sc::QueryOptions options = ipso_options(0);
  options.tolerance = 0;
  const int used = std::min<int>(4, static_cast<int>(pairs.size()));
  std::vector<sc::ConvexPolyhedron> as, bs;
  for (int k = 0; k < used; ++k) {
    as.emplace_back(pairs[k].a);
    bs.emplace_back(pairs[k].b);
    as.back().hull();  // built before the clock starts
    bs.back().hull();
  }
  double sink = 0;
  using Clock = std::chrono::steady_clock;
  const auto solve = [&](bool library, int s) {
    const auto t0 = Clock::now();
    if (library) {
      options.seed = static_cast<std::uint64_t>(s);
      sink += sc::distance(as[s % used], bs[s % used], options).distance;
    } else {
      sink += plain(pairs[s % used], s);
    }
    return std::chrono::duration<double, std::micro>(Clock::now() - t0).count();
  };
  for (int s = 0; s < used; ++s) solve(true, s);  // warm-up: the library's workspace, the caches
  const double one = solve(false, 0);
  const int solves = std::max(2 * used, static_cast<int>(80000 / one));  // about 80 ms a round
  std::vector<double> ipso, plain_times, ratios;
  for (int round = 0; round < rounds; ++round) {
    double t_ipso = 0, t_plain = 0;
    for (int s = 0; s < solves; ++s) {
      if (s % 2) {
        t_ipso += solve(true, s);
        t_plain += solve(false, s);
      } else {
        t_plain += solve(false, s);
        t_ipso += solve(true, s);
      }
    }
    ipso.push_back(t_ipso / solves);
    plain_times.push_back(t_plain / solves);
    ratios.push_back(t_ipso / t_plain);
  }
  if (sink == 42) std::puts("");
  return {median(ipso), median(plain_times), median(ratios)};
}

// FNV-1a over the bits of every answer: equal across instruction sets exactly when the answers
// are bitwise equal.
std::uint64_t fingerprint(const std::vector<double>& values) {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  for (double v : values) {
    std::uint64_t bits;
    std::memcpy(&bits, &v, sizeof bits);
    for (int i = 0; i < 8; ++i) h = (h ^ ((bits >> (8 * i)) & 0xff)) * 0x100000001b3ULL;
  }
  return h;
}

int run_targets(bool quick, const char* json_path) {
  const std::vector<int> sizes = {4, 8, 16, 64};
  const int rounds = quick ? 3 : 9;
  std::string json = "{\"isa\": \"" + std::string(sc::swarm_instruction_set()) + "\", \"sizes\": [";
  std::printf("kernels: %s\n", sc::swarm_instruction_set());
  std::printf("%4s | %-34s | %-34s | %9s %9s %7s\n", "n", "ipso within 1e-6 (median error)",
              "plain within 1e-6 (median error)", "ipso us", "plain us", "ratio");
  std::vector<double> answers;
  for (std::size_t i = 0; i < sizes.size(); ++i) {
    const int n = sizes[i];
    const int count = quick ? 50 : (n == 64 ? 200 : 400);
    const std::vector<Pair> pairs = workload(n, count, 14000 + n);
    const Accuracy ipso = accuracy(pairs, [&](const Pair& p, std::uint64_t seed) {
      const double d =
          sc::distance(sc::ConvexPolyhedron(p.a), sc::ConvexPolyhedron(p.b), ipso_options(seed))
              .distance;
      answers.push_back(d);
      return d;
    });
    const Accuracy reference = accuracy(pairs, plain);
    const Timing t = time_full_budget(pairs, rounds);
    char line[512];
    std::snprintf(line, sizeof line,
                  "%4d | %5.1f%% (%3d/%3d, %8.1e)          | %5.1f%% (%3d/%3d, %8.1e)          | "
                  "%9.1f %9.1f %7.3f\n",
                  n, 100.0 * ipso.within / ipso.pairs, ipso.within, ipso.pairs, ipso.median_error,
                  100.0 * reference.within / reference.pairs, reference.within, reference.pairs,
                  reference.median_error, t.ipso_us, t.plain_us, t.ratio);
    std::fputs(line, stdout);
    std::fflush(stdout);
    char entry[1024];
    std::snprintf(entry, sizeof entry,
                  "%s{\"n\": %d, \"pairs\": %d, \"ipso_within\": %d, \"ipso_median_error\": %.3e, "
                  "\"ipso_p90_error\": %.3e, \"plain_within\": %d, \"plain_median_error\": %.3e, "
                  "\"plain_p90_error\": %.3e, \"ipso_us\": %.2f, \"plain_us\": %.2f, "
                  "\"ratio\": %.4f}",
                  i ? ", " : "", n, ipso.pairs, ipso.within, ipso.median_error, ipso.p90_error,
                  reference.within, reference.median_error, reference.p90_error, t.ipso_us,
                  t.plain_us, t.ratio);
    json += entry;
  }
  char tail[128];
  std::snprintf(tail, sizeof tail, "], \"fingerprint\": \"%016llx\", \"rounds\": %d}\n",
                static_cast<unsigned long long>(fingerprint(answers)), rounds);
  json += tail;
  std::printf("fingerprint of every ipso answer: %016llx\n",
              static_cast<unsigned long long>(fingerprint(answers)));
  if (json_path != nullptr) std::ofstream(json_path) << json;
  return 0;
}

// The sweep behind the default velocity limit, on pairs drawn with other seeds than the targets'.
// Each cell: the share of separated pairs answered within 1e-6 at the paper's budget, and the
// median number of iterations the solve ran (it stops once certified to the default tolerance).
int run_sweep(bool quick) {
  const std::vector<int> sizes = {4, 8, 16, 32, 64};
  const std::vector<double> limits = {0.01, 0.015, 0.02, 0.025, 0.03, 0.04,
                                      0.05, 0.07,  0.1,  0.2,   0.5,  1.0};
  std::vector<std::vector<Pair>> pairs;
  for (int n : sizes) pairs.push_back(workload(n, quick ? 40 : (n >= 32 ? 250 : 500), 77000 + n));
  std::printf("separated pairs within 1e-6 at the paper's budget, and median iterations run (of");
  for (std::size_t i = 0; i < sizes.size(); ++i) std::printf(" %zu", pairs[i].size());
  std::printf(" pairs)\n%-28s", "method, velocity_limit");
  for (int n : sizes) std::printf(" | n=%-11d", n);
  std::printf(" | mean\n");
  for (sc::Method method : {sc::Method::ipso, sc::Method::pso}) {
    for (double limit : limits) {
      std::printf("%-21s %6.3f", sc::method_name(method), limit);
      double total = 0;
      for (std::size_t i = 0; i < sizes.size(); ++i) {
        std::vector<double> iterations;
        const Accuracy a = accuracy(pairs[i], [&](const Pair& p, std::uint64_t seed) {
          sc::QueryOptions options = ipso_options(seed);
          options.method = method;
          options.swarm.velocity_limit = limit;
          const sc::DistanceResult r =
              sc::distance(sc::ConvexPolyhedron(p.a), sc::ConvexPolyhedron(p.b), options);
          iterations.push_back(r.iterations);
          return r.distance;
        });
        const double percent = 100.0 * a.within / a.pairs;
        total += percent;
        std::printf(" | %5.1f%% %5.0f", percent, median(iterations));
      }
      std::printf(" | %5.1f%%\n", total / sizes.size());
      std::fflush(stdout);
    }
  }
  return 0;
}

// The choices the paper leaves open, measured with the plain PSO: each row changes one choice from
// swarmcollide's (r1, r2 per weight; components clamped; velocity = the move made; the global best
// updated once per generation), on the sweep's pairs.
int run_choices(bool quick) {
  const std::vector<int> sizes = {4, 8, 16, 32, 64};
  std::vector<std::vector<Pair>> pairs;
  for (int n : sizes) pairs.push_back(workload(n, quick ? 40 : (n >= 32 ? 150 : 300), 77000 + n));
  struct Choice {
    const char* name;
    PlainPsoOptions options;
  };
  std::vector<Choice> choices(6);
  choices[0].name = "swarmcollide's choices";
  choices[1].name = "r1, r2 once per particle";
  choices[1].options.factors_per_weight = false;
  choices[2].name = "whole velocity scaled";
  choices[2].options.scale_whole_velocity = true;
  choices[3].name = "velocity not projected";
  choices[3].options.after_projection = VelocityAfterProjection::unprojected;
  choices[4].name = "clipped components zeroed";
  choices[4].options.after_projection = VelocityAfterProjection::clipped_zeroed;
  choices[5].name = "asynchronous global best";
  choices[5].options.asynchronous = true;
  std::printf("plain PSO, velocity_limit %.3f: separated pairs within 1e-6 (of",
              PlainPsoOptions{}.velocity_limit);
  for (const auto& p : pairs) std::printf(" %zu", p.size());
  std::printf(" pairs)\n%-28s", "choice");
  for (int n : sizes) std::printf(" | n=%-5d", n);
  std::printf(" | mean\n");
  for (const Choice& choice : choices) {
    std::printf("%-28s", choice.name);
    double total = 0;
    for (const auto& p : pairs) {
      const Accuracy a = accuracy(p, [&](const Pair& pair, std::uint64_t seed) {
        return plain_pso(pair.a.data(), static_cast<int>(pair.a.rows()), pair.b.data(),
                         static_cast<int>(pair.b.rows()), choice.options, seed);
      });
      total += 100.0 * a.within / a.pairs;
      std::printf(" | %6.1f%%", 100.0 * a.within / a.pairs);
    }
    std::printf(" | %5.1f%%\n", total / sizes.size());
    std::fflush(stdout);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  bool quick = false, sweep = false, choices = false;
  const char* json = nullptr;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--quick")) {
      quick = true;
    } else if (!std::strcmp(argv[i], "--sweep")) {
      sweep = true;
    } else if (!std::strcmp(argv[i], "--choices")) {
      choices = true;
    } else if (!std::strcmp(argv[i], "--json") && i + 1 < argc) {
      json = argv[++i];
    } else {
      std::fprintf(
          stderr,
          "usage: swarmcollide-swarm-targets [--quick] [--sweep | --choices] [--json FILE]\n");
      return 2;
    }
  }
  try {
    if (sweep) return run_sweep(quick);
    return choices ? run_choices(quick) : run_targets(quick, json);
  } catch (const std::exception& error) {
    std::fprintf(stderr, "%s\n", error.what());
    return 3;
  }
}
