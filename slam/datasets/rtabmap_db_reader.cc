#include "slam/datasets/rtabmap_db_reader.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <sstream>

#include "slam/core/check.h"
#include "slam/datasets/calibration_blob.h"
#include "slam/datasets/frame_assembly.h"
#include "slam/datasets/image_blob.h"
#include "slam/datasets/sqlite_database.h"

namespace duskmap {
namespace {

namespace fs = std::filesystem;

struct DbFrame {
  int64_t node_id = 0;
  double stamp_s = 0.0;
  Rigid3d odom_from_body;
  std::optional<Rigid3d> world_from_body;
};

struct DbSession {
  SessionInfo info;
  std::string db_path;
  std::vector<DbFrame> frames;
};

std::string VersionText(const RtabmapVersion& v) {
  return std::to_string(v[0]) + "." + std::to_string(v[1]) + "." + std::to_string(v[2]);
}

void CheckSchema(const SqliteDatabase& db) {
  const std::string& path = db.path();
  SLAM_THROW_IF_NOT(InputError, db.HasTable("Admin"))
      << path << ": missing table Admin (not an RTAB-Map database?)";
  SqliteStatement admin = db.Prepare("SELECT version FROM Admin");
  SLAM_THROW_IF_NOT(InputError, admin.Step()) << path << ": table Admin is empty";
  const std::string text = admin.Text(0);
  const std::optional<RtabmapVersion> version = ParseRtabmapVersion(text);
  SLAM_THROW_IF_NOT(InputError, version.has_value() && *version >= kOldestRtabmapSchema &&
                                    *version <= kNewestRtabmapSchema)
      << path << ": unknown schema version '" << text << "' (supported: "
      << VersionText(kOldestRtabmapSchema) << " to 0." << kNewestRtabmapSchema[1] << ".x)";
  const std::map<std::string, std::vector<std::string>> required = {
      {"Node", {"id", "map_id", "weight", "stamp", "pose", "ground_truth_pose"}},
      {"Data", {"id", "image", "depth", "calibration"}}};
  for (const auto& [table, columns] : required) {
    SLAM_THROW_IF_NOT(InputError, db.HasTable(table)) << path << ": missing table " << table;
    const std::set<std::string> present = db.Columns(table);
    for (const std::string& column : columns) {
      SLAM_THROW_IF_NOT(InputError, present.count(column))
          << path << ": table " << table << " has no column " << column;
    }
  }
}

// Reads one Node row into *frame; returns the problem, or "" when usable.
std::string ReadNode(const SqliteStatement& row, const std::string& where, DbFrame* frame) {
  frame->node_id = row.Int64(0);
  frame->stamp_s = row.Double(2);
  if (!std::isfinite(frame->stamp_s)) return "timestamp is not finite";
  try {
    size_t size = 0;
    const uint8_t* pose = row.Blob(3, &size);
    const std::optional<Rigid3d> odom = ParseTransformBlob(pose, size, where + ": pose");
    if (!odom) return "odometry pose is null";
    frame->odom_from_body = *odom;
    const uint8_t* truth = row.Blob(4, &size);
    if (truth) frame->world_from_body = ParseTransformBlob(truth, size, where + ": ground_truth_pose");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

std::vector<DbSession> IndexDatabase(const std::string& path, const DatasetReadOptions& options) {
  SqliteDatabase db(path);
  CheckSchema(db);
  SqliteStatement row = db.Prepare(
      "SELECT n.id, n.map_id, n.stamp, n.pose, n.ground_truth_pose FROM Node n JOIN Data d "
      "ON d.id = n.id WHERE n.weight > -9 AND d.image IS NOT NULL ORDER BY n.map_id, n.id");
  std::map<int64_t, std::vector<DbFrame>> maps;
  while (row.Step()) {
    const std::string where = path + ": node " + std::to_string(row.Int64(0));
    DbFrame frame;
    std::string problem = ReadNode(row, where, &frame);
    std::vector<DbFrame>& frames = maps[row.Int64(1)];
    if (problem.empty() && !frames.empty() && !(frame.stamp_s > frames.back().stamp_s)) {
      std::ostringstream text;
      text.precision(17);
      text << "timestamp " << frame.stamp_s << " s is not after node " << frames.back().node_id
           << "'s " << frames.back().stamp_s << " s";
      problem = text.str();
    }
    if (!problem.empty()) {
      ReportBadFrame(options, problem.rfind(path, 0) == 0 ? problem : where + ": " + problem);
      continue;
    }
    frames.push_back(frame);
  }
  SLAM_THROW_IF_NOT(InputError, !maps.empty()) << path << ": no node with an image";
  const std::string stem = fs::path(path).stem().string();
  std::vector<DbSession> sessions;
  for (auto& [map_id, frames] : maps) {
    DbSession session;
    session.db_path = path;
    session.info.name = maps.size() == 1 ? stem : stem + ".map" + std::to_string(map_id);
    session.info.num_frames = static_cast<int64_t>(frames.size());
    session.info.has_ground_truth =
        !frames.empty() && std::all_of(frames.begin(), frames.end(),
                                       [](const DbFrame& f) { return f.world_from_body.has_value(); });
    session.frames = std::move(frames);
    sessions.push_back(std::move(session));
  }
  return sessions;
}

class DbSessionReader : public SessionReader {
 public:
  explicit DbSessionReader(std::shared_ptr<const DbSession> session)
      : session_(std::move(session)),
        db_(session_->db_path),
        data_(db_.Prepare("SELECT image, depth, calibration FROM Data WHERE id = ?")) {}

  const SessionInfo& info() const override { return session_->info; }
  void Rewind() override { next_ = 0; }
  std::optional<RgbdFrame> Next() override {
    if (next_ >= session_->frames.size()) return std::nullopt;
    const DbFrame& node = session_->frames[next_];
    RgbdFrame frame;
    frame.frame_index = static_cast<int64_t>(next_++);
    frame.session = session_->info.name;  // no image_name: the images are blobs
    ReadFrame(node, &frame);
    return frame;
  }

 private:
  void ReadFrame(const DbFrame& node, RgbdFrame* frame) {
    const std::string where = db_.path() + ": node " + std::to_string(node.node_id);
    data_.Reset();
    data_.BindInt64(1, node.node_id);
    SLAM_THROW_IF_NOT(InputError, data_.Step()) << where << ": no Data row";
    size_t size = 0;
    const uint8_t* blob = data_.Blob(2, &size);
    SLAM_THROW_IF_NOT(InputError, blob != nullptr) << where << ": no calibration";
    const CameraCalibration calibration = ParseCalibrationBlob(blob, size, where + ": calibration");
    blob = data_.Blob(0, &size);
    const cv::Mat bgr = DecodeColorBlob(blob, size, where + ": image");
    blob = data_.Blob(1, &size);
    const cv::Mat depth_m = blob ? DecodeDepthBlob(blob, size, where + ": depth") : cv::Mat();
    assembler_.Assemble(bgr, depth_m, calibration, where, frame);
    frame->timestamp_s = node.stamp_s;
    frame->odom_from_body = node.odom_from_body;
    if (node.world_from_body) frame->world_from_camera = *node.world_from_body * frame->body_from_camera;
  }

  std::shared_ptr<const DbSession> session_;
  SqliteDatabase db_;
  SqliteStatement data_;
  FrameAssembler assembler_;
  size_t next_ = 0;
};

class DbDatasetReader : public DatasetReader {
 public:
  explicit DbDatasetReader(std::vector<DbSession> sessions) {
    for (DbSession& session : sessions) {
      sessions_.push_back(std::make_shared<const DbSession>(std::move(session)));
    }
  }
  std::string format() const override { return "rtabmap-db"; }
  std::vector<SessionInfo> Sessions() const override {
    std::vector<SessionInfo> infos;
    for (const auto& session : sessions_) infos.push_back(session->info);
    return infos;
  }
  std::unique_ptr<SessionReader> OpenSession(const std::string& name) const override {
    for (const auto& session : sessions_) {
      if (session->info.name == name) return std::make_unique<DbSessionReader>(session);
    }
    SLAM_THROW(InputError) << "rtabmap-db dataset: no session named '" << name << "'";
    return nullptr;
  }

 private:
  std::vector<std::shared_ptr<const DbSession>> sessions_;
};

std::vector<std::string> DatabaseFiles(const std::string& path) {
  if (!fs::is_directory(path)) return {path};
  std::vector<std::string> files;
  for (const auto& entry : fs::directory_iterator(path)) {
    if (entry.is_regular_file() && entry.path().extension() == ".db") {
      files.push_back(entry.path().string());
    }
  }
  std::sort(files.begin(), files.end());
  SLAM_THROW_IF_NOT(InputError, !files.empty()) << path << ": no .db file in this folder";
  return files;
}

}  // namespace

std::optional<RtabmapVersion> ParseRtabmapVersion(const std::string& text) {
  RtabmapVersion version{};
  std::istringstream stream(text);
  for (int i = 0; i < 3; ++i) {
    std::string part;
    if (!std::getline(stream, part, '.') || part.empty() || part.size() > 6 ||
        part.find_first_not_of("0123456789") != std::string::npos) {
      return std::nullopt;
    }
    version[i] = std::stoi(part);
  }
  if (stream.peek() != std::char_traits<char>::eof()) return std::nullopt;
  return version;
}

std::unique_ptr<DatasetReader> OpenRtabmapDatabase(const std::string& path,
                                                   const DatasetReadOptions& options) {
  options.Check();
  std::vector<DbSession> sessions;
  for (const std::string& file : DatabaseFiles(path)) {
    for (DbSession& session : IndexDatabase(file, options)) {
      for (const DbSession& other : sessions) {
        SLAM_THROW_IF_NOT(InputError, other.info.name != session.info.name)
            << file << ": session name '" << session.info.name << "' already used by "
            << other.db_path;
      }
      sessions.push_back(std::move(session));
    }
  }
  return std::make_unique<DbDatasetReader>(std::move(sessions));
}

}  // namespace duskmap
