#include "slam/datasets/rtabmap_images_reader.h"

#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "slam/datasets/rtabmap_db_reader.h"
#include "tests/datasets/dataset_test_util.h"

namespace duskmap {
namespace {

using testing::ErrorOf;
using testing::ReadAllFrames;
using testing::ReadText;
using testing::WriteText;

class RtabmapImagesFixture : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = testing::SharedRtabmapDir();
    if (dir_.empty()) {
      GTEST_SKIP() << "shared RTAB-Map fixtures not found under " << DUSKMAP_SHARED_DIR
                   << "/data/rtabmap; skipping";
    }
    export_dir_ = dir_ + "/rtabmap-export";
  }
  // A writable copy of the export in a fresh temp folder; returns its path.
  std::string CopyExport() {
    const std::string copy = testing::MakeTempDir() + "/export";
    return testing::CopyWritable(export_dir_, copy);
  }
  // The export rearranged as one release session folder (rgb/, depth/, ...).
  std::string MakeReleaseLayout(const std::string& name) {
    const std::string root = testing::MakeTempDir();
    const std::string session = root + "/" + name;
    std::filesystem::create_directories(session);
    for (const char* kind : {"rgb", "depth", "calib"}) {
      testing::CopyWritable(export_dir_ + "/session_small_" + kind, session + "/" + kind);
    }
    testing::CopyWritable(export_dir_ + "/session_small_poses.txt", session + "/device_poses.txt");
    testing::CopyWritable(export_dir_ + "/session_small_camera_poses.txt",
                          session + "/camera_poses.txt");
    return session;
  }
  std::string dir_, export_dir_;
};

TEST_F(RtabmapImagesFixture, ExportAgreesWithTheDatabase) {
  const auto reader = OpenRtabmapImages(export_dir_);
  EXPECT_EQ(reader->format(), "rtabmap-images");
  const std::vector<SessionInfo> sessions = reader->Sessions();
  ASSERT_EQ(sessions.size(), 1u);
  EXPECT_EQ(sessions[0].name, "session_small");
  EXPECT_EQ(sessions[0].num_frames, 10);
  EXPECT_FALSE(sessions[0].has_ground_truth);
  const std::vector<RgbdFrame> images = ReadAllFrames(*reader->OpenSession("session_small"));
  const std::vector<RgbdFrame> nodes = ReadAllFrames(
      *OpenRtabmapDatabase(dir_ + "/rtabmap-db/session_small.db")->OpenSession("session_small"));
  ASSERT_EQ(images.size(), 10u);
  ASSERT_EQ(nodes.size(), 10u);
  for (size_t i = 0; i < images.size(); ++i) {
    SCOPED_TRACE(i);
    const RgbdFrame& a = images[i];
    const RgbdFrame& b = nodes[i];
    EXPECT_NEAR(a.timestamp_s, b.timestamp_s, 1e-6);
    EXPECT_EQ(cv::norm(a.depth_m, b.depth_m, cv::NORM_INF), 0.0);  // bit-exact
    EXPECT_LE(cv::norm(a.bgr, b.bgr, cv::NORM_INF), 50.0);         // one JPEG generation
    EXPECT_EQ(a.camera.width, b.camera.width);
    EXPECT_DOUBLE_EQ(a.camera.fx, b.camera.fx);
    EXPECT_DOUBLE_EQ(a.camera.cx, b.camera.cx);
    EXPECT_LT((a.body_from_camera.translation - b.body_from_camera.translation).norm(), 1e-9);
    EXPECT_LT(RotationAngleRad(a.body_from_camera.rotation, b.body_from_camera.rotation), 1e-9);
    EXPECT_LT((a.odom_from_body.translation - b.odom_from_body.translation).norm(), 2e-6);
    EXPECT_LT(RotationAngleRad(a.odom_from_body.rotation, b.odom_from_body.rotation), 2e-5);
    EXPECT_FALSE(a.world_from_camera.has_value());
  }
}

TEST_F(RtabmapImagesFixture, ReleaseLayoutSessionIsNamedAfterItsFolder) {
  const std::string session = MakeReleaseLayout("1");
  const auto reader = OpenRtabmapImages(session);
  ASSERT_EQ(reader->Sessions().size(), 1u);
  EXPECT_EQ(reader->Sessions()[0].name, "1");
  EXPECT_EQ(ReadAllFrames(*reader->OpenSession("1")).size(), 10u);
  // The parent folder lists its release sessions by folder name.
  std::filesystem::rename(session, std::filesystem::path(session).parent_path() / "A");
  const auto parent = OpenRtabmapImages(std::filesystem::path(session).parent_path().string());
  ASSERT_EQ(parent->Sessions().size(), 1u);
  EXPECT_EQ(parent->Sessions()[0].name, "A");
}

// A folder that turns into a symlink loop after opening is named in a
// one-line InputError by Next(), not std::filesystem's exception text.
TEST_F(RtabmapImagesFixture, SymlinkLoopMetByNextIsAnInputError) {
  const std::string session = MakeReleaseLayout("loop");
  const auto reader = OpenRtabmapImages(session);
  const std::unique_ptr<SessionReader> frames = reader->OpenSession("loop");
  ASSERT_TRUE(frames->Next().has_value());
  const std::string depth = session + "/depth";
  std::filesystem::remove_all(depth);
  std::filesystem::create_directory_symlink(depth, depth);
  EXPECT_EQ(ErrorOf([&] { frames->Next(); }), depth + ": Too many levels of symbolic links");
  // Opening the folder again names the same problem.
  std::filesystem::remove(depth);
  std::filesystem::remove_all(session + "/rgb");
  std::filesystem::create_directory_symlink(session + "/rgb", session + "/rgb");
  EXPECT_EQ(ErrorOf([&] { OpenRtabmapImages(session); }),
            session + "/rgb: Too many levels of symbolic links");
}

TEST_F(RtabmapImagesFixture, OnlyCameraPosesRecoverDevicePoses) {
  const std::string session = MakeReleaseLayout("cam");
  const RgbdFrame with_device = *OpenRtabmapImages(session)->OpenSession("cam")->Next();
  std::filesystem::remove(session + "/device_poses.txt");
  const RgbdFrame from_camera = *OpenRtabmapImages(session)->OpenSession("cam")->Next();
  EXPECT_LT((with_device.odom_from_body.translation - from_camera.odom_from_body.translation).norm(),
            1e-5);
  EXPECT_LT(RotationAngleRad(with_device.odom_from_body.rotation, from_camera.odom_from_body.rotation),
            1e-5);
}

TEST_F(RtabmapImagesFixture, LowResolutionDepthIsRegisteredByNearestNeighbour) {
  const std::string session = MakeReleaseLayout("lowres");
  const std::string depth_path = session + "/depth/1700000000.300000.png";
  const cv::Mat full = cv::imread(depth_path, cv::IMREAD_UNCHANGED);
  cv::Mat half;
  cv::resize(full, half, cv::Size(160, 120), 0, 0, cv::INTER_NEAREST);
  cv::imwrite(depth_path, half);
  const std::vector<RgbdFrame> frames = ReadAllFrames(*OpenRtabmapImages(session)->OpenSession("lowres"));
  const RgbdFrame& frame = frames[3];
  ASSERT_EQ(frame.depth_m.size(), frame.bgr.size());
  cv::Mat expected_mm;
  cv::resize(half, expected_mm, cv::Size(320, 240), 0, 0, cv::INTER_NEAREST);
  cv::Mat ours_mm;
  frame.depth_m.convertTo(ours_mm, CV_16UC1, 1000.0);
  EXPECT_EQ(cv::norm(ours_mm, expected_mm, cv::NORM_INF), 0.0);
  EXPECT_DOUBLE_EQ(frame.camera.fx, 262.5);  // intrinsics stay those of the colour image
}

TEST_F(RtabmapImagesFixture, CalibrationForAnotherResolutionIsScaledOrRejected) {
  const std::string session = MakeReleaseLayout("calib");
  const std::string yaml_path = session + "/calib/1700000000.200000.yaml";
  std::string yaml = ReadText(yaml_path);
  // Calibrated at 640x480 (double the image): intrinsics are scaled by 0.5.
  std::string doubled = yaml;
  doubled.replace(doubled.find("image_width: 320"), 16, "image_width: 640");
  doubled.replace(doubled.find("image_height: 240"), 17, "image_height: 480");
  doubled.replace(doubled.find("2.6250000000000000e+02"), 22, "5.2500000000000000e+02");
  doubled.replace(doubled.find("2.6250000000000000e+02"), 22, "5.2500000000000000e+02");
  WriteText(yaml_path, doubled);
  const std::vector<RgbdFrame> frames = ReadAllFrames(*OpenRtabmapImages(session)->OpenSession("calib"));
  EXPECT_DOUBLE_EQ(frames[2].camera.fx, 262.5);
  EXPECT_EQ(frames[2].camera.width, 320);
  // A different aspect ratio is an error naming the image.
  std::string wrong = yaml;
  wrong.replace(wrong.find("image_height: 240"), 17, "image_height: 100");
  WriteText(yaml_path, wrong);
  const auto reader = OpenRtabmapImages(session);
  EXPECT_EQ(ErrorOf([&] { ReadAllFrames(*reader->OpenSession("calib")); }),
            session + "/rgb/1700000000.200000.jpg: calibration is for 320x100 but the image is 320x240");
}

TEST_F(RtabmapImagesFixture, BadPoseLinesNameFileAndLine) {
  const std::string session = MakeReleaseLayout("poses");
  const std::string poses_path = session + "/device_poses.txt";
  std::string poses = ReadText(poses_path);
  const std::string original = poses;
  poses.replace(poses.find("-0.143086"), 9, "nan");
  WriteText(poses_path, poses);
  EXPECT_EQ(ErrorOf([&] { OpenRtabmapImages(session); }),
            poses_path + ":3: non-finite value 'nan'");
  // With skipping: the bad line is logged, its image has no pose and is skipped too.
  DatasetReadOptions options;
  options.skip_bad_frames = true;
  options.skip_log = std::make_shared<SkipLog>();
  const auto reader = OpenRtabmapImages(session, options);
  EXPECT_EQ(reader->Sessions()[0].num_frames, 9);
  EXPECT_EQ(options.skip_log->count(), 2);
  // Timestamps going backwards.
  poses = original;
  poses.replace(poses.find("1700000000.500000"), 17, "1700000000.050000");
  WriteText(poses_path, poses);
  EXPECT_EQ(ErrorOf([&] { OpenRtabmapImages(session); }),
            poses_path + ":7: timestamp 1700000000.050000 is not after the previous one "
                         "(1700000000.400000)");
  // Camera poses that disagree with device pose x local_transform.
  WriteText(poses_path, original);
  std::string camera = ReadText(session + "/camera_poses.txt");
  camera.replace(camera.find("\n1700000000.100000 ") + 19, 1, "9");
  WriteText(session + "/camera_poses.txt", camera);
  EXPECT_NE(ErrorOf([&] { OpenRtabmapImages(session); })
                .find(session + "/camera_poses.txt:3: camera pose disagrees with"),
            std::string::npos);
}

TEST_F(RtabmapImagesFixture, UnreadableImagesNameTheirFile) {
  const std::string session = MakeReleaseLayout("images");
  const std::string jpg = session + "/rgb/1700000000.600000.jpg";
  const std::string bytes = ReadText(jpg);
  WriteText(jpg, bytes.substr(0, bytes.size() / 2));
  const auto reader = OpenRtabmapImages(session);
  EXPECT_EQ(ErrorOf([&] { ReadAllFrames(*reader->OpenSession("images")); }),
            jpg + ": JPEG is truncated (no end-of-image marker)");
  const std::string png = session + "/depth/1700000000.600000.png";
  WriteText(jpg, bytes);
  cv::imwrite(png, cv::Mat(240, 320, CV_8UC3, cv::Scalar(1, 2, 3)));
  EXPECT_NE(ErrorOf([&] { ReadAllFrames(*reader->OpenSession("images")); })
                .find(png + ": depth of unexpected type: PNG with 3 channel(s)"),
            std::string::npos);
  std::filesystem::remove(png);
  EXPECT_EQ(ErrorOf([&] { ReadAllFrames(*reader->OpenSession("images")); }), png + ": cannot open");
  // An image without a pose line.
  WriteText(session + "/rgb/1800000000.000000.jpg", bytes);
  EXPECT_EQ(ErrorOf([&] { OpenRtabmapImages(session); }),
            session + "/rgb/1800000000.000000.jpg: no pose line for this image in " + session +
                "/device_poses.txt");
}

TEST_F(RtabmapImagesFixture, FolderWithoutSessionsOrCalibration) {
  const std::string empty = testing::MakeTempDir();
  EXPECT_EQ(ErrorOf([&] { OpenRtabmapImages(empty); }),
            empty + ": no RTAB-Map image session (rgb/ or <prefix>_rgb/ folder)");
  const std::string session = MakeReleaseLayout("nocalib");
  std::filesystem::remove_all(session + "/calib");
  EXPECT_EQ(ErrorOf([&] { OpenRtabmapImages(session); }),
            session + "/calib: calibration folder not found");
}

}  // namespace
}  // namespace duskmap
