#pragma once

#include <cstdint>

// The swarm's inner loops over raw arrays. Each is compiled for several instruction sets and the
// widest the processor has is chosen at load time; the files that include Eigen stay on the
// baseline so that their objects keep the alignment FCL was built with.
//
// Layout (structure of arrays): a swarm matrix has one row per weight (lambda then delta) and
// one column per particle; row r of particle j is at `data[r * stride + j]`. Per-particle arrays
// hold one value per particle.

namespace swarmcollide::detail {

/// Eight xoshiro256++ generators stepped side by side, so that one step yields eight numbers in a
/// few vector instructions. Integer arithmetic only: the same seed gives the same numbers on every
/// processor.
struct UniformLanes {
  static constexpr int kLanes = 8;
  std::uint64_t state[4][kLanes];

  explicit UniformLanes(std::uint64_t seed);
};

/// Fills `out[0, count)` with uniform numbers in [0, 1); `count` is a multiple of kLanes.
void draw_uniforms(UniformLanes& lanes, double* out, int count);

/// One uniform point of the probability simplex with `count` weights per particle, written to the
/// `count` rows of `out`: the gaps between count - 1 sorted uniform numbers, taken from the
/// count - 1 rows of `uniforms` (which are sorted in place). `column` is scratch for count - 1
/// values, used when the rows are too many for a sorting network.
void uniform_simplex_points(int count, int particles, int stride, double* uniforms, double* out,
                            double* column);

/// Particles are processed a block of kLanes at a time: `stride` is a multiple of kLanes and
/// the columns between `particles` and `stride` are computed too but never reported.
struct SwarmView {
  int rows;
  int particles;
  int stride;
  double* position;
  double* velocity;
  double* personal_best;
};

/// How particles are scored. `signed_vertices` holds, per row, -x_i for A's rows and y_j for
/// B's, three values each, so that sum_r w_r v_r is the offset of (5). With `check_bounds`, a
/// weight outside [0, 1] also makes a particle infeasible.
struct Fitness {
  const double* signed_vertices;
  bool check_bounds;
  double feasibility_tolerance;
};

/// A score orders particles as Conditions 1-3 do, by one integer comparison, smaller being
/// better: the bits of the square of (5) for a feasible particle, less kFeasibleKeyShift, and the
/// bits of the violation (6) otherwise. Nonnegative doubles order like their bits, and the shift
/// puts every feasible score below every infeasible one.
constexpr std::int64_t kFeasibleKeyShift = 0x7ff0000000000001LL;

/// Per particle, its personal best's score and whether the last generation improved it (nonzero).
struct Bests {
  std::int64_t* key;
  std::int64_t* improved;
};

/// Scores every particle's position and takes it as its personal best (generation 0).
void score_initial_positions(const SwarmView& swarm, int rows_a, const Fitness& fitness,
                             const Bests& bests);

/// One generation's move: per particle, the inertia w and the pulls c1 r1 and c2 r2 of (10); the
/// global best's weights, one per row; the velocity limit; and whether a move that leaves a
/// simplex is projected back onto it.
struct Move {
  const double* inertia;
  const double* pull_own;
  const double* pull_global;
  const double* global_best;
  double velocity_limit;
  bool project;
};

/// The most weights per body projected for a block of particles at once, by a sorting network;
/// longer vectors are projected one particle at a time by std::sort.
constexpr int kMaxRowsProjectedTogether = 8;

/// One generation for every particle, block by block while its rows are in cache:
/// - (10)-(11): v = w v + c1 r1 (p - x) + c2 r2 (g - x), and x + v written to `next`. A particle
///   whose largest velocity component exceeds the limit has its whole velocity scaled down, so
///   that the move keeps the weights' sums.
/// - With `project`, a particle with a negative weight is projected onto the simplexes, by the
///   sort-based threshold, and the displacement added to its velocity.
/// - Conditions 1-3: a particle whose score beats its personal best's (feasible beats infeasible,
///   then the smaller value wins) takes its new position as personal best; `improved` marks it.
/// Padding columns take part like particles and may be marked improved. Returns whether any
/// column improved. `column` is scratch for `rows` values.
bool advance_particles(const SwarmView& swarm, int rows_a, const Move& move, const Fitness& fitness,
                       const Bests& bests, double* next, double* column);

/// The rank (0 = best) of each particle's personal best score, ties going to the lower index.
/// Counting rather than sorting: no branch depends on the data. `key` and `rank` hold
/// `particles` values rounded up to whole blocks of kLanes.
void rank_personal_bests(int particles, const std::int64_t* key, std::int64_t* rank);

}  // namespace swarmcollide::detail
