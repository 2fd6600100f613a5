// Reader of one TUM RGB-D sequence folder (rgb.txt, depth.txt, optional
// groundtruth.txt and odometry.txt, optional calibration.json) as a dataset
// with one session named after the folder.
//  - Intrinsics and depth scale come from calibration.json when present,
//    otherwise from DefaultTumCalibration(folder name) (TUM: scale 5000).
//  - Each rgb image is associated with the depth image of nearest timestamp
//    within 0.02 s (TUM's associate.py default); rgb images without one are
//    skipped.
//  - Ground truth (world_from_camera) and odometry (odom_from_body) are
//    interpolated at the rgb timestamp (gap at most 0.05 s); frames without
//    odometry get the identity odometry pose. body_from_camera is identity.
// A listed image that is missing, or a malformed index line, throws InputError
// naming the file when the dataset is opened; an unreadable image throws when
// its frame is read.
#pragma once

#include <memory>
#include <string>

#include "slam/io/calibration.h"
#include "slam/io/dataset_reader.h"

namespace duskmap {

std::unique_ptr<DatasetReader> OpenTumDataset(const std::string& path);

// The session reader behind OpenTumDataset, shared by the synthetic dataset
// reader; `info` provides the name and clock time, frames are counted here.
std::unique_ptr<SessionReader> OpenTumSession(const std::string& path, SessionInfo info);

}  // namespace duskmap
