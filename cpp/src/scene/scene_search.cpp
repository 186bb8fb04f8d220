// The scene's threshold searches: pairs within a threshold of each other, the threshold raised
// until enough are found (min_distance, nearest).
#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "../geometry/unit_direction.hpp"
#include "scene_impl.hpp"
#include "swarmcollide/queries/batch.hpp"

namespace swarmcollide {

using detail::Candidate;
using detail::overlap;
using detail::PairAnswer;
using detail::PairProof;
using detail::PairQuestion;
using detail::padded;
using detail::SceneBody;

Scalar Scene::Impl::extent() const {
  // nearest([]) asks it of an empty scene, which has no extent.
  if (bodies.empty()) return 0;
  Aabb all = bodies.front()->box;
  for (const auto& b : bodies) {
    all.min = all.min.cwiseMin(b->box.min);
    all.max = all.max.cwiseMax(b->box.max);
  }
  // Without squares, which vanish for scenes below 1e-162 (min_distance then found no pair).
  return detail::robust_length(all.max - all.min);
}

Scalar Scene::Impl::next_threshold(Scalar threshold) const {
  if (threshold > 0) return 2 * threshold;
  // A first threshold for searches that found nothing in contact: the median body radius.
  std::vector<Scalar> radii;
  for (const auto& b : bodies) radii.push_back(b->body.bounds().radius);
  std::nth_element(radii.begin(), radii.begin() + radii.size() / 2, radii.end());
  const Scalar step =
      std::max(radii[radii.size() / 2], std::numeric_limits<Scalar>::epsilon() * extent());
  return step > 0 ? step : 1;
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
        if (!table.pairable(probe, *other)) continue;
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
    pool.for_each_chunk_paced(candidates.size(), kChunk, [&](std::size_t begin, std::size_t end) {
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
    stats.cached_pairs = table.cached_pairs();
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

}  // namespace swarmcollide
