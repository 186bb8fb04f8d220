#pragma once

#include <Eigen/Geometry>
#include <cmath>
#include <cstdint>
#include <random>

#include "swarmcollide/geometry/convex_polyhedron.hpp"

// Standard normals by Box-Muller on mt19937_64, whose output the C++ standard fixes; the
// standard's normal_distribution is not portable across library implementations, and the bench
// workloads must be the same bodies on every machine.
class Normals {
 public:
  explicit Normals(std::uint64_t seed) : engine_(seed) {}
  double uniform() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }
  double next() {
    const double u1 = uniform();
    const double u2 = uniform();
    return std::sqrt(-2 * std::log1p(-u1)) * std::cos(2 * M_PI * u2);
  }
  swarmcollide::Vector3 unit() {
    const swarmcollide::Vector3 v(next(), next(), next());
    return v / v.norm();
  }
  // A uniformly random rotation: a normalised quaternion of four normals.
  swarmcollide::Matrix3 rotation() {
    Eigen::Quaterniond q(next(), next(), next(), next());
    q.normalize();
    return q.toRotationMatrix();
  }

 private:
  std::mt19937_64 engine_;
};
