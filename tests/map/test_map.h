// A small random map for the map module's tests.
#pragma once

#include <random>
#include <string>

#include <gtest/gtest.h>
#include <sqlite3.h>

#include "slam/map/table_checksums.h"

#include "slam/core/random.h"
#include "slam/map/map.h"

namespace duskmap::testing {

inline MapNode RandomNode(NodeId id, SessionId session, int num_features, int descriptor_cols,
                          bool binary, Rng& rng,
                          DescriptorStorage storage = DescriptorStorage::kFloat32) {
  std::uniform_real_distribution<float> u(0.f, 300.f);
  MapNode n;
  n.id = id;
  n.session = session;
  n.frame_index = id * 3;
  n.timestamp_s = 100.0 + id;
  n.map_from_body = Rigid3d(Eigen::Quaterniond::UnitRandom(), Eigen::Vector3d::Random());
  n.odom_from_body = Rigid3d(Eigen::Quaterniond::UnitRandom(), Eigen::Vector3d::Random());
  n.body_from_camera = Rigid3d(Eigen::Quaterniond::UnitRandom(), Eigen::Vector3d(0.1, 0, 0.2));
  n.camera = PinholeCamera{320, 240, 260.0, 261.0, 159.5, 119.5};
  if (id % 2) n.truth_from_camera = n.map_from_body * n.body_from_camera;
  FrameFeatures f;
  for (int i = 0; i < num_features; ++i) {
    f.keypoints.emplace_back(u(rng), u(rng), 7.f + i % 5, u(rng), 1.f / (i + 1), i % 3, -1);
    f.points_in_camera.push_back(
        i % 7 == 0 ? Eigen::Vector3f(Eigen::Vector3f::Constant(std::nanf("")))
                   : Eigen::Vector3f(Eigen::Vector3f::Random()));
  }
  f.kind = binary ? DescriptorKind::kBinary : DescriptorKind::kFloat;
  f.descriptors = cv::Mat(num_features, descriptor_cols, binary ? CV_8U : CV_32F);
  cv::randu(f.descriptors, 0, binary ? 255 : 1);
  n.features = CompactFeatures::Encode(f, storage);
  for (int i = 0; i < num_features / 2; ++i) {
    if (i % 4 == 0) continue;
    n.word_ids.push_back(static_cast<WordId>(id * 100 + i));
    n.word_counts.push_back(1 + i % 3);
  }
  n.vocabulary_features = num_features;
  return n;
}

// Two sessions of `nodes_per_session` nodes chained by odometry links and
// joined by one loop closure; a few words.
inline Map MakeTestMap(int nodes_per_session = 5, int num_features = 40, bool binary = false,
                       uint64_t seed = 7,
                       DescriptorStorage storage = DescriptorStorage::kFloat32) {
  Rng rng(seed);
  cv::setRNGSeed(static_cast<int>(seed));
  MapMetadata metadata;
  metadata.feature_type = binary ? "brief" : "surf";
  metadata.feature_parameters_json = R"({"type":"surf","max_features":1000})";
  metadata.engine_parameters_json = R"({"mapping":{}})";
  metadata.descriptor_storage = storage;
  Map map(metadata);
  const int cols = binary ? 32 : 64;
  NodeId id = 1;
  for (SessionId s = 0; s < 2; ++s) {
    map.AddSession(std::to_string(s + 1), s == 0 ? std::optional<std::string>("16:46") : std::nullopt);
    for (int i = 0; i < nodes_per_session; ++i, ++id) {
      map.AddNode(RandomNode(id, s, num_features, cols, binary, rng, storage));
      if (i > 0) {
        Link link;
        link.from = id - 1;
        link.to = id;
        link.from_from_to = map.node(id - 1).map_from_body.Inverse() * map.node(id).map_from_body;
        link.information = Information6d::Identity() * (100.0 + id);
        link.information(0, 5) = link.information(5, 0) = 0.5;
        map.AddLink(link);
      }
    }
  }
  Link loop;
  loop.from = id - 1;
  loop.to = 2;
  loop.type = LinkType::kLoopClosure;
  loop.from_from_to = Rigid3d(Eigen::Quaterniond::UnitRandom(), Eigen::Vector3d(0.1, 0.2, 0.3));
  map.AddLink(loop);
  MapWords words;
  words.descriptors = cv::Mat(6, cols, binary ? CV_8U : CV_32F);
  cv::randu(words.descriptors, 0, binary ? 255 : 1);
  words.ids = {3, 4, 8, 100, 101, 250};
  map.SetWords(words);
  return map;
}

// Runs one SQL statement on a saved map file (to forge bad inputs).
inline void ExecuteSql(const std::string& path, const std::string& sql) {
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(path.c_str(), &db), SQLITE_OK) << path;
  const int rc = sqlite3_exec(db, sql.c_str(), nullptr, nullptr, nullptr);
  sqlite3_close(db);
  ASSERT_EQ(rc, SQLITE_OK) << sql;
}

// Runs one SQL statement on a saved map file and records the table
// checksums anew, as a map written with those values would have them: for
// tests of the checks behind the checksums (row sizes, layouts).
inline void ExecuteSqlResealed(const std::string& path, const std::string& sql) {
  ExecuteSql(path, sql + "; DELETE FROM checksums;");
  mapdb::SqliteDatabase db(path, /*read_only=*/false);
  mapdb::WriteChecksums(db);
}

}  // namespace duskmap::testing
