#include "slam/vocabulary/word_slots.h"

#include <iterator>
#include <map>
#include <random>
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

// The ids a merged multi-session map keeps: a tenth of those ever created.
TEST(WordSlots, PackedFormAnswersAsTheDenseOneInAFractionOfTheBytes) {
  std::mt19937 rng(7);
  WordSlots slots;
  std::map<WordId, uint32_t> expected;
  for (WordId id = 1; id <= 200000; ++id) {
    if (rng() % 10 != 0) continue;
    const uint32_t slot = static_cast<uint32_t>(rng() % 1000000);
    slots.Set(id, slot);
    expected[id] = slot;
  }
  const size_t dense_bytes = slots.MemoryBytes();
  slots.Pack();
  ASSERT_TRUE(slots.packed());
  EXPECT_LT(slots.MemoryBytes(), dense_bytes / 4);
  EXPECT_EQ(slots.size(), expected.size());
  for (WordId id = -1; id <= 200100; ++id) {
    const auto it = expected.find(id);
    ASSERT_EQ(slots.Find(id), it == expected.end() ? WordSlots::kNone : it->second) << id;
  }
  // Replacing and erasing keep the packed form.
  const WordId some = expected.begin()->first;
  slots.Set(some, 5);
  expected[some] = 5;
  const WordId other = std::next(expected.begin(), 100)->first;
  EXPECT_TRUE(slots.Erase(other));
  EXPECT_FALSE(slots.Erase(other));
  EXPECT_FALSE(slots.Erase(other + 1));  // never present
  expected.erase(other);
  EXPECT_TRUE(slots.packed());
  EXPECT_EQ(slots.size(), expected.size());
  std::map<WordId, uint32_t> seen;
  slots.ForEach([&seen](WordId id, uint32_t slot) { seen[id] = slot; });
  EXPECT_EQ(seen, expected);
  // A new id turns it dense again, with every id kept.
  slots.Set(300000, 9);
  expected[300000] = 9;
  EXPECT_FALSE(slots.packed());
  EXPECT_EQ(slots.size(), expected.size());
  for (const auto& [id, slot] : expected) ASSERT_EQ(slots.Find(id), slot) << id;
  EXPECT_EQ(slots.Find(other), WordSlots::kNone);
}

TEST(WordSlots, PackKeepsTheDenseFormWhenItIsSmaller) {
  WordSlots slots;
  for (WordId id = 1; id <= 1000; ++id) slots.Set(id, static_cast<uint32_t>(id));
  slots.Pack();
  EXPECT_FALSE(slots.packed());
  EXPECT_EQ(slots.Find(500), 500u);
  WordSlots empty;
  empty.Pack();
  EXPECT_EQ(empty.Find(1), WordSlots::kNone);
  EXPECT_EQ(empty.MemoryBytes(), 0u);
}

}  // namespace
}  // namespace duskmap
