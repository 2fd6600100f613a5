#include "slam/io/tum_dataset.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <opencv2/imgcodecs.hpp>

#include "slam/core/check.h"
#include "slam/io/trajectory_io.h"
#include "slam/io/tum_writer.h"

namespace duskmap {
namespace {
namespace fs = std::filesystem;

constexpr double kMaxAssociationGapS = 0.02;
constexpr double kMaxPoseGapS = 0.05;

struct IndexEntry {
  double timestamp_s = 0.0;
  std::string file;  // relative to the sequence folder
};

std::vector<IndexEntry> ReadIndex(const std::string& folder, const std::string& name) {
  const std::string path = folder + "/" + name;
  std::ifstream in(path);
  SLAM_THROW_IF_NOT(InputError, in.good()) << path << ": cannot open index file";
  std::vector<IndexEntry> entries;
  std::string line;
  int line_number = 0;
  while (std::getline(in, line)) {
    ++line_number;
    const size_t first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') continue;
    std::istringstream fields(line);
    IndexEntry entry;
    SLAM_THROW_IF_NOT(InputError, static_cast<bool>(fields >> entry.timestamp_s >> entry.file) &&
                                      std::isfinite(entry.timestamp_s))
        << path << ":" << line_number << ": malformed line (expected 'timestamp filename')";
    SLAM_THROW_IF_NOT(InputError, fs::is_regular_file(folder + "/" + entry.file))
        << folder << "/" << entry.file << ": missing image (listed in " << name << ":"
        << line_number << ")";
    entries.push_back(entry);
  }
  std::stable_sort(entries.begin(), entries.end(),
                   [](const IndexEntry& a, const IndexEntry& b) { return a.timestamp_s < b.timestamp_s; });
  return entries;
}

struct FrameEntry {
  double timestamp_s = 0.0;
  std::string rgb_file;
  std::string depth_file;
};

std::vector<FrameEntry> Associate(const std::vector<IndexEntry>& rgb,
                                  const std::vector<IndexEntry>& depth) {
  std::vector<FrameEntry> frames;
  for (const IndexEntry& color : rgb) {
    const auto after = std::lower_bound(
        depth.begin(), depth.end(), color.timestamp_s,
        [](const IndexEntry& d, double t) { return d.timestamp_s < t; });
    const IndexEntry* best = nullptr;
    double best_gap = kMaxAssociationGapS;
    for (auto it : {after, after == depth.begin() ? depth.end() : after - 1}) {
      if (it == depth.end()) continue;
      const double gap = std::abs(it->timestamp_s - color.timestamp_s);
      if (gap <= best_gap) {
        best_gap = gap;
        best = &*it;
      }
    }
    if (best != nullptr) frames.push_back({color.timestamp_s, color.file, best->file});
  }
  return frames;
}

std::vector<TrajectoryPose> ReadOptionalTrajectory(const std::string& path) {
  if (!fs::exists(path)) return {};
  return ReadTrajectory(path);
}

class TumSessionReader : public SessionReader {
 public:
  TumSessionReader(const std::string& folder, SessionInfo info) : folder_(folder), info_(std::move(info)) {
    SLAM_THROW_IF_NOT(InputError, fs::is_directory(folder_)) << folder_ << ": not a folder";
    const std::string calibration_path = folder_ + "/" + kCalibrationFileName;
    calibration_ = fs::exists(calibration_path)
                       ? ReadCalibration(calibration_path)
                       : DefaultTumCalibration(fs::path(folder_).filename().string());
    frames_ = Associate(ReadIndex(folder_, "rgb.txt"), ReadIndex(folder_, "depth.txt"));
    ground_truth_ = ReadOptionalTrajectory(folder_ + "/groundtruth.txt");
    odometry_ = ReadOptionalTrajectory(folder_ + "/odometry.txt");
    info_.num_frames = static_cast<int64_t>(frames_.size());
    info_.has_ground_truth = !ground_truth_.empty();
  }

  const SessionInfo& info() const override { return info_; }
  void Rewind() override { next_ = 0; }

  std::optional<RgbdFrame> Next() override {
    if (next_ >= frames_.size()) return std::nullopt;
    const FrameEntry& entry = frames_[next_];
    RgbdFrame frame;
    frame.frame_index = static_cast<int64_t>(next_);
    frame.timestamp_s = entry.timestamp_s;
    frame.camera = calibration_.camera;
    frame.bgr = ReadImage(entry.rgb_file, cv::IMREAD_COLOR, CV_8UC3);
    frame.depth_m = RawToDepth(ReadImage(entry.depth_file, cv::IMREAD_ANYDEPTH, CV_16UC1),
                               calibration_.depth_scale);
    SLAM_THROW_IF_NOT(InputError, frame.bgr.size() == frame.depth_m.size())
        << folder_ << "/" << entry.depth_file << ": size differs from its rgb image";
    SLAM_THROW_IF_NOT(InputError, frame.bgr.cols == calibration_.camera.width &&
                                      frame.bgr.rows == calibration_.camera.height)
        << folder_ << "/" << entry.rgb_file << ": size differs from the calibration";
    frame.world_from_camera = InterpolatePose(ground_truth_, entry.timestamp_s, kMaxPoseGapS);
    frame.odom_from_body =
        InterpolatePose(odometry_, entry.timestamp_s, kMaxPoseGapS).value_or(Rigid3d::Identity());
    ++next_;
    return frame;
  }

 private:
  cv::Mat ReadImage(const std::string& file, int flags, int expected_type) const {
    const std::string path = folder_ + "/" + file;
    cv::Mat image = cv::imread(path, flags);
    SLAM_THROW_IF_NOT(InputError, !image.empty()) << path << ": cannot read image (truncated or corrupt)";
    SLAM_THROW_IF_NOT(InputError, image.type() == expected_type)
        << path << ": unexpected image type " << image.type();
    return image;
  }

  std::string folder_;
  SessionInfo info_;
  TumCalibration calibration_;
  std::vector<FrameEntry> frames_;
  std::vector<TrajectoryPose> ground_truth_;
  std::vector<TrajectoryPose> odometry_;
  size_t next_ = 0;
};

class TumDatasetReader : public DatasetReader {
 public:
  explicit TumDatasetReader(const std::string& path) : path_(path) {
    std::string name = fs::path(path).lexically_normal().filename().string();
    if (name.empty()) name = fs::path(path).lexically_normal().parent_path().filename().string();
    SessionInfo info;
    info.name = name;
    // Opening validates the layout now, so a broken sequence fails early.
    info_ = TumSessionReader(path_, info).info();
  }
  std::string format() const override { return "tum"; }
  std::vector<SessionInfo> Sessions() const override { return {info_}; }
  std::unique_ptr<SessionReader> OpenSession(const std::string& name) const override {
    SLAM_THROW_IF_NOT(InputError, name == info_.name)
        << path_ << ": no session named '" << name << "' (the sequence is '" << info_.name << "')";
    return std::make_unique<TumSessionReader>(path_, info_);
  }

 private:
  std::string path_;
  SessionInfo info_;
};

}  // namespace

std::unique_ptr<SessionReader> OpenTumSession(const std::string& path, SessionInfo info) {
  return std::make_unique<TumSessionReader>(path, std::move(info));
}

std::unique_ptr<DatasetReader> OpenTumDataset(const std::string& path) {
  return std::make_unique<TumDatasetReader>(path);
}

}  // namespace duskmap
