#include "slam/io/image_file.h"

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "slam/core/check.h"
#include "tests/testing/error_of.h"
#include "tests/testing/temp_dir.h"

namespace duskmap {
namespace {

namespace fs = std::filesystem;
using testing::ErrorOf;
using testing::ProcessTempDir;

std::string Bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

cv::Mat Noise(int type) {
  cv::Mat image(48, 64, type);
  cv::randu(image, 0, type == CV_16UC1 ? 65535 : 255);
  return image;
}

TEST(WriteImageFile, WritesTheBytesImwriteWrites) {
  const fs::path dir(ProcessTempDir("image_file_bytes"));
  for (const cv::Mat& image : {Noise(CV_8UC3), Noise(CV_16UC1)}) {
    for (const std::vector<int>& params :
         {std::vector<int>{}, std::vector<int>{cv::IMWRITE_PNG_COMPRESSION, 9}}) {
      ASSERT_TRUE(cv::imwrite((dir / "ref.png").string(), image, params));
      WriteImageFile((dir / "ours.png").string(), image, params);
      EXPECT_EQ(Bytes(dir / "ours.png"), Bytes(dir / "ref.png"));
    }
  }
}

TEST(WriteImageFile, AFullDiskNamesTheFileAndTheReasonAndLeavesNothing) {
  if (!fs::exists("/dev/full")) GTEST_SKIP() << "no /dev/full on this system";
  const fs::path path = fs::path(ProcessTempDir("image_file_full")) / "frame.png";
  fs::create_symlink("/dev/full", path);  // takes the file, refuses every write with ENOSPC
  EXPECT_EQ(ErrorOf([&] { WriteImageFile(path.string(), Noise(CV_8UC3)); }),
            path.string() + ": cannot write image: No space left on device");
  EXPECT_FALSE(fs::exists(fs::symlink_status(path)));
}

TEST(WriteImageFile, MissingFolderAndUnknownFormatAreOneLineErrors) {
  const fs::path dir(ProcessTempDir("image_file_bad"));
  EXPECT_EQ(ErrorOf([&] { WriteImageFile((dir / "no" / "a.png").string(), Noise(CV_8UC3)); }),
            (dir / "no" / "a.png").string() + ": cannot write image: No such file or directory");
  const std::string unknown = ErrorOf([&] { WriteImageFile((dir / "a.xyz").string(), Noise(CV_8UC3)); });
  EXPECT_EQ(unknown.rfind((dir / "a.xyz").string() + ": cannot encode image", 0), 0u) << unknown;
  EXPECT_EQ(ErrorOf([&] { WriteImageFile((dir / "noext").string(), Noise(CV_8UC3)); }),
            (dir / "noext").string() + ": cannot encode image: no file extension");
  EXPECT_FALSE(fs::exists(dir / "a.xyz"));
}

}  // namespace
}  // namespace duskmap
