#include "slam/datasets/dataset_factory.h"

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace duskmap
