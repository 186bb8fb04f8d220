#pragma once

#include <cstdint>

#include "../detail/instruction_set.hpp"

// The swarm's inner loops over raw arrays. Each is compiled once per instruction set (AVX-512,
// AVX2, and the x86-64 baseline), with vectors one register wide; the widest set the processor
// runs is used unless SWARMCOLLIDE_ISA names another. Every set gives the same bits for a seed.
// The files that include Eigen stay on the baseline so that their objects keep the alignment FCL
// was built with.
//
// Layout (structure of arrays): a swarm matrix has one row per weight (lambda then delta) and
// one column per particle; row r of particle j is at `data[r * stride + j]`. Per-particle arrays
// hold one value per particle.

namespace swarmcollide::detail {

/// Eight xoshiro256++ generators stepped side by side, so that one step yields eight numbers in a
/// few vector instructions; lane l serves the particles j with j % kLanes == l. Integer arithmetic
/// only: the same seed gives the same numbers on every processor.
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

/// Particles are processed in blocks of kLanes, one per generator lane: `stride` is a multiple of
/// kLanes and the columns between `particles` and `stride` are computed too but never reported.
struct SwarmView {
  int rows;
  int particles;
  int stride;
  double* position;
  double* velocity;
  double* personal_best;
};

/// Values the kernels apply to every particle are stored kSplat times in a row, 16-byte aligned,
/// so that the baseline (SSE2, which cannot broadcast from memory) loads one as a whole vector.
constexpr int kSplat = 2;

/// How particles are scored. `signed_vertices` holds, per row, -x_i for A's rows and y_j for
/// B's, three coordinates each stored kSplat times (x x y y z z), so that sum_r w_r v_r is the
/// offset of (5). With `check_bounds`, a weight outside [0, 1] also makes a particle infeasible.
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

/// One generation's move: per particle, the inertia w and the acceleration coefficients of (10);
/// the global best's weights, one per row stored kSplat times; the velocity limit; and the
/// constraint handling.
/// - With `project` (ConstraintHandling::projection), r1 and r2 are drawn per weight from `lanes`,
///   as (3) writes the update: `pull_own` and `pull_global` hold c1 and c2.
/// - Without (the paper's feasibility rules), r1 and r2 are one pair per particle, already
///   folded in: `pull_own` and `pull_global` hold c1 r1 and c2 r2.
struct Move {
  const double* inertia;
  const double* pull_own;
  const double* pull_global;
  const double* global_best;
  double velocity_limit;
  bool project;
  UniformLanes* lanes;
};

/// One generation for every particle, a few columns at a time:
/// - (10)-(11): v = w v + c1 r1 (p - x) + c2 r2 (g - x), and x + v written to `next`.
/// - With `project`: each velocity component is clamped to the limit, each body's weights are
///   projected onto its simplex (exact to rounding, any number of weights: a sorting network up to
///   16, Michelot's method above), and the velocity becomes the move actually made.
/// - Without: a velocity whose largest component exceeds the limit is scaled as a whole, so the
///   move keeps the weights' sums; nothing is projected.
/// - Conditions 1-3: a particle whose score beats its personal best's (feasible beats infeasible,
///   then the smaller value wins) takes its new position as personal best; `improved` marks it.
/// Padding columns take part like particles and may be marked improved. Returns whether any
/// column improved.
bool advance_particles(const SwarmView& swarm, int rows_a, const Move& move, const Fitness& fitness,
                       const Bests& bests, double* next);

/// A particle and its personal best's score, as order_by_personal_best sorts them.
struct RankedParticle {
  std::int64_t key;
  int particle;
};

/// Sorts `order` (a permutation of the particles) by personal best score, ties going to the
/// lower index, so that order[0] is the best. `order` must already be in that order but for the
/// particles marked in `improved` (nonzero), as last generation's order is after a generation's
/// moves. The particles not marked keep their order; the marked ones (13 to 20 of 40 per
/// generation, on average, on 4- to 16-vertex pairs at the paper's budget) are taken out, sorted
/// among themselves by insertion and merged back.
/// `scratch` holds 2 (particles + 1) entries. The same on every instruction set.
void order_by_personal_best(int particles, const std::int64_t* key, const std::int64_t* improved,
                            int* order, RankedParticle* scratch);

}  // namespace swarmcollide::detail
