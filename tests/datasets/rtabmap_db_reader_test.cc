#include "slam/datasets/rtabmap_db_reader.h"

#include <gtest/gtest.h>

#include <cstring>
#include <limits>

#include <opencv2/imgcodecs.hpp>

#include "slam/datasets/poses_file.h"
#include "tests/datasets/dataset_test_util.h"

namespace duskmap {
namespace {

using testing::ErrorOf;
using testing::ExecSql;
using testing::ReadAllFrames;

constexpr double kPoseFileRoundingM = 2e-6;
constexpr double kPoseFileRoundingRad = 2e-5;

TEST(ParseRtabmapVersion, ParsesThreeComponents) {
  EXPECT_EQ(ParseRtabmapVersion("0.23.8"), (RtabmapVersion{0, 23, 8}));
  EXPECT_FALSE(ParseRtabmapVersion("0.23").has_value());
  EXPECT_FALSE(ParseRtabmapVersion("0.23.8.1").has_value());
  EXPECT_FALSE(ParseRtabmapVersion("0.x.8").has_value());
  EXPECT_TRUE(RtabmapVersion({0, 10, 0}) > RtabmapVersion({0, 9, 1}));
}

class RtabmapDbFixture : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = testing::SharedRtabmapDir();
    if (dir_.empty()) {
      GTEST_SKIP() << "shared RTAB-Map fixtures not found under " << DUSKMAP_SHARED_DIR
                   << "/data/rtabmap; skipping";
    }
    db_ = dir_ + "/rtabmap-db/session_small.db";
    export_ = dir_ + "/rtabmap-export/session_small";
  }
  // A writable copy of session_small.db in a fresh temp folder.
  std::string CopyDb() {
    const std::string copy = testing::MakeTempDir() + "/session_small.db";
    testing::CopyWritable(db_, copy);
    return copy;
  }
  std::string dir_, db_, export_;
};

TEST_F(RtabmapDbFixture, SessionSmallMatchesTheExport) {
  const auto reader = OpenRtabmapDatabase(db_);
  EXPECT_EQ(reader->format(), "rtabmap-db");
  const std::vector<SessionInfo> sessions = reader->Sessions();
  ASSERT_EQ(sessions.size(), 1u);
  EXPECT_EQ(sessions[0].name, "session_small");
  EXPECT_EQ(sessions[0].num_frames, 10);
  EXPECT_TRUE(sessions[0].has_ground_truth);
  EXPECT_FALSE(sessions[0].clock_time.has_value());
  const auto session = reader->OpenSession("session_small");
  const std::vector<RgbdFrame> frames = ReadAllFrames(*session);
  ASSERT_EQ(frames.size(), 10u);
  const PosesFile poses = ReadPosesFile(export_ + "_poses.txt");
  const PosesFile camera_poses = ReadPosesFile(export_ + "_camera_poses.txt");
  ASSERT_EQ(poses.poses.size(), 10u);
  for (size_t i = 0; i < frames.size(); ++i) {
    const RgbdFrame& f = frames[i];
    const std::string stem = poses.poses[i].stamp_text;
    SCOPED_TRACE(stem);
    EXPECT_EQ(f.frame_index, static_cast<int64_t>(i));
    EXPECT_NEAR(f.timestamp_s, poses.poses[i].stamp_s, 1e-6);
    // Depth: bit-exact against the exported 16-bit PNG.
    const cv::Mat depth_mm =
        cv::imread(export_ + "_depth/" + stem + ".png", cv::IMREAD_UNCHANGED);
    ASSERT_EQ(depth_mm.type(), CV_16UC1);
    ASSERT_EQ(f.depth_m.type(), CV_32FC1);
    cv::Mat ours_mm;
    f.depth_m.convertTo(ours_mm, CV_16UC1, 1000.0);
    EXPECT_EQ(cv::norm(ours_mm, depth_mm, cv::NORM_INF), 0.0);
    // Colour: the export is our decode re-encoded at quality 95 (one JPEG
    // generation apart); pixels agree within JPEG loss.
    const cv::Mat exported = cv::imread(export_ + "_rgb/" + stem + ".jpg", cv::IMREAD_COLOR);
    ASSERT_EQ(f.bgr.type(), CV_8UC3);
    ASSERT_EQ(f.bgr.size(), exported.size());
    EXPECT_LE(cv::norm(f.bgr, exported, cv::NORM_INF), 50.0);
    EXPECT_LT(cv::norm(f.bgr, exported, cv::NORM_L1) / (f.bgr.total() * 3), 3.0);
    // Calibration.
    EXPECT_EQ(f.camera.width, 320);
    EXPECT_EQ(f.camera.height, 240);
    EXPECT_DOUBLE_EQ(f.camera.fx, 262.5);
    EXPECT_DOUBLE_EQ(f.camera.cy, 119.5);
    // Poses: odometry and camera poses against the export (6 decimals).
    const Rigid3d& expected = poses.poses[i].map_from_frame;
    EXPECT_LT((f.odom_from_body.translation - expected.translation).norm(), kPoseFileRoundingM);
    EXPECT_LT(RotationAngleRad(f.odom_from_body.rotation, expected.rotation), kPoseFileRoundingRad);
    const Rigid3d camera = f.odom_from_camera();
    EXPECT_LT((camera.translation - camera_poses.poses[i].map_from_frame.translation).norm(),
              kPoseFileRoundingM);
    EXPECT_LT(RotationAngleRad(camera.rotation, camera_poses.poses[i].map_from_frame.rotation),
              kPoseFileRoundingRad);
    ASSERT_TRUE(f.world_from_camera.has_value());
    EXPECT_TRUE(f.world_from_camera->IsFinite());
  }
  // Rewind restarts at the first frame.
  session->Rewind();
  EXPECT_EQ(session->Next()->frame_index, 0);
}

TEST_F(RtabmapDbFixture, ColourIsTheDatabaseJpegBeforeReencoding) {
  // Re-encoding our decode at OpenCV's default quality (95) reproduces the
  // export's JPEG exactly when the libjpeg build matches RTAB-Map's; in any
  // case the decoded re-encode must be close to the export's pixels.
  const auto session = OpenRtabmapDatabase(db_)->OpenSession("session_small");
  const RgbdFrame frame = *session->Next();
  std::vector<uint8_t> reencoded;
  cv::imencode(".jpg", frame.bgr, reencoded);
  const cv::Mat round_trip = cv::imdecode(reencoded, cv::IMREAD_COLOR);
  const cv::Mat exported =
      cv::imread(export_ + "_rgb/1700000000.000000.jpg", cv::IMREAD_COLOR);
  EXPECT_LE(cv::norm(round_trip, exported, cv::NORM_INF), 2.0);
}

TEST_F(RtabmapDbFixture, MergedDatabaseGivesOneSessionPerMapId) {
  const auto reader = OpenRtabmapDatabase(dir_ + "/rtabmap-db/merged_two_sessions.db");
  const std::vector<SessionInfo> sessions = reader->Sessions();
  ASSERT_EQ(sessions.size(), 2u);
  EXPECT_EQ(sessions[0].name, "merged_two_sessions.map0");
  EXPECT_EQ(sessions[1].name, "merged_two_sessions.map1");
  EXPECT_EQ(sessions[0].num_frames, 10);
  EXPECT_EQ(sessions[1].num_frames, 10);
  const RgbdFrame first0 = *reader->OpenSession("merged_two_sessions.map0")->Next();
  const RgbdFrame first1 = *reader->OpenSession("merged_two_sessions.map1")->Next();
  // Each session keeps its own odometry frame: node 11's pose equals node 1's.
  EXPECT_LT((first0.odom_from_body.translation - first1.odom_from_body.translation).norm(), 1e-9);
  // Session 1's depth is byte-identical to session_small's (RVL is lossless).
  const RgbdFrame small = *OpenRtabmapDatabase(db_)->OpenSession("session_small")->Next();
  EXPECT_EQ(cv::norm(first0.depth_m, small.depth_m, cv::NORM_INF), 0.0);
  EXPECT_NE(ErrorOf([&] { reader->OpenSession("map7"); }).find("no session named 'map7'"),
            std::string::npos);
}

TEST_F(RtabmapDbFixture, FolderOfDatabasesListsAllSessions) {
  const auto reader = OpenRtabmapDatabase(dir_ + "/rtabmap-db");
  const std::vector<SessionInfo> sessions = reader->Sessions();
  ASSERT_EQ(sessions.size(), 3u);
  EXPECT_EQ(sessions[2].name, "session_small");
}

TEST_F(RtabmapDbFixture, UnknownSchemaVersion) {
  const std::string db = CopyDb();
  for (const std::string version : {"0.17.6", "1.0.0", "banana"}) {
    ExecSql(db, "UPDATE Admin SET version = '" + version + "'");
    EXPECT_EQ(ErrorOf([&] { OpenRtabmapDatabase(db); }),
              db + ": unknown schema version '" + version + "' (supported: 0.18.0 to 0.23.x)");
  }
}

TEST_F(RtabmapDbFixture, MissingTableOrColumn) {
  const std::string db = CopyDb();
  ExecSql(db, "DROP TABLE Data");
  EXPECT_EQ(ErrorOf([&] { OpenRtabmapDatabase(db); }), db + ": missing table Data");
  ExecSql(db, "DROP TABLE Admin");
  EXPECT_EQ(ErrorOf([&] { OpenRtabmapDatabase(db); }),
            db + ": missing table Admin (not an RTAB-Map database?)");
  const std::string not_db = testing::MakeTempDir() + "/junk.db";
  testing::WriteText(not_db, std::string(5000, 'x'));
  EXPECT_NE(ErrorOf([&] { OpenRtabmapDatabase(not_db); }).find("file is not a database"),
            std::string::npos);
}

// Reads every frame with skip_bad_frames and returns the skip log.
std::shared_ptr<SkipLog> ReadSkipping(const std::string& db, size_t expected_frames) {
  DatasetReadOptions options;
  options.skip_bad_frames = true;
  options.skip_log = std::make_shared<SkipLog>();
  const auto reader = OpenRtabmapDatabase(db, options);
  size_t frames = 0;
  for (const SessionInfo& info : reader->Sessions()) {
    const auto session = reader->OpenSession(info.name);
    while (true) {
      try {
        if (!session->Next()) break;
        ++frames;
      } catch (const InputError& e) {
        options.skip_log->Add(e.what());
      }
    }
  }
  EXPECT_EQ(frames, expected_frames);
  return options.skip_log;
}

// Reads every frame without skipping; returns the first error.
std::string FirstReadError(const std::string& db) {
  return ErrorOf([&] {
    const auto reader = OpenRtabmapDatabase(db);
    const auto session = reader->OpenSession(reader->Sessions().front().name);
    ReadAllFrames(*session);
  });
}

TEST_F(RtabmapDbFixture, TruncatedImageBlob) {
  const std::string db = CopyDb();
  ExecSql(db, "UPDATE Data SET image = substr(image, 1, 2000) WHERE id = 3");
  EXPECT_EQ(FirstReadError(db), db + ": node 3: image: JPEG is truncated (no end-of-image marker)");
  const auto log = ReadSkipping(db, 9);
  EXPECT_EQ(log->count(), 1);
}

TEST_F(RtabmapDbFixture, TruncatedDepthAndPoseBlobs) {
  const std::string db = CopyDb();
  ExecSql(db, "UPDATE Data SET depth = substr(depth, 1, 1000) WHERE id = 4");
  EXPECT_EQ(FirstReadError(db), db + ": node 4: depth: RVL payload is truncated");
  ExecSql(db, "UPDATE Node SET pose = substr(pose, 1, 40) WHERE id = 6");
  EXPECT_EQ(FirstReadError(db), db + ": node 6: pose: transform blob has 40 bytes, expected 48");
  const auto log = ReadSkipping(db, 8);
  EXPECT_EQ(log->count(), 2);
}

TEST_F(RtabmapDbFixture, UndecodableImageAndDepthOfUnexpectedType) {
  const std::string db = CopyDb();
  std::vector<uint8_t> garbage = {0xFF, 0xD8, 0xFF, 0xE0};
  for (int i = 0; i < 300; ++i) garbage.push_back(static_cast<uint8_t>(i * 7));
  garbage.push_back(0xFF);
  garbage.push_back(0xD9);
  testing::SetBlob(db, "Data", "image", 2, garbage);
  EXPECT_EQ(FirstReadError(db), db + ": node 2: image: JPEG image does not decode");
  const std::string db2 = CopyDb();
  ExecSql(db2, "UPDATE Data SET depth = (SELECT image FROM Data WHERE id = 1) WHERE id = 5");
  EXPECT_EQ(FirstReadError(db2),
            db2 + ": node 5: depth: depth of unexpected type: JPEG (expected RVL or PNG)");
  // An 8-bit one-channel PNG is not depth either.
  std::vector<uint8_t> png;
  cv::imencode(".png", cv::Mat(240, 320, CV_8UC1, cv::Scalar(9)), png);
  testing::SetBlob(db2, "Data", "depth", 5, png);
  EXPECT_NE(FirstReadError(db2).find("node 5: depth: depth of unexpected type: PNG with 1 channel"),
            std::string::npos);
}

TEST_F(RtabmapDbFixture, NonFinitePoseAndBackwardsTimestamps) {
  const std::string db = CopyDb();
  std::vector<uint8_t> pose = testing::GetBlob(db, "SELECT pose FROM Node WHERE id = 4");
  const float nan = std::numeric_limits<float>::quiet_NaN();
  std::memcpy(pose.data() + 12, &nan, sizeof(float));
  testing::SetBlob(db, "Node", "pose", 4, pose);
  EXPECT_EQ(ErrorOf([&] { OpenRtabmapDatabase(db); }),
            db + ": node 4: pose: transform has non-finite values");
  const std::string db2 = CopyDb();
  ExecSql(db2, "UPDATE Node SET stamp = 1699999999.0 WHERE id = 7");
  EXPECT_EQ(ErrorOf([&] { OpenRtabmapDatabase(db2); }),
            db2 + ": node 7: timestamp 1699999999 s is not after node 6's 1700000000.5 s");
  const auto log = ReadSkipping(db2, 9);
  ASSERT_EQ(log->count(), 1);
  EXPECT_NE(log->messages()[0].find("node 7"), std::string::npos);
}

TEST_F(RtabmapDbFixture, CalibrationNotMatchingImageSize) {
  const std::string db = CopyDb();
  std::vector<uint8_t> calibration =
      testing::GetBlob(db, "SELECT calibration FROM Data WHERE id = 8");
  const int32_t width = 300;
  std::memcpy(calibration.data() + 16, &width, sizeof(width));
  testing::SetBlob(db, "Data", "calibration", 8, calibration);
  EXPECT_EQ(FirstReadError(db), db + ": node 8: calibration is for 300x240 but the image is 320x240");
  calibration.resize(100);
  testing::SetBlob(db, "Data", "calibration", 8, calibration);
  EXPECT_EQ(FirstReadError(db),
            db + ": node 8: calibration: calibration blob is truncated (100 of 164 bytes)");
}

TEST_F(RtabmapDbFixture, SkipOptionRequiresALog) {
  DatasetReadOptions options;
  options.skip_bad_frames = true;
  EXPECT_THROW(OpenRtabmapDatabase(db_, options), ConfigError);
}

}  // namespace
}  // namespace duskmap
