// A scene's pair table: the pairs the broadphase proposes, with what the last query proved about
// each; private to the library's sources.
#pragma once

#include <cstddef>
#include <cstdint>
#include <unordered_set>
#include <utility>
#include <vector>

#include "../solvers/expanding_polytope.hpp"
#include "fcl_broadphase.hpp"
#include "pair_cache.hpp"
#include "scene_body.hpp"

namespace swarmcollide::detail {

/// A pair of bodies, in id order.
struct Candidate {
  std::uint64_t key;
  const SceneBody* first;
  const SceneBody* second;
  /// In the pair table: the pair's proof is not empty (read with the boxes, so that the scan
  /// touches a proof only to drop it).
  bool cached = false;
};

/// Every pairable pair whose broadphase boxes overlap, once, in no particular order (in key
/// order after it is made afresh), and beside each pair what the last query proved about it
/// (with warm starts; a pair that was not a candidate has no proof). A query sorts out its
/// candidates from the table by their padded boxes, so the broadphase is traversed only when
/// bodies leave their boxes, and a proof stays where it is from frame to frame.
class PairTable {
 public:
  /// The pairs, and `proofs[i]` what the last query proved about `pairs[i]`.
  std::vector<Candidate> pairs;
  std::vector<PairProof> proofs;
  /// `surfaces[i]` the surface of `pairs[i]`'s last expanding polytope, where a contact's depth
  /// kept one (penetration's KeptSurface).
  std::vector<KeptSurface> surfaces;

  /// Whether two broadphase objects make a pair: two bodies whose filters pair them and whose
  /// pair is not excluded. Read from the objects, whose copies of the ids and filters lie beside
  /// the boxes a traversal has just read.
  bool pairable(const BoxedObject& a, const BoxedObject& b) const {
    return a.id != b.id && a.filter.pairs_with(b.filter) &&
           (excluded_.empty() ||
            excluded_.count(pair_key(std::min(a.id, b.id), std::max(a.id, b.id))) == 0);
  }
  /// Never pair `a` and `b` (exclude), or pair them again (include); either remakes the table.
  void exclude(BodyId a, BodyId b);
  void include(BodyId a, BodyId b);
  /// The excluded pairs, the smaller id first, in increasing order.
  std::vector<std::pair<BodyId, BodyId>> excluded() const;

  /// A body just added (ids are handed out in order, from 0): its pairs join at the next update.
  void add_body(SceneBody* body);
  /// The pairs of `body` are out of date: its broadphase box changed.
  void requery(SceneBody* body);
  /// The table is made afresh at the next update (boxes re-padded, filters changed).
  void invalidate() { stale_ = true; }
  /// Brings the table up to date with `broadphase`, whose objects' ids are below `id_limit`. It
  /// is made afresh when stale or when more than a quarter of the `body_count` bodies left their
  /// boxes: one traversal then costs less than a query per body. With `warm_start`, the pairs it
  /// held keep their proofs.
  void update(FclBroadphase& broadphase, std::size_t body_count, BodyId id_limit,
              bool warm_start);
  /// Drops the bodies of ids `gone`: their pairs, their requeries and their exclusions.
  void remove(const std::unordered_set<BodyId>& gone);
  /// How many pairs have a proof.
  std::size_t cached_pairs() const;
  /// The bytes the proofs and the kept surfaces take.
  std::size_t cache_bytes() const;

 private:
  void add_pair(const BoxedObject* a, const BoxedObject* b, std::vector<Candidate>& out) const;
  // By key, then without repeats.
  void sort_pairs(std::vector<Candidate>& found, BodyId id_limit);
  // The table from a traversal of the whole broadphase, in key order.
  void remake(FclBroadphase& broadphase, BodyId id_limit, bool warm_start);
  // The table after the requeried bodies changed their broadphase boxes (or arrived): their
  // pairs are asked of the broadphase again; those still there keep their places and proofs,
  // the others leave, and new ones are appended.
  void requery_pairs(FclBroadphase& broadphase, BodyId id_limit);

  std::unordered_set<std::uint64_t> excluded_;
  // Bodies whose pairs are out of date, and the same as a flag per id, which the table's keys
  // name without touching the bodies.
  std::vector<SceneBody*> requeried_bodies_;
  std::vector<std::uint8_t> requeried_;
  bool stale_ = true;
  // Buffers reused from update to update.
  std::vector<ObjectPair> overlaps_;
  std::vector<Candidate> fresh_;
  std::vector<Candidate> sorted_;
  std::vector<std::uint8_t> kept_;
  std::vector<std::pair<std::uint64_t, std::uint32_t>> order_;
  std::vector<std::pair<std::uint64_t, std::uint32_t>> order_scratch_;
  std::vector<PairProof> new_proofs_;
  std::vector<KeptSurface> new_surfaces_;
};

}  // namespace swarmcollide::detail
