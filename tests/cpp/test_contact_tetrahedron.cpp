// The base search of the tetrahedron a scene's contact leaves for its pair's next penetration
// (contact_tetrahedron): the triangle deepest around a point, against every triangle computed.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <vector>

#include "scene/contact_tetrahedron.hpp"

namespace swarmcollide::detail {
namespace {

struct Found {
  bool found = false;
  std::array<std::size_t, 3> base{};
};

// Every triangle's barycentric coordinates in turn, as contact_tetrahedron computed them before
// the masks: the first triangle with the largest least coordinate, if above zero.
Found every_triangle(const std::vector<Eigen::Vector2d>& points, const Eigen::Vector2d& q) {
  const auto cross = [](const Eigen::Vector2d& x, const Eigen::Vector2d& y) {
    return x.x() * y.y() - x.y() * y.x();
  };
  Found out;
  Scalar best = 0;
  const std::size_t count = points.size();
  for (std::size_t p = 0; p < count; ++p) {
    for (std::size_t r = p + 1; r < count; ++r) {
      for (std::size_t s = r + 1; s < count; ++s) {
        const Scalar area = cross(points[r] - points[p], points[s] - points[p]);
        if (!(std::abs(area) > 0)) continue;
        const Scalar wp = cross(points[r] - q, points[s] - q) / area;
        const Scalar wr = cross(points[s] - q, points[p] - q) / area;
        const Scalar least = std::min({wp, wr, 1 - wp - wr});
        if (least > best) {
          best = least;
          out.base = {p, r, s};
          out.found = true;
        }
      }
    }
  }
  return out;
}

void expect_same(const std::vector<Eigen::Vector2d>& points, const Eigen::Vector2d& q,
                 int& found) {
  const Found expected = every_triangle(points, q);
  std::array<std::size_t, 3> base{};
  const bool got = deepest_triangle(points.data(), points.size(), q, base);
  ASSERT_EQ(got, expected.found);
  if (got) {
    EXPECT_EQ(base, expected.base);
    ++found;
  }
}

// Points of a face of a Minkowski difference (every corner of one small polygon less every
// corner of another: rows of collinear points, repeated differences), random ones, and points
// of an integer grid (ties between triangles, q on their edges and corners), around points
// inside and outside them.
TEST(ContactTetrahedron, DeepestTriangleIsEveryTrianglesPick) {
  std::mt19937_64 rng(24);
  std::uniform_real_distribution<Scalar> unit(-1, 1);
  std::uniform_int_distribution<int> small(-2, 2);
  int found = 0;
  int cases = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const int kind = trial % 3;
    std::vector<Eigen::Vector2d> points;
    if (kind == 0) {
      std::vector<Eigen::Vector2d> a;
      std::vector<Eigen::Vector2d> b;
      const int na = 1 + trial / 3 % 4;
      const int nb = 1 + trial / 12 % 4;
      const Scalar scale = trial % 2 == 0 ? 1 : 0.01;
      for (int i = 0; i < na; ++i) a.emplace_back(unit(rng), unit(rng));
      for (int j = 0; j < nb; ++j) b.emplace_back(scale * unit(rng), scale * unit(rng));
      // A square less a square, as two boxes' faces.
      if (trial % 7 == 0 && na == 4) a = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
      if (trial % 7 == 0 && nb == 4) b = {{0, 0}, {0.5, 0}, {0.5, 0.5}, {0, 0.5}};
      for (const auto& x : a) {
        for (const auto& y : b) points.push_back(y - x);
      }
    } else if (kind == 1) {
      const int count = 3 + trial / 3 % 14;
      for (int m = 0; m < count; ++m) points.emplace_back(unit(rng), unit(rng));
    } else {
      const int count = 3 + trial / 3 % 14;
      for (int m = 0; m < count; ++m) points.emplace_back(small(rng), small(rng));
    }
    if (points.size() < 3 || points.size() > kMostBasePoints) continue;
    Eigen::Vector2d centre = Eigen::Vector2d::Zero();
    for (const auto& p : points) centre += p / static_cast<Scalar>(points.size());
    const Eigen::Vector2d half = kind == 2 ? Eigen::Vector2d(small(rng) / 2.0, small(rng) / 2.0)
                                           : Eigen::Vector2d((points[0] + points[1]) / 2);
    const std::array<Eigen::Vector2d, 4> around{centre, Eigen::Vector2d(unit(rng), unit(rng)),
                                                points[0], half};
    for (const auto& q : around) {
      expect_same(points, q, found);
      ++cases;
    }
  }
  // Enough cases have a triangle around q for the comparison to say something.
  EXPECT_GT(found, cases / 4);
}

}  // namespace
}  // namespace swarmcollide::detail
