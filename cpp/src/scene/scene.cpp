#include "swarmcollide/scene/scene.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <mutex>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <unordered_set>
#include <utility>

#include "../queries/dispatch.hpp"
#include "fcl_broadphase.hpp"
#include "narrowphase.hpp"
#include "pair_cache.hpp"
#include "scene_body.hpp"
#include "swarmcollide/queries/batch.hpp"
#include "swarmcollide/queries/methods.hpp"
#include "thread_pool.hpp"

namespace swarmcollide {

namespace {

using detail::displacement;
using detail::encloses;
using detail::fatten;
using detail::overlap;
using detail::PairAnswer;
using detail::PairProof;
using detail::PairQuestion;
using detail::padded;
using detail::padding;
using detail::prefetch_body;
using detail::prefetch_box;
using detail::prefetch_points;
using detail::own_reach;
using detail::refuse_placement;
using detail::SceneBody;
using detail::update_box;
using detail::within_range;

constexpr Scalar kEpsilon = std::numeric_limits<Scalar>::epsilon();
// Pairs a thread takes at a time: enough to make taking them cheap, few enough to balance.
constexpr std::size_t kChunk = 32;
// How many pairs ahead the table's scan asks for the bodies' padded boxes.
constexpr std::size_t kBoxesAhead = 8;

// A pair of bodies, in id order.
struct Candidate {
  std::uint64_t key;
  const SceneBody* first;
  const SceneBody* second;
  /// In the pair table: the pair's proof is not empty (read with the boxes, so that the scan
  /// touches a proof only to drop it).
  bool cached = false;
};

// Sorts `items` by `rank(item)`, a number below 2^bits, with a least-significant-digit radix
// sort through `scratch`: a frame sorts tens of thousands of pairs, where comparison sorting took
// a tenth of the frame.
template <typename T, typename Rank>
void radix_sort(std::vector<T>& items, std::vector<T>& scratch, int bits, const Rank& rank) {
  constexpr int kDigit = 11;
  constexpr std::size_t kBuckets = std::size_t{1} << kDigit;
  scratch.resize(items.size());
  for (int shift = 0; shift < bits; shift += kDigit) {
    std::array<std::size_t, kBuckets + 1> start{};
    for (const T& item : items) ++start[((rank(item) >> shift) & (kBuckets - 1)) + 1];
    for (std::size_t d = 1; d <= kBuckets; ++d) start[d] += start[d - 1];
    for (const T& item : items) scratch[start[(rank(item) >> shift) & (kBuckets - 1)]++] = item;
    items.swap(scratch);
  }
}

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
  // Bodies moved since their boxes were computed.
  std::vector<SceneBody*> moved;
  // The threshold the bodies' padded boxes are padded for.
  Scalar padded_for = 0;
  std::unordered_set<std::uint64_t> excluded;
  // The pair table: every pairable pair whose broadphase boxes overlap, once, in no particular
  // order (in key order after it is made afresh), and beside each pair what the last query proved
  // about it (with warm starts; a pair that was not a candidate has no proof). A query sorts out
  // its candidates from the table by their padded boxes, so the broadphase is traversed only when
  // bodies leave their boxes, and a proof stays where it is from frame to frame.
  std::vector<Candidate> table;
  std::vector<PairProof> proofs;
  // Bodies whose pairs in the table are out of date (added, or their broadphase box changed),
  // and the same as a flag per id, which the table's keys name without touching the bodies.
  std::vector<SceneBody*> requery;
  std::vector<std::uint8_t> requeried;
  // The table is made afresh at the next query (boxes re-padded, filters or exclusions changed).
  bool table_stale = true;
  SceneStats stats;
  // Buffers reused from query to query.
  std::vector<detail::ObjectPair> overlaps;
  std::vector<Candidate> fresh;
  std::vector<Candidate> sorted;
  std::vector<std::uint8_t> kept;
  std::vector<std::pair<std::uint64_t, std::uint32_t>> order;
  std::vector<std::pair<std::uint64_t, std::uint32_t>> order_scratch;
  std::vector<PairProof> new_proofs;
  // What `answer` found, chunk by chunk (each chunk's pairs that belong, with their keys, and how
  // every pair was settled), then all in key order. Only the pairs that belong are kept: at
  // 10,000 bodies a frame has 50,000 candidates and a third of them belong.
  // `found` holds `size` answers; the entries past it are kept with their contact point buffers,
  // which the next query's answers take over instead of allocating their own.
  struct ChunkOutput {
    std::vector<std::pair<std::uint64_t, PairAnswer>> found;
    std::size_t size = 0;
    SceneStats tally;
  };
  std::vector<ChunkOutput> chunk_outputs;
  using Found = std::pair<std::uint64_t, const PairAnswer*>;
  std::vector<Found> found;
  std::vector<Found> found_scratch;
  // `nearest`'s candidates and answers, one per candidate.
  std::vector<Candidate> candidates;
  std::vector<PairAnswer> answers;

  SceneBody& find(BodyId id) {
    if (id >= slot.size() || slot[id] == kNoSlot) throw std::invalid_argument(unknown_id(id));
    return *bodies[slot[id]];
  }
  const SceneBody& find(BodyId id) const { return const_cast<Impl*>(this)->find(id); }

  // Throws std::invalid_argument for a pair of an unknown body or of a body with itself.
  void check_pairs(const std::vector<std::pair<BodyId, BodyId>>& pairs) const {
    for (const auto& [a, b] : pairs) {
      find(a);
      find(b);
      if (a == b) {
        throw std::invalid_argument("pairs lists (" + std::to_string(a) + ", " +
                                    std::to_string(b) +
                                    "): a body is never paired with itself; list two ids");
      }
    }
  }

  Scalar pad_of(const SceneBody& b, Scalar threshold) const {
    return padding(threshold, b.body.bounds().radius, options.query.tolerance);
  }

  // The significant bits of an id, and a pair's key as a number of twice as many bits that
  // sorts as the key does.
  int id_bits() const {
    int bits = 1;
    while ((std::uint64_t{1} << bits) < next_id) ++bits;
    return bits;
  }

  void mark_requery(SceneBody* b) {
    if (requeried[b->id]) return;
    requeried[b->id] = 1;
    requery.push_back(b);
  }

  // Brings the padded boxes up to date for queries at `threshold`, and the broadphase's boxes
  // where the padded ones left them.
  void fit_boxes(Scalar threshold) {
    for (SceneBody* b : moved) {
      update_box(*b);
      b->moved = false;
    }
    const bool repad = threshold != padded_for;
    padded_for = threshold;
    std::vector<detail::BoxedObject*> objects;
    if (repad) {
      for (auto& b : bodies) {
        b->padded = padded(b->box, pad_of(*b, threshold));
        fatten(*b);
      }
      table_stale = true;
    } else {
      for (SceneBody* b : moved) {
        b->padded = padded(b->box, pad_of(*b, threshold));
        if (encloses(b->object.getAABB(), b->padded)) continue;
        fatten(*b);
        objects.push_back(&b->object);
        mark_requery(b);
      }
    }
    moved.clear();
    const bool all = repad || objects.size() * 4 > bodies.size();
    if (all || !objects.empty()) broadphase.refit(objects, all);
  }

  // Read from the broadphase's objects, whose copies of the ids and filters lie beside the boxes
  // the traversal has just read.
  bool pairable(const detail::BoxedObject& a, const detail::BoxedObject& b) const {
    return a.id != b.id && a.filter.pairs_with(b.filter) &&
           (excluded.empty() ||
            excluded.count(detail::pair_key(std::min(a.id, b.id), std::max(a.id, b.id))) == 0);
  }

  void add_pair(const detail::BoxedObject* a, const detail::BoxedObject* b,
                std::vector<Candidate>& out) const {
    if (!pairable(*a, *b)) return;
    if (b->id < a->id) std::swap(a, b);
    out.push_back({detail::pair_key(a->id, b->id), static_cast<const SceneBody*>(a->owner()),
                   static_cast<const SceneBody*>(b->owner())});
  }

  // By key, then without repeats.
  void sort_pairs(std::vector<Candidate>& pairs) {
    const int bits = id_bits();
    radix_sort(pairs, sorted, 2 * bits, [bits](const Candidate& c) {
      return (static_cast<std::uint64_t>(detail::key_first(c.key)) << bits) |
             detail::key_second(c.key);
    });
    pairs.erase(std::unique(pairs.begin(), pairs.end(),
                            [](const Candidate& x, const Candidate& y) { return x.key == y.key; }),
                pairs.end());
  }

  // The table from a traversal of the whole broadphase, in key order; with warm starts, the
  // proofs of pairs it held already carried over.
  void remake_table() {
    overlaps.clear();
    broadphase.overlapping_pairs(overlaps);
    fresh.clear();
    for (const auto& [p, q] : overlaps) add_pair(p, q, fresh);
    sort_pairs(fresh);
    new_proofs.clear();
    new_proofs.reserve(fresh.size());
    if (options.warm_start && !table.empty()) {
      order.clear();
      for (std::size_t i = 0; i < table.size(); ++i) {
        order.emplace_back(table[i].key, static_cast<std::uint32_t>(i));
      }
      const int bits = id_bits();
      radix_sort(order, order_scratch, 2 * bits, [bits](const auto& o) {
        return (static_cast<std::uint64_t>(detail::key_first(o.first)) << bits) |
               detail::key_second(o.first);
      });
      auto old = order.begin();
      for (Candidate& c : fresh) {
        while (old != order.end() && old->first < c.key) ++old;
        if (old != order.end() && old->first == c.key) {
          new_proofs.push_back(proofs[old->second]);
          c.cached = table[old->second].cached;
        } else {
          new_proofs.emplace_back(c.key);
        }
      }
    } else {
      for (const Candidate& c : fresh) new_proofs.emplace_back(c.key);
    }
    table.swap(fresh);
    proofs.swap(new_proofs);
  }

  // The table after the bodies in `requery` changed their broadphase boxes (or arrived): their
  // pairs are asked of the broadphase again; those still there keep their places and proofs,
  // the others leave, and new ones are appended.
  void requery_table() {
    fresh.clear();
    for (SceneBody* b : requery) {
      overlaps.clear();
      broadphase.overlapping(&b->object, overlaps);
      for (const auto& [self, other] : overlaps) add_pair(self, other, fresh);
    }
    // A pair of two such bodies is found from both.
    sort_pairs(fresh);
    kept.assign(fresh.size(), 0);
    for (std::size_t i = 0; i < table.size();) {
      const std::uint64_t key = table[i].key;
      if (!requeried[detail::key_first(key)] && !requeried[detail::key_second(key)]) {
        ++i;
        continue;
      }
      const auto at =
          std::lower_bound(fresh.begin(), fresh.end(), key,
                           [](const Candidate& c, std::uint64_t k) { return c.key < k; });
      if (at != fresh.end() && at->key == key) {
        kept[at - fresh.begin()] = 1;
        ++i;
        continue;
      }
      table[i] = table.back();
      table.pop_back();
      proofs[i] = proofs.back();
      proofs.pop_back();
    }
    for (std::size_t j = 0; j < fresh.size(); ++j) {
      if (kept[j]) continue;
      table.push_back(fresh[j]);
      proofs.emplace_back(fresh[j].key);
    }
  }

  // Brings the boxes and the pair table up to date for a query at `threshold`. The table is
  // made afresh when many bodies left their boxes: one traversal then costs less than a query
  // per body.
  void collect(Scalar threshold) {
    fit_boxes(threshold);
    if (table_stale || requery.size() * 4 > bodies.size()) {
      remake_table();
    } else if (!requery.empty()) {
      requery_table();
    }
    for (SceneBody* b : requery) requeried[b->id] = 0;
    requery.clear();
    table_stale = false;
  }

  std::size_t cached_pairs() const {
    return static_cast<std::size_t>(
        std::count_if(proofs.begin(), proofs.end(),
                      [](const PairProof& p) { return p.kind != PairProof::Kind::none; }));
  }

  // Answers the candidates among the table's pairs [begin, end), at most kChunk of them. The
  // candidates are sorted out first, then answered, each pass asking for the memory its next
  // steps read.
  void answer_chunk(const PairQuestion& question, std::size_t begin, std::size_t end) {
    ChunkOutput& out = chunk_outputs[begin / kChunk];
    thread_local PairAnswer answer;
    thread_local PairProof unkept;
    const QueryOptions& base = options.query;
    QueryOptions pair_options = base;
    std::array<std::uint32_t, kChunk> picked;
    std::size_t count = 0;
    for (std::size_t i = begin; i < std::min(end, begin + kBoxesAhead); ++i) {
      prefetch_box(table[i].first);
      prefetch_box(table[i].second);
    }
    for (std::size_t i = begin; i < end; ++i) {
      if (i + kBoxesAhead < end) {
        prefetch_box(table[i + kBoxesAhead].first);
        prefetch_box(table[i + kBoxesAhead].second);
      }
      Candidate& c = table[i];
      if (overlap(c.first->padded, c.second->padded)) {
        picked[count++] = static_cast<std::uint32_t>(i);
        prefetch_body(c.first);
        prefetch_body(c.second);
        __builtin_prefetch(&proofs[i]);
      } else if (c.cached) {
        // Not a candidate: its proof is dropped, as when the broadphase no longer returns a pair.
        proofs[i] = PairProof(c.key);
        c.cached = false;
      }
    }
    out.tally.candidates += count;
    for (std::size_t k = 0; k < count; ++k) {
      if (k + 2 < count) {
        prefetch_points(table[picked[k + 2]].first);
        prefetch_points(table[picked[k + 2]].second);
      }
      Candidate& c = table[picked[k]];
      PairProof& proof = question.warm ? proofs[picked[k]] : unkept;
      if (!question.warm) proof = PairProof(c.key);
      pair_options.seed = pair_seed(base.seed, c.key);
      try {
        detail::answer_pair(
            {&c.first->body, &c.first->pose, c.first->travelled, c.first->compound.get()},
            {&c.second->body, &c.second->pose, c.second->travelled, c.second->compound.get()},
            proof, pair_options, question, answer);
      } catch (const std::invalid_argument& error) {
        throw std::invalid_argument("bodies " + std::to_string(c.first->id) + " and " +
                                    std::to_string(c.second->id) + ": " + error.what());
      }
      tally(out.tally, answer);
      if (question.warm) {
        c.cached = proof.kind != PairProof::Kind::none;
        out.tally.cached_pairs += c.cached;
      }
      if (answer.belongs) {
        if (out.size == out.found.size()) out.found.emplace_back();
        out.found[out.size].first = c.key;
        // The reused buffer goes back to `answer`, which answer_pair clears.
        std::swap(out.found[out.size].second, answer);
        ++out.size;
      }
    }
  }

  // Answers `question` for every candidate of the table, the pairs whose padded boxes overlap, on
  // the pool. With warm starts, each candidate's proof is tried first and replaced by what its
  // answer proves; the proofs of the table's other pairs are dropped, as they would be if the
  // broadphase no longer returned the pair.
  void answer(const PairQuestion& asked) {
    const std::size_t n = table.size();
    PairQuestion question = asked;
    question.warm = asked.warm && options.warm_start;
    chunk_outputs.resize(n / kChunk + 1);
    for (ChunkOutput& out : chunk_outputs) {
      out.size = 0;
      out.tally = SceneStats{};
    }
    // A single-threaded pool takes all the pairs at once; they are still answered a chunk at a
    // time.
    pool.for_each_chunk(n, kChunk, [&](std::size_t first, std::size_t last) {
      for (std::size_t begin = first; begin < last; begin += kChunk) {
        answer_chunk(question, begin, std::min(last, begin + kChunk));
      }
    });
    found.clear();
    stats = SceneStats{};
    for (ChunkOutput& out : chunk_outputs) {
      for (std::size_t k = 0; k < out.size; ++k) {
        found.emplace_back(out.found[k].first, &out.found[k].second);
      }
      add(stats, out.tally);
      stats.candidates += out.tally.candidates;
      stats.cached_pairs += out.tally.cached_pairs;
    }
    // In key order: the table is, except for pairs appended since it was made.
    const auto by_key = [](const Found& x, const Found& y) { return x.first < y.first; };
    if (!std::is_sorted(found.begin(), found.end(), by_key)) {
      const int bits = id_bits();
      radix_sort(found, found_scratch, 2 * bits, [bits](const Found& f) {
        return (static_cast<std::uint64_t>(detail::key_first(f.first)) << bits) |
               detail::key_second(f.first);
      });
    }
    stats.cache_bytes = proofs.capacity() * sizeof(PairProof);
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

  // The answers that belong, in key order.
  SceneResult gather() const {
    SceneResult result = sized(found.size());
    for (std::size_t r = 0; r < found.size(); ++r) {
      const std::uint64_t key = found[r].first;
      put(result, r, detail::key_first(key), detail::key_second(key), *found[r].second);
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
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    detail::require_shapes(s.options.query.method, bodies[i], bodies[i]);
    const Scalar reach = own_reach(bodies[i]);
    if (!(reach <= kMaxSceneCoordinate / 2)) {
      refuse_placement("bodies[" + std::to_string(i) + "] reaches from its own origin to", reach);
    }
    if (!poses.empty() && !within_range(poses[i])) {
      refuse_placement("poses[" + std::to_string(i) + "] moves its body along an axis by",
                       poses[i].translation.cwiseAbs().maxCoeff());
    }
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
    body->padded = padded(body->box, s.pad_of(*body, s.padded_for));
    // No margin until it moves.
    body->object.set_box(body->padded);
    objects.push_back(&body->object);
    s.slot.push_back(static_cast<std::uint32_t>(s.bodies.size()));
    s.requeried.push_back(0);
    s.mark_requery(body.get());
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
    if (!within_range(poses[i])) {
      refuse_placement("poses[" + std::to_string(i) + "] moves body " + std::to_string(ids[i]) +
                           " along an axis by",
                       poses[i].translation.cwiseAbs().maxCoeff());
    }
  }
  for (std::size_t i = 0; i < ids.size(); ++i) {
    SceneBody& b = *targets[i];
    const Scalar step = displacement(b.body, b.reach, b.pose, poses[i]);
    b.travelled += step;
    b.pose = poses[i];
    // A body moved twice is boxed once, its steps since the last boxing summed.
    b.step = b.moved ? b.step + step : step;
    if (!b.moved) s.moved.push_back(&b);
    b.moved = true;
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
  const auto leaving = [&](const SceneBody* b) { return gone.count(b->id) > 0; };
  s.moved.erase(std::remove_if(s.moved.begin(), s.moved.end(), leaving), s.moved.end());
  s.requery.erase(std::remove_if(s.requery.begin(), s.requery.end(), leaving), s.requery.end());
  for (BodyId id : ids) s.requeried[id] = 0;
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
  std::size_t kept = 0;
  for (std::size_t i = 0; i < s.table.size(); ++i) {
    if (involves(s.table[i].key)) continue;
    s.table[kept] = s.table[i];
    s.proofs[kept] = s.proofs[i];
    ++kept;
  }
  s.table.resize(kept);
  s.proofs.resize(kept);
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
  s.table_stale = true;
}

void Scene::exclude(const std::vector<std::pair<BodyId, BodyId>>& pairs) {
  Impl& s = *impl_;
  const std::lock_guard<std::mutex> lock(s.mutex);
  s.check_pairs(pairs);
  for (const auto& [a, b] : pairs)
    s.excluded.insert(detail::pair_key(std::min(a, b), std::max(a, b)));
  s.table_stale = true;
}

void Scene::include(const std::vector<std::pair<BodyId, BodyId>>& pairs) {
  Impl& s = *impl_;
  const std::lock_guard<std::mutex> lock(s.mutex);
  s.check_pairs(pairs);
  for (const auto& [a, b] : pairs)
    s.excluded.erase(detail::pair_key(std::min(a, b), std::max(a, b)));
  s.table_stale = true;
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
  if (!(distance >= 0) || !(distance <= kMaxSceneCoordinate)) {
    std::ostringstream message;
    message << "distance must be a number in [0, " << kMaxSceneCoordinate << "], got " << distance;
    throw std::invalid_argument(message.str());
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
  // The extent of the bodies where they are now, not where the last query left them.
  fit_boxes(padded_for);
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
    const Found* best = nullptr;
    for (const Found& f : found) {
      if (best == nullptr || f.second->distance < best->second->distance) best = &f;
    }
    if (best != nullptr) {
      SceneResult result = sized(1);
      put(result, 0, detail::key_first(best->first), detail::key_second(best->first),
          *best->second);
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
  fit_boxes(padded_for);
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
      const Aabb probe_box = padded(b.box, pad);
      probe.set_box(probe_box);
      overlaps.clear();
      broadphase.overlapping(&probe, overlaps);
      for (const auto& [self, other] : overlaps) {
        if (!pairable(probe, *other)) continue;
        const auto* o = static_cast<const SceneBody*>(other->owner());
        // The broadphase holds boxes with margins; the candidates are those whose padded boxes
        // overlap the probe.
        if (!overlap(probe_box, o->padded)) continue;
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
    stats.candidates = candidates.size();
    stats.cached_pairs = cached_pairs();
    stats.cache_bytes = proofs.capacity() * sizeof(PairProof);
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
  for (const auto& [key, answer] : s.found) {
    result.offsets(row) = static_cast<std::int64_t>(total);
    result.counts(row) = static_cast<int>(answer->points.size());
    total += answer->points.size();
    ++row;
  }
  result.points.resize(static_cast<Eigen::Index>(total), 3);
  result.point_pair.resize(static_cast<Eigen::Index>(total));
  Eigen::Index p = 0;
  row = 0;
  for (const auto& [key, answer] : s.found) {
    for (const Vector3& point : answer->points) {
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
