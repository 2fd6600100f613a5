#include "slam/experiment/feature_cache.h"

#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>
#include <unistd.h>

#include "slam/core/check.h"
#include "tests/testing/temp_dir.h"

namespace duskmap {
namespace {

SessionInfo NamedSession(const std::string& name) {
  SessionInfo session;
  session.name = name;
  return session;
}

namespace fs = std::filesystem;

class FeatureCacheTest : public ::testing::Test {
 protected:
  void SetUp() override {
    path_ = testing::ProcessTempPath("feature_cache.bin");
  }
  void TearDown() override { fs::remove(path_); }

  static RgbdFrame Frame(int64_t index, bool with_truth) {
    RgbdFrame frame;
    frame.frame_index = index;
    frame.timestamp_s = 100.0 + index;
    frame.camera = PinholeCamera{640, 480, 525.0, 526.0, 319.5, 239.5};
    frame.body_from_camera = Rigid3d(Eigen::Quaterniond(0.5, -0.5, 0.5, -0.5), {0.1, 0.0, 1.2});
    frame.odom_from_body = Rigid3d(Eigen::Quaterniond::Identity(), {0.5 * index, 0.2, 0.0});
    if (with_truth) frame.world_from_camera = Rigid3d(Eigen::Quaterniond::Identity(), {1, 2, 3});
    frame.bgr = cv::Mat(480, 640, CV_8UC3, cv::Scalar(1, 2, 3));  // never stored
    return frame;
  }

  static FrameFeatures Features(int n, DescriptorKind kind) {
    FrameFeatures f;
    f.kind = kind;
    f.descriptors = kind == DescriptorKind::kFloat ? cv::Mat(n, 64, CV_32F) : cv::Mat(n, 32, CV_8U);
    if (n == 0) f.descriptors = cv::Mat();  // as extractors return it
    if (n > 0) cv::randu(f.descriptors, 0, 255);
    for (int i = 0; i < n; ++i) {
      f.keypoints.emplace_back(10.f + i, 20.f + i, 7.f, 45.f, 0.5f / (i + 1), i % 3, -1);
      f.points_in_camera.push_back(i % 2 ? Eigen::Vector3f(0.1f * i, 0.2f, 1.5f)
                                         : Eigen::Vector3f::Constant(NAN));
    }
    return f;
  }

  fs::path path_;
};

TEST_F(FeatureCacheTest, RoundTripKeepsMetadataAndFeaturesButNoImages) {
  SessionInfo info;
  info.name = "3";
  info.clock_time = "17:54";
  info.has_ground_truth = true;
  const FrameFeatures first = Features(5, DescriptorKind::kFloat);
  const FrameFeatures empty = Features(0, DescriptorKind::kFloat);
  {
    FeatureCacheWriter writer(path_, "surf", info);
    writer.Append(Frame(0, true), first);
    writer.Append(Frame(4, false), empty);
    writer.Close();
    EXPECT_EQ(writer.num_frames(), 2);
  }
  FeatureCacheReader reader(path_);
  EXPECT_EQ(reader.extractor(), "surf");
  EXPECT_EQ(reader.info().name, "3");
  EXPECT_EQ(reader.info().clock_time, std::optional<std::string>("17:54"));
  EXPECT_TRUE(reader.info().has_ground_truth);
  EXPECT_EQ(reader.info().num_frames, 2);

  std::optional<FrameFeatures> features;
  std::optional<RgbdFrame> frame = reader.Next(&features);
  ASSERT_TRUE(frame && features);
  EXPECT_EQ(frame->frame_index, 0);
  EXPECT_DOUBLE_EQ(frame->timestamp_s, 100.0);
  EXPECT_TRUE(frame->bgr.empty());
  EXPECT_DOUBLE_EQ(frame->camera.fy, 526.0);
  EXPECT_TRUE(frame->body_from_camera.translation.isApprox(Eigen::Vector3d(0.1, 0.0, 1.2)));
  ASSERT_TRUE(frame->world_from_camera.has_value());
  EXPECT_EQ(features->size(), 5u);
  EXPECT_EQ(cv::norm(features->descriptors, first.descriptors, cv::NORM_INF), 0.0);
  EXPECT_FLOAT_EQ(features->keypoints[3].response, first.keypoints[3].response);
  EXPECT_EQ(features->keypoints[2].octave, 2);
  EXPECT_FALSE(features->HasPoint(0));
  EXPECT_TRUE(features->points_in_camera[3].isApprox(first.points_in_camera[3]));

  frame = reader.Next(&features);
  ASSERT_TRUE(frame && features);
  EXPECT_EQ(frame->frame_index, 4);
  EXPECT_FALSE(frame->world_from_camera.has_value());
  EXPECT_TRUE(features->empty());
  EXPECT_FALSE(reader.Next(&features).has_value());
  EXPECT_FALSE(features.has_value());
}

TEST_F(FeatureCacheTest, BinaryDescriptorsKeepTheirKind) {
  const FrameFeatures binary = Features(3, DescriptorKind::kBinary);
  {
    FeatureCacheWriter writer(path_, "orb", NamedSession("A"));
    writer.Append(Frame(0, false), binary);
    writer.Close();
  }
  FeatureCacheReader reader(path_);
  std::optional<FrameFeatures> features;
  ASSERT_TRUE(reader.Next(&features));
  EXPECT_EQ(features->kind, DescriptorKind::kBinary);
  EXPECT_EQ(features->descriptors.type(), CV_8U);
  EXPECT_EQ(cv::norm(features->descriptors, binary.descriptors, cv::NORM_INF), 0.0);
}

TEST_F(FeatureCacheTest, UnclosedOrTruncatedFileIsAnErrorNamingIt) {
  {
    FeatureCacheWriter writer(path_, "orb", NamedSession("A"));
    writer.Append(Frame(0, false), Features(4, DescriptorKind::kBinary));
    writer.Append(Frame(1, false), Features(4, DescriptorKind::kBinary));
    writer.Close();
  }
  fs::resize_file(path_, fs::file_size(path_) - 30);
  FeatureCacheReader reader(path_);
  std::optional<FrameFeatures> features;
  ASSERT_TRUE(reader.Next(&features));
  try {
    reader.Next(&features);
    FAIL() << "a truncated frame was read";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(path_.string() + ": truncated feature cache"),
              std::string::npos)
        << e.what();
  }
}

TEST_F(FeatureCacheTest, OtherFilesAreRejected) {
  std::ofstream(path_) << "not a cache at all";
  EXPECT_THROW(FeatureCacheReader reader(path_), InputError);
  EXPECT_THROW(FeatureCacheReader reader(path_.string() + ".missing"), InputError);
}

TEST_F(FeatureCacheTest, InconsistentFeaturesAreRefused) {
  FrameFeatures bad = Features(3, DescriptorKind::kFloat);
  bad.points_in_camera.pop_back();
  FeatureCacheWriter writer(path_, "surf", NamedSession("A"));
  EXPECT_THROW(writer.Append(Frame(0, false), bad), InputError);
}

}  // namespace
}  // namespace duskmap
