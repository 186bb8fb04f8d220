// A body of a scene and what the broadphase keeps of it: its boxes, how far it moved, and the
// range of coordinates a scene takes; private to the library's sources.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <memory>
#include <string>
#include <utility>

#include "fcl_broadphase.hpp"
#include "swarmcollide/geometry/aabb.hpp"
#include "swarmcollide/geometry/compound_body.hpp"
#include "swarmcollide/geometry/convex_polyhedron.hpp"
#include "swarmcollide/geometry/pose.hpp"
#include "swarmcollide/scene/scene_options.hpp"

namespace swarmcollide::detail {

// The largest distance of the body's points from the centre of its box: what a turn about that
// centre moves them by, per radian. Often well below the box's half-diagonal.
Scalar reach_about_centre(const ConvexPolyhedron& body);

// A body of the scene with what the broadphase keeps of it. What the narrowphase reads comes
// first: the padded box of every pair of the table in the first cache line, what it reads of
// every candidate in the next four (see `prefetch_body`).
struct SceneBody {
  SceneBody(BodyId id_, ConvexPolyhedron body_, std::shared_ptr<const CompoundBody> compound_,
            const Pose& pose_, const BodyFilter& filter_)
      : id(id_),
        filter(filter_),
        compound(std::move(compound_)),
        pose(pose_),
        body(std::move(body_)),
        reach(reach_about_centre(body)),
        object(this, id_, filter_) {}

  BodyId id;
  BodyFilter filter;
  /// `box` padded for the threshold of the last query (see `padding`): two bodies are a
  /// candidate pair when these overlap.
  Aabb padded;
  /// An odometer: a bound on how far any point of the body has moved since it was added.
  Scalar travelled = 0;
  /// The compound body, null for a convex one.
  std::shared_ptr<const CompoundBody> compound;
  Pose pose;
  /// The body, or a compound body's envelope (the hull of its parts), which the broadphase
  /// boxes and the narrowphase screens with.
  ConvexPolyhedron body;
  /// The largest distance of its points from the centre of its box (see displacement).
  Scalar reach;
  /// What the last set_poses added to the odometer: how far the body may move by the next,
  /// which sets the margin of its broadphase box (see `fatten`).
  Scalar step = 0;
  /// The smallest box holding the body at its pose, widened by the rounding of computing it.
  Aabb box;
  /// Support points of the box's six faces, from which hill climbing on large bodies starts.
  std::array<int, 6> box_supports{-1, -1, -1, -1, -1, -1};
  /// Listed among the scene's moved bodies (its box is out of date).
  bool moved = false;
  /// The box the broadphase holds: `padded` with a margin for motion (see `fatten`).
  BoxedObject object;
};

// Asks for what the narrowphase will read of a body: its pose and the head of its polyhedron
// now, its points once those have arrived. Candidates meet bodies in no particular order, so
// without this every pair waits for memory several times.
inline void prefetch_box(const SceneBody* b) { __builtin_prefetch(b); }
inline void prefetch_body(const SceneBody* b) {
  const char* p = reinterpret_cast<const char*>(b);
  for (int line = 1; line < 5; ++line) __builtin_prefetch(p + 64 * line);
}
// The points the narrowphase reads: centred on the body's box, by rows (it scans by rows; see
// answer_pair). Until session 45 this fetched the points as given, which no solver has read
// since f3a63c2 (warm frames of 10,000 bodies about 4% faster: bench/README.md).
inline void prefetch_points(const SceneBody* b) {
  const VertexMatrix& points = b->body.centred_vertices();
  const char* p = reinterpret_cast<const char*>(points.data());
  const std::size_t bytes = 3 * sizeof(Scalar) * static_cast<std::size_t>(points.rows());
  for (std::size_t at = 0; at < std::min<std::size_t>(bytes, 256); at += 64) {
    __builtin_prefetch(p + at);
  }
}

// A bound on how far any point of a body moves from `from` to `to`: its box centre c moves by
// |c' - c|, and every point turns about it by at most |R' - R| times `reach`. Each term is
// computed with a few roundings of the magnitudes involved, which the margins cover.
Scalar displacement(const ConvexPolyhedron& body, Scalar reach, const Pose& from, const Pose& to);

// The world box of `b`: its points' extremes along the axes, found in the body's own frame
// (scanning small bodies, climbing large ones from the last frame's supports), so moving a body
// never touches its hull. Each coordinate R x + t carries at most a few roundings of |x| + |t|.
void update_box(SceneBody& b);

// How far the broadphase box of a body of radius `radius` is padded so that every pair within
// `threshold` plus the tolerance of each other has overlapping boxes. Such a pair is at most
// d <= threshold + tol S apart, where the pair's size S = |c_b - c_a| + 2 max(r_a, r_b) is at
// most d + 4 max(r_a, r_b) (each body lies within its radius of its centre); so d <= (threshold
// + 4 tol max(r)) / (1 - tol), and padding each box by (threshold / 2 + 4 tol r) / (1 - tol)
// covers it. The verdict's rounding margin is absorbed by raising tol by 1e-12.
inline Scalar padding(Scalar threshold, Scalar radius, Scalar tolerance) {
  const Scalar tol = tolerance + 1e-12;
  return (threshold / 2 + 4 * tol * radius) / (1 - tol);
}

inline Aabb padded(const Aabb& box, Scalar pad) {
  return {box.min - Vector3::Constant(pad), box.max + Vector3::Constant(pad)};
}

// FCL's test (AABB::overlap): boxes that touch overlap.
inline bool overlap(const Aabb& a, const Aabb& b) {
  return (a.min.array() <= b.max.array()).all() && (b.min.array() <= a.max.array()).all();
}

inline bool encloses(const fcl::AABBd& outer, const Aabb& inner) {
  return (outer.min_.array() <= inner.min.array()).all() &&
         (inner.max.array() <= outer.max_.array()).all();
}

// The broadphase holds each body's padded box with a margin, so that it is told of a body only
// when its padded box leaves that larger box, and the pairs it returns stay valid meanwhile (a
// superset of the candidates, which are sorted out by their padded boxes): the fat boxes of
// Box2D's and Bullet's dynamic trees. The margin is a few of the body's last steps, at most a
// fraction of its size; a body that has not moved gets none, so a still scene has no more pairs
// than candidates.
void fatten(SceneBody& b);

// How far from its own origin `body` reaches: its points lie within this of it. A scene takes
// bodies that reach at most kMaxSceneCoordinate / 2, moved by at most as much along each axis, so
// that every coordinate stays within kMaxSceneCoordinate; set_poses then checks a pose without
// reading its body (a pass over every body's memory cost about a tenth of a warm frame).
Scalar own_reach(const ConvexPolyhedron& body);

// True when `pose` moves a body by at most kMaxSceneCoordinate / 2 along each axis.
inline bool within_range(const Pose& pose) {
  return pose.translation.cwiseAbs().maxCoeff() <= kMaxSceneCoordinate / 2;
}

// Refuses a body out of range: "`what` `value`; a scene takes ..." and the fix.
[[noreturn]] void refuse_placement(const std::string& what, Scalar value);

}  // namespace swarmcollide::detail
