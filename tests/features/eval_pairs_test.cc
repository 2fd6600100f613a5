#include "slam/features/eval/eval_pairs.h"

#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "slam/core/check.h"
#include "tests/testing/error_of.h"
#include "tests/testing/temp_dir.h"

namespace duskmap {
namespace {

using testing::ErrorOf;

TEST(EvalPairs, ListsAreSplitAndChecked) {
  const std::vector<PairSelector> list = ParsePairList("1-5, 1-6,notredame/2-3");
  ASSERT_EQ(list.size(), 3u);
  EXPECT_EQ(list[1].text, "1-6");
  EXPECT_EQ(list[2].origin, "--pairs");
  EXPECT_EQ(ErrorOf([] { ParsePairList("1-5,,1-6"); }),
            "--pairs: '1-5,,1-6' has an empty item (expected e.g. 1-5,1-6)");
  EXPECT_EQ(ErrorOf([] { ParsePairList("1-5,1-5"); }), "--pairs: pair '1-5' listed twice");

  const ImagePairSelector qualified = ParseImagePairSelector({"notredame/2-13", "--pairs"});
  EXPECT_EQ(qualified.sequence, "notredame");
  EXPECT_EQ(qualified.first_index, 2);
  EXPECT_EQ(qualified.second_index, 13);
  for (const char* bad : {"1", "1-", "-2", "0-2", "a-b", "1-2-3", "/1-2", "+1-2"}) {
    EXPECT_EQ(ErrorOf([&] { ParseImagePairSelector({bad, "--pairs"}); }),
              std::string("--pairs: '") + bad +
                  "' is not an image pair <i>-<j> or <sequence>/<i>-<j> (imgN's N, from 1)");
  }
  EXPECT_EQ(ErrorOf([] { ParseImagePairSelector({"3-3", "--pairs"}); }),
            "--pairs: '3-3' pairs an image with itself");
}

// Found by tests/fuzz/eval_pairs_fuzz: `--pairs "$(cat list)"` passed a
// line break, and the message quoting the item ran over two lines.
TEST(EvalPairs, ALineBreakInPairsIsRefusedInOneLine) {
  const std::string message =
      "--pairs: the list holds a line break (one line, e.g. 1-5,1-6; a file of pairs goes to --pairs-file)";
  EXPECT_EQ(ErrorOf([] { ParsePairList("day/1-4\ndusk/4-7"); }), message);
  EXPECT_EQ(ErrorOf([] { ParsePairList("1-5,\n1-6"); }), message);
  EXPECT_EQ(ParsePairList("1-5,1-6\r").back().text, "1-6");  // a trailing CR is trimmed, as before
}

TEST(EvalPairs, ListTextIsParsedAsTheFileIs) {
  const std::vector<PairSelector> list = ParsePairListText("1-5 # day\r\n\n a/2-3,4-1\n", "pairs.txt");
  ASSERT_EQ(list.size(), 3u);
  EXPECT_EQ(list[0].text, "1-5");
  EXPECT_EQ(list[1].origin, "pairs.txt:3");
  EXPECT_EQ(list[2].text, "4-1");
  EXPECT_EQ(ErrorOf([] { ParsePairListText("1-5,\n", "pairs.txt"); }), "pairs.txt:1: '1-5,' has an empty item");
  EXPECT_EQ(ErrorOf([] { ParsePairListText("", "pairs.txt"); }), "pairs.txt: lists no pair");
}

TEST(EvalPairs, ListFilesNameTheirLines) {
  const std::string dir = testing::ProcessTempDir("eval_pairs");
  const std::string path = dir + "/night.txt";
  std::ofstream(path) << "# day -> night\n1-5\n\n1-6, 2-6  # dusk\n";
  const std::vector<PairSelector> list = ReadPairListFile(path);
  ASSERT_EQ(list.size(), 3u);
  EXPECT_EQ(list[0].text, "1-5");
  EXPECT_EQ(list[2].text, "2-6");
  EXPECT_EQ(list[2].origin, path + ":4");
  std::ofstream(path) << "1-5\n1-5\n";
  EXPECT_EQ(ErrorOf([&] { ReadPairListFile(path); }), path + ":2: pair '1-5' listed twice");
  std::ofstream(path) << "# nothing\n";
  EXPECT_EQ(ErrorOf([&] { ReadPairListFile(path); }), path + ": lists no pair");
  EXPECT_EQ(ErrorOf([&] { ReadPairListFile(dir + "/absent.txt"); }),
            dir + "/absent.txt: cannot read the pair list");
}

}  // namespace
}  // namespace duskmap
