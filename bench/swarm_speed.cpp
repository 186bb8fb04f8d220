// swarmcollide-swarm-speed: the swarm's time on the paper's pairs (full budget and with the
// certified early stop) and its accuracy at the paper's budget on random sphere polytopes, against
// the exact method. Prints one line per measurement; with --json FILE also writes them as rows
// (bench/record.py adds the machine and the command).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "sphere_polytope.hpp"
#include "swarmcollide/queries/query.hpp"

namespace sc = swarmcollide;

namespace {

constexpr int kTimedSeeds = 3000;
constexpr int kAccuracyPairs = 100;

sc::QueryOptions ipso(sc::ConstraintHandling handling, double tolerance) {
  sc::QueryOptions options;
  options.method = sc::Method::ipso;
  options.swarm.constraint_handling = handling;
  options.tolerance = tolerance;
  return options;
}

const char* handling_name(sc::ConstraintHandling handling) {
  return handling == sc::ConstraintHandling::projection ? "projection" : "feasibility";
}

// Times `distance(a, b)` over kTimedSeeds seeds; prints one line and returns it as a JSON row.
std::string time_queries(const char* pair, const sc::ConvexPolyhedron& a,
                         const sc::ConvexPolyhedron& b, sc::QueryOptions options) {
  std::vector<double> micros;
  double sum = 0;
  for (int seed = 0; seed < kTimedSeeds; ++seed) {
    options.seed = static_cast<std::uint64_t>(seed);
    const sc::Query query(options);
    const auto start = std::chrono::steady_clock::now();
    sum += query.distance(a, b).distance;
    micros.push_back(
        std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start)
            .count());
  }
  std::sort(micros.begin(), micros.end());
  const double median = micros[micros.size() / 2], p90 = micros[micros.size() * 9 / 10];
  const char* handling = handling_name(options.swarm.constraint_handling);
  std::printf(
      "paper %s pair, ipso %s, tolerance %g: median %.1f us, p90 %.1f us (mean distance "
      "%.6f)\n",
      pair, handling, options.tolerance, median, p90, sum / kTimedSeeds);
  char row[512];
  std::snprintf(row, sizeof row,
                "{\"kind\": \"time\", \"pair\": \"paper %s\", \"method\": \"ipso\", "
                "\"constraint_handling\": \"%s\", \"tolerance\": %g, \"median_us\": %.2f, "
                "\"p90_us\": %.2f, \"mean_distance\": %.9f}",
                pair, handling, options.tolerance, median, p90, sum / kTimedSeeds);
  return row;
}

// ipso at its defaults on kAccuracyPairs separated pairs of n-point sphere polytopes.
std::string accuracy(int n) {
  std::mt19937_64 rng(static_cast<std::uint64_t>(n));
  sc::QueryOptions exact;
  exact.method = sc::Method::exact;
  int within = 0;
  std::vector<double> errors;
  for (int k = 0; k < kAccuracyPairs; ++k) {
    const double shift = 2 + (k % 2 ? 0.5 : 1e-2);
    const sc::ConvexPolyhedron a(sphere_polytope(n, rng, 0)), b(sphere_polytope(n, rng, shift));
    const double truth = sc::Query(exact).distance(a, b).distance;
    sc::QueryOptions options = ipso(sc::ConstraintHandling::projection, sc::kDefaultTolerance);
    options.seed = static_cast<std::uint64_t>(k);
    const double error = sc::Query(options).distance(a, b).distance - truth;
    within += error <= 1e-6;
    errors.push_back(error);
  }
  std::sort(errors.begin(), errors.end());
  const double median = errors[errors.size() / 2], worst = errors.back();
  std::printf(
      "%d-point sphere polytopes: %d/%d separated pairs within 1e-6, median error %.2e, "
      "worst %.2e\n",
      n, within, kAccuracyPairs, median, worst);
  char row[512];
  std::snprintf(row, sizeof row,
                "{\"kind\": \"accuracy\", \"vertices\": %d, \"method\": \"ipso\", \"pairs\": %d, "
                "\"within_1e-6\": %d, \"median_error\": %.3e, \"worst_error\": %.3e}",
                n, kAccuracyPairs, within, median, worst);
  return row;
}

}  // namespace

int main(int argc, char** argv) {
  const char* json = nullptr;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--json") && i + 1 < argc) {
      json = argv[++i];
    } else {
      std::fprintf(stderr, "usage: swarmcollide-swarm-speed [--json FILE]\n");
      return 2;
    }
  }
  sc::VertexMatrix tetrahedron(4, 3), separate(4, 3), touching(4, 3);
  tetrahedron << 0, 1, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0;
  separate << 1, -1, 0, 2, -2, 0, 0, -2, 2, 0, -2, 0;
  touching << 1, 0, 0, 2, -2, 0, 0, -2, 2, 0, -2, 0;
  const sc::ConvexPolyhedron a(tetrahedron), b_separate(separate), b_touching(touching);
  std::vector<std::string> rows;
  // Tolerance 0 runs the whole budget; 1e-6 stops once the answer is certified to it.
  for (double tolerance : {0.0, 1e-6}) {
    rows.push_back(time_queries("touching", a, b_touching,
                                ipso(sc::ConstraintHandling::projection, tolerance)));
  }
  for (auto handling : {sc::ConstraintHandling::projection, sc::ConstraintHandling::feasibility}) {
    for (double tolerance : {0.0, 1e-6}) {
      rows.push_back(time_queries("separated", a, b_separate, ipso(handling, tolerance)));
    }
  }
  for (int n : {8, 16, 64}) rows.push_back(accuracy(n));
  if (json != nullptr) {
    std::ofstream out(json);
    out << "{\"rows\": [\n";
    for (std::size_t i = 0; i < rows.size(); ++i) {
      out << "  " << rows[i] << (i + 1 < rows.size() ? ",\n" : "\n");
    }
    out << "]}\n";
  }
  return 0;
}
