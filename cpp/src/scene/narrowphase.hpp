// The answer a scene gives one candidate pair; private to the library's sources.
#pragma once

#include <vector>

#include "pair_cache.hpp"
#include "swarmcollide/geometry/compound_body.hpp"
#include "swarmcollide/geometry/convex_polyhedron.hpp"
#include "swarmcollide/geometry/pose.hpp"
#include "swarmcollide/queries/options.hpp"

namespace swarmcollide::detail {

struct KeptSurface;

/// What a scene query asks of each candidate pair.
struct PairQuestion {
  /// A pair belongs to the answer when its distance is at most `threshold` (world units) plus
  /// the tolerance: 0 for contact.
  Scalar threshold = 0;
  /// For pairs that belong: the distance to the tolerance (else the bounds that decided).
  bool distance = false;
  /// For pairs that belong: the signed distance and up to `max_points` contact points.
  bool contacts = false;
  int max_points = 4;
  /// Hand verdicts the method cannot prove to the exact method.
  bool escalate = true;
  /// Re-evaluate and update the pair's proof (else answer from scratch and leave it).
  bool warm = true;
};

/// How a pair was settled.
enum class Settled : unsigned char {
  /// By the separation along the line between the bodies' centres (no proof was cached).
  screened,
  /// By a cached lower bound on the distance less the bodies' motion since (no support
  /// evaluated).
  warm_bounded,
  /// By re-evaluating a cached separating direction.
  warm_rejected,
  /// By re-evaluating a cached enclosing simplex.
  warm_proven,
  /// By the method's solver.
  solved,
  /// By the exact method, after the method's solver could not prove the verdict.
  escalated,
};

/// One pair's answer, in world units.
struct PairAnswer {
  bool belongs = false;
  /// The verdict (and, where one is reported, the value) is proven.
  bool certified = false;
  Settled settled = Settled::solved;
  Scalar distance = 0;
  Scalar lower_bound = 0;
  Vector3 point_a = Vector3::Zero();
  Vector3 point_b = Vector3::Zero();
  Vector3 normal = Vector3::Zero();
  /// Contact points (for `contacts`).
  std::vector<Vector3> points;
};

/// A body of the scene as the narrowphase sees it.
struct PlacedBody {
  /// The body, or a compound body's envelope.
  const ConvexPolyhedron* body;
  /// Its pose, already validated (see validate_pose): the narrowphase does not check it again.
  const Pose* pose;
  /// Its odometer: a bound on how far any of its points has moved since it was added.
  Scalar travelled = 0;
  /// The compound body, null for a convex one.
  const CompoundBody* compound = nullptr;
};

/// Answers `question` for bodies `a` and `b` (in that order: vectors point from a to b) with
/// `options` (already seeded for the pair), into `out` (every field set). `proof` (never null)
/// holds what an earlier query proved about the pair, expressed for this order; with
/// `question.warm` it is tried first and replaced by what this answer proves. Verdicts and
/// certificates are made by verdict.hpp's `finish_result`, as for every query. A pair with a
/// compound body is screened by the envelopes (a cached bound or direction, or the centres'
/// line) and otherwise answered by Query's compound queries; an enclosing simplex of envelopes
/// proves nothing about their parts, so none is kept for it. `surface`, when not null, is the
/// pair's kept expansion surface (see penetration), read and replaced by a contact's depth.
void answer_pair(const PlacedBody& a, const PlacedBody& b, PairProof& proof,
                 const QueryOptions& options, const PairQuestion& question, PairAnswer& out,
                 KeptSurface* surface = nullptr);

}  // namespace swarmcollide::detail
