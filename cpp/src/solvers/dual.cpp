#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <numeric>
#include <utility>
#include <vector>

#include "dual_swarm.hpp"
#include "exact_solver.hpp"
#include "minkowski.hpp"
#include "swarmcollide/detail/random.hpp"
#include "swarmcollide/solvers/swarm.hpp"
#include "wolfe_min_norm.hpp"
#include "witness.hpp"

namespace swarmcollide::detail {

namespace {

constexpr Scalar kPi = 3.14159265358979323846;
// Largest feature the penetration finish enumerates planes and edge pairs of.
constexpr std::size_t kPenetrationFeatureCap = 6;
// Distinct personal bests the penetration finish starts from after each round.
constexpr int kPenetrationStarts = 12;
// Rounds of the penetration search that cover the whole sphere.
constexpr int kGlobalRounds = 3;
// Largest factor by which the penetration finish widens the feature slack.
constexpr Scalar kPenetrationWidening = 512;
// Exact subproblems the finish solves from one direction before the swarm takes over again. From
// the first generation's best direction, the bench's 512-vertex pairs need up to 10; with fewer,
// a quarter of them wait a dozen swarm iterations for the next finish.
constexpr int kFinishSteps = 10;
// Candidate sets the penetration finish tries from one direction.
constexpr int kPenetrationSteps = 12;

using Point2 = Eigen::Matrix<Scalar, 2, 1>;

// The weights of an upper bound: a convex combination of at most four pairs (x_ia, y_ib), as
// Wolfe's corral gives them, kept sparse so that recording a better bound costs nothing in the
// bodies' sizes; the dense weights are built once, for the result.
struct Witness {
  std::array<int, MinNormPoint::kCapacity> ia{};
  std::array<int, MinNormPoint::kCapacity> ib{};
  std::array<Scalar, MinNormPoint::kCapacity> weights{};
  int size = 0;
  Vector3 point_a = Vector3::Zero();
  Vector3 point_b = Vector3::Zero();
  Scalar distance = std::numeric_limits<Scalar>::infinity();
  // The corral it came from encloses the origin: a proof that the bodies share a point.
  bool encloses_origin = false;
};

// Buffers that a solve reuses from the previous one on the same thread, so that a warmed-up solve
// allocates nothing but its result.
struct Workspace {
  // All zero between uses.
  std::vector<char> visited_a;
  std::vector<char> visited_b;
  std::vector<int> feature_a;
  std::vector<int> feature_b;
  std::vector<int> grown;
  std::vector<Point2> x;
  std::vector<Point2> v;
  std::vector<Point2> p;
  std::vector<Scalar> fx;
  std::vector<Scalar> fp;
  std::vector<int> ha;
  std::vector<int> hb;
  std::vector<int> order;
  std::vector<ParticleCoefficients> coefficients;
  std::vector<std::pair<int, int>> starts;
  std::vector<Vector3> candidates;
  std::vector<Scalar> history;
};

Workspace& thread_workspace() {
  thread_local Workspace workspace;
  return workspace;
}

// The exponential map of the unit sphere at `centre`: a tangent vector w goes to the point at
// geodesic distance |w| along it. Smooth at the centre and onto the whole sphere for |w| <= pi,
// so the swarm's two coordinates have no pole to trip over.
struct Chart {
  Vector3 centre;
  Vector3 e1;
  Vector3 e2;

  explicit Chart(const Vector3& c) : centre(c) {
    const Vector3 helper = std::abs(c.x()) < 0.6 ? Vector3::UnitX() : Vector3::UnitY();
    e1 = c.cross(helper).normalized();
    e2 = c.cross(e1);
  }

  Vector3 direction(const Point2& w) const {
    const Scalar r = w.norm();
    if (r == 0) return centre;
    return (std::cos(r) * centre + (std::sin(r) / r) * (w.x() * e1 + w.y() * e2)).normalized();
  }
};

// What a round of the swarm looks for.
enum class Search {
  // Upper and lower bound within the tolerance, or a common point.
  distance,
  // The largest separation (minus the penetration depth) of overlapping bodies.
  penetration,
};

class DualSolver {
 public:
  DualSolver(const FramedPair& pair, const DualOptions& options, std::uint64_t seed,
             int exact_iterations, Goal goal)
      : pair_(pair),
        a_(pair.a),
        b_(pair.b),
        options_(options),
        exact_iterations_(exact_iterations),
        goal_(goal),
        rng_(seed),
        ws_(thread_workspace()) {
    tolerance_ = pair.tolerance;
    slack_ = options.feature_tolerance * pair.frame.size;
    if (ws_.visited_a.size() < static_cast<std::size_t>(a_.size())) ws_.visited_a.resize(a_.size());
    if (ws_.visited_b.size() < static_cast<std::size_t>(b_.size())) ws_.visited_b.resize(b_.size());
    ws_.history.clear();
  }

  Answer distance() {
    const Vector3 between = b_.offset() - a_.offset();
    const Vector3 centre = between.norm() > 0 ? Vector3(between.normalized()) : Vector3::UnitX();
    int ia = -1;
    int ib = -1;
    offer_lower(centre, separation(centre, ia, ib));
    offer_vertex_pair(ia, ib);
    hint_a_ = ia;
    hint_b_ = ib;
    ws_.history.push_back(best_.distance);
    search(Search::distance, centre, kPi / 2);
    return result();
  }

  // The dual's swarm finds the basin of the largest separation of overlapping bodies; the exact
  // penetration solver, started from its direction, proves the depth.
  Answer signed_distance() {
    Answer apart = distance();
    if (apart.lower > kFrameRounding) return apart;
    search(Search::penetration, best_n_, kPi);
    Answer overlap = exact_signed_distance(pair_, exact_iterations_, best_n_);
    overlap.iterations += iterations_;
    overlap.evaluations += evaluations_;
    overlap.history = ws_.history;
    overlap.intersection_proven = overlap.intersection_proven || apart.intersection_proven;
    return overlap;
  }

 private:
  // s(n) with the support points warm-started from (and returned in) ia, ib.
  Scalar separation(const Vector3& n, int& ia, int& ib) {
    ++evaluations_;
    return detail::separation(a_, b_, n, ia, ib);
  }

  void offer_lower(const Vector3& n, Scalar s) {
    if (s > best_s_) {
      best_s_ = s;
      best_n_ = n;
    }
  }

  void offer_vertex_pair(int ia, int ib) {
    Witness w;
    w.ia[0] = ia;
    w.ib[0] = ib;
    w.weights[0] = 1;
    w.size = 1;
    w.point_a = a_.vertex(ia);
    w.point_b = b_.vertex(ib);
    w.distance = (w.point_b - w.point_a).norm();
    offer_upper(w);
  }

  void offer_upper(const Witness& w) {
    if (w.distance < best_.distance) best_ = w;
  }

  // The witness of Wolfe's corral, whose indices are the bodies' own.
  Witness witness_of(const MinNormPoint& m) const {
    Witness w;
    w.size = m.size;
    Scalar total = 0;
    for (int k = 0; k < m.size; ++k) total += m.weights[k];
    for (int k = 0; k < m.size; ++k) {
      w.ia[k] = m.corral[k].ia;
      w.ib[k] = m.corral[k].ib;
      w.weights[k] = m.weights[k] / total;
      w.point_a += w.weights[k] * a_.vertex(w.ia[k]);
      w.point_b += w.weights[k] * b_.vertex(w.ib[k]);
    }
    w.distance = (w.point_b - w.point_a).norm();
    if (m.size == 4) {
      w.encloses_origin =
          encloses_origin({m.corral[0].p, m.corral[1].p, m.corral[2].p, m.corral[3].p});
    }
    return w;
  }

  // Contact proven (by witnesses within the tolerance, beyond rounding, or a corral around the
  // origin).
  bool colliding() const {
    return best_.encloses_origin || best_.distance + kFrameRounding <= tolerance_;
  }
  // A verdict needs only one bound to prove it; a distance needs them within the tolerance.
  bool converged() const {
    if (colliding()) return true;
    if (goal_ == Goal::verdict && best_s_ - kFrameRounding > tolerance_) return true;
    return best_s_ > 0 && best_.distance - best_s_ <= tolerance_;
  }

  // Points of `body` within the slack of its supporting plane along `n`, highest first, into
  // `found`: a scan for small bodies, a flood over the hull's edge graph from the support point
  // for large ones (the vertices above a plane span a connected subgraph of a polytope's graph).
  static void feature(const FramedBody& body, const Vector3& n, int& hint,
                      std::vector<char>& visited, Scalar slack, std::vector<int>& found) {
    hint = body.support_index(n, hint);
    const Scalar floor = body.vertex(hint).dot(n) - slack;
    found.clear();
    if (body.size() <= kHillClimbingThreshold) {
      for (int i = 0; i < body.size(); ++i) {
        if (body.vertex(i).dot(n) >= floor) found.push_back(i);
      }
    } else {
      const Hull& h = body.hull();
      found.push_back(hint);
      visited[hint] = 1;
      for (std::size_t k = 0; k < found.size(); ++k) {
        const int i = found[k];
        for (int e = h.neighbour_offsets[i]; e < h.neighbour_offsets[i + 1]; ++e) {
          const int j = h.neighbours[e];
          if (!visited[j] && body.vertex(j).dot(n) >= floor) {
            visited[j] = 1;
            found.push_back(j);
          }
        }
      }
      for (int i : found) visited[i] = 0;
    }
    std::sort(found.begin(), found.end(),
              [&](int i, int j) { return body.vertex(i).dot(n) > body.vertex(j).dot(n); });
  }

  // The exact nearest points of the hulls of two features: Wolfe's algorithm on their Minkowski
  // difference from the supporting pair along `start`, with support points by scanning the
  // features and the stopping scale of `exact_nearest_points` on the same points.
  Witness nearest_between(const std::vector<int>& fa, const std::vector<int>& fb,
                          const Vector3& start) const {
    const auto oracle = [&](const Vector3& d) {
      int i = fa[0];
      Scalar highest = a_.vertex(i).dot(d);
      for (std::size_t k = 1; k < fa.size(); ++k) {
        const Scalar h = a_.vertex(fa[k]).dot(d);
        if (h > highest) {
          highest = h;
          i = fa[k];
        }
      }
      int j = fb[0];
      Scalar lowest = b_.vertex(j).dot(d);
      for (std::size_t k = 1; k < fb.size(); ++k) {
        const Scalar h = b_.vertex(fb[k]).dot(d);
        if (h < lowest) {
          lowest = h;
          j = fb[k];
        }
      }
      return OraclePoint{b_.vertex(j) - a_.vertex(i), i, j};
    };
    // In the frame every point lies in the unit ball, so 2 bounds every difference.
    return witness_of(wolfe_min_norm(oracle, start, 2, exact_iterations_));
  }

  // Adds the points of `more` missing from `into`; returns whether any was.
  static bool merge(std::vector<int>& into, const std::vector<int>& more) {
    bool grew = false;
    for (int i : more) {
      if (std::find(into.begin(), into.end(), i) == into.end()) {
        into.push_back(i);
        grew = true;
      }
    }
    return grew;
  }

  // The distance finish: the exact nearest points of the two supporting features give feasible
  // weights (an upper bound) and a direction (a lower bound). When the bounds still differ, the
  // support points along the new direction lie outside the features (otherwise the subproblem's
  // optimum would be separated by it), so the features grow by the supporting features there and
  // the subproblem is solved again, up to kFinishSteps times before the swarm takes over again.
  void finish_distance(const Vector3& n) {
    std::vector<int>& fa = ws_.feature_a;
    std::vector<int>& fb = ws_.feature_b;
    feature(a_, n, hint_a_, ws_.visited_a, slack_, fa);
    feature(b_, -n, hint_b_, ws_.visited_b, slack_, fb);
    // Each subproblem grows around the previous one's nearest points, so Wolfe starts there.
    Vector3 start = n;
    for (int step = 0; step < kFinishSteps; ++step) {
      const Witness sub = nearest_between(fa, fb, start);
      offer_upper(sub);
      if (converged() || !(sub.distance > 0)) return;
      const Vector3 next = (sub.point_b - sub.point_a).normalized();
      start = next;
      int ia = hint_a_;
      int ib = hint_b_;
      offer_lower(next, separation(next, ia, ib));
      if (converged()) return;
      feature(a_, next, ia, ws_.visited_a, slack_, ws_.grown);
      const bool grew_a = merge(fa, ws_.grown);
      feature(b_, -next, ib, ws_.visited_b, slack_, ws_.grown);
      const bool grew_b = merge(fb, ws_.grown);
      if (!grew_a && !grew_b) return;  // rounding: nothing left to add
    }
  }

  // The penetration finish: the largest separation of overlapping polytopes is reached at a facet
  // normal of the Minkowski difference, i.e. a face normal of either body or the cross product of
  // an edge of each; those spanned by the supporting features are tried.
  // A facet whose foot point lies outside it is no local maximum; its neighbours, which the
  // supporting features show once the slack is wide enough, are better, so the slack widens
  // until a candidate improves or it reaches the cap.
  void finish_penetration(Vector3 n) {
    Scalar widen = 1;
    for (int step = 0; step < kPenetrationSteps && widen <= kPenetrationWidening; ++step) {
      std::vector<int>& fa = ws_.feature_a;
      std::vector<int>& fb = ws_.feature_b;
      feature(a_, n, hint_a_, ws_.visited_a, widen * slack_, fa);
      feature(b_, -n, hint_b_, ws_.visited_b, widen * slack_, fb);
      fa.resize(std::min(fa.size(), kPenetrationFeatureCap));
      fb.resize(std::min(fb.size(), kPenetrationFeatureCap));
      std::vector<Vector3>& candidates = ws_.candidates;
      candidates.clear();
      for (const auto& [body, f] : {std::pair{&a_, &fa}, std::pair{&b_, &fb}}) {
        const auto row = [&](int i) -> Vector3 { return body->vertex(i); };
        for (std::size_t i = 0; i < f->size(); ++i) {
          for (std::size_t j = i + 1; j < f->size(); ++j) {
            for (std::size_t k = j + 1; k < f->size(); ++k) {
              const Vector3 p = row((*f)[i]);
              candidates.push_back((row((*f)[j]) - p).cross(row((*f)[k]) - p));
            }
          }
        }
      }
      for (std::size_t i = 0; i < fa.size(); ++i) {
        for (std::size_t j = i + 1; j < fa.size(); ++j) {
          const Vector3 ea = a_.vertex(fa[j]) - a_.vertex(fa[i]);
          for (std::size_t k = 0; k < fb.size(); ++k) {
            for (std::size_t l = k + 1; l < fb.size(); ++l) {
              candidates.push_back(ea.cross(b_.vertex(fb[l]) - b_.vertex(fb[k])));
            }
          }
        }
      }
      const Scalar previous = best_s_;
      for (Vector3 c : candidates) {
        const Scalar length = c.norm();
        if (!(length > 1e-12)) continue;
        c /= length;
        if (c.dot(n) < 0) c = -c;
        int ia = hint_a_;
        int ib = hint_b_;
        offer_lower(c, separation(c, ia, ib));
      }
      if (best_s_ > previous) {
        n = best_n_;
        widen = 1;
      } else {
        widen *= 8;
      }
    }
  }

  void finish(Search goal, const Vector3& n) {
    if (goal == Search::distance) {
      finish_distance(n);
    } else {
      finish_penetration(n);
    }
  }

  // Wolfe's algorithm on the Minkowski difference B - A from the best direction: a common point
  // when the bodies overlap (which no direction can show), else the exact nearest points.
  void common_point() {
    int ia = hint_a_;
    int ib = hint_b_;
    const auto oracle = [&](const Vector3& d) {
      ++evaluations_;
      return minkowski_support(a_, b_, d, ia, ib);
    };
    const Witness w = witness_of(wolfe_min_norm(oracle, best_n_, 2, exact_iterations_));
    offer_upper(w);
    if (w.distance > 0) {
      const Vector3 n = (w.point_b - w.point_a).normalized();
      int ja = ia;
      int jb = ib;
      offer_lower(n, separation(n, ja, jb));
    }
  }

  // By rejection from the square: no trigonometry, 2.5 draws on average.
  Point2 uniform_in_disc(Scalar radius) {
    for (;;) {
      const Point2 u(2 * rng_.uniform() - 1, 2 * rng_.uniform() - 1);
      if (u.squaredNorm() <= 1) return radius * u;
    }
  }

  // Where hill climbing along `n` should start: the highest along `n` of `start` and the support
  // points `found` of the particles seeded before. A new particle may point anywhere in the disc,
  // and the nearest earlier answer spares most of the climb from the centre's.
  static int nearest_start(const FramedBody& body, const Vector3& n,
                           const std::vector<int>& found, int count, int start) {
    if (body.size() <= kHillClimbingThreshold) return start;
    Scalar highest = body.vertex(start).dot(n);
    for (int k = 0; k < count; ++k) {
      const Scalar h = body.vertex(found[k]).dot(n);
      if (h > highest) {
        highest = h;
        start = found[k];
      }
    }
    return start;
  }

  // Particles by decreasing personal best, ties by index (a stable sort's order, without the
  // buffer std::stable_sort allocates).
  void rank_by_personal_best(std::vector<int>& order) const {
    const std::vector<Scalar>& fp = ws_.fp;
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(),
              [&](int i, int j) { return fp[i] > fp[j] || (fp[i] == fp[j] && i < j); });
  }

  // One round of the paper's swarm, (8)-(11) with rank-based inertia, maximising s over the
  // chart at `centre`; particle 0 starts at the centre. Returns when converged (distance goal)
  // or after max_iterations.
  void round(Search goal, const Vector3& centre, Scalar radius) {
    const Chart chart(centre);
    const int np = options_.swarm_size;
    std::vector<Point2>& x = ws_.x;
    std::vector<Point2>& v = ws_.v;
    std::vector<Point2>& p = ws_.p;
    std::vector<Scalar>& fx = ws_.fx;
    std::vector<Scalar>& fp = ws_.fp;
    std::vector<int>& ha = ws_.ha;
    std::vector<int>& hb = ws_.hb;
    x.resize(np);
    v.resize(np);
    fx.resize(np);
    ha.resize(np);
    hb.resize(np);
    for (int j = 0; j < np; ++j) {
      x[j] = j == 0 ? Point2::Zero() : uniform_in_disc(radius);
      v[j] = uniform_in_disc(radius) - x[j];
      const Vector3 n = chart.direction(x[j]);
      ha[j] = nearest_start(a_, n, ha, j, hint_a_);
      hb[j] = nearest_start(b_, -n, hb, j, hint_b_);
      fx[j] = separation(n, ha[j], hb[j]);
    }
    p = x;
    fp = fx;
    int g = static_cast<int>(std::max_element(fp.begin(), fp.end()) - fp.begin());
    std::pair<int, int> finished{-1, -1};
    const auto improve = [&](int best) {
      const Vector3 n = chart.direction(p[best]);
      offer_lower(n, fp[best]);
      if (std::pair{ha[best], hb[best]} == finished) return;
      finished = {ha[best], hb[best]};
      hint_a_ = ha[best];
      hint_b_ = hb[best];
      finish(goal, n);
    };
    improve(g);
    std::vector<int>& order = ws_.order;
    std::vector<ParticleCoefficients>& coefficients = ws_.coefficients;
    order.resize(np);
    coefficients.resize(np);
    for (int iteration = 0; iteration < options_.max_iterations; ++iteration) {
      if (goal == Search::distance && converged()) break;
      rank_by_personal_best(order);
      for (int rank = 1; rank <= np; ++rank) {
        coefficients[order[rank - 1]] =
            rank_adaptive_coefficients(rank, np, options_.w_min, options_.w_max);
      }
      for (int j = 0; j < np; ++j) {
        const ParticleCoefficients& c = coefficients[j];
        const Scalar r1 = rng_.uniform();
        const Scalar r2 = rng_.uniform();
        v[j] = c.w * v[j] + c.c1 * r1 * (p[j] - x[j]) + c.c2 * r2 * (p[g] - x[j]);
        const Scalar speed = v[j].norm();
        if (speed > radius) v[j] *= radius / speed;
        x[j] += v[j];
        fx[j] = separation(chart.direction(x[j]), ha[j], hb[j]);
        if (fx[j] > fp[j]) {
          fp[j] = fx[j];
          p[j] = x[j];
        }
      }
      const int best = static_cast<int>(std::max_element(fp.begin(), fp.end()) - fp.begin());
      const bool improved = fp[best] > fp[g];
      g = best;
      if (improved) improve(g);
      ++iterations_;
      ws_.history.push_back(best_.distance);
    }
    if (goal == Search::distance) {
      if (!converged()) {
        finished = {-1, -1};
        improve(g);
      }
      return;
    }
    // Overlapping bodies: s has a local maximum at many facets of the Minkowski difference, so
    // the finish climbs from the best few distinct personal bests, not only the swarm's best.
    rank_by_personal_best(order);
    std::vector<std::pair<int, int>>& done = ws_.starts;
    done.clear();
    for (int j : order) {
      if (static_cast<int>(done.size()) >= kPenetrationStarts) break;
      if (std::find(done.begin(), done.end(), std::pair{ha[j], hb[j]}) != done.end()) continue;
      done.emplace_back(ha[j], hb[j]);
      hint_a_ = ha[j];
      hint_b_ = hb[j];
      const Vector3 n = chart.direction(p[j]);
      offer_lower(n, fp[j]);
      finish_penetration(n);
    }
  }

  void search(Search goal, Vector3 centre, Scalar radius) {
    bool tried_common_point = false;
    for (int r = 0; r < options_.max_rounds; ++r) {
      const Scalar before = best_s_;
      round(goal, centre, radius);
      if (goal == Search::distance) {
        if (converged()) return;
        if (best_s_ <= tolerance_ && !tried_common_point) {
          tried_common_point = true;
          common_point();
          if (converged()) return;
        }
      } else if (r >= kGlobalRounds && best_s_ - before <= tolerance_) {
        return;
      }
      // Overlapping bodies: the first rounds restart over the whole sphere to find the basin.
      if (goal == Search::penetration && r + 1 < kGlobalRounds) {
        centre = best_n_;
        continue;
      }
      // Re-seed around the best direction, in a disc that shrinks unless the best moved far.
      const Scalar moved = std::acos(std::clamp(centre.dot(best_n_), Scalar(-1), Scalar(1)));
      radius = std::min(radius, std::max(2 * moved, radius / 4));
      centre = best_n_;
    }
  }

  Answer result() {
    Answer r;
    r.upper = best_.distance;
    r.point_a = best_.point_a;
    r.point_b = best_.point_b;
    r.weights_a = ConvexWeights(a_.size(), best_.ia, best_.weights, best_.size);
    r.weights_b = ConvexWeights(b_.size(), best_.ib, best_.weights, best_.size);
    r.lower = best_s_;
    r.direction = best_n_;
    r.iterations = iterations_;
    r.evaluations = evaluations_;
    r.history = ws_.history;
    r.intersection_proven = best_.encloses_origin;
    return r;
  }

  const FramedPair& pair_;
  const FramedBody& a_;
  const FramedBody& b_;
  const DualOptions& options_;
  const int exact_iterations_;
  const Goal goal_;
  Xoshiro256 rng_;
  Workspace& ws_;
  Scalar tolerance_ = 0;
  Scalar slack_ = 0;
  int hint_a_ = -1;
  int hint_b_ = -1;
  Scalar best_s_ = -std::numeric_limits<Scalar>::infinity();
  Vector3 best_n_ = Vector3::UnitX();
  Witness best_;
  int iterations_ = 0;
  long evaluations_ = 0;
};

}  // namespace

Answer solve_dual(const FramedPair& pair, const QueryOptions& options, Goal goal) {
  DualSolver solver(pair, options.dual, options.seed, options.exact.max_iterations, goal);
  return goal == Goal::signed_distance ? solver.signed_distance() : solver.distance();
}

}  // namespace swarmcollide::detail
