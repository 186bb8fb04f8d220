#include "column_scan.hpp"

#include <cstdint>
#include <stdexcept>

// Each set's scan computes every height lane by lane as the scalar loop does, `(x d_x + y d_y) +
// z d_z` with the products rounded apart (this file is compiled without contraction), takes the
// greatest, and returns the first point whose height equals it: the first maximiser, whatever the
// width, when no height is NaN. Where one is, the scalar comparisons decide, on the same heights.
// Only GCC on x86-64 gets the wider sets, as the swarm's kernels (swarm_kernels.cpp).
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
#define SWARMCOLLIDE_WIDER_SCANS 1
#endif
#if defined(__x86_64__)
#include <immintrin.h>
#endif

namespace swarmcollide::detail {

static_assert(kColumnCapacity % kColumnPadding == 0, "whole registers of the widest set");
static_assert(kColumnCapacity <= 32, "the scans gather equal heights in a 32-bit mask");
static_assert(kColumnPadding % 8 == 0, "the AVX2 scan reads two registers a step");

#ifdef SWARMCOLLIDE_WIDER_SCANS
#pragma GCC push_options
#pragma GCC target("arch=x86-64-v3")
int scan_columns_avx2(const double* columns, int count, double dx, double dy, double dz) {
  const double* x = columns;
  const double* y = x + kColumnCapacity;
  const double* z = y + kColumnCapacity;
  const __m256d along_x = _mm256_set1_pd(dx);
  const __m256d along_y = _mm256_set1_pd(dy);
  const __m256d along_z = _mm256_set1_pd(dz);
  const auto heights_at = [&](int i) {
    return _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(_mm256_loadu_pd(x + i), along_x),
                                       _mm256_mul_pd(_mm256_loadu_pd(y + i), along_y)),
                         _mm256_mul_pd(_mm256_loadu_pd(z + i), along_z));
  };
  // The greatest of `h` in every lane: swap the halves, then the neighbours.
  const auto greatest = [](__m256d h) {
    h = _mm256_max_pd(h, _mm256_permute2f128_pd(h, h, 1));
    return _mm256_max_pd(h, _mm256_permute_pd(h, 0b0101));
  };
  const auto lanes_equal = [](__m256d h, __m256d top) {
    return _mm256_movemask_pd(_mm256_cmp_pd(h, top, _CMP_EQ_OQ));
  };
  // Up to eight points (the searches' small bodies, scanned at every step) in registers, without
  // the loops and the heights' stores and loads: a quarter of a 4-point scan's instructions.
  if (count <= kFewColumns) {
    const __m256d low = heights_at(0);
    const __m256d high = count > 4 ? heights_at(4) : low;
    if (_mm256_movemask_pd(_mm256_cmp_pd(low, high, _CMP_UNORD_Q)) != 0) {
      return first_highest_column(columns, count, dx, dy, dz);
    }
    const __m256d top = greatest(_mm256_max_pd(low, high));
    // The first of the eight equal to the greatest, without a branch on which half holds it:
    // that branch went the other way about half the time, and a search's next direction waits
    // on the index (collide_many's 8-point rows near contact: the same instructions, a fifth less
    // time; valgrind's branch simulation, this scan's mispredictions 345,216 -> 26 in 60,000).
    const int equal = lanes_equal(low, top) | lanes_equal(high, top) << 4;
    return __builtin_ctz(static_cast<unsigned>(equal));
  }
  // Larger bodies two registers a step (the columns are padded to kColumnPadding entries).
  alignas(32) double heights[kColumnCapacity];
  __m256d top = _mm256_setzero_pd();
  __m256d unordered = _mm256_setzero_pd();
  for (int i = 0; i < count; i += 8) {
    const __m256d low = heights_at(i);
    const __m256d high = heights_at(i + 4);
    _mm256_store_pd(heights + i, low);
    _mm256_store_pd(heights + i + 4, high);
    const __m256d pair_top = _mm256_max_pd(low, high);
    top = i == 0 ? pair_top : _mm256_max_pd(top, pair_top);
    unordered = _mm256_or_pd(unordered, _mm256_cmp_pd(low, high, _CMP_UNORD_Q));
  }
  if (_mm256_movemask_pd(unordered) != 0) return first_highest_column(columns, count, dx, dy, dz);
  top = greatest(top);
  // Every point's equality to the greatest in one mask, as above.
  std::uint32_t equal = 0;
  for (int i = 0; i < count; i += 4) {
    equal |= static_cast<std::uint32_t>(lanes_equal(_mm256_load_pd(heights + i), top)) << i;
  }
  return __builtin_ctz(equal);
}
#pragma GCC pop_options

#pragma GCC push_options
#pragma GCC target("arch=x86-64-v4")
// GCC 12's own AVX-512 intrinsics start from a self-initialised `_mm512_undefined_pd`, which its
// -Wmaybe-uninitialized reports in every caller.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
// Eight points a step (scan_columns gives bodies of up to kFewColumns points to AVX2's scan).
int scan_columns_avx512(const double* columns, int count, double dx, double dy, double dz) {
  const double* x = columns;
  const double* y = x + kColumnCapacity;
  const double* z = y + kColumnCapacity;
  const __m512d along_x = _mm512_set1_pd(dx);
  const __m512d along_y = _mm512_set1_pd(dy);
  const __m512d along_z = _mm512_set1_pd(dz);
  __m512d heights[kColumnCapacity / 8];
  const int steps = (count + 7) / 8;
  __m512d top = _mm512_setzero_pd();
  __mmask8 unordered = 0;
  for (int s = 0; s < steps; ++s) {
    const int i = 8 * s;
    const __m512d h =
        _mm512_add_pd(_mm512_add_pd(_mm512_mul_pd(_mm512_loadu_pd(x + i), along_x),
                                    _mm512_mul_pd(_mm512_loadu_pd(y + i), along_y)),
                      _mm512_mul_pd(_mm512_loadu_pd(z + i), along_z));
    heights[s] = h;
    top = s == 0 ? h : _mm512_max_pd(top, h);
    unordered |= _mm512_cmp_pd_mask(h, h, _CMP_UNORD_Q);
  }
  if (unordered != 0) return first_highest_column(columns, count, dx, dy, dz);
  // The greatest in every lane: the halves', then as the AVX2 scan finds it.
  __m256d half = _mm256_max_pd(_mm512_castpd512_pd256(top), _mm512_extractf64x4_pd(top, 1));
  half = _mm256_max_pd(half, _mm256_permute2f128_pd(half, half, 1));
  half = _mm256_max_pd(half, _mm256_permute_pd(half, 0b0101));
  const __m512d greatest = _mm512_broadcastsd_pd(_mm256_castpd256_pd128(half));
  // Every point's equality to the greatest in one mask, as the AVX2 scan finds it.
  std::uint32_t equal = 0;
  for (int s = 0; s < steps; ++s) {
    equal |= static_cast<std::uint32_t>(_mm512_cmp_pd_mask(heights[s], greatest, _CMP_EQ_OQ))
             << (8 * s);
  }
  return __builtin_ctz(equal);
}
#pragma GCC diagnostic pop
#pragma GCC pop_options
#endif

#ifndef SWARMCOLLIDE_WIDER_SCANS
int scan_columns_avx2(const double* columns, int count, double dx, double dy, double dz) {
  return scan_columns_baseline(columns, count, dx, dy, dz);
}
int scan_columns_avx512(const double* columns, int count, double dx, double dy, double dz) {
  return scan_columns_baseline(columns, count, dx, dy, dz);
}
#endif

ColumnScan column_scan_for(KernelIsa isa) {
  if (isa != KernelIsa::baseline && kernel_isa_available(isa)) {
    return isa == KernelIsa::avx512 ? &scan_columns_avx512 : &scan_columns_avx2;
  }
  return &scan_columns_baseline;
}

std::atomic<int> column_scan_set{-1};

int choose_column_scan(const double* columns, int count, double dx, double dy, double dz) {
  KernelIsa isa = KernelIsa::baseline;
  try {
    isa = kernel_isa();
  } catch (const std::runtime_error&) {
    isa = widest_kernel_isa();
  }
  // A race makes two threads choose the same set.
  column_scan_set.store(static_cast<int>(isa), std::memory_order_relaxed);
  return column_scan_for(isa)(columns, count, dx, dy, dz);
}

}  // namespace swarmcollide::detail
