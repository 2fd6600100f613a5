// `generate --textures DIR`: every .png/.jpg in DIR is used or refused by
// name; one that cannot be read was skipped without a word (issue 48).
#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "slam/core/check.h"
#include "slam/synthetic/scene/textures.h"
#include "tests/testing/error_of.h"
#include "tests/testing/temp_dir.h"

namespace duskmap {
namespace {
namespace fs = std::filesystem;

fs::path TexturesFolder(const std::string& name) {
  const fs::path folder = testing::ProcessTempDir("user_textures_" + name);
  fs::create_directories(folder);
  EXPECT_TRUE(cv::imwrite((folder / "a.png").string(), cv::Mat(8, 8, CV_8UC3, cv::Scalar(1, 2, 3))));
  std::ofstream(folder / "notes.txt") << "not an image: not looked at";
  return folder;
}

void WriteBytes(const fs::path& path, const std::vector<uint8_t>& bytes) {
  std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()),
                                              static_cast<std::streamsize>(bytes.size()));
}

TEST(UserTextures, ReadableImagesAreLoadedAndOtherExtensionsIgnored) {
  const fs::path folder = TexturesFolder("good");
  EXPECT_EQ(LoadUserTextures(folder.string()).size(), 1u);
}

TEST(UserTextures, AnImageThatCannotBeReadIsAnErrorNamingIt) {
  // Whole (it ends with IEND) but its pixels do not decode.
  const fs::path folder = TexturesFolder("corrupt");
  std::vector<uint8_t> png;
  ASSERT_TRUE(cv::imencode(".png", cv::Mat(8, 8, CV_8UC3, cv::Scalar(9, 9, 9)), png));
  for (size_t i = 41; i + 16 < png.size(); ++i) png[i] = 0x5A;  // the IDAT data
  WriteBytes(folder / "b.png", png);
  EXPECT_EQ(testing::ErrorOf([&] { LoadUserTextures(folder.string()); }),
            (folder / "b.png").string() +
                ": cannot read this --textures image (unreadable or corrupt; fix or remove it)");
}

TEST(UserTextures, CutAndNonRegularFilesAreErrorsNamingThem) {
  const fs::path cut = TexturesFolder("cut");
  std::vector<uint8_t> jpeg;
  ASSERT_TRUE(cv::imencode(".jpg", cv::Mat(64, 64, CV_8UC3, cv::Scalar(9, 99, 199)), jpeg));
  jpeg.resize(jpeg.size() / 2);
  WriteBytes(cut / "c.jpg", jpeg);
  EXPECT_EQ(testing::ErrorOf([&] { LoadUserTextures(cut.string()); }),
            (cut / "c.jpg").string() + ": JPEG is truncated (no end-of-image marker)");
  const fs::path fifo = TexturesFolder("fifo");
  ASSERT_EQ(::mkfifo((fifo / "d.png").c_str(), 0600), 0);
  EXPECT_EQ(testing::ErrorOf([&] { LoadUserTextures(fifo.string()); }),
            (fifo / "d.png").string() + ": is a FIFO (named pipe), not a regular file");
}

}  // namespace
}  // namespace duskmap
