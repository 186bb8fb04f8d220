// The paper's swarm over separating directions; private to the library's sources.
#pragma once

#include <cstdint>
#include <vector>

#include "../geometry/framed_body.hpp"
#include "swarmcollide/detail/random.hpp"
#include "swarmcollide/solvers/dual_options.hpp"
#include "swarmcollide/solvers/swarm.hpp"

namespace swarmcollide::detail {

/// The paper's rank-adaptive swarm (8)-(11) maximising the separation
/// `s(n) = min_j n.y_j - max_i n.x_i` over unit directions, a function of two parameters whatever
/// the vertex count. The particles live in the exponential chart of the sphere at a round's
/// centre, so they have no pole to trip over; each keeps the support points of its last
/// direction, from which hill climbing on large bodies starts. One round at a time: `seed`, then
/// `step` until the caller is satisfied. Its buffers are thread-local, so a warmed-up swarm
/// allocates nothing.
class DirectionSwarm {
 public:
  DirectionSwarm(const FramedPair& pair, const DualOptions& options, std::uint64_t seed);

  /// A round: particle 0 at `centre`, the others and their first velocities uniform in the
  /// disc of `radius` (radians) around it; supports climb from `hint_a`, `hint_b` or an earlier
  /// particle's, whichever is higher.
  void seed(const Vector3& centre, Scalar radius, int hint_a, int hint_b);
  /// One move (10)-(11) of every particle, ranked by personal best for (8)-(9); returns whether
  /// the global best improved.
  bool step();

  /// The global best: its direction, its separation and its support points (a curved body's
  /// numbered among its points when asked: the particles' own are not).
  Vector3 best_direction() const;
  Scalar best_value() const { return personal_value()[best_]; }
  int best_support_a() const;
  int best_support_b() const;
  /// Separations evaluated so far.
  long evaluations() const { return evaluations_; }

 private:
  struct Chart {
    Vector3 centre;
    Vector3 e1;
    Vector3 e2;
    Vector3 direction(const Eigen::Vector2d& w) const;
  };

  Scalar evaluate(const Vector3& n, int& ia, int& ib);
  Eigen::Vector2d uniform_in_disc(Scalar radius);
  const std::vector<Scalar>& personal_value() const;

  const FramedPair& pair_;
  const DualOptions& options_;
  Xoshiro256 rng_;
  Chart chart_;
  Scalar radius_ = 0;
  int best_ = 0;
  long evaluations_ = 0;
};

}  // namespace swarmcollide::detail
