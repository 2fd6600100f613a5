#include "slam/vocabulary/word_slots.h"

#include <utility>
#include <vector>

#include <gtest/gtest.h>

namespace duskmap {
namespace {

TEST(WordSlots, SetFindEraseAndVisitInIdOrder) {
  WordSlots slots;
  EXPECT_TRUE(slots.empty());
  EXPECT_EQ(slots.Find(1), WordSlots::kNone);
  EXPECT_EQ(slots.Find(0), WordSlots::kNone);
  EXPECT_EQ(slots.Find(-1), WordSlots::kNone);
  slots.Set(40, 7);
  slots.Set(3, 0);
  slots.Set(1000, 2);
  slots.Set(3, 9);  // replaces
  EXPECT_EQ(slots.size(), 3u);
  EXPECT_EQ(slots.Find(3), 9u);
  EXPECT_EQ(slots.Find(40), 7u);
  EXPECT_EQ(slots.Find(41), WordSlots::kNone);
  EXPECT_EQ(slots.Find(5000), WordSlots::kNone);
  EXPECT_TRUE(slots.Erase(40));
  EXPECT_FALSE(slots.Erase(40));
  EXPECT_FALSE(slots.Contains(40));
  std::vector<std::pair<WordId, uint32_t>> seen;
  slots.ForEach([&seen](WordId id, uint32_t slot) { seen.push_back({id, slot}); });
  EXPECT_EQ(seen, (std::vector<std::pair<WordId, uint32_t>>{{3, 9}, {1000, 2}}));
  // Four bytes per id up to the largest, not per live word and hash node.
  EXPECT_GE(slots.MemoryBytes(), 1001 * sizeof(uint32_t));
  EXPECT_LE(slots.MemoryBytes(), 2 * 1001 * sizeof(uint32_t));
  slots.Clear();
  EXPECT_TRUE(slots.empty());
  EXPECT_EQ(slots.MemoryBytes(), 0u);
}

}  // namespace
}  // namespace duskmap
