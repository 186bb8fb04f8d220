#include "swarmcollide/problem/certificate.hpp"

#include <stdexcept>

namespace swarmcollide {

Scalar separation(const ConvexPolyhedron& a, const ConvexPolyhedron& b, const Vector3& direction) {
  const Scalar length = direction.norm();
  if (!(length > 0) || !direction.allFinite()) {
    throw std::invalid_argument("direction must be a finite, nonzero vector");
  }
  const Vector3 n = direction / length;
  return (b.vertices() * n).minCoeff() - (a.vertices() * n).maxCoeff();
}

}  // namespace swarmcollide
