#pragma once

#include <memory>
#include <utility>
#include <vector>

#include "swarmcollide/geometry/compound_body.hpp"
#include "swarmcollide/geometry/convex_polyhedron.hpp"
#include "swarmcollide/geometry/pose.hpp"
#include "swarmcollide/scene/scene_options.hpp"
#include "swarmcollide/scene/scene_result.hpp"
#include "swarmcollide/scene/sweep_result.hpp"

namespace swarmcollide {

/// Many convex (or compound) bodies, each defined once in its own frame and placed by a pose, and
/// the queries that concern all their pairs: which collide, which lie within a distance, which are
/// nearest, and where they touch.
///
/// An FCL broadphase manager, given tight boxes computed from the bodies' support functions
/// (with margins for motion, so that it is asked again only about bodies that left them),
/// collects the candidate pairs; the narrowphase (the options' method, certified as
/// `Query::collision` is) answers them on a pool of threads. With `warm_start`, each candidate
/// pair keeps what the last query proved about it, a separating direction and its support points
/// in the bodies' own frames or a simplex of their difference enclosing the origin; the next
/// query re-evaluates it first (a few support evaluations) and starts the solver from it when it
/// no longer settles the pair. A pair's cache is dropped when it stops being a candidate.
///
/// Results list pairs in increasing order of (first id, second id); for pair queries the first
/// id is the smaller. Calls are serialised: a Scene may be shared between threads, and queries
/// use its own pool.
class Scene {
 public:
  /// Throws std::invalid_argument for invalid options (see SceneOptions::validate).
  explicit Scene(SceneOptions options = {});
  ~Scene();
  Scene(Scene&&) noexcept;
  Scene& operator=(Scene&&) noexcept;

  const SceneOptions& options() const;

  /// Adds bodies at `poses` (empty: every body at the identity) with `filter`; returns their
  /// ids. Throws std::invalid_argument, adding nothing, when the lengths differ or a pose is
  /// invalid (see validate_pose).
  std::vector<BodyId> add(std::vector<ConvexPolyhedron> bodies, const std::vector<Pose>& poses = {},
                          const BodyFilter& filter = {});
  BodyId add(ConvexPolyhedron body, const Pose& pose = {}, const BodyFilter& filter = {});
  /// Adds compound bodies. The broadphase boxes, and the narrowphase first screens, a compound
  /// body by its envelope (the hull of its parts); a pair that the envelopes do not settle is
  /// answered as Query answers compound bodies (branch and bound over the parts, certified for
  /// them), and contacts are found between the deepest pair of parts.
  std::vector<BodyId> add(std::vector<CompoundBody> bodies, const std::vector<Pose>& poses = {},
                          const BodyFilter& filter = {});
  BodyId add(CompoundBody body, const Pose& pose = {}, const BodyFilter& filter = {});
  /// Moves bodies; their hulls are never recomputed. Throws std::invalid_argument, moving
  /// nothing, for an unknown or repeated id, lengths that differ or an invalid pose.
  void set_poses(const std::vector<BodyId>& ids, const std::vector<Pose>& poses);
  /// Removes bodies, with every cached proof and exclusion that concerns them. Throws
  /// std::invalid_argument, removing nothing, for an unknown or repeated id.
  void remove(const std::vector<BodyId>& ids);
  /// Sets the group and mask of bodies (see BodyFilter).
  void set_filter(const std::vector<BodyId>& ids, const BodyFilter& filter);
  /// Never pair (or pair again) the bodies of each of `pairs`. Throws std::invalid_argument,
  /// changing nothing, for an unknown id or a body paired with itself.
  void exclude(const std::vector<std::pair<BodyId, BodyId>>& pairs);
  void include(const std::vector<std::pair<BodyId, BodyId>>& pairs);
  /// The pairs excluded (and not included again), the smaller id first, in increasing order.
  std::vector<std::pair<BodyId, BodyId>> excluded() const;
  /// The id the next body added gets: ids are handed out in increasing order, never reused.
  BodyId next_id() const;
  /// Hands out no id below `id`: the next body added gets it. With the accessors above, a scene
  /// rebuilt from another's bodies gives them the same ids (Python's pickling). Throws
  /// std::invalid_argument for an id below next_id().
  void skip_ids(BodyId id);

  /// Number of bodies.
  std::size_t size() const;
  /// Ids of the bodies, ascending.
  std::vector<BodyId> ids() const;
  /// True when the scene holds a body with this id.
  bool contains(BodyId id) const;
  /// A body (a compound body's envelope), its pose and its filter; std::invalid_argument for an
  /// unknown id.
  const ConvexPolyhedron& body(BodyId id) const;
  /// The compound body with this id, null for a convex body; std::invalid_argument for an
  /// unknown id.
  const CompoundBody* compound(BodyId id) const;
  const Pose& pose(BodyId id) const;
  const BodyFilter& filter(BodyId id) const;

  /// Every pair in contact (within the tolerance of each other), with the answers of
  /// `Query::collision`: certified unless a verdict could not be proven.
  SceneResult colliding_pairs();
  /// Every pair whose distance is at most `distance` (up to the tolerance), with its distance
  /// to the tolerance. The broadphase pads each box by half of `distance`. Throws
  /// std::invalid_argument for a negative or non-finite distance, or for a method without
  /// distances.
  SceneResult pairs_within(Scalar distance);
  /// The pair at the smallest distance (one row, none for fewer than two pairable bodies); ties
  /// within the tolerance go to the first pair in id order.
  SceneResult min_distance();
  /// For each of `ids`, its `k` nearest bodies, nearest first (fewer when the scene has fewer
  /// pairable bodies): rows `(id, other)`, A being the body asked about. Throws
  /// std::invalid_argument for an unknown id or k < 1.
  SceneResult nearest(const std::vector<BodyId>& ids, int k = 1);
  /// Every pair in contact with its certified signed distance, contact normal and up to
  /// `max_points` contact points, found by clipping the two supporting features along the normal
  /// against each other: a box resting on a face gives its four corners. Throws
  /// std::invalid_argument for max_points < 1 or a method that measures no penetration.
  ContactResult contacts(int max_points = 4);

  /// Moves the bodies `ids` from their poses to `poses` (the others stay still), and returns
  /// every pair that touches during the motion, of which at least one body moves, with its
  /// first contact bracketed as `time_of_impact` brackets it (each pair seeded as the scene's
  /// queries seed it; pairs of two still bodies are `colliding_pairs`' to answer). Candidates
  /// are the pairs, filtered as the scene's queries filter them, whose swept boxes overlap: boxes
  /// proven to hold each moving body over its whole motion, padded for the contact threshold.
  /// The pairs are answered on the scene's threads; the answers do not depend on their number.
  /// Then the bodies are left at `poses`, as set_poses leaves them, whatever was found. Throws
  /// std::invalid_argument, moving nothing, for an unknown or repeated id, lengths that differ,
  /// an invalid pose or options, or a method without signed distances.
  SweepResult sweep(const std::vector<BodyId>& ids, const std::vector<Pose>& poses,
                    const SweepOptions& options = {});

  /// What the last query did.
  const SceneStats& stats() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace swarmcollide
