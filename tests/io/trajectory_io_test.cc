#include "slam/io/trajectory_io.h"

#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "slam/core/check.h"
#include "tests/testing/temp_dir.h"

namespace duskmap {
namespace {

std::string TempPath(const std::string& name) {
  return testing::ProcessTempPath("io_" + name);
}

TEST(WriteTrajectory, RoundTripKeepsPoses) {
  std::vector<TrajectoryPose> poses;
  for (int i = 0; i < 5; ++i) {
    const Eigen::Quaterniond q(Eigen::AngleAxisd(0.3 * i, Eigen::Vector3d(0.2, 1.0, -0.4).normalized()));
    poses.push_back({100.0 + i * 0.5, Rigid3d(q, Eigen::Vector3d(i, -2.0 * i, 0.1 * i))});
  }
  const std::string path = TempPath("round_trip.txt");
  WriteTrajectory(path, poses, "test");
  const std::vector<TrajectoryPose> read = ReadTrajectory(path);
  ASSERT_EQ(read.size(), poses.size());
  for (size_t i = 0; i < poses.size(); ++i) {
    EXPECT_NEAR(read[i].timestamp_s, poses[i].timestamp_s, 1e-6);
    EXPECT_LT((read[i].pose.translation - poses[i].pose.translation).norm(), 1e-8);
    EXPECT_LT(read[i].pose.rotation.angularDistance(poses[i].pose.rotation), 1e-8);
  }
}

TEST(ReadTrajectory, MalformedLineNamesFileAndLine) {
  const std::string path = TempPath("malformed.txt");
  std::ofstream(path) << "# header\n1.0 0 0 0 0 0 0 1\n2.0 0 0 0 0 0\n";
  try {
    ReadTrajectory(path);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(path + ":3"), std::string::npos) << e.what();
  }
}

TEST(ReadTrajectory, MissingFileThrows) {
  EXPECT_THROW(ReadTrajectory(TempPath("does_not_exist.txt")), InputError);
}

TEST(InterpolatePose, InterpolatesBetweenAndRejectsGaps) {
  std::vector<TrajectoryPose> poses = {{0.0, Rigid3d(Eigen::Quaterniond::Identity(), Eigen::Vector3d(0, 0, 0))},
                                    {1.0, Rigid3d(Eigen::Quaterniond::Identity(), Eigen::Vector3d(2, 0, 0))}};
  const auto mid = InterpolatePose(poses, 0.25, 1.0);
  ASSERT_TRUE(mid.has_value());
  EXPECT_NEAR(mid->translation.x(), 0.5, 1e-12);
  EXPECT_FALSE(InterpolatePose(poses, 0.5, 0.1).has_value());
  EXPECT_TRUE(InterpolatePose(poses, 1.05, 0.1).has_value());
}

}  // namespace
}  // namespace duskmap
