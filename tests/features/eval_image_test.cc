#include "slam/features/eval_image.h"

#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "tests/testing/error_of.h"

namespace duskmap {
namespace {

TEST(EvalImageTest, ReadsBgrAndNamesWhatItCannotRead) {
  const std::string dir = std::string(DUSKMAP_BINARY_DIR) + "/eval_image_test";
  std::filesystem::create_directories(dir);
  const cv::Mat gray(12, 20, CV_8UC1, cv::Scalar(77));
  ASSERT_TRUE(cv::imwrite(dir + "/gray.png", gray));
  const cv::Mat image = ReadEvalImage(dir + "/gray.png");
  EXPECT_EQ(image.type(), CV_8UC3);
  EXPECT_EQ(image.size(), gray.size());
  EXPECT_EQ(image.at<cv::Vec3b>(3, 4), cv::Vec3b(77, 77, 77));
  std::ofstream(dir + "/junk.png") << "not a png";
  EXPECT_EQ(testing::ErrorOf([&] { ReadEvalImage(dir + "/junk.png"); }),
            dir + "/junk.png: cannot read image");
  EXPECT_EQ(testing::ErrorOf([&] { ReadEvalImage(dir + "/absent.png"); }),
            dir + "/absent.png: cannot read image");
}

}  // namespace
}  // namespace duskmap
