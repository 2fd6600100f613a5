// Reader of one TUM RGB-D sequence folder (rgb.txt, depth.txt, optional
// groundtruth.txt and odometry.txt, optional calibration.json) as a dataset
// with one session named after the folder.
//  - Intrinsics and depth scale come from calibration.json when present,
//    otherwise from DefaultTumCalibration(folder name) (TUM: scale 5000).
//  - rgb.txt and depth.txt must each list strictly increasing timestamps
//    (no line out of order, no duplicate), and each rgb image is associated
//    with the depth image of nearest timestamp within 0.02 s (TUM's
//    associate.py default): every rgb line must find one, no depth image may
//    serve two rgb lines, and every depth line must be used. Anything else
//    throws InputError naming the index file and line, unless
//    TumReadOptions::allow_unordered (see below).
//  - Ground truth (world_from_camera) and odometry (odom_from_body) are
//    interpolated at the rgb timestamp (gap at most 0.05 s); frames without
//    odometry get the identity odometry pose. body_from_camera is identity.
// A listed image that is missing, a malformed index line, or a path that
// cannot be examined (a symlink loop, no permission) throws InputError naming
// the file when the dataset is opened; an unreadable image, or one whose
// header declares more than kMaxImagePixels (image_header.h), throws when its
// frame is read, before it is decoded.
#pragma once

#include <memory>
#include <string>

#include "slam/io/calibration.h"
#include "slam/io/dataset_reader.h"

namespace duskmap {

// How the index files of a TUM-layout folder are read.
struct TumReadOptions {
  // false (default): rgb.txt/depth.txt lines out of order, duplicated, or
  // without a 1:1 rgb-depth match are errors naming the file and line.
  // true: the lenient reading of real recordings whose streams drop frames:
  // each index is sorted by timestamp (duplicates kept), each rgb image takes
  // the nearest depth image within 0.02 s (a depth image may serve several),
  // and rgb images without one are skipped.
  bool allow_unordered = false;
};

std::unique_ptr<DatasetReader> OpenTumDataset(const std::string& path,
                                              const TumReadOptions& options = {});

// The session reader behind OpenTumDataset, shared by the synthetic dataset
// reader; `info` provides the name and clock time, frames are counted here.
std::unique_ptr<SessionReader> OpenTumSession(const std::string& path, SessionInfo info,
                                              const TumReadOptions& options = {});

}  // namespace duskmap
