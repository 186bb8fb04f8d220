// swarmcollide-callgrind-curved: instructions per signed distance of curved shapes (cylinders,
// cones, ellipsoids, spheres, capsules, boxes), ours against coal's primitives, counted by callgrind. Run
// it through `bench/callgrind_query.py --curved`, which starts it under valgrind with collection
// off and prints the table; alone it only answers the queries.
//
// The pairs are bench/curved_coal.py's kind pairs, drawn the same way (sizes in [0.2, 1], A
// within 0.2 of the origin and B within 1.6, random rotations) from a fixed seed, and split by
// coal's signed distance into apart and overlapping ones. Each contender answers its pairs once
// uncounted, then `--repeats` times with collection on; the counts are dumped under the label
// "pair=KINDS PROXIMITY signed_distance CONTENDER CALLS". Contenders: ours
// (Query::signed_distance with explicit poses, the default method) and coal::distance with
// enable_signed_distance on its own primitives (its shape-shape dispatch, as a coal user calls
// it), at its default GJK and EPA tolerances (an absolute 1e-6) and, as "coal_matched", at ours:
// 1e-9 of the pair's size as our frame measures it (the distance between the bodies' box centres
// plus the larger box radius twice). On curved surfaces each further digit costs steps, so the
// default comparison asks 1000x more precision of us than of coal; "ours_at_1e-6" asks ours for
// coal's absolute 1e-6 (a tolerance of 1e-6 over that size).
#include <coal/collision_data.h>
#include <coal/distance.h>
#include <coal/shape/geometric_shapes.h>
#include <valgrind/callgrind.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "coal_convex.hpp"
#include "normals.hpp"
#include "swarmcollide/geometry/shapes.hpp"
#include "swarmcollide/queries/query.hpp"

namespace sc = swarmcollide;

namespace {

struct Shape {
  // Held through shared_ptr made from the derived type, which deletes it as that type.
  std::shared_ptr<sc::ConvexPolyhedron> ours;
  std::shared_ptr<coal::ShapeBase> coal;
};

double uniform(Normals& random, double low, double high) {
  return low + (high - low) * random.uniform();
}

Shape make(const std::string& kind, Normals& random) {
  const double r = uniform(random, 0.2, 1.0);
  const double h = uniform(random, 0.2, 1.0);
  if (kind == "cylinder") {
    return {std::make_shared<sc::Cylinder>(r, h), std::make_shared<coal::Cylinder>(r, 2 * h)};
  }
  if (kind == "cone") {
    return {std::make_shared<sc::Cone>(r, h), std::make_shared<coal::Cone>(r, 2 * h)};
  }
  if (kind == "sphere") {
    return {std::make_shared<sc::Sphere>(r), std::make_shared<coal::Sphere>(r)};
  }
  if (kind == "capsule") {
    return {std::make_shared<sc::Capsule>(r, h), std::make_shared<coal::Capsule>(r, 2 * h)};
  }
  const sc::Vector3 extents(uniform(random, 0.2, 1.0), uniform(random, 0.2, 1.0),
                            uniform(random, 0.2, 1.0));
  if (kind == "ellipsoid") {
    return {std::make_shared<sc::Ellipsoid>(extents), std::make_shared<coal::Ellipsoid>(extents)};
  }
  return {std::make_shared<sc::Box>(extents), std::make_shared<coal::Box>(2 * extents)};
}

struct Case {
  Shape a;
  Shape b;
  sc::Pose pose_a;
  sc::Pose pose_b;
  coal::Transform3s coal_a;
  coal::Transform3s coal_b;
};

sc::Pose random_pose(Normals& random, double spread) {
  sc::Pose pose;
  pose.rotation = random.rotation();
  pose.translation = sc::Vector3(uniform(random, -spread, spread), uniform(random, -spread, spread),
                                 uniform(random, -spread, spread));
  return pose;
}

// The pair's size as our frame measures it.
double pair_size(const Case& c) {
  const sc::Vector3 centre_a = c.pose_a.rotation * c.a.ours->bounds().centre + c.pose_a.translation;
  const sc::Vector3 centre_b = c.pose_b.rotation * c.b.ours->bounds().centre + c.pose_b.translation;
  return (centre_b - centre_a).norm() +
         2 * std::max(c.a.ours->bounds().radius, c.b.ours->bounds().radius);
}

// coal's signed distance, at its default tolerances unless `matched` (at ours, see above).
double coal_signed_distance(const Case& c, coal::DistanceResult& result, bool matched = false) {
  coal::DistanceRequest request;
  request.enable_signed_distance = true;
  if (matched) {
    request.gjk_tolerance = request.epa_tolerance = sc::kDefaultTolerance * pair_size(c);
  }
  result.clear();
  return coal::distance(c.a.coal.get(), c.coal_a, c.b.coal.get(), c.coal_b, request, result);
}

}  // namespace

int main(int argc, char** argv) {
  int pairs = 20;
  int repeats = 5;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--pairs" && i + 1 < argc) {
      pairs = std::atoi(argv[++i]);
    } else if (arg == "--repeats" && i + 1 < argc) {
      repeats = std::atoi(argv[++i]);
    } else {
      std::fprintf(stderr, "usage: %s [--pairs P] [--repeats R]\n", argv[0]);
      leave(2);
    }
  }
  const std::vector<std::pair<std::string, std::string>> kinds{
      {"cylinder", "cylinder"},  {"cylinder", "cone"},  {"cone", "cone"},
      {"ellipsoid", "ellipsoid"}, {"cylinder", "ellipsoid"}, {"cone", "ellipsoid"},
      {"cylinder", "sphere"},    {"ellipsoid", "box"},  {"cone", "box"},
      // A scene of balls and capsules asks these (coal answers the first three in closed form).
      {"sphere", "sphere"},      {"sphere", "capsule"}, {"capsule", "capsule"},
      {"sphere", "box"},         {"capsule", "box"}};
  Normals random(26);
  const sc::Query query;
  coal::DistanceResult coal_result;
  double sink = 0;
  int failed_matched = 0;  // coal's answers at our tolerance that are +-DBL_MAX, inf or NaN
  int asked = 0;
  for (const auto& [kind_a, kind_b] : kinds) {
    // Drawn until both proximities have `pairs` pairs (coal's sign decides).
    std::vector<Case> apart;
    std::vector<Case> overlap;
    while (static_cast<int>(apart.size()) < pairs || static_cast<int>(overlap.size()) < pairs) {
      Case c{make(kind_a, random), make(kind_b, random), random_pose(random, 0.2),
             random_pose(random, 1.6), {}, {}};
      c.coal_a = coal::Transform3s(c.pose_a.rotation, c.pose_a.translation);
      c.coal_b = coal::Transform3s(c.pose_b.rotation, c.pose_b.translation);
      std::vector<Case>& bin = coal_signed_distance(c, coal_result) < 0 ? overlap : apart;
      if (static_cast<int>(bin.size()) < pairs) bin.push_back(std::move(c));
    }
    for (const auto& [proximity, cases] :
         {std::make_pair("apart", &apart), std::make_pair("overlap", &overlap)}) {
      int uncertified = 0;
      for (const Case& c : *cases) {
        uncertified += !query.signed_distance(*c.a.ours, c.pose_a, *c.b.ours, c.pose_b).certified;
        // coal answers -DBL_MAX where its EPA fails at that tolerance.
        failed_matched += !(std::abs(coal_signed_distance(c, coal_result, true)) < 1e300);
      }
      if (uncertified) {
        std::printf("%s-%s %s: %d uncertified\n", kind_a.c_str(), kind_b.c_str(), proximity,
                    uncertified);
      }
      const auto ours = [&] {
        double sum = 0;
        for (const Case& c : *cases) {
          sum += query.signed_distance(*c.a.ours, c.pose_a, *c.b.ours, c.pose_b).distance;
        }
        return sum;
      };
      // Ours at coal's precision: bounds proven within an absolute 1e-6 (curved_coal.py's
      // "dual at 1e-6"), each pair's query made once.
      std::vector<sc::Query> coarse;
      for (const Case& c : *cases) {
        sc::QueryOptions options;
        options.tolerance = 1e-6 / pair_size(c);
        coarse.emplace_back(options);
      }
      const auto ours_coarse = [&] {
        double sum = 0;
        for (std::size_t i = 0; i < cases->size(); ++i) {
          const Case& c = (*cases)[i];
          sum += coarse[i].signed_distance(*c.a.ours, c.pose_a, *c.b.ours, c.pose_b).distance;
        }
        return sum;
      };
      const auto theirs = [&] {
        double sum = 0;
        for (const Case& c : *cases) sum += coal_signed_distance(c, coal_result);
        return sum;
      };
      const auto theirs_matched = [&] {
        double sum = 0;
        for (const Case& c : *cases) sum += coal_signed_distance(c, coal_result, true);
        return sum;
      };
      asked += static_cast<int>(cases->size());
      for (const auto& [name, run] :
           {std::make_pair("ours", std::function<double()>(ours)),
            std::make_pair("coal", std::function<double()>(theirs)),
            std::make_pair("coal_matched", std::function<double()>(theirs_matched)),
            std::make_pair("ours_at_1e-6", std::function<double()>(ours_coarse))}) {
        // The printed sum is ours and coal's at its defaults, as before coal_matched (whose
        // failures, -DBL_MAX, would overflow it) and ours_at_1e-6 were added.
        const bool summed = std::string(name) == "ours" || std::string(name) == "coal";
        const auto answer = [&] {
          const double sum = run();
          if (summed) sink += sum;
        };
        answer();
        CALLGRIND_TOGGLE_COLLECT;
        for (int r = 0; r < repeats; ++r) answer();
        CALLGRIND_TOGGLE_COLLECT;
        const std::string label = "pair=" + kind_a + "-" + kind_b + " " + proximity +
                                  " signed_distance " + name + " " +
                                  std::to_string(pairs * repeats);
        CALLGRIND_DUMP_STATS_AT(label.c_str());
      }
    }
  }
  std::printf("sum %.17g\n", sink);
  std::printf("coal at our tolerance: %d of %d answers failed (DBL_MAX, inf or NaN)\n",
              failed_matched, asked);
  leave(0);
}
