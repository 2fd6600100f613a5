#include "slam/io/tum_dataset.h"

#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "slam/core/check.h"
#include "slam/io/synthetic_dataset.h"
#include "slam/io/tum_writer.h"
#include "tests/testing/temp_dir.h"

namespace duskmap {
namespace {
namespace fs = std::filesystem;

using testing::ProcessTempDir;

std::vector<RgbdFrame> MakeFrames(int count) {
  std::vector<RgbdFrame> frames;
  cv::RNG rng(5);
  for (int i = 0; i < count; ++i) {
    RgbdFrame f;
    f.frame_index = i;
    f.timestamp_s = 60000.0 + i;
    f.bgr = cv::Mat(24, 32, CV_8UC3);
    rng.fill(f.bgr, cv::RNG::UNIFORM, 0, 256);
    f.depth_m = cv::Mat(24, 32, CV_32FC1);
    rng.fill(f.depth_m, cv::RNG::UNIFORM, 0.5, 4.0);
    f.depth_m.at<float>(0, 0) = 0.0f;
    f.world_from_camera = Rigid3d(Eigen::Quaterniond(Eigen::AngleAxisd(0.1 * i, Eigen::Vector3d::UnitY())),
                                  Eigen::Vector3d(i, 0.5, 1.3));
    f.odom_from_body = Rigid3d(Eigen::Quaterniond::Identity(), Eigen::Vector3d(0, 0, 0.55 * i));
    frames.push_back(f);
  }
  return frames;
}

TumCalibration SmallCalibration() {
  TumCalibration c;
  c.camera.width = 32;
  c.camera.height = 24;
  c.camera.fx = c.camera.fy = 30.0;
  c.camera.cx = 15.5;
  c.camera.cy = 11.5;
  c.depth_scale = 1000.0;
  return c;
}

std::string WriteSession(const fs::path& folder, const std::vector<RgbdFrame>& frames) {
  TumSessionWriter writer(folder.string(), SmallCalibration());
  for (const RgbdFrame& f : frames) writer.Write(f);
  writer.Finish();
  return folder.string();
}

// The message of the InputError `f` throws ("" when it throws none).
template <typename F>
std::string ErrorOf(F f) {
  try {
    f();
  } catch (const InputError& e) {
    // Ordering errors end with how to read such a recording anyway
    // (checked once in AllowUnorderedHintEndsOrderingErrors).
    std::string message = e.what();
    const std::string hint = "; --allow-unordered reads it as recorded";
    if (message.size() > hint.size() && message.compare(message.size() - hint.size(), hint.size(), hint) == 0) {
      message.resize(message.size() - hint.size());
    }
    return message;
  }
  return "";
}

TumReadOptions Lenient() {
  TumReadOptions options;
  options.allow_unordered = true;
  return options;
}

std::vector<std::string> ReadLines(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

void WriteLines(const std::string& path, const std::vector<std::string>& lines) {
  std::ofstream out(path);
  for (const std::string& line : lines) out << line << "\n";
}

// The index line of a written frame ("<stamp> rgb/<stamp>.png").
std::string IndexLine(const std::string& kind, double timestamp_s) {
  return TumStamp(timestamp_s) + " " + kind + "/" + TumStamp(timestamp_s) + ".png";
}

std::vector<double> Timestamps(SessionReader& session) {
  std::vector<double> timestamps;
  while (const std::optional<RgbdFrame> f = session.Next()) timestamps.push_back(f->timestamp_s);
  return timestamps;
}

TEST(TumDataset, WriteReadRoundTrip) {
  const std::vector<RgbdFrame> frames = MakeFrames(4);
  const std::string path = WriteSession(fs::path(ProcessTempDir("tum_round")) / "seq", frames);
  std::unique_ptr<DatasetReader> dataset = OpenTumDataset(path);
  ASSERT_EQ(dataset->Sessions().size(), 1u);
  EXPECT_EQ(dataset->Sessions()[0].name, "seq");
  EXPECT_EQ(dataset->Sessions()[0].num_frames, 4);
  std::unique_ptr<SessionReader> session = dataset->OpenSession("seq");
  for (const RgbdFrame& expected : frames) {
    const std::optional<RgbdFrame> f = session->Next();
    ASSERT_TRUE(f.has_value());
    EXPECT_NEAR(f->timestamp_s, expected.timestamp_s, 1e-6);
    EXPECT_EQ(cv::norm(f->bgr, expected.bgr, cv::NORM_INF), 0.0);
    EXPECT_LE(cv::norm(f->depth_m, expected.depth_m, cv::NORM_INF), 0.0006);  // millimetre rounding
    EXPECT_EQ(f->depth_m.at<float>(0, 0), 0.0f);
    ASSERT_TRUE(f->world_from_camera.has_value());
    EXPECT_LT((f->world_from_camera->translation - expected.world_from_camera->translation).norm(), 1e-6);
    EXPECT_LT((f->odom_from_body.translation - expected.odom_from_body.translation).norm(), 1e-6);
    EXPECT_DOUBLE_EQ(f->camera.fx, 30.0);
  }
  EXPECT_FALSE(session->Next().has_value());
  session->Rewind();
  EXPECT_TRUE(session->Next().has_value());
}

TEST(TumDataset, MissingImageNamesTheFile) {
  const std::string path = WriteSession(fs::path(ProcessTempDir("tum_missing")) / "seq", MakeFrames(3));
  const std::string victim = path + "/rgb/" + TumStamp(60002.0) + ".png";
  fs::remove(victim);
  try {
    OpenTumDataset(path);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(TumStamp(60002.0) + ".png"), std::string::npos) << e.what();
  }
}

TEST(TumDataset, TruncatedImageThrowsWhenRead) {
  const std::string path = WriteSession(fs::path(ProcessTempDir("tum_truncated")) / "seq", MakeFrames(3));
  const std::string victim = path + "/depth/" + TumStamp(60001.0) + ".png";
  fs::resize_file(victim, 40);
  std::unique_ptr<SessionReader> session = OpenTumDataset(path)->OpenSession("seq");
  EXPECT_TRUE(session->Next().has_value());
  try {
    session->Next();
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(victim), std::string::npos) << e.what();
  }
}

TEST(TumDataset, TruncatedIndexLineThrows) {
  const std::string path = WriteSession(fs::path(ProcessTempDir("tum_index")) / "seq", MakeFrames(2));
  std::ofstream(path + "/rgb.txt", std::ios::app) << "60005.0\n";
  EXPECT_THROW(OpenTumDataset(path), InputError);
}

TEST(TumDataset, RealTumFolderUsesPublishedIntrinsicsAndAssociates) {
  const fs::path folder = fs::path(ProcessTempDir("tum_fr1")) / "rgbd_dataset_freiburg1_xyz";
  fs::create_directories(folder / "rgb");
  fs::create_directories(folder / "depth");
  cv::imwrite((folder / "rgb/1.000000.png").string(), cv::Mat(480, 640, CV_8UC3, cv::Scalar(1, 2, 3)));
  cv::imwrite((folder / "depth/1.010000.png").string(), cv::Mat(480, 640, CV_16UC1, cv::Scalar(5000)));
  cv::imwrite((folder / "rgb/2.000000.png").string(), cv::Mat(480, 640, CV_8UC3, cv::Scalar(1, 2, 3)));
  std::ofstream(folder / "rgb.txt") << "# color\n1.000000 rgb/1.000000.png\n2.000000 rgb/2.000000.png\n";
  std::ofstream(folder / "depth.txt") << "1.010000 depth/1.010000.png\n";
  std::ofstream(folder / "groundtruth.txt") << "0.99 1 2 3 0 0 0 1\n1.02 1 2 3 0 0 0 1\n";
  // rgb 2.0 has no depth within 0.02 s: an error, unless read leniently.
  EXPECT_EQ(ErrorOf([&] { OpenTumDataset(folder.string()); }),
            folder.string() + "/rgb.txt:3: no depth image within 0.02 s of 2.000000 in depth.txt");
  std::unique_ptr<DatasetReader> dataset = OpenTumDataset(folder.string(), Lenient());
  EXPECT_EQ(dataset->Sessions()[0].num_frames, 1);  // rgb 2.0 is skipped
  const std::optional<RgbdFrame> f = dataset->OpenSession("rgbd_dataset_freiburg1_xyz")->Next();
  ASSERT_TRUE(f.has_value());
  EXPECT_DOUBLE_EQ(f->camera.fx, 517.3);
  EXPECT_FLOAT_EQ(f->depth_m.at<float>(10, 10), 1.0f);  // 5000 units per metre
  ASSERT_TRUE(f->world_from_camera.has_value());
  EXPECT_NEAR(f->world_from_camera->translation.y(), 2.0, 1e-9);
}

// The writer's index files: two comment lines, then one line per frame
// (frame k on line k + 3), rgb and depth with the same timestamps.
TEST(TumDataset, GeneratedIndexFilesAreStrictlyIncreasingAndOneToOne) {
  const std::string path = WriteSession(fs::path(ProcessTempDir("tum_strict_ok")) / "seq", MakeFrames(5));
  EXPECT_EQ(ReadLines(path + "/rgb.txt")[2], IndexLine("rgb", 60000.0));
  EXPECT_EQ(ReadLines(path + "/depth.txt")[6], IndexLine("depth", 60004.0));
  EXPECT_EQ(OpenTumDataset(path)->Sessions()[0].num_frames, 5);
}

TEST(TumDataset, OutOfOrderLineNamesFileAndLine) {
  const std::string path = WriteSession(fs::path(ProcessTempDir("tum_unordered")) / "seq", MakeFrames(4));
  std::vector<std::string> lines = ReadLines(path + "/rgb.txt");
  std::swap(lines[3], lines[4]);  // lines 4 and 5: 60002 before 60001
  WriteLines(path + "/rgb.txt", lines);
  EXPECT_EQ(ErrorOf([&] { OpenTumDataset(path); }),
            path + "/rgb.txt:5: timestamp 60001.000000 is not after line 4's 60002.000000 (out of "
                   "order)");
  // Leniently, the lines are sorted: every frame, in time order.
  std::unique_ptr<DatasetReader> dataset = OpenTumDataset(path, Lenient());
  EXPECT_EQ(Timestamps(*dataset->OpenSession("seq")),
            (std::vector<double>{60000.0, 60001.0, 60002.0, 60003.0}));
}

TEST(TumDataset, OutOfOrderDepthLineNamesDepthTxt) {
  const std::string path = WriteSession(fs::path(ProcessTempDir("tum_unordered_depth")) / "seq", MakeFrames(3));
  std::vector<std::string> lines = ReadLines(path + "/depth.txt");
  std::swap(lines[2], lines[4]);
  WriteLines(path + "/depth.txt", lines);
  const std::string message = ErrorOf([&] { OpenTumDataset(path); });
  EXPECT_EQ(message.rfind(path + "/depth.txt:4: timestamp 60001.000000 is not after line 3's "
                                 "60002.000000",
                          0),
            0u)
      << message;
  EXPECT_EQ(OpenTumDataset(path, Lenient())->Sessions()[0].num_frames, 3);
}

TEST(TumDataset, AllowUnorderedHintEndsOrderingErrors) {
  const std::string path = WriteSession(fs::path(ProcessTempDir("tum_hint")) / "seq", MakeFrames(3));
  std::vector<std::string> lines = ReadLines(path + "/rgb.txt");
  std::swap(lines[2], lines[4]);
  WriteLines(path + "/rgb.txt", lines);
  try {
    OpenTumDataset(path);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("(out of order); --allow-unordered reads it as recorded"), std::string::npos)
        << message;
  }
}

TEST(TumDataset, DuplicateLineNamesBothLines) {
  const std::string path = WriteSession(fs::path(ProcessTempDir("tum_duplicate")) / "seq", MakeFrames(3));
  std::vector<std::string> lines = ReadLines(path + "/rgb.txt");
  lines.push_back(lines[3]);  // line 6 repeats line 4 (60001)
  WriteLines(path + "/rgb.txt", lines);
  EXPECT_EQ(ErrorOf([&] { OpenTumDataset(path); }),
            path + "/rgb.txt:6: duplicate timestamp 60001.000000 (also on line 4)");
  // An adjacent repeat is named the same way.
  lines.pop_back();
  lines.insert(lines.begin() + 4, lines[3]);
  WriteLines(path + "/rgb.txt", lines);
  EXPECT_EQ(ErrorOf([&] { OpenTumDataset(path); }),
            path + "/rgb.txt:5: duplicate timestamp 60001.000000 (also on line 4)");
  // Leniently, as before: the frame is read twice.
  std::unique_ptr<DatasetReader> dataset = OpenTumDataset(path, Lenient());
  EXPECT_EQ(Timestamps(*dataset->OpenSession("seq")),
            (std::vector<double>{60000.0, 60001.0, 60001.0, 60002.0}));
}

TEST(TumDataset, RgbLineWithoutDepthNamesTheRgbLine) {
  const std::string path = WriteSession(fs::path(ProcessTempDir("tum_no_depth")) / "seq", MakeFrames(4));
  std::vector<std::string> lines = ReadLines(path + "/depth.txt");
  lines.erase(lines.begin() + 4);  // depth 60002
  WriteLines(path + "/depth.txt", lines);
  EXPECT_EQ(ErrorOf([&] { OpenTumDataset(path); }),
            path + "/rgb.txt:5: no depth image within 0.02 s of 60002.000000 in depth.txt");
  // Leniently, as before: the frame is skipped.
  std::unique_ptr<DatasetReader> dataset = OpenTumDataset(path, Lenient());
  EXPECT_EQ(Timestamps(*dataset->OpenSession("seq")),
            (std::vector<double>{60000.0, 60001.0, 60003.0}));
}

TEST(TumDataset, DepthImageNearestToTwoRgbLinesIsAnError) {
  const std::string path = WriteSession(fs::path(ProcessTempDir("tum_depth_twice")) / "seq", MakeFrames(3));
  std::vector<std::string> lines = ReadLines(path + "/rgb.txt");
  // rgb 60000.010 (line 4) has depth 60000 (depth.txt:3) as its nearest, as rgb 60000 has.
  lines.insert(lines.begin() + 3, "60000.010000 rgb/" + TumStamp(60000.0) + ".png");
  WriteLines(path + "/rgb.txt", lines);
  EXPECT_EQ(ErrorOf([&] { OpenTumDataset(path); }),
            path + "/rgb.txt:4: the nearest depth image to 60000.010000 (depth.txt:3, "
                   "60000.000000) is already used by line 3's 60000.000000 (one depth image for "
                   "two rgb images)");
  EXPECT_EQ(OpenTumDataset(path, Lenient())->Sessions()[0].num_frames, 4);
}

TEST(TumDataset, DepthLineWithoutRgbNamesTheDepthLine) {
  const std::string path = WriteSession(fs::path(ProcessTempDir("tum_no_rgb")) / "seq", MakeFrames(4));
  std::vector<std::string> lines = ReadLines(path + "/rgb.txt");
  lines.erase(lines.begin() + 3);  // rgb 60001: its frame would vanish unnoticed
  WriteLines(path + "/rgb.txt", lines);
  EXPECT_EQ(ErrorOf([&] { OpenTumDataset(path); }),
            path + "/depth.txt:4: depth image at 60001.000000 is not matched by any rgb.txt line "
                   "(each rgb image takes its nearest depth image within 0.02 s)");
  EXPECT_EQ(OpenTumDataset(path, Lenient())->Sessions()[0].num_frames, 3);
}

TEST(TumDataset, ImageOverThePixelLimitIsRefusedBeforeDecoding) {
  const std::string path = WriteSession(fs::path(ProcessTempDir("tum_huge")) / "seq", MakeFrames(2));
  const std::string victim = path + "/rgb/" + TumStamp(60001.0) + ".png";
  {
    // A PNG signature and an IHDR chunk declaring 20000x20000 8-bit RGB, and
    // no pixel data: decoding it would allocate 1.2 GB before failing.
    const unsigned char header[] = {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A,
                                    0, 0, 0, 13, 'I', 'H', 'D', 'R',
                                    0, 0, 0x4E, 0x20, 0, 0, 0x4E, 0x20,
                                    8, 2, 0, 0, 0, 0, 0, 0, 0};
    std::ofstream(victim, std::ios::binary | std::ios::trunc)
        .write(reinterpret_cast<const char*>(header), sizeof(header));
  }
  std::unique_ptr<SessionReader> session = OpenTumDataset(path)->OpenSession("seq");
  EXPECT_TRUE(session->Next().has_value());
  EXPECT_EQ(ErrorOf([&] { session->Next(); }),
            victim + ": 20000x20000 image exceeds the 64-Mpixel limit");
}

// OpenCV decodes a JPEG cut short into a partly grey image without an error:
// the reader refuses it from its missing end-of-image marker.
TEST(TumDataset, TruncatedJpegInASessionIsRefused) {
  const std::string path = WriteSession(fs::path(ProcessTempDir("tum_cut_jpeg")) / "seq", MakeFrames(2));
  const std::string stamp = TumStamp(60001.0);
  std::vector<uint8_t> jpeg;
  ASSERT_TRUE(cv::imencode(".jpg", MakeFrames(2)[1].bgr, jpeg));
  jpeg.resize(jpeg.size() * 2 / 3);
  const std::string victim = path + "/rgb/" + stamp + ".jpg";
  std::ofstream(victim, std::ios::binary).write(reinterpret_cast<const char*>(jpeg.data()),
                                                static_cast<std::streamsize>(jpeg.size()));
  std::vector<std::string> lines = ReadLines(path + "/rgb.txt");
  for (std::string& line : lines) {
    if (line == IndexLine("rgb", 60001.0)) line = stamp + " rgb/" + stamp + ".jpg";
  }
  WriteLines(path + "/rgb.txt", lines);
  ASSERT_FALSE(cv::imread(victim).empty()) << "OpenCV refuses a cut JPEG itself now";
  std::unique_ptr<SessionReader> session = OpenTumDataset(path)->OpenSession("seq");
  EXPECT_TRUE(session->Next().has_value());
  EXPECT_EQ(ErrorOf([&] { session->Next(); }), victim + ": JPEG is truncated (no end-of-image marker)");
}

// Depth is one channel of 16 bits: a 16-bit colour PNG was read as its grey
// conversion without a word.
TEST(TumDataset, ColourDepthImageIsRefused) {
  const std::string path = WriteSession(fs::path(ProcessTempDir("tum_colour_depth")) / "seq", MakeFrames(2));
  const std::string victim = path + "/depth/" + TumStamp(60001.0) + ".png";
  ASSERT_TRUE(cv::imwrite(victim, cv::Mat(24, 32, CV_16UC3, cv::Scalar(1000, 2000, 3000))));
  std::unique_ptr<SessionReader> session = OpenTumDataset(path)->OpenSession("seq");
  EXPECT_TRUE(session->Next().has_value());
  EXPECT_EQ(ErrorOf([&] { session->Next(); }),
            victim + ": depth image must be single-channel 16-bit, got 3 channel(s) of 16 bits");
  // 8-bit grey depth is refused the same way.
  ASSERT_TRUE(cv::imwrite(victim, cv::Mat(24, 32, CV_8UC1, cv::Scalar(7))));
  session->Rewind();
  EXPECT_TRUE(session->Next().has_value());
  EXPECT_EQ(ErrorOf([&] { session->Next(); }),
            victim + ": depth image must be single-channel 16-bit, got 1 channel(s) of 8 bits");
}

// A FIFO opened for reading blocks until a writer appears: index files and
// images that are not regular files are refused from their type. (The alarm
// ends the test process should the reader block again.)
TEST(TumDataset, FifoAndFolderInputsAreRefusedWithoutOpening) {
  alarm(120);
  const std::string path = WriteSession(fs::path(ProcessTempDir("tum_fifo")) / "seq", MakeFrames(2));
  const std::string image = path + "/rgb/" + TumStamp(60001.0) + ".png";
  fs::remove(image);
  ASSERT_EQ(::mkfifo(image.c_str(), 0600), 0);
  EXPECT_EQ(ErrorOf([&] { OpenTumDataset(path); }), image + ": is a FIFO (named pipe), not a regular file");
  const std::string other = WriteSession(fs::path(ProcessTempDir("tum_fifo_index")) / "seq", MakeFrames(2));
  fs::remove(other + "/rgb.txt");
  ASSERT_EQ(::mkfifo((other + "/rgb.txt").c_str(), 0600), 0);
  EXPECT_EQ(ErrorOf([&] { OpenTumDataset(other); }),
            other + "/rgb.txt: is a FIFO (named pipe), not a regular file");
  const std::string third = WriteSession(fs::path(ProcessTempDir("tum_folder_truth")) / "seq", MakeFrames(2));
  fs::remove(third + "/groundtruth.txt");
  fs::create_directories(third + "/groundtruth.txt");
  EXPECT_EQ(ErrorOf([&] { OpenTumDataset(third); }),
            third + "/groundtruth.txt: is a folder, not a regular file");
  // A synthetic dataset's manifest.json: not "missing", but what it is.
  const fs::path dataset = ProcessTempDir("synthetic_fifo_manifest");
  fs::create_directories(dataset);
  ASSERT_EQ(::mkfifo((dataset / kManifestFileName).c_str(), 0600), 0);
  EXPECT_EQ(ErrorOf([&] { OpenSyntheticDataset(dataset.string()); }),
            (dataset / kManifestFileName).string() + ": is a FIFO (named pipe), not a regular file");
  alarm(0);
}

TEST(TumDataset, SymlinkLoopsAreInputErrorsNamingThePath) {
  const std::string path = WriteSession(fs::path(ProcessTempDir("tum_loop")) / "seq", MakeFrames(2));
  const std::string loop_problem = ": Too many levels of symbolic links";
  // A listed image.
  const std::string image = path + "/depth/" + TumStamp(60001.0) + ".png";
  fs::remove(image);
  fs::create_symlink(image, image);
  EXPECT_EQ(ErrorOf([&] { OpenTumDataset(path); }), image + loop_problem);
  // An optional file (ground truth), which is otherwise tested for existence.
  const std::string other = WriteSession(fs::path(ProcessTempDir("tum_loop_truth")) / "seq", MakeFrames(2));
  const std::string truth = other + "/groundtruth.txt";
  fs::remove(truth);
  fs::create_symlink(truth, truth);
  EXPECT_EQ(ErrorOf([&] { OpenTumDataset(other); }), truth + loop_problem);
  // The sequence folder itself.
  const std::string folder = (fs::path(ProcessTempDir("tum_loop_folder")) / "seq").string();
  fs::create_symlink(folder, folder);
  EXPECT_EQ(ErrorOf([&] { OpenTumDataset(folder); }), folder + loop_problem);
}

TEST(TumCalibrationFile, DepthScaleOutsideOneToOneHundredThousandIsRefused) {
  const fs::path root = ProcessTempDir("tum_calibration_scale");
  fs::create_directories(root);
  const std::string path = (root / kCalibrationFileName).string();
  TumCalibration c = SmallCalibration();
  for (const double scale : {1.0, 1000.0, 5000.0, 100000.0}) {
    c.depth_scale = scale;
    WriteCalibration(path, c);
    EXPECT_EQ(ReadCalibration(path).depth_scale, scale);
  }
  for (const double scale : {1e-300, 0.5, 0.0, -1000.0, 1e6}) {
    c.depth_scale = scale;
    WriteCalibration(path, c);
    EXPECT_NE(ErrorOf([&] { ReadCalibration(path); })
                  .find(path + ": depth_scale must be in [1, 100000] raw units per metre"),
              std::string::npos)
        << scale;
  }
}

// calibration.json is written and read through its codec (calibration_json.h):
// the same text as the hand-written writer made, every key required, unknown
// keys refused with the file's name.
TEST(TumCalibrationFile, WrittenTextAndRequiredKeys) {
  const fs::path root = ProcessTempDir("tum_calibration_text");
  const std::string path = (root / kCalibrationFileName).string();
  TumCalibration c;
  c.camera = PinholeCamera{640, 480, 525.0, 526.5, 319.5, 239.5};
  c.depth_scale = 1000.0;
  WriteCalibration(path, c);
  std::ifstream in(path);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(text,
            "{\n  \"cx\": 319.5,\n  \"cy\": 239.5,\n  \"depth_scale\": 1000.0,\n  \"fx\": 525.0,\n"
            "  \"fy\": 526.5,\n  \"height\": 480,\n  \"width\": 640\n}\n");
  const TumCalibration back = ReadCalibration(path);
  EXPECT_EQ(back.camera.width, 640);
  EXPECT_EQ(back.camera.fy, 526.5);
  EXPECT_EQ(back.depth_scale, 1000.0);

  std::ofstream(path) << R"({"width": 640, "height": 480, "fx": 525, "fy": 525, "cx": 319.5,
                              "cy": 239.5})";
  EXPECT_EQ(ErrorOf([&] { ReadCalibration(path); }), path + ": missing key 'depth_scale'");
  std::ofstream(path) << R"({"width": 640, "height": 480, "fx": 525, "fy": 525, "cx": 319.5,
                              "cy": 239.5, "depth_scale": 1000, "k1": 0.1})";
  EXPECT_NE(ErrorOf([&] { ReadCalibration(path); }).find(path), std::string::npos);
  EXPECT_NE(ErrorOf([&] { ReadCalibration(path); }).find("k1"), std::string::npos);
}

TEST(SyntheticDataset, ManifestCreditsItsAssetsOnlyWhenItHasAny) {
  const fs::path root = ProcessTempDir("tum_synthetic_assets");
  fs::create_directories(root);
  const ManifestSession session{"1", "1", "16:46", "mapping"};
  WriteManifest(root.string(), {{session}, {}});
  std::ifstream written(root / kManifestFileName);
  const std::string text((std::istreambuf_iterator<char>(written)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("sessions"), std::string::npos);
  EXPECT_EQ(text.find("assets"), std::string::npos);
  WriteManifest(root.string(), {{session}, {{"Bed", "BlendSwap-CC-0.sh3f#Blend Swap CC-0#bed1", "Someone", "Public domain"}}});
  const DatasetManifest manifest = ReadManifest(root.string());
  ASSERT_EQ(manifest.assets.size(), 1u);
  EXPECT_EQ(manifest.assets[0].name, "Bed");
  EXPECT_EQ(manifest.assets[0].source, "BlendSwap-CC-0.sh3f#Blend Swap CC-0#bed1");
  EXPECT_EQ(manifest.assets[0].creator, "Someone");
  EXPECT_EQ(manifest.assets[0].license, "Public domain");
}

// The text the hand-written writer gave before the manifest had a codec
// (datasets' checksums depend on it), and strict reading.
TEST(SyntheticDataset, ManifestIsWrittenAsBeforeAndReadStrictly) {
  const fs::path root = ProcessTempDir("tum_synthetic_text");
  fs::create_directories(root);
  const std::string path = (root / kManifestFileName).string();
  const auto text = [&] {
    std::ifstream in(path);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  };
  WriteManifest(root.string(), {{{"1", "1", "16:46", "mapping"}}, {}});
  EXPECT_EQ(text(),
            "{\n  \"format\": \"duskmap-synthetic\",\n  \"sessions\": [\n    {\n      \"clock_time\": \"16:46\",\n"
            "      \"folder\": \"1\",\n      \"name\": \"1\",\n      \"role\": \"mapping\"\n    }\n  ],\n"
            "  \"version\": 1\n}\n");
  WriteManifest(root.string(), {{{"A", "A", "16:51", "localization"}}, {{"Bed", "c.sh3f#bed1", "", "CC0"}}});
  EXPECT_EQ(text(),
            "{\n  \"assets\": [\n    {\n      \"creator\": \"\",\n      \"license\": \"CC0\",\n"
            "      \"name\": \"Bed\",\n      \"source\": \"c.sh3f#bed1\"\n    }\n  ],\n"
            "  \"format\": \"duskmap-synthetic\",\n  \"sessions\": [\n    {\n      \"clock_time\": \"16:51\",\n"
            "      \"folder\": \"A\",\n      \"name\": \"A\",\n      \"role\": \"localization\"\n    }\n  ],\n"
            "  \"version\": 1\n}\n");
  const auto error_for = [&](const std::string& json) {
    std::ofstream(path) << json;
    return ErrorOf([&] { ReadManifest(root.string()); });
  };
  const std::string head = R"({"format": "duskmap-synthetic", "version": 1, )";
  EXPECT_EQ(error_for(head + R"("sessions": [{"name": "1", "folder": "1", "colour": 1}]})"),
            path + ".sessions[0]: unknown key 'colour'");
  EXPECT_EQ(error_for(head + R"("sessions": [{"folder": "1"}]})"), path + ".sessions[0]: missing key 'name'");
  EXPECT_EQ(error_for(head + R"("sessions": []})"), path + ": 'sessions' must be a non-empty array");
  EXPECT_EQ(error_for(head + R"("sessions": [{"name": "1", "folder": "1"}, {"name": "1", "folder": "2"}]})"),
            path + ": duplicate session '1'");
  EXPECT_EQ(error_for(head + R"("sessions": [{"name": "1", "folder": "1"}], "assets": [{"name": "x"}]})"),
            path + ".assets[0]: missing key 'source'");
  EXPECT_EQ(error_for(R"({"format": "other", "version": 1, "sessions": []})"),
            path + ": unsupported format 'other' version 1");
}

TEST(SyntheticDataset, ManifestListsSessions) {
  const fs::path root = ProcessTempDir("tum_synthetic");
  WriteSession(root / "1", MakeFrames(2));
  WriteSession(root / "A", MakeFrames(3));
  WriteManifest(root.string(), {{{"1", "1", "16:46", "mapping"}, {"A", "A", "16:51", "localization"}}, {}});
  std::unique_ptr<DatasetReader> dataset = OpenSyntheticDataset(root.string());
  const std::vector<SessionInfo> sessions = dataset->Sessions();
  ASSERT_EQ(sessions.size(), 2u);
  EXPECT_EQ(sessions[1].name, "A");
  EXPECT_EQ(sessions[1].clock_time.value_or(""), "16:51");
  EXPECT_EQ(sessions[1].num_frames, 3);
  EXPECT_TRUE(sessions[0].has_ground_truth);
  EXPECT_THROW(dataset->OpenSession("Z"), InputError);
}

TEST(SyntheticDataset, SessionFolderOutsideTheDatasetIsRefused) {
  EXPECT_TRUE(IsFolderInsideDataset("1"));
  EXPECT_TRUE(IsFolderInsideDataset("sessions/1"));
  EXPECT_TRUE(IsFolderInsideDataset("./1"));
  EXPECT_FALSE(IsFolderInsideDataset(""));
  EXPECT_FALSE(IsFolderInsideDataset("../x"));
  EXPECT_FALSE(IsFolderInsideDataset("a/../../x"));
  EXPECT_FALSE(IsFolderInsideDataset("/tmp/x"));
  const fs::path root = ProcessTempDir("tum_synthetic_escape");
  WriteSession(root / "outside", MakeFrames(2));
  const fs::path dataset = root / "dataset";
  fs::create_directories(dataset);
  WriteManifest(dataset.string(), {{{"1", "../outside", "16:46", "mapping"}}, {}});
  EXPECT_EQ(ErrorOf([&] { OpenSyntheticDataset(dataset.string()); }),
            (dataset / kManifestFileName).string() +
                ": session '1' folder '../outside' must be a relative path inside the dataset "
                "(no '..', not absolute)");
}

TEST(SyntheticDataset, MissingSessionFolderThrows) {
  const fs::path root = ProcessTempDir("tum_synthetic_missing");
  WriteManifest(root.string(), {{{"1", "1", "16:46", "mapping"}}, {}});
  EXPECT_THROW(OpenSyntheticDataset(root.string()), InputError);
  EXPECT_THROW(OpenSyntheticDataset((root / "nowhere").string()), InputError);
}

TEST(SyntheticDataset, SessionIndexFilesAreReadStrictlyUnlessAllowed) {
  const fs::path root = ProcessTempDir("tum_synthetic_strict");
  WriteSession(root / "1", MakeFrames(3));
  WriteManifest(root.string(), {{{"1", "1", "16:46", "mapping"}}, {}});
  const std::string rgb = (root / "1" / "rgb.txt").string();
  std::vector<std::string> lines = ReadLines(rgb);
  std::swap(lines[2], lines[3]);
  WriteLines(rgb, lines);
  EXPECT_EQ(ErrorOf([&] { OpenSyntheticDataset(root.string()); }),
            rgb + ":4: timestamp 60000.000000 is not after line 3's 60001.000000 (out of order)");
  EXPECT_EQ(OpenSyntheticDataset(root.string(), Lenient())->Sessions()[0].num_frames, 3);
}

TEST(SyntheticDataset, ManifestSymlinkLoopIsAnInputError) {
  const fs::path root = ProcessTempDir("tum_synthetic_loop");
  const std::string manifest = (root / kManifestFileName).string();
  fs::create_symlink(manifest, manifest);
  EXPECT_EQ(ErrorOf([&] { OpenSyntheticDataset(root.string()); }),
            manifest + ": Too many levels of symbolic links");
}

}  // namespace
}  // namespace duskmap
