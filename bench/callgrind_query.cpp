// swarmcollide-callgrind-query: instructions per query, ours against coal's GJK and EPA, counted
// by callgrind (which the machine's load does not disturb). Run it through
// bench/callgrind_query.py, which starts it under `valgrind --tool=callgrind
// --collect-atstart=no` and prints the table; alone it only answers the queries.
//
// Each workload (n vertices, apart by 1 or overlapping by 1e-2, and with --gap apart by 1e-2: the
// random pairs of random_pairs.hpp, both bodies under one random rigid pose) is answered by each
// contender once uncounted (so thread-local buffers and lazily built hulls exist), then `--repeats`
// times over its pairs with collection on, and the counts dumped under the label "n=N PROXIMITY
// QUERY CONTENDER PAIRS*REPEATS". Contenders: ours (Query with explicit poses: distance, collision,
// signed_distance; distance_many and collide_many over lists of the bodies with pose lists, one
// thread), coal's GJKSolver (distance, a collision verdict stopping at the first separating plane,
// and the signed distance by GJK + EPA), its support hint cleared before each call as in
// narrowphase_coal.cpp; and the fcl method's distance and verdict beside the FCL calls it wraps
// (`fcl::distance` and `fcl::collide` with FCL's own GJK, GST_INDEP, on prebuilt fcl::Convexd,
// requests reused). Natively coal's fastest is often not its default GJK but one of
// narrowphase_coal.cpp's other variants: the bounding boxes' centres as the initial guess
// ("coal_box"), Nesterov's acceleration ("coal_nesterov"), or both ("coal_nesterov_box"); their
// distances and verdicts are counted too, their answers summed apart from the checksum "sum"
// (which stays that of the rows above).
#include <coal/collision_data.h>
#include <coal/narrowphase/narrowphase.h>
#include <coal/shape/convex.h>
#include <valgrind/callgrind.h>

#include <cstdio>
#include <cstdlib>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "coal_convex.hpp"
#include "normals.hpp"
#include "random_pairs.hpp"
#include "swarmcollide/queries/batch.hpp"
#include "swarmcollide/queries/query.hpp"

namespace sc = swarmcollide;

namespace {

struct Workload {
  std::vector<sc::ConvexPolyhedron> a;
  std::vector<sc::ConvexPolyhedron> b;
  std::vector<std::shared_ptr<coal::Convex<coal::Triangle>>> coal_a;
  std::vector<std::shared_ptr<coal::Convex<coal::Triangle>>> coal_b;
  std::vector<std::shared_ptr<fcl::Convexd>> fcl_a;
  std::vector<std::shared_ptr<fcl::Convexd>> fcl_b;
  sc::Pose pose;
  coal::Transform3s coal_pose;
  fcl::Transform3d fcl_pose;
};

Workload workload(int n, double target, int proximity_index, int pairs) {
  Workload w;
  for (int i = 0; i < pairs; ++i) {
    auto [a, b] = random_pair_points(n, target, random_pair_seed(n, proximity_index, i));
    w.a.emplace_back(std::move(a));
    w.b.emplace_back(std::move(b));
    w.coal_a.push_back(to_coal(w.a.back()));
    w.coal_b.push_back(to_coal(w.b.back()));
    w.fcl_a.push_back(to_fcl(w.a.back(), sc::Vector3::Zero()));
    w.fcl_b.push_back(to_fcl(w.b.back(), sc::Vector3::Zero()));
  }
  Normals normals(random_pair_seed(n, proximity_index, pairs));
  w.pose.rotation = normals.rotation();
  w.pose.translation = normals.unit();
  w.coal_pose = coal::Transform3s(w.pose.rotation, w.pose.translation);
  w.fcl_pose = fcl::Transform3d::Identity();
  w.fcl_pose.linear() = w.pose.rotation;
  w.fcl_pose.translation() = w.pose.translation;
  return w;
}

coal::DistanceRequest distance_request(
    bool signed_distance, coal::GJKVariant variant = coal::GJKVariant::DefaultGJK,
    coal::GJKInitialGuess guess = coal::GJKInitialGuess::DefaultGuess) {
  coal::DistanceRequest request;
  request.enable_signed_distance = signed_distance;
  request.gjk_variant = variant;
  request.gjk_initial_guess = guess;
  return request;
}

coal::CollisionRequest collision_request(
    coal::GJKVariant variant = coal::GJKVariant::DefaultGJK,
    coal::GJKInitialGuess guess = coal::GJKInitialGuess::DefaultGuess) {
  coal::CollisionRequest request;
  request.enable_contact = false;
  request.distance_upper_bound = 0;  // stop at the first separating plane, as our verdict does
  request.gjk_variant = variant;
  request.gjk_initial_guess = guess;
  return request;
}

// coal's GJK variants besides its default, as narrowphase_coal.cpp times them.
struct CoalVariant {
  const char* name;
  coal::GJKVariant variant;
  coal::GJKInitialGuess guess;
};
const CoalVariant kCoalVariants[] = {
    {"coal_box", coal::GJKVariant::DefaultGJK, coal::GJKInitialGuess::BoundingVolumeGuess},
    {"coal_nesterov", coal::GJKVariant::NesterovAcceleration,
     coal::GJKInitialGuess::DefaultGuess},
    {"coal_nesterov_box", coal::GJKVariant::NesterovAcceleration,
     coal::GJKInitialGuess::BoundingVolumeGuess}};

struct Contender {
  std::string query;
  std::string name;
  // Answers every pair once; the sum keeps the calls from being optimised away.
  std::function<double()> run;
};

}  // namespace

int main(int argc, char** argv) {
  std::vector<int> sizes{4, 8, 16, 64};
  int pairs = 20;
  int repeats = 5;
  bool gap = false;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--sizes" && i + 1 < argc) {
      sizes.clear();
      const std::string list = argv[++i];
      for (std::size_t start = 0; start < list.size();) {
        const std::size_t comma = list.find(',', start);
        sizes.push_back(std::stoi(list.substr(start, comma - start)));
        start = comma == std::string::npos ? list.size() : comma + 1;
      }
    } else if (arg == "--pairs" && i + 1 < argc) {
      pairs = std::atoi(argv[++i]);
    } else if (arg == "--repeats" && i + 1 < argc) {
      repeats = std::atoi(argv[++i]);
    } else if (arg == "--gap") {
      gap = true;
    } else {
      std::fprintf(stderr, "usage: %s [--sizes 4,8,16,64] [--pairs P] [--repeats R] [--gap]\n",
                   argv[0]);
      leave(2);
    }
  }
  struct Proximity {
    const char* name;
    double target;
    int index;  // swarmcollide_bench.cpp's, which seeds the pairs
  };
  std::vector<Proximity> proximities{{"apart", 1.0, 0}, {"overlap", -1e-2, 7}};
  // narrowphase_coal.cpp's "gap 1e-2" pairs, apart by a hundredth: a verdict's search there runs
  // until a direction separates them, where "apart" settles at the centres' direction.
  if (gap) proximities.insert(proximities.begin() + 1, {"gap", 1e-2, 2});
  double sink = 0;
  double variants_sink = 0;  // coal's other variants, kept out of the checksum
  for (int n : sizes) {
    for (const Proximity& proximity : proximities) {
      const Workload w = workload(n, proximity.target, proximity.index, pairs);
      const sc::Query query;  // the default method, dual, at the default tolerance
      const sc::QueryOptions options;
      sc::QueryOptions fcl_options;
      fcl_options.method = sc::Method::fcl;
      const sc::Query fcl_query(fcl_options);
      // FCL's own GJK (the one the fcl method runs) with its request and result reused.
      const fcl::DistanceRequestd fcl_request(true, false, 0, 0, 1e-10, fcl::GST_INDEP);
      sc::BatchSettings one_thread;
      one_thread.threads = 1;
      sc::BatchPoses poses;
      poses.a.assign(pairs, w.pose);
      poses.b.assign(pairs, w.pose);
      coal::GJKSolver coal_distance(distance_request(false));
      coal::GJKSolver coal_signed(distance_request(true));
      coal::GJKSolver coal_collide(collision_request());
      const auto coal_call = [&w](coal::GJKSolver& solver, bool signed_distance) {
        double sum = 0;
        coal::Vec3s p1, p2, normal;
        for (std::size_t i = 0; i < w.a.size(); ++i) {
          solver.support_func_cached_guess.setZero();
          sum += solver.shapeDistance(*w.coal_a[i], w.coal_pose, *w.coal_b[i], w.coal_pose,
                                      signed_distance, p1, p2, normal);
        }
        return sum;
      };
      const auto our_distances = [&w](const sc::Query& asked) {
        double sum = 0;
        for (std::size_t i = 0; i < w.a.size(); ++i)
          sum += asked.distance(w.a[i], w.pose, w.b[i], w.pose).distance;
        return sum;
      };
      const std::vector<Contender> contenders{
          {"distance", "ours", [&] { return our_distances(query); }},
          {"distance", "coal", [&] { return coal_call(coal_distance, false); }},
          {"distance", "ours_fcl", [&] { return our_distances(fcl_query); }},
          {"distance", "fcl",
           [&] {
             double sum = 0;
             fcl::DistanceResultd result;
             for (std::size_t i = 0; i < w.a.size(); ++i) {
               result.clear();
               fcl::distance(w.fcl_a[i].get(), w.fcl_pose, w.fcl_b[i].get(), w.fcl_pose,
                             fcl_request, result);
               sum += result.min_distance;
             }
             return sum;
           }},
          {"distance", "ours_batch",
           [&] {
             return sc::distance_many(w.a, w.b, options, one_thread, poses).distance.sum();
           }},
          {"collide", "ours",
           [&] {
             double sum = 0;
             for (std::size_t i = 0; i < w.a.size(); ++i)
               sum += query.collide(w.a[i], w.pose, w.b[i], w.pose);
             return sum;
           }},
          {"collide", "coal", [&] { return coal_call(coal_collide, false); }},
          {"collide", "ours_batch",
           [&] {
             return sc::collide_many(w.a, w.b, options, one_thread, poses).distance.sum();
           }},
          {"signed_distance", "ours",
           [&] {
             double sum = 0;
             for (std::size_t i = 0; i < w.a.size(); ++i)
               sum += query.signed_distance(w.a[i], w.pose, w.b[i], w.pose).distance;
             return sum;
           }},
          {"signed_distance", "coal", [&] { return coal_call(coal_signed, true); }},
      };
      // Our answers must be certified, or the counts are of another workload.
      int uncertified = 0;
      for (std::size_t i = 0; i < w.a.size(); ++i) {
        uncertified += !query.distance(w.a[i], w.pose, w.b[i], w.pose).certified;
        uncertified += !query.collision(w.a[i], w.pose, w.b[i], w.pose).certified;
        uncertified += !query.signed_distance(w.a[i], w.pose, w.b[i], w.pose).certified;
      }
      if (uncertified) std::printf("n=%d %s: %d uncertified\n", n, proximity.name, uncertified);
      std::vector<Contender> variants;
      std::vector<std::unique_ptr<coal::GJKSolver>> variant_solvers;
      // The fcl method's verdict beside FCL's own collide (GST_INDEP, no contacts, request
      // reused), kept out of the checksum as coal's variants are.
      const fcl::CollisionRequestd fcl_collide_request(1, false, 1, false, true, fcl::GST_INDEP);
      variants.push_back({"collide", "ours_fcl", [&] {
                            double sum = 0;
                            for (std::size_t i = 0; i < w.a.size(); ++i)
                              sum += fcl_query.collide(w.a[i], w.pose, w.b[i], w.pose);
                            return sum;
                          }});
      variants.push_back({"collide", "fcl", [&] {
                            double sum = 0;
                            fcl::CollisionResultd result;
                            for (std::size_t i = 0; i < w.a.size(); ++i) {
                              result.clear();
                              sum += fcl::collide(w.fcl_a[i].get(), w.fcl_pose, w.fcl_b[i].get(),
                                                  w.fcl_pose, fcl_collide_request, result);
                            }
                            return sum;
                          }});
      for (const CoalVariant& v : kCoalVariants) {
        variant_solvers.push_back(
            std::make_unique<coal::GJKSolver>(distance_request(false, v.variant, v.guess)));
        coal::GJKSolver* distance = variant_solvers.back().get();
        variants.push_back({"distance", v.name, [=] { return coal_call(*distance, false); }});
        variant_solvers.push_back(
            std::make_unique<coal::GJKSolver>(collision_request(v.variant, v.guess)));
        coal::GJKSolver* collide = variant_solvers.back().get();
        variants.push_back({"collide", v.name, [=] { return coal_call(*collide, false); }});
      }
      const auto count = [&](const Contender& c, double& into) {
        into += c.run();
        CALLGRIND_TOGGLE_COLLECT;
        for (int r = 0; r < repeats; ++r) into += c.run();
        CALLGRIND_TOGGLE_COLLECT;
        const std::string label = "n=" + std::to_string(n) + " " + proximity.name + " " +
                                  c.query + " " + c.name + " " +
                                  std::to_string(pairs * repeats);
        CALLGRIND_DUMP_STATS_AT(label.c_str());
      };
      for (const Contender& c : contenders) count(c, sink);
      for (const Contender& c : variants) count(c, variants_sink);
    }
  }
  std::printf("sum %.17g\n", sink);
  std::printf("coal variants' sum %.17g\n", variants_sink);
  leave(0);
}
