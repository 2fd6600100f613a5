// The results folders `duskmap report` merges must be the shards of one run:
// each folder's run.json records the same configuration (experiment and
// engine config, dataset identity, feature files, duskmap version), the same
// features and sessions and the same shard count, and each shard appears
// once. A shard missing is said by its index, so that it can be resubmitted
// alone (scripts/slurm_matrix.sh --only).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "slam/experiment/run_manifest.h"

namespace duskmap {

struct ShardFolder {
  std::filesystem::path results_dir;
  RunManifest manifest;  // its run.json
};

// Reads every folder's run.json (InputError naming the file when one is
// missing or malformed), in the given order.
std::vector<ShardFolder> ReadShardFolders(const std::vector<std::filesystem::path>& results_dirs);

// Throws InputError naming a folder's run.json when it is not a shard of the
// first folder's run: another configuration (the first differing key named,
// as FirstJsonDifference says it; compared only where both runs recorded
// one), other features or sessions, another shard count, or a shard given
// twice.
void CheckShardsOfOneRun(const std::vector<ShardFolder>& folders);

// The shard indices of the first folder's run that no folder holds, ascending.
std::vector<int> MissingShards(const std::vector<ShardFolder>& folders);

// Throws InputError when MissingShards is not empty: "--results: shard 1 of 3
// missing (the folders hold shards 0, 2 of one run); ..." .
void CheckShardsComplete(const std::vector<ShardFolder>& folders);

}  // namespace duskmap
