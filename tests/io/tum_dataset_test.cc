#include "slam/io/tum_dataset.h"

#include <unistd.h>

#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "slam/core/check.h"
#include "slam/io/synthetic_dataset.h"
#include "slam/io/tum_writer.h"

namespace duskmap {
namespace {
namespace fs = std::filesystem;

fs::path TempRoot(const std::string& name) {
  const fs::path root = fs::temp_directory_path() / ("duskmap_tum_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(root);
  fs::create_directories(root);
  return root;
}

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

TEST(TumDataset, WriteReadRoundTrip) {
  const std::vector<RgbdFrame> frames = MakeFrames(4);
  const std::string path = WriteSession(TempRoot("round") / "seq", frames);
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
  const std::string path = WriteSession(TempRoot("missing") / "seq", MakeFrames(3));
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
  const std::string path = WriteSession(TempRoot("truncated") / "seq", MakeFrames(3));
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
  const std::string path = WriteSession(TempRoot("index") / "seq", MakeFrames(2));
  std::ofstream(path + "/rgb.txt", std::ios::app) << "60005.0\n";
  EXPECT_THROW(OpenTumDataset(path), InputError);
}

TEST(TumDataset, RealTumFolderUsesPublishedIntrinsicsAndAssociates) {
  const fs::path folder = TempRoot("fr1") / "rgbd_dataset_freiburg1_xyz";
  fs::create_directories(folder / "rgb");
  fs::create_directories(folder / "depth");
  cv::imwrite((folder / "rgb/1.000000.png").string(), cv::Mat(480, 640, CV_8UC3, cv::Scalar(1, 2, 3)));
  cv::imwrite((folder / "depth/1.010000.png").string(), cv::Mat(480, 640, CV_16UC1, cv::Scalar(5000)));
  cv::imwrite((folder / "rgb/2.000000.png").string(), cv::Mat(480, 640, CV_8UC3, cv::Scalar(1, 2, 3)));
  std::ofstream(folder / "rgb.txt") << "# color\n1.000000 rgb/1.000000.png\n2.000000 rgb/2.000000.png\n";
  std::ofstream(folder / "depth.txt") << "1.010000 depth/1.010000.png\n";
  std::ofstream(folder / "groundtruth.txt") << "0.99 1 2 3 0 0 0 1\n1.02 1 2 3 0 0 0 1\n";
  std::unique_ptr<DatasetReader> dataset = OpenTumDataset(folder.string());
  EXPECT_EQ(dataset->Sessions()[0].num_frames, 1);  // rgb 2.0 has no depth within 0.02 s
  const std::optional<RgbdFrame> f = dataset->OpenSession("rgbd_dataset_freiburg1_xyz")->Next();
  ASSERT_TRUE(f.has_value());
  EXPECT_DOUBLE_EQ(f->camera.fx, 517.3);
  EXPECT_FLOAT_EQ(f->depth_m.at<float>(10, 10), 1.0f);  // 5000 units per metre
  ASSERT_TRUE(f->world_from_camera.has_value());
  EXPECT_NEAR(f->world_from_camera->translation.y(), 2.0, 1e-9);
}

TEST(SyntheticDataset, ManifestListsSessions) {
  const fs::path root = TempRoot("synthetic");
  WriteSession(root / "1", MakeFrames(2));
  WriteSession(root / "A", MakeFrames(3));
  WriteManifest(root.string(), {{{"1", "1", "16:46", "mapping"}, {"A", "A", "16:51", "localization"}}});
  std::unique_ptr<DatasetReader> dataset = OpenSyntheticDataset(root.string());
  const std::vector<SessionInfo> sessions = dataset->Sessions();
  ASSERT_EQ(sessions.size(), 2u);
  EXPECT_EQ(sessions[1].name, "A");
  EXPECT_EQ(sessions[1].clock_time.value_or(""), "16:51");
  EXPECT_EQ(sessions[1].num_frames, 3);
  EXPECT_TRUE(sessions[0].has_ground_truth);
  EXPECT_THROW(dataset->OpenSession("Z"), InputError);
}

TEST(SyntheticDataset, MissingSessionFolderThrows) {
  const fs::path root = TempRoot("synthetic_missing");
  WriteManifest(root.string(), {{{"1", "1", "16:46", "mapping"}}});
  EXPECT_THROW(OpenSyntheticDataset(root.string()), InputError);
  EXPECT_THROW(OpenSyntheticDataset((root / "nowhere").string()), InputError);
}

}  // namespace
}  // namespace duskmap
