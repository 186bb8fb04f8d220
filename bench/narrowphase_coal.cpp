// swarmcollide-narrowphase-coal: the default method's distance and collide verdict against coal's
// GJK (C++, prebuilt shapes), per vertex count, on the random pairs of swarmcollide_bench.cpp.
// Built only when coal is found (bench/CMakeLists.txt); results: bench/RESULTS.md.
//
// How coal is called: one GJKSolver per contender, set once from its request, answering each pair
// with `shapeDistance` on prebuilt `coal::Convex` shapes (the cheapest call coal offers; a
// `ComputeDistance` functor does the same after a `set`). A GJKSolver keeps the support points
// of its last answer as the next call's hill-climbing start (`support_func_cached_guess`, used
// whatever the initial-guess setting); the bench asks the same pair again and again, so the
// solver would start at the answer. That hint is cleared before every call, as a fresh query
// (`coal::distance`, which builds its solver per call) starts. Each coal variant below is timed,
// and the ratios are against the fastest of them (lowest median) on each workload: coal's best
// correct usage.
#include <coal/collision_data.h>
#include <coal/narrowphase/narrowphase.h>
#include <coal/shape/convex.h>
#include <coal/shape/geometric_shapes.h>

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
#include "coal_convex.hpp"
#include "swarmcollide/queries/query.hpp"

namespace sc = swarmcollide;

namespace {

// coal's own precision (its default GJK tolerance): our bounds must enclose coal's distance to it.
constexpr double kCoalTolerance = 1e-6;
// Each contender's turn in a round lasts at least this long, so the clock's resolution and the
// loop's overhead do not enter.
constexpr double kTurnSeconds = 2e-3;

struct Proximity {
  const char* name;
  double target;
  int index;  // in swarmcollide_bench.cpp's list, which seeds the pairs
};

using CoalConvex = coal::Convex<coal::Triangle>;

struct Pair {
  sc::ConvexPolyhedron a;
  sc::ConvexPolyhedron b;
  std::shared_ptr<CoalConvex> coal_a;
  std::shared_ptr<CoalConvex> coal_b;
};

// A coal solver as one contender uses it, and one answer of it (support hint cleared first).
struct CoalCall {
  coal::GJKSolver solver;
  double operator()(const Pair& p) {
    static const coal::Transform3s identity = coal::Transform3s::Identity();
    coal::Vec3s p1, p2, normal;
    solver.support_func_cached_guess.setZero();
    return solver.shapeDistance(*p.coal_a, identity, *p.coal_b, identity, false, p1, p2, normal);
  }
};

coal::DistanceRequest distance_request(coal::GJKVariant variant, coal::GJKInitialGuess guess) {
  coal::DistanceRequest request;
  request.enable_signed_distance = false;  // a distance, as ours: no EPA for overlaps
  request.gjk_variant = variant;
  request.gjk_initial_guess = guess;
  return request;
}

coal::CollisionRequest collision_request(coal::GJKVariant variant, coal::GJKInitialGuess guess) {
  coal::CollisionRequest request;  // one contact, security margin 0
  request.enable_contact = false;  // a verdict, as ours: no EPA for overlaps
  // GJK stops at the first separating plane, as our verdict does (coal's default runs it on to the
  // distance).
  request.distance_upper_bound = 0;
  request.gjk_variant = variant;
  request.gjk_initial_guess = guess;
  return request;
}

struct Contender {
  std::string name;
  bool ours;
  bool collide;
  // Answers pair i; the result is summed so that no call can be optimised away.
  std::function<double(std::size_t)> run;
};

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t m = v.size() / 2;
  return v.size() % 2 ? v[m] : (v[m - 1] + v[m]) / 2;
}

struct Options {
  bool quick = false;
  std::vector<int> sizes;
  std::string json;
  int rounds = 0;
  // Only the contenders whose names start with this (for profiling one of them).
  std::string only;
  // Only the proximities whose names start with this ("overlap", for profiling one of them).
  std::string proximity;
};

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--quick") {
      o.quick = true;
    } else if (arg == "--json" && i + 1 < argc) {
      o.json = argv[++i];
    } else if (arg == "--only" && i + 1 < argc) {
      o.only = argv[++i];
    } else if (arg == "--proximity" && i + 1 < argc) {
      o.proximity = argv[++i];
    } else if (arg == "--rounds" && i + 1 < argc) {
      o.rounds = std::atoi(argv[++i]);
    } else if (arg == "--sizes" && i + 1 < argc) {
      std::string list = argv[++i];
      for (std::size_t start = 0; start < list.size();) {
        const std::size_t comma = list.find(',', start);
        o.sizes.push_back(std::stoi(list.substr(start, comma - start)));
        start = comma == std::string::npos ? list.size() : comma + 1;
      }
    } else {
      std::fprintf(stderr,
                   "usage: %s [--quick] [--sizes 8,64,...] [--rounds R] [--only NAME] "
                   "[--proximity NAME] [--json PATH]\n",
                   argv[0]);
      leave(2);
    }
  }
  if (o.sizes.empty()) {
    o.sizes = o.quick ? std::vector<int>{8, 64, 512, 4096}
                      : std::vector<int>{4, 8, 16, 32, 64, 128, 260, 512, 1024, 2048, 4096};
  }
  if (o.rounds <= 0) o.rounds = o.quick ? 7 : 21;
  return o;
}

}  // namespace

int main(int argc, char** argv) {
  const Options options = parse(argc, argv);
  const std::vector<Proximity> proximities = {
      {"apart", 1.0, 0}, {"gap 1e-2", 1e-2, 2}, {"overlap 1e-2", -1e-2, 7}};
  const int pair_count = options.quick ? 5 : 20;
  std::string rows;
  std::printf("%-5s %-13s %-32s %9s %7s\n", "n", "proximity", "contender", "us/call", "ratio");
  for (int n : options.sizes) {
    for (const Proximity& proximity : proximities) {
      if (std::string(proximity.name).rfind(options.proximity, 0) != 0) continue;
      std::vector<Pair> pairs;
      std::vector<sc::Query> queries;
      for (int i = 0; i < pair_count; ++i) {
        auto [a_points, b_points] =
            random_pair_points(n, proximity.target, random_pair_seed(n, proximity.index, i));
        Pair p{sc::ConvexPolyhedron(std::move(a_points)), sc::ConvexPolyhedron(std::move(b_points)),
               nullptr, nullptr};
        p.coal_a = to_coal(p.a);
        p.coal_b = to_coal(p.b);
        pairs.push_back(std::move(p));
        sc::QueryOptions o;  // the default method, dual, at the default tolerance
        o.seed = static_cast<std::uint64_t>(i);
        queries.emplace_back(o);
      }
      struct CoalVariant {
        const char* name;
        coal::GJKVariant variant;
        coal::GJKInitialGuess guess;
      };
      const std::vector<CoalVariant> variants = {
          {"coal GJK", coal::GJKVariant::DefaultGJK, coal::GJKInitialGuess::DefaultGuess},
          {"coal GJK box guess", coal::GJKVariant::DefaultGJK,
           coal::GJKInitialGuess::BoundingVolumeGuess},
          {"coal Nesterov", coal::GJKVariant::NesterovAcceleration,
           coal::GJKInitialGuess::DefaultGuess},
          {"coal Nesterov box guess", coal::GJKVariant::NesterovAcceleration,
           coal::GJKInitialGuess::BoundingVolumeGuess}};
      std::vector<std::unique_ptr<CoalCall>> distance_calls, collide_calls;
      std::vector<Contender> contenders;
      contenders.push_back({"dual distance", true, false, [&](std::size_t i) {
                              return queries[i].distance(pairs[i].a, pairs[i].b).distance;
                            }});
      contenders.push_back({"dual collide", true, true, [&](std::size_t i) {
                              return queries[i].collide(pairs[i].a, pairs[i].b) ? 1.0 : 0.0;
                            }});
      for (const CoalVariant& v : variants) {
        distance_calls.push_back(std::make_unique<CoalCall>());
        distance_calls.back()->solver.set(distance_request(v.variant, v.guess));
        CoalCall* d = distance_calls.back().get();
        contenders.push_back({std::string(v.name) + " distance", false, false,
                              [d, &pairs](std::size_t i) { return (*d)(pairs[i]); }});
        collide_calls.push_back(std::make_unique<CoalCall>());
        const coal::CollisionRequest request = collision_request(v.variant, v.guess);
        collide_calls.back()->solver.set(request);
        CoalCall* c = collide_calls.back().get();
        const double threshold = request.collision_distance_threshold;
        contenders.push_back({std::string(v.name) + " collide", false, true,
                              [c, &pairs, threshold](std::size_t i) {
                                return (*c)(pairs[i]) <= threshold ? 1.0 : 0.0;
                              }});
      }

      if (!options.only.empty()) {
        contenders.erase(std::remove_if(contenders.begin(), contenders.end(),
                                        [&](const Contender& c) {
                                          return c.name.rfind(options.only, 0) != 0;
                                        }),
                         contenders.end());
      }

      // Accuracy, once per pair: our certified bounds must enclose coal's distance to its
      // precision, and the verdicts must agree.
      int uncertified = 0, outside = 0, verdicts_differ = 0;
      double worst_gap = 0;
      CoalCall reference;
      reference.solver.set(distance_request(coal::GJKVariant::DefaultGJK,
                                            coal::GJKInitialGuess::DefaultGuess));
      for (std::size_t i = 0; i < pairs.size(); ++i) {
        const double coal_distance = std::max(0.0, reference(pairs[i]));
        const sc::DistanceResult r = queries[i].distance(pairs[i].a, pairs[i].b);
        const sc::DistanceResult v = queries[i].collision(pairs[i].a, pairs[i].b);
        uncertified += !r.certified + !v.certified;
        if (r.lower_bound > coal_distance + kCoalTolerance ||
            r.distance < coal_distance - kCoalTolerance) {
          ++outside;
        }
        worst_gap = std::max(worst_gap, std::abs(r.distance - coal_distance));
        verdicts_differ += v.colliding != (proximity.target < 0);
      }

      // Rounds: every contender in turn (the order rotates), each turn repeating the pairs until
      // it lasts kTurnSeconds; its time per call in each round.
      std::vector<std::vector<double>> per_call(contenders.size());
      std::vector<int> repeats(contenders.size(), 1);
      double sink = 0;
      for (std::size_t c = 0; c < contenders.size(); ++c) {
        for (;;) {
          const auto start = std::chrono::steady_clock::now();
          for (int r = 0; r < repeats[c]; ++r) {
            for (std::size_t i = 0; i < pairs.size(); ++i) sink += contenders[c].run(i);
          }
          const double seconds =
              std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
          if (seconds >= kTurnSeconds) break;
          repeats[c] *= 2;
        }
      }
      for (int round = 0; round < options.rounds; ++round) {
        for (std::size_t k = 0; k < contenders.size(); ++k) {
          const std::size_t c = (k + round) % contenders.size();
          const auto start = std::chrono::steady_clock::now();
          for (int r = 0; r < repeats[c]; ++r) {
            for (std::size_t i = 0; i < pairs.size(); ++i) sink += contenders[c].run(i);
          }
          const double seconds =
              std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
          per_call[c].push_back(1e6 * seconds / (repeats[c] * static_cast<double>(pairs.size())));
        }
      }
      if (sink == 42.4242) std::puts("");

      // Ratios: each contender over coal's fastest variant for this query (the lowest median
      // time per call), round by round, median over rounds.
      for (bool collide : {false, true}) {
        std::size_t coal_best = contenders.size();
        for (std::size_t c = 0; c < contenders.size(); ++c) {
          if (contenders[c].ours || contenders[c].collide != collide) continue;
          if (coal_best == contenders.size() ||
              median(per_call[c]) < median(per_call[coal_best])) {
            coal_best = c;
          }
        }
        for (std::size_t c = 0; c < contenders.size(); ++c) {
          if (contenders[c].collide != collide) continue;
          // Without a coal contender (--only), the ratios are NaN.
          std::vector<double> ratios;
          for (int r = 0; r < options.rounds; ++r) {
            ratios.push_back(coal_best < contenders.size()
                                 ? per_call[c][r] / per_call[coal_best][r]
                                 : std::nan(""));
          }
          const double us = median(per_call[c]);
          const double ratio = median(ratios);
          std::printf("%-5d %-13s %-32s %9.3f %7.2f\n", n, proximity.name,
                      contenders[c].name.c_str(), us, ratio);
          char row[640];
          std::snprintf(row, sizeof row,
                        "%s{\"vertices\": %d, \"proximity\": \"%s\", \"contender\": \"%s\", "
                        "\"query\": \"%s\", \"microseconds\": %.6g, \"coal_best\": \"%s\", "
                        "\"ratio_to_coal_best\": %.6g, \"ratio_min\": %.6g, \"ratio_max\": %.6g, "
                        "\"pairs\": %zu, \"uncertified\": %d, \"outside_bounds\": %d, "
                        "\"wrong_verdicts\": %d, \"largest_difference\": %.3g}",
                        rows.empty() ? "" : ",\n", n, proximity.name, contenders[c].name.c_str(),
                        collide ? "collide" : "distance", us,
                        coal_best < contenders.size() ? contenders[coal_best].name.c_str() : "",
                        ratio, *std::min_element(ratios.begin(), ratios.end()),
                        *std::max_element(ratios.begin(), ratios.end()), pairs.size(),
                        contenders[c].ours ? uncertified : 0, contenders[c].ours ? outside : 0,
                        contenders[c].ours ? verdicts_differ : 0,
                        contenders[c].ours ? worst_gap : 0.0);
          rows += row;
        }
      }
      if (uncertified || outside || verdicts_differ) {
        std::printf("n=%d %s: %d uncertified, %d outside the bounds, %d wrong verdicts\n", n,
                    proximity.name, uncertified, outside, verdicts_differ);
      }
      std::fflush(stdout);
    }
  }
  if (!options.json.empty()) {
    std::ofstream out(options.json);
    out << "{\"rounds\": " << options.rounds << ", \"coal_tolerance\": " << kCoalTolerance
        << ",\n\"rows\": [\n"
        << rows << "\n]}\n";
  }
  leave(0);
}
