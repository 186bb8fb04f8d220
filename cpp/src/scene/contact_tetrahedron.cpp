#include "contact_tetrahedron.hpp"

#include <array>
#include <cmath>

#include "../solvers/minkowski.hpp"

namespace swarmcollide::detail {

namespace {

// Differences of feature points searched for a base triangle: the search is cubic in them, and
// the contacts of a frame are mostly a vertex on a face (three or four) or an edge across an edge
// (four).
constexpr std::size_t kMostFacePoints = 16;

}  // namespace

bool contact_tetrahedron(const FramedPair& pair, const Vector3& n, const ContactFeatures& features,
                         PairProof::Enclosing& out) {
  const std::size_t count = features.a.size() * features.b.size();
  if (count < 3 || count > kMostFacePoints) return false;
  int apex_a = out.a[3];
  int apex_b = out.b[3];
  const Vector3 apex = minkowski_support(pair.a, pair.b, -n, apex_a, apex_b).p;
  std::array<Vector3, kMostFacePoints> face;
  std::array<int, kMostFacePoints> face_a;
  std::array<int, kMostFacePoints> face_b;
  std::size_t k = 0;
  Scalar height = 0;
  for (int i : features.a) {
    for (int j : features.b) {
      face[k] = pair.b.vertex(j) - pair.a.vertex(i);
      face_a[k] = i;
      face_b[k] = j;
      height += n.dot(face[k]) / static_cast<Scalar>(count);
      ++k;
    }
  }
  const Scalar apex_height = n.dot(apex);
  if (!(apex_height > 0 && height < 0)) return false;
  // Where the line from the apex through the origin meets the face's plane, in coordinates of
  // that plane; the base is the triangle of face points around it with the largest least
  // barycentric coordinate (the one it is deepest inside).
  const Vector3 helper = std::abs(n.x()) < 0.6 ? Vector3::UnitX() : Vector3::UnitY();
  const Vector3 u = n.cross(helper).normalized();
  const Vector3 v = n.cross(u);
  const Vector3 meet = apex * (height / apex_height);
  const auto plane = [&](const Vector3& p) { return Eigen::Vector2d(u.dot(p), v.dot(p)); };
  const Eigen::Vector2d q = plane(meet);
  std::array<Eigen::Vector2d, kMostFacePoints> flat;
  for (std::size_t m = 0; m < count; ++m) flat[m] = plane(face[m]);
  const auto cross = [](const Eigen::Vector2d& x, const Eigen::Vector2d& y) {
    return x.x() * y.y() - x.y() * y.x();
  };
  Scalar best = 0;
  std::array<std::size_t, 3> base{};
  bool found = false;
  for (std::size_t p = 0; p < count; ++p) {
    for (std::size_t r = p + 1; r < count; ++r) {
      for (std::size_t s = r + 1; s < count; ++s) {
        const Scalar area = cross(flat[r] - flat[p], flat[s] - flat[p]);
        if (!(std::abs(area) > 0)) continue;
        const Scalar wp = cross(flat[r] - q, flat[s] - q) / area;
        const Scalar wr = cross(flat[s] - q, flat[p] - q) / area;
        const Scalar least = std::min({wp, wr, 1 - wp - wr});
        if (least > best) {
          best = least;
          base = {p, r, s};
          found = true;
        }
      }
    }
  }
  if (!found) return false;
  const std::array<Vector3, 4> corners{face[base[0]], face[base[1]], face[base[2]], apex};
  if (!encloses_origin(corners)) return false;
  for (int c = 0; c < 3; ++c) {
    out.a[c] = face_a[base[c]];
    out.b[c] = face_b[base[c]];
  }
  out.a[3] = apex_a;
  out.b[3] = apex_b;
  return true;
}

}  // namespace swarmcollide::detail
