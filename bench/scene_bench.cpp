// swarmcollide-scene-bench: a Scene's frames (one thread and two) against FCL's
// DynamicAABBTree manager with GJK collide per candidate, on N unit-size 8-vertex hulls with
// random rotations, about 3-4 colliding pairs per body; a cold frame, then warm frames of small
// motion; and pairs within 0.1 against FCL's manager on inflated boxes with fcl::distance.
// Contenders run interleaved, frame by frame, on the same poses. Results: bench/RESULTS.md.
#include <fcl/broadphase/broadphase_dynamic_AABB_tree.h>
#include <fcl/geometry/shape/convex.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/distance.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <iostream>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "normals.hpp"
#include "swarmcollide/scene/scene.hpp"

namespace sc = swarmcollide;

namespace {

// Bodies per unit volume that give about 3.5 colliding pairs per body (measured: see `calibrate`).
constexpr double kDensity = 2.85;
// Small motion: per frame, each body moves by a Gaussian step of this deviation per axis and
// turns by this angle (radians) about its own random axis.
constexpr double kStep = 0.004;
constexpr double kTurn = 0.01;

double now() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// CPU time of the whole process: on a machine shared with other jobs it counts only the time
// this process ran, which wall-clock time does not.
double cpu_now() {
  timespec t;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0 : v[v.size() / 2];
}

// N hulls of 8 points on the sphere of radius 1/2 (every point is a vertex), and the poses of
// `frames` frames: random rotations and positions in a cube, then small motion.
struct Workload {
  int n = 0;
  double side = 0;
  std::vector<sc::ConvexPolyhedron> bodies;
  std::vector<std::vector<sc::Pose>> frames;
};

Workload make_workload(int n, int frames, std::uint64_t seed) {
  Normals normals(seed);
  Workload w;
  w.n = n;
  w.side = std::cbrt(n / kDensity);
  std::vector<sc::Pose> poses(n);
  std::vector<sc::Vector3> velocity(n);
  std::vector<sc::Matrix3> spin(n);
  for (int i = 0; i < n; ++i) {
    sc::VertexMatrix points(8, 3);
    for (int k = 0; k < 8; ++k) points.row(k) = 0.5 * normals.unit().transpose();
    w.bodies.emplace_back(points);
    poses[i].rotation = normals.rotation();
    poses[i].translation =
        sc::Vector3(normals.uniform(), normals.uniform(), normals.uniform()) * w.side;
    velocity[i] = kStep * sc::Vector3(normals.next(), normals.next(), normals.next());
    spin[i] = Eigen::AngleAxisd(kTurn, normals.unit()).toRotationMatrix();
  }
  for (int f = 0; f < frames; ++f) {
    w.frames.push_back(poses);
    for (int i = 0; i < n; ++i) {
      // Re-orthonormalised so that rounding never accumulates past the pose tolerance.
      poses[i].rotation =
          Eigen::Quaterniond(spin[i] * poses[i].rotation).normalized().toRotationMatrix();
      poses[i].translation += velocity[i];
    }
  }
  return w;
}

std::shared_ptr<fcl::Convexd> to_fcl(const sc::ConvexPolyhedron& body) {
  const sc::Hull& hull = body.hull();
  std::vector<int> local(body.size(), -1);
  auto vertices = std::make_shared<std::vector<fcl::Vector3d>>();
  for (int i : hull.vertex_indices) {
    local[i] = static_cast<int>(vertices->size());
    vertices->push_back(body.vertices().row(i).transpose());
  }
  auto faces = std::make_shared<std::vector<int>>();
  for (Eigen::Index f = 0; f < hull.faces.rows(); ++f) {
    faces->insert(faces->end(),
                  {3, local[hull.faces(f, 0)], local[hull.faces(f, 1)], local[hull.faces(f, 2)]});
  }
  return std::make_shared<fcl::Convexd>(vertices, static_cast<int>(hull.faces.rows()), faces);
}

// An FCL object whose box, FCL's own (the box of the bounding sphere for a rotated object), is
// widened by `pad`: how an FCL user gets the pairs within a distance from a manager.
class PaddedObject : public fcl::CollisionObjectd {
 public:
  using fcl::CollisionObjectd::CollisionObjectd;
  void pad(double by) {
    computeAABB();
    aabb.min_.array() -= by;
    aabb.max_.array() += by;
  }
};

struct FrameCount {
  std::size_t candidates = 0;
  std::size_t hits = 0;
};

struct FclNarrow {
  fcl::CollisionRequestd request;
  FrameCount count;
};

bool fcl_collide(fcl::CollisionObjectd* a, fcl::CollisionObjectd* b, void* data) {
  auto* d = static_cast<FclNarrow*>(data);
  ++d->count.candidates;
  fcl::CollisionResultd result;
  fcl::collide(a, b, d->request, result);
  d->count.hits += result.isCollision();
  return false;
}

struct FclWithin {
  fcl::DistanceRequestd request;
  double within = 0;
  FrameCount count;
};

bool fcl_within(fcl::CollisionObjectd* a, fcl::CollisionObjectd* b, void* data) {
  auto* d = static_cast<FclWithin*>(data);
  ++d->count.candidates;
  fcl::DistanceResultd result;
  d->count.hits += fcl::distance(a, b, d->request, result) <= d->within;
  return false;
}

// FCL as its users run it: objects with the bodies' hulls as fcl::Convexd, a DynamicAABBTree
// manager, and fcl::collide (GJK, FCL's default solver) in the manager's callback.
class FclScene {
 public:
  explicit FclScene(const Workload& w) {
    for (const auto& body : w.bodies) {
      objects_.push_back(std::make_unique<PaddedObject>(to_fcl(body)));
    }
  }
  FrameCount cold(const std::vector<sc::Pose>& poses) {
    place(poses);
    manager_ = std::make_unique<fcl::DynamicAABBTreeCollisionManagerd>();
    std::vector<fcl::CollisionObjectd*> base;
    for (auto& o : objects_) base.push_back(o.get());
    manager_->registerObjects(base);
    manager_->setup();
    return collide();
  }
  FrameCount frame(const std::vector<sc::Pose>& poses) {
    place(poses);
    manager_->update();
    return collide();
  }
  // Pairs within `d`: boxes padded by d/2, fcl::distance per candidate.
  FrameCount within(const std::vector<sc::Pose>& poses, double d) {
    place(poses);
    for (auto& o : objects_) o->pad(d / 2);
    auto manager = std::make_unique<fcl::DynamicAABBTreeCollisionManagerd>();
    std::vector<fcl::CollisionObjectd*> base;
    for (auto& o : objects_) base.push_back(o.get());
    manager->registerObjects(base);
    manager->setup();
    FclWithin data;
    data.within = d;
    manager->collide(&data, fcl_within);
    return data.count;
  }

 private:
  void place(const std::vector<sc::Pose>& poses) {
    for (std::size_t i = 0; i < objects_.size(); ++i) {
      objects_[i]->setTransform(poses[i].rotation, poses[i].translation);
      objects_[i]->computeAABB();
    }
  }
  FrameCount collide() {
    FclNarrow data;
    manager_->collide(&data, fcl_collide);
    return data.count;
  }
  std::vector<std::unique_ptr<PaddedObject>> objects_;
  std::unique_ptr<fcl::DynamicAABBTreeCollisionManagerd> manager_;
};

// Each query returns the pairs it found; its stats are read after the timing (stats()), as a
// user who reads them reads them apart from the frame: their cache_bytes walks the pair table.
class OurScene {
 public:
  OurScene(const Workload& w, int threads) : w_(w) { options_.threads = threads; }
  std::size_t cold(const std::vector<sc::Pose>& poses) {
    scene_ = std::make_unique<sc::Scene>(options_);
    ids_ = scene_->add(w_.bodies, poses);
    return query();
  }
  std::size_t frame(const std::vector<sc::Pose>& poses) {
    scene_->set_poses(ids_, poses);
    return query();
  }
  // A fresh scene, kept for its stats.
  std::size_t within(const std::vector<sc::Pose>& poses, double d) {
    within_ = std::make_unique<sc::Scene>(options_);
    within_->add(w_.bodies, poses);
    return static_cast<std::size_t>(within_->pairs_within(d).size());
  }
  const sc::SceneStats& stats() const { return scene_->stats(); }
  const sc::SceneStats& within_stats() const { return within_->stats(); }

 private:
  std::size_t query() { return static_cast<std::size_t>(scene_->colliding_pairs().size()); }
  const Workload& w_;
  sc::SceneOptions options_;
  std::unique_ptr<sc::Scene> scene_;
  std::unique_ptr<sc::Scene> within_;
  std::vector<sc::BodyId> ids_;
};

struct Row {
  Row(std::string who, int size, std::string kind, bool our_scene = false)
      : contender(std::move(who)), n(size), frame(std::move(kind)), ours(our_scene) {}
  std::string contender;
  int n;
  std::string frame;
  std::vector<double> seconds;
  std::vector<double> cpu_seconds;
  std::size_t pairs = 0;
  std::size_t candidates = 0;
  sc::SceneStats stats;
  bool ours;
};

std::string json_row(const Row& r) {
  std::ostringstream out;
  out.precision(9);
  out << "{\"contender\": \"" << r.contender << "\", \"n\": " << r.n << ", \"frame\": \"" << r.frame
      << "\", \"median_s\": " << median(r.seconds)
      << ", \"min_s\": " << *std::min_element(r.seconds.begin(), r.seconds.end())
      << ", \"max_s\": " << *std::max_element(r.seconds.begin(), r.seconds.end())
      << ", \"median_cpu_s\": " << median(r.cpu_seconds) << ", \"repeats\": " << r.seconds.size()
      << ", \"pairs\": " << r.pairs << ", \"candidates\": " << r.candidates;
  if (r.ours) {
    const sc::SceneStats& s = r.stats;
    out << ", \"certified\": " << s.certified << ", \"screened\": " << s.screened
        << ", \"warm_bounded\": " << s.warm_bounded << ", \"warm_rejected\": " << s.warm_rejected
        << ", \"warm_proven\": " << s.warm_proven << ", \"solved\": " << s.solved
        << ", \"escalations\": " << s.escalations << ", \"cached_pairs\": " << s.cached_pairs
        << ", \"cache_bytes\": " << s.cache_bytes;
  }
  out << "}";
  return out.str();
}

void print(const Row& r) {
  std::printf("%-22s N=%-6d %-7s %9.3f ms (cpu %8.3f, min %8.3f, %zu runs)  pairs %zu  cand %zu",
              r.contender.c_str(), r.n, r.frame.c_str(), 1e3 * median(r.seconds),
              1e3 * median(r.cpu_seconds),
              1e3 * *std::min_element(r.seconds.begin(), r.seconds.end()), r.seconds.size(),
              r.pairs, r.candidates);
  if (r.ours) {
    const sc::SceneStats& s = r.stats;
    std::printf("  cert %zu  screened %zu  warm %zu+%zu+%zu  solved %zu  esc %zu  cache %zu B/pair",
                s.certified, s.screened, s.warm_bounded, s.warm_rejected, s.warm_proven, s.solved,
                s.escalations, s.cached_pairs ? s.cache_bytes / s.cached_pairs : 0);
  }
  std::printf("\n");
  std::fflush(stdout);
}

std::string load_average() {
  double load[3] = {0, 0, 0};
  if (getloadavg(load, 3) != 3) return "[]";
  std::ostringstream out;
  out << "[" << load[0] << ", " << load[1] << ", " << load[2] << "]";
  return out.str();
}

// Runs `run()` and adds its wall-clock and CPU times to `row`.
template <typename Run>
auto timed(Row& row, const Run& run) {
  const double start = now();
  const double cpu_start = cpu_now();
  auto result = run();
  row.cpu_seconds.push_back(cpu_now() - cpu_start);
  row.seconds.push_back(now() - start);
  return result;
}

}  // namespace

int main(int argc, char** argv) {
  bool quick = false;
  std::string json_path;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--quick") {
      quick = true;
    } else if (arg == "--json" && i + 1 < argc) {
      json_path = argv[++i];
    } else {
      std::cerr << "usage: swarmcollide-scene-bench [--quick] [--json path]\n";
      return 2;
    }
  }
  const std::string load_before = load_average();
  std::vector<Row> rows;
  const int warm_frames = quick ? 5 : 20;
  const int cold_repeats = quick ? 3 : 7;
  for (const int n : {1000, 10000}) {
    const Workload w = make_workload(n, warm_frames + 1, 2024 + n);
    FclScene fcl(w);
    OurScene one(w, 1);
    OurScene two(w, 2);
    Row fcl_cold{"fcl_manager_gjk", n, "cold"};
    Row fcl_warm{"fcl_manager_gjk", n, "warm"};
    Row one_cold{"scene_1_thread", n, "cold", true};
    Row one_warm{"scene_1_thread", n, "warm", true};
    Row two_cold{"scene_2_threads", n, "cold", true};
    Row two_warm{"scene_2_threads", n, "warm", true};
    // Cold frames: every contender builds its structures from nothing, in turn.
    for (int rep = 0; rep < cold_repeats; ++rep) {
      const FrameCount f = timed(fcl_cold, [&] { return fcl.cold(w.frames[0]); });
      fcl_cold.pairs = f.hits;
      fcl_cold.candidates = f.candidates;
      for (auto [scene, row] : {std::pair{&one, &one_cold}, std::pair{&two, &two_cold}}) {
        row->pairs = timed(*row, [&] { return scene->cold(w.frames[0]); });
        row->stats = scene->stats();
        row->candidates = row->stats.candidates;
      }
    }
    // Warm frames: the same motion for every contender, which keeps its state between frames.
    for (int f = 1; f <= warm_frames; ++f) {
      const FrameCount c = timed(fcl_warm, [&] { return fcl.frame(w.frames[f]); });
      fcl_warm.pairs = c.hits;
      fcl_warm.candidates = c.candidates;
      for (auto [scene, row] : {std::pair{&one, &one_warm}, std::pair{&two, &two_warm}}) {
        row->pairs = timed(*row, [&] { return scene->frame(w.frames[f]); });
        row->stats = scene->stats();
        row->candidates = row->stats.candidates;
      }
    }
    for (const Row* r : {&fcl_cold, &one_cold, &two_cold, &fcl_warm, &one_warm, &two_warm}) {
      print(*r);
      rows.push_back(*r);
    }
    if (n == 10000 || quick) {
      Row fcl_within{"fcl_inflated_distance", n, "within"};
      Row one_within{"scene_1_thread", n, "within", true};
      Row two_within{"scene_2_threads", n, "within", true};
      for (int rep = 0; rep < (quick ? 1 : 3); ++rep) {
        const FrameCount c = timed(fcl_within, [&] { return fcl.within(w.frames[0], 0.1); });
        fcl_within.pairs = c.hits;
        fcl_within.candidates = c.candidates;
        for (auto [scene, row] : {std::pair{&one, &one_within}, std::pair{&two, &two_within}}) {
          row->pairs = timed(*row, [&] { return scene->within(w.frames[0], 0.1); });
          row->stats = scene->within_stats();
          row->candidates = row->stats.candidates;
        }
      }
      for (const Row* r : {&fcl_within, &one_within, &two_within}) {
        print(*r);
        rows.push_back(*r);
      }
    }
  }
  if (!json_path.empty()) {
    std::ofstream out(json_path);
    out << "{\"context\": {\"load_before\": " << load_before
        << ", \"load_after\": " << load_average() << ", \"density\": " << kDensity
        << ", \"step\": " << kStep << ", \"turn\": " << kTurn
        << ", \"warm_frames\": " << warm_frames << ", \"cold_repeats\": " << cold_repeats
        << ", \"mode\": \"" << (quick ? "quick" : "full") << "\"},\n \"rows\": [\n";
    for (std::size_t i = 0; i < rows.size(); ++i) {
      out << "  " << json_row(rows[i]) << (i + 1 < rows.size() ? ",\n" : "\n");
    }
    out << "]}\n";
  }
  return 0;
}
