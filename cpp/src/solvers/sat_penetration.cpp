#include "sat_penetration.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "minkowski.hpp"
#include "witness.hpp"

namespace swarmcollide::detail {

namespace {

constexpr Scalar kEpsilon = std::numeric_limits<Scalar>::epsilon();

// An axis with the bound on how far its separation can be from that of the exact axis it
// stands for: its direction's rounding, 8 eps |u||v| / |u x v| radians for a cross product of
// rounded vectors u and v, times 2, the largest |y - x| in the frame (s is 2-Lipschitz there).
struct Axis {
  Vector3 direction;
  Scalar error;
};

void add_cross(const Vector3& u, const Vector3& v, std::vector<Axis>& axes) {
  const Vector3 c = u.cross(v);
  const Scalar length = c.norm();
  if (!(length > 0)) return;
  const Scalar error = kFrameRounding + 16 * kEpsilon * u.norm() * v.norm() / length;
  axes.push_back({c / length, error});
  axes.push_back({-c / length, error});
}

std::vector<std::pair<int, int>> edges_of(const Hull& hull) {
  std::vector<std::pair<int, int>> edges;
  const int points = static_cast<int>(hull.neighbour_offsets.size()) - 1;
  for (int i = 0; i < points; ++i) {
    for (int k = hull.neighbour_offsets[i]; k < hull.neighbour_offsets[i + 1]; ++k) {
      if (hull.neighbours[k] > i) edges.emplace_back(i, hull.neighbours[k]);
    }
  }
  return edges;
}

// How far the body's points are from the affine hull its Hull declares (flat, a segment or a
// point, to within the flatness tolerance): candidates computed for the declared shape can miss
// the true optimum by at most this much.
Scalar deviation_from_hull(const FramedBody& body) {
  const Hull& hull = body.hull();
  if (hull.dimension == 3) return 0;
  const Vector3 origin = body.vertex(hull.vertex_indices[0]);
  Scalar deviation = 0;
  if (hull.dimension == 0) {
    for (int i = 0; i < body.size(); ++i) deviation = std::max(deviation, (body.vertex(i) - origin).norm());
  } else if (hull.dimension == 1) {
    const Vector3 axis = (body.vertex(hull.vertex_indices[1]) - origin).normalized();
    for (int i = 0; i < body.size(); ++i) {
      deviation = std::max(deviation, (body.vertex(i) - origin).cross(axis).norm());
    }
  } else {
    const int* f = &hull.faces(0, 0);
    const Vector3 normal =
        (body.vertex(f[1]) - origin).cross(body.vertex(f[2]) - origin).normalized();
    for (int i = 0; i < body.size(); ++i) {
      deviation = std::max(deviation, std::abs(normal.dot(body.vertex(i) - origin)));
    }
  }
  return deviation + kFrameRounding;
}

// Whether B - A has an interior; without one, the bodies cannot overlap by any depth.
bool difference_is_solid(const FramedBody& a, const FramedBody& b) {
  const int da = a.hull().dimension;
  const int db = b.hull().dimension;
  if (da == 3 || db == 3) return true;
  if (da + db < 3) return false;
  const auto normal_of = [](const FramedBody& body) {
    const int* f = &body.hull().faces(0, 0);
    return Vector3((body.vertex(f[1]) - body.vertex(f[0])).cross(body.vertex(f[2]) - body.vertex(f[0])).normalized());
  };
  const auto axis_of = [](const FramedBody& body) {
    const auto& v = body.hull().vertex_indices;
    return Vector3((body.vertex(v[1]) - body.vertex(v[0])).normalized());
  };
  if (da == 2 && db == 2) return normal_of(a).cross(normal_of(b)).norm() > 1e-12;
  const Vector3 normal = da == 2 ? normal_of(a) : normal_of(b);
  const Vector3 axis = da == 1 ? axis_of(a) : axis_of(b);
  return std::abs(normal.dot(axis)) > 1e-12;
}

}  // namespace

Answer sat_penetration(const FramedPair& pair, const Vector3& hint, Scalar distance_upper,
                       long max_edge_pairs) {
  const FramedBody& a = pair.a;
  const FramedBody& b = pair.b;
  std::vector<Axis> axes;
  if (hint.norm() > 0) axes.push_back({hint.normalized(), kFrameRounding});
  for (const FramedBody* body : {&a, &b}) {
    const FaceMatrix& faces = body->hull().faces;
    for (Eigen::Index f = 0; f < faces.rows(); ++f) {
      const Vector3 p = body->vertex(faces(f, 0));
      add_cross(body->vertex(faces(f, 1)) - p, body->vertex(faces(f, 2)) - p, axes);
    }
  }
  const auto edges_a = edges_of(a.hull());
  const auto edges_b = edges_of(b.hull());
  // A difference without interior (collinear segments, say) has no facets; a direction across
  // an edge is then among the best.
  for (const auto& [body, edges] : {std::pair{&a, &edges_a}, std::pair{&b, &edges_b}}) {
    for (const auto& [i, j] : *edges) {
      const Vector3 across = (body->vertex(j) - body->vertex(i)).unitOrthogonal();
      axes.push_back({across, kFrameRounding});
      axes.push_back({-across, kFrameRounding});
    }
  }
  const bool enumerated =
      static_cast<long>(edges_a.size()) * static_cast<long>(edges_b.size()) <= max_edge_pairs;
  if (enumerated) {
    for (const auto& [i, j] : edges_a) {
      const Vector3 ea = a.vertex(j) - a.vertex(i);
      for (const auto& [k, l] : edges_b) add_cross(ea, b.vertex(l) - b.vertex(k), axes);
    }
  }
  Answer answer;
  Scalar bound = -std::numeric_limits<Scalar>::infinity();
  Vector3 best = Vector3::UnitX();
  answer.lower = -std::numeric_limits<Scalar>::infinity();
  int hint_a = -1;
  int hint_b = -1;
  for (const Axis& axis : axes) {
    const Scalar s = separation(a, b, axis.direction, hint_a, hint_b);
    ++answer.evaluations;
    bound = std::max(bound, s + axis.error);
    if (s > answer.lower) {
      answer.lower = s;
      best = axis.direction;
    }
  }
  if (!(answer.lower > -std::numeric_limits<Scalar>::infinity())) {
    answer.lower = separation(a, b, best);
  }
  answer.upper = distance_upper;
  if (enumerated && difference_is_solid(a, b)) {
    answer.upper = std::min(answer.upper,
                            bound + deviation_from_hull(a) + deviation_from_hull(b));
  }
  signed_witnesses(pair, best, answer.lower, answer);
  return answer;
}

}  // namespace swarmcollide::detail
