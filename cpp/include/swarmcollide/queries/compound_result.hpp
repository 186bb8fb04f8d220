#pragma once

#include "swarmcollide/queries/distance_result.hpp"

namespace swarmcollide {

/// What a query between compound bodies did with their part pairs.
struct CompoundStats {
  /// Part pairs of the two bodies: parts of A times parts of B.
  long part_pairs = 0;
  /// Pairs of tree nodes whose bounding volumes were compared.
  long volume_tests = 0;
  /// Part pairs settled by the separation along the line between their centres (two support
  /// evaluations), with no solver.
  long screened = 0;
  /// Part pairs handed to the method's solver.
  long solved = 0;

  /// Part pairs never looked at: ruled out, with every other pair below their tree nodes, by
  /// the bounding volumes' certified lower bound.
  long pruned() const { return part_pairs - screened - solved; }
};

/// The answer of a query between compound bodies: a DistanceResult over the union of the parts,
/// with the pair of parts that realises it.
///
/// `lower_bound <= true value <= distance` holds for the union of the convex parts (certified
/// for the parts, not for whatever the parts approximate): `distance` is achieved by the witness
/// points, which lie on parts `part_a` and `part_b` (weights over those parts' points), and
/// `lower_bound` bounds every part pair from below. For signed distances the value is the
/// smallest signed distance over part pairs: minus the deepest part-pair penetration when some
/// parts overlap, which is not in general the penetration depth of the non-convex union.
struct CompoundResult : DistanceResult {
  /// Index of the part of A, and of B, that realise `distance`.
  int part_a = 0;
  int part_b = 0;
  CompoundStats stats;
};

}  // namespace swarmcollide
