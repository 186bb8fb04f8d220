// History, the answer's sequence of best upper bounds: its first values held in place, the rest
// on the heap, used as a std::vector<Scalar> is.
#include <gtest/gtest.h>

#include <utility>
#include <vector>

#include "swarmcollide/queries/history.hpp"

namespace swarmcollide {
namespace {

// The values 0.5, 1.5, ... of a history of `count` values, built by push_back.
History counted(int count) {
  History h;
  for (int k = 0; k < count; ++k) h.push_back(k + 0.5);
  return h;
}

TEST(History, HoldsItsValuesInOrderOnEitherSideOfTheInlineCapacity) {
  for (int count = 0; count <= 3 * static_cast<int>(History::kInline) + 1; ++count) {
    const History h = counted(count);
    ASSERT_EQ(h.size(), static_cast<std::size_t>(count));
    EXPECT_EQ(h.empty(), count == 0);
    const std::vector<Scalar> values(h.begin(), h.end());
    for (int k = 0; k < count; ++k) {
      EXPECT_EQ(h[k], k + 0.5) << count;
      EXPECT_EQ(values[k], k + 0.5) << count;
    }
    if (count > 0) EXPECT_EQ(h.back(), count - 0.5);
  }
}

TEST(History, CopiesAndMovesKeepTheValues) {
  for (int count : {1, static_cast<int>(History::kInline), 7}) {
    const History original = counted(count);
    History copy = original;
    EXPECT_EQ(copy, original);
    History moved = std::move(copy);
    EXPECT_EQ(moved, original) << count;
    EXPECT_TRUE(copy.empty());  // NOLINT(bugprone-use-after-move): a moved-from history is empty
    History assigned = counted(3);
    assigned = std::move(moved);
    EXPECT_EQ(assigned, original) << count;
    moved = original;
    moved.push_back(99);
    EXPECT_NE(moved, original);
    EXPECT_EQ(moved.back(), 99);
  }
}

TEST(History, EditsInPlaceReachEveryValue) {
  History h = counted(5);
  h.reserve(100);
  for (Scalar& value : h) value *= 2;
  EXPECT_EQ(h[0], 1.0);
  EXPECT_EQ(h[4], 9.0);
  h.push_back(20);
  EXPECT_EQ(h.size(), 6u);
  EXPECT_EQ(h[5], 20.0);
}

}  // namespace
}  // namespace swarmcollide
