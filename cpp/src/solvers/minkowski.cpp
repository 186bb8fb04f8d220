#include "minkowski.hpp"

#include <cmath>

namespace swarmcollide::detail {

namespace {

// Signed distance of the origin from the plane of (p, q, r), positive on the side the
// right-hand normal points to, and whether its sign is beyond doubt: the determinant's
// rounding is bounded by a multiple of its permanent, and the points themselves carry
// kFrameRounding.
struct PlaneSide {
  Scalar distance;
  bool certain;
  /// The plane's normal (q - p) x (r - p), and the origin's side as -p . normal.
  Vector3 normal;
  Scalar determinant;
  /// The edges q - p and r - p it was computed from.
  Vector3 u;
  Vector3 v;
};

// A bound on the rounding of the determinant w . (u x v) computed from rounded differences: 64
// roundoffs of its permanent, the sum of its terms' magnitudes.
Scalar determinant_rounding(const Vector3& w, const Vector3& u, const Vector3& v) {
  const Vector3 aw = w.cwiseAbs();
  const Vector3 au = u.cwiseAbs();
  const Vector3 av = v.cwiseAbs();
  const Scalar permanent = aw.x() * (au.y() * av.z() + au.z() * av.y()) +
                           aw.y() * (au.z() * av.x() + au.x() * av.z()) +
                           aw.z() * (au.x() * av.y() + au.y() * av.x());
  return 64 * kRoundoff * permanent;
}

PlaneSide side_of_origin(const Vector3& p, const Vector3& q, const Vector3& r) {
  const Vector3 u = q - p;
  const Vector3 v = r - p;
  const Vector3 normal = u.cross(v);
  const Scalar length = normal.norm();
  if (!(length > 0)) return {0, false, normal, 0, u, v};
  const Scalar determinant = -p.dot(normal);
  const Scalar rounding = determinant_rounding(p, u, v);
  const Scalar distance = determinant / length;
  return {distance, std::abs(determinant) > rounding && std::abs(distance) > 4 * kFrameRounding,
          normal, determinant, u, v};
}

}  // namespace

void supporting_feature(const FramedBody& body, const Vector3& n, int top, Scalar slack,
                        std::vector<char>& visited, std::vector<int>& found) {
  const Scalar floor = body.height(top, n) - slack;
  found.clear();
  // A curved body's points (its support points so far) have no hull to flood: they are scanned.
  const Hull* h = body.curved() || body.size() <= kHillClimbingThreshold ? nullptr : &body.hull();
  if (h == nullptr || !(h->neighbour_offsets[top] < h->neighbour_offsets[top + 1])) {
    for (int i = 0; i < body.size(); ++i) {
      if (body.height(i, n) >= floor) found.push_back(i);
    }
    return;
  }
  if (visited.size() < static_cast<std::size_t>(body.size())) visited.resize(body.size(), 0);
  found.push_back(top);
  visited[top] = 1;
  for (std::size_t k = 0; k < found.size(); ++k) {
    const int i = found[k];
    for (int e = h->neighbour_offsets[i]; e < h->neighbour_offsets[i + 1]; ++e) {
      const int j = h->neighbours[e];
      if (!visited[j] && body.height(j, n) >= floor) {
        visited[j] = 1;
        found.push_back(j);
      }
    }
  }
  for (int i : found) visited[i] = 0;
}

// The tetrahedron's faces, each with the vertex opposite it, all oriented alike: a face's
// normal (q - p) x (r - p) points away from its opposite vertex for one orientation of the
// tetrahedron and towards it for the other, the same for every face.
constexpr int kFaces[4][4] = {{1, 2, 3, 0}, {0, 3, 2, 1}, {0, 1, 3, 2}, {0, 2, 1, 3}};

bool encloses_origin(const std::array<Vector3, 4>& points, std::array<Scalar, 4>& weights) {
  // The origin is inside when it is on the inner side of each face, the side of the fourth point;
  // its barycentric coordinate for that point is the ratio of their two sides.
  for (const auto& face : kFaces) {
    const PlaneSide origin = side_of_origin(points[face[0]], points[face[1]], points[face[2]]);
    if (!origin.certain) return false;
    // The fourth point's side must be beyond doubt too: a flat tetrahedron has its fourth point
    // in the face's plane, where rounding alone picks the side, and encloses nothing.
    const Vector3 w = points[face[3]] - points[face[0]];
    const Scalar opposite = origin.normal.dot(w);
    if (!(std::abs(opposite) > determinant_rounding(w, origin.u, origin.v)) ||
        (origin.distance > 0) != (opposite > 0)) {
      return false;
    }
    weights[face[3]] = origin.determinant / opposite;
  }
  return true;
}

bool encloses_origin(const std::array<Vector3, 4>& points) {
  // Without the weights the fourth points' sides need not be computed. With the faces oriented
  // alike, the origin's four determinants (of the tetrahedra it makes with each face) sum, in
  // exact arithmetic, to the fourth point's determinant, the same for every face (six times the
  // signed volume). Where all four are of one sign beyond their rounding, so is that sum: the
  // tetrahedron is not flat, and each barycentric coordinate of the origin, a determinant over
  // the sum, is positive. The origin is then strictly inside, and by more than the points'
  // rounding (each face's `certain`).
  bool inner_side = false;
  for (int f = 0; f < 4; ++f) {
    const int* face = kFaces[f];
    const PlaneSide origin = side_of_origin(points[face[0]], points[face[1]], points[face[2]]);
    if (!origin.certain) return false;
    if (f == 0) {
      inner_side = origin.distance > 0;
    } else if ((origin.distance > 0) != inner_side) {
      return false;
    }
  }
  return true;
}

}  // namespace swarmcollide::detail
