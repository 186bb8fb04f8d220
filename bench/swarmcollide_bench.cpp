// swarmcollide-bench: every method side by side with FCL and libccd, on the paper's tetrahedra
// and on random convex polytopes at several proximities. Results: bench/RESULTS.md.
#include <benchmark/benchmark.h>
#include <ccd/ccd.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/distance.h>
#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "normals.hpp"
#include "random_pairs.hpp"
#include "swarmcollide/queries/methods.hpp"
#include "swarmcollide/queries/query.hpp"

namespace sc = swarmcollide;

namespace {

// A separated pair counts as solved when the reported distance is within this of the reference.
constexpr double kAccuracy = 1e-6;
// Pairs per random workload in a full run; every seeded row prepares one query per pair.
constexpr int kPairsPerWorkload = 20;
// The GJK that swarmcollide's "fcl" method runs is FCL's own (GST_INDEP's implementation), so the
// direct FCL distance rows call that one too.
constexpr fcl::GJKSolverType kFclOwnGjk = fcl::GST_INDEP;

// What libccd's callbacks see: a body, shifted like the FCL shapes.
struct CcdShape {
  const sc::ConvexPolyhedron* body;
  sc::Vector3 origin;
  sc::Vector3 centre;
};

void ccd_support(const void* object, const ccd_vec3_t* direction, ccd_vec3_t* out) {
  const auto* shape = static_cast<const CcdShape*>(object);
  const sc::Vector3 d(direction->v[0], direction->v[1], direction->v[2]);
  const sc::Vector3 p = shape->body->support(d) - shape->origin;
  for (int k = 0; k < 3; ++k) out->v[k] = p(k);
}

void ccd_centre(const void* object, ccd_vec3_t* out) {
  const auto* shape = static_cast<const CcdShape*>(object);
  for (int k = 0; k < 3; ++k) out->v[k] = shape->centre(k);
}

struct Pair {
  sc::ConvexPolyhedron a;
  sc::ConvexPolyhedron b;
  sc::DistanceResult reference;
  sc::Vector3 origin;
  std::shared_ptr<fcl::Convexd> fcl_a;
  std::shared_ptr<fcl::Convexd> fcl_b;
  CcdShape ccd_a;
  CcdShape ccd_b;
};

std::unique_ptr<Pair> build_pair(sc::VertexMatrix a_points, sc::VertexMatrix b_points) {
  sc::ConvexPolyhedron a(std::move(a_points));
  sc::ConvexPolyhedron b(std::move(b_points));
  const sc::Aabb box = a.aabb();
  const sc::Vector3 origin = (box.min + box.max) / 2;
  sc::QueryOptions exact;
  exact.method = sc::Method::exact;
  sc::DistanceResult reference = sc::Query(exact).distance(a, b);
  auto pair = std::unique_ptr<Pair>(
      new Pair{a, b, reference, origin, to_fcl(a, origin), to_fcl(b, origin), {}, {}});
  pair->ccd_a = {&pair->a, origin, pair->a.vertices().colwise().mean().transpose() - origin};
  pair->ccd_b = {&pair->b, origin, pair->b.vertices().colwise().mean().transpose() - origin};
  return pair;
}

// Two random n-vertex polytopes at signed distance `target` (random_pairs.hpp).
std::unique_ptr<Pair> random_pair(int n, double target, std::uint64_t seed) {
  auto [a_points, b_points] = random_pair_points(n, target, seed);
  return build_pair(std::move(a_points), std::move(b_points));
}

struct Workload {
  std::string name;
  int n = 0;              // vertices per body (0: the paper's pairs)
  std::string proximity;  // "apart", "gap 1e-2", "overlap 1e-3", or the paper pair's name
  double target = 0;      // intended signed distance
  std::vector<std::unique_ptr<Pair>> pairs;
};

enum class Kind {
  distance,
  fcl_distance,
  sc_collide,
  fcl_collide,
  fcl_collide_direct,
  sc_signed,
  fcl_signed_direct,
  ccd_gjk
};

struct Row {
  std::string name;
  Kind kind;
  sc::QueryOptions options;
  bool iterative;       // swarm and penalty: limited pairs at the largest size
  const char* library;  // whose code answers
  // One query per pair index, seeded with it, built before timing as a user keeps a Query.
  std::vector<sc::Query> seeded = {};
};

sc::QueryOptions using_method(sc::Method method) {
  sc::QueryOptions options;
  options.method = method;
  return options;
}

std::vector<sc::Query> seeded_queries(sc::QueryOptions options) {
  std::vector<sc::Query> queries;
  for (int seed = 0; seed < kPairsPerWorkload; ++seed) {
    options.seed = static_cast<std::uint64_t>(seed);
    queries.emplace_back(options);
  }
  return queries;
}

std::vector<Row> make_rows() {
  std::vector<Row> rows;
  for (auto method : {sc::Method::ipso, sc::Method::pso}) {
    for (auto handling :
         {sc::ConstraintHandling::projection, sc::ConstraintHandling::feasibility}) {
      sc::QueryOptions o = using_method(method);
      o.swarm.constraint_handling = handling;
      const std::string suffix =
          handling == sc::ConstraintHandling::projection ? "projection" : "feasibility";
      rows.push_back({std::string(sc::method_name(method)) + " " + suffix, Kind::distance, o, true,
                      "swarmcollide"});
    }
  }
  for (sc::Method method :
       {sc::Method::penalty, sc::Method::dual, sc::Method::exact, sc::Method::fcl}) {
    rows.push_back({sc::method_name(method), Kind::distance, using_method(method),
                    method == sc::Method::penalty, "swarmcollide"});
  }
  // FCL's own distance on prebuilt shapes, as an FCL user calls it: the cost of the query alone.
  rows.push_back({"FCL distance direct", Kind::fcl_distance, {}, false, "FCL"});
  // The fcl method's collide and signed distance beside the FCL calls they wrap (GST_INDEP's GJK;
  // for an overlapping pair's signed distance FCL runs its EPA, the method the library's own).
  rows.push_back({"collide fcl", Kind::sc_collide, using_method(sc::Method::fcl), false,
                  "swarmcollide"});
  rows.push_back({"FCL collide direct", Kind::fcl_collide_direct, {}, false, "FCL"});
  rows.push_back({"signed fcl", Kind::sc_signed, using_method(sc::Method::fcl), false,
                  "swarmcollide"});
  rows.push_back({"FCL signed distance direct", Kind::fcl_signed_direct, {}, false, "FCL"});
  rows.push_back({"collide libccd", Kind::sc_collide, using_method(sc::Method::libccd), false,
                  "swarmcollide"});
  rows.push_back({"FCL collide", Kind::fcl_collide, {}, false, "FCL"});
  rows.push_back({"libccd GJK intersect", Kind::ccd_gjk, {}, false, "libccd"});
  for (Row& row : rows) {
    if (row.kind == Kind::distance || row.kind == Kind::sc_collide ||
        row.kind == Kind::sc_signed) {
      row.seeded = seeded_queries(row.options);
    }
  }
  return rows;
}

ccd_t ccd_settings() {
  ccd_t ccd;
  CCD_INIT(&ccd);
  ccd.support1 = ccd_support;
  ccd.support2 = ccd_support;
  ccd.center1 = ccd_centre;
  ccd.center2 = ccd_centre;
  ccd.max_iterations = 1000;
  return ccd;
}

// One query of a row on pair `index` of its workload (seeded with the index); returns the verdict
// and, for distance rows, the result.
bool answer(const Row& row, const Pair& p, std::size_t index, sc::DistanceResult* result) {
  switch (row.kind) {
    case Kind::distance:
      *result = row.seeded[index].distance(p.a, p.b);
      return result->colliding;
    case Kind::fcl_distance: {
      // FCL answers -1 for touching and overlapping pairs; the bodies are of unit size, so the
      // library's default relative tolerance is also the contact threshold here.
      const double d =
          fcl_distance_raw(*p.fcl_a, *p.fcl_b, sc::Vector3::Zero(), false, kFclOwnGjk).min_distance;
      result->distance = std::max(d, 0.0);
      result->colliding = d <= sc::kDefaultTolerance;
      return result->colliding;
    }
    case Kind::sc_collide:
      return row.seeded[index].collide(p.a, p.b);
    case Kind::sc_signed:
      *result = row.seeded[index].signed_distance(p.a, p.b);
      return result->colliding;
    case Kind::fcl_signed_direct: {
      const double d =
          fcl_distance_raw(*p.fcl_a, *p.fcl_b, sc::Vector3::Zero(), true, kFclOwnGjk).min_distance;
      result->distance = d;
      result->colliding = d <= sc::kDefaultTolerance;
      return result->colliding;
    }
    case Kind::fcl_collide:
    case Kind::fcl_collide_direct: {
      // The default request: GST_LIBCCD, one contact, no contact data; "direct" GST_INDEP.
      fcl::CollisionRequestd request;
      if (row.kind == Kind::fcl_collide_direct) request.gjk_solver_type = kFclOwnGjk;
      fcl::CollisionResultd out;
      fcl::collide(p.fcl_a.get(), fcl::Transform3d::Identity(), p.fcl_b.get(),
                   fcl::Transform3d::Identity(), request, out);
      return out.isCollision();
    }
    case Kind::ccd_gjk: {
      static const ccd_t ccd = ccd_settings();
      return ccdGJKIntersect(&p.ccd_a, &p.ccd_b, &ccd) != 0;
    }
  }
  return false;
}

// What a direct FCL user gets for this pair, probed in a child process because some of FCL's
// paths abort: 0 fine, 1 a wrong answer, -1 the query aborted (killed by a signal).
int probe_raw_fcl(const Pair& p) {
  std::fflush(nullptr);
  const pid_t pid = fork();
  if (pid == 0) {
    const int null = open("/dev/null", O_WRONLY);
    dup2(null, STDOUT_FILENO);
    dup2(null, STDERR_FILENO);
    const sc::Vector3 zero = sc::Vector3::Zero();
    const bool colliding = p.reference.colliding;
    // Unsigned distance: FCL documents -1 for overlapping pairs, so only separated ones count.
    const double d = fcl_distance_raw(*p.fcl_a, *p.fcl_b, zero, false, kFclOwnGjk).min_distance;
    int code = 0;
    if (!colliding && !(std::abs(d - p.reference.distance) <= kAccuracy)) code = 1;
    // Signed distance: for overlapping pairs it must not be positive.
    const double s = fcl_distance_raw(*p.fcl_a, *p.fcl_b, zero, true, kFclOwnGjk).min_distance;
    if (colliding && !(s <= kAccuracy)) code = 1;
    if (!colliding && !(std::abs(s - p.reference.distance) <= kAccuracy)) code = 1;
    _exit(code);
  }
  int status = 0;
  waitpid(pid, &status, 0);
  if (WIFSIGNALED(status)) return -1;
  return WEXITSTATUS(status);
}

// Accuracy of a row on a workload, from one untimed pass (the timed passes repeat the same
// seeded queries).
struct Accuracy {
  int pairs = 0;
  int of_pairs = 0;
  bool has_distance = false;
  double iterations = 0, evaluations = 0;  // means
  double error_max = 0, error_median = 0;  // |distance - reference|
  int separated = 0, within = 0;           // separated pairs, and those within kAccuracy
  int wrong_verdicts = 0, certified = 0;
  int raw_wrong = -1, raw_aborts = -1;  // direct FCL calls (fcl rows only)
  double seconds = 0;                   // wall time of the untimed pass, for the schedule
};

int pairs_for(const Row& row, const Workload& w, bool quick) {
  const int all = static_cast<int>(w.pairs.size());
  if (row.iterative && w.n >= 4096) return std::min(all, quick ? 1 : 3);
  return all;
}

Accuracy measure(const Row& row, const Workload& w, bool quick) {
  const auto start = std::chrono::steady_clock::now();
  Accuracy acc;
  acc.of_pairs = static_cast<int>(w.pairs.size());
  acc.pairs = pairs_for(row, w, quick);
  acc.has_distance = row.kind == Kind::distance || row.kind == Kind::fcl_distance ||
                     row.kind == Kind::sc_signed || row.kind == Kind::fcl_signed_direct;
  std::vector<double> errors;
  for (int i = 0; i < acc.pairs; ++i) {
    const Pair& p = *w.pairs[i];
    sc::DistanceResult r;
    const bool verdict = answer(row, p, static_cast<std::size_t>(i), &r);
    if (verdict != p.reference.colliding) ++acc.wrong_verdicts;
    if (!acc.has_distance) continue;
    acc.iterations += r.iterations;
    acc.evaluations += static_cast<double>(r.evaluations);
    if (r.certified) ++acc.certified;
    // Signed rows are compared on their distance: their depths are not the reference's.
    const double error = std::abs(std::max(r.distance, 0.0) - p.reference.distance);
    errors.push_back(error);
    if (!p.reference.colliding) {
      ++acc.separated;
      if (error <= kAccuracy) ++acc.within;
    }
  }
  if (acc.has_distance && acc.pairs > 0) {
    acc.iterations /= acc.pairs;
    acc.evaluations /= acc.pairs;
    std::sort(errors.begin(), errors.end());
    acc.error_max = errors.back();
    acc.error_median = errors[errors.size() / 2];
  }
  if (row.kind == Kind::distance && row.options.method == sc::Method::fcl) {
    acc.raw_wrong = acc.raw_aborts = 0;
    for (int i = 0; i < acc.pairs; ++i) {
      const int probe = probe_raw_fcl(*w.pairs[i]);
      if (probe == -1) ++acc.raw_aborts;
      if (probe == 1) ++acc.raw_wrong;
    }
  }
  acc.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return acc;
}

void run(benchmark::State& state, const Row* row, const Workload* w, Accuracy acc) {
  const int pairs = acc.pairs;
  sc::DistanceResult r;
  for (auto _ : state) {
    for (int i = 0; i < pairs; ++i) {
      const bool verdict = answer(*row, *w->pairs[i], static_cast<std::size_t>(i), &r);
      benchmark::DoNotOptimize(verdict);
      benchmark::DoNotOptimize(r.distance);
    }
  }
  // One benchmark iteration answers every pair once: real_time / pairs is the time per query.
  state.counters["pairs"] = pairs;
  state.counters["of_pairs"] = acc.of_pairs;
  state.counters["has_distance"] = acc.has_distance;
  state.counters["iterations_mean"] = acc.iterations;
  state.counters["evaluations_mean"] = acc.evaluations;
  state.counters["error_max"] = acc.error_max;
  state.counters["error_median"] = acc.error_median;
  state.counters["separated"] = acc.separated;
  state.counters["within_1e-6"] = acc.within;
  state.counters["wrong_verdicts"] = acc.wrong_verdicts;
  state.counters["certified"] = acc.certified;
  state.counters["raw_fcl_wrong"] = acc.raw_wrong;
  state.counters["raw_fcl_aborts"] = acc.raw_aborts;
  if (pairs < acc.of_pairs) {
    state.SetLabel("only " + std::to_string(pairs) + " of " + std::to_string(acc.of_pairs) +
                   " pairs: too slow for the full set");
  }
}

sc::VertexMatrix tetrahedron(std::initializer_list<double> xyz) {
  sc::VertexMatrix v(4, 3);
  std::copy(xyz.begin(), xyz.end(), v.data());
  return v;
}

std::vector<Workload> make_workloads(bool quick, const std::vector<int>& only_sizes) {
  std::vector<Workload> workloads;
  const sc::VertexMatrix a = tetrahedron({0, 1, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0});
  Workload touching{"paper touching", 0, "touching", 0, {}};
  touching.pairs.push_back(build_pair(a, tetrahedron({1, 0, 0, 2, -2, 0, 0, -2, 2, 0, -2, 0})));
  Workload separate{"paper separate", 0, "separate", 1, {}};
  separate.pairs.push_back(build_pair(a, tetrahedron({1, -1, 0, 2, -2, 0, 0, -2, 2, 0, -2, 0})));
  workloads.push_back(std::move(touching));
  workloads.push_back(std::move(separate));

  const std::vector<BenchProximity>& proximities = bench_proximities();
  // --quick's proximities (apart, gap 1e-3, overlap 1e-2), by their index in the full list.
  const std::vector<std::size_t> quick_proximities = {0, 3, 7};
  std::vector<int> sizes =
      quick ? std::vector<int>{8, 64} : std::vector<int>{4, 8, 16, 64, 512, 4096};
  if (!only_sizes.empty()) sizes = only_sizes;
  const int pairs = quick ? 5 : kPairsPerWorkload;
  for (int n : sizes) {
    for (std::size_t k = 0; k < proximities.size(); ++k) {
      if (quick && std::find(quick_proximities.begin(), quick_proximities.end(), k) ==
                       quick_proximities.end()) {
        continue;
      }
      std::fprintf(stderr, "\rgenerating n=%d %-14s", n, proximities[k].name);
      Workload w{"n=" + std::to_string(n) + " " + proximities[k].name,
                 n,
                 proximities[k].name,
                 proximities[k].target,
                 {}};
      for (int i = 0; i < pairs; ++i) {
        // The seed depends on the size, the proximity's index in the full list and the pair's
        // index, not on --quick (whose gap 1e-3 and overlap 1e-2 once took the seeds of the
        // full list's second and third proximities).
        const std::uint64_t seed = random_pair_seed(n, static_cast<int>(k), i);
        w.pairs.push_back(random_pair(n, proximities[k].target, seed));
      }
      workloads.push_back(std::move(w));
    }
  }
  std::fprintf(stderr, "\n");
  return workloads;
}

std::string cpu_model() {
  std::ifstream cpuinfo("/proc/cpuinfo");
  std::string line;
  while (std::getline(cpuinfo, line)) {
    if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
  }
  return "unknown";
}

}  // namespace

int main(int argc, char** argv) {
  bool quick = false;
  std::string json;
  std::vector<int> sizes;
  std::vector<std::string> only_rows;
  std::vector<char*> args = {argv[0]};
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--quick") {
      quick = true;
    } else if (arg == "--json" && i + 1 < argc) {
      json = argv[++i];
    } else if (arg == "--sizes" && i + 1 < argc) {
      std::string list = argv[++i];
      for (std::size_t pos = 0; pos < list.size();) {
        const std::size_t comma = std::min(list.find(',', pos), list.size());
        sizes.push_back(std::stoi(list.substr(pos, comma - pos)));
        pos = comma + 1;
      }
    } else if (arg == "--rows" && i + 1 < argc) {
      std::string list = argv[++i];
      for (std::size_t pos = 0; pos < list.size();) {
        const std::size_t comma = std::min(list.find(',', pos), list.size());
        only_rows.push_back(list.substr(pos, comma - pos));
        pos = comma + 1;
      }
    } else if (arg == "--help" || arg == "-h") {
      std::cout << "usage: swarmcollide-bench [--quick] [--json FILE] [--benchmark_* flags]\n"
                   "  --quick      a reduced set (paper pairs, n = 8, 64, three proximities)\n"
                   "  --json FILE  Google Benchmark JSON with the accuracy counters\n"
                   "  --sizes LIST only these vertex counts, e.g. 8,64 (the paper pairs always)\n"
                   "  --rows LIST  only these rows, e.g. 'fcl,FCL distance direct'\n";
      return 0;
    } else {
      args.push_back(argv[i]);
    }
  }
  std::string out_flag = "--benchmark_out=" + json;
  std::string format_flag = "--benchmark_out_format=json";
  if (!json.empty()) {
    args.push_back(out_flag.data());
    args.push_back(format_flag.data());
  }
  int bench_argc = static_cast<int>(args.size());
  benchmark::Initialize(&bench_argc, args.data());
  if (benchmark::ReportUnrecognizedArguments(bench_argc, args.data())) return 1;

  benchmark::AddCustomContext("cpu_model", cpu_model());
  benchmark::AddCustomContext("compiler", SWARMCOLLIDE_BENCH_COMPILER);
  benchmark::AddCustomContext("mode", quick ? "quick" : "full");
  benchmark::AddCustomContext("accuracy_threshold", "1e-6");
  benchmark::AddCustomContext("reference", "swarmcollide::Query, method exact (certified)");

  static const std::vector<Row> rows = make_rows();
  static const std::vector<Workload> workloads = make_workloads(quick, sizes);
  // Many short repetitions: their median resists the odd descheduled one on a shared machine.
  const int repetitions = quick ? 3 : 9;
  const double min_time = quick ? 0.01 : 0.03;
  std::size_t done = 0;
  for (const Workload& w : workloads) {
    ++done;
    for (const Row& row : rows) {
      if (!only_rows.empty() &&
          std::find(only_rows.begin(), only_rows.end(), row.name) == only_rows.end()) {
        continue;
      }
      // FCL's signed distance asserts on some touching and overlapping pairs (its EPA finds no
      // contact): it is timed where it answers, on separated pairs.
      if (row.kind == Kind::fcl_signed_direct && !(w.target > 0)) continue;
      const Accuracy acc = measure(row, w, quick);
      std::fprintf(stderr, "\raccuracy pass %zu/%zu %-24s %-22s %8.3f s", done, workloads.size(),
                   w.name.c_str(), row.name.c_str(), acc.seconds);
      // A row whose single pass over the pairs takes over a second gets 3 repetitions of one
      // pass each: every repetition still times the whole pair set.
      const bool slow = acc.seconds > 1.0;
      benchmark::RegisterBenchmark((row.name + "|" + w.name).c_str(), run, &row, &w, acc)
          ->Repetitions(slow ? 3 : repetitions)
          ->ReportAggregatesOnly(true)
          ->MinTime(min_time)
          ->MinWarmUpTime(min_time / 2)
          ->UseRealTime()
          ->Unit(benchmark::kMicrosecond)
          ->ComputeStatistics(
              "min",
              [](const std::vector<double>& v) { return *std::min_element(v.begin(), v.end()); })
          ->ComputeStatistics("max", [](const std::vector<double>& v) {
            return *std::max_element(v.begin(), v.end());
          });
    }
  }
  std::fprintf(stderr, "\n");
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
