// swarmcollide-penetration-coal: the default method's signed distance of overlapping pairs
// against coal's GJK + EPA (issue 25, item 2), C++ against C++ on shapes built once.
//
//   swarmcollide-penetration-coal [--quick] [--repeats K] [--sizes 8,64] [--json FILE]
//                                 [--only ours|coal]
//
// `--only` times one contender alone (for a profiler; the ratios are then meaningless).
// Pairs: two random polytopes of n vertices (the hull of n points on the unit sphere, so the
// bodies' diameter is about 2) under random rotations, B moved along a random direction until the
// exact signed distance is -1e-2 or -0.6 (0.3 of the diameter). Each pair is timed K times per
// contender, the two contenders alternating call by call; the per-pair medians are summed per
// workload and reported as the ratio ours / coal. Accuracy: coal's depth (its EPA's tolerance is
// 1e-6) against our certified bounds, counted as outside when it falls beyond them by more than
// coal's tolerance, and whether each of our answers is certified. Iterations: ours are Wolfe's
// and the expanding polytope's, coal's its GJK's and its EPA's.
#include <coal/collision_data.h>
#include <coal/distance.h>
#include <coal/narrowphase/narrowphase.h>
#include <coal/shape/convex.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "coal_convex.hpp"
#include "normals.hpp"
#include "swarmcollide/queries/methods.hpp"
#include "swarmcollide/queries/query.hpp"

namespace sc = swarmcollide;

namespace {

// coal's own EPA tolerance (EPA_DEFAULT_TOLERANCE): its depth counts as outside our bounds only
// when it is beyond them by more than this.
constexpr double kCoalTolerance = 1e-6;

// The hull vertices of `n` random points on the unit sphere.
sc::VertexMatrix sphere_polytope(int n, Normals& normals) {
  sc::VertexMatrix points(n, 3);
  for (int i = 0; i < n; ++i) points.row(i) = normals.unit().transpose();
  const sc::ConvexPolyhedron body(points);
  const std::vector<int>& indices = body.hull().vertex_indices;
  sc::VertexMatrix vertices(static_cast<Eigen::Index>(indices.size()), 3);
  for (std::size_t k = 0; k < indices.size(); ++k) vertices.row(k) = points.row(indices[k]);
  return vertices;
}

coal::Transform3s coal_transform(const sc::Pose& pose) {
  return coal::Transform3s(pose.rotation, pose.translation);
}

struct Pair {
  sc::ConvexPolyhedron a;
  sc::ConvexPolyhedron b;
  sc::Pose pose_a;
  sc::Pose pose_b;
  std::shared_ptr<coal::ConvexBase> coal_a;
  std::shared_ptr<coal::ConvexBase> coal_b;
  coal::Transform3s coal_pose_a;
  coal::Transform3s coal_pose_b;
};

// A pair of random n-vertex polytopes whose exact signed distance is `target` (< 0), by bisection
// on B's translation along a random unit vector (the exact method's certified answer).
std::unique_ptr<Pair> overlapping_pair(int n, double target, std::uint64_t seed) {
  Normals normals(seed);
  sc::ConvexPolyhedron a(sphere_polytope(n, normals));
  sc::ConvexPolyhedron b(sphere_polytope(n, normals));
  sc::Pose pose_a{normals.rotation(), sc::Vector3::Zero()};
  sc::Pose pose_b{normals.rotation(), sc::Vector3::Zero()};
  const sc::Vector3 u = normals.unit();
  sc::QueryOptions exact;
  exact.method = sc::Method::exact;
  const sc::Query query(exact);
  const auto signed_distance = [&](double t) {
    pose_b.translation = t * u;
    return query.signed_distance(a, pose_a, b, pose_b).distance;
  };
  double lo = 0;
  double hi = 2.5;  // bodies within unit balls are apart once their centres are 2 apart
  for (int step = 0; step < 60 && hi - lo > 1e-14; ++step) {
    const double mid = (lo + hi) / 2;
    (signed_distance(mid) < target ? lo : hi) = mid;
  }
  pose_b.translation = hi * u;
  auto pair = std::make_unique<Pair>(Pair{a, b, pose_a, pose_b, to_coal(a), to_coal(b),
                                          coal_transform(pose_a), coal_transform(pose_b)});
  return pair;
}

struct Workload {
  int n;
  std::string overlap;
  double target;
  std::vector<std::unique_ptr<Pair>> pairs;
};

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t m = v.size() / 2;
  return v.size() % 2 ? v[m] : (v[m - 1] + v[m]) / 2;
}

struct Outcome {
  double ours_us = 0;  // sums over the pairs of the per-pair median times
  double coal_us = 0;
  int pairs = 0;
  int certified = 0;
  int coal_outside = 0;       // coal's depth beyond our bounds by more than its tolerance
  double coal_excess = 0;     // the largest amount by which it was beyond them
  double widest_gap = 0;      // our largest (upper - lower)
  double largest_angle = 0;   // degrees between our normal and coal's
  double iterations = 0;      // our mean iterations (the search's and the expansion's)
  double coal_iterations = 0;  // coal's mean iterations (its GJK's and its EPA's)
};

// Which contenders run: both unless `--only` names one.
struct Contenders {
  bool ours = true;
  bool coal = true;
};

Outcome measure(const Workload& w, int repeats, Contenders run) {
  const sc::Query ours;  // the defaults: method dual, tolerance 1e-9
  coal::GJKSolver solver;
  Outcome out;
  for (const auto& p : w.pairs) {
    sc::DistanceResult answer;
    double coal_distance = 0;
    coal::Vec3s p1, p2, coal_normal;
    std::vector<double> ours_times, coal_times;
    for (int r = 0; r < repeats; ++r) {
      auto start = std::chrono::steady_clock::now();
      if (run.ours) answer = ours.signed_distance(p->a, p->pose_a, p->b, p->pose_b);
      ours_times.push_back(seconds_since(start));
      start = std::chrono::steady_clock::now();
      if (run.coal) {
        coal_distance = solver.shapeDistance(*p->coal_a, p->coal_pose_a, *p->coal_b,
                                             p->coal_pose_b, true, p1, p2, coal_normal);
      }
      coal_times.push_back(seconds_since(start));
    }
    out.ours_us += 1e6 * median(ours_times);
    out.coal_us += 1e6 * median(coal_times);
    ++out.pairs;
    out.certified += answer.certified;
    out.iterations += static_cast<double>(answer.iterations) / w.pairs.size();
    if (run.coal) {
      out.coal_iterations +=
          static_cast<double>(solver.gjk.getNumIterations() + solver.epa.getNumIterations()) /
          w.pairs.size();
    }
    const double excess =
        std::max(answer.lower_bound - coal_distance, coal_distance - answer.distance);
    if (excess > kCoalTolerance) ++out.coal_outside;
    out.coal_excess = std::max(out.coal_excess, excess);
    out.widest_gap = std::max(out.widest_gap, answer.distance - answer.lower_bound);
    const double cosine = std::clamp(answer.direction.dot(coal_normal), -1.0, 1.0);
    out.largest_angle = std::max(out.largest_angle, std::acos(cosine) * 180 / M_PI);
  }
  return out;
}

std::vector<int> parse_sizes(const char* text) {
  std::vector<int> sizes;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) sizes.push_back(std::stoi(item));
  return sizes;
}

}  // namespace

int main(int argc, char** argv) {
  bool quick = false;
  int repeats = 0;
  std::string json;
  Contenders run;
  std::vector<int> sizes = {4, 8, 16, 32, 64, 128, 256, 512, 1024, 2048, 4096};
  for (int k = 1; k < argc; ++k) {
    if (!std::strcmp(argv[k], "--quick")) {
      quick = true;
    } else if (!std::strcmp(argv[k], "--repeats") && k + 1 < argc) {
      repeats = std::atoi(argv[++k]);
    } else if (!std::strcmp(argv[k], "--sizes") && k + 1 < argc) {
      sizes = parse_sizes(argv[++k]);
    } else if (!std::strcmp(argv[k], "--only") && k + 1 < argc) {
      const std::string only = argv[++k];
      run.ours = only == "ours";
      run.coal = only == "coal";
    } else if (!std::strcmp(argv[k], "--json") && k + 1 < argc) {
      json = argv[++k];
    } else {
      std::fprintf(stderr, "usage: %s [--quick] [--repeats K] [--sizes 8,64] [--json FILE] [--only ours|coal]\n",
                   argv[0]);
      leave(2);
    }
  }
  if (quick && sizes.size() == 11) sizes = {4, 8, 64, 512, 4096};
  const int pairs = quick ? 5 : 20;
  if (repeats <= 0) repeats = quick ? 11 : 31;

  std::vector<Workload> workloads;
  for (int n : sizes) {
    for (const auto& [name, target] : {std::pair{"1e-2", -1e-2}, std::pair{"0.6", -0.6}}) {
      Workload w{n, name, target, {}};
      for (int seed = 0; seed < pairs; ++seed) {
        w.pairs.push_back(overlapping_pair(n, target, 1000 * n + seed));
      }
      workloads.push_back(std::move(w));
    }
  }
  std::ostringstream rows;
  std::printf("%6s %8s %10s %10s %7s %10s %12s %11s %10s %6s %10s\n", "n", "overlap", "ours_us",
              "coal_us", "ratio", "certified", "coal_outside", "coal_excess", "angle_deg", "iters",
              "coal_iters");
  for (const Workload& w : workloads) {
    const Outcome o = measure(w, repeats, run);
    const double ratio = o.ours_us / o.coal_us;
    std::printf("%6d %8s %10.2f %10.2f %7.2f %7d/%-2d %12d %11.2e %10.2e %6.1f %10.1f\n", w.n,
                w.overlap.c_str(), o.ours_us / o.pairs, o.coal_us / o.pairs, ratio, o.certified,
                o.pairs, o.coal_outside, o.coal_excess, o.largest_angle, o.iterations,
                o.coal_iterations);
    std::fflush(stdout);
    rows << (rows.tellp() > 0 ? ",\n" : "") << "{\"n\": " << w.n << ", \"overlap\": \""
         << w.overlap << "\", \"pairs\": " << o.pairs << ", \"ours_us\": " << o.ours_us / o.pairs
         << ", \"coal_us\": " << o.coal_us / o.pairs << ", \"ratio\": " << ratio
         << ", \"certified\": " << o.certified << ", \"coal_outside\": " << o.coal_outside
         << ", \"coal_excess\": " << o.coal_excess << ", \"widest_gap\": " << o.widest_gap
         << ", \"largest_angle_deg\": " << o.largest_angle
         << ", \"mean_iterations\": " << o.iterations
         << ", \"coal_mean_iterations\": " << o.coal_iterations << "}";
  }
  if (!json.empty()) {
    std::ofstream out(json);
    out << "{\"repeats\": " << repeats << ", \"rows\": [\n" << rows.str() << "\n]}\n";
  }
  leave(0);
}
