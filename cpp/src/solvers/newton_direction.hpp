// Newton's steps on the separating direction for the Wolfe searches of curved pairs; private to
// the library's sources.
#pragma once

#include <algorithm>
#include <cmath>

#include "../geometry/framed_curved_support.hpp"
#include "whole_search.hpp"
#include "wolfe_min_norm.hpp"

namespace swarmcollide::detail {

/// Where a curved pair's Wolfe search asks its oracle points once the bodies' nearest points lie
/// on smooth parts of their surfaces (a rim, an ellipsoid, a vertex beside them): not along the
/// corral's point x but along Newton's step on the separation. The distance is the largest
/// separation phi(n) = min over B - A of n . p over unit n; its gradient at n is the support point
/// p(n), and its Hessian in the plane across n is -(K + phi P), K the derivative of p(n) (the
/// bodies' curvatures at their support points, FramedBody::add_support_curvature) and P the
/// projection across n. Newton's step t = (P K P + phi I)^-1 P p then turns n towards the optimum
/// quadratically, where Wolfe's corrals close a rim against a rim by a factor of about 4 a step.
/// It is solved as a 2 x 2 system on the unit vectors across n (K's quadratic form on them), in
/// place of session 42's 3 x 3 matrices and their Cholesky factor.
///
/// A cylinder's support point jumps from one rim to the other as the direction crosses the
/// normals to its axis, a cone's between its apex and its base rim as it crosses the normals to
/// its slant lines; where the nearest point lies on the mantle between, phi has a crease there
/// and the support points' own gaps stay large. Once the directions asked have crossed a crease
/// (`Crease`) and lie within about 6 degrees of it, the step is taken on it: from n moved onto
/// it, along the one direction e = normal x n that stays on it, where phi is smooth (the rim's
/// curvature; on a cone's slant, the nearest point's share of it, as the apex does not move),
/// and a cone's step is moved back onto its crease at the new azimuth. Where both bodies'
/// creases hold the nearest points, the direction normal to both (for two cylinders the optimum
/// itself). On a crease either part's point is a support point, and Wolfe's corral needs both:
/// each direction is tilted towards x's part by a thousandth of the tolerance, so that the part
/// asked is the one x would rather have.
///
/// A polyhedron beside an ellipsoid (NewtonDirection<true>) has such a crease at each edge: its
/// support point jumps between the edge's ends as the direction crosses the normals to the edge
/// (an ellipsoid nearest a box's edge, half of the random pairs apart, took 20 support points, a
/// corral's factor of about 4 a step). Once the support has moved from one end to the other and
/// back, the directions lie across that edge, and it is taken as a crease of no curvature of its
/// own whose normal is the edge's direction; a step along it that is refused (the nearest point
/// at a vertex or on a face after all) forgets the edge rather than ending the steps.
/// `callgrind_query.py --curved`: ellipsoid-box apart 16,970 -> 14,413 instructions (an edge taken
/// at the first move, 15,068: vertex contacts then stepped along edges they were not near). The
/// same steps for cylinders and cones beside boxes asked 12-17% fewer support points but cost
/// cone-box 10,788 -> 11,315 instructions (2,000 cylinder-box pairs within 1%): those pairs keep
/// Wolfe's corrals, as session 43 found.
///
/// Any direction's support point is a point of B - A and its separation along the direction a
/// lower bound, so the bounds stay proven whatever is asked (`measured`). As NesterovDirection,
/// a point asked along Newton's direction is kept only where it lies nearer than the corral along
/// x by more than Wolfe's tests' rounding; otherwise the point along x is asked as well, and the
/// steps end for the search.
///
/// Pairs with an ellipsoid, and pairs of cylinders and cones, search this way
/// (curved_search.cpp), measured with `bench/callgrind_query.py --curved --pairs 100 --repeats
/// 1`, instructions per signed distance apart (session 43, session 42's steps -> the creases,
/// the 2 x 2 system and the steps out of line): cylinder-cylinder 16,157 -> 14,585, cylinder-cone
/// 16,676 -> 14,767, cone-cone 15,004 -> 13,596, cylinder-ellipsoid 16,514 -> 15,181,
/// cone-ellipsoid 16,977 -> 14,633, ellipsoid-box 17,269 -> 17,028. A cylinder or a cone beside
/// a box lost with the steps (cone-box 10,801 -> 11,658; a C++ probe of 300 random cylinder-box
/// pairs apart 14,837 -> 15,720): a box's edges and faces make creases that are not modelled, and
/// the tests of every step cost more than the steps save. Session 42: a start at a gap of 1e-2
/// or 1e-3 of the separation (kStart) gave cone-ellipsoid 15,724 and 16,868 where 1e-1 gave
/// 15,660 (20 pairs).
template <bool kEdges>
class NewtonDirection {
 public:
  explicit NewtonDirection(const FramedPair& pair)
      : pair_(pair),
        crease_a_(pair.a, 1),
        crease_b_(pair.b, -1),
        creases_(crease_a_.tracked() || crease_b_.tracked()),
        tilt_(1e-3 * pair.tolerance),
        smallest_step_(10 * pair.tolerance) {}

  /// The point `support` gives for the corral's point `x`: asked along direction(x), and along x
  /// as well where Newton's point is not kept (which ends the steps).
  template <typename Support>
  __attribute__((always_inline)) OraclePoint ask(const Vector3& x, Support& support) {
    for (;;) {
      const Vector3& d = direction(x);
      const OraclePoint q = support(d);
      if (keep(x, q)) {
        last_ = d;
        last_point_ = q.p;
        last_a_ = q.ia;
        last_b_ = q.ib;
        return q;
      }
    }
  }

  /// The separation of the kept point `q` along the direction it was asked for: Newton's unit
  /// direction, or the corral's point `x` of norm 1 / `inverse_x`.
  Separation measured(const MinNormPoint& current, const OraclePoint& q, Scalar inverse_x) const {
    if (extrapolated_) return Separation{asked_.dot(q.p), asked_};
    return Separation{current.x.dot(q.p) * inverse_x, current.x * inverse_x};
  }

 private:
  // The crease of the separation made by one body (CreaseShape, or with kEdges a polyhedron's
  // edge between its last two support points), whose support is asked along `side` (1 for A, -1
  // for B) times the direction, and whether the search's directions have crossed it (the body's
  // support point moved from one part to the other between two asks; an edge's, there and back),
  // which puts the nearest point on the segment between the parts.
  class Crease {
   public:
    Crease(const FramedBody& body, Scalar side)
        : side_(side), tracked_(body.crease_shape(shape_)), edges_(!body.curved()) {
      slant_ = std::sqrt(shape_.radius * shape_.radius +
                         4 * shape_.half_length * shape_.half_length);
    }
    bool tracked() const { return tracked_ || edges(); }
    bool edges() const { return kEdges && edges_; }
    // An edge stepped along in vain: not a crease until the support crosses it again.
    void forget_edge() {
      if (edges()) crossed_ = false;
    }
    // Whether the crease's normal turns with the direction's azimuth (a cone's).
    bool turns() const { return shape_.cone; }
    // Whether the nearest point is taken on the crease, from the last direction asked, d (of
    // squared length `squared_length`): the directions asked have crossed it, and d lies within
    // about 6 degrees of it. Called once for every direction asked after the first, with the
    // body and the index of its support point along d.
    bool active(const Vector3& d, Scalar squared_length, const FramedBody& body, int index) {
      on_ = false;
      if (edges()) {
        if (index != vertex_ && index >= 0) {
          // A move to another vertex ends a crossing; a move back to the vertex before crosses
          // the edge between the two.
          crossed_ = false;
          if (index == before_ && vertex_ >= 0) {
            const Vector3 edge = body.vertex(index) - body.vertex(vertex_);
            const Scalar length = edge.norm();
            if (length > 0) {
              normal_ = edge / length;
              crossed_ = true;
            }
          }
          before_ = vertex_;
          vertex_ = index;
        }
        if (!crossed_) return false;
        const Scalar along = normal_.dot(d);
        on_ = along * along < 0.01 * squared_length;
        return on_;
      }
      if (!tracked_) return false;
      const Scalar along_axis = side_ * shape_.axis.dot(d);
      if (!shape_.cone) {
        if (along_axis * previous_height_ < 0) crossed_ = true;
        previous_height_ = along_axis;
        on_ = crossed_ && along_axis * along_axis < 0.01 * squared_length;
        return on_;
      }
      // The apex's height above the base rim along d, 2 h a - r |d_xy| (a = axis . d), has the
      // sign of 4 h^2 a^2 - r^2 (|d|^2 - a^2) where a > 0, and is negative elsewhere: its
      // square root is taken only once the directions have crossed the crease.
      const Scalar apex = 2 * shape_.half_length * along_axis;
      const Scalar across_squared = std::max(squared_length - along_axis * along_axis, Scalar(0));
      const Scalar rim_squared = shape_.radius * shape_.radius * across_squared;
      const Scalar sign = apex > 0 && apex * apex > rim_squared ? 1 : -1;
      if (sign * previous_height_ < 0) crossed_ = true;
      previous_height_ = sign;
      if (!crossed_) return false;
      const Scalar height = (apex - std::sqrt(rim_squared)) / slant_;
      on_ = height * height < 0.01 * squared_length;
      return on_;
    }
    // At the unit direction n (the body's own side of it): the crease's unit normal (from the
    // base rim to the top rim or the apex, at n's azimuth), and the curvature along the
    // direction across n that stays on it of the point of the segment between the two parts
    // nearest `other` across the normal (a point of the other body): a rim's r / |n_xy|, times
    // that point's share of the base rim for a cone (its apex does not move). The normal is
    // kept for `tilt`. False along the axis.
    bool at(const Vector3& n, const Vector3& other, Vector3& normal, Scalar& curvature) {
      if (edges()) {
        normal = normal_;
        curvature = 0;
        return true;
      }
      const Vector3 m = side_ * n;
      const Scalar along_axis = shape_.axis.dot(m);
      const Scalar across = std::sqrt(std::max(1 - along_axis * along_axis, Scalar(0)));
      if (!(across > 0)) return false;
      curvature = shape_.radius / across;
      if (!shape_.cone) {
        normal = shape_.axis;
      } else {
        // The apex less the rim point at m's azimuth, (-r u, 2 h) in the cone's own frame.
        const Vector3 outward = (m - along_axis * shape_.axis) / across;
        normal = (2 * shape_.half_length * shape_.axis - shape_.radius * outward) / slant_;
        curvature *= std::clamp((shape_.apex - other).dot(normal) / slant_, Scalar(0), Scalar(1));
      }
      normal_ = normal;
      return true;
    }
    // Adds to `direction` a tilt of `amount` along the crease's normal towards x's part: on the
    // crease either part's point is a support point, and the one x would rather have is asked.
    void tilt(const Vector3& x, Scalar amount, Vector3& direction) const {
      if (on_) direction += std::copysign(amount, x.dot(normal_)) * normal_;
    }

   private:
    CreaseShape shape_;
    Scalar side_;
    bool tracked_;
    // A polyhedron's edges are tracked where kEdges allows (edges()): its last support point and
    // the one before.
    bool edges_;
    int vertex_ = -1;
    int before_ = -1;
    // |apex - rim| in the frame (a cone's; unused for a cylinder).
    Scalar slant_ = 0;
    // The last height's sign carrier: a cylinder's axis . d, a cone's sign (+1 apex, -1 rim).
    Scalar previous_height_ = 0;
    bool crossed_ = false;
    bool on_ = false;
    Vector3 normal_ = Vector3::Zero();
  };

  // The direction to ask for the corral's point `x`: Newton's from the last direction asked and
  // its point where that point's own gap |p| - n . p is within kStart of its separation n . p
  // (the supports then lie on the smooth parts that the nearest points will), else x.
  const Vector3& direction(const Vector3& x) {
    extrapolated_ = false;
    edge_step_ = false;
    if (!on_ || !asked_once_) {
      asked_once_ = true;
      return x;
    }
    const Scalar along = last_.dot(last_point_);
    if (!(along > 0)) return x;
    const Scalar squared_length = last_.squaredNorm();
    if (creases_) {
      const bool on_a = crease_a_.active(last_, squared_length, pair_.a, last_a_);
      const bool on_b = crease_b_.active(last_, squared_length, pair_.b, last_b_);
      if (on_a || on_b) {
        edge_step_ = (on_a && crease_a_.edges()) || (on_b && crease_b_.edges());
        const Vector3 n = last_ / std::sqrt(squared_length);
        if (on_a && on_b) return across_creases(n, x);
        return on_a ? along_crease(n, crease_a_, pair_.b, -1, pair_.b.vertex(last_b_), x)
                    : along_crease(n, crease_b_, pair_.a, 1, pair_.a.vertex(last_a_), x);
      }
    }
    const Scalar threshold = (1 + kStart) * along;
    if (!(last_point_.squaredNorm() * squared_length <= threshold * threshold)) return x;
    return smooth_step(last_ / std::sqrt(squared_length), x);
  }

  // Newton's step from the unit direction n (last_) where the support points lie on smooth
  // parts. Out of line, as the creases' steps: the searches that inline it whole run every step
  // through the tests above, and a few through this (inlined, the larger loop took two
  // ellipsoids' and two cylinders' searches 3-5% more instructions).
  [[gnu::noinline]] const Vector3& smooth_step(const Vector3& n, const Vector3& x) {
    const Scalar phi = n.dot(last_point_);
    // In the plane across n, on the unit vectors u along the gradient P p and v = n x u, Newton's
    // step solves the 2 x 2 system (K + phi I) (a, b) = (|P p|, 0).
    const Vector3 gradient = last_point_ - phi * n;
    const Scalar slope = gradient.norm();
    if (!(slope > 0)) return x;
    const Vector3 u = gradient / slope;
    const Vector3 v = n.cross(u);
    Vector3 form = Vector3::Zero();
    if (!pair_.a.add_support_curvature(n, u, v, form) ||
        !pair_.b.add_support_curvature(-n, u, v, form)) {
      on_ = false;
      return x;
    }
    const Scalar uu = form(0) + phi;
    const Scalar vv = form(2) + phi;
    const Scalar determinant = uu * vv - form(1) * form(1);
    if (!(determinant > 0)) return x;
    const Vector3 step = (slope / determinant) * (vv * u - form(1) * v);
    const Vector3 turned = n + step;
    const Scalar length = turned.norm();
    const bool short_step = step.squaredNorm() < kLargestStep * kLargestStep;
    if (!(length > 0) || !std::isfinite(length) || !short_step) return x;
    if (step.squaredNorm() < smallest_step_ * smallest_step_) return converged(x);
    asked_ = turned / length;
    extrapolated_ = true;
    return asked_;
  }

  // Both bodies' nearest points on their creases: the direction normal to both creases (for
  // two cylinders the optimum itself; a cone's crease turns with the direction's azimuth).
  [[gnu::noinline]] const Vector3& across_creases(const Vector3& n, const Vector3& x) {
    Vector3 normal_a;
    Vector3 normal_b;
    Scalar unused;
    if (!crease_a_.at(n, pair_.b.vertex(last_b_), normal_a, unused) ||
        !crease_b_.at(n, pair_.a.vertex(last_a_), normal_b, unused)) {
      return x;
    }
    const Vector3 normal = normal_a.cross(normal_b);
    const Scalar length = normal.norm();
    if (!(length > 0x1p-20)) {
      return along_crease(n, crease_a_, pair_.b, -1, pair_.b.vertex(last_b_), x);
    }
    return ask_tilted(normal.dot(n) < 0 ? Vector3(-normal / length) : Vector3(normal / length),
                      x);
  }

  // One body's nearest point on its crease (`crease`; the other body `other`, whose support is
  // asked along `side` times the direction, and its last support point `other_point`): the
  // direction lies on the crease, where the separation is smooth along the one direction e that
  // stays on it; Newton's step along e, from n moved onto the crease.
  [[gnu::noinline]] const Vector3& along_crease(const Vector3& n, Crease& crease,
                                                const FramedBody& other,
                              Scalar side, const Vector3& other_point, const Vector3& x) {
    Vector3 normal;
    Scalar own;
    if (!crease.at(n, other_point, normal, own)) return x;
    const Vector3 onto = n - n.dot(normal) * normal;
    const Scalar onto_length = onto.norm();
    if (!(onto_length > 0)) return x;
    const Vector3 m = onto / onto_length;
    const Vector3 e = normal.cross(m);
    // The support point at n stands for the one at m: the crease's two parts differ only along
    // its normal, which m and e are normal to, and n lies on the crease after the first step.
    // The start's test comes before the other body's curvature, which most calls need not read.
    const Scalar phi = m.dot(last_point_);
    const Scalar slope = e.dot(last_point_);
    if (!(phi > 0) || !(slope * slope <= (2 + kStart) * kStart * phi * phi)) return x;
    Vector3 form = Vector3::Zero();
    if (!other.add_support_curvature(side * m, e, e, form)) {
      on_ = false;
      return x;
    }
    const Scalar curvature = form(0) + own + phi;
    if (!(curvature > 0)) return x;
    const Scalar step = slope / curvature;
    if (!(std::abs(step) < kLargestStep)) return x;
    if (std::abs(step) < smallest_step_) return converged(x);
    Vector3 turned = (m + step * e).normalized();
    // A cone's crease turns with the azimuth (its normal is the slant at the azimuth): the
    // step, along the crease's tangent, is moved back onto it at the new azimuth.
    if (crease.turns()) {
      if (!crease.at(turned, other_point, normal, own)) return x;
      turned = (turned - turned.dot(normal) * normal).normalized();
    }
    return ask_tilted(turned, x);
  }

  // `direction`, tilted a hair towards x's part along each crease's normal (Crease::tilt).
  const Vector3& ask_tilted(const Vector3& direction, const Vector3& x) {
    Vector3 tilted = direction;
    crease_a_.tilt(x, tilt_, tilted);
    crease_b_.tilt(x, tilt_, tilted);
    const Scalar length = tilted.norm();
    if (!(length > 0) || !std::isfinite(length)) return x;
    asked_ = tilted / length;
    extrapolated_ = true;
    return asked_;
  }

  // Whether the point `q`, asked along direction(x), is kept (nearer_than_corral);
  // a point refused ends the steps (along an edge, forgets the edge), and ask() asks again.
  bool keep(const Vector3& x, const OraclePoint& q) {
    if (!extrapolated_ || nearer_than_corral(x, x.dot(q.p))) return true;
    if (edge_step_) {
      edge_step_ = false;
      crease_a_.forget_edge();
      crease_b_.forget_edge();
      return false;
    }
    on_ = false;
    return false;
  }

  // A support point's gap |p| - n . p within this of its separation n . p starts the steps;
  // steps longer than kLargestStep (about half a radian) are not asked.
  static constexpr Scalar kStart = 1e-1;
  static constexpr Scalar kLargestStep = 0.5;

  // A step shorter than smallest_step_: the direction is Newton's to its square, and the
  // corral's point x as near; the rest is asked along x, so that the last lower bound lies along
  // the witnesses' direction (a signed distance's finish reads the separation along them, and
  // asked a support pair of its own, out of line, where the search's last direction was
  // Newton's: a C++ probe of 300 random pairs apart, two cylinders at 1e-9, 17,298 -> 16,107
  // instructions a query; at 3e-7, 16,304 -> 15,141).
  const Vector3& converged(const Vector3& x) {
    on_ = false;
    return x;
  }

  const FramedPair& pair_;
  Crease crease_a_;
  Crease crease_b_;
  // Whether either body is a cylinder or a cone (else no crease is tracked).
  bool creases_;
  // How far a direction on a crease is tilted towards x's part: a thousandth of the tolerance,
  // which the separation loses at most twice over (the frame's points lie in the unit ball).
  Scalar tilt_;
  // Steps shorter than this end Newton's steps (`converged`): ten times the tolerance (10 to
  // 300 times it gave within 3% of each other at tolerances 3e-7 to 1e-11; a fixed 1e-3 took up
  // to 20% more instructions at 1e-9, a fixed 1e-7 up to 5% more at 3e-7).
  Scalar smallest_step_;
  // The last direction asked and its point, from which the next step starts.
  Vector3 last_ = Vector3::Zero();
  Vector3 last_point_ = Vector3::Zero();
  // The bodies' points of last_point_.
  int last_a_ = -1;
  int last_b_ = -1;
  // Newton's last direction (unit).
  Vector3 asked_ = Vector3::Zero();
  // Whether the first point (along the start) was asked, the steps are still on, and the point
  // just asked was asked along asked_.
  bool asked_once_ = false;
  bool on_ = true;
  bool extrapolated_ = false;
  bool edge_step_ = false;
};

}  // namespace swarmcollide::detail
