// Sorting a scene's pairs by their keys; private to the library's sources.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "pair_cache.hpp"

namespace swarmcollide::detail {

/// Sorts `items` by `rank(item)`, a number below 2^bits, with a least-significant-digit radix
/// sort through `scratch`: a frame sorts tens of thousands of pairs, where comparison sorting took
/// a tenth of the frame.
template <typename T, typename Rank>
void radix_sort(std::vector<T>& items, std::vector<T>& scratch, int bits, const Rank& rank) {
  constexpr int kDigit = 11;
  constexpr std::size_t kBuckets = std::size_t{1} << kDigit;
  scratch.resize(items.size());
  for (int shift = 0; shift < bits; shift += kDigit) {
    std::array<std::size_t, kBuckets + 1> start{};
    for (const T& item : items) ++start[((rank(item) >> shift) & (kBuckets - 1)) + 1];
    for (std::size_t d = 1; d <= kBuckets; ++d) start[d] += start[d - 1];
    for (const T& item : items) scratch[start[(rank(item) >> shift) & (kBuckets - 1)]++] = item;
    items.swap(scratch);
  }
}

/// The significant bits of ids below `id_limit` (at least one).
inline int id_bits(std::uint64_t id_limit) {
  int bits = 1;
  while ((std::uint64_t{1} << bits) < id_limit) ++bits;
  return bits;
}

/// Sorts `items` by the pair key `key_of(item)` of ids below `id_limit`: the key packed into
/// twice the ids' significant bits, which sorts as the key does, in as few radix passes as the
/// scene's ids need.
template <typename T, typename KeyOf>
void sort_by_pair_key(std::vector<T>& items, std::vector<T>& scratch, std::uint64_t id_limit,
                      const KeyOf& key_of) {
  const int bits = id_bits(id_limit);
  radix_sort(items, scratch, 2 * bits, [bits, &key_of](const T& item) {
    const std::uint64_t key = key_of(item);
    return (static_cast<std::uint64_t>(key_first(key)) << bits) | key_second(key);
  });
}

}  // namespace swarmcollide::detail
