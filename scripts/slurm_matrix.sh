#!/usr/bin/env bash
# Spreads an experiment matrix over a Slurm cluster as a job array, then merges
# the shards into one report.
#
#   scripts/slurm_matrix.sh CONFIG SHARDS [RESULTS_ROOT]
#
# Submits SHARDS array tasks; task i runs `duskmap run CONFIG --shard i/SHARDS`
# into RESULTS_ROOT/shard-i (resumable: a re-submitted task skips finished
# jobs), and a final job, started once every task succeeded, runs
# `duskmap report` over all shard folders into RESULTS_ROOT/report.
# Every shard builds the maps it owns and extracts only the features those
# maps and their localization sessions need, so shards share no files.
# Pass extra sbatch options (partition, account, time) through SBATCH_ARGS.
set -euo pipefail

if [ $# -lt 2 ]; then
  echo "usage: $0 CONFIG SHARDS [RESULTS_ROOT]" >&2
  exit 2
fi
config=$(realpath "$1")
shards=$2
root=$(realpath -m "${3:-results-slurm}")
repo=$(cd "$(dirname "$0")/.." && pwd)
duskmap="$repo/build/experiments/duskmap"
[ -x "$duskmap" ] || { echo "$0: $duskmap: not built (run scripts/build.sh)" >&2; exit 1; }
case "$shards" in ''|*[!0-9]*) echo "$0: SHARDS must be a positive integer" >&2; exit 2;; esac
mkdir -p "$root/logs"

array_id=$(sbatch --parsable ${SBATCH_ARGS:-} \
  --job-name=duskmap-matrix --array=0-$((shards - 1)) --cpus-per-task=2 \
  --output="$root/logs/shard-%a.log" \
  --wrap="\"$duskmap\" run \"$config\" --shard \$SLURM_ARRAY_TASK_ID/$shards \
          --output \"$root/shard-\$SLURM_ARRAY_TASK_ID\" --jobs 2 --resume")

shard_dirs=""
for ((i = 0; i < shards; ++i)); do shard_dirs+=" \"$root/shard-$i\""; done
report_id=$(sbatch --parsable ${SBATCH_ARGS:-} \
  --job-name=duskmap-report --dependency=afterok:"$array_id" \
  --output="$root/logs/report.log" \
  --wrap="\"$duskmap\" report \"$config\" --results $shard_dirs --output \"$root/report\"")

echo "submitted shards as array job $array_id and the report as job $report_id"
echo "results: $root/shard-*/, report: $root/report/report.md"
