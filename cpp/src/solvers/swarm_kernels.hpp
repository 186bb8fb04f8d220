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

struct SwarmView {
  int rows;
  int particles;
  int stride;
  double* position;
  double* velocity;
  double* personal_best;
};

/// (10) and (11) for every weight of every particle: v = w v + c1 r1 (p - x) + c2 r2 (g - x), with
/// the per-particle w, c1 r1 and c2 r2 and the global best's weights g, then x + v written to
/// `next`. A particle whose largest velocity component exceeds `limit` has its whole velocity
/// scaled down, so that the move keeps the weights' sums. `largest` is scratch; `lowest_a` and
/// `lowest_b` receive each particle's smallest new lambda and delta.
void move_particles(const SwarmView& swarm, int rows_a, const double* inertia,
                    const double* pull_own, const double* pull_global, const double* global_best,
                    double limit, double* next, double* largest, double* lowest_a,
                    double* lowest_b);

/// The most weights per body that `project_rows_onto_simplex` handles; it costs O(k^2) per
/// particle, and longer vectors are projected one particle at a time by sorting.
constexpr int kMaxRowsProjectedTogether = 8;

/// Projects the `count` rows starting at `first_row` onto the probability simplex for every
/// particle whose `lowest` weight is negative, adding the displacement to its velocity. Uses
/// theta = max over i of (sum of the weights >= w_i, minus 1) / (their number), which equals the
/// sort-based threshold of the projection without sorting. `theta`, `sum` and `count_at_least`
/// are scratch arrays of `particles` values.
void project_rows_onto_simplex(const SwarmView& swarm, int first_row, int count,
                               const double* lowest, double* theta, double* sum,
                               double* count_at_least);

/// Each particle's objective (5) and violation (6): `offset` gets sum_j delta_j y_j - sum_i
/// lambda_i x_i component by component; `signed_vertices` holds, per row, -x_i for A's rows and
/// y_j for B's, three values each. With `check_bounds`, a weight outside [0, 1] also makes the
/// particle infeasible. `value` is the square of (5) for feasible particles and (6) otherwise;
/// `feasible` is 1 or 0.
struct FitnessScratch {
  double* offset_x;
  double* offset_y;
  double* offset_z;
  double* sum_a;
  double* sum_b;
  double* lowest;
  double* highest;
};
void evaluate_fitness(const SwarmView& swarm, int rows_a, const double* signed_vertices,
                      bool check_bounds, double feasibility_tolerance,
                      const FitnessScratch& scratch, double* value, double* feasible);

/// Conditions 1-3: a particle whose new fitness beats its personal best's (feasible beats
/// infeasible, then the smaller value wins) takes its position as personal best. Returns whether
/// any particle improved.
bool keep_personal_bests(const SwarmView& swarm, const double* value, const double* feasible,
                         double* best_value, double* best_feasible, double* improved);

/// The rank (0 = best) of each particle's personal best under the ordering of Conditions 1-3,
/// ties going to the lower index. Counting rather than sorting: no branch depends on the data.
/// `key` is scratch for `particles` values.
void rank_personal_bests(int particles, const double* best_feasible, const double* best_value,
                         std::int64_t* key, std::int64_t* rank);

}  // namespace swarmcollide::detail
