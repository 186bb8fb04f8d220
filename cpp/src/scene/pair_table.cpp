#include "pair_table.hpp"

#include <algorithm>

#include "radix_sort.hpp"

namespace swarmcollide::detail {

void PairTable::exclude(BodyId a, BodyId b) {
  excluded_.insert(pair_key(std::min(a, b), std::max(a, b)));
  stale_ = true;
}

void PairTable::include(BodyId a, BodyId b) {
  excluded_.erase(pair_key(std::min(a, b), std::max(a, b)));
  stale_ = true;
}

std::vector<std::pair<BodyId, BodyId>> PairTable::excluded() const {
  std::vector<std::uint64_t> keys(excluded_.begin(), excluded_.end());
  std::sort(keys.begin(), keys.end());
  std::vector<std::pair<BodyId, BodyId>> pairs;
  pairs.reserve(keys.size());
  for (std::uint64_t key : keys) pairs.emplace_back(key_first(key), key_second(key));
  return pairs;
}

void PairTable::add_body(SceneBody* body) {
  if (requeried_.size() <= body->id) requeried_.resize(body->id + std::size_t{1}, 0);
  requery(body);
}

void PairTable::requery(SceneBody* body) {
  if (requeried_[body->id]) return;
  requeried_[body->id] = 1;
  requeried_bodies_.push_back(body);
}

void PairTable::update(FclBroadphase& broadphase, std::size_t body_count, BodyId id_limit,
                       bool warm_start) {
  if (stale_ || requeried_bodies_.size() * 4 > body_count) {
    remake(broadphase, id_limit, warm_start);
  } else if (!requeried_bodies_.empty()) {
    requery_pairs(broadphase, id_limit);
  }
  for (SceneBody* b : requeried_bodies_) requeried_[b->id] = 0;
  requeried_bodies_.clear();
  stale_ = false;
}

void PairTable::remove(const std::unordered_set<BodyId>& gone) {
  const auto leaving = [&](const SceneBody* b) { return gone.count(b->id) > 0; };
  requeried_bodies_.erase(
      std::remove_if(requeried_bodies_.begin(), requeried_bodies_.end(), leaving),
      requeried_bodies_.end());
  for (BodyId id : gone) requeried_[id] = 0;
  const auto involves = [&](std::uint64_t key) {
    return gone.count(key_first(key)) > 0 || gone.count(key_second(key)) > 0;
  };
  std::size_t kept = 0;
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    if (involves(pairs[i].key)) continue;
    pairs[kept] = pairs[i];
    proofs[kept] = proofs[i];
    std::swap(surfaces[kept], surfaces[i]);
    ++kept;
  }
  pairs.resize(kept);
  proofs.resize(kept);
  surfaces.resize(kept);
  for (auto it = excluded_.begin(); it != excluded_.end();) {
    it = involves(*it) ? excluded_.erase(it) : std::next(it);
  }
}

std::size_t PairTable::cached_pairs() const {
  return static_cast<std::size_t>(
      std::count_if(proofs.begin(), proofs.end(),
                    [](const PairProof& p) { return p.kind != PairProof::Kind::none; }));
}

std::size_t PairTable::cache_bytes() const {
  std::size_t bytes =
      proofs.capacity() * sizeof(PairProof) + surfaces.capacity() * sizeof(KeptSurface);
  for (const KeptSurface& s : surfaces) {
    bytes += s.corners.capacity() * sizeof(s.corners[0]) + s.faces.capacity() * sizeof(s.faces[0]);
  }
  return bytes;
}

void PairTable::add_pair(const BoxedObject* a, const BoxedObject* b,
                         std::vector<Candidate>& out) const {
  if (!pairable(*a, *b)) return;
  if (b->id < a->id) std::swap(a, b);
  out.push_back({pair_key(a->id, b->id), static_cast<const SceneBody*>(a->owner()),
                 static_cast<const SceneBody*>(b->owner())});
}

void PairTable::sort_pairs(std::vector<Candidate>& found, BodyId id_limit) {
  sort_by_pair_key(found, sorted_, id_limit, [](const Candidate& c) { return c.key; });
  found.erase(std::unique(found.begin(), found.end(),
                          [](const Candidate& x, const Candidate& y) { return x.key == y.key; }),
              found.end());
}

void PairTable::remake(FclBroadphase& broadphase, BodyId id_limit, bool warm_start) {
  overlaps_.clear();
  broadphase.overlapping_pairs(overlaps_);
  fresh_.clear();
  for (const auto& [p, q] : overlaps_) add_pair(p, q, fresh_);
  sort_pairs(fresh_, id_limit);
  new_proofs_.clear();
  new_proofs_.reserve(fresh_.size());
  new_surfaces_.clear();
  new_surfaces_.resize(fresh_.size());
  if (warm_start && !pairs.empty()) {
    order_.clear();
    for (std::size_t i = 0; i < pairs.size(); ++i) {
      order_.emplace_back(pairs[i].key, static_cast<std::uint32_t>(i));
    }
    sort_by_pair_key(order_, order_scratch_, id_limit, [](const auto& o) { return o.first; });
    auto old = order_.begin();
    for (Candidate& c : fresh_) {
      while (old != order_.end() && old->first < c.key) ++old;
      if (old != order_.end() && old->first == c.key) {
        std::swap(new_surfaces_[new_proofs_.size()], surfaces[old->second]);
        new_proofs_.push_back(proofs[old->second]);
        c.cached = pairs[old->second].cached;
      } else {
        new_proofs_.emplace_back(c.key);
      }
    }
  } else {
    for (const Candidate& c : fresh_) new_proofs_.emplace_back(c.key);
  }
  pairs.swap(fresh_);
  proofs.swap(new_proofs_);
  surfaces.swap(new_surfaces_);
}

void PairTable::requery_pairs(FclBroadphase& broadphase, BodyId id_limit) {
  fresh_.clear();
  for (SceneBody* b : requeried_bodies_) {
    overlaps_.clear();
    broadphase.overlapping(&b->object, overlaps_);
    for (const auto& [self, other] : overlaps_) add_pair(self, other, fresh_);
  }
  // A pair of two such bodies is found from both.
  sort_pairs(fresh_, id_limit);
  kept_.assign(fresh_.size(), 0);
  for (std::size_t i = 0; i < pairs.size();) {
    const std::uint64_t key = pairs[i].key;
    if (!requeried_[key_first(key)] && !requeried_[key_second(key)]) {
      ++i;
      continue;
    }
    const auto at = std::lower_bound(fresh_.begin(), fresh_.end(), key,
                                     [](const Candidate& c, std::uint64_t k) { return c.key < k; });
    if (at != fresh_.end() && at->key == key) {
      kept_[at - fresh_.begin()] = 1;
      ++i;
      continue;
    }
    pairs[i] = pairs.back();
    pairs.pop_back();
    proofs[i] = proofs.back();
    proofs.pop_back();
    std::swap(surfaces[i], surfaces.back());
    surfaces.pop_back();
  }
  for (std::size_t j = 0; j < fresh_.size(); ++j) {
    if (kept_[j]) continue;
    pairs.push_back(fresh_[j]);
    proofs.emplace_back(fresh_[j].key);
    surfaces.emplace_back();
  }
}

}  // namespace swarmcollide::detail
