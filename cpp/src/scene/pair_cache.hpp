// What a scene remembers about a candidate pair between queries; private to the library.
#pragma once

#include <cstdint>

#include "swarmcollide/scene/scene_result.hpp"

namespace swarmcollide::detail {

/// A candidate pair's key: the smaller id in the high 32 bits. Sorting keys sorts pairs by
/// (first id, second id).
inline std::uint64_t pair_key(BodyId first, BodyId second) {
  return (static_cast<std::uint64_t>(first) << 32) | second;
}
inline BodyId key_first(std::uint64_t key) { return static_cast<BodyId>(key >> 32); }
inline BodyId key_second(std::uint64_t key) { return static_cast<BodyId>(key & 0xFFFFFFFFu); }

/// What the last query proved about a pair, in terms that survive motion: a direction in the
/// first body's own frame, which turns with it, and indices of the bodies' own points. Each kind
/// is re-evaluated at the new poses in a few support evaluations and, when it still settles the
/// pair, settles it with a new proof; otherwise it is where the solver starts.
///
/// 48 bytes: the key, the kind, and 32 bytes holding one proof or the other.
struct PairProof {
  enum class Kind : std::uint8_t {
    /// Nothing proven yet.
    none,
    /// A direction along which the bodies were apart (or nearly so), with the support points
    /// it had, from which hill climbing on large bodies starts.
    separating,
    /// Four point pairs (a[k], b[k]) whose differences b - a formed a tetrahedron enclosing the
    /// origin: a proof of overlap while it still encloses it.
    enclosing,
  };
  struct Separating {
    double direction[3];
    std::int32_t support_a;
    std::int32_t support_b;
  };
  struct Enclosing {
    std::int32_t a[4];
    std::int32_t b[4];
  };

  std::uint64_t key = 0;
  Kind kind = Kind::none;
  union {
    Separating separating;
    Enclosing enclosing;
  };

  PairProof() : separating{} {}
  explicit PairProof(std::uint64_t pair) : key(pair), separating{} {}
};

}  // namespace swarmcollide::detail
