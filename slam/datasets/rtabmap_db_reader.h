// Reader of RTAB-Map databases, straight from SQLite (no RTAB-Map code).
// Supported schemas: Admin.version 0.18.0 up to 0.23.x (serialized camera
// models); see ../shared/data/rtabmap/FORMAT_NOTES.md for the layout.
//  - PATH is one .db file or a folder of .db files (each read in name order).
//  - Frames are the nodes with an image (Node.weight > -9, Data.image not
//    NULL), in id order, grouped by Node.map_id into sessions. A database
//    with one map id gives one session named after the file stem
//    ("session_small"); with several, "<stem>.map<id>" ("merged.map0", ...).
//  - odom_from_body = Node.pose (per-session odometry, base frame);
//    body_from_camera = the calibration's local_transform; world_from_camera
//    = Node.ground_truth_pose * local_transform when it is not null.
//  - Colour: JPEG/PNG; depth: RVL, 16-bit PNG (mm) or float PNG (m), sniffed.
//  - Clock time is not stored in a database: SessionInfo.clock_time is unset.
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <string>

#include "slam/datasets/dataset_read_options.h"
#include "slam/io/dataset_reader.h"

namespace duskmap {

using RtabmapVersion = std::array<int, 3>;  // major, minor, patch
inline constexpr RtabmapVersion kOldestRtabmapSchema = {0, 18, 0};
inline constexpr RtabmapVersion kNewestRtabmapSchema = {0, 23, 999};

// "0.23.8" -> {0, 23, 8}; nullopt when not three dot-separated integers.
std::optional<RtabmapVersion> ParseRtabmapVersion(const std::string& text);

// Opens a database or a folder of databases. Problems found while indexing
// (unknown schema version, missing table or column, not a database) throw
// InputError "<file>: ..."; per-node problems (truncated pose blob, non-finite
// pose, timestamp going backwards) throw "<file>: node <id>: ..." unless
// options.skip_bad_frames, which drops and logs the node.
std::unique_ptr<DatasetReader> OpenRtabmapDatabase(const std::string& path,
                                                   const DatasetReadOptions& options = {});

}  // namespace duskmap
