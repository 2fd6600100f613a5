#include "slam/datasets/calibration_yaml.h"

#include <gtest/gtest.h>

#include "slam/core/check.h"
#include "tests/datasets/dataset_test_util.h"

namespace duskmap {
namespace {

using testing::ErrorOf;

const char kExportYaml[] = R"(%YAML:1.0
---
camera_name: "1700000000.400000"
image_width: 320
image_height: 240
camera_matrix:
   rows: 3
   cols: 3
   data: [ 2.6250000000000000e+02, 0., 1.5950000000000000e+02, 0.,
       2.6250000000000000e+02, 1.1950000000000000e+02, 0., 0., 1. ]
local_transform:
   rows: 3
   cols: 4
   data: [ 0., 0., 1., 0., -1., 0., 0., 0., 0., -1., 0., 0. ]
)";

TEST(ParseCalibrationYaml, ReadsRtabmapExport) {
  const CameraCalibration c = ParseCalibrationYaml(kExportYaml, "x.yaml");
  EXPECT_EQ(c.name, "1700000000.400000");
  EXPECT_EQ(c.image_width, 320);
  EXPECT_EQ(c.image_height, 240);
  const PinholeCamera camera = c.Pinhole();
  EXPECT_DOUBLE_EQ(camera.fx, 262.5);
  EXPECT_DOUBLE_EQ(camera.fy, 262.5);
  EXPECT_DOUBLE_EQ(camera.cx, 159.5);
  EXPECT_DOUBLE_EQ(camera.cy, 119.5);
  EXPECT_FALSE(c.HasDistortion());
  // Optical frame: camera z = body x, camera x = -body y, camera y = -body z.
  const Eigen::Vector3d z_in_body = c.body_from_camera.rotation * Eigen::Vector3d::UnitZ();
  EXPECT_TRUE(z_in_body.isApprox(Eigen::Vector3d::UnitX(), 1e-12));
  const Eigen::Vector3d x_in_body = c.body_from_camera.rotation * Eigen::Vector3d::UnitX();
  EXPECT_TRUE(x_in_body.isApprox(-Eigen::Vector3d::UnitY(), 1e-12));
}

TEST(ParseCalibrationYaml, ReadsOptionalDistortionRectificationProjection) {
  std::string text = kExportYaml;
  text.insert(text.find("local_transform"),
              "distortion_coefficients:\n   rows: 1\n   cols: 4\n   data: [ 0.1, 0.01, 0.001, 0.0001 ]\n"
              "distortion_model: equidistant\n"
              "rectification_matrix:\n   rows: 3\n   cols: 3\n   data: [ 1., 0., 0., 0., 1., 0., 0., 0., 1. ]\n"
              "projection_matrix:\n   rows: 3\n   cols: 4\n"
              "   data: [ 200., 0., 160., 0., 0., 201., 120., 0., 0., 0., 1., 0. ]\n");
  const CameraCalibration c = ParseCalibrationYaml(text, "x.yaml");
  EXPECT_TRUE(c.fisheye);
  ASSERT_EQ(c.distortion.size(), 4u);
  EXPECT_DOUBLE_EQ(c.distortion[3], 0.0001);
  ASSERT_TRUE(c.rectification.has_value());
  EXPECT_DOUBLE_EQ(c.Pinhole().fy, 201.0);  // from P
  EXPECT_DOUBLE_EQ(c.Pinhole().cx, 160.0);
}

TEST(ParseCalibrationYaml, ErrorsNameFileLineAndProblem) {
  std::string missing = kExportYaml;
  missing.erase(missing.find("local_transform"));
  EXPECT_EQ(ErrorOf([&] { ParseCalibrationYaml(missing, "c.yaml"); }),
            "c.yaml: missing required key 'local_transform'");

  std::string short_data = kExportYaml;
  short_data.replace(short_data.find(" 0., 0., 1. ]"), 13, " 0., 1. ]");
  EXPECT_EQ(ErrorOf([&] { ParseCalibrationYaml(short_data, "c.yaml"); }),
            "c.yaml:6: camera_matrix: 8 values for a 3x3 matrix");

  std::string bad_number = kExportYaml;
  bad_number.replace(bad_number.find("2.6250000000000000e+02"), 22, "x");
  EXPECT_NE(ErrorOf([&] { ParseCalibrationYaml(bad_number, "c.yaml"); }).find("'x' is not a number"),
            std::string::npos);

  std::string unterminated = kExportYaml;
  unterminated.erase(unterminated.rfind(']'), 1);
  EXPECT_NE(ErrorOf([&] { ParseCalibrationYaml(unterminated, "c.yaml"); }).find("unterminated list"),
            std::string::npos);

  std::string not_rotation = kExportYaml;
  not_rotation.replace(not_rotation.find("[ 0., 0., 1., 0., -1."), 21, "[ 0., 0., 2., 0., -1.");
  EXPECT_NE(ErrorOf([&] { ParseCalibrationYaml(not_rotation, "c.yaml"); }).find("not a rotation"),
            std::string::npos);

  std::string zero_focal = kExportYaml;
  zero_focal.replace(zero_focal.find("2.6250000000000000e+02"), 22, "0.");
  EXPECT_NE(ErrorOf([&] { ParseCalibrationYaml(zero_focal, "c.yaml"); }).find("not positive"),
            std::string::npos);

  EXPECT_NE(ErrorOf([&] { ParseCalibrationYaml("image_width 3\n", "c.yaml"); })
                .find("c.yaml:1: expected 'key: value'"),
            std::string::npos);
}

TEST(CameraForImage, ScalesUniformResizesAndRejectsOtherSizes) {
  const CameraCalibration c = ParseCalibrationYaml(kExportYaml, "x.yaml");
  const PinholeCamera half = CameraForImage(c, 160, 120, "img");
  EXPECT_EQ(half.width, 160);
  EXPECT_DOUBLE_EQ(half.fx, 131.25);
  EXPECT_DOUBLE_EQ(half.cx, (159.5 + 0.5) * 0.5 - 0.5);
  EXPECT_EQ(ErrorOf([&] { CameraForImage(c, 320, 200, "img.jpg"); }),
            "img.jpg: calibration is for 320x240 but the image is 320x200");
}

}  // namespace
}  // namespace duskmap
