#include "slam/io/tum_writer.h"

#include <cstdio>
#include <fstream>

#include "slam/core/check.h"
#include "slam/core/system_error.h"
#include "slam/io/folder_commit.h"
#include "slam/io/image_file.h"

namespace duskmap {

std::string TumStamp(double timestamp_s) {
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), "%.6f", timestamp_s);
  return buffer;
}

cv::Mat DepthToRaw(const cv::Mat& depth_m, double depth_scale) {
  SLAM_CHECK(depth_m.type() == CV_32FC1);
  cv::Mat raw(depth_m.size(), CV_16UC1);
  for (int r = 0; r < depth_m.rows; ++r) {
    const float* in = depth_m.ptr<float>(r);
    uint16_t* out = raw.ptr<uint16_t>(r);
    for (int c = 0; c < depth_m.cols; ++c) {
      const double v = in[c] * depth_scale + 0.5;
      out[c] = (in[c] > 0.0f && v < 65535.0) ? static_cast<uint16_t>(v) : 0;
    }
  }
  return raw;
}

cv::Mat RawToDepth(const cv::Mat& raw, double depth_scale) {
  cv::Mat depth_m;
  raw.convertTo(depth_m, CV_32F, 1.0 / depth_scale);
  return depth_m;
}

TumSessionWriter::TumSessionWriter(const std::string& folder, const TumCalibration& calibration)
    : folder_(folder), calibration_(calibration) {
  CreateFolder(folder_ + "/rgb");
  CreateFolder(folder_ + "/depth");
}

void TumSessionWriter::Write(const RgbdFrame& frame) {
  SLAM_CHECK(!finished_);
  SLAM_CHECK(frame.bgr.type() == CV_8UC3 && frame.depth_m.type() == CV_32FC1);
  const std::string stamp = TumStamp(frame.timestamp_s);
  const std::string rgb_name = "rgb/" + stamp + ".png";
  const std::string depth_name = "depth/" + stamp + ".png";
  // OpenCV's default PNG settings (no explicit level: SUB filter, zlib level
  // 1, run-length strategy) encode a noisy 640x480 frame about 3x faster than
  // an explicit IMWRITE_PNG_COMPRESSION (adaptive filters, default strategy)
  // and give slightly smaller files on camera-noisy images.
  const std::vector<int> params;
  WriteImageFile(folder_ + "/" + rgb_name, frame.bgr, params);
  WriteImageFile(folder_ + "/" + depth_name, DepthToRaw(frame.depth_m, calibration_.depth_scale),
                 params);
  rgb_lines_.push_back(stamp + " " + rgb_name);
  depth_lines_.push_back(stamp + " " + depth_name);
  if (frame.world_from_camera) ground_truth_.push_back({frame.timestamp_s, *frame.world_from_camera});
  odometry_.push_back({frame.timestamp_s, frame.odom_from_body});
}

namespace {
void WriteIndex(const std::string& path, const std::string& kind,
                const std::vector<std::string>& lines) {
  std::ofstream out(path);
  SLAM_THROW_IF_NOT(InputError, out.good()) << path << ": cannot write";
  out << "# " << kind << " images\n# timestamp filename\n";
  for (const std::string& line : lines) out << line << "\n";
  out.flush();
  SLAM_THROW_IF_NOT(InputError, out.good()) << path << ": write failed: " << LastSystemError();
}
}  // namespace

void TumSessionWriter::Finish() {
  SLAM_CHECK(!finished_);
  WriteIndex(folder_ + "/rgb.txt", "color", rgb_lines_);
  WriteIndex(folder_ + "/depth.txt", "depth", depth_lines_);
  if (!ground_truth_.empty()) {
    WriteTrajectory(folder_ + "/groundtruth.txt", ground_truth_, "ground truth world_from_camera");
  }
  WriteTrajectory(folder_ + "/odometry.txt", odometry_, "odometry odom_from_body");
  WriteCalibration(folder_ + "/" + kCalibrationFileName, calibration_);
  finished_ = true;
}

}  // namespace duskmap
