// Reader of RTAB-Map image releases (the paper's "Images" archive) and of
// `rtabmap-export --images --poses --poses_camera --poses_format 11` output.
//
// A session is a set of folders and files sharing a prefix:
//   release layout:  <session>/rgb/*.jpg, depth/*.png, calib/*.yaml,
//                    device_poses.txt, camera_poses.txt
//   export layout:   <prefix>_rgb/, <prefix>_depth/, <prefix>_calib/,
//                    <prefix>_poses.txt, <prefix>_camera_poses.txt
// PATH may be one release session folder (session named after the folder),
// a folder of export outputs (one session per <prefix>), or a folder whose
// subfolders are release sessions (one session per subfolder, by name).
//
// Each colour image `<stem>.jpg` (or .png) is matched to the pose line whose
// stamp is written `<stem>` (or whose id is `<stem>`) and read with
// depth/<stem>.png (16-bit mm, optional folder) and calib/<stem>.yaml.
// odom_from_body comes from device_poses.txt (or camera pose * local^-1 when
// only camera_poses.txt exists); when both exist they must agree. The poses
// are the files' (VIO or exported map-frame) poses; there is no ground truth.
// Frames are in pose-file order; timestamps must increase.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "slam/datasets/dataset_read_options.h"
#include "slam/io/dataset_reader.h"

namespace duskmap {

struct ImageSessionLayout {
  std::string name;
  std::string rgb_dir, depth_dir, calib_dir;  // depth_dir may not exist
  std::string device_poses, camera_poses;     // either may not exist (not both)
};

// The image sessions found at `path` (empty when it holds none).
std::vector<ImageSessionLayout> FindImageSessions(const std::string& path);

// Throws InputError "<file>[:<line>]: ..." for a folder without image
// sessions, missing calibration folder or pose files; per-frame problems
// found while indexing (bad pose line, image without pose, camera/device pose
// disagreement) throw unless options.skip_bad_frames, which drops and logs them.
std::unique_ptr<DatasetReader> OpenRtabmapImages(const std::string& path,
                                                 const DatasetReadOptions& options = {});

}  // namespace duskmap
