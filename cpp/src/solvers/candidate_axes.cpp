#include "candidate_axes.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "../geometry/unit_direction.hpp"
#include "minkowski.hpp"

namespace swarmcollide::detail {

namespace {

// Crossings of edges at least this far from parallel (sine of the angle) take their axis from a
// cross product in double precision: its direction is within 16 u / sine of the true one.
constexpr Scalar kWellConditioned = 1e-4;
// Closer to parallel, the cross product is formed in extended precision (unit roundoff 2^-64)
// down to this sine; below it the facet normal is bounded over the arc it can lie on instead.
constexpr Scalar kExtendedConditioned = 1e-9;
constexpr long double kExtendedRoundoff = 0x1p-64L;
// Slack of the membership tests of the arc method's own boundary points (computed by acos and
// atan2 to about 1e-15); admitting more points only raises the bound.
constexpr Scalar kBoundarySlack = 1e-12;
constexpr Scalar kSqrt3 = 1.7320508075688772;

// A unit normal of the triangle (p, q, r) and a bound on its angle to the exact one: the edge
// vectors carry one roundoff per coordinate and the cross product two more, so the error of the
// unnormalised normal is within 8 u |q - p| |r - p|; doubled, plus normalisation. The lengths
// are taken without squaring tiny entries (robust_length): a body far smaller than its pair has
// edges whose squares vanish. Where the cross product itself underflows (its entries lose their
// digits below 2^-1022), the normal is not trusted.
void triangle_normal(const Vector3& p, const Vector3& q, const Vector3& r, Vector3& normal,
                     Scalar& error) {
  const Vector3 e1 = q - p;
  const Vector3 e2 = r - p;
  const Vector3 c = e1.cross(e2);
  const Scalar length = robust_length(c);
  if (!(length >= std::numeric_limits<Scalar>::min())) {
    normal = Vector3::UnitZ();
    error = 4;  // useless, and so safe: any direction is within angle pi
    return;
  }
  normal = unit_direction_or(c, Vector3::UnitZ());
  error = 16 * kRoundoff * robust_length(e1) * robust_length(e2) / length + 4 * kRoundoff;
}

}  // namespace

void CandidateAxes::collect(const FramedBody& body, bool negate, std::vector<Arc>& arcs,
                            std::vector<Facet>& facets, std::vector<int>& slot_face,
                            std::vector<int>& ring, Scalar& hull_error) {
  arcs.clear();
  facets.clear();
  hull_error = 0;
  const Hull& hull = body.hull();
  const Scalar sign = negate ? -1 : 1;
  const auto add_arc = [&](int p, int q, const Vector3& u, const Vector3& v, Scalar tau,
                           bool full) {
    Arc arc;
    arc.p = p;
    arc.q = q;
    // An edge too short to have a direction in this frame leaves the Gauss map unknown: the
    // hulls then stray from the polytopes described by an unknown distance (no bound).
    const std::optional<Vector3> t = unit_direction(body.vertex(q) - body.vertex(p));
    if (!t) hull_error = std::numeric_limits<Scalar>::infinity();
    arc.t = t ? *t : Vector3::UnitX();
    arc.u = sign * u;
    arc.v = sign * v;
    arc.P = arc.t.cross(arc.u);
    arc.Q = arc.v.cross(arc.t);
    arc.M = arc.u + arc.v;
    arc.tau = tau;
    arc.full = full;
    if (full) arc.P = arc.Q = arc.M = Vector3::Zero();
    arcs.push_back(arc);
  };
  // How far the points stray from the structure the hull describes (rounding in Qhull, or the
  // flattening of nearly flat, collinear or coincident sets): the bound holds for the described
  // polytopes, which are within this (Hausdorff) distance of the true hulls.
  const auto stray = [&](const Vector3& normal, const Vector3& origin, bool both_sides) {
    Scalar worst = 0;
    for (int i = 0; i < body.size(); ++i) {
      const Scalar h = normal.dot(body.vertex(i) - origin);
      worst = std::max(worst, both_sides ? std::abs(h) : h);
    }
    return worst;
  };
  const int count = static_cast<int>(hull.faces.rows());
  if (hull.dimension == 3) {
    facets.resize(count);
    for (int f = 0; f < count; ++f) {
      const Vector3 p = body.vertex(hull.faces(f, 0));
      triangle_normal(p, body.vertex(hull.faces(f, 1)), body.vertex(hull.faces(f, 2)),
                      facets[f].normal, facets[f].error);
      hull_error = std::max(hull_error, stray(facets[f].normal, p, false));
      facets[f].normal *= sign;
      facets[f].vertex = hull.faces(f, 0);
    }
    // The face on the left of each directed edge, by the edge's slot in the adjacency rows.
    const std::vector<int>& offsets = hull.neighbour_offsets;
    const auto slot = [&](int p, int q) {
      for (int s = offsets[p]; s < offsets[p + 1]; ++s) {
        if (hull.neighbours[s] == q) return s;
      }
      return -1;
    };
    slot_face.assign(hull.neighbours.size(), -1);
    for (int f = 0; f < count; ++f) {
      for (int k = 0; k < 3; ++k) {
        const int s = slot(hull.faces(f, k), hull.faces(f, (k + 1) % 3));
        if (s >= 0) slot_face[s] = f;
      }
    }
    for (int p = 0; p < body.size(); ++p) {
      for (int s = offsets[p]; s < offsets[p + 1]; ++s) {
        const int q = hull.neighbours[s];
        if (q < p) continue;
        const int f = slot_face[s];
        const int back = slot(q, p);
        const int g = back >= 0 ? slot_face[back] : -1;
        if (f < 0 || g < 0) continue;
        // Facets were already negated for B; the arc takes the body's own normals.
        add_arc(p, q, sign * facets[f].normal, sign * facets[g].normal,
                2 * (facets[f].error + facets[g].error) + 16 * kRoundoff, false);
      }
    }
  } else if (hull.dimension == 2) {
    // The top half of the faces is a fan over the ring: (r0, r1, r2), (r0, r2, r3), ...
    const int fan = count / 2;
    ring.clear();
    ring.push_back(hull.faces(0, 0));
    ring.push_back(hull.faces(0, 1));
    for (int f = 0; f < fan; ++f) ring.push_back(hull.faces(f, 2));
    // The normal from the best-shaped fan triangle is the most accurate.
    Vector3 normal = Vector3::UnitZ();
    Scalar error = 4;
    for (int f = 0; f < fan; ++f) {
      Vector3 n;
      Scalar e;
      triangle_normal(body.vertex(hull.faces(f, 0)), body.vertex(hull.faces(f, 1)),
                      body.vertex(hull.faces(f, 2)), n, e);
      if (e < error) {
        error = e;
        normal = n;
      }
    }
    hull_error = stray(normal, body.vertex(ring[0]), true);
    facets.push_back({sign * normal, error, ring[0]});
    facets.push_back({-sign * normal, error, ring[0]});
    const int size = static_cast<int>(ring.size());
    for (int i = 0; i < size; ++i) {
      add_arc(ring[i], ring[(i + 1) % size], normal, -normal, 2 * error + 16 * kRoundoff, false);
    }
  } else if (hull.dimension == 1) {
    const int p = hull.vertex_indices[0];
    const int q = hull.vertex_indices[1];
    add_arc(p, q, Vector3::Zero(), Vector3::Zero(), 0, true);
    const Vector3 t = arcs.back().t;
    for (int i = 0; i < body.size(); ++i) {
      const Vector3 d = body.vertex(i) - body.vertex(p);
      hull_error = std::max(hull_error, (d - d.dot(t) * t).norm());
    }
  } else {
    const Vector3 origin = body.vertex(hull.vertex_indices[0]);
    for (int i = 0; i < body.size(); ++i) {
      hull_error = std::max(hull_error, (body.vertex(i) - origin).norm());
    }
  }
}

void CandidateAxes::offer(AxesBound& bound, const Vector3& n, Scalar estimate, Scalar error) {
  bound.upper = std::max(bound.upper, estimate + error);
  // The best direction by its estimate, not its bound: a sliver's loose error must not win.
  if (estimate > best_estimate_) {
    best_estimate_ = estimate;
    bound.best_normal = n;
  }
}

AxesBound CandidateAxes::run(const FramedBody& a, const FramedBody& b, Scalar coordinate) {
  AxesBound bound;
  best_estimate_ = -std::numeric_limits<Scalar>::infinity();
  Scalar error_a = 0;
  Scalar error_b = 0;
  collect(a, false, arcs_a_, facets_a_, slot_face_, ring_, error_a);
  collect(b, true, arcs_b_, facets_b_, slot_face_, ring_, error_b);
  const Scalar hull_error = error_a + error_b;
  const Scalar reach = 2 * kSqrt3 * coordinate;  // bounds |y - x|
  const Scalar margin = separation_margin(coordinate);
  // A flat A - B lies in a plane; the candidates include both normals of it (a flat body's
  // faces, two segments' crossing, or the axes) within angle `error`, and s(n) + s(-n) >= -error
  // * width then, so the bound cannot fall below -flat_slack.
  Scalar flat_slack = 4 * margin;
  for (const auto* facets : {&facets_a_, &facets_b_}) {
    if (facets->size() == 2)
      flat_slack = std::max(flat_slack, 2 * ((*facets)[0].error + 8 * kRoundoff) * reach);
  }

  // Face normals: A's support is the face itself, B's is climbed to (and vice versa).
  int climb_a = -1;
  int climb_b = -1;
  for (const Facet& f : facets_a_) {
    climb_b = b.support_index(-f.normal, climb_b);
    const Vector3 w = b.vertex(climb_b) - a.vertex(f.vertex);
    offer(bound, f.normal, f.normal.dot(w), (f.error + 8 * kRoundoff) * w.norm());
  }
  for (const Facet& f : facets_b_) {
    climb_a = a.support_index(f.normal, climb_a);
    const Vector3 w = b.vertex(f.vertex) - a.vertex(climb_a);
    offer(bound, f.normal, f.normal.dot(w), (f.error + 8 * kRoundoff) * w.norm());
  }

  // Edge pairs whose arcs cross (inclusively): the facet normal is +-(t_a x t_b) and the edges
  // are the supports there, so n.(y_b - x_a) is the separation.
  const auto on_arc = [](const Arc& arc, const Vector3& x, Scalar slack) {
    if (arc.full) return true;
    const Scalar s = arc.tau + slack;
    return x.dot(arc.P) >= -s && x.dot(arc.Q) >= -s && x.dot(arc.M) >= -2 * s;
  };
  for (const Arc& ea : arcs_a_) {
    for (const Arc& eb : arcs_b_) {
      ++bound.pairs;
      // The arc of one edge must reach the great circle of the other.
      if (!ea.full) {
        const Scalar du = ea.u.dot(eb.t);
        const Scalar dv = ea.v.dot(eb.t);
        const Scalar s = ea.tau + 1e-12;
        if ((du > s && dv > s) || (du < -s && dv < -s)) continue;
      }
      if (!eb.full) {
        const Scalar du = eb.u.dot(ea.t);
        const Scalar dv = eb.v.dot(ea.t);
        const Scalar s = eb.tau + 1e-12;
        if ((du > s && dv > s) || (du < -s && dv < -s)) continue;
      }
      const Vector3 w = b.vertex(eb.p) - a.vertex(ea.p);
      Vector3 k = ea.t.cross(eb.t);
      Scalar sine = k.norm();
      Scalar error = 16 * kRoundoff / sine + 4 * kRoundoff;
      if (!(sine >= kWellConditioned)) {
        using Extended = Eigen::Matrix<long double, 3, 1>;
        const Extended da = a.vertex(ea.q).cast<long double>() - a.vertex(ea.p).cast<long double>();
        const Extended db = b.vertex(eb.q).cast<long double>() - b.vertex(eb.p).cast<long double>();
        const Extended kx = da.cross(db);
        const long double relative = kx.norm() / (da.norm() * db.norm());
        sine = static_cast<Scalar>(relative);
        if (sine >= kExtendedConditioned) {
          // Made unit before it is rounded to double: two edges of a body 1e-154 of its pair's
          // size have a cross product whose entries underflow there.
          k = (kx / kx.norm()).cast<Scalar>();
          error = static_cast<Scalar>(16 * kExtendedRoundoff / relative) + 4 * kRoundoff;
        } else {
          // Nearly parallel: the facet normal lies on ea's great circle, on both arcs. Bound
          // n.w over that set: its maximum is at the direction of w or at a boundary point.
          const Vector3 e1 = unit_direction_or(
              ea.full ? ea.t.unitOrthogonal() : Vector3(ea.u - ea.u.dot(ea.t) * ea.t),
              ea.t.unitOrthogonal());
          const Vector3 e2 = ea.t.cross(e1);
          std::array<std::pair<Vector3, Scalar>, 6> constraints;
          int used = 0;
          for (const Arc* arc : {&ea, &eb}) {
            if (arc->full) continue;
            constraints[used++] = {arc->P, arc->tau};
            constraints[used++] = {arc->Q, arc->tau};
            constraints[used++] = {arc->M, 2 * arc->tau};
          }
          std::array<Vector3, 13> points;
          int count = 0;
          const Vector3 toward = w.dot(e1) * e1 + w.dot(e2) * e2;
          points[count++] = unit_direction_or(toward, e1);
          for (int c = 0; c < used; ++c) {
            const Vector3& v = constraints[c].first;
            const Scalar c1 = v.dot(e1);
            const Scalar c2 = v.dot(e2);
            const Scalar rho = std::hypot(c1, c2);
            if (!(rho > constraints[c].second)) continue;
            const Scalar centre = std::atan2(c2, c1);
            const Scalar half = std::acos(-constraints[c].second / rho);
            for (const Scalar phi : {centre - half, centre + half}) {
              points[count++] = std::cos(phi) * e1 + std::sin(phi) * e2;
            }
          }
          Scalar best = -1e300;
          Vector3 best_point = points[0];
          for (int i = 0; i < count; ++i) {
            bool member = true;
            for (int c = 0; c < used; ++c) {
              member = member && points[i].dot(constraints[c].first) >=
                                     -(constraints[c].second + kBoundarySlack);
            }
            if (member && points[i].dot(w) > best) {
              best = points[i].dot(w);
              best_point = points[i];
            }
          }
          if (best > -1e300) offer(bound, best_point, best, 16 * kRoundoff * w.norm());
          // Two nearly parallel segments span a parallelogram whose width across any direction
          // orthogonal to one of them is at most sine times its length.
          if (ea.full && eb.full)
            flat_slack = std::max(flat_slack, 2 * (sine + 8 * kRoundoff) * reach);
          continue;
        }
      }
      k.normalize();  // unit already, or the cross product of unit vectors at a sine >= 1e-4
      if (ea.full && eb.full)
        flat_slack = std::max(flat_slack, 2 * (error + 8 * kRoundoff) * reach);
      for (const Scalar side : {1.0, -1.0}) {
        const Vector3 n = side * k;
        if (on_arc(ea, n, error) && on_arc(eb, n, error)) {
          offer(bound, n, n.dot(w), (error + 8 * kRoundoff) * w.norm());
        }
      }
    }
  }

  // Extra axes never hurt, and make a flat difference of point-like bodies show its plane: the
  // coordinate axes and, for a segment, two directions across it. Their separations are computed
  // along the exact (stored) directions, by scanning.
  std::array<Vector3, 10> extra;
  int extras = 0;
  for (int i = 0; i < 3; ++i) extra[extras++] = Vector3::Unit(i);
  for (const auto* arcs : {&arcs_a_, &arcs_b_}) {
    if (arcs->size() == 1 && arcs->front().full) {
      const Vector3 across = arcs->front().t.unitOrthogonal();
      extra[extras++] = across;
      extra[extras++] = arcs->front().t.cross(across);
    }
  }
  for (int i = 0; i < extras; ++i) {
    for (const Scalar side : {1.0, -1.0}) {
      const Vector3 n = side * extra[i];
      offer(bound, n, exact_separation(a, b, n), margin);
    }
  }
  bound.upper += hull_error;
  bound.flat_slack = flat_slack + 2 * hull_error;
  return bound;
}

}  // namespace swarmcollide::detail
