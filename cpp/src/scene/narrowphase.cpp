#include "narrowphase.hpp"

#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>

#include "../geometry/normalise.hpp"
#include "../geometry/unit_direction.hpp"
#include "../queries/dispatch.hpp"
#include "../queries/rounded.hpp"
#include "../queries/verdict.hpp"
#include "../solvers/dual_swarm.hpp"
#include "../solvers/exact_solver.hpp"
#include "../solvers/minkowski.hpp"
#include "../solvers/witness.hpp"
#include "contact_manifold.hpp"
#include "contact_tetrahedron.hpp"
#include "swarmcollide/queries/methods.hpp"
#include "swarmcollide/queries/query.hpp"

namespace swarmcollide::detail {

namespace {

constexpr Scalar kInfinity = std::numeric_limits<Scalar>::infinity();
constexpr Scalar kEpsilon = std::numeric_limits<Scalar>::epsilon();

// A common point of the bodies, as the witnesses on each (frame coordinates).
struct CommonPoint {
  Vector3 point_a;
  Vector3 point_b;
};

// A tetrahedron's point pairs placed at the pair's present poses: on_a[k] of A and on_b[k] of B.
struct PlacedTetrahedron {
  std::array<Vector3, 4> on_a;
  std::array<Vector3, 4> on_b;
};

PlacedTetrahedron place(const FramedPair& pair, const PairProof::Enclosing& proof) {
  PlacedTetrahedron t;
  for (int k = 0; k < 4; ++k) {
    t.on_a[k] = pair.a.vertex(proof.a[k]);
    t.on_b[k] = pair.b.vertex(proof.b[k]);
  }
  return t;
}

// The common point a tetrahedron of point pairs (on_a[k], on_b[k]) proves when it encloses the
// origin (encloses_origin, beyond rounding): the origin's barycentric coordinates weigh the pairs'
// points on each body.
std::optional<CommonPoint> common_point(const PlacedTetrahedron& t) {
  const std::array<Vector3, 4>& on_a = t.on_a;
  const std::array<Vector3, 4>& on_b = t.on_b;
  std::array<Scalar, 4> weight;
  if (!encloses_origin({on_b[0] - on_a[0], on_b[1] - on_a[1], on_b[2] - on_a[2], on_b[3] - on_a[3]},
                       weight)) {
    return std::nullopt;
  }
  const Scalar total = weight[0] + weight[1] + weight[2] + weight[3];
  CommonPoint common{Vector3::Zero(), Vector3::Zero()};
  for (int k = 0; k < 4; ++k) {
    common.point_a += (weight[k] / total) * on_a[k];
    common.point_b += (weight[k] / total) * on_b[k];
  }
  return common;
}

// The cached tetrahedron (`proof`, placed as `t`) as a corral of Wolfe's algorithm (equal
// weights): where Wolfe's algorithm restarts, or, once it is known to enclose the origin at the
// new poses, where the expanding polytope starts.
MinNormPoint corral_of(const PlacedTetrahedron& t, const PairProof::Enclosing& proof) {
  MinNormPoint corral;
  for (int k = 0; k < 4; ++k) {
    corral.corral[k] = {t.on_b[k] - t.on_a[k], proof.a[k], proof.b[k]};
    corral.weights[k] = 0.25;
    corral.x += 0.25 * corral.corral[k].p;
  }
  corral.size = 4;
  return corral;
}

// A cached tetrahedron that no longer encloses the origin (placed as `t`) is where Wolfe's
// algorithm starts: after a small motion a step or two find one that does, whose common point is
// the answer and which replaces the cached one (and `t`, placed). Otherwise the pair is answered
// as if nothing were cached.
std::optional<CommonPoint> repaired(const FramedPair& pair, PairProof::Enclosing& proof,
                                    PlacedTetrahedron& t, int max_iterations) {
  const MinNormPoint start = corral_of(t, proof);
  int ia = proof.a[0];
  int ib = proof.b[0];
  const auto oracle = [&](const Vector3& d) {
    return minkowski_support(pair.a, pair.b, d, ia, ib);
  };
  const MinNormPoint found = wolfe_min_norm_from(oracle, start, 2, max_iterations);
  if (found.size != 4) return std::nullopt;
  PairProof::Enclosing found_proof;
  for (int k = 0; k < 4; ++k) {
    found_proof.a[k] = found.corral[k].ia;
    found_proof.b[k] = found.corral[k].ib;
  }
  const PlacedTetrahedron found_placed = place(pair, found_proof);
  std::optional<CommonPoint> common = common_point(found_placed);
  if (common) {
    proof = found_proof;
    t = found_placed;
  }
  return common;
}

// The index with the largest weight: a point of the supporting feature, where hill climbing
// along a nearby direction should start.
int heaviest(const ConvexWeights& weights) {
  int index = -1;
  Scalar largest = 0;
  weights.for_each([&](int i, Scalar w) {
    if (w > largest) {
      largest = w;
      index = i;
    }
  });
  return index;
}

// Rounded towards minus (plus) infinity: a float that still bounds `x` from below (above).
float float_below(Scalar x) {
  const float f = static_cast<float>(x);
  return static_cast<Scalar>(f) <= x ? f
                                     : std::nextafter(f, -std::numeric_limits<float>::infinity());
}
float float_above(Scalar x) {
  const float f = static_cast<float>(x);
  return static_cast<Scalar>(f) >= x ? f
                                     : std::nextafter(f, std::numeric_limits<float>::infinity());
}

// A separating proof: unit direction `n` (frame) with separation `s` of the cores along it
// (frame units, so that `s - kFrameRounding` is certified, less the radii for rounded bodies),
// support points `ia` and `ib`, made when the bodies' odometers summed to `travelled`.
void keep_separating(const FramedPair& pair, const Vector3& n, Scalar s, int ia, int ib,
                     Scalar travelled, PairProof& proof) {
  const Vector3 local = pair.a.local_direction(n);
  proof.kind = PairProof::Kind::separating;
  proof.separating = {
      {static_cast<float>(local.x()), static_cast<float>(local.y()), static_cast<float>(local.z())},
      ia,
      ib};
  proof.lower = float_below(pair.frame.length_to_world(rounded_lower(pair, s) - kFrameRounding));
  proof.size = float_above(pair.frame.length_to_world(pair.frame.size) * (1 + 1e-12));
  proof.travelled = travelled;
}

// What `answer` proves about the pair, kept in `proof`: the point pairs of an enclosing corral
// (the k-th stored weights of A and of B come from its k-th point), else its direction.
// Its bound stays the last one proven, with the odometers then: still sound, since `moved`
// counts every motion since.
void remember(const FramedPair& pair, const Answer& answer, PairProof& proof) {
  // A curved body's point indices are its support points of one query: a tetrahedron of them
  // means nothing in the next frame, so its pairs keep separating directions only.
  if (answer.intersection_proven && !pair.a.curved() && !pair.b.curved()) {
    PairProof::Enclosing enclosing{};
    int count_a = 0;
    int count_b = 0;
    answer.weights_a.for_each([&](int i, Scalar) {
      if (count_a < 4) enclosing.a[count_a] = i;
      ++count_a;
    });
    answer.weights_b.for_each([&](int i, Scalar) {
      if (count_b < 4) enclosing.b[count_b] = i;
      ++count_b;
    });
    if (count_a == 4 && count_b == 4) {
      proof.kind = PairProof::Kind::enclosing;
      proof.enclosing = enclosing;
      proof.on_face = false;
      proof.lower = -std::numeric_limits<float>::infinity();
      return;
    }
  }
  if (!(answer.direction.squaredNorm() > 0)) return;
  const Vector3 local = pair.a.local_direction(answer.direction);
  proof.kind = PairProof::Kind::separating;
  proof.separating = {
      {static_cast<float>(local.x()), static_cast<float>(local.y()), static_cast<float>(local.z())},
      heaviest(answer.weights_a),
      heaviest(answer.weights_b)};
}

// The method's solver, started from `start` when it is the dual and one is given.
Answer solve(const FramedPair& pair, const QueryOptions& options, Goal goal,
             const std::optional<DualStart>& start) {
  if (options.method == Method::dual && start) return solve_dual(pair, options, goal, *start);
  return solver_for(options.method)(pair, options, goal);
}

std::optional<DualStart> start_from(const Answer& answer) {
  if (!(answer.direction.squaredNorm() > 0)) return std::nullopt;
  return DualStart{answer.direction, heaviest(answer.weights_a), heaviest(answer.weights_b)};
}

void take_values(const DistanceResult& r, PairAnswer& out) {
  out.distance = r.distance;
  out.lower_bound = r.lower_bound;
  out.point_a = r.point_a;
  out.point_b = r.point_b;
  out.normal = r.direction;
}

// The contact points of `pair` from its certified signed distance `contact`: the clipped
// supporting features along its normal (left in `features`; true), or the midpoint of the
// witnesses when there is no normal (the bodies only touch at a point; false).
bool add_contact_points(const FramedPair& pair, const DistanceResult& contact,
                        const PairQuestion& question, PairAnswer& out, ContactFeatures& features) {
  if (!(contact.direction.squaredNorm() > 0)) {
    out.points.push_back(contact.point_a / 2 + contact.point_b / 2);
    return false;
  }
  const std::size_t first = out.points.size();
  contact_points(pair, contact.direction, kContactFeatureTolerance * pair.frame.size,
                 question.max_points, out.points, features);
  for (std::size_t k = first; k < out.points.size(); ++k) {
    out.points[k] = pair.frame.point_to_world(out.points[k]);
  }
  return true;
}

// A pair with a compound body, once the envelopes have not settled it: the compound queries,
// whose answers name the parts, and contact points between the deepest pair of parts.
void answer_compounds(const PlacedBody& a, const PlacedBody& b, const FramedPair& pair,
                      const FramedPair& gate, PairProof& proof, const QueryOptions& options,
                      const PairQuestion& question, Scalar travelled, PairAnswer& out) {
  std::optional<CompoundBody> own_a;
  std::optional<CompoundBody> own_b;
  const CompoundBody& ca = a.compound ? *a.compound : own_a.emplace(*a.body);
  const CompoundBody& cb = b.compound ? *b.compound : own_b.emplace(*b.body);
  const Query query(options);
  // The threshold plus the tolerance, in world units: within it a pair belongs.
  const Scalar contact = pair.frame.length_to_world(gate.tolerance);
  CompoundResult r = question.distance
                         ? query.distance(ca, *a.pose, cb, *b.pose)
                         : query.collision(ca, *a.pose, cb, *b.pose, question.escalate);
  if (r.escalated_from) out.settled = Settled::escalated;
  const bool apart = question.distance ? r.lower_bound > contact : !r.colliding;
  out.lower_bound = r.lower_bound;
  if (apart) {
    out.certified = r.certified;
    // The part pair's direction and the compound lower bound hold for the envelopes' next
    // evaluation and for the bound-after-motion test alike.
    if (question.warm && r.direction.squaredNorm() > 0 && r.lower_bound > 0) {
      const Vector3 local = pair.a.local_direction(r.direction);
      proof.kind = PairProof::Kind::separating;
      proof.separating = {{static_cast<float>(local.x()), static_cast<float>(local.y()),
                           static_cast<float>(local.z())},
                          -1,
                          -1};
      proof.lower = float_below(r.lower_bound * (1 - 1e-12));
      proof.size = float_above(pair.frame.length_to_world(pair.frame.size) * (1 + 1e-12));
      proof.travelled = travelled;
    }
    return;
  }
  out.belongs = true;
  out.certified = r.certified && (!question.distance || r.distance <= contact || r.colliding);
  take_values(r, out);
  if (!question.contacts) return;
  const CompoundResult deepest = query.signed_distance(ca, *a.pose, cb, *b.pose);
  out.certified = out.certified && deepest.certified;
  take_values(deepest, out);
  const FramedPair parts = frame_pair(ca.parts()[deepest.part_a], *a.pose,
                                      cb.parts()[deepest.part_b], *b.pose, options.tolerance);
  thread_local ContactFeatures features;
  add_contact_points(parts, deepest, question, out, features);
}

}  // namespace

void answer_pair(const PlacedBody& a, const PlacedBody& b, PairProof& proof,
                 const QueryOptions& options, const PairQuestion& question, PairAnswer& out,
                 KeptSurface* surface) {
  // Every field is set afresh: `out` is a buffer reused from query to query.
  out.belongs = false;
  out.certified = false;
  out.settled = Settled::solved;
  out.distance = 0;
  out.lower_bound = 0;
  out.point_a.setZero();
  out.point_b.setZero();
  out.normal.setZero();
  out.points.clear();
  // The bodies' travel since the proof, with the rounding of the odometers' difference.
  const Scalar travelled = a.travelled + b.travelled;
  if (question.warm && proof.kind == PairProof::Kind::separating) {
    const Scalar moved = travelled - proof.travelled + 4 * kEpsilon * travelled;
    if (apart_after_motion(proof.lower, proof.size, moved, question.threshold, options.tolerance)) {
      out.settled = Settled::warm_bounded;
      out.certified = true;
      out.lower_bound = proof.lower - moved;
      return;
    }
  }
  // The scene validated both poses when they were set. Its bodies' points are mostly out of
  // cache in a frame (thousands of bodies, each met in a few pairs): scanned by rows, each body's
  // points are fetched once, where scans of its columns fetched the columns and then the rows
  // that place what they found (warm frames of 10,000 bodies 19.5 -> 15.6 ms, bench/README.md).
  FramedPair pair = frame_validated_pair(*a.body, *a.pose, *b.body, *b.pose, options.tolerance);
  pair.a.scan_rows();
  pair.b.scan_rows();
  // The pair as the verdict sees it: in contact means within the threshold and the tolerance (a
  // copy only when the threshold is not zero).
  std::optional<FramedPair> padded_gate;
  if (question.threshold != 0) {
    padded_gate.emplace(pair);
    padded_gate->tolerance += times_power_of_two(question.threshold, -pair.frame.exponent);
  }
  const FramedPair& gate = padded_gate ? *padded_gate : pair;
  const Method method = options.method;

  // A cached simplex that still encloses the origin proves contact at any threshold, and a
  // distance of zero (to rounding): its common point is the answer.
  const bool compound = a.compound != nullptr || b.compound != nullptr;
  std::optional<CommonPoint> common;
  // The cached tetrahedron placed at these poses, once it is (its corners are those of the
  // expanding polytope's start too).
  PlacedTetrahedron placed;
  // The contact tetrahedron kept from the last frame still encloses the origin.
  bool face_kept = false;
  if (question.warm && proof.kind == PairProof::Kind::enclosing && !compound) {
    placed = place(pair, proof.enclosing);
    common = common_point(placed);
    face_kept = common && proof.on_face;
    if (!common) {
      common = repaired(pair, proof.enclosing, placed, options.exact.max_iterations);
      if (common) proof.on_face = false;
    }
  }
  bool value_settled = true;
  std::optional<DualStart> next;
  if (common) {
    const Scalar gap = (common->point_b - common->point_a).norm();
    out.settled = Settled::warm_proven;
    out.belongs = out.certified = verdict_proven(gate, 0, gap, true);
    out.distance = pair.frame.length_to_world(gap);
    out.point_a = pair.frame.point_to_world(common->point_a);
    out.point_b = pair.frame.point_to_world(common->point_b);
  } else {
    // The direction to try next: the cached one, else the line between the centres. Either
    // settles most pairs apart in two support evaluations; otherwise the solver starts from it.
    const bool cached = question.warm && proof.kind == PairProof::Kind::separating;
    Vector3 n;
    int ia = -1;
    int ib = -1;
    if (cached) {
      const PairProof::Separating& last = proof.separating;
      const Vector3 local(static_cast<Scalar>(last.direction[0]),
                          static_cast<Scalar>(last.direction[1]),
                          static_cast<Scalar>(last.direction[2]));
      n = (pair.a.rotated() ? Vector3(pair.a.rotation() * local) : local).normalized();
      ia = last.support_a;
      ib = last.support_b;
    } else {
      const Vector3 between = pair.b.offset() - pair.a.offset();
      n = unit_direction_or(between, Vector3::UnitX());
    }
    const Scalar s = separation(pair.a, pair.b, n, ia, ib);
    if (verdict_proven(gate, s, kInfinity, false)) {
      out.settled = cached ? Settled::warm_rejected : Settled::screened;
      out.certified = true;
      out.lower_bound = pair.frame.length_to_world(rounded_lower(pair, s));
      if (question.warm) keep_separating(pair, n, s, ia, ib, travelled, proof);
      return;
    }
    if (compound) {
      if (question.warm) proof.kind = PairProof::Kind::none;
      return answer_compounds(a, b, pair, gate, proof, options, question, travelled, out);
    }

    // The verdict, as Query::collision decides it (methods without distances decide by their
    // signed distance), then escalated when unproven.
    const Goal verdict =
        method_info(method).capabilities & kDistance ? Goal::verdict : Goal::signed_distance;
    Answer answer = solve(gate, options, verdict, DualStart{n, ia, ib});
    if (question.warm) remember(pair, answer, proof);
    value_settled =
        goal_reached(pair, Goal::distance, answer.lower, answer.upper, answer.intersection_proven);
    next = start_from(answer);
    DistanceResult r = finish_result(gate, std::move(answer), method, verdict);
    if (!r.certified && question.escalate && method != Method::exact) {
      QueryOptions exact = options;
      exact.method = Method::exact;
      Answer decided = solver_for(Method::exact)(gate, exact, Goal::verdict);
      if (question.warm) remember(pair, decided, proof);
      value_settled = goal_reached(pair, Goal::distance, decided.lower, decided.upper,
                                   decided.intersection_proven);
      next = start_from(decided);
      r = finish_result(gate, std::move(decided), Method::exact, Goal::verdict);
      out.settled = Settled::escalated;
    }
    out.certified = r.certified;
    out.lower_bound = r.lower_bound;
    if (!r.colliding) return;
    out.belongs = true;
    take_values(r, out);
  }

  if (question.contacts) {
    // The dual's signed distance of an overlapping pair is the penetration solver's, started from
    // a tetrahedron of the pair's points around the origin (overlap_first): the cached one, or the
    // one the verdict just proved and kept, when it encloses the origin at these poses, saves
    // running Wolfe's algorithm again to find one.
    std::optional<CommonPoint> tetrahedron_common = common;
    if (!common && question.warm && proof.kind == PairProof::Kind::enclosing) {
      placed = place(pair, proof.enclosing);
      tetrahedron_common = common_point(placed);
      face_kept = tetrahedron_common && proof.on_face;
    }
    // The surface of the pair's last expansion (never a curved body's: its support points are
    // numbered as they are found, and its indices name other points at other poses). One made
    // from a solver's corral (a pair's first contact) is dropped where a contact tetrahedron is
    // made after it: on a resting contact that tetrahedron's expansion takes a step or two,
    // fewer than placing a surface again costs, and it is kept only where it takes more.
    KeptSurface* kept_surface = !pair.a.curved() && !pair.b.curved() ? surface : nullptr;
    const bool surface_was_kept = kept_surface != nullptr && !kept_surface->faces.empty();
    const auto signed_distance = [&](Method m) {
      QueryOptions o = options;
      o.method = m;
      if (m == Method::dual && tetrahedron_common) {
        const MinNormPoint corral = corral_of(placed, proof.enclosing);
        // No direction to try first: the polytope from the tetrahedron finds the normal, and a
        // hint would only cost two more support climbs.
        Answer overlap =
            exact_penetration(pair, o.exact.max_iterations, Vector3::Zero(),
                              (tetrahedron_common->point_b - tetrahedron_common->point_a).norm(),
                              &corral, kept_surface);
        overlap.intersection_proven = true;
        return finish_result(pair, std::move(overlap), m, Goal::signed_distance);
      }
      return finish_result(pair, solve(pair, o, Goal::signed_distance, next), m,
                           Goal::signed_distance);
    };
    DistanceResult contact = signed_distance(method);
    const bool corral_surface = kept_surface != nullptr && !surface_was_kept && !face_kept;
    if (!contact.certified && question.escalate && method != Method::exact) {
      contact = signed_distance(Method::exact);
      out.settled = Settled::escalated;
    }
    out.certified = out.certified && contact.certified;
    take_values(contact, out);
    thread_local ContactFeatures features;
    // An overlap's contact face makes the tetrahedron the next frame's penetration starts from,
    // unless the one made so in an earlier frame still encloses the origin: after a small
    // motion it is still on the face (a pile's resting contacts, frame after frame), and the
    // next frame checks it again at its poses (common_point) before anything starts from it.
    if (add_contact_points(pair, contact, question, out, features) && question.warm &&
        contact.distance < 0 && !face_kept) {
      // The last tetrahedron's apex starts the climbs to the new one's.
      PairProof::Enclosing tetrahedron{};
      const bool kept = proof.kind == PairProof::Kind::enclosing;
      tetrahedron.a[3] = kept ? proof.enclosing.a[3] : -1;
      tetrahedron.b[3] = kept ? proof.enclosing.b[3] : -1;
      if (!pair.a.curved() && !pair.b.curved() &&
          contact_tetrahedron(pair, contact.direction, features, tetrahedron)) {
        proof.kind = PairProof::Kind::enclosing;
        proof.enclosing = tetrahedron;
        proof.on_face = true;
        if (corral_surface) kept_surface->clear();
        proof.lower = -std::numeric_limits<float>::infinity();
      }
    }
  } else if (question.distance && !value_settled) {
    Answer measured = solve(pair, options, Goal::distance, next);
    if (question.warm) remember(pair, measured, proof);
    const DistanceResult d = finish_result(pair, std::move(measured), method, Goal::distance);
    out.certified = out.certified && d.certified;
    take_values(d, out);
  }
}

}  // namespace swarmcollide::detail
