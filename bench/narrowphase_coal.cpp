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
//
// By default each workload is 20 pairs asked again and again, which lets the processor's branch
// predictors learn each call's path; `--poses K` asks each pair at K random placements instead
// (random_placements), 20 K different questions of the same bodies.
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
#include <stdexcept>
#include <string>
#include <vector>

#include "random_pairs.hpp"
#include "coal_convex.hpp"
#include "swarmcollide/queries/query.hpp"

namespace sc = swarmcollide;

namespace {

// coal's own precision: its default GJK tolerance, which its default convergence test applies as
// `tolerance * (1 + distance)` (GJK::checkConvergence stops once the distance found is within
// that of the best separating plane's). Our bounds must enclose coal's distance to it.
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

// One call's question: a pair of bodies, and where they are (the identity, unless --poses).
struct Placement {
  const Pair* pair;
  std::size_t index;  // the pair's, which seeds its query
  sc::Pose pose_a, pose_b;
  coal::Transform3s coal_pose_a = coal::Transform3s::Identity();
  coal::Transform3s coal_pose_b = coal::Transform3s::Identity();
};

coal::Transform3s to_coal(const sc::Pose& pose) {
  return coal::Transform3s(pose.rotation, pose.translation);
}

// A coal solver as one contender uses it, and one answer of it (support hint cleared first).
struct CoalCall {
  coal::GJKSolver solver;
  double operator()(const Placement& p) {
    coal::Vec3s p1, p2, normal;
    solver.support_func_cached_guess.setZero();
    return solver.shapeDistance(*p.pair->coal_a, p.coal_pose_a, *p.pair->coal_b, p.coal_pose_b,
                                false, p1, p2, normal);
  }
};

// `count` placements of the pair's bodies (centred on their centroids): each body turned by a
// random rotation, B moved from A along a random direction until the exact signed distance is
// `target` (bisection on the translation), so that every call asks a different question of the
// same few bodies, as a planner's poses do.
std::vector<Placement> random_placements(const Pair& pair, std::size_t index, double target,
                                         int count, Normals& normals) {
  sc::QueryOptions exact_options;
  exact_options.method = sc::Method::exact;
  const sc::Query exact(exact_options);
  const double reach = pair.a.vertices().rowwise().norm().maxCoeff() +
                       pair.b.vertices().rowwise().norm().maxCoeff() + std::abs(target) + 1;
  std::vector<Placement> placements;
  for (int draws = 0; static_cast<int>(placements.size()) < count; ++draws) {
    if (draws == 100 * count) throw std::runtime_error("random_placements: no placement found");
    Placement p{&pair, index, {}, {}};
    p.pose_a.rotation = normals.rotation();
    p.pose_b.rotation = normals.rotation();
    const sc::Vector3 u = normals.unit();
    const auto signed_distance = [&](double t) {
      p.pose_b.translation = t * u;
      return exact.signed_distance(pair.a, p.pose_a, pair.b, p.pose_b).distance;
    };
    // Thin bodies cannot overlap by some targets: such draws are replaced by the next.
    double lo = 0, hi = reach;
    if (!(signed_distance(lo) < target) || !(signed_distance(hi) > target)) continue;
    for (int step = 0; step < 64 && hi - lo > 1e-15; ++step) {
      const double mid = (lo + hi) / 2;
      (signed_distance(mid) < target ? lo : hi) = mid;
    }
    p.pose_b.translation = hi * u;
    p.coal_pose_a = to_coal(p.pose_a);
    p.coal_pose_b = to_coal(p.pose_b);
    placements.push_back(p);
  }
  return placements;
}

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
  int pairs = 0;  // pairs per workload (0: 20, 5 with --quick)
  int poses = 0;  // placements of each pair (0: the pair as drawn, with identity poses)
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
    } else if (arg == "--poses" && i + 1 < argc) {
      o.poses = std::atoi(argv[++i]);
    } else if (arg == "--pairs" && i + 1 < argc) {
      o.pairs = std::atoi(argv[++i]);
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
                   "usage: %s [--quick] [--sizes 8,64,...] [--pairs P] [--poses K] [--rounds R] "
                   "[--only NAME] [--proximity NAME] [--json PATH]\n",
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
  const int pair_count = options.pairs > 0 ? options.pairs : options.quick ? 5 : 20;
  const bool placed = options.poses > 0;
  std::string rows;
  std::printf("%-5s %-13s %-32s %9s %7s\n", "n", "proximity", "contender", "us/call", "ratio");
  for (int n : options.sizes) {
    for (const Proximity& proximity : proximities) {
      if (std::string(proximity.name).rfind(options.proximity, 0) != 0) continue;
      std::vector<Pair> pairs;
      std::vector<sc::Query> queries;
      pairs.reserve(pair_count);
      for (int i = 0; i < pair_count; ++i) {
        auto [a_points, b_points] =
            random_pair_points(n, proximity.target, random_pair_seed(n, proximity.index, i));
        if (placed) {  // each body in its own frame, about its centroid
          a_points.rowwise() -= a_points.colwise().mean().eval();
          b_points.rowwise() -= b_points.colwise().mean().eval();
        }
        Pair p{sc::ConvexPolyhedron(std::move(a_points)), sc::ConvexPolyhedron(std::move(b_points)),
               nullptr, nullptr};
        p.coal_a = to_coal(p.a);
        p.coal_b = to_coal(p.b);
        pairs.push_back(std::move(p));
        sc::QueryOptions o;  // the default method, dual, at the default tolerance
        o.seed = static_cast<std::uint64_t>(i);
        queries.emplace_back(o);
      }
      // Pair after pair, each at its k-th placement in the k-th pass, as a loop over different
      // questions asks them.
      std::vector<Placement> placements;
      if (!placed) {
        for (std::size_t i = 0; i < pairs.size(); ++i) placements.push_back({&pairs[i], i, {}, {}});
      } else {
        std::vector<std::vector<Placement>> per_pair;
        for (std::size_t i = 0; i < pairs.size(); ++i) {
          Normals normals(random_pair_seed(n, proximity.index, static_cast<int>(i)) + 0x5eed);
          per_pair.push_back(
              random_placements(pairs[i], i, proximity.target, options.poses, normals));
        }
        for (int k = 0; k < options.poses; ++k) {
          for (const std::vector<Placement>& some : per_pair) placements.push_back(some[k]);
        }
      }
      const auto our_distance = [&](const Placement& p) {
        const sc::Query& q = queries[p.index];
        return placed ? q.distance(p.pair->a, p.pose_a, p.pair->b, p.pose_b)
                      : q.distance(p.pair->a, p.pair->b);
      };
      const auto our_verdict = [&](const Placement& p) {
        const sc::Query& q = queries[p.index];
        return placed ? q.collision(p.pair->a, p.pose_a, p.pair->b, p.pose_b)
                      : q.collision(p.pair->a, p.pair->b);
      };
      const auto our_collide = [&](const Placement& p) {
        const sc::Query& q = queries[p.index];
        return placed ? q.collide(p.pair->a, p.pose_a, p.pair->b, p.pose_b)
                      : q.collide(p.pair->a, p.pair->b);
      };
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
                              return our_distance(placements[i]).distance;
                            }});
      contenders.push_back({"dual collide", true, true, [&](std::size_t i) {
                              return our_collide(placements[i]) ? 1.0 : 0.0;
                            }});
      for (const CoalVariant& v : variants) {
        distance_calls.push_back(std::make_unique<CoalCall>());
        distance_calls.back()->solver.set(distance_request(v.variant, v.guess));
        CoalCall* d = distance_calls.back().get();
        contenders.push_back({std::string(v.name) + " distance", false, false,
                              [d, &placements](std::size_t i) { return (*d)(placements[i]); }});
        collide_calls.push_back(std::make_unique<CoalCall>());
        const coal::CollisionRequest request = collision_request(v.variant, v.guess);
        collide_calls.back()->solver.set(request);
        CoalCall* c = collide_calls.back().get();
        const double threshold = request.collision_distance_threshold;
        contenders.push_back({std::string(v.name) + " collide", false, true,
                              [c, &placements, threshold](std::size_t i) {
                                return (*c)(placements[i]) <= threshold ? 1.0 : 0.0;
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
      for (const Placement& p : placements) {
        const double coal_distance = std::max(0.0, reference(p));
        const sc::DistanceResult r = our_distance(p);
        const sc::DistanceResult v = our_verdict(p);
        uncertified += !r.certified + !v.certified;
        const double coal_precision = kCoalTolerance * (1 + coal_distance);
        if (r.lower_bound > coal_distance + coal_precision ||
            r.distance < coal_distance - coal_precision) {
          if (++outside <= 3) {
            std::fprintf(stderr,
                         "n=%d %s, pair %zu: coal's distance %.17g outside our bounds [%.17g, "
                         "%.17g]\n",
                         n, proximity.name, p.index, coal_distance, r.lower_bound, r.distance);
          }
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
            for (std::size_t i = 0; i < placements.size(); ++i) sink += contenders[c].run(i);
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
            for (std::size_t i = 0; i < placements.size(); ++i) sink += contenders[c].run(i);
          }
          const double seconds =
              std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
          const double calls = repeats[c] * static_cast<double>(placements.size());
          per_call[c].push_back(1e6 * seconds / calls);
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
                        *std::max_element(ratios.begin(), ratios.end()), placements.size(),
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
    out << "{\"rounds\": " << options.rounds << ", \"poses_per_pair\": " << options.poses
        << ", \"coal_tolerance\": " << kCoalTolerance
        << ",\n\"rows\": [\n"
        << rows << "\n]}\n";
  }
  leave(0);
}
