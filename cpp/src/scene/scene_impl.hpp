// What a Scene holds: its bodies, the broadphase, the pair table and the buffers its queries
// reuse; private to the library's sources (scene.cpp answers pairs, scene_search.cpp searches).
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "fcl_broadphase.hpp"
#include "narrowphase.hpp"
#include "pair_cache.hpp"
#include "pair_table.hpp"
#include "scene_body.hpp"
#include "swarmcollide/queries/methods.hpp"
#include "swarmcollide/scene/scene.hpp"
#include "../detail/hardware_threads.hpp"
#include "../detail/thread_pool.hpp"

namespace swarmcollide {

struct Scene::Impl {
  explicit Impl(const SceneOptions& o)
      : options(o),
        broadphase(o.broadphase),
        pool(o.threads > 0 ? o.threads
                           : static_cast<int>(detail::hardware_threads())) {}

  /// Pairs a thread takes at a time: enough to make taking them cheap, few enough to balance.
  static constexpr std::size_t kChunk = 32;

  SceneOptions options;
  mutable std::mutex mutex;
  std::vector<std::unique_ptr<detail::SceneBody>> bodies;
  // The slot in `bodies` of each id ever given, kNoSlot once removed: ids are handed out in
  // order, so a vector is the map (four bytes per id ever given), and moving every body a frame
  // costs no hashing.
  static constexpr std::uint32_t kNoSlot = 0xFFFFFFFFu;
  std::vector<std::uint32_t> slot;
  BodyId next_id = 0;
  detail::FclBroadphase broadphase;
  detail::ThreadPool pool;
  // Bodies moved since their boxes were computed.
  std::vector<detail::SceneBody*> moved;
  // The threshold the bodies' padded boxes are padded for.
  Scalar padded_for = 0;
  detail::PairTable table;
  SceneStats stats;
  // What `answer` found, chunk by chunk (each chunk's pairs that belong, with their keys, and how
  // every pair was settled), then all in key order. Only the pairs that belong are kept: at
  // 10,000 bodies a frame has 50,000 candidates and a third of them belong.
  // `found` holds `size` answers; the entries past it are kept with their contact point buffers,
  // which the next query's answers take over instead of allocating their own.
  struct ChunkOutput {
    std::vector<std::pair<std::uint64_t, detail::PairAnswer>> found;
    std::size_t size = 0;
    SceneStats tally;
  };
  std::vector<ChunkOutput> chunk_outputs;
  using Found = std::pair<std::uint64_t, const detail::PairAnswer*>;
  std::vector<Found> found;
  std::vector<Found> found_scratch;
  // `nearest`'s broadphase probes, candidates and answers, one per candidate.
  std::vector<detail::ObjectPair> overlaps;
  std::vector<detail::Candidate> candidates;
  std::vector<detail::PairAnswer> answers;

  detail::SceneBody& find(BodyId id) {
    if (id >= slot.size() || slot[id] == kNoSlot) {
      throw std::invalid_argument("no body with id " + std::to_string(id) + " in the scene");
    }
    return *bodies[slot[id]];
  }
  const detail::SceneBody& find(BodyId id) const { return const_cast<Impl*>(this)->find(id); }
  // Throws std::invalid_argument for a pair of an unknown body or of a body with itself.
  void check_pairs(const std::vector<std::pair<BodyId, BodyId>>& pairs) const;
  Scalar pad_of(const detail::SceneBody& b, Scalar threshold) const {
    return detail::padding(threshold, b.body.bounds().radius, options.query.tolerance);
  }
  // Throws std::invalid_argument when the scene's method cannot answer `query`.
  void require(Capability capability, const char* query) const;

  // Adds bodies (with their compound bodies, none for convex ones); the caller holds the lock.
  std::vector<BodyId> add(std::vector<ConvexPolyhedron> bodies,
                          std::vector<std::shared_ptr<const CompoundBody>> compounds,
                          const std::vector<Pose>& poses, const BodyFilter& filter);
  // The bodies `ids` names, each once, for the new poses `poses` (one each), which are checked:
  // rigid, and within the range the scene can place. Throws std::invalid_argument naming the
  // first fault.
  std::vector<detail::SceneBody*> bodies_to_move(const std::vector<BodyId>& ids,
                                                 const std::vector<Pose>& poses);
  // Puts `b` at `pose` (checked by the caller), adding its step to its odometer and listing it
  // among the moved bodies.
  void move_to(detail::SceneBody& b, const Pose& pose);
  // Brings the padded boxes up to date for queries at `threshold`, and the broadphase's boxes
  // where the padded ones left them.
  void fit_boxes(Scalar threshold);
  // Brings the boxes and the pair table up to date for a query at `threshold`.
  void collect(Scalar threshold);
  // Answers `question` for every candidate of the table, the pairs whose padded boxes overlap,
  // on the pool, into `found` in key order and `stats`.
  void answer(const detail::PairQuestion& asked);
  // The candidates among the table's pairs [begin, end), at most kChunk of them.
  void answer_chunk(const detail::PairQuestion& question, std::size_t begin, std::size_t end);
  // The answers that belong, in key order.
  SceneResult gather() const;

  // The threshold searches (scene_search.cpp).
  SceneResult min_distance();
  SceneResult nearest(const std::vector<BodyId>& ids, int k);
  // The largest distance between two points of any two boxes: a threshold beyond which every
  // pair is a candidate and within it.
  Scalar extent() const;
  // The threshold after `threshold` for searches that found too little: twice as far, starting
  // from the median body radius (from 1 when every body is one point: the scene's extent is then
  // zero, and any positive threshold covers it).
  Scalar next_threshold(Scalar threshold) const;

  static void tally(SceneStats& s, const detail::PairAnswer& a);
  static void add(SceneStats& s, const SceneStats& more);
  static SceneResult sized(std::size_t rows);
  static void put(SceneResult& result, std::size_t row, BodyId a, BodyId b,
                  const detail::PairAnswer& answer);
  // The answer for the pair in the other order: A and B swapped, vectors reversed.
  static void turn_around(detail::PairAnswer& answer) {
    std::swap(answer.point_a, answer.point_b);
    answer.normal = -answer.normal;
  }
};

}  // namespace swarmcollide
