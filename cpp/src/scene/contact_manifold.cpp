#include "contact_manifold.hpp"

#include <algorithm>
#include <cmath>

#include "../geometry/nearest_on_segments.hpp"
#include "../solvers/minkowski.hpp"

namespace swarmcollide::detail {

namespace {

using Point2 = Eigen::Vector2d;
using Polygon = std::vector<Point2>;

// The polygons of one contact_points call, kept by each thread from call to call so that a frame
// of contacts allocates nothing once they have grown: the projected features, their hulls, the
// clipped overlap and the reduced one, and the clipping's and reduction's scratch.
struct Polygons {
  Polygon pa;
  Polygon pb;
  Polygon hull_a;
  Polygon hull_b;
  Polygon meet;
  Polygon reduced;
  Polygon scratch;
  std::vector<std::size_t> chosen;
};

Scalar cross(const Point2& a, const Point2& b) { return a.x() * b.y() - a.y() * b.x(); }

// Signed distance of `p` from the line through the edge (a, b), positive on its left.
Scalar side(const Point2& a, const Point2& b, const Point2& p) {
  const Point2 edge = b - a;
  return cross(edge, p - a) / edge.norm();
}

// The convex hull of `points` (sorted in place) into `hull`, counter-clockwise, dropping points
// within `eps` of the hull's edges: one point when all lie within `eps` of each other, the two
// ends when they lie within `eps` of a line.
void convex_hull(Polygon& points, Scalar eps, Polygon& hull) {
  std::sort(points.begin(), points.end(), [](const Point2& a, const Point2& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  std::size_t far = 0;
  for (std::size_t k = 1; k < points.size(); ++k) {
    if ((points[k] - points[0]).norm() > (points[far] - points[0]).norm()) far = k;
  }
  if ((points[far] - points[0]).norm() <= eps) {
    hull.assign(1, points[0]);
    return;
  }
  const Point2 a = points[0];
  const Point2 b = points[far];
  Scalar off_line = 0;
  for (const Point2& p : points) off_line = std::max(off_line, std::abs(side(a, b, p)));
  if (off_line <= eps) {
    // The ends along the line: the extremes of the projections.
    const Point2 u = (b - a).normalized();
    const auto by_projection = [&](const Point2& p, const Point2& q) {
      return u.dot(p) < u.dot(q);
    };
    const auto ends = std::minmax_element(points.begin(), points.end(), by_projection);
    const Point2 first = *ends.first;
    const Point2 last = *ends.second;
    hull.assign({first, last});
    return;
  }
  // Andrew's monotone chain; a turn within eps of straight does not make a vertex.
  hull.resize(2 * points.size());
  std::size_t k = 0;
  const auto turns_left = [&](const Point2& o, const Point2& p, const Point2& q) {
    return (p - o).norm() > 0 && side(o, p, q) > eps;
  };
  for (const Point2& p : points) {
    while (k >= 2 && !turns_left(hull[k - 2], hull[k - 1], p)) --k;
    hull[k++] = p;
  }
  for (std::size_t i = points.size() - 1, lower = k + 1; i-- > 0;) {
    while (k >= lower && !turns_left(hull[k - 2], hull[k - 1], points[i])) --k;
    hull[k++] = points[i];
  }
  hull.resize(k - 1);
}

// The part of convex polygon `subject` inside convex polygon `clip` (both counter-clockwise,
// at least three vertices) into `out`: Sutherland and Hodgman, one edge of `clip` at a time,
// alternating between `out` and `next`.
void clip_polygon(const Polygon& polygon, const Polygon& clip, Scalar eps, Polygon& out,
                  Polygon& next) {
  Polygon& subject = out;
  subject.assign(polygon.begin(), polygon.end());
  for (std::size_t e = 0; e < clip.size() && !subject.empty(); ++e) {
    const Point2& a = clip[e];
    const Point2& b = clip[(e + 1) % clip.size()];
    next.clear();
    for (std::size_t k = 0; k < subject.size(); ++k) {
      const Point2& p = subject[k];
      const Point2& q = subject[(k + 1) % subject.size()];
      const Scalar sp = side(a, b, p);
      const Scalar sq = side(a, b, q);
      if (sp >= -eps) next.push_back(p);
      if ((sp > eps && sq < -eps) || (sp < -eps && sq > eps)) {
        next.push_back(p + (q - p) * (sp / (sp - sq)));
      }
    }
    subject.swap(next);
  }
}

// The part of segment (s, t) inside convex polygon `clip` (counter-clockwise, at least three
// vertices) into `out`: its ends, one point when they coincide, none when it misses.
void clip_segment(const Point2& s, const Point2& t, const Polygon& clip, Scalar eps,
                  Polygon& out) {
  out.clear();
  Scalar low = 0;
  Scalar high = 1;
  for (std::size_t e = 0; e < clip.size(); ++e) {
    const Point2& a = clip[e];
    const Point2& b = clip[(e + 1) % clip.size()];
    const Scalar fs = side(a, b, s) + eps;
    const Scalar ft = side(a, b, t) + eps;
    // Inside where fs + u (ft - fs) >= 0.
    if (fs < 0 && ft < 0) return;
    if (fs < 0) low = std::max(low, fs / (fs - ft));
    if (ft < 0) high = std::min(high, fs / (fs - ft));
  }
  if (low > high) return;
  const Point2 p = s + low * (t - s);
  const Point2 q = s + high * (t - s);
  if ((q - p).norm() <= eps) {
    out.push_back((p + q) / 2);
  } else {
    out.push_back(p);
    out.push_back(q);
  }
}

// The nearest points of segments (p0, p1) and (q0, q1) (either may be a point), their midpoint.
Point2 nearest_midpoint(const Point2& p0, const Point2& p1, const Point2& q0, const Point2& q1) {
  Scalar s;
  Scalar t;
  nearest_on_segments(p0, p1, q0, q1, 0, s, t);
  return (p0 + s * (p1 - p0) + q0 + t * (q1 - q0)) / 2;
}

// Two segments, into `out`: where they cross (one point), or the ends of their common part when
// they are parallel and overlap (two points).
void meet_segments(const Point2& p0, const Point2& p1, const Point2& q0, const Point2& q1,
                   Scalar eps, Polygon& out) {
  const Point2 d = p1 - p0;
  const Scalar length = d.norm();
  const Point2 u = d / length;
  if (std::abs(side(p0, p1, q0)) <= eps && std::abs(side(p0, p1, q1)) <= eps) {
    // Along one line: the common interval of the projections onto it.
    const Scalar a = std::max(Scalar(0), std::min(u.dot(q0 - p0), u.dot(q1 - p0)));
    const Scalar b = std::min(length, std::max(u.dot(q0 - p0), u.dot(q1 - p0)));
    if (b - a > eps) {
      out.assign({Point2(p0 + a * u), Point2(p0 + b * u)});
      return;
    }
  }
  out.assign(1, nearest_midpoint(p0, p1, q0, q1));
}

// Where features `fa` and `fb` (each a point, a segment or a polygon) overlap, into `out`.
void intersect(const Polygon& fa, const Polygon& fb, Scalar eps, Polygon& out, Polygon& scratch) {
  const Polygon& small = fa.size() <= fb.size() ? fa : fb;
  const Polygon& large = fa.size() <= fb.size() ? fb : fa;
  if (small.size() == 1) {
    out.assign(1, large.size() <= 2 ? nearest_midpoint(small[0], small[0], large[0], large.back())
                                    : small[0]);
  } else if (small.size() == 2) {
    if (large.size() == 2) {
      meet_segments(small[0], small[1], large[0], large[1], eps, out);
    } else {
      clip_segment(small[0], small[1], large, eps, out);
    }
  } else {
    clip_polygon(large, small, eps, out, scratch);
  }
}

// The `count` vertices of counter-clockwise polygon `polygon` spanning the largest area found
// greedily, into `reduced`: the two farthest apart, then each time the vertex adding the largest
// triangle (`chosen` holds their indices).
void reduce(const Polygon& polygon, int count, Polygon& reduced, std::vector<std::size_t>& chosen) {
  const std::size_t n = polygon.size();
  if (n <= static_cast<std::size_t>(count)) {
    reduced.assign(polygon.begin(), polygon.end());
    return;
  }
  if (count == 1) {
    Point2 mean = Point2::Zero();
    for (const Point2& p : polygon) mean += p;
    reduced.assign(1, mean / static_cast<Scalar>(n));
    return;
  }
  std::size_t first = 0;
  std::size_t second = 1;
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n; ++j) {
      if ((polygon[i] - polygon[j]).squaredNorm() >
          (polygon[first] - polygon[second]).squaredNorm()) {
        first = i;
        second = j;
      }
    }
  }
  chosen.assign({first, second});
  while (chosen.size() < static_cast<std::size_t>(count)) {
    std::size_t best = n;
    Scalar best_area = -1;
    for (std::size_t m = 0; m < n; ++m) {
      if (std::find(chosen.begin(), chosen.end(), m) != chosen.end()) continue;
      // Its neighbours among the chosen, in the polygon's cyclic order.
      std::size_t before = chosen.back();
      std::size_t after = chosen.front();
      for (std::size_t k = 0; k < chosen.size(); ++k) {
        if (chosen[k] < m) before = chosen[k];
        if (chosen[k] > m) {
          after = chosen[k];
          break;
        }
      }
      const Scalar area =
          std::abs(cross(polygon[after] - polygon[before], polygon[m] - polygon[before]));
      if (area > best_area) {
        best_area = area;
        best = m;
      }
    }
    chosen.insert(std::upper_bound(chosen.begin(), chosen.end(), best), best);
  }
  reduced.clear();
  for (std::size_t i : chosen) reduced.push_back(polygon[i]);
}

// Appends to `projected` (as coordinates along `u` and `v`, which span the plane normal to the
// unit `d`) points of a curved body's supporting feature along `d` that its numbered points may
// lack: these are the support points found so far (FramedBody), which hold the feature only where
// a solver happened to find its extremes. A pair framed afresh for its contact points (a compound
// body's deepest part pair) held one point of a cylinder's side, a rim's, which met the other
// body's feature nowhere: their midpoint was 0.3 off both surfaces. So the support function is
// asked along `d` tilted towards four directions around it, each by the largest of the angles
// 1, 2^-5, ..., 2^-20 radians whose point lies within `slack` below `top` (the supporting plane's
// height along `d`): a disc's rim where a cap or a base faces `d` (and then four more of its
// points, between those), a side's ends, a smooth surface's points near the support point, which
// meet the other feature where the normal is a little off. The points are not numbered: added to
// the body's support points (a hash and a row each), 40 of them made the contacts of 200 curved
// bodies and boxes (277 pairs) 35% more instructions than before; these make them 7% more
// (callgrind).
void add_feature_points(const FramedBody& body, const Vector3& d, Scalar top, Scalar slack,
                        const Vector3& u, const Vector3& v, Polygon& projected) {
  const auto kept = [&](const Vector3& towards, Scalar tilt) {
    const Vector3 tilted = body.local_direction(d + tilt * towards);
    const Vector3 p = body.placed_point(body.curved_local_support(tilted));
    if (!(d.dot(p) >= top - slack)) return false;
    projected.emplace_back(u.dot(p), v.dot(p));
    return true;
  };
  bool disc = false;
  for (const Vector3& towards : {u, v, Vector3(-u), Vector3(-v)}) {
    for (Scalar tilt = 1; tilt > 0x1p-21; tilt *= 0x1p-5) {
      if (kept(towards, tilt)) {
        disc = disc || tilt == 1;
        break;
      }
    }
  }
  if (!disc) return;
  constexpr Scalar kDiagonal = 0.70710678118654752;
  for (const Vector3& towards : {Vector3(kDiagonal * (u + v)), Vector3(kDiagonal * (v - u)),
                                 Vector3(-kDiagonal * (u + v)), Vector3(kDiagonal * (u - v))}) {
    kept(towards, 1);
  }
}

}  // namespace

void contact_points(const FramedPair& pair, const Vector3& n, Scalar slack, int max_points,
                    std::vector<Vector3>& out, ContactFeatures& features) {
  // The features from their top points: found by climbing and flooding the hulls on large
  // bodies, whose every point a scan would place in the frame.
  std::vector<int>& feature_a = features.a;
  std::vector<int>& feature_b = features.b;
  thread_local std::vector<char> visited;
  const int top_index_a = pair.a.support_index(n, -1);
  const int top_index_b = pair.b.support_index(-n, -1);
  supporting_feature(pair.a, n, top_index_a, slack, visited, feature_a);
  supporting_feature(pair.b, -n, top_index_b, slack, visited, feature_b);
  const Vector3 helper = std::abs(n.x()) < 0.6 ? Vector3::UnitX() : Vector3::UnitY();
  const Vector3 u = n.cross(helper).normalized();
  const Vector3 v = n.cross(u);
  thread_local Polygons polygons;
  Polygons& g = polygons;
  g.pa.clear();
  g.pb.clear();
  for (int i : feature_a) {
    const Vector3 p = pair.a.vertex(i);
    g.pa.emplace_back(u.dot(p), v.dot(p));
  }
  for (int j : feature_b) {
    const Vector3 p = pair.b.vertex(j);
    g.pb.emplace_back(u.dot(p), v.dot(p));
  }
  const Scalar top_a = n.dot(pair.a.vertex(top_index_a));
  const Scalar bottom_b = n.dot(pair.b.vertex(top_index_b));
  if (pair.a.curved()) add_feature_points(pair.a, n, top_a, slack, u, v, g.pa);
  if (pair.b.curved()) add_feature_points(pair.b, -n, -bottom_b, slack, u, v, g.pb);
  // Halfway between the supporting planes of the rounded bodies: the cores' moved out by the radii.
  const Scalar height = (top_a + pair.radius_a) / 2 + (bottom_b - pair.radius_b) / 2;
  convex_hull(g.pa, slack, g.hull_a);
  convex_hull(g.pb, slack, g.hull_b);
  intersect(g.hull_a, g.hull_b, slack, g.meet, g.scratch);
  if (g.meet.empty()) {
    // Rounding, for features that barely touch at their borders: where they come nearest.
    Point2 mean_a = Point2::Zero();
    Point2 mean_b = Point2::Zero();
    for (const Point2& p : g.hull_a) mean_a += p / static_cast<Scalar>(g.hull_a.size());
    for (const Point2& p : g.hull_b) mean_b += p / static_cast<Scalar>(g.hull_b.size());
    g.meet.assign(1, (mean_a + mean_b) / 2);
  }
  reduce(g.meet, max_points, g.reduced, g.chosen);
  for (const Point2& p : g.reduced) out.push_back(p.x() * u + p.y() * v + height * n);
}

}  // namespace swarmcollide::detail
