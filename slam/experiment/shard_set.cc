#include "slam/experiment/shard_set.h"

#include <algorithm>
#include <map>
#include <set>
#include <sstream>

#include "slam/core/check.h"

namespace duskmap {
namespace fs = std::filesystem;

namespace {

std::string ManifestPath(const ShardFolder& folder) {
  return (folder.results_dir / "run.json").string();
}

std::string ShardName(const RunManifest& m) {
  return std::to_string(m.shard_index) + "/" + std::to_string(m.shard_count);
}

std::string JoinIndices(const std::vector<int>& indices) {
  std::ostringstream out;
  for (size_t i = 0; i < indices.size(); ++i) out << (i ? ", " : "") << indices[i];
  return out.str();
}

// Why `other` is not a shard of `first`'s run ("" when it is one).
std::string OtherRun(const RunManifest& first, const RunManifest& other) {
  // The records themselves, not their checksums: a record is what says
  // which config, data and program made the results.
  if (!first.configuration.is_null() && !other.configuration.is_null()) {
    const std::string difference = FirstJsonDifference(first.configuration, other.configuration);
    if (!difference.empty()) return "another configuration, first at " + difference;
  }
  if (other.features != first.features) return "other feature columns ran";
  if (other.session_clock != first.session_clock) return "other sessions or clock times";
  if (other.shard_count != first.shard_count) {
    return "shard " + ShardName(other) + ", the first is shard " + ShardName(first);
  }
  return "";
}

}  // namespace

std::vector<ShardFolder> ReadShardFolders(const std::vector<fs::path>& results_dirs) {
  std::vector<ShardFolder> folders;
  folders.reserve(results_dirs.size());
  for (const fs::path& dir : results_dirs) folders.push_back({dir, ReadRunManifest(dir)});
  return folders;
}

void CheckShardsOfOneRun(const std::vector<ShardFolder>& folders) {
  SLAM_THROW_IF_NOT(InputError, !folders.empty()) << "--results: no results folder";
  const ShardFolder& first = folders.front();
  for (const ShardFolder& folder : folders) {
    const RunManifest& m = folder.manifest;
    SLAM_THROW_IF_NOT(InputError, m.shard_count >= 1 && m.shard_count <= kMaxShardCount &&
                                      m.shard_index >= 0 &&
                                      m.shard_index < m.shard_count)
        << ManifestPath(folder) << ": shard " << ShardName(m)
        << " is out of range (malformed run manifest)";
  }
  std::map<int, const ShardFolder*> holder;  // by shard index
  for (const ShardFolder& folder : folders) {
    const std::string why = OtherRun(first.manifest, folder.manifest);
    SLAM_THROW_IF_NOT(InputError, why.empty())
        << ManifestPath(folder) << ": not a shard of the run in " << ManifestPath(first) << " ("
        << why << "); merge only the shards of one run";
    const int index = folder.manifest.shard_index;
    const auto [held, inserted] = holder.emplace(index, &folder);
    SLAM_THROW_IF_NOT(InputError, inserted)
        << ManifestPath(folder) << ": shard " << ShardName(folder.manifest) << " given twice (also "
        << ManifestPath(*held->second) << ")";
  }
}

std::vector<int> MissingShards(const std::vector<ShardFolder>& folders) {
  if (folders.empty()) return {};
  std::set<int> held;
  for (const ShardFolder& folder : folders) held.insert(folder.manifest.shard_index);
  std::vector<int> missing;
  for (int i = 0; i < folders.front().manifest.shard_count; ++i) {
    if (!held.count(i)) missing.push_back(i);
  }
  return missing;
}

void CheckShardsComplete(const std::vector<ShardFolder>& folders) {
  const std::vector<int> missing = MissingShards(folders);
  if (missing.empty()) return;
  std::vector<int> held;
  for (const ShardFolder& folder : folders) held.push_back(folder.manifest.shard_index);
  std::sort(held.begin(), held.end());
  SLAM_THROW(InputError) << "--results: shard" << (missing.size() > 1 ? "s " : " ")
                         << JoinIndices(missing) << " of " << folders.front().manifest.shard_count
                         << " missing (the folders hold shard" << (held.size() > 1 ? "s " : " ")
                         << JoinIndices(held) << " of the run in " << ManifestPath(folders.front())
                         << "); add the missing shard's folder, or --allow-missing for a partial report";
}

}  // namespace duskmap
