#include "swarmcollide/solvers/dual.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <utility>
#include <vector>

#include "exact_internal.hpp"
#include "swarmcollide/detail/random.hpp"
#include "swarmcollide/solvers/exact_nearest_points.hpp"
#include "swarmcollide/solvers/swarm.hpp"

namespace swarmcollide {

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
// Exact subproblems the finish solves from one direction before the swarm takes over again.
constexpr int kFinishSteps = 6;

using Point2 = Eigen::Matrix<Scalar, 2, 1>;

Scalar diagonal(const ConvexPolyhedron& body) {
  const Aabb box = body.aabb();
  return (box.max - box.min).norm();
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

enum class Goal {
  // Upper and lower bound within the tolerance, or a common point.
  distance,
  // The largest separation (minus the penetration depth) of overlapping bodies.
  penetration,
};

class DualSolver {
 public:
  DualSolver(const ConvexPolyhedron& a, const ConvexPolyhedron& b, const DualOptions& options)
      : a_(a), b_(b), options_(options), rng_(options.seed) {
    const Scalar size = std::max(diagonal(a), diagonal(b));
    scale_ = exact_internal::pair_scale(a, b);
    tolerance_ = options.tolerance > 0 ? options.tolerance
                                       : options.relative_tolerance * (size > 0 ? size : scale_);
    slack_ = options.feature_tolerance * size;
    visited_a_.assign(a.size(), 0);
    visited_b_.assign(b.size(), 0);
  }

  DistanceResult distance() {
    const Vector3 between =
        (b_.vertices().colwise().mean() - a_.vertices().colwise().mean()).transpose();
    const Vector3 centre = between.norm() > 0 ? Vector3(between.normalized()) : Vector3::UnitX();
    int ia = -1;
    int ib = -1;
    offer_lower(centre, separation(centre, ia, ib));
    offer_vertex_pair(ia, ib);
    hint_a_ = ia;
    hint_b_ = ib;
    history_.push_back(best_upper_);
    search(Goal::distance, centre, kPi / 2);
    return result();
  }

  DistanceResult signed_distance() {
    DistanceResult apart = distance();
    if (!apart.colliding) return apart;
    search(Goal::penetration, best_n_, kPi);
    DistanceResult r =
        exact_internal::penetration_result(a_, b_, best_n_, -best_s_, "dual", tolerance_);
    r.iterations = iterations_;
    r.evaluations = evaluations_;
    r.history = history_;
    r.certified = apart.certified;
    r.status = apart.status;
    return r;
  }

 private:
  // s(n) with the support points warm-started from (and returned in) ia, ib.
  Scalar separation(const Vector3& n, int& ia, int& ib) {
    ia = a_.support_index(n, ia);
    ib = b_.support_index(-n, ib);
    ++evaluations_;
    return (b_.vertices().row(ib) - a_.vertices().row(ia)).dot(n);
  }

  void offer_lower(const Vector3& n, Scalar s) {
    if (s > best_s_) {
      best_s_ = s;
      best_n_ = n;
    }
  }

  void offer_vertex_pair(int ia, int ib) {
    const Scalar d = (b_.vertices().row(ib) - a_.vertices().row(ia)).norm();
    if (d < best_upper_) {
      best_upper_ = d;
      weights_a_ = VectorX::Zero(a_.size());
      weights_b_ = VectorX::Zero(b_.size());
      weights_a_(ia) = 1;
      weights_b_(ib) = 1;
      point_a_ = a_.vertices().row(ia).transpose();
      point_b_ = b_.vertices().row(ib).transpose();
    }
  }

  bool colliding() const { return best_upper_ <= tolerance_; }
  bool converged() const {
    return colliding() || (best_s_ > tolerance_ && best_upper_ - best_s_ <= tolerance_);
  }

  // Points of `body` within the slack of its supporting plane along `n`, highest first: a scan
  // for small bodies, a flood over the hull's edge graph from the support point for large ones
  // (the vertices above a plane span a connected subgraph of a polytope's graph).
  std::vector<int> feature(const ConvexPolyhedron& body, const Vector3& n, int& hint,
                           std::vector<char>& visited, Scalar slack) {
    hint = body.support_index(n, hint);
    const VertexMatrix& v = body.vertices();
    const Scalar floor = v.row(hint).dot(n) - slack;
    std::vector<int> found;
    if (body.size() <= kHillClimbingThreshold) {
      for (int i = 0; i < body.size(); ++i) {
        if (v.row(i).dot(n) >= floor) found.push_back(i);
      }
    } else {
      const Hull& h = body.hull();
      found.push_back(hint);
      visited[hint] = 1;
      for (std::size_t k = 0; k < found.size(); ++k) {
        const int i = found[k];
        for (int e = h.neighbour_offsets[i]; e < h.neighbour_offsets[i + 1]; ++e) {
          const int j = h.neighbours[e];
          if (!visited[j] && v.row(j).dot(n) >= floor) {
            visited[j] = 1;
            found.push_back(j);
          }
        }
      }
      for (int i : found) visited[i] = 0;
    }
    std::sort(found.begin(), found.end(),
              [&](int i, int j) { return v.row(i).dot(n) > v.row(j).dot(n); });
    return found;
  }

  static VertexMatrix rows_of(const ConvexPolyhedron& body, const std::vector<int>& rows) {
    VertexMatrix m(static_cast<Eigen::Index>(rows.size()), 3);
    for (std::size_t k = 0; k < rows.size(); ++k) m.row(k) = body.vertices().row(rows[k]);
    return m;
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
  // the subproblem is solved again, a few times at most before the swarm takes over again.
  void finish_distance(const Vector3& n) {
    std::vector<int> fa = feature(a_, n, hint_a_, visited_a_, slack_);
    std::vector<int> fb = feature(b_, -n, hint_b_, visited_b_, slack_);
    ExactOptions exact;
    exact.tolerance = tolerance_;
    for (int step = 0; step < kFinishSteps; ++step) {
      const DistanceResult sub = exact_nearest_points(ConvexPolyhedron(rows_of(a_, fa)),
                                                      ConvexPolyhedron(rows_of(b_, fb)), exact);
      if (sub.distance < best_upper_) {
        best_upper_ = sub.distance;
        weights_a_ = VectorX::Zero(a_.size());
        weights_b_ = VectorX::Zero(b_.size());
        for (std::size_t k = 0; k < fa.size(); ++k) weights_a_(fa[k]) = sub.weights_a(k);
        for (std::size_t k = 0; k < fb.size(); ++k) weights_b_(fb[k]) = sub.weights_b(k);
        point_a_ = sub.point_a;
        point_b_ = sub.point_b;
      }
      if (converged() || !(sub.distance > 0)) return;
      const Vector3 next = (sub.point_b - sub.point_a).normalized();
      int ia = hint_a_;
      int ib = hint_b_;
      offer_lower(next, separation(next, ia, ib));
      if (converged()) return;
      const bool grew_a = merge(fa, feature(a_, next, ia, visited_a_, slack_));
      const bool grew_b = merge(fb, feature(b_, -next, ib, visited_b_, slack_));
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
    for (int step = 0; step < 2 * kFinishSteps && widen <= kPenetrationWidening; ++step) {
      std::vector<int> fa = feature(a_, n, hint_a_, visited_a_, widen * slack_);
      std::vector<int> fb = feature(b_, -n, hint_b_, visited_b_, widen * slack_);
      fa.resize(std::min(fa.size(), kPenetrationFeatureCap));
      fb.resize(std::min(fb.size(), kPenetrationFeatureCap));
      std::vector<Vector3> candidates;
      for (const auto& [body, f] : {std::pair{&a_, &fa}, std::pair{&b_, &fb}}) {
        const auto row = [&](int i) -> Vector3 { return body->vertices().row(i).transpose(); };
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
          const Vector3 ea = a_.vertices().row(fa[j]) - a_.vertices().row(fa[i]);
          for (std::size_t k = 0; k < fb.size(); ++k) {
            for (std::size_t l = k + 1; l < fb.size(); ++l) {
              candidates.push_back(
                  ea.cross((b_.vertices().row(fb[l]) - b_.vertices().row(fb[k])).transpose()));
            }
          }
        }
      }
      const Scalar previous = best_s_;
      for (Vector3 c : candidates) {
        const Scalar length = c.norm();
        if (!(length > 1e-12 * scale_ * scale_)) continue;
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

  void finish(Goal goal, const Vector3& n) {
    if (goal == Goal::distance) {
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
      ia = a_.support_index(d, ia);
      ib = b_.support_index(-d, ib);
      ++evaluations_;
      return exact_internal::OraclePoint{
          (b_.vertices().row(ib) - a_.vertices().row(ia)).transpose(), ia, ib};
    };
    const exact_internal::MinNormPoint m =
        exact_internal::wolfe_min_norm(oracle, best_n_, scale_, 1000);
    VectorX wa = VectorX::Zero(a_.size());
    VectorX wb = VectorX::Zero(b_.size());
    for (std::size_t k = 0; k < m.corral.size(); ++k) {
      wa(m.corral[k].ia) += m.weights[k];
      wb(m.corral[k].ib) += m.weights[k];
    }
    wa /= wa.sum();
    wb /= wb.sum();
    DistanceResult r =
        exact_internal::result_from_weights(a_, b_, std::move(wa), std::move(wb), "dual", 0);
    if (r.distance < best_upper_) {
      best_upper_ = r.distance;
      weights_a_ = std::move(r.weights_a);
      weights_b_ = std::move(r.weights_b);
      point_a_ = r.point_a;
      point_b_ = r.point_b;
    }
    if (r.distance > 0) {
      const Vector3 n = (r.point_b - r.point_a).normalized();
      int ja = ia;
      int jb = ib;
      offer_lower(n, separation(n, ja, jb));
    }
  }

  Point2 uniform_in_disc(Scalar radius) {
    const Scalar r = radius * std::sqrt(rng_.uniform());
    const Scalar t = 2 * kPi * rng_.uniform();
    return {r * std::cos(t), r * std::sin(t)};
  }

  // One round of the paper's swarm, (8)-(11) with rank-based inertia, maximising s over the
  // chart at `centre`; particle 0 starts at the centre. Returns when converged (distance goal)
  // or after max_iterations.
  void round(Goal goal, const Vector3& centre, Scalar radius) {
    const Chart chart(centre);
    const int np = options_.swarm_size;
    std::vector<Point2> x(np), v(np), p(np);
    std::vector<Scalar> fx(np), fp(np);
    std::vector<int> ha(np, hint_a_), hb(np, hint_b_);
    for (int j = 0; j < np; ++j) {
      x[j] = j == 0 ? Point2::Zero() : uniform_in_disc(radius);
      v[j] = uniform_in_disc(radius) - x[j];
      fx[j] = separation(chart.direction(x[j]), ha[j], hb[j]);
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
    std::vector<int> order(np);
    std::vector<ParticleCoefficients> coefficients(np);
    for (int iteration = 0; iteration < options_.max_iterations; ++iteration) {
      if (goal == Goal::distance && converged()) break;
      std::iota(order.begin(), order.end(), 0);
      std::stable_sort(order.begin(), order.end(), [&](int i, int j) { return fp[i] > fp[j]; });
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
      history_.push_back(best_upper_);
    }
    if (goal == Goal::distance) {
      if (!converged()) {
        finished = {-1, -1};
        improve(g);
      }
      return;
    }
    // Overlapping bodies: s has a local maximum at many facets of the Minkowski difference, so
    // the finish climbs from the best few distinct personal bests, not only the swarm's best.
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(), [&](int i, int j) { return fp[i] > fp[j]; });
    std::vector<std::pair<int, int>> done;
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

  void search(Goal goal, Vector3 centre, Scalar radius) {
    bool tried_common_point = false;
    for (int r = 0; r < options_.max_rounds; ++r) {
      const Scalar before = best_s_;
      round(goal, centre, radius);
      if (goal == Goal::distance) {
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
      if (goal == Goal::penetration && r + 1 < kGlobalRounds) {
        centre = best_n_;
        continue;
      }
      // Re-seed around the best direction, in a disc that shrinks unless the best moved far.
      const Scalar moved = std::acos(std::clamp(centre.dot(best_n_), Scalar(-1), Scalar(1)));
      radius = std::min(radius, std::max(2 * moved, radius / 4));
      centre = best_n_;
    }
  }

  DistanceResult result() {
    DistanceResult r;
    r.distance = best_upper_;
    r.point_a = point_a_;
    r.point_b = point_b_;
    r.weights_a = weights_a_;
    r.weights_b = weights_b_;
    if (best_s_ > 0) {
      r.lower_bound = best_s_;
      r.direction = best_n_;
    }
    r.iterations = iterations_;
    r.evaluations = evaluations_;
    r.history = history_;
    r.colliding = colliding();
    r.certified = r.colliding || r.lower_bound > tolerance_;
    r.method = "dual";
    r.status = converged() ? SolverStatus::converged : SolverStatus::max_iterations;
    return r;
  }

  const ConvexPolyhedron& a_;
  const ConvexPolyhedron& b_;
  const DualOptions& options_;
  detail::Xoshiro256 rng_;
  Scalar scale_ = 0;
  Scalar tolerance_ = 0;
  Scalar slack_ = 0;
  std::vector<char> visited_a_;
  std::vector<char> visited_b_;
  int hint_a_ = -1;
  int hint_b_ = -1;
  Scalar best_s_ = -std::numeric_limits<Scalar>::infinity();
  Vector3 best_n_ = Vector3::UnitX();
  Scalar best_upper_ = std::numeric_limits<Scalar>::infinity();
  VectorX weights_a_;
  VectorX weights_b_;
  Vector3 point_a_ = Vector3::Zero();
  Vector3 point_b_ = Vector3::Zero();
  int iterations_ = 0;
  long evaluations_ = 0;
  std::vector<Scalar> history_;
};

}  // namespace

DistanceResult solve_dual(const ConvexPolyhedron& a, const ConvexPolyhedron& b,
                          const DualOptions& options) {
  options.validate();
  return DualSolver(a, b, options).distance();
}

DistanceResult dual_signed_distance(const ConvexPolyhedron& a, const ConvexPolyhedron& b,
                                    const DualOptions& options) {
  options.validate();
  return DualSolver(a, b, options).signed_distance();
}

}  // namespace swarmcollide
