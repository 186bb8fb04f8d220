// swarmcollide-fcl-ratio: the fcl method over the raw FCL call it wraps, the two timed in turns
// within each round, on the random pairs of swarmcollide_bench.cpp (random_pairs.hpp). Its
// ratios are issue 25's third item; results: bench/RESULTS.md.
//
// swarmcollide-bench times each row on its own, one after another, so that a row's median and the
// one it is divided by come from different minutes of a shared machine (cells moved by up to a
// third between two runs, bench/README.md session 67). Here each round times the fcl method and
// its FCL call back to back, the order alternating, and a ratio is the median over rounds of each
// round's ratio. The FCL calls are swarmcollide-bench's: `fcl::distance` (nearest points on,
// GST_INDEP's GJK, the one the method runs) for the distance and, on pairs apart, the signed
// distance (FCL's EPA asserts on some overlapping pairs), and `fcl::collide` (GST_INDEP, one
// contact, no contact data) for the verdict, on `fcl::Convexd` shapes built once.
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/distance.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "random_pairs.hpp"
#include "swarmcollide/queries/query.hpp"

namespace sc = swarmcollide;

namespace {

// Each contender's turn in a round lasts at least this long, so the clock's resolution and the
// loop's overhead do not enter.
constexpr double kTurnSeconds = 2e-3;
constexpr fcl::GJKSolverType kFclOwnGjk = fcl::GST_INDEP;

struct Pair {
  sc::ConvexPolyhedron a;
  sc::ConvexPolyhedron b;
  std::shared_ptr<fcl::Convexd> fcl_a;
  std::shared_ptr<fcl::Convexd> fcl_b;
};

// The method's call and FCL's, each answering pair i (summed, so no call is optimised away).
struct CallPair {
  const char* name;
  std::function<double(std::size_t)> ours;
  std::function<double(std::size_t)> fcl;
};

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t m = v.size() / 2;
  return v.size() % 2 ? v[m] : (v[m - 1] + v[m]) / 2;
}

// Microseconds per call of `run` over `count` pairs, repeated `repeats` times.
double time_turn(const std::function<double(std::size_t)>& run, std::size_t count, int repeats,
                 double& sink) {
  const auto start = std::chrono::steady_clock::now();
  for (int r = 0; r < repeats; ++r) {
    for (std::size_t i = 0; i < count; ++i) sink += run(i);
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return 1e6 * seconds / (repeats * static_cast<double>(count));
}

// Repetitions of the pairs that make a turn last kTurnSeconds.
int repeats_for(const std::function<double(std::size_t)>& run, std::size_t count, double& sink) {
  int repeats = 1;
  while (time_turn(run, count, repeats, sink) * repeats * count < 1e6 * kTurnSeconds) repeats *= 2;
  return repeats;
}

struct Options {
  std::vector<int> sizes = {4, 8, 16, 64, 512, 4096};
  int rounds = 21;
  int pairs = 20;
  std::string json;
};

[[noreturn]] void usage(const char* program) {
  std::fprintf(stderr, "usage: %s [--quick] [--sizes 4,8,...] [--rounds R] [--json PATH]\n",
               program);
  std::exit(2);
}

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--quick") {
      o.sizes = {8, 64};
      o.rounds = 7;
      o.pairs = 5;
    } else if (arg == "--json" && i + 1 < argc) {
      o.json = argv[++i];
    } else if (arg == "--rounds" && i + 1 < argc) {
      o.rounds = std::atoi(argv[++i]);
    } else if (arg == "--sizes" && i + 1 < argc) {
      o.sizes.clear();
      const std::string list = argv[++i];
      for (std::size_t start = 0; start < list.size();) {
        const std::size_t comma = std::min(list.find(',', start), list.size());
        o.sizes.push_back(std::atoi(list.substr(start, comma - start).c_str()));
        start = comma + 1;
      }
    } else {
      usage(argv[0]);
    }
  }
  // Hulls of fewer than four points on the sphere are not bodies of three dimensions.
  if (o.rounds < 1 || o.sizes.empty() ||
      *std::min_element(o.sizes.begin(), o.sizes.end()) < 4) {
    usage(argv[0]);
  }
  return o;
}

}  // namespace

int main(int argc, char** argv) {
  const Options options = parse(argc, argv);
  std::vector<sc::Query> queries;  // one per pair index, seeded with it, as swarmcollide-bench's
  for (int i = 0; i < options.pairs; ++i) {
    sc::QueryOptions o;
    o.method = sc::Method::fcl;
    o.seed = static_cast<std::uint64_t>(i);
    queries.emplace_back(o);
  }
  std::printf("%-5s %-13s %-16s %10s %10s %7s %7s %7s\n", "n", "proximity", "query", "fcl (us)",
              "FCL (us)", "ratio", "min", "max");
  std::string rows;
  int uncertified = 0;
  double sink = 0;
  for (int n : options.sizes) {
    for (std::size_t k = 0; k < bench_proximities().size(); ++k) {
      const BenchProximity& proximity = bench_proximities()[k];
      std::vector<Pair> pairs;
      for (int i = 0; i < options.pairs; ++i) {
        auto [a_points, b_points] =
            random_pair_points(n, proximity.target, random_pair_seed(n, static_cast<int>(k), i));
        sc::ConvexPolyhedron a(std::move(a_points));
        sc::ConvexPolyhedron b(std::move(b_points));
        const sc::Aabb box = a.aabb();
        const sc::Vector3 origin = (box.min + box.max) / 2;
        pairs.push_back({a, b, to_fcl(a, origin), to_fcl(b, origin)});
      }
      const fcl::Vector3d zero = fcl::Vector3d::Zero();
      std::vector<CallPair> asked = {
          {"distance",
           [&](std::size_t i) { return queries[i].distance(pairs[i].a, pairs[i].b).distance; },
           [&](std::size_t i) {
             return fcl_distance_raw(*pairs[i].fcl_a, *pairs[i].fcl_b, zero, false, kFclOwnGjk)
                 .min_distance;
           }},
          {"collide",
           [&](std::size_t i) { return queries[i].collide(pairs[i].a, pairs[i].b) ? 1.0 : 0.0; },
           [&](std::size_t i) {
             fcl::CollisionRequestd request;
             request.gjk_solver_type = kFclOwnGjk;
             fcl::CollisionResultd out;
             fcl::collide(pairs[i].fcl_a.get(), fcl::Transform3d::Identity(),
                          pairs[i].fcl_b.get(), fcl::Transform3d::Identity(), request, out);
             return out.isCollision() ? 1.0 : 0.0;
           }}};
      if (proximity.target > 0) {
        asked.push_back(
            {"signed distance",
             [&](std::size_t i) {
               return queries[i].signed_distance(pairs[i].a, pairs[i].b).distance;
             },
             [&](std::size_t i) {
               return fcl_distance_raw(*pairs[i].fcl_a, *pairs[i].fcl_b, zero, true, kFclOwnGjk)
                   .min_distance;
             }});
      }
      for (std::size_t i = 0; i < pairs.size(); ++i) {
        uncertified += !queries[i].distance(pairs[i].a, pairs[i].b).certified;
        uncertified += !queries[i].collision(pairs[i].a, pairs[i].b).certified;
        uncertified += !queries[i].signed_distance(pairs[i].a, pairs[i].b).certified;
      }
      for (const CallPair& query : asked) {
        const int ours_repeats = repeats_for(query.ours, pairs.size(), sink);
        const int fcl_repeats = repeats_for(query.fcl, pairs.size(), sink);
        std::vector<double> ours_us, fcl_us, ratios;
        for (int round = 0; round < options.rounds; ++round) {
          double ours = 0, fcl = 0;
          if (round % 2 == 0) {
            ours = time_turn(query.ours, pairs.size(), ours_repeats, sink);
            fcl = time_turn(query.fcl, pairs.size(), fcl_repeats, sink);
          } else {
            fcl = time_turn(query.fcl, pairs.size(), fcl_repeats, sink);
            ours = time_turn(query.ours, pairs.size(), ours_repeats, sink);
          }
          ours_us.push_back(ours);
          fcl_us.push_back(fcl);
          ratios.push_back(ours / fcl);
        }
        const double ratio = median(ratios);
        const double low = *std::min_element(ratios.begin(), ratios.end());
        const double high = *std::max_element(ratios.begin(), ratios.end());
        std::printf("%-5d %-13s %-16s %10.3f %10.3f %7.2f %7.2f %7.2f\n", n, proximity.name,
                    query.name, median(ours_us), median(fcl_us), ratio, low, high);
        std::fflush(stdout);
        char row[400];
        std::snprintf(row, sizeof row,
                      "%s{\"vertices\": %d, \"proximity\": \"%s\", \"query\": \"%s\", "
                      "\"fcl_method_us\": %.6g, \"fcl_direct_us\": %.6g, \"ratio\": %.6g, "
                      "\"ratio_min\": %.6g, \"ratio_max\": %.6g, \"pairs\": %zu}",
                      rows.empty() ? "" : ",\n", n, proximity.name, query.name, median(ours_us),
                      median(fcl_us), ratio, low, high, pairs.size());
        rows += row;
      }
    }
  }
  if (sink == 42.4242) std::puts("");
  std::printf("uncertified answers (distance, verdict, signed distance of every pair): %d\n",
              uncertified);
  if (!options.json.empty()) {
    std::ofstream out(options.json);
    out << "{\"rounds\": " << options.rounds << ", \"uncertified\": " << uncertified
        << ",\n\"rows\": [\n"
        << rows << "\n]}\n";
  }
  return uncertified == 0 ? 0 : 1;
}
