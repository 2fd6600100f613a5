#include "slam/datasets/rtabmap_images_reader.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include <opencv2/core.hpp>

#include "slam/core/check.h"
#include "slam/core/input_file.h"
#include "slam/datasets/calibration_yaml.h"
#include "slam/datasets/frame_assembly.h"
#include "slam/datasets/image_blob.h"
#include "slam/datasets/poses_file.h"
#include "slam/io/path_status.h"

namespace duskmap {
namespace {

namespace fs = std::filesystem;

constexpr double kPoseAgreementM = 1e-3;
constexpr double kPoseAgreementRad = 1e-3;

struct ImageFrame {
  std::string stem;
  std::string rgb_path;
  std::string name;  // relative to the session folder: "rgb/<stem>.jpg", "<prefix>_rgb/<stem>.jpg"
  double stamp_s = 0.0;
  Rigid3d odom_from_body;
};

struct ImageSession {
  SessionInfo info;
  ImageSessionLayout layout;
  std::vector<ImageFrame> frames;
};

std::string ReadFileBytes(const std::string& path) {
  RefuseNonRegularFile(path);  // before opening: a FIFO would block
  std::ifstream in(path, std::ios::binary);
  SLAM_THROW_IF_NOT(InputError, in.good()) << path << ": cannot open";
  std::ostringstream contents;
  contents << in.rdbuf();
  return contents.str();
}

ImageSessionLayout ReleaseLayout(const fs::path& folder) {
  ImageSessionLayout layout;
  layout.name = folder.filename().string();
  if (layout.name.empty()) layout.name = folder.parent_path().filename().string();
  layout.rgb_dir = (folder / "rgb").string();
  layout.depth_dir = (folder / "depth").string();
  layout.calib_dir = (folder / "calib").string();
  layout.device_poses = (folder / "device_poses.txt").string();
  layout.camera_poses = (folder / "camera_poses.txt").string();
  return layout;
}

ImageSessionLayout ExportLayout(const fs::path& folder, const std::string& prefix) {
  ImageSessionLayout layout;
  layout.name = prefix;
  layout.rgb_dir = (folder / (prefix + "_rgb")).string();
  layout.depth_dir = (folder / (prefix + "_depth")).string();
  layout.calib_dir = (folder / (prefix + "_calib")).string();
  layout.device_poses = (folder / (prefix + "_poses.txt")).string();
  layout.camera_poses = (folder / (prefix + "_camera_poses.txt")).string();
  return layout;
}

// Pose lines by the text that names their image: the stamp and the id.
std::map<std::string, PoseLine> IndexPoses(const std::string& path,
                                              const DatasetReadOptions& options) {
  std::map<std::string, PoseLine> index;
  if (!PathExists(path)) return index;
  const PosesFile file = ReadPosesFile(path);
  for (const BadPoseLine& bad : file.bad_lines) {
    ReportBadFrame(options, path + ":" + std::to_string(bad.line) + ": " + bad.problem);
  }
  for (const PoseLine& pose : file.poses) {
    index[pose.stamp_text] = pose;
    if (pose.id >= 0) index.emplace(std::to_string(pose.id), pose);
  }
  return index;
}

const PoseLine* FindPose(const std::map<std::string, PoseLine>& index,
                            const std::string& stem) {
  const auto it = index.find(stem);
  return it == index.end() ? nullptr : &it->second;
}

// Cross-checks camera_poses against device pose * local_transform.
std::string CheckCameraPose(const ImageSessionLayout& layout, const PoseLine& device,
                            const PoseLine& camera, const std::string& stem) {
  const Rigid3d body_from_camera =
      ReadCalibrationYaml((fs::path(layout.calib_dir) / (stem + ".yaml")).string()).body_from_camera;
  const Rigid3d expected = device.map_from_frame * body_from_camera;
  const double dt = (expected.translation - camera.map_from_frame.translation).norm();
  const double dr = RotationAngleRad(expected.rotation, camera.map_from_frame.rotation);
  if (dt <= kPoseAgreementM && dr <= kPoseAgreementRad) return "";
  std::ostringstream text;
  text << layout.camera_poses << ":" << camera.line << ": camera pose disagrees with "
       << layout.device_poses << ":" << device.line << " x local_transform by " << dt << " m, "
       << dr << " rad";
  return text.str();
}

// Resolves one colour image into a frame; returns the problem or "".
std::string ResolveFrame(const ImageSessionLayout& layout,
                         const std::map<std::string, PoseLine>& device,
                         const std::map<std::string, PoseLine>& camera, ImageFrame* frame) {
  const PoseLine* device_pose = FindPose(device, frame->stem);
  const PoseLine* camera_pose = FindPose(camera, frame->stem);
  const std::string pose_file = device_pose || PathExists(layout.device_poses)
                                    ? layout.device_poses : layout.camera_poses;
  if (!device_pose && (PathExists(layout.device_poses) || !camera_pose)) {
    return frame->rgb_path + ": no pose line for this image in " + pose_file;
  }
  if (device_pose) {
    frame->stamp_s = device_pose->stamp_s;
    frame->odom_from_body = device_pose->map_from_frame;
    return camera_pose ? CheckCameraPose(layout, *device_pose, *camera_pose, frame->stem) : "";
  }
  const Rigid3d body_from_camera =
      ReadCalibrationYaml((fs::path(layout.calib_dir) / (frame->stem + ".yaml")).string())
          .body_from_camera;
  frame->stamp_s = camera_pose->stamp_s;
  frame->odom_from_body = camera_pose->map_from_frame * body_from_camera.Inverse();
  return "";
}

ImageSession IndexSession(const ImageSessionLayout& layout, const DatasetReadOptions& options) {
  SLAM_THROW_IF_NOT(InputError, IsDirectoryPath(layout.calib_dir))
      << layout.calib_dir << ": calibration folder not found";
  SLAM_THROW_IF_NOT(InputError, PathExists(layout.device_poses) || PathExists(layout.camera_poses))
      << layout.device_poses << ": pose file not found (nor " << layout.camera_poses << ")";
  const auto device = IndexPoses(layout.device_poses, options);
  const auto camera = IndexPoses(layout.camera_poses, options);
  ImageSession session;
  session.layout = layout;
  for (const fs::path& entry : SortedFolderEntries(layout.rgb_dir)) {
    const std::string extension = entry.extension().string();
    if (extension != ".jpg" && extension != ".jpeg" && extension != ".png") continue;
    ImageFrame frame;
    frame.stem = entry.stem().string();
    frame.rgb_path = entry.string();
    frame.name = (entry.parent_path().filename() / entry.filename()).string();
    std::string problem;
    try {
      problem = ResolveFrame(layout, device, camera, &frame);
    } catch (const InputError& e) {
      problem = e.what();
    }
    if (problem.empty()) {
      session.frames.push_back(frame);
    } else {
      ReportBadFrame(options, problem);
    }
  }
  std::sort(session.frames.begin(), session.frames.end(),
            [](const ImageFrame& a, const ImageFrame& b) { return a.stamp_s < b.stamp_s; });
  SLAM_THROW_IF_NOT(InputError, !session.frames.empty())
      << layout.rgb_dir << ": no usable colour image";
  session.info.name = layout.name;
  session.info.num_frames = static_cast<int64_t>(session.frames.size());
  session.info.has_ground_truth = false;
  return session;
}

class ImageSessionReader : public SessionReader {
 public:
  explicit ImageSessionReader(std::shared_ptr<const ImageSession> session)
      : session_(std::move(session)) {}

  const SessionInfo& info() const override { return session_->info; }
  void Rewind() override { next_ = 0; }
  std::optional<RgbdFrame> Next() override {
    if (next_ >= session_->frames.size()) return std::nullopt;
    const ImageFrame& image = session_->frames[next_];
    RgbdFrame frame;
    frame.frame_index = static_cast<int64_t>(next_++);
    const ImageSessionLayout& layout = session_->layout;
    const CameraCalibration calibration =
        ReadCalibrationYaml((fs::path(layout.calib_dir) / (image.stem + ".yaml")).string());
    const std::string rgb = ReadFileBytes(image.rgb_path);
    const cv::Mat bgr = DecodeColorBlob(reinterpret_cast<const uint8_t*>(rgb.data()), rgb.size(),
                                        image.rgb_path);
    cv::Mat depth_m;
    if (IsDirectoryPath(layout.depth_dir)) {
      const std::string depth_path = (fs::path(layout.depth_dir) / (image.stem + ".png")).string();
      const std::string depth = ReadFileBytes(depth_path);
      depth_m = DecodeDepthBlob(reinterpret_cast<const uint8_t*>(depth.data()), depth.size(),
                                depth_path);
    }
    assembler_.Assemble(bgr, depth_m, calibration, image.rgb_path, &frame);
    frame.timestamp_s = image.stamp_s;
    frame.session = session_->info.name;
    frame.image_name = image.name;
    frame.image_file = image.rgb_path;
    frame.odom_from_body = image.odom_from_body;
    return frame;
  }

 private:
  std::shared_ptr<const ImageSession> session_;
  FrameAssembler assembler_;
  size_t next_ = 0;
};

class ImageDatasetReader : public DatasetReader {
 public:
  explicit ImageDatasetReader(std::vector<ImageSession> sessions) {
    for (ImageSession& session : sessions) {
      sessions_.push_back(std::make_shared<const ImageSession>(std::move(session)));
    }
  }
  std::string format() const override { return "rtabmap-images"; }
  std::vector<SessionInfo> Sessions() const override {
    std::vector<SessionInfo> infos;
    for (const auto& session : sessions_) infos.push_back(session->info);
    return infos;
  }
  std::unique_ptr<SessionReader> OpenSession(const std::string& name) const override {
    for (const auto& session : sessions_) {
      if (session->info.name == name) return std::make_unique<ImageSessionReader>(session);
    }
    SLAM_THROW(InputError) << "rtabmap-images dataset: no session named '" << name << "'";
    return nullptr;
  }

 private:
  std::vector<std::shared_ptr<const ImageSession>> sessions_;
};

}  // namespace

std::vector<ImageSessionLayout> FindImageSessions(const std::string& path) {
  const fs::path folder(path);
  if (!IsDirectoryPath(folder)) return {};
  if (IsDirectoryPath(folder / "rgb")) return {ReleaseLayout(folder)};
  std::vector<ImageSessionLayout> sessions;
  const std::string suffix = "_rgb";
  for (const fs::path& entry : SortedFolderEntries(folder)) {
    const std::string name = entry.filename().string();
    if (!IsDirectoryPath(entry)) continue;
    if (name.size() > suffix.size() && name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0) {
      sessions.push_back(ExportLayout(folder, name.substr(0, name.size() - suffix.size())));
    } else if (IsDirectoryPath(entry / "rgb")) {
      sessions.push_back(ReleaseLayout(entry));
    }
  }
  return sessions;
}

std::unique_ptr<DatasetReader> OpenRtabmapImages(const std::string& path,
                                                 const DatasetReadOptions& options) {
  options.Check();
  const std::vector<ImageSessionLayout> layouts = FindImageSessions(path);
  SLAM_THROW_IF_NOT(InputError, !layouts.empty())
      << path << ": no RTAB-Map image session (rgb/ or <prefix>_rgb/ folder)";
  std::vector<ImageSession> sessions;
  for (const ImageSessionLayout& layout : layouts) {
    for (const ImageSession& other : sessions) {
      SLAM_THROW_IF_NOT(InputError, other.info.name != layout.name)
          << layout.rgb_dir << ": session name '" << layout.name << "' is used twice";
    }
    sessions.push_back(IndexSession(layout, options));
  }
  return std::make_unique<ImageDatasetReader>(std::move(sessions));
}

}  // namespace duskmap
