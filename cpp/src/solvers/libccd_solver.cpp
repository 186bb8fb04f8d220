#include "libccd_solver.hpp"

#include <ccd/ccd.h>

#include <array>
#include <optional>

#include "../geometry/unit_direction.hpp"
#include "../queries/verdict.hpp"
#include "exact_solver.hpp"
#include "minkowski.hpp"
#include "witness.hpp"

namespace swarmcollide::detail {

namespace {

// The support points libccd's GJK saw last, newest at `count - 1` modulo the capacity.
constexpr int kRecorded = 8;

// What libccd's callbacks receive: the two bodies, the remaining budget of support calls, and
// what GJK asked for last (to check its answers).
struct CcdQuery {
  const FramedBody* a;
  const FramedBody* b;
  long budget;
  bool exhausted = false;
  Vector3 last_direction = Vector3::Zero();
  std::array<OraclePoint, kRecorded> recorded{};
  int count = 0;
  int pending_a = -1;
};

struct CcdShape {
  CcdQuery* query;
  bool is_a;
};

void to_ccd(const Vector3& v, ccd_vec3_t* out) {
  for (int k = 0; k < 3; ++k) out->v[k] = v(k);
}

// libccd asks for A's support along d, then B's along -d.
void support(const void* object, const ccd_vec3_t* direction, ccd_vec3_t* out) {
  const auto* shape = static_cast<const CcdShape*>(object);
  CcdQuery& q = *shape->query;
  if (q.budget <= 0) {
    // Both bodies at the origin: the difference's support is the origin, which no EPA step can
    // expand and every GJK or EPA test stops at.
    q.exhausted = true;
    to_ccd(Vector3::Zero(), out);
    return;
  }
  --q.budget;
  const Vector3 d(direction->v[0], direction->v[1], direction->v[2]);
  if (shape->is_a) {
    q.last_direction = d;
    q.pending_a = q.a->support_index(d);
    to_ccd(q.a->vertex(q.pending_a), out);
  } else {
    const int j = q.b->support_index(d);
    if (q.pending_a >= 0) {
      q.recorded[q.count % kRecorded] = {q.b->vertex(j) - q.a->vertex(q.pending_a), q.pending_a, j};
      ++q.count;
    }
    to_ccd(q.b->vertex(j), out);
  }
}

// One libccd call's state: the shapes its callbacks receive and its configuration, with the
// support budget of 4 x max_iterations calls.
struct CcdCall {
  CcdQuery query;
  CcdShape a{&query, true};
  CcdShape b{&query, false};
  ccd_t ccd;

  CcdCall(const FramedPair& pair, int max_iterations)
      : query{&pair.a, &pair.b, 4L * max_iterations} {
    CCD_INIT(&ccd);
    ccd.support1 = support;
    ccd.support2 = support;
    ccd.max_iterations = static_cast<unsigned long>(max_iterations);
    // In the frame the bodies lie in the unit ball: a depth to near double precision.
    ccd.epa_tolerance = 1e-14;
  }
  CcdCall(const CcdCall&) = delete;
  CcdCall& operator=(const CcdCall&) = delete;
};

// A tetrahedron of recorded support points (with the newest) that encloses the origin, as the
// answer it gives; false when none does beyond rounding.
bool enclosing_tetrahedron(const FramedPair& pair, const CcdQuery& q, Answer& answer) {
  const int n = std::min(q.count, kRecorded);
  const int newest = (q.count - 1) % kRecorded;
  for (int i = 0; i < n; ++i) {
    for (int j = i + 1; j < n; ++j) {
      for (int k = j + 1; k < n; ++k) {
        if (i == newest || j == newest || k == newest) continue;
        const std::array<OraclePoint, 4> points = {q.recorded[newest], q.recorded[i], q.recorded[j],
                                                   q.recorded[k]};
        if (!encloses_origin({points[0].p, points[1].p, points[2].p, points[3].p})) continue;
        const auto oracle = [&points](const Vector3& d) {
          OraclePoint best = points[0];
          for (const OraclePoint& p : points) {
            if (d.dot(p.p) < d.dot(best.p)) best = p;
          }
          return best;
        };
        answer = answer_from_corral(pair, wolfe_min_norm(oracle, points[0].p, 2, 100));
        answer.intersection_proven = true;
        return true;
      }
    }
  }
  return false;
}

Answer verdict(const FramedPair& pair, int max_iterations) {
  CcdCall call(pair, max_iterations);
  const CcdQuery& q = call.query;
  Answer answer;
  if (ccdGJKIntersect(&call.a, &call.b, &call.ccd)) {
    if (!q.exhausted && enclosing_tetrahedron(pair, q, answer)) return answer;
  } else if (const std::optional<Vector3> unit = unit_direction(q.last_direction);
             !q.exhausted && unit) {
    // libccd's "no" comes from a direction along which the whole difference lies beyond the
    // origin: a separating direction from A to B (at a gap of 1e-160, tolerance 0, one whose
    // squares underflow: unit_direction).
    const Vector3 n = *unit;
    answer.lower = separation(pair.a, pair.b, n);
    answer.direction = n;
    if (answer.lower - kFrameRounding > pair.tolerance) {
      // Witnesses are not needed for the verdict, but every answer carries valid ones: the
      // support points along the direction bound the distance from above.
      int ia = -1;
      int ib = -1;
      Answer witnessed =
          answer_from_corral(pair, single_point(minkowski_support(pair.a, pair.b, n, ia, ib)));
      witnessed.lower = answer.lower;
      witnessed.direction = n;
      return witnessed;
    }
  }
  Answer exact = exact_distance(pair, max_iterations, Vector3::Zero());
  exact.answered_by = Method::exact;
  return exact;
}

Answer signed_distance(const FramedPair& pair, int max_iterations) {
  CcdCall call(pair, max_iterations);
  const CcdQuery& q = call.query;
  ccd_real_t depth = 0;
  ccd_vec3_t direction;
  ccd_vec3_t position;
  const int status = ccdGJKPenetration(&call.a, &call.b, &call.ccd, &depth, &direction, &position);
  // libccd: translating B by depth * direction brings the bodies into touching contact, so the
  // direction is the contact normal from A to B.
  const Vector3 n(direction.v[0], direction.v[1], direction.v[2]);
  const std::optional<Vector3> unit = unit_direction(n);
  if (status != 0 || q.exhausted || !(depth > 0) || !unit) {
    Answer exact = exact_signed_distance(pair, max_iterations, Vector3::Zero());
    exact.answered_by = Method::exact;
    return exact;
  }
  const Vector3 normal = *unit;
  const Scalar libccd_separation = separation(pair.a, pair.b, normal);
  // The exact solver, started from libccd's normal, proves the depth; libccd's answer stands
  // when nothing separates better by more than the tolerance.
  Answer proof = exact_signed_distance(pair, max_iterations, normal);
  if (proof.lower > libccd_separation + pair.tolerance) proof.answered_by = Method::exact;
  return proof;
}

}  // namespace

Answer solve_libccd(const FramedPair& pair, const QueryOptions& options, Goal goal) {
  if (goal == Goal::signed_distance) return signed_distance(pair, options.exact.max_iterations);
  return verdict(pair, options.exact.max_iterations);
}

}  // namespace swarmcollide::detail
