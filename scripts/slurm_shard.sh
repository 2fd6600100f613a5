#!/usr/bin/env bash
# One array task of scripts/slurm_matrix.sh (sbatch runs it; the task index is
# SLURM_ARRAY_TASK_ID): runs shard i of the matrix into ROOT/shard-i and
# records its exit status in ROOT/logs/shard-i.exit, which
# scripts/slurm_merge.sh reads. A task killed or cancelled leaves no status.
#
#   slurm_shard.sh DUSKMAP CONFIG SHARDS ROOT
#
# DUSKMAP_JOBS (default 2) is --jobs; DUSKMAP_FEATURE_CACHE, when set, is the
# --feature-cache folder (one per node, on the node's local disk).
set -uo pipefail
if [ $# -ne 4 ] || [ -z "${SLURM_ARRAY_TASK_ID:-}" ]; then
  echo "usage: SLURM_ARRAY_TASK_ID=i $0 DUSKMAP CONFIG SHARDS ROOT" >&2
  exit 2
fi
duskmap=$1 config=$2 shards=$3 root=$4
i=$SLURM_ARRAY_TASK_ID
status="$root/logs/shard-$i.exit"
rm -f "$status"
args=(run "$config" --shard "$i/$shards" --output "$root/shard-$i" --jobs "${DUSKMAP_JOBS:-2}" --resume)
if [ -n "${DUSKMAP_FEATURE_CACHE:-}" ]; then args+=(--feature-cache "$DUSKMAP_FEATURE_CACHE"); fi
echo "shard $i/$shards on $(hostname -s): ${args[*]}"
"$duskmap" "${args[@]}"
rc=$?
echo "$rc" >"$status.tmp-$$" && mv "$status.tmp-$$" "$status"
exit "$rc"
