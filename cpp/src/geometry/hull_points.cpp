#include "swarmcollide/geometry/hull_points.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>
#include <vector>

#include "framed_body.hpp"
#include "hull_graph.hpp"
#include "normalise.hpp"

// Why leaving a point out is sound. The solvers compare the points as `centred` holds them
// (supports, separations, and the certificates' rounding margins, which cover the rounding of the
// centring itself), so a point may be left out when it lies, in exact arithmetic, in the hull of
// the points kept: no direction's support maximum then changes, and every bound proven over the
// kept points holds over all of them. Two kinds of point are left out:
// - exact repeats of an earlier point (the earliest copy stays, so ties still go to the first
//   index);
// - points strictly behind the plane of every triangle of the hull's surface, each side decided
//   beyond rounding (Shewchuk's error bound for orient3d). The triangles' corners are kept points
//   and form a closed, consistently oriented surface (checked here). The solid angles its
//   triangles subtend at such a point all have one sign and none is zero, so their sum, 4 pi
//   times the surface's winding number around the point, is not zero; the surface lies in the
//   hull of its corners, outside which its winding number is zero: the point is in that hull.
// Nothing here trusts Qhull's tolerances: a point that its merged facets left off the vertex set
// although it lies outside them by a hair, or on them, is not strictly behind every plane, and is
// kept. So is every point of a flat or collinear body but repeats (a flat hull lists each triangle
// twice, facing both ways, so no point is behind all of them). Kept points that are not vertices
// of the hull are off its edge graph: hill climbs never reach them, as before, while the scans
// that proven bounds rest on read them. The test runs on `centred` scaled by a power of two
// (exactly), so its outcome does not depend on the body's scale or on an exact translation.

namespace swarmcollide {

namespace {

// Shewchuk's bound on the rounding of orient3d's determinant computed from rounded differences,
// relative to its permanent: o3derrboundA = (7 + 56 u) u (predicates.c), rounded up to 8 u. The
// absolute term covers products that underflow (each off by at most 2^-1074), far below any
// determinant of points in the unit ball that the test could decide.
constexpr Scalar kOrientationBound = 8 * detail::kRoundoff;
constexpr Scalar kUnderflow = std::numeric_limits<Scalar>::min();

// The triangles of the hull's surface set up for orientation tests against many points, one
// array per quantity so that the test of a point against all of them vectorises: for each, its
// first corner a, the 2x2 minors of its edges u = b - a and v = c - a (their cross product,
// outward by the right-hand rule) and the magnitudes of each minor's two terms.
struct Planes {
  std::vector<Scalar> corner[3];
  std::vector<Scalar> minor[3];
  std::vector<Scalar> magnitude[3];

  void add(const VertexMatrix& points, int a, int b, int c) {
    const Vector3 u = points.row(b) - points.row(a);
    const Vector3 v = points.row(c) - points.row(a);
    for (int k = 0; k < 3; ++k) {
      const int i = (k + 1) % 3;
      const int j = (k + 2) % 3;
      const Scalar first = u(i) * v(j);
      const Scalar second = u(j) * v(i);
      corner[k].push_back(points(a, k));
      minor[k].push_back(first - second);
      magnitude[k].push_back(std::abs(first) + std::abs(second));
    }
  }

  // True when `x` is strictly behind every plane beyond doubt. Each determinant
  // (x - a) . (u x v) is a sum of three coordinates times 2x2 minors of the other two rows, as
  // orient3dfast sums it (expanded along x - a rather than along the z column: the same form for
  // Shewchuk's analysis), and its permanent the same sum of magnitudes.
  bool all_behind(const Vector3& x) const {
    const std::size_t count = corner[0].size();
    bool behind = true;
    for (std::size_t t = 0; t < count; ++t) {
      const Scalar wx = x.x() - corner[0][t];
      const Scalar wy = x.y() - corner[1][t];
      const Scalar wz = x.z() - corner[2][t];
      const Scalar determinant = wx * minor[0][t] + wy * minor[1][t] + wz * minor[2][t];
      const Scalar permanent = std::abs(wx) * magnitude[0][t] + std::abs(wy) * magnitude[1][t] +
                               std::abs(wz) * magnitude[2][t];
      behind &= determinant < -(kOrientationBound * permanent + kUnderflow);
    }
    return behind;
  }
};

// For each point, the first point with exactly its coordinates (itself when it is the first).
std::vector<int> first_copies(const VertexMatrix& points) {
  const int n = static_cast<int>(points.rows());
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  const auto row = [&points](int i) {
    return std::array<Scalar, 3>{points(i, 0), points(i, 1), points(i, 2)};
  };
  std::stable_sort(order.begin(), order.end(), [&](int i, int j) { return row(i) < row(j); });
  std::vector<int> first(n);
  for (int k = 0; k < n; ++k) {
    const bool repeat = k > 0 && row(order[k]) == row(order[k - 1]);
    first[order[k]] = repeat ? first[order[k - 1]] : order[k];
  }
  return first;
}

}  // namespace

HullPoints find_hull_points(const VertexMatrix& centred, const Hull& hull) {
  const int n = static_cast<int>(centred.rows());
  // Every point a vertex (so no two alike): all are read.
  if (static_cast<int>(hull.vertex_indices.size()) == n) return HullPoints{};
  const std::vector<int> first = first_copies(centred);
  std::vector<char> kept(n, 0);
  for (int v : hull.vertex_indices) kept[first[v]] = 1;
  std::vector<Eigen::RowVector3i> triangles;
  for (Eigen::Index f = 0; f < hull.faces.rows(); ++f) {
    triangles.emplace_back(first[hull.faces(f, 0)], first[hull.faces(f, 1)],
                           first[hull.faces(f, 2)]);
  }
  if (hull.dimension == 3 && detail::closed_surface(triangles)) {
    const int exponent = detail::exponent_above(centred.cwiseAbs().maxCoeff());
    VertexMatrix unit(n, 3);
    for (int i = 0; i < n; ++i) {
      for (int k = 0; k < 3; ++k) unit(i, k) = detail::times_power_of_two(centred(i, k), -exponent);
    }
    Planes planes;
    for (const auto& t : triangles) planes.add(unit, t(0), t(1), t(2));
    for (int i = 0; i < n; ++i) {
      if (first[i] == i && !kept[i]) kept[i] = !planes.all_behind(unit.row(i).transpose());
    }
  } else {
    for (int i = 0; i < n; ++i) kept[i] = kept[i] || first[i] == i;
  }

  HullPoints points;
  std::vector<int> position(n, -1);
  for (int i = 0; i < n; ++i) {
    if (!kept[i]) continue;
    position[i] = static_cast<int>(points.indices.size());
    points.indices.push_back(i);
  }
  if (static_cast<int>(points.indices.size()) == n) return HullPoints{};
  points.every_point = false;
  const int count = static_cast<int>(points.indices.size());
  points.centred.resize(count, 3);
  for (int k = 0; k < count; ++k) points.centred.row(k) = centred.row(points.indices[k]);
  points.hull.dimension = hull.dimension;
  for (int v : hull.vertex_indices) points.hull.vertex_indices.push_back(position[first[v]]);
  std::sort(points.hull.vertex_indices.begin(), points.hull.vertex_indices.end());
  points.hull.faces.resize(hull.faces.rows(), 3);
  for (Eigen::Index f = 0; f < hull.faces.rows(); ++f) {
    for (int k = 0; k < 3; ++k) points.hull.faces(f, k) = position[triangles[f](k)];
  }
  detail::fill_adjacency(points.hull, points.centred);
  return points;
}

}  // namespace swarmcollide
