#include "swarmcollide/scene/scene.hpp"

#include <algorithm>
#include <array>
#include <limits>
#include <mutex>
#include <sstream>
#include <stdexcept>
#include <string>
#include <unordered_set>
#include <utility>

#include "../queries/dispatch.hpp"
#include "radix_sort.hpp"
#include "scene_impl.hpp"
#include "swarmcollide/queries/batch.hpp"

namespace swarmcollide {

namespace {

using detail::Candidate;
using detail::displacement;
using detail::encloses;
using detail::fatten;
using detail::overlap;
using detail::PairAnswer;
using detail::PairProof;
using detail::PairQuestion;
using detail::padded;
using detail::prefetch_body;
using detail::prefetch_box;
using detail::prefetch_points;
using detail::own_reach;
using detail::refuse_placement;
using detail::SceneBody;
using detail::update_box;
using detail::within_range;

// How many pairs ahead the table's scan asks for the bodies' padded boxes.
constexpr std::size_t kBoxesAhead = 8;

}  // namespace

void Scene::Impl::check_pairs(const std::vector<std::pair<BodyId, BodyId>>& pairs) const {
  for (const auto& [a, b] : pairs) {
    find(a);
    find(b);
    if (a == b) {
      throw std::invalid_argument("pairs lists (" + std::to_string(a) + ", " + std::to_string(b) +
                                  "): a body is never paired with itself; list two ids");
    }
  }
}

void Scene::Impl::require(Capability capability, const char* query) const {
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

void Scene::Impl::fit_boxes(Scalar threshold) {
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
    table.invalidate();
  } else {
    for (SceneBody* b : moved) {
      b->padded = padded(b->box, pad_of(*b, threshold));
      if (encloses(b->object.getAABB(), b->padded)) continue;
      fatten(*b);
      objects.push_back(&b->object);
      table.requery(b);
    }
  }
  moved.clear();
  const bool all = repad || objects.size() * 4 > bodies.size();
  if (all || !objects.empty()) broadphase.refit(objects, all);
}

void Scene::Impl::collect(Scalar threshold) {
  fit_boxes(threshold);
  table.update(broadphase, bodies.size(), next_id, options.warm_start);
}

// Answers the candidates among the table's pairs [begin, end), at most kChunk of them. The
// candidates are sorted out first, then answered, each pass asking for the memory its next
// steps read.
void Scene::Impl::answer_chunk(const PairQuestion& question, std::size_t begin,
                                std::size_t end) {
  ChunkOutput& out = chunk_outputs[begin / kChunk];
  thread_local PairAnswer answer;
  thread_local PairProof unkept;
  const QueryOptions& base = options.query;
  QueryOptions pair_options = base;
  std::array<std::uint32_t, kChunk> picked;
  std::size_t count = 0;
  for (std::size_t i = begin; i < std::min(end, begin + kBoxesAhead); ++i) {
    prefetch_box(table.pairs[i].first);
    prefetch_box(table.pairs[i].second);
  }
  for (std::size_t i = begin; i < end; ++i) {
    if (i + kBoxesAhead < end) {
      prefetch_box(table.pairs[i + kBoxesAhead].first);
      prefetch_box(table.pairs[i + kBoxesAhead].second);
    }
    Candidate& c = table.pairs[i];
    if (overlap(c.first->padded, c.second->padded)) {
      picked[count++] = static_cast<std::uint32_t>(i);
      prefetch_body(c.first);
      prefetch_body(c.second);
      __builtin_prefetch(&table.proofs[i]);
    } else if (c.cached) {
      // Not a candidate: its proof is dropped, as when the broadphase no longer returns a pair.
      table.proofs[i] = PairProof(c.key);
      table.surfaces[i].clear();
      c.cached = false;
    }
  }
  out.tally.candidates += count;
  for (std::size_t k = 0; k < count; ++k) {
    if (k + 2 < count) {
      prefetch_points(table.pairs[picked[k + 2]].first);
      prefetch_points(table.pairs[picked[k + 2]].second);
    }
    Candidate& c = table.pairs[picked[k]];
    PairProof& proof = question.warm ? table.proofs[picked[k]] : unkept;
    if (!question.warm) proof = PairProof(c.key);
    pair_options.seed = pair_seed(base.seed, c.key);
    try {
      detail::answer_pair(
          {&c.first->body, &c.first->pose, c.first->travelled, c.first->compound.get()},
          {&c.second->body, &c.second->pose, c.second->travelled, c.second->compound.get()},
          proof, pair_options, question, answer,
          question.warm ? &table.surfaces[picked[k]] : nullptr);
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
void Scene::Impl::answer(const PairQuestion& asked) {
  const std::size_t n = table.pairs.size();
  PairQuestion question = asked;
  question.warm = asked.warm && options.warm_start;
  chunk_outputs.resize(n / kChunk + 1);
  for (ChunkOutput& out : chunk_outputs) {
    out.size = 0;
    out.tally = SceneStats{};
  }
  // A single-threaded pool takes all the pairs at once; they are still answered a chunk at a
  // time.
  pool.for_each_chunk_paced(n, kChunk, [&](std::size_t first, std::size_t last) {
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
    detail::sort_by_pair_key(found, found_scratch, next_id, [](const Found& f) { return f.first; });
  }
}

void Scene::Impl::tally(SceneStats& s, const PairAnswer& a) {
  s.screened += a.settled == detail::Settled::screened;
  s.warm_bounded += a.settled == detail::Settled::warm_bounded;
  s.warm_rejected += a.settled == detail::Settled::warm_rejected;
  s.warm_proven += a.settled == detail::Settled::warm_proven;
  s.solved += a.settled == detail::Settled::solved || a.settled == detail::Settled::escalated;
  s.escalations += a.settled == detail::Settled::escalated;
  s.certified += a.certified;
}

void Scene::Impl::add(SceneStats& s, const SceneStats& more) {
  s.screened += more.screened;
  s.warm_bounded += more.warm_bounded;
  s.warm_rejected += more.warm_rejected;
  s.warm_proven += more.warm_proven;
  s.solved += more.solved;
  s.escalations += more.escalations;
  s.certified += more.certified;
}

SceneResult Scene::Impl::gather() const {
  SceneResult result = sized(found.size());
  for (std::size_t r = 0; r < found.size(); ++r) {
    const std::uint64_t key = found[r].first;
    put(result, r, detail::key_first(key), detail::key_second(key), *found[r].second);
  }
  return result;
}

SceneResult Scene::Impl::sized(std::size_t rows) {
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

void Scene::Impl::put(SceneResult& result, std::size_t row, BodyId a, BodyId b,
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
    if (!compounds.empty()) {
      detail::require_parts(s.options.query.method, *compounds[i], *compounds[i]);
    }
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
    s.table.add_body(body.get());
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

std::vector<SceneBody*> Scene::Impl::bodies_to_move(const std::vector<BodyId>& ids,
                                                    const std::vector<Pose>& poses) {
  if (ids.size() != poses.size()) {
    throw std::invalid_argument("ids and poses must have the same length, got " +
                                std::to_string(ids.size()) + " and " +
                                std::to_string(poses.size()));
  }
  std::vector<SceneBody*> targets;
  targets.reserve(ids.size());
  for (std::size_t i = 0; i < ids.size(); ++i) {
    targets.push_back(&find(ids[i]));
    validate_pose(poses[i], "poses", i);
    if (!within_range(poses[i])) {
      refuse_placement("poses[" + std::to_string(i) + "] moves body " + std::to_string(ids[i]) +
                           " along an axis by",
                       poses[i].translation.cwiseAbs().maxCoeff());
    }
  }
  // A body given two poses would end at whichever came last, silently. The bodies sorted: a set
  // of ids allocated a node per body of every frame's set_poses.
  std::vector<SceneBody*> sorted = targets;
  std::sort(sorted.begin(), sorted.end());
  const auto twice = std::adjacent_find(sorted.begin(), sorted.end());
  if (twice != sorted.end()) {
    throw std::invalid_argument("ids lists body " + std::to_string((*twice)->id) +
                                " twice; give each body one pose");
  }
  return targets;
}

void Scene::set_poses(const std::vector<BodyId>& ids, const std::vector<Pose>& poses) {
  Impl& s = *impl_;
  const std::lock_guard<std::mutex> lock(s.mutex);
  const std::vector<SceneBody*> targets = s.bodies_to_move(ids, poses);
  for (std::size_t i = 0; i < ids.size(); ++i) s.move_to(*targets[i], poses[i]);
}

void Scene::Impl::move_to(SceneBody& b, const Pose& pose) {
  const Scalar step = displacement(b.body, b.reach, b.pose, pose);
  b.travelled += step;
  b.pose = pose;
  // A body moved twice is boxed once, its steps since the last boxing summed.
  b.step = b.moved ? b.step + step : step;
  if (!b.moved) moved.push_back(&b);
  b.moved = true;
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
  s.table.remove(gone);
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
  s.table.invalidate();
}

void Scene::exclude(const std::vector<std::pair<BodyId, BodyId>>& pairs) {
  Impl& s = *impl_;
  const std::lock_guard<std::mutex> lock(s.mutex);
  s.check_pairs(pairs);
  for (const auto& [a, b] : pairs) s.table.exclude(a, b);
}

void Scene::include(const std::vector<std::pair<BodyId, BodyId>>& pairs) {
  Impl& s = *impl_;
  const std::lock_guard<std::mutex> lock(s.mutex);
  s.check_pairs(pairs);
  for (const auto& [a, b] : pairs) s.table.include(a, b);
}

std::vector<std::pair<BodyId, BodyId>> Scene::excluded() const {
  const std::lock_guard<std::mutex> lock(impl_->mutex);
  return impl_->table.excluded();
}

BodyId Scene::next_id() const {
  const std::lock_guard<std::mutex> lock(impl_->mutex);
  return impl_->next_id;
}

void Scene::skip_ids(BodyId id) {
  Impl& s = *impl_;
  const std::lock_guard<std::mutex> lock(s.mutex);
  if (id < s.next_id) {
    throw std::invalid_argument("skip_ids: id " + std::to_string(id) + " was given out already (" +
                                "the next id is " + std::to_string(s.next_id) + ")");
  }
  // The skipped ids were never given: no slot holds them.
  s.slot.resize(id, Impl::kNoSlot);
  s.next_id = id;
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
  // Summed here, when asked, not by every query: the kept surfaces' sizes are read from every
  // pair's record, and that walk of the table was a third of the misses warm frames of 10,000
  // bodies (with no surface at all) gained after 441b84b (bench/README.md, session 45).
  impl_->stats.cache_bytes = impl_->table.cache_bytes();
  return impl_->stats;
}

}  // namespace swarmcollide
