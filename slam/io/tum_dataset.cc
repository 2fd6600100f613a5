#include "slam/io/tum_dataset.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <system_error>

#include <opencv2/imgcodecs.hpp>

#include "slam/core/check.h"
#include "slam/core/input_file.h"
#include "slam/io/image_header.h"
#include "slam/io/path_status.h"
#include "slam/io/trajectory_io.h"
#include "slam/io/tum_writer.h"

namespace duskmap {
namespace {
namespace fs = std::filesystem;

constexpr double kMaxAssociationGapS = 0.02;
// Real TUM recordings drop frames (rgb without depth within 20 ms): such a
// recording is read as TUM's associate.py reads it with --allow-unordered.
constexpr const char* kAllowUnorderedHint = "; --allow-unordered reads it as recorded";
constexpr double kMaxPoseGapS = 0.05;

struct IndexEntry {
  double timestamp_s = 0.0;
  std::string stamp;  // the timestamp as written, for messages
  std::string file;   // relative to the sequence folder
  int line = 0;       // 1-based line number in the index file
};

fs::file_status StatusOf(const std::string& path) { return PathStatus(path); }

std::vector<IndexEntry> ReadIndex(const std::string& folder, const std::string& name,
                                  const TumReadOptions& options) {
  const std::string path = folder + "/" + name;
  StatusOf(path);
  RefuseNonRegularFile(path);  // before opening: a FIFO would block
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
    entry.line = line_number;
    fields >> std::ws;
    const std::streamoff stamp_begin = fields.tellg();
    const bool has_timestamp = static_cast<bool>(fields >> entry.timestamp_s);
    if (has_timestamp) {
      const std::streamoff stamp_end = fields.eof() ? static_cast<std::streamoff>(line.size())
                                                    : static_cast<std::streamoff>(fields.tellg());
      entry.stamp = line.substr(stamp_begin, stamp_end - stamp_begin);
    }
    SLAM_THROW_IF_NOT(InputError, has_timestamp && static_cast<bool>(fields >> entry.file) &&
                                      std::isfinite(entry.timestamp_s))
        << path << ":" << line_number << ": malformed line (expected 'timestamp filename')";
    RefuseNonRegularFile(folder + "/" + entry.file);
    SLAM_THROW_IF_NOT(InputError,
                      StatusOf(folder + "/" + entry.file).type() == fs::file_type::regular)
        << folder << "/" << entry.file << ": missing image (listed in " << name << ":"
        << line_number << ")";
    if (!options.allow_unordered && !entries.empty() &&
        !(entry.timestamp_s > entries.back().timestamp_s)) {
      // Lines so far are strictly increasing: an equal one is found by bisection.
      const auto same = std::lower_bound(
          entries.begin(), entries.end(), entry.timestamp_s,
          [](const IndexEntry& e, double t) { return e.timestamp_s < t; });
      SLAM_THROW_IF_NOT(InputError, same == entries.end() || same->timestamp_s != entry.timestamp_s)
          << path << ":" << line_number << ": duplicate timestamp " << entry.stamp
          << " (also on line " << same->line << ")" << kAllowUnorderedHint;
      SLAM_THROW(InputError) << path << ":" << line_number << ": timestamp " << entry.stamp
                             << " is not after line " << entries.back().line << "'s "
                             << entries.back().stamp << " (out of order)" << kAllowUnorderedHint;
    }
    entries.push_back(entry);
  }
  if (options.allow_unordered) {
    std::stable_sort(entries.begin(), entries.end(), [](const IndexEntry& a, const IndexEntry& b) {
      return a.timestamp_s < b.timestamp_s;
    });
  }
  return entries;
}

struct FrameEntry {
  double timestamp_s = 0.0;
  std::string rgb_file;
  std::string depth_file;
};

// The depth entry of nearest timestamp within kMaxAssociationGapS of `t`, or
// depth.end(); `depth` is sorted by timestamp.
std::vector<IndexEntry>::const_iterator NearestDepth(const std::vector<IndexEntry>& depth,
                                                     double t) {
  const auto after = std::lower_bound(
      depth.begin(), depth.end(), t,
      [](const IndexEntry& d, double v) { return d.timestamp_s < v; });
  auto best = depth.end();
  double best_gap = kMaxAssociationGapS;
  for (auto it : {after, after == depth.begin() ? depth.end() : after - 1}) {
    if (it == depth.end()) continue;
    const double gap = std::abs(it->timestamp_s - t);
    if (gap <= best_gap) {
      best_gap = gap;
      best = it;
    }
  }
  return best;
}

// Pairs each rgb image with its nearest depth image. Unless allow_unordered,
// the pairing must be 1:1 (every rgb and every depth line used once); the
// first exception throws naming the index file and line.
std::vector<FrameEntry> Associate(const std::string& folder, const std::vector<IndexEntry>& rgb,
                                  const std::vector<IndexEntry>& depth,
                                  const TumReadOptions& options) {
  std::vector<FrameEntry> frames;
  std::vector<const IndexEntry*> used_by(depth.size(), nullptr);  // the rgb entry of each depth
  for (const IndexEntry& color : rgb) {
    const auto best = NearestDepth(depth, color.timestamp_s);
    if (options.allow_unordered) {
      if (best != depth.end()) frames.push_back({color.timestamp_s, color.file, best->file});
      continue;
    }
    SLAM_THROW_IF_NOT(InputError, best != depth.end())
        << folder << "/rgb.txt:" << color.line << ": no depth image within "
        << kMaxAssociationGapS << " s of " << color.stamp << " in depth.txt" << kAllowUnorderedHint;
    const IndexEntry*& user = used_by[static_cast<size_t>(best - depth.begin())];
    SLAM_THROW_IF_NOT(InputError, user == nullptr)
        << folder << "/rgb.txt:" << color.line << ": the nearest depth image to " << color.stamp
        << " (depth.txt:" << best->line << ", " << best->stamp << ") is already used by line "
        << user->line << "'s " << user->stamp << " (one depth image for two rgb images)"
        << kAllowUnorderedHint;
    user = &color;
    frames.push_back({color.timestamp_s, color.file, best->file});
  }
  if (!options.allow_unordered) {
    for (size_t i = 0; i < depth.size(); ++i) {
      SLAM_THROW_IF_NOT(InputError, used_by[i] != nullptr)
          << folder << "/depth.txt:" << depth[i].line << ": depth image at " << depth[i].stamp
          << " is not matched by any rgb.txt line (each rgb image takes its nearest depth "
             "image within "
          << kMaxAssociationGapS << " s)" << kAllowUnorderedHint;
    }
  }
  return frames;
}

std::vector<TrajectoryPose> ReadOptionalTrajectory(const std::string& path) {
  if (StatusOf(path).type() == fs::file_type::not_found) return {};
  return ReadTrajectory(path);
}

class TumSessionReader : public SessionReader {
 public:
  TumSessionReader(const std::string& folder, SessionInfo info, const TumReadOptions& options)
      : folder_(folder), info_(std::move(info)) {
    SLAM_THROW_IF_NOT(InputError, StatusOf(folder_).type() == fs::file_type::directory)
        << folder_ << ": not a folder";
    const std::string calibration_path = folder_ + "/" + kCalibrationFileName;
    calibration_ = StatusOf(calibration_path).type() != fs::file_type::not_found
                       ? ReadCalibration(calibration_path)
                       : DefaultTumCalibration(fs::path(folder_).filename().string());
    frames_ = Associate(folder_, ReadIndex(folder_, "rgb.txt", options),
                        ReadIndex(folder_, "depth.txt", options), options);
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
    frame.session = info_.name;
    frame.image_name = entry.rgb_file;
    frame.image_file = folder_ + "/" + entry.rgb_file;
    frame.camera = calibration_.camera;
    frame.bgr = ReadImage(entry.rgb_file, cv::IMREAD_COLOR, CV_8UC3);
    // Unchanged, so that a colour or 8-bit PNG is refused instead of converted.
    frame.depth_m = RawToDepth(ReadImage(entry.depth_file, cv::IMREAD_UNCHANGED, CV_16UC1),
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
    // Type, size and truncation before the decoder allocates what the header
    // declares or fills a cut JPEG with grey.
    CheckImageFileBeforeDecoding(path);
    cv::Mat image = cv::imread(path, flags);
    SLAM_THROW_IF_NOT(InputError, !image.empty()) << path << ": cannot read image (truncated or corrupt)";
    SLAM_THROW_IF_NOT(InputError, image.type() == expected_type)
        << path << ": " << (expected_type == CV_16UC1 ? "depth" : "colour")
        << " image must be " << (expected_type == CV_16UC1 ? "single-channel 16-bit" : "8-bit BGR")
        << ", got " << image.channels() << " channel(s) of " << (image.elemSize1() * 8) << " bits";
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
  TumDatasetReader(const std::string& path, const TumReadOptions& options)
      : path_(path), options_(options) {
    std::string name = fs::path(path).lexically_normal().filename().string();
    if (name.empty()) name = fs::path(path).lexically_normal().parent_path().filename().string();
    SessionInfo info;
    info.name = name;
    // Opening validates the layout now, so a broken sequence fails early.
    info_ = TumSessionReader(path_, info, options_).info();
  }
  std::string format() const override { return "tum"; }
  std::vector<SessionInfo> Sessions() const override { return {info_}; }
  std::unique_ptr<SessionReader> OpenSession(const std::string& name) const override {
    SLAM_THROW_IF_NOT(InputError, name == info_.name)
        << path_ << ": no session named '" << name << "' (the sequence is '" << info_.name << "')";
    return std::make_unique<TumSessionReader>(path_, info_, options_);
  }

 private:
  std::string path_;
  TumReadOptions options_;
  SessionInfo info_;
};

}  // namespace

std::unique_ptr<SessionReader> OpenTumSession(const std::string& path, SessionInfo info,
                                              const TumReadOptions& options) {
  return std::make_unique<TumSessionReader>(path, std::move(info), options);
}

std::unique_ptr<DatasetReader> OpenTumDataset(const std::string& path,
                                              const TumReadOptions& options) {
  return std::make_unique<TumDatasetReader>(path, options);
}

}  // namespace duskmap
