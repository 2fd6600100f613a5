#include "slam/datasets/dataset_factory.h"

#include <gtest/gtest.h>

#include "slam/io/synthetic_dataset.h"
#include "slam/io/tum_writer.h"
#include "tests/datasets/dataset_test_util.h"

namespace duskmap {
namespace {

using testing::ErrorOf;
namespace fs = std::filesystem;

TEST(DatasetFormats, ListsTheFourFormats) {
  EXPECT_EQ(DatasetFormats(),
            (std::vector<std::string>{"synthetic", "tum", "rtabmap-images", "rtabmap-db"}));
}

TEST(DetectDatasetFormat, RecognisesFolderContents) {
  const std::string root = testing::MakeTempDir();
  // TUM and duskmap's synthetic sessions have rgb/ folders like an image
  // release; their index files decide.
  fs::create_directories(root + "/tum/rgb");
  testing::WriteText(root + "/tum/rgb.txt", "");
  testing::WriteText(root + "/tum/depth.txt", "");
  EXPECT_EQ(DetectDatasetFormat(root + "/tum"), "tum");
  fs::create_directories(root + "/synthetic/1/rgb");
  testing::WriteText(root + "/synthetic/manifest.json", "{}");
  EXPECT_EQ(DetectDatasetFormat(root + "/synthetic"), "synthetic");
  fs::create_directories(root + "/release/rgb");
  EXPECT_EQ(DetectDatasetFormat(root + "/release"), "rtabmap-images");
  fs::create_directories(root + "/export/x_rgb");
  EXPECT_EQ(DetectDatasetFormat(root + "/export"), "rtabmap-images");
  fs::create_directories(root + "/dbs");
  testing::WriteText(root + "/dbs/a.db", "");
  EXPECT_EQ(DetectDatasetFormat(root + "/dbs"), "rtabmap-db");
  EXPECT_EQ(DetectDatasetFormat(root + "/dbs/a.db"), "rtabmap-db");
}

TEST(DetectDatasetFormat, AmbiguousOrUnknownContentsAreErrors) {
  const std::string root = testing::MakeTempDir();
  fs::create_directories(root + "/both/rgb");
  testing::WriteText(root + "/both/a.db", "");
  EXPECT_EQ(ErrorOf([&] { DetectDatasetFormat(root + "/both"); }),
            root + "/both: ambiguous dataset format (rtabmap-images, rtabmap-db); pass "
                   "--dataset-format");
  fs::create_directories(root + "/nothing");
  EXPECT_NE(ErrorOf([&] { DetectDatasetFormat(root + "/nothing"); })
                .find("cannot detect the dataset format"),
            std::string::npos);
  EXPECT_EQ(ErrorOf([&] { DetectDatasetFormat(root + "/missing"); }),
            root + "/missing: no such file or folder");
}

TEST(OpenDataset, RejectsUnknownFormatNames) {
  EXPECT_THROW(OpenDataset("/tmp", "colmap"), ConfigError);
  EXPECT_EQ(ErrorOf([] { OpenDataset("/tmp", "colmap"); }),
            "dataset format 'colmap' is unknown (expected auto, synthetic, tum, rtabmap-images, "
            "rtabmap-db)");
}

TEST(OpenDataset, DispatchesToTheDetectedReader) {
  SKIP_WITHOUT_SHARED_RTABMAP(dir);
  EXPECT_EQ(OpenDataset(dir + "/rtabmap-db/session_small.db")->format(), "rtabmap-db");
  EXPECT_EQ(OpenDataset(dir + "/rtabmap-export")->format(), "rtabmap-images");
  EXPECT_EQ(OpenDataset(dir + "/rtabmap-export", "rtabmap-images")->format(), "rtabmap-images");
  // Forcing the wrong format fails with the reader's own error.
  EXPECT_NE(ErrorOf([&] { OpenDataset(dir + "/rtabmap-export", "rtabmap-db"); }).find("no .db file"),
            std::string::npos);
}

TEST(OpenDataset, SkipBadFramesSkipsFramesThatFailToDecodeAndCountsThem) {
  SKIP_WITHOUT_SHARED_RTABMAP(dir);
  const std::string db = testing::MakeTempDir() + "/s.db";
  testing::CopyWritable(dir + "/rtabmap-db/session_small.db", db);
  testing::ExecSql(db, "UPDATE Data SET image = substr(image, 1, 500) WHERE id IN (2, 9)");
  EXPECT_NE(ErrorOf([&] { testing::ReadAllFrames(*OpenDataset(db)->OpenSession("s")); })
                .find("node 2: image: JPEG is truncated"),
            std::string::npos);
  DatasetReadOptions options;
  options.skip_bad_frames = true;
  options.skip_log = std::make_shared<SkipLog>();
  const auto reader = OpenDataset(db, "auto", options);
  const auto session = reader->OpenSession("s");
  EXPECT_EQ(testing::ReadAllFrames(*session).size(), 8u);
  EXPECT_EQ(options.skip_log->count(), 2);
  // A second pass does not count the same frames twice.
  session->Rewind();
  EXPECT_EQ(testing::ReadAllFrames(*session).size(), 8u);
  EXPECT_EQ(options.skip_log->count(), 2);
  EXPECT_EQ(options.skip_log->messages()[0],
            db + ": node 2: image: JPEG is truncated (no end-of-image marker)");
}

// A TUM-layout folder of `count` tiny frames at 100, 101, ... s whose rgb.txt
// lists the first two frames in reverse order (lines 3 and 4).
std::string WriteUnorderedTumFolder(const std::string& folder, int count) {
  TumCalibration calibration;
  calibration.camera.width = 8;
  calibration.camera.height = 6;
  calibration.camera.fx = calibration.camera.fy = 8.0;
  calibration.camera.cx = 3.5;
  calibration.camera.cy = 2.5;
  calibration.depth_scale = 1000.0;
  TumSessionWriter writer(folder, calibration);
  for (int i = 0; i < count; ++i) {
    RgbdFrame frame;
    frame.timestamp_s = 100.0 + i;
    frame.bgr = cv::Mat(6, 8, CV_8UC3, cv::Scalar(i, 2, 3));
    frame.depth_m = cv::Mat(6, 8, CV_32FC1, cv::Scalar(1.5f));
    writer.Write(frame);
  }
  writer.Finish();
  std::vector<std::string> lines;
  {
    std::ifstream in(folder + "/rgb.txt");
    for (std::string line; std::getline(in, line);) lines.push_back(line);
  }
  std::swap(lines[2], lines[3]);
  std::ofstream out(folder + "/rgb.txt");
  for (const std::string& line : lines) out << line << "\n";
  return folder;
}

TEST(OpenDataset, AllowUnorderedReachesTheTumReader) {
  const std::string tum = WriteUnorderedTumFolder(testing::MakeTempDir() + "/seq", 3);
  EXPECT_THROW(OpenDataset(tum), InputError);
  EXPECT_EQ(ErrorOf([&] { OpenDataset(tum, "tum"); }),
            tum + "/rgb.txt:4: timestamp 100.000000 is not after line 3's 101.000000 (out of "
                  "order); --allow-unordered reads it as recorded");
  DatasetReadOptions options;
  options.allow_unordered = true;
  const auto reader = OpenDataset(tum, "auto", options);
  EXPECT_EQ(reader->format(), "tum");
  const auto frames = testing::ReadAllFrames(*reader->OpenSession("seq"));
  ASSERT_EQ(frames.size(), 3u);
  EXPECT_DOUBLE_EQ(frames[0].timestamp_s, 100.0);
  EXPECT_DOUBLE_EQ(frames[1].timestamp_s, 101.0);
}

TEST(OpenDataset, AllowUnorderedReachesTheSyntheticReader) {
  const std::string root = testing::MakeTempDir();
  WriteUnorderedTumFolder(root + "/1", 2);
  WriteManifest(root, {{{"1", "1", "16:46", "mapping"}}, {}});
  EXPECT_THROW(OpenDataset(root), InputError);
  EXPECT_EQ(ErrorOf([&] { OpenDataset(root, "synthetic"); }),
            root + "/1/rgb.txt:4: timestamp 100.000000 is not after line 3's 101.000000 (out of "
                   "order); --allow-unordered reads it as recorded");
  DatasetReadOptions options;
  options.allow_unordered = true;
  EXPECT_EQ(OpenDataset(root, "auto", options)->Sessions()[0].num_frames, 2);
  // With skipping too (the wrapper keeps the lenient reading).
  options.skip_bad_frames = true;
  options.skip_log = std::make_shared<SkipLog>();
  EXPECT_EQ(OpenDataset(root, "synthetic", options)->Sessions()[0].num_frames, 2);
}

TEST(DetectDatasetFormat, SymlinkLoopsAreInputErrorsNamingThePath) {
  const std::string root = testing::MakeTempDir();
  const std::string loop_problem = ": Too many levels of symbolic links";
  // The dataset path itself.
  fs::create_symlink(root + "/loop", root + "/loop");
  EXPECT_THROW(DetectDatasetFormat(root + "/loop"), InputError);
  EXPECT_EQ(ErrorOf([&] { DetectDatasetFormat(root + "/loop"); }), root + "/loop" + loop_problem);
  EXPECT_THROW(OpenDataset(root + "/loop"), InputError);
  // An index file that decides the format.
  fs::create_directories(root + "/tum");
  testing::WriteText(root + "/tum/rgb.txt", "");
  fs::create_symlink(root + "/tum/depth.txt", root + "/tum/depth.txt");
  EXPECT_EQ(ErrorOf([&] { DetectDatasetFormat(root + "/tum"); }),
            root + "/tum/depth.txt" + loop_problem);
  // A .db file in a folder of databases.
  fs::create_directories(root + "/dbs");
  fs::create_symlink(root + "/dbs/a.db", root + "/dbs/a.db");
  EXPECT_EQ(ErrorOf([&] { DetectDatasetFormat(root + "/dbs"); }),
            root + "/dbs/a.db" + loop_problem);
  // An entry met while looking for image sessions (<prefix>_rgb/ folders).
  fs::create_directories(root + "/export");
  fs::create_symlink(root + "/export/x", root + "/export/x");
  EXPECT_THROW(DetectDatasetFormat(root + "/export"), InputError);
  EXPECT_EQ(ErrorOf([&] { DetectDatasetFormat(root + "/export"); }),
            root + "/export/x" + loop_problem);
}

TEST(OpenDataset, SymlinkLoopInsideATumFolderIsAnInputError) {
  const std::string tum = testing::MakeTempDir() + "/seq";
  WriteUnorderedTumFolder(tum, 2);
  fs::remove(tum + "/odometry.txt");
  fs::create_symlink(tum + "/odometry.txt", tum + "/odometry.txt");
  DatasetReadOptions options;
  options.allow_unordered = true;
  EXPECT_THROW(OpenDataset(tum, "tum", options), InputError);
  EXPECT_EQ(ErrorOf([&] { OpenDataset(tum, "auto", options); }),
            tum + "/odometry.txt: Too many levels of symbolic links");
}

}  // namespace
}  // namespace duskmap
