// Can this machine answer twice as many rows on 2 threads as on 1, and do our batches? Pure loops
// (a dependent integer chain, independent floating-point chains, a pass over an L2-sized and a
// memory-sized array, the memory traffic of cheap batch rows with their threads' rows changing
// between runs or not: row_pattern) and the batches over poses (one 8-vertex body against another
// at m poses, as bench/pose_batch.py asks them from Python) each run on 1 thread and on 2, the
// order alternating between rounds. A loop's 2 threads each do half its work; a batch runs either as one
// call with `threads=2` ("pool") or as two calls with `threads=1` on two std::threads, each on
// half the poses into its own result ("halves"): when the halves scale and the pool does not, the
// pool's own sharing is to blame; when neither does, the machine is. Prints, per case, the median
// over rounds of wall(1) / wall(2), the CPU time over the wall time of the 2-thread runs, the CPU
// time of a unit of work on 2 threads over that on 1 (1.00: each thread runs as fast beside the
// other as alone), the time the hypervisor stole (/proc/stat) per 2-thread run, and the minor page
// faults and the wall time of a 1-thread and of a 2-thread run.
//
//   swarmcollide-thread-scaling [ROWS] [ROUNDS] [FILTER]
//
// FILTER, when given, keeps the cases whose names contain it. On a shared machine run it as
// `chrt -f 1 swarmcollide-thread-scaling ...` (a real-time priority, for a minute): there the
// threads run as on a quiet machine, where under the default scheduler a thread started for a
// batch of a few milliseconds waits behind other sessions' work and two threads scale by 1.0x.
//
// With `wake [ROUNDS]` it times waking a thread asleep on a condition variable after the caller
// slept 0, 1, 2, 5 and 30 ms: what `notify_one` costs the caller, and how long the woken thread
// takes to start (what a batch's other threads cost before their first row; run_batch's rule).
//
// With `count KIND STATE ROWS [VERTICES [THREADS]]` (KIND collide, distance or signed_distance;
// STATE apart or overlapping; VERTICES 8 unless given, THREADS 1) it answers that batch once to
// warm it, then once more with callgrind's collection on: run under `valgrind --tool=callgrind
// --collect-atstart=no`, the instructions of the second call over ROWS are the instructions per
// row. It prints a hash of every field of every row, which a change that keeps the answers must
// keep bit for bit (on any number of threads).
#include <sys/resource.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include <valgrind/callgrind.h>

#include "normals.hpp"
#include "swarmcollide/queries/batch.hpp"

namespace sc = swarmcollide;

namespace {

double now() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

double process_cpu() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// The steal time of every CPU so far, in seconds (the 8th field of /proc/stat's "cpu" line).
double stolen() {
  std::ifstream stat("/proc/stat");
  std::string cpu;
  long long fields[8] = {};
  stat >> cpu;
  for (long long& f : fields) stat >> f;
  return static_cast<double>(fields[7]) / static_cast<double>(sysconf(_SC_CLK_TCK));
}

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  return values[values.size() / 2];
}

// Work split into `parts`: `run(part, parts)` does part `part` of it.
using Work = std::function<void(int part, int parts)>;

struct Timing {
  double wall;
  double cpu;
  double steal;
  double faults;
};

// The process's minor page faults so far.
double faults() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_minflt);
}

// `work` on `threads` std::threads (the calling thread one of them), or as one call when `pooled`
// (the work starts its own threads).
Timing timed(const Work& work, int threads, bool pooled) {
  const double steal = stolen();
  const double faulted = faults();
  const double cpu = process_cpu();
  const double wall = now();
  if (pooled) {
    work(0, threads);
  } else {
    std::vector<std::thread> pool;
    for (int t = 1; t < threads; ++t) pool.emplace_back(work, t, threads);
    work(0, threads);
    for (auto& thread : pool) thread.join();
  }
  const double elapsed = now() - wall;
  const double used = process_cpu() - cpu;
  return {elapsed, used, stolen() - steal, faults() - faulted};
}

volatile std::uint64_t sink_int;
volatile double sink_double;

// Integer multiplications, each waiting for the last: latency-bound, no memory.
Work chain(std::uint64_t steps) {
  return [steps](int, int parts) {
    std::uint64_t x = 1;
    for (std::uint64_t i = 0; i < steps / static_cast<std::uint64_t>(parts); ++i) {
      x = x * 6364136223846793005ULL + 1442695040888963407ULL;
    }
    sink_int = x;
  };
}

// Eight independent multiply-add chains: throughput-bound on the floating-point units.
Work fma8(std::uint64_t steps) {
  return [steps](int, int parts) {
    double x[8] = {1, 2, 3, 4, 5, 6, 7, 8};
    for (std::uint64_t i = 0; i < steps / static_cast<std::uint64_t>(parts); ++i) {
      for (double& v : x) v = v * 0.999999 + 1e-7;
    }
    double s = 0;
    for (double v : x) s += v;
    sink_double = s;
  };
}

// Passes over a thread's own array of `bytes`: L2 (256 KiB) or memory (64 MiB).
Work sweep(std::size_t bytes, std::uint64_t total_bytes) {
  auto arrays = std::make_shared<std::vector<std::vector<std::uint64_t>>>(
      2, std::vector<std::uint64_t>(bytes / 8, 1));
  return [arrays, bytes, total_bytes](int part, int parts) {
    const std::vector<std::uint64_t>& a = (*arrays)[static_cast<std::size_t>(part)];
    std::uint64_t s = 0;
    const std::uint64_t passes = total_bytes / bytes / static_cast<std::uint64_t>(parts);
    for (std::uint64_t p = 0; p < passes; ++p) {
      for (std::uint64_t v : a) s += v;
    }
    sink_int = s;
  };
}

// The memory traffic of batch rows that the ball screens settle, without the library: each row
// reads 12 doubles (a pose) and does a few dozen dependent multiply-adds, then writes 103 bytes
// into 11 arrays (a BatchResult's row), both blocks kept between runs as a reused result is.
// `shared`: the threads take guided chunks from one counter (so a row's thread changes from run
// to run, as the batches' rows did before they were split into a range per thread); otherwise
// part p answers the p-th range of the rows in every run. When the shared counter costs more CPU
// than the ranges, moving cache lines between the cores is expensive in the machine's current
// state (at times it cost 18% here, at others nothing).
Work row_pattern(std::size_t count, bool shared) {
  struct State {
    std::vector<double> poses;
    std::vector<double> doubles;  // distance, lower bound, three 3-vectors
    std::vector<int> ints;        // iterations, part_a, part_b
    std::vector<unsigned char> flags;
    std::atomic<std::size_t> next{0};
    std::atomic<int> finished{0};
  };
  auto state = std::make_shared<State>();
  state->poses.assign(12 * count, 0.5);
  state->doubles.assign(11 * count, 0);
  state->ints.assign(3 * count, 0);
  state->flags.assign(3 * count, 0);
  return [state, count, shared](int part, int parts) {
    State& s = *state;
    const auto answer = [&s, count](std::size_t begin, std::size_t end) {
      for (std::size_t i = begin; i < end; ++i) {
        const double* pose = &s.poses[12 * i];
        double x = pose[0] + pose[9];
        double y = pose[4] + pose[10];
        double z = pose[8] + pose[11];
        for (int k = 0; k < 15; ++k) {
          x = x * 0.999 + y * 1e-3;
          y = y * 0.998 + z * 1e-3;
          z = z * 0.997 + x * 1e-3;
        }
        s.doubles[i] = x;
        s.doubles[count + i] = y;
        for (int k = 0; k < 9; ++k) s.doubles[(2 + k / 3) * count + 3 * i + k % 3] = z + k;
        for (int k = 0; k < 3; ++k) s.ints[k * count + i] = k;
        for (int k = 0; k < 3; ++k) s.flags[k * count + i] = x > 0;
      }
    };
    if (!shared) {
      const auto p = static_cast<std::size_t>(part);
      const auto n = static_cast<std::size_t>(parts);
      return answer(count * p / n, count * (p + 1) / n);
    }
    for (std::size_t start = s.next.load();;) {
      if (start >= count) break;
      const std::size_t left = count - start;
      const std::size_t share = left / (4 * static_cast<std::size_t>(parts));
      const std::size_t rows =
          share >= 64 ? (share + 63) / 64 * 64 : std::max<std::size_t>(share, 8);
      const std::size_t end = start + std::min(rows, left);
      if (!s.next.compare_exchange_weak(start, end)) continue;
      answer(start, end);
      start = s.next.load();
    }
    // The last part to finish resets the counter for the next run (which starts after every
    // part of this one has been joined).
    if (s.finished.fetch_add(1) + 1 == parts) {
      s.next.store(0);
      s.finished.store(0);
    }
  };
}

struct PoseRows {
  std::vector<double> rotations;
  std::vector<double> translations;
  std::size_t count;

  sc::PoseArray part(std::size_t first, std::size_t rows) const {
    sc::PoseArray array;
    array.rotations = rotations.data() + 9 * first;
    array.translations = translations.data() + 3 * first;
    array.count = rows;
    return array;
  }
};

PoseRows poses(std::size_t count, double length, std::uint64_t seed) {
  Normals normals(seed);
  PoseRows rows{std::vector<double>(9 * count), std::vector<double>(3 * count), count};
  for (std::size_t i = 0; i < count; ++i) {
    const sc::Matrix3 r = normals.rotation();
    const sc::Vector3 t = normals.unit() * length;
    for (int j = 0; j < 3; ++j) {
      for (int k = 0; k < 3; ++k) rows.rotations[9 * i + 3 * j + k] = r(j, k);
      rows.translations[3 * i + j] = t(j);
    }
  }
  return rows;
}

sc::ConvexPolyhedron sphere_body(int n, std::uint64_t seed) {
  Normals normals(seed);
  sc::VertexMatrix points(n, 3);
  for (int i = 0; i < n; ++i) points.row(i) = normals.unit().transpose();
  return sc::ConvexPolyhedron(points);
}

using Batch = sc::BatchResult (*)(const sc::BatchBodies<sc::ConvexPolyhedron>&,
                                  const sc::BatchBodies<sc::ConvexPolyhedron>&,
                                  const sc::QueryOptions&, const sc::BatchSettings&,
                                  const sc::BatchPoses&);

// One call with `threads` threads over every row.
Work pool(Batch batch, const sc::ConvexPolyhedron& a, const sc::ConvexPolyhedron& b,
          const PoseRows& rows) {
  return [batch, &a, &b, &rows](int, int parts) {
    sc::BatchSettings settings;
    settings.threads = parts;
    sc::BatchPoses at;
    at.array_b = rows.part(0, rows.count);
    const sc::BatchResult result = batch(a, b, sc::QueryOptions{}, settings, at);
    sink_double = result.distance[0];
  };
}

// Part `part` of the rows by a call with one thread, into its own result.
Work halves(Batch batch, const sc::ConvexPolyhedron& a, const sc::ConvexPolyhedron& b,
            const PoseRows& rows) {
  return [batch, &a, &b, &rows](int part, int parts) {
    const std::size_t share = rows.count / static_cast<std::size_t>(parts);
    sc::BatchSettings settings;
    settings.threads = 1;
    settings.first_index = share * static_cast<std::size_t>(part);
    sc::BatchPoses at;
    at.array_b = rows.part(settings.first_index, share);
    const sc::BatchResult result = batch(a, b, sc::QueryOptions{}, settings, at);
    sink_double = result.distance[0];
  };
}

std::string filter;

void compare(const char* name, const Work& work, bool pooled, int rounds) {
  if (std::string(name).find(filter) == std::string::npos) return;
  work(0, 1);  // warm
  std::vector<double> gains, busy, slowdown, steal, faults_one, faults_two, walls_one, walls_two;
  for (int r = 0; r < rounds; ++r) {
    Timing one{}, two{};
    if (r % 2 == 0) {
      one = timed(work, 1, pooled);
      two = timed(work, 2, pooled);
    } else {
      two = timed(work, 2, pooled);
      one = timed(work, 1, pooled);
    }
    gains.push_back(one.wall / two.wall);
    busy.push_back(two.cpu / two.wall);
    slowdown.push_back(two.cpu / one.cpu);
    steal.push_back(two.steal / two.wall);
    walls_one.push_back(one.wall * 1e6);
    walls_two.push_back(two.wall * 1e6);
    faults_one.push_back(one.faults);
    faults_two.push_back(two.faults);
  }
  std::printf("%-34s 2/1 %.2fx (min %.2f max %.2f)  cpu/wall(2) %.2f  cpu(2)/cpu(1) %.2f  "
              "steal/wall(2) %.2f  faults %.0f / %.0f  wall %.0f / %.0f us\n",
              name, median(gains), *std::min_element(gains.begin(), gains.end()),
              *std::max_element(gains.begin(), gains.end()), median(busy), median(slowdown),
              median(steal), median(faults_one), median(faults_two), median(walls_one),
              median(walls_two));
  std::fflush(stdout);
}

// A hash of the bits of every field of every row of `result` (FNV-1a over their bytes).
std::uint64_t result_hash(const sc::BatchResult& result) {
  std::uint64_t hash = 14695981039346656037ULL;
  const auto mix = [&hash](const void* data, std::size_t bytes) {
    const auto* byte = static_cast<const unsigned char*>(data);
    for (std::size_t k = 0; k < bytes; ++k) hash = (hash ^ byte[k]) * 1099511628211ULL;
  };
  for (std::size_t i = 0; i < result.rows(); ++i) {
    const auto row = static_cast<Eigen::Index>(i);
    const double values[] = {result.distance(row),   result.lower_bound(row),
                             result.point_a(row, 0), result.point_a(row, 1),
                             result.point_a(row, 2), result.point_b(row, 0),
                             result.point_b(row, 1), result.point_b(row, 2),
                             result.direction(row, 0), result.direction(row, 1),
                             result.direction(row, 2)};
    const int counts[] = {result.iterations(row), result.part_a(row), result.part_b(row)};
    const bool flags[] = {result.colliding(row), result.certified(row), result.escalated(row)};
    mix(values, sizeof values);
    mix(counts, sizeof counts);
    mix(flags, sizeof flags);
  }
  return hash;
}

int count_instructions(const std::string& kind, const std::string& state, std::size_t count,
                       int vertices, int threads) {
  const sc::ConvexPolyhedron a = sphere_body(vertices, 1);
  const sc::ConvexPolyhedron b = sphere_body(vertices, 2);
  const PoseRows rows = poses(count, state == "apart" ? 3.0 : 1.8, 3);
  const Batch batch = kind == "collide"    ? Batch{&sc::collide_many}
                      : kind == "distance" ? Batch{&sc::distance_many}
                                           : Batch{&sc::signed_distance_many};
  sc::BatchSettings settings;
  settings.threads = threads;
  sc::BatchPoses at;
  at.array_b = rows.part(0, rows.count);
  batch(a, b, sc::QueryOptions{}, settings, at);
  CALLGRIND_TOGGLE_COLLECT;
  const sc::BatchResult result = batch(a, b, sc::QueryOptions{}, settings, at);
  CALLGRIND_TOGGLE_COLLECT;
  std::printf("%s %s %zu rows, %d vertices, %d threads: hash %016llx\n", kind.c_str(),
              state.c_str(), count, vertices, threads,
              static_cast<unsigned long long>(result_hash(result)));
  return 0;
}

// The `wake` probe: per idle time, the median and range over `rounds` of the caller's notify and
// of the woken thread's start after it.
int wake_latency(int rounds) {
  std::mutex mutex;
  std::condition_variable wake;
  int generation = 0;  // -1: stop
  double woke_at = 0;
  std::atomic<bool> started{false};
  std::thread sleeper([&] {
    int seen = 0;
    std::unique_lock<std::mutex> lock(mutex);
    for (;;) {
      wake.wait(lock, [&] { return generation != seen; });
      if (generation < 0) return;
      seen = generation;
      woke_at = now();
      started.store(true, std::memory_order_release);
    }
  });
  const auto range = [](std::vector<double> us) {
    std::sort(us.begin(), us.end());
    char text[64];
    std::snprintf(text, sizeof text, "%.1f us (%.1f-%.1f)", us[us.size() / 2], us.front(),
                  us.back());
    return std::string(text);
  };
  for (int idle_ms : {0, 1, 2, 5, 30}) {
    std::vector<double> notify, start;
    for (int r = 0; r < rounds; ++r) {
      std::this_thread::sleep_for(std::chrono::milliseconds(idle_ms));
      started.store(false, std::memory_order_relaxed);
      const double asked = now();
      {
        const std::lock_guard<std::mutex> lock(mutex);
        ++generation;
      }
      wake.notify_one();
      notify.push_back((now() - asked) * 1e6);
      while (!started.load(std::memory_order_acquire)) {
      }
      const std::lock_guard<std::mutex> lock(mutex);
      start.push_back((woke_at - asked) * 1e6);
    }
    std::printf("asleep after %2d ms idle: notify %s, start %s\n", idle_ms,
                range(notify).c_str(), range(start).c_str());
  }
  {
    const std::lock_guard<std::mutex> lock(mutex);
    generation = -1;
  }
  wake.notify_one();
  sleeper.join();
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc >= 2 && argc <= 3 && std::string(argv[1]) == "wake") {
    return wake_latency(argc > 2 ? std::atoi(argv[2]) : 40);
  }
  if (argc >= 5 && argc <= 7 && std::string(argv[1]) == "count") {
    return count_instructions(argv[2], argv[3], std::strtoul(argv[4], nullptr, 10),
                              argc > 5 ? std::atoi(argv[5]) : 8, argc > 6 ? std::atoi(argv[6]) : 1);
  }
  const std::size_t count = argc > 1 ? std::strtoul(argv[1], nullptr, 10) : 20000;
  const int rounds = argc > 2 ? std::atoi(argv[2]) : 11;
  if (argc > 3) filter = argv[3];
  std::ifstream load("/proc/loadavg");
  std::string line;
  std::getline(load, line);
  std::printf("rows %zu, rounds %d, load %s\n", count, rounds, line.c_str());
  compare("integer chain", chain(200'000'000), false, rounds);
  compare("8 fma chains", fma8(50'000'000), false, rounds);
  compare("sweep 256 KiB (L2)", sweep(256 << 10, std::uint64_t{8} << 30), false, rounds);
  compare("sweep 64 MiB (memory)", sweep(64 << 20, std::uint64_t{4} << 30), false, rounds);
  compare("row pattern, shared counter", row_pattern(count, true), false, rounds);
  compare("row pattern, a range per thread", row_pattern(count, false), false, rounds);
  const sc::ConvexPolyhedron a = sphere_body(8, 1);
  const sc::ConvexPolyhedron b = sphere_body(8, 2);
  for (const auto& [state, length] : {std::pair<const char*, double>{"apart", 3.0},
                                      std::pair<const char*, double>{"overlapping", 1.8}}) {
    const PoseRows rows = poses(count, length, 3);
    for (const auto& [kind, batch] :
         {std::pair<const char*, Batch>{"collide", &sc::collide_many},
          std::pair<const char*, Batch>{"distance", &sc::distance_many}}) {
      const std::string label = std::string(kind) + " 8v " + state;
      compare((label + " pool").c_str(), pool(batch, a, b, rows), true, rounds);
      compare((label + " halves").c_str(), halves(batch, a, b, rows), false, rounds);
    }
  }
  std::getline(std::ifstream("/proc/loadavg"), line);
  std::printf("load after %s\n", line.c_str());
  return 0;
}
