#include "swarmcollide/scene/scene.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>
#include <unordered_set>
#include <utility>

#include "fcl_broadphase.hpp"
#include "narrowphase.hpp"
#include "pair_cache.hpp"
#include "swarmcollide/queries/batch.hpp"
#include "swarmcollide/queries/methods.hpp"
#include "thread_pool.hpp"

namespace swarmcollide {

namespace {

using detail::PairAnswer;
using detail::PairProof;
using detail::PairQuestion;

constexpr Scalar kEpsilon = std::numeric_limits<Scalar>::epsilon();
// Pairs a thread takes at a time: enough to make taking them cheap, few enough to balance.
constexpr std::size_t kChunk = 32;

// The largest distance of the body's points from the centre of its box: what a turn about that
// centre moves them by, per radian. Often well below the box's half-diagonal.
Scalar reach_about_centre(const ConvexPolyhedron& body) {
  return (body.vertices().rowwise() - body.bounds().centre.transpose()).rowwise().norm().maxCoeff();
}

// A body of the scene with what the broadphase keeps of it. What the narrowphase reads of every
// candidate comes first, in the first four cache lines (see `prefetch`).
struct SceneBody {
  SceneBody(BodyId id_, ConvexPolyhedron body_, std::shared_ptr<const CompoundBody> compound_,
            const Pose& pose_, const BodyFilter& filter_)
      : id(id_),
        filter(filter_),
        pose(pose_),
        body(std::move(body_)),
        reach(reach_about_centre(body)),
        compound(std::move(compound_)),
        object(this, id_, filter_) {}

  BodyId id;
  BodyFilter filter;
  /// An odometer: a bound on how far any point of the body has moved since it was added.
  Scalar travelled = 0;
  Pose pose;
  /// The body, or a compound body's envelope (the hull of its parts), which the broadphase
  /// boxes and the narrowphase screens with.
  ConvexPolyhedron body;
  /// The largest distance of its points from the centre of its box (see displacement).
  Scalar reach;
  /// The compound body, null for a convex one.
  std::shared_ptr<const CompoundBody> compound;
  /// The smallest box holding the body at its pose, widened by the rounding of computing it.
  Aabb box;
  /// Support points of the box's six faces, from which hill climbing on large bodies starts.
  std::array<int, 6> box_supports{-1, -1, -1, -1, -1, -1};
  /// Listed among the scene's moved bodies (its box is out of date).
  bool moved = false;
  /// The box the broadphase holds: `box` padded for the threshold of the last query.
  detail::BoxedObject object;
};

// Asks for what the narrowphase will read of a body: its pose and the head of its polyhedron
// now, its points once those have arrived. Candidates meet bodies in no particular order, so
// without this every pair waits for memory several times.
void prefetch_head(const SceneBody* b) {
  const char* p = reinterpret_cast<const char*>(b);
  for (int line = 0; line < 4; ++line) __builtin_prefetch(p + 64 * line);
}
void prefetch_points(const SceneBody* b) { __builtin_prefetch(b->body.vertices().data()); }

// The norm of R' - R, for rotations R and R' (to the 1e-9 that poses are validated to): from the
// angle theta of R'^T R, |R' - R|_2 = 2 sin(theta / 2) = sqrt(3 - trace(R'^T R)), with a margin
// for the rotations' own error; or the Frobenius norm, never smaller, when that is less (for a
// rotation that did not change, exactly zero).
Scalar turn(const Matrix3& from, const Matrix3& to) {
  const Scalar frobenius = (to - from).norm();
  const Scalar trace = (to.transpose() * from).trace();
  return std::min(frobenius, std::sqrt(std::max(Scalar(0), 3 - trace) + 1e-8));
}

// A bound on how far any point of a body moves from `from` to `to`: its box centre c moves by
// |c' - c|, and every point turns about it by at most |R' - R| times `reach`. Each term is
// computed with a few roundings of the magnitudes involved, which the margins cover.
Scalar displacement(const ConvexPolyhedron& body, Scalar reach, const Pose& from, const Pose& to) {
  const Vector3& c = body.bounds().centre;
  const Vector3 old_centre = from.rotation * c + from.translation;
  const Vector3 new_centre = to.rotation * c + to.translation;
  const Scalar moved = (new_centre - old_centre).norm() + turn(from.rotation, to.rotation) * reach;
  const Scalar magnitude = old_centre.cwiseAbs().maxCoeff() + new_centre.cwiseAbs().maxCoeff() +
                           c.cwiseAbs().maxCoeff() + reach;
  return moved * (1 + 1e-12) + 16 * kEpsilon * magnitude;
}

// The world box of `b`: its points' extremes along the axes, found in the body's own frame
// (scanning small bodies, climbing large ones from the last frame's supports), so moving a body
// never touches its hull. Each coordinate R x + t carries at most a few roundings of |x| + |t|.
void update_box(SceneBody& b) {
  const Matrix3& r = b.pose.rotation;
  const Vector3& t = b.pose.translation;
  const VertexMatrix& points = b.body.vertices();
  Vector3 low;
  Vector3 high;
  if (b.body.size() <= kHillClimbingThreshold) {
    low = r * points.row(0).transpose() + t;
    high = low;
    for (int i = 1; i < b.body.size(); ++i) {
      const Vector3 p = r * points.row(i).transpose() + t;
      low = low.cwiseMin(p);
      high = high.cwiseMax(p);
    }
  } else {
    for (int k = 0; k < 3; ++k) {
      const Vector3 axis = r.row(k).transpose();
      int& up = b.box_supports[2 * k];
      int& down = b.box_supports[2 * k + 1];
      up = b.body.support_index(axis, up);
      down = b.body.support_index(-axis, down);
      high(k) = axis.dot(points.row(up).transpose()) + t(k);
      low(k) = axis.dot(points.row(down).transpose()) + t(k);
    }
  }
  const Scalar reach = b.body.bounds().centre.cwiseAbs().maxCoeff() + b.body.bounds().radius +
                       t.cwiseAbs().maxCoeff();
  const Vector3 rounding = Vector3::Constant(16 * kEpsilon * reach);
  b.box = {low - rounding, high + rounding};
}

// How far the broadphase box of a body of radius `radius` is padded so that every pair within
// `threshold` plus the tolerance of each other has overlapping boxes. Such a pair is at most
// d <= threshold + tol S apart, where the pair's size S = |c_b - c_a| + 2 max(r_a, r_b) is at
// most d + 4 max(r_a, r_b) (each body lies within its radius of its centre); so d <= (threshold
// + 4 tol max(r)) / (1 - tol), and padding each box by (threshold / 2 + 4 tol r) / (1 - tol)
// covers it. The verdict's rounding margin is absorbed by raising tol by 1e-12.
Scalar padding(Scalar threshold, Scalar radius, Scalar tolerance) {
  const Scalar tol = tolerance + 1e-12;
  return (threshold / 2 + 4 * tol * radius) / (1 - tol);
}

Aabb padded(const Aabb& box, Scalar pad) {
  return {box.min - Vector3::Constant(pad), box.max + Vector3::Constant(pad)};
}

// A candidate pair, its bodies in id order.
struct Candidate {
  std::uint64_t key;
  const SceneBody* first;
  const SceneBody* second;
};

std::string unknown_id(BodyId id) {
  return "no body with id " + std::to_string(id) + " in the scene";
}

}  // namespace

struct Scene::Impl {
  explicit Impl(const SceneOptions& o)
      : options(o),
        broadphase(o.broadphase),
        pool(o.threads > 0 ? o.threads
                           : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()))) {}

  SceneOptions options;
  mutable std::mutex mutex;
  std::vector<std::unique_ptr<SceneBody>> bodies;
  // The slot in `bodies` of each id ever given, kNoSlot once removed: ids are handed out in
  // order, so a vector is the map (four bytes per id ever given), and moving every body a frame
  // costs no hashing.
  static constexpr std::uint32_t kNoSlot = 0xFFFFFFFFu;
  std::vector<std::uint32_t> slot;
  BodyId next_id = 0;
  detail::FclBroadphase broadphase;
  detail::ThreadPool pool;
  // Bodies moved (or added) since their boxes were computed.
  std::vector<SceneBody*> moved;
  // The threshold the broadphase's boxes are padded for.
  Scalar padded_for = 0;
  std::unordered_set<std::uint64_t> excluded;
  // Proofs of the last query's candidates, by key.
  std::vector<PairProof> cache;
  SceneStats stats;
  // Buffers reused from query to query.
  std::vector<detail::ObjectPair> overlaps;
  std::vector<Candidate> candidates;
  std::vector<Candidate> sorted;
  // What `answer` found, chunk by chunk (each chunk's pairs that belong, with their candidate
  // index, and how every pair was settled), then all in candidate order. Only the pairs that
  // belong are kept: at 10,000 bodies a frame has 50,000 candidates and a third of them belong.
  struct ChunkOutput {
    std::vector<std::pair<std::size_t, PairAnswer>> found;
    SceneStats tally;
  };
  std::vector<ChunkOutput> chunk_outputs;
  std::vector<std::pair<std::size_t, PairAnswer>> found;
  // `nearest`'s answers, one per candidate.
  std::vector<PairAnswer> answers;
  std::vector<PairProof> proofs;

  SceneBody& find(BodyId id) {
    if (id >= slot.size() || slot[id] == kNoSlot) throw std::invalid_argument(unknown_id(id));
    return *bodies[slot[id]];
  }
  const SceneBody& find(BodyId id) const { return const_cast<Impl*>(this)->find(id); }

  Scalar pad_of(const SceneBody& b, Scalar threshold) const {
    return padding(threshold, b.body.bounds().radius, options.query.tolerance);
  }

  // Brings the broadphase's boxes up to date for queries at `threshold`.
  void prepare(Scalar threshold) {
    for (SceneBody* b : moved) {
      update_box(*b);
      b->moved = false;
    }
    const bool repad = threshold != padded_for;
    if (repad) {
      for (auto& b : bodies) b->object.set_box(padded(b->box, pad_of(*b, threshold)));
    } else {
      for (SceneBody* b : moved) b->object.set_box(padded(b->box, pad_of(*b, threshold)));
    }
    padded_for = threshold;
    std::vector<detail::BoxedObject*> objects;
    const bool all = repad || moved.size() * 4 > bodies.size();
    if (!all) {
      for (SceneBody* b : moved) objects.push_back(&b->object);
    }
    if (all || !objects.empty()) broadphase.refit(objects, all);
    moved.clear();
  }

  // Read from the broadphase's objects, whose copies of the ids and filters lie beside the boxes
  // the traversal has just read.
  bool pairable(const detail::BoxedObject& a, const detail::BoxedObject& b) const {
    return a.id != b.id && a.filter.pairs_with(b.filter) &&
           (excluded.empty() ||
            excluded.count(detail::pair_key(std::min(a.id, b.id), std::max(a.id, b.id))) == 0);
  }

  void add_candidate(const detail::BoxedObject* a, const detail::BoxedObject* b) {
    if (!pairable(*a, *b)) return;
    if (b->id < a->id) std::swap(a, b);
    candidates.push_back({detail::pair_key(a->id, b->id), static_cast<const SceneBody*>(a->owner()),
                          static_cast<const SceneBody*>(b->owner())});
  }

  // By key, then without repeats. A least-significant-digit radix sort on the ids' significant
  // bits: the candidates of a frame number tens of thousands, where comparison sorting took a
  // tenth of the frame.
  void sort_candidates() {
    int bits = 1;
    while ((std::uint64_t{1} << bits) < next_id) ++bits;
    const auto rank = [bits](const Candidate& c) {
      return (static_cast<std::uint64_t>(detail::key_first(c.key)) << bits) |
             detail::key_second(c.key);
    };
    constexpr int kDigit = 11;
    constexpr std::size_t kBuckets = std::size_t{1} << kDigit;
    sorted.resize(candidates.size());
    for (int shift = 0; shift < 2 * bits; shift += kDigit) {
      std::array<std::size_t, kBuckets + 1> start{};
      for (const Candidate& c : candidates) ++start[((rank(c) >> shift) & (kBuckets - 1)) + 1];
      for (std::size_t d = 1; d <= kBuckets; ++d) start[d] += start[d - 1];
      for (const Candidate& c : candidates)
        sorted[start[(rank(c) >> shift) & (kBuckets - 1)]++] = c;
      candidates.swap(sorted);
    }
    candidates.erase(
        std::unique(candidates.begin(), candidates.end(),
                    [](const Candidate& x, const Candidate& y) { return x.key == y.key; }),
        candidates.end());
  }

  // Every pairable pair whose padded boxes overlap, in key order.
  void collect(Scalar threshold) {
    prepare(threshold);
    overlaps.clear();
    broadphase.overlapping_pairs(overlaps);
    candidates.clear();
    for (const auto& [p, q] : overlaps) add_candidate(p, q);
    sort_candidates();
  }

  // Answers `question` for every candidate on the pool. With warm starts, `proofs` holds each
  // candidate's cached proof (found by merging the sorted keys) and becomes the cache: pairs
  // the broadphase no longer returned are dropped.
  void answer(const PairQuestion& asked) {
    const std::size_t n = candidates.size();
    PairQuestion question = asked;
    question.warm = asked.warm && options.warm_start;
    proofs.clear();
    proofs.reserve(n);
    auto old = cache.begin();
    for (const Candidate& c : candidates) {
      while (question.warm && old != cache.end() && old->key < c.key) ++old;
      if (question.warm && old != cache.end() && old->key == c.key) {
        proofs.push_back(*old);
      } else {
        proofs.emplace_back(c.key);
      }
    }
    chunk_outputs.resize(n / kChunk + 1);
    for (ChunkOutput& out : chunk_outputs) {
      out.found.clear();
      out.tally = SceneStats{};
    }
    const QueryOptions& base = options.query;
    pool.for_each_chunk(n, kChunk, [&](std::size_t begin, std::size_t end) {
      ChunkOutput& out = chunk_outputs[begin / kChunk];
      thread_local PairAnswer answer;
      QueryOptions pair_options = base;
      for (std::size_t i = begin; i < end; ++i) {
        if (i + 8 < end) prefetch_head(candidates[i + 8].second);
        if (i + 4 < end) prefetch_points(candidates[i + 4].second);
        const Candidate& c = candidates[i];
        pair_options.seed = pair_seed(base.seed, c.key);
        try {
          detail::answer_pair(
              {&c.first->body, &c.first->pose, c.first->travelled, c.first->compound.get()},
              {&c.second->body, &c.second->pose, c.second->travelled, c.second->compound.get()},
              proofs[i], pair_options, question, answer);
        } catch (const std::invalid_argument& error) {
          throw std::invalid_argument("bodies " + std::to_string(c.first->id) + " and " +
                                      std::to_string(c.second->id) + ": " + error.what());
        }
        tally(out.tally, answer);
        if (answer.belongs) out.found.emplace_back(i, answer);
      }
    });
    found.clear();
    stats = SceneStats{};
    for (ChunkOutput& out : chunk_outputs) {
      for (auto& f : out.found) found.push_back(std::move(f));
      add(stats, out.tally);
    }
    if (question.warm) {
      proofs.erase(
          std::remove_if(proofs.begin(), proofs.end(),
                         [](const PairProof& p) { return p.kind == PairProof::Kind::none; }),
          proofs.end());
      cache.swap(proofs);
    }
    finish_stats(n);
  }

  static void tally(SceneStats& s, const PairAnswer& a) {
    s.screened += a.settled == detail::Settled::screened;
    s.warm_bounded += a.settled == detail::Settled::warm_bounded;
    s.warm_rejected += a.settled == detail::Settled::warm_rejected;
    s.warm_proven += a.settled == detail::Settled::warm_proven;
    s.solved += a.settled == detail::Settled::solved || a.settled == detail::Settled::escalated;
    s.escalations += a.settled == detail::Settled::escalated;
    s.certified += a.certified;
  }

  static void add(SceneStats& s, const SceneStats& more) {
    s.screened += more.screened;
    s.warm_bounded += more.warm_bounded;
    s.warm_rejected += more.warm_rejected;
    s.warm_proven += more.warm_proven;
    s.solved += more.solved;
    s.escalations += more.escalations;
    s.certified += more.certified;
  }

  void finish_stats(std::size_t candidates_answered) {
    stats.candidates = candidates_answered;
    stats.cached_pairs = cache.size();
    stats.cache_bytes = cache.capacity() * sizeof(PairProof);
  }

  // The answers that belong, in candidate (key) order.
  SceneResult gather() const {
    SceneResult result = sized(found.size());
    for (std::size_t r = 0; r < found.size(); ++r) {
      const Candidate& c = candidates[found[r].first];
      put(result, r, c.first->id, c.second->id, found[r].second);
    }
    return result;
  }

  static SceneResult sized(std::size_t rows) {
    const auto m = static_cast<Eigen::Index>(rows);
    SceneResult r;
    r.pairs.resize(m, 2);
    r.distance.resize(m);
    r.lower_bound.resize(m);
    r.point_a.resize(m, 3);
    r.point_b.resize(m, 3);
    r.normal.resize(m, 3);
    r.certified.resize(m);
    return r;
  }

  static void put(SceneResult& result, std::size_t row, BodyId a, BodyId b,
                  const PairAnswer& answer) {
    const auto r = static_cast<Eigen::Index>(row);
    result.pairs(r, 0) = a;
    result.pairs(r, 1) = b;
    result.distance(r) = answer.distance;
    result.lower_bound(r) = answer.lower_bound;
    result.point_a.row(r) = answer.point_a.transpose();
    result.point_b.row(r) = answer.point_b.transpose();
    result.normal.row(r) = answer.normal.transpose();
    result.certified(r) = answer.certified;
  }

  // The answer for the pair in the other order: A and B swapped, vectors reversed.
  static void turn_around(PairAnswer& answer) {
    std::swap(answer.point_a, answer.point_b);
    answer.normal = -answer.normal;
  }

  void require(Capability capability, const char* query) const {
    const Method method = options.query.method;
    if (method_info(method).capabilities & capability) return;
    std::string able;
    for (const MethodInfo& info : method_table()) {
      if (info.capabilities & capability) {
        able += std::string(able.empty() ? "'" : ", '") + info.name + "'";
      }
    }
    throw std::invalid_argument(std::string(query) + " is not available with method '" +
                                method_name(method) + "'; use one of " + able);
  }

  // The largest distance between two points of any two boxes: a threshold beyond which every
  // pair is a candidate and within it.
  Scalar extent() const {
    Aabb all = bodies.front()->box;
    for (const auto& b : bodies) {
      all.min = all.min.cwiseMin(b->box.min);
      all.max = all.max.cwiseMax(b->box.max);
    }
    return (all.max - all.min).norm();
  }

  // The threshold after `threshold` for searches that found too little: twice as far, starting
  // from the median body radius (from 1 when every body is one point: the scene's extent is then
  // zero, and any positive threshold covers it).
  Scalar next_threshold(Scalar threshold) const {
    if (threshold > 0) return 2 * threshold;
    const Scalar step = first_step();
    return step > 0 ? step : 1;
  }

  // A first threshold for searches that found nothing in contact: the median body radius.
  Scalar first_step() const {
    std::vector<Scalar> radii;
    for (const auto& b : bodies) radii.push_back(b->body.bounds().radius);
    std::nth_element(radii.begin(), radii.begin() + radii.size() / 2, radii.end());
    return std::max(radii[radii.size() / 2], kEpsilon * extent());
  }

  SceneResult min_distance();
  SceneResult nearest(const std::vector<BodyId>& ids, int k);
  // Adds bodies (with their compound bodies, none for convex ones); the caller holds the lock.
  std::vector<BodyId> add(std::vector<ConvexPolyhedron> bodies,
                          std::vector<std::shared_ptr<const CompoundBody>> compounds,
                          const std::vector<Pose>& poses, const BodyFilter& filter);
};

Scene::Scene(SceneOptions options) {
  options.validate();
  impl_ = std::make_unique<Impl>(options);
}

Scene::~Scene() = default;
Scene::Scene(Scene&&) noexcept = default;
Scene& Scene::operator=(Scene&&) noexcept = default;

const SceneOptions& Scene::options() const { return impl_->options; }

std::vector<BodyId> Scene::Impl::add(std::vector<ConvexPolyhedron> bodies,
                                     std::vector<std::shared_ptr<const CompoundBody>> compounds,
                                     const std::vector<Pose>& poses, const BodyFilter& filter) {
  Impl& s = *this;
  if (!poses.empty() && poses.size() != bodies.size()) {
    throw std::invalid_argument("poses must have one pose per body: got " +
                                std::to_string(poses.size()) + " poses for " +
                                std::to_string(bodies.size()) + " bodies");
  }
  for (std::size_t i = 0; i < poses.size(); ++i) {
    validate_pose(poses[i], "poses", i);
  }
  if (bodies.size() > std::numeric_limits<BodyId>::max() - std::size_t{s.next_id}) {
    throw std::invalid_argument("the scene has given out every id (2**32); build a new scene");
  }
  std::vector<BodyId> ids;
  std::vector<detail::BoxedObject*> objects;
  ids.reserve(bodies.size());
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const BodyId id = s.next_id++;
    auto body = std::make_unique<SceneBody>(id, std::move(bodies[i]),
                                            compounds.empty() ? nullptr : std::move(compounds[i]),
                                            poses.empty() ? Pose{} : poses[i], filter);
    update_box(*body);
    body->object.set_box(padded(body->box, s.pad_of(*body, s.padded_for)));
    objects.push_back(&body->object);
    s.slot.push_back(static_cast<std::uint32_t>(s.bodies.size()));
    s.bodies.push_back(std::move(body));
    ids.push_back(id);
  }
  s.broadphase.insert(objects);
  return ids;
}

std::vector<BodyId> Scene::add(std::vector<ConvexPolyhedron> bodies, const std::vector<Pose>& poses,
                               const BodyFilter& filter) {
  const std::lock_guard<std::mutex> lock(impl_->mutex);
  return impl_->add(std::move(bodies), {}, poses, filter);
}

std::vector<BodyId> Scene::add(std::vector<CompoundBody> bodies, const std::vector<Pose>& poses,
                               const BodyFilter& filter) {
  std::vector<ConvexPolyhedron> envelopes;
  std::vector<std::shared_ptr<const CompoundBody>> compounds;
  for (CompoundBody& body : bodies) {
    envelopes.push_back(body.envelope());
    compounds.push_back(std::make_shared<const CompoundBody>(std::move(body)));
  }
  const std::lock_guard<std::mutex> lock(impl_->mutex);
  return impl_->add(std::move(envelopes), std::move(compounds), poses, filter);
}

BodyId Scene::add(CompoundBody body, const Pose& pose, const BodyFilter& filter) {
  std::vector<CompoundBody> one;
  one.push_back(std::move(body));
  return add(std::move(one), {pose}, filter).front();
}

BodyId Scene::add(ConvexPolyhedron body, const Pose& pose, const BodyFilter& filter) {
  std::vector<ConvexPolyhedron> one;
  one.push_back(std::move(body));
  return add(std::move(one), {pose}, filter).front();
}

void Scene::set_poses(const std::vector<BodyId>& ids, const std::vector<Pose>& poses) {
  Impl& s = *impl_;
  const std::lock_guard<std::mutex> lock(s.mutex);
  if (ids.size() != poses.size()) {
    throw std::invalid_argument("ids and poses must have the same length, got " +
                                std::to_string(ids.size()) + " and " +
                                std::to_string(poses.size()));
  }
  std::vector<SceneBody*> targets;
  targets.reserve(ids.size());
  for (std::size_t i = 0; i < ids.size(); ++i) {
    targets.push_back(&s.find(ids[i]));
    validate_pose(poses[i], "poses", i);
  }
  for (std::size_t i = 0; i < ids.size(); ++i) {
    targets[i]->travelled +=
        displacement(targets[i]->body, targets[i]->reach, targets[i]->pose, poses[i]);
    targets[i]->pose = poses[i];
    // A body moved twice is boxed once.
    if (!targets[i]->moved) s.moved.push_back(targets[i]);
    targets[i]->moved = true;
  }
}

void Scene::remove(const std::vector<BodyId>& ids) {
  Impl& s = *impl_;
  const std::lock_guard<std::mutex> lock(s.mutex);
  std::unordered_set<BodyId> gone;
  for (BodyId id : ids) {
    s.find(id);
    if (!gone.insert(id).second) {
      throw std::invalid_argument("ids lists body " + std::to_string(id) + " twice");
    }
  }
  std::vector<detail::BoxedObject*> objects;
  for (BodyId id : ids) objects.push_back(&s.find(id).object);
  s.broadphase.erase(objects);
  s.moved.erase(std::remove_if(s.moved.begin(), s.moved.end(),
                               [&](const SceneBody* b) { return gone.count(b->id) > 0; }),
                s.moved.end());
  for (BodyId id : ids) {
    const std::size_t at = s.slot[id];
    // The last body fills the slot.
    if (at + 1 != s.bodies.size()) {
      std::swap(s.bodies[at], s.bodies.back());
      s.slot[s.bodies[at]->id] = static_cast<std::uint32_t>(at);
    }
    s.bodies.pop_back();
    s.slot[id] = Impl::kNoSlot;
  }
  const auto involves = [&](std::uint64_t key) {
    return gone.count(detail::key_first(key)) > 0 || gone.count(detail::key_second(key)) > 0;
  };
  s.cache.erase(std::remove_if(s.cache.begin(), s.cache.end(),
                               [&](const PairProof& p) { return involves(p.key); }),
                s.cache.end());
  for (auto it = s.excluded.begin(); it != s.excluded.end();) {
    it = involves(*it) ? s.excluded.erase(it) : std::next(it);
  }
}

void Scene::set_filter(const std::vector<BodyId>& ids, const BodyFilter& filter) {
  Impl& s = *impl_;
  const std::lock_guard<std::mutex> lock(s.mutex);
  for (BodyId id : ids) s.find(id);
  for (BodyId id : ids) {
    SceneBody& b = s.find(id);
    b.filter = filter;
    b.object.filter = filter;
  }
}

void Scene::exclude(const std::vector<std::pair<BodyId, BodyId>>& pairs) {
  Impl& s = *impl_;
  const std::lock_guard<std::mutex> lock(s.mutex);
  for (const auto& [a, b] : pairs) {
    s.find(a);
    s.find(b);
  }
  for (const auto& [a, b] : pairs)
    s.excluded.insert(detail::pair_key(std::min(a, b), std::max(a, b)));
}

void Scene::include(const std::vector<std::pair<BodyId, BodyId>>& pairs) {
  Impl& s = *impl_;
  const std::lock_guard<std::mutex> lock(s.mutex);
  for (const auto& [a, b] : pairs)
    s.excluded.erase(detail::pair_key(std::min(a, b), std::max(a, b)));
}

std::size_t Scene::size() const {
  const std::lock_guard<std::mutex> lock(impl_->mutex);
  return impl_->bodies.size();
}

std::vector<BodyId> Scene::ids() const {
  const std::lock_guard<std::mutex> lock(impl_->mutex);
  std::vector<BodyId> ids;
  for (const auto& b : impl_->bodies) ids.push_back(b->id);
  std::sort(ids.begin(), ids.end());
  return ids;
}

bool Scene::contains(BodyId id) const {
  const std::lock_guard<std::mutex> lock(impl_->mutex);
  return id < impl_->slot.size() && impl_->slot[id] != Impl::kNoSlot;
}

const ConvexPolyhedron& Scene::body(BodyId id) const {
  const std::lock_guard<std::mutex> lock(impl_->mutex);
  return impl_->find(id).body;
}

const CompoundBody* Scene::compound(BodyId id) const {
  const std::lock_guard<std::mutex> lock(impl_->mutex);
  return impl_->find(id).compound.get();
}

const Pose& Scene::pose(BodyId id) const {
  const std::lock_guard<std::mutex> lock(impl_->mutex);
  return impl_->find(id).pose;
}

const BodyFilter& Scene::filter(BodyId id) const {
  const std::lock_guard<std::mutex> lock(impl_->mutex);
  return impl_->find(id).filter;
}

SceneResult Scene::colliding_pairs() {
  Impl& s = *impl_;
  const std::lock_guard<std::mutex> lock(s.mutex);
  s.require(kCollide, "colliding_pairs");
  s.collect(0);
  PairQuestion question;
  question.escalate = s.options.escalate;
  s.answer(question);
  return s.gather();
}

SceneResult Scene::pairs_within(Scalar distance) {
  Impl& s = *impl_;
  const std::lock_guard<std::mutex> lock(s.mutex);
  if (!(distance >= 0) || !std::isfinite(distance)) {
    throw std::invalid_argument("distance must be a finite number >= 0, got " +
                                std::to_string(distance));
  }
  s.require(kDistance, "pairs_within");
  s.collect(distance);
  PairQuestion question;
  question.threshold = distance;
  question.distance = true;
  question.escalate = s.options.escalate;
  s.answer(question);
  return s.gather();
}

SceneResult Scene::Impl::min_distance() {
  require(kDistance, "min_distance");
  if (bodies.size() < 2) return sized(0);
  // Pairs within a threshold, the threshold raised until some are: every other pair is
  // farther than the threshold, so the nearest of those found is the nearest of all.
  const Scalar far = extent();
  Scalar threshold = 0;
  PairQuestion question;
  question.distance = true;
  question.escalate = options.escalate;
  for (;;) {
    collect(threshold);
    question.threshold = threshold;
    answer(question);
    const std::pair<std::size_t, PairAnswer>* best = nullptr;
    for (const auto& f : found) {
      if (best == nullptr || f.second.distance < best->second.distance) best = &f;
    }
    if (best != nullptr) {
      SceneResult result = sized(1);
      const Candidate& c = candidates[best->first];
      put(result, 0, c.first->id, c.second->id, best->second);
      return result;
    }
    // No pairable pair at all once every box overlaps every other.
    if (threshold > far) return sized(0);
    threshold = next_threshold(threshold);
  }
}

SceneResult Scene::min_distance() {
  const std::lock_guard<std::mutex> lock(impl_->mutex);
  return impl_->min_distance();
}

SceneResult Scene::Impl::nearest(const std::vector<BodyId>& ids, int k) {
  require(kDistance, "nearest");
  if (k < 1) throw std::invalid_argument("k must be at least 1, got " + std::to_string(k));
  std::vector<SceneBody*> asked;
  for (BodyId id : ids) asked.push_back(&find(id));
  prepare(padded_for);
  const Scalar far = extent();
  Scalar largest_radius = 0;
  for (const auto& b : bodies) largest_radius = std::max(largest_radius, b->body.bounds().radius);

  // Each body's search: pairs within a threshold of it, the threshold raised until k are.
  struct Search {
    explicit Search(SceneBody* b) : body(b) {}
    SceneBody* body;
    Scalar threshold = 0;
    // (distance, row): rows of this round's `rows` while searching, of `final_rows` when done.
    std::vector<std::pair<Scalar, std::size_t>> found;
    bool done = false;
  };
  std::vector<Search> searches;
  for (SceneBody* b : asked) searches.emplace_back(b);
  // This round's pairs that lie within their search's threshold: (other, answer as seen from
  // the asker); and the rows of finished searches.
  std::vector<std::pair<BodyId, PairAnswer>> rows;
  struct FinalRow {
    BodyId asker;
    BodyId other;
    PairAnswer answer;
  };
  std::vector<FinalRow> final_rows;
  PairQuestion question;
  question.distance = true;
  question.escalate = options.escalate;
  question.warm = false;
  std::vector<PairProof> scratch;
  for (bool pending = true; pending;) {
    // The candidates of every pending search, answered together on the pool.
    candidates.clear();
    std::vector<std::size_t> asker;
    std::vector<Scalar> thresholds;
    for (std::size_t s = 0; s < searches.size(); ++s) {
      Search& search = searches[s];
      if (search.done) continue;
      const SceneBody& b = *search.body;
      // The whole padding on the asker's side: the others' boxes are at least tight.
      const Scalar tol = options.query.tolerance + 1e-12;
      const Scalar pad =
          (search.threshold + 4 * tol * (b.body.bounds().radius + largest_radius)) / (1 - tol);
      detail::BoxedObject probe(search.body, b.id, b.filter);
      probe.set_box(padded(b.box, pad));
      overlaps.clear();
      broadphase.overlapping(&probe, overlaps);
      for (const auto& [self, other] : overlaps) {
        if (!pairable(probe, *other)) continue;
        const auto* o = static_cast<const SceneBody*>(other->owner());
        candidates.push_back({detail::pair_key(b.id, o->id), &b, o});
        asker.push_back(s);
        thresholds.push_back(search.threshold);
      }
    }
    answers.resize(candidates.size());
    scratch.assign(candidates.size(), PairProof{});
    const QueryOptions& base = options.query;
    pool.for_each_chunk(candidates.size(), kChunk, [&](std::size_t begin, std::size_t end) {
      QueryOptions pair_options = base;
      PairQuestion q = question;
      for (std::size_t i = begin; i < end; ++i) {
        const Candidate& c = candidates[i];
        // Answered in id order, as every other query answers the pair, then turned around.
        const bool flip = c.second->id < c.first->id;
        const SceneBody* lo = flip ? c.second : c.first;
        const SceneBody* hi = flip ? c.first : c.second;
        pair_options.seed = pair_seed(base.seed, detail::pair_key(lo->id, hi->id));
        q.threshold = thresholds[i];
        try {
          detail::answer_pair({&lo->body, &lo->pose, 0, lo->compound.get()},
                              {&hi->body, &hi->pose, 0, hi->compound.get()}, scratch[i],
                              pair_options, q, answers[i]);
          if (flip) turn_around(answers[i]);
        } catch (const std::invalid_argument& error) {
          throw std::invalid_argument("bodies " + std::to_string(lo->id) + " and " +
                                      std::to_string(hi->id) + ": " + error.what());
        }
      }
    });
    stats = SceneStats{};
    for (const PairAnswer& a : answers) tally(stats, a);
    finish_stats(candidates.size());
    for (Search& search : searches) {
      if (!search.done) search.found.clear();
    }
    rows.clear();
    for (std::size_t i = 0; i < candidates.size(); ++i) {
      if (!answers[i].belongs) continue;
      searches[asker[i]].found.emplace_back(answers[i].distance, rows.size());
      rows.emplace_back(candidates[i].second->id, answers[i]);
    }
    pending = false;
    for (Search& search : searches) {
      if (search.done) continue;
      if (search.found.size() >= static_cast<std::size_t>(k) || search.threshold > far) {
        search.done = true;
        // Nearest first; equal distances by id.
        std::sort(search.found.begin(), search.found.end(), [&](const auto& x, const auto& y) {
          return x.first < y.first ||
                 (x.first == y.first && rows[x.second].first < rows[y.second].first);
        });
        search.found.resize(std::min(search.found.size(), static_cast<std::size_t>(k)));
        // Keep the rows: the next round overwrites this one's.
        std::vector<std::pair<Scalar, std::size_t>> kept;
        for (const auto& f : search.found) {
          kept.emplace_back(f.first, final_rows.size());
          final_rows.push_back({search.body->id, rows[f.second].first, rows[f.second].second});
        }
        search.found = std::move(kept);
      } else {
        search.threshold = next_threshold(search.threshold);
        pending = true;
      }
    }
  }
  SceneResult result = sized(final_rows.size());
  std::size_t r = 0;
  for (const Search& search : searches) {
    for (const auto& f : search.found) {
      const FinalRow& row = final_rows[f.second];
      put(result, r++, row.asker, row.other, row.answer);
    }
  }
  return result;
}

SceneResult Scene::nearest(const std::vector<BodyId>& ids, int k) {
  const std::lock_guard<std::mutex> lock(impl_->mutex);
  return impl_->nearest(ids, k);
}

ContactResult Scene::contacts(int max_points) {
  Impl& s = *impl_;
  const std::lock_guard<std::mutex> lock(s.mutex);
  if (max_points < 1) {
    throw std::invalid_argument("max_points must be at least 1, got " + std::to_string(max_points));
  }
  s.require(kSignedDistance, "contacts");
  s.collect(0);
  PairQuestion question;
  question.contacts = true;
  question.max_points = max_points;
  question.escalate = s.options.escalate;
  s.answer(question);
  ContactResult result;
  static_cast<SceneResult&>(result) = s.gather();
  const Eigen::Index m = result.size();
  result.counts.resize(m);
  result.offsets.resize(m);
  std::size_t total = 0;
  Eigen::Index row = 0;
  for (const auto& [index, answer] : s.found) {
    result.offsets(row) = static_cast<std::int64_t>(total);
    result.counts(row) = static_cast<int>(answer.points.size());
    total += answer.points.size();
    ++row;
  }
  result.points.resize(static_cast<Eigen::Index>(total), 3);
  result.point_pair.resize(static_cast<Eigen::Index>(total));
  Eigen::Index p = 0;
  row = 0;
  for (const auto& [index, answer] : s.found) {
    for (const Vector3& point : answer.points) {
      result.points.row(p) = point.transpose();
      result.point_pair(p) = row;
      ++p;
    }
    ++row;
  }
  return result;
}

const SceneStats& Scene::stats() const {
  const std::lock_guard<std::mutex> lock(impl_->mutex);
  return impl_->stats;
}

}  // namespace swarmcollide
