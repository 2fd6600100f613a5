#include "slam/datasets/poses_file.h"

#include <gtest/gtest.h>

#include "slam/core/check.h"

namespace duskmap {
namespace {

TEST(ParsePosesText, ReadsFormat11WithHeader) {
  const PosesFile file = ParsePosesText(
      "#timestamp x y z qx qy qz qw id\n"
      "1700000000.000000 0.000000 0.000000 0.000000 0.707107 0.000000 0.707107 0.000000 1\n"
      "1700000000.100000 -0.000000 -0.143086 -0.012518 0.704496 -0.060706 0.704496 -0.060706 2\n");
  ASSERT_TRUE(file.bad_lines.empty());
  ASSERT_EQ(file.poses.size(), 2u);
  EXPECT_EQ(file.poses[0].line, 2);
  EXPECT_EQ(file.poses[0].stamp_text, "1700000000.000000");
  EXPECT_EQ(file.poses[1].id, 2);
  EXPECT_DOUBLE_EQ(file.poses[1].stamp_s, 1700000000.1);
  EXPECT_NEAR(file.poses[1].map_from_frame.translation.y(), -0.143086, 1e-12);
  // qw = 0 is a valid 180 degree rotation (the first pose of the fixture).
  EXPECT_NEAR(file.poses[0].map_from_frame.rotation.x(), std::sqrt(0.5), 1e-6);
}

TEST(ParsePosesText, AcceptsLinesWithoutIdAndCrLf) {
  const PosesFile file = ParsePosesText("1.0 1 2 3 0 0 0 1\r\n\n2.0 1 2 3 0 0 0 1\r\n");
  ASSERT_TRUE(file.bad_lines.empty());
  ASSERT_EQ(file.poses.size(), 2u);
  EXPECT_EQ(file.poses[0].id, -1);
  EXPECT_EQ(file.poses[1].line, 3);
}

TEST(ParsePosesText, ListsEveryBadLineWithItsNumber) {
  const PosesFile file = ParsePosesText(
      "1.0 0 0 0 0 0 0 1 1\n"
      "2.0 nan 0 0 0 0 0 1 2\n"           // non-finite
      "3.0 0 0 0 0 0 0 1\n"               // fine (no id)
      "2.5 0 0 0 0 0 0 1 4\n"             // backwards
      "4.0 0 0 0 0 0 0 2 5\n"             // not unit
      "5.0 0 0 0 0 0 0 1 x\n"             // bad id
      "6.0 0 0 0 0 0 1\n"                 // too few fields
      "7.0 0 0 abc 0 0 0 1 8\n"           // not a number
      "8.0 0 0 0 0 0 0 1 9\n");
  ASSERT_EQ(file.poses.size(), 3u);
  EXPECT_EQ(file.poses[1].line, 3);
  EXPECT_EQ(file.poses[2].line, 9);
  ASSERT_EQ(file.bad_lines.size(), 6u);
  EXPECT_EQ(file.bad_lines[0].line, 2);
  EXPECT_NE(file.bad_lines[0].problem.find("non-finite"), std::string::npos);
  EXPECT_EQ(file.bad_lines[1].line, 4);
  EXPECT_NE(file.bad_lines[1].problem.find("not after the previous"), std::string::npos);
  EXPECT_NE(file.bad_lines[2].problem.find("not unit length"), std::string::npos);
  EXPECT_NE(file.bad_lines[3].problem.find("id 'x'"), std::string::npos);
  EXPECT_NE(file.bad_lines[4].problem.find("7 fields"), std::string::npos);
  EXPECT_NE(file.bad_lines[5].problem.find("'abc' is not a number"), std::string::npos);
}

TEST(ParsePosesText, EqualTimestampsAreBackwards) {
  const PosesFile file = ParsePosesText("1.0 0 0 0 0 0 0 1\n1.0 0 0 0 0 0 0 1\n");
  EXPECT_EQ(file.poses.size(), 1u);
  EXPECT_EQ(file.bad_lines.size(), 1u);
}

TEST(ReadPosesFile, MissingFileThrowsNamingIt) {
  try {
    ReadPosesFile("/nonexistent/poses.txt");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/poses.txt"), std::string::npos);
  }
}

}  // namespace
}  // namespace duskmap
