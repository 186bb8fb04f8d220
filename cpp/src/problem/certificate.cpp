#include "swarmcollide/problem/certificate.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>

namespace swarmcollide {

Scalar separation(const ConvexPolyhedron& a, const ConvexPolyhedron& b, const Vector3& direction) {
  const Scalar length = direction.norm();
  if (!(length > 0) || !direction.allFinite()) {
    throw std::invalid_argument("direction must be a finite, nonzero vector");
  }
  const Vector3 n = direction / length;
  // Loops rather than matrix-vector products: no temporaries inside solver iterations.
  Scalar lowest_b = std::numeric_limits<Scalar>::infinity();
  for (Eigen::Index j = 0; j < b.vertices().rows(); ++j) {
    lowest_b = std::min(lowest_b, b.vertices().row(j).dot(n));
  }
  Scalar highest_a = -std::numeric_limits<Scalar>::infinity();
  for (Eigen::Index i = 0; i < a.vertices().rows(); ++i) {
    highest_a = std::max(highest_a, a.vertices().row(i).dot(n));
  }
  return lowest_b - highest_a;
}

}  // namespace swarmcollide
