// Node descriptor rows shared with the vocabulary's words: found exactly,
// decoded bit for bit as before, smaller, refused by SaveMap, and the
// LoadMapAndWords option.
#include "slam/map/shared_rows.h"

#include <cstring>
#include <filesystem>

#include <gtest/gtest.h>

#include "slam/core/check.h"
#include "slam/map/map_store.h"
#include "tests/map/test_map.h"

namespace duskmap {
namespace {

// Words made of every third row of every node (in the words' stored form),
// plus random words nobody holds.
MapWords WordsFromNodeRows(const Map& map, WordRowFormat format, size_t* rows_copied) {
  const int cols = map.metadata().descriptor_cols;
  const size_t bytes = WordRowBytes(format, cols);
  std::vector<std::vector<uint8_t>> rows;
  for (const auto& [id, node] : map.nodes()) {
    std::vector<uint8_t> row(bytes);
    for (size_t i = 0; i < node.features.size(); i += 3) {
      if (!node.features.RowAsStoredWord(i, format, row.data())) continue;
      rows.push_back(row);
    }
  }
  *rows_copied = rows.size();
  cv::RNG rng(5);
  for (int extra = 0; extra < 10; ++extra) {
    std::vector<uint8_t> row(bytes);
    rng.fill(cv::Mat(1, static_cast<int>(bytes), CV_8U, row.data()), cv::RNG::UNIFORM, 0, 256);
    rows.push_back(row);
  }
  MapWords words;
  const bool floats = format == WordRowFormat::kFloat32;
  words.descriptors.create(static_cast<int>(rows.size()),
                           floats ? cols : static_cast<int>(bytes), floats ? CV_32F : CV_8U);
  for (size_t r = 0; r < rows.size(); ++r) {
    std::memcpy(words.descriptors.ptr(static_cast<int>(r)), rows[r].data(), bytes);
    words.ids.push_back(static_cast<WordId>(10 + 2 * r));
  }
  words.next_word_id = words.ids.back() + 1;
  return words;
}

void ExpectSameFeatures(const FrameFeatures& a, const FrameFeatures& b) {
  ASSERT_EQ(a.size(), b.size());
  ASSERT_EQ(a.descriptors.type(), b.descriptors.type());
  ASSERT_EQ(a.descriptors.size(), b.descriptors.size());
  for (int r = 0; r < a.descriptors.rows; ++r) {
    ASSERT_EQ(std::memcmp(a.descriptors.ptr(r), b.descriptors.ptr(r),
                          a.descriptors.cols * a.descriptors.elemSize()),
              0)
        << "row " << r;
  }
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a.keypoints[i].pt, b.keypoints[i].pt);
    EXPECT_EQ(a.keypoints[i].response, b.keypoints[i].response);
    EXPECT_EQ(a.points_in_camera[i].hasNaN(), b.points_in_camera[i].hasNaN());
  }
}

struct Case {
  const char* name;
  bool binary;
  DescriptorStorage nodes;
  DescriptorStorage words;
};

TEST(SharedRows, RowsEqualToWordsAreSharedAndDecodeBitForBit) {
  const DescriptorStorage f32 = DescriptorStorage::kFloat32, u8 = DescriptorStorage::kUint8;
  for (const Case& c : {Case{"binary", true, f32, f32}, Case{"float32", false, f32, f32},
                        Case{"uint8", false, u8, u8}}) {
    SCOPED_TRACE(c.name);
    Map map = testing::MakeTestMap(4, 50, c.binary, 11, c.nodes);
    map.mutable_metadata().word_storage = c.words;
    const WordRowFormat format = WordRowFormatFor(map.metadata().descriptor_kind, c.words);
    size_t copied = 0;
    const MapWords words = WordsFromNodeRows(map, format, &copied);
    ASSERT_GT(copied, 0u);
    const Map original = map;
    const SharedRowsSummary summary = ShareNodeRowsWithWords(words, &map);
    EXPECT_EQ(summary.rows, 8u * 50u);
    EXPECT_EQ(summary.shared_rows, copied);
    EXPECT_LT(summary.bytes_after, summary.bytes_before);
    const MapWordsRowSource source(words, format);
    for (const auto& [id, node] : map.nodes()) {
      EXPECT_TRUE(node.features.has_shared_rows());
      EXPECT_EQ(node.features.num_shared_rows(), 17u);  // rows 0, 3, ..., 48
      ExpectSameFeatures(node.features.Decode(&source), original.node(id).features.Decode());
      EXPECT_THROW(node.features.Decode(), InputError);  // the words are needed
    }
    const std::string path = ::testing::TempDir() + "/shared_rows.db";
    try {
      SaveMap(map, path);
      ADD_FAILURE() << "a map with shared rows was saved";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("cannot be saved"), std::string::npos) << e.what();
    }
    EXPECT_FALSE(std::filesystem::exists(path));
  }
}

// Float32 node rows cannot be 8-bit words and the reverse: nothing is shared.
TEST(SharedRows, RowsInAnotherFormThanTheWordsStayOwn) {
  Map map = testing::MakeTestMap(3, 30, false, 12, DescriptorStorage::kFloat32);
  size_t copied = 0;
  const MapWords words = WordsFromNodeRows(map, WordRowFormat::kFloat32, &copied);
  map.mutable_metadata().word_storage = DescriptorStorage::kUint8;  // words claimed 8-bit
  MapWords quantized;
  quantized.ids = words.ids;
  quantized.descriptors = cv::Mat(static_cast<int>(words.ids.size()),
                                  static_cast<int>(WordRowBytes(WordRowFormat::kQuantized8, 64)),
                                  CV_8U, cv::Scalar(0));
  const SharedRowsSummary summary = ShareNodeRowsWithWords(quantized, &map);
  EXPECT_EQ(summary.shared_rows, 0u);
  EXPECT_EQ(summary.bytes_after, summary.bytes_before);
}

TEST(SharedRows, AWordThatIsNotTheRowIsRejected) {
  Map map = testing::MakeTestMap(2, 20, true, 13);
  size_t copied = 0;
  const MapWords words = WordsFromNodeRows(map, WordRowFormat::kBinary, &copied);
  const MapWordsRowSource source(words, WordRowFormat::kBinary);
  CompactFeatures features = map.node(1).features;
  std::vector<WordId> row_words(features.size(), kNoWord);
  row_words[1] = words.ids[0];  // row 0's word, not row 1's
  EXPECT_THROW(features.ShareRowsWithWords(row_words, source), InputError);
  row_words[1] = 9;  // no such word
  EXPECT_THROW(features.ShareRowsWithWords(row_words, source), InputError);
  EXPECT_FALSE(features.has_shared_rows());
}

TEST(SharedRows, LoadMapAndWordsSharesUnlessAskedNotTo) {
  Map map = testing::MakeTestMap(3, 40, true, 14);
  size_t copied = 0;
  map.SetWords(WordsFromNodeRows(map, WordRowFormat::kBinary, &copied));
  const std::string path = ::testing::TempDir() + "/shared_rows_load.db";
  SaveMap(map, path);
  const MapAndWords shared = LoadMapAndWords(path);
  MapLoadOptions own_rows;
  own_rows.share_node_rows_with_words = false;
  const MapAndWords own = LoadMapAndWords(path, own_rows);
  size_t shared_rows = 0;
  const MapWordsRowSource source(shared.words, WordRowFormat::kBinary);
  for (const auto& [id, node] : shared.map.nodes()) {
    shared_rows += node.features.num_shared_rows();
    EXPECT_FALSE(own.map.node(id).features.has_shared_rows());
    ExpectSameFeatures(node.features.Decode(&source), own.map.node(id).features.Decode());
  }
  EXPECT_EQ(shared_rows, copied);
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace duskmap
