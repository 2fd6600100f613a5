#include "slam/io/image_header.h"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <vector>

#include "slam/core/check.h"
#include "tests/testing/temp_dir.h"

namespace duskmap {
namespace {
namespace fs = std::filesystem;

std::string TempFile(const std::string& name) {
  return testing::ProcessTempPath("image_header_" + name);
}

std::string WriteBytes(const std::string& name, const std::vector<uint8_t>& bytes) {
  const std::string path = TempFile(name);
  std::ofstream(path, std::ios::binary | std::ios::trunc)
      .write(reinterpret_cast<const char*>(bytes.data()),
             static_cast<std::streamsize>(bytes.size()));
  return path;
}

void Append(std::vector<uint8_t>* bytes, std::initializer_list<int> values) {
  for (int v : values) bytes->push_back(static_cast<uint8_t>(v));
}

// A PNG signature and IHDR chunk declaring width x height, and no pixel data.
std::vector<uint8_t> PngHeader(uint32_t width, uint32_t height) {
  std::vector<uint8_t> bytes = {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A,
                                0,    0,   0,   13,  'I',  'H',  'D',  'R'};
  for (uint32_t v : {width, height})
    Append(&bytes, {int(v >> 24), int(v >> 16 & 255), int(v >> 8 & 255), int(v & 255)});
  Append(&bytes, {8, 2, 0, 0, 0, 0, 0, 0, 0});  // bit depth, colour type, ..., CRC
  return bytes;
}

// SOI, a JFIF APP0, a large APP1 (past the bytes read up front), fill bytes,
// a DHT (C4, not a frame header), then SOF2 declaring width x height.
std::vector<uint8_t> JpegHeader(int width, int height) {
  std::vector<uint8_t> bytes = {0xFF, 0xD8};
  Append(&bytes, {0xFF, 0xE0, 0, 16, 'J', 'F', 'I', 'F', 0, 1, 1, 0, 0, 1, 0, 1, 0, 0});
  const int app1_length = 30000;
  Append(&bytes, {0xFF, 0xE1, app1_length >> 8, app1_length & 255});
  bytes.resize(bytes.size() + app1_length - 2, 0xAB);
  Append(&bytes, {0xFF, 0xFF, 0xFF});  // two fill bytes before the marker
  Append(&bytes, {0xC4, 0, 5, 0, 0, 0});
  Append(&bytes, {0xFF, 0xC2, 0, 17, 8, height >> 8, height & 255, width >> 8, width & 255, 3, 1,
                  0x22, 0, 2, 0x11, 1, 3, 0x11, 1});
  Append(&bytes, {0xFF, 0xDA});  // scan data would follow
  return bytes;
}

std::string ErrorOf(const std::string& path) {
  try {
    CheckImageFilePixelLimit(path);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(ImageHeader, LimitIs64Mpixels) { EXPECT_EQ(kMaxImagePixels, 64 * 1024 * 1024); }

TEST(ImageHeader, LargePngIsRefusedFromItsHeader) {
  const std::string path = WriteBytes("huge.png", PngHeader(20000, 20000));
  const std::optional<ImageHeaderSize> size = ReadImageFileHeaderSize(path);
  ASSERT_TRUE(size.has_value());
  EXPECT_EQ(size->width, 20000);
  EXPECT_EQ(size->height, 20000);
  EXPECT_EQ(ErrorOf(path), path + ": 20000x20000 image exceeds the 64-Mpixel limit");
  // The largest sides a PNG can declare do not overflow the product.
  const std::string widest = WriteBytes("widest.png", PngHeader(0xFFFFFFFFu, 0xFFFFFFFFu));
  EXPECT_EQ(ErrorOf(widest), widest + ": 4294967295x4294967295 image exceeds the 64-Mpixel limit");
}

TEST(ImageHeader, LargeJpegIsRefusedFromItsFrameHeader) {
  const std::vector<uint8_t> bytes = JpegHeader(20000, 20000);
  const std::string path = WriteBytes("huge.jpg", bytes);
  const std::optional<ImageHeaderSize> size = ReadImageFileHeaderSize(path);
  ASSERT_TRUE(size.has_value());
  EXPECT_EQ(size->width, 20000);
  EXPECT_EQ(size->height, 20000);
  EXPECT_EQ(ErrorOf(path), path + ": 20000x20000 image exceeds the 64-Mpixel limit");
  // The in-memory reading agrees.
  const std::optional<ImageHeaderSize> in_memory = ReadImageHeaderSize(bytes.data(), bytes.size());
  ASSERT_TRUE(in_memory.has_value());
  EXPECT_EQ(in_memory->width, 20000);
}

TEST(ImageHeader, LargePnmIsRefusedFromItsHeader) {
  const std::string text = "P5\n# a comment\n20000   20000\n255\n";
  const std::string path = WriteBytes("huge.pgm", std::vector<uint8_t>(text.begin(), text.end()));
  EXPECT_EQ(ErrorOf(path), path + ": 20000x20000 image exceeds the 64-Mpixel limit");
}

TEST(ImageHeader, ReadsTheSizeOfRealEncodedImages) {
  const cv::Mat image(37, 53, CV_8UC3, cv::Scalar(10, 20, 30));
  for (const auto& [name, params] : std::vector<std::pair<std::string, std::vector<int>>>{
           {"small.png", {}},
           {"small.jpg", {}},
           {"progressive.jpg", {cv::IMWRITE_JPEG_PROGRESSIVE, 1}},
           {"small.ppm", {}},
           {"small.pgm", {}}}) {
    const std::string path = TempFile(name);
    ASSERT_TRUE(cv::imwrite(
        path, name == "small.pgm" ? cv::Mat(37, 53, CV_8UC1, cv::Scalar(9)) : image, params));
    const std::optional<ImageHeaderSize> size = ReadImageFileHeaderSize(path);
    ASSERT_TRUE(size.has_value()) << name;
    EXPECT_EQ(size->width, 53) << name;
    EXPECT_EQ(size->height, 37) << name;
    EXPECT_EQ(ErrorOf(path), "") << name;
  }
  // Exactly 64 Mpixels passes; one row more does not.
  const std::string at_limit = WriteBytes("at_limit.png", PngHeader(8192, 8192));
  EXPECT_EQ(ErrorOf(at_limit), "");
  EXPECT_NE(ErrorOf(WriteBytes("over.png", PngHeader(8192, 8193))), "");
}

// A format whose size nothing reads first is refused by name, not decoded.
TEST(ImageHeader, OtherFormatsAreRefusedByName) {
  const std::string tiff = TempFile("small.tiff");
  ASSERT_TRUE(cv::imwrite(tiff, cv::Mat(4, 4, CV_8UC3, cv::Scalar(1, 2, 3))));
  EXPECT_FALSE(ReadImageFileHeaderSize(tiff).has_value());
  EXPECT_EQ(ErrorOf(tiff), tiff + ": not a PNG, JPEG, PNM or BMP image (only these are read: "
                                  "their size is checked before decoding)");
  const std::string gif = WriteBytes("small.gif", {'G', 'I', 'F', '8', '9', 'a', 4, 0, 4, 0});
  EXPECT_NE(ErrorOf(gif).find(": not a PNG, JPEG, PNM or BMP image"), std::string::npos);
}

// BMP (the feature benchmarks' pairs may be BMP): its size from the DIB header.
TEST(ImageHeader, BmpSizeIsReadFromItsHeader) {
  const std::string bmp = TempFile("small.bmp");
  ASSERT_TRUE(cv::imwrite(bmp, cv::Mat(3, 5, CV_8UC3, cv::Scalar(1, 2, 3))));
  const std::optional<ImageHeaderSize> size = ReadImageFileHeaderSize(bmp);
  ASSERT_TRUE(size.has_value());
  EXPECT_EQ(size->width, 5);
  EXPECT_EQ(size->height, 3);
  EXPECT_EQ(ErrorOf(bmp), "");
  // 100000 x -100000 (top-down): refused before decoding.
  std::vector<uint8_t> huge = {'B', 'M', 0, 0, 0, 0, 0, 0, 0, 0, 54, 0, 0, 0, 40, 0, 0, 0};
  Append(&huge, {0xA0, 0x86, 0x01, 0x00, 0x60, 0x79, 0xFE, 0xFF, 1, 0, 24, 0});
  huge.resize(64, 0);
  const std::string huge_path = WriteBytes("huge.bmp", huge);
  EXPECT_EQ(ErrorOf(huge_path), huge_path + ": 100000x100000 image exceeds the 64-Mpixel limit");
  // "BM" and then no BMP header: no size (the decoder judges the file).
  const std::string text = "BM is how this text starts, and it goes on for a while.";
  EXPECT_FALSE(ReadImageFileHeaderSize(WriteBytes("bm.txt", std::vector<uint8_t>(text.begin(), text.end())))
                   .has_value());
}

std::string BeforeDecodingErrorOf(const std::string& path) {
  try {
    CheckImageFileBeforeDecoding(path);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// A decoder given a JPEG cut short returns a partly grey image without an
// error: the file is refused from its missing end-of-image marker.
TEST(ImageHeader, CutImagesAreRefusedBeforeDecoding) {
  cv::Mat noise(128, 128, CV_8UC3);
  cv::randu(noise, 0, 256);  // scan data well past the headers, where the cut falls
  std::vector<uint8_t> jpeg;
  ASSERT_TRUE(cv::imencode(".jpg", noise, jpeg));
  EXPECT_EQ(BeforeDecodingErrorOf(WriteBytes("whole.jpg", jpeg)), "");
  jpeg.resize(jpeg.size() * 2 / 3);
  const std::string cut = WriteBytes("cut.jpg", jpeg);
  EXPECT_FALSE(cv::imread(cut).empty()) << "OpenCV now refuses a cut JPEG itself";
  EXPECT_EQ(BeforeDecodingErrorOf(cut), cut + ": JPEG is truncated (no end-of-image marker)");
  std::vector<uint8_t> png;
  ASSERT_TRUE(cv::imencode(".png", cv::Mat(64, 64, CV_8UC3, cv::Scalar(10, 200, 30)), png));
  EXPECT_EQ(BeforeDecodingErrorOf(WriteBytes("whole.png", png)), "");
  png.resize(png.size() - 5);
  const std::string cut_png = WriteBytes("cut.png", png);
  EXPECT_EQ(BeforeDecodingErrorOf(cut_png), cut_png + ": PNG is truncated (no IEND chunk)");
  // A file whose header declares too many pixels is refused by the same call.
  const std::string huge = WriteBytes("huge.ppm", {'P', '6', '\n', '1', '0', '0', '0', '0', '0', ' ',
                                                   '1', '0', '0', '0', '0', '0', '\n', '2', '5', '5', '\n'});
  EXPECT_EQ(BeforeDecodingErrorOf(huge), huge + ": 100000x100000 image exceeds the 64-Mpixel limit");
}

// A FIFO would block the decoder's open(); a folder is no image.
TEST(ImageHeader, NonRegularFilesAreRefusedWithoutOpening) {
  const std::string fifo = TempFile("image_fifo.png");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_EQ(BeforeDecodingErrorOf(fifo), fifo + ": is a FIFO (named pipe), not a regular file");
  const std::string folder = TempFile("folder.png");
  fs::create_directories(folder);
  EXPECT_EQ(BeforeDecodingErrorOf(folder), folder + ": is a folder, not a regular file");
  EXPECT_EQ(BeforeDecodingErrorOf(TempFile("missing.png")), "");  // named by the caller
}

// PNG sides are 32-bit: their product must not overflow before the check.
TEST(ImageHeader, LargestDeclarableSidesAreJudgedWithoutOverflow) {
  EXPECT_FALSE(WithinPixelLimit({0xFFFFFFFFLL, 0xFFFFFFFFLL}));
  EXPECT_FALSE(WithinPixelLimit({1, kMaxImagePixels + 1}));
  EXPECT_FALSE(WithinPixelLimit({-1, 4}));
  EXPECT_TRUE(WithinPixelLimit({1, kMaxImagePixels}));
  EXPECT_TRUE(WithinPixelLimit({0, 0}));
  EXPECT_NE(ErrorOf(WriteBytes("widest.png", PngHeader(0xFFFFFFFFu, 0xFFFFFFFFu))), "");
}

TEST(ImageHeader, CutShortHeadersAreLeftToTheDecoder) {
  std::vector<uint8_t> png = PngHeader(20000, 20000);
  png.resize(20);  // IHDR cut short
  EXPECT_FALSE(ReadImageFileHeaderSize(WriteBytes("short.png", png)).has_value());
  std::vector<uint8_t> jpeg = JpegHeader(20000, 20000);
  jpeg.resize(5000);  // inside the APP1 segment
  EXPECT_FALSE(ReadImageFileHeaderSize(WriteBytes("short.jpg", jpeg)).has_value());
  EXPECT_FALSE(ReadImageFileHeaderSize(WriteBytes("empty.png", {})).has_value());
  EXPECT_FALSE(ReadImageFileHeaderSize(TempFile("does_not_exist.png")).has_value());
  const std::string text = "P6\n20000";  // height missing
  EXPECT_FALSE(ReadImageFileHeaderSize(
                   WriteBytes("short.ppm", std::vector<uint8_t>(text.begin(), text.end())))
                   .has_value());
}

}  // namespace
}  // namespace duskmap
