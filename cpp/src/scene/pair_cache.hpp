// What a scene remembers about a candidate pair between queries; private to the library.
#pragma once

#include <cstdint>
#include <limits>

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
/// first body's own frame, which turns with it, and indices of the bodies' own points. A
/// separating proof also keeps the distance it proved, and how far the two bodies had travelled
/// then: while the bodies have moved less than that distance's excess over the contact
/// threshold, the pair is still apart with no support evaluated at all. Otherwise each kind is
/// re-evaluated at the new poses in a few support evaluations and, when it still settles the
/// pair, settles it with a fresh proof; if not, it is where the solver starts.
///
/// 64 bytes, one cache line: the key, the kind, the bounds, and 32 bytes holding one proof or
/// the other.
struct PairProof {
  enum class Kind : std::uint8_t {
    /// Nothing proven yet.
    none,
    /// A direction along which the bodies were apart (or nearly so), with the support points
    /// it had, from which hill climbing on large bodies starts. Single precision: any unit
    /// direction gives a valid bound, and this one is only where the evaluation starts.
    separating,
    /// Four point pairs (a[k], b[k]) whose differences b - a formed a tetrahedron enclosing the
    /// origin: a proof of overlap while it still encloses it.
    enclosing,
  };
  struct Separating {
    float direction[3];
    std::int32_t support_a;
    std::int32_t support_b;
  };
  struct Enclosing {
    std::int32_t a[4];
    std::int32_t b[4];
  };

  std::uint64_t key = 0;
  Kind kind = Kind::none;
  /// An enclosing proof made by a contact (contact_tetrahedron: its base on the contact face),
  /// not by a solver's corral: while it still encloses the origin it is kept as it is.
  bool on_face = false;
  /// A certified lower bound on the pair's distance when the proof was made (world units,
  /// rounded down; minus infinity when none), and the pair's size then (rounded up).
  float lower = -std::numeric_limits<float>::infinity();
  float size = 0;
  /// The sum of the two bodies' odometers (Scene) when the proof was made.
  double travelled = 0;
  union {
    Separating separating;
    Enclosing enclosing;
  };

  PairProof() : separating{} {}
  explicit PairProof(std::uint64_t pair) : key(pair), separating{} {}
};

static_assert(sizeof(PairProof) == 64, "a proof fills one cache line");

}  // namespace swarmcollide::detail
