#include "slam/features/eval/eval_image.h"

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
  // Checked before decoding, as the dataset readers' images are.
  std::ofstream(dir + "/junk.png") << "not a png";
  EXPECT_EQ(testing::ErrorOf([&] { ReadEvalImage(dir + "/junk.png"); }),
            dir + "/junk.png: not a PNG, JPEG, PNM or BMP image (only these are read: their size is "
                  "checked before decoding)");
  std::ofstream(dir + "/huge.ppm", std::ios::binary) << "P6\n100000 100000\n255\n" << std::string(64, '\0');
  EXPECT_EQ(testing::ErrorOf([&] { ReadEvalImage(dir + "/huge.ppm"); }),
            dir + "/huge.ppm: 100000x100000 image exceeds the 64-Mpixel limit");
  std::ofstream(dir + "/short.ppm", std::ios::binary) << "P6\n20 12\n255\n" << std::string(64, '\1');
  EXPECT_EQ(testing::ErrorOf([&] { ReadEvalImage(dir + "/short.ppm"); }),
            dir + "/short.ppm: cannot read image");
  EXPECT_EQ(testing::ErrorOf([&] { ReadEvalImage(dir + "/absent.png"); }),
            dir + "/absent.png: cannot read image");
}

}  // namespace
}  // namespace duskmap
