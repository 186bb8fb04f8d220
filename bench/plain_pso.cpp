// A plain particle swarm for model (2), compiled with -O3 -march=native: one particle and one
// weight at a time, no intrinsics, no vector types. It allocates its arrays once per solve.
#include "plain_pso.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <vector>

namespace {

// xoshiro256++ seeded by splitmix64, as swarmcollide seeds its generators.
class Xoshiro {
 public:
  explicit Xoshiro(std::uint64_t seed) {
    for (auto& word : s_) {
      seed += 0x9e3779b97f4a7c15ULL;
      std::uint64_t z = seed;
      z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
      z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
      word = z ^ (z >> 31);
    }
  }
  std::uint64_t next() {
    const std::uint64_t result = rotl(s_[0] + s_[3], 23) + s_[0];
    const std::uint64_t t = s_[1] << 17;
    s_[2] ^= s_[0];
    s_[3] ^= s_[1];
    s_[1] ^= s_[2];
    s_[0] ^= s_[3];
    s_[2] ^= t;
    s_[3] = rotl(s_[3], 45);
    return result;
  }
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }

 private:
  static std::uint64_t rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
  std::uint64_t s_[4];
};

// Sort-based Euclidean projection onto the probability simplex (insertion sort: short vectors).
void project(double* w, int n, double* sorted) {
  for (int i = 0; i < n; ++i) {
    int k = i;
    for (; k > 0 && sorted[k - 1] < w[i]; --k) sorted[k] = sorted[k - 1];
    sorted[k] = w[i];
  }
  double sum = 0, theta = 0;
  for (int k = 0; k < n; ++k) {
    sum += sorted[k];
    const double t = (sum - 1) / (k + 1);
    if (sorted[k] > t) theta = t;
  }
  for (int i = 0; i < n; ++i) w[i] = std::max(w[i] - theta, 0.0);
}

// A uniform point of the simplex: the gaps between n - 1 sorted uniform numbers.
void uniform_point(double* w, int n, Xoshiro& rng, double* cuts) {
  for (int i = 0; i < n - 1; ++i) cuts[i] = rng.uniform();
  std::sort(cuts, cuts + n - 1);
  double previous = 0;
  for (int i = 0; i < n - 1; ++i) {
    w[i] = cuts[i] - previous;
    previous = cuts[i];
  }
  w[n - 1] = 1 - previous;
}

template <bool kFactorsPerWeight, bool kScaleWholeVelocity, VelocityAfterProjection kAfter,
          bool kAsynchronous>
double solve(const double* a, int ka, const double* b, int kb, const PlainPsoOptions& options,
             std::uint64_t seed) {
  const int n = ka + kb;
  const int size = options.swarm_size;
  // Per weight, the vertex it weighs with its sign: -x_i for A, y_j for B.
  std::vector<double> vertex(3 * n);
  for (int i = 0; i < 3 * ka; ++i) vertex[i] = -a[i];
  for (int i = 0; i < 3 * kb; ++i) vertex[3 * ka + i] = b[i];
  const auto score = [&](const double* w) {
    double g[3] = {0, 0, 0};
    for (int r = 0; r < n; ++r) {
      for (int c = 0; c < 3; ++c) g[c] += vertex[3 * r + c] * w[r];
    }
    return g[0] * g[0] + g[1] * g[1] + g[2] * g[2];
  };

  Xoshiro rng(seed);
  std::vector<double> x(size * n), v(size * n), p(size * n), best(size);
  std::vector<double> g(n), moved(n), scratch(n);
  std::vector<int> order(size);
  std::vector<double> w(size), c(size);
  for (int j = 0; j < size; ++j) {
    double* xj = &x[j * n];
    uniform_point(xj, ka, rng, scratch.data());
    uniform_point(xj + ka, kb, rng, scratch.data());
    double* vj = &v[j * n];
    uniform_point(vj, ka, rng, scratch.data());
    uniform_point(vj + ka, kb, rng, scratch.data());
    for (int r = 0; r < n; ++r) vj[r] -= xj[r];
    std::copy(xj, xj + n, &p[j * n]);
    best[j] = score(xj);
  }
  int global = static_cast<int>(std::min_element(best.begin(), best.end()) - best.begin());
  const double limit = options.velocity_limit;
  for (int iteration = 0; iteration < options.max_iterations; ++iteration) {
    // (8)-(9) by the rank of each personal best.
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(),
              [&](int i, int k) { return best[i] < best[k] || (best[i] == best[k] && i < k); });
    for (int rank = 0; rank < size; ++rank) {
      const double wi =
          options.w_min + (options.w_max - options.w_min) * (size - 1 - rank) / (size - 1);
      w[order[rank]] = wi;
      c[order[rank]] = (wi + 1 + 2 * std::sqrt(wi)) / 2;
    }
    std::copy(&p[global * n], &p[global * n] + n, g.begin());
    for (int j = 0; j < size; ++j) {
      double* xj = &x[j * n];
      double* vj = &v[j * n];
      const double* pj = &p[j * n];
      // One 64-bit draw gives r1 and r2, 32 bits each, as swarmcollide draws them.
      std::uint64_t bits = 0;
      if constexpr (!kFactorsPerWeight) bits = rng.next();
      double largest = 0;
      for (int r = 0; r < n; ++r) {
        if constexpr (kFactorsPerWeight) bits = rng.next();
        const double r1 = static_cast<double>(bits >> 32) * 0x1.0p-32;
        const double r2 = static_cast<double>(bits & 0xffffffffULL) * 0x1.0p-32;
        double velocity = w[j] * vj[r] + c[j] * r1 * (pj[r] - xj[r]) + c[j] * r2 * (g[r] - xj[r]);
        if constexpr (kScaleWholeVelocity) {
          largest = std::max(largest, std::abs(velocity));
        } else {
          velocity = std::clamp(velocity, -limit, limit);
        }
        if constexpr (kAfter != VelocityAfterProjection::move_made) vj[r] = velocity;
        moved[r] = xj[r] + velocity;
      }
      if (kScaleWholeVelocity && largest > limit) {
        for (int r = 0; r < n; ++r) {
          const double velocity = (moved[r] - xj[r]) * (limit / largest);
          if constexpr (kAfter != VelocityAfterProjection::move_made) vj[r] = velocity;
          moved[r] = xj[r] + velocity;
        }
      }
      project(moved.data(), ka, scratch.data());
      project(moved.data() + ka, kb, scratch.data());
      for (int r = 0; r < n; ++r) {
        if constexpr (kAfter == VelocityAfterProjection::move_made) vj[r] = moved[r] - xj[r];
        if constexpr (kAfter == VelocityAfterProjection::clipped_zeroed) {
          if (moved[r] == 0) vj[r] = 0;
        }
        xj[r] = moved[r];
      }
      const double s = score(xj);
      if (s < best[j]) {
        best[j] = s;
        std::copy(xj, xj + n, &p[j * n]);
        if (kAsynchronous && s < best[global]) {
          global = j;
          std::copy(xj, xj + n, g.begin());
        }
      }
    }
    global = static_cast<int>(std::min_element(best.begin(), best.end()) - best.begin());
  }
  return std::sqrt(best[global]);
}

}  // namespace

double plain_pso(const double* a, int ka, const double* b, int kb, const PlainPsoOptions& options,
                 std::uint64_t seed) {
  using After = VelocityAfterProjection;
  // Each alternative is compiled on its own, so that the default pays nothing for the others.
  const int changes = !options.factors_per_weight + options.scale_whole_velocity +
                      (options.after_projection != After::move_made) + options.asynchronous;
  if (changes > 1) throw std::invalid_argument("plain_pso: change one choice at a time");
  if (!options.factors_per_weight) {
    return solve<false, false, After::move_made, false>(a, ka, b, kb, options, seed);
  }
  if (options.scale_whole_velocity) {
    return solve<true, true, After::move_made, false>(a, ka, b, kb, options, seed);
  }
  if (options.after_projection == After::unprojected) {
    return solve<true, false, After::unprojected, false>(a, ka, b, kb, options, seed);
  }
  if (options.after_projection == After::clipped_zeroed) {
    return solve<true, false, After::clipped_zeroed, false>(a, ka, b, kb, options, seed);
  }
  if (options.asynchronous) {
    return solve<true, false, After::move_made, true>(a, ka, b, kb, options, seed);
  }
  return solve<true, false, After::move_made, false>(a, ka, b, kb, options, seed);
}
