#!/usr/bin/env bash
# Spreads an experiment matrix over a Slurm cluster as a job array, then merges
# the shards into one report.
#
#   scripts/slurm_matrix.sh CONFIG SHARDS [RESULTS_ROOT] [--only I[,J...]] [--wait]
#
# Submits SHARDS array tasks (scripts/slurm_shard.sh); task i runs
# `duskmap run CONFIG --shard i/SHARDS` into RESULTS_ROOT/shard-i (resumable: a
# resubmitted task skips finished jobs) and logs to RESULTS_ROOT/logs/shard-i.log.
# A merge job (scripts/slurm_merge.sh) starts once every task has ended,
# successful or not: it names each shard that failed or was killed, with its
# log, or runs `duskmap report` over all shard folders into RESULTS_ROOT/report.
# Every shard builds the maps it owns and extracts only the features those
# maps and their localization sessions need, so shards share no files.
#
#   --only I[,J...]  resubmits only these shards (after a failure), and the merge again;
#                    indices are decimal (01 is 1), an empty item is an error
#   --wait           waits until the merge job has written its status (a failed squeue
#                    is retried) and exits with it
#
# SBATCH_ARGS adds sbatch options (partition, account, time); DUSKMAP_BIN is
# the program (default build/experiments/duskmap, at the same path on every node); DUSKMAP_JOBS
# (default 2) is each task's --jobs and CPUs; DUSKMAP_FEATURE_CACHE is each
# task's --feature-cache (a folder on the node's local disk); DUSKMAP_REPORT_ARGS
# adds `duskmap report` options. docs/experiments.md: running on a real cluster.
set -euo pipefail

usage() { echo "usage: $0 CONFIG SHARDS [RESULTS_ROOT] [--only I[,J...]] [--wait]" >&2; exit 2; }
positional=() only="" only_set=0 wait=0
while [ $# -gt 0 ]; do
  case "$1" in
    --only) [ $# -ge 2 ] || usage; only=$2; only_set=1; shift 2;;
    --wait) wait=1; shift;;
    -*) usage;;
    *) positional+=("$1"); shift;;
  esac
done
[ ${#positional[@]} -ge 2 ] && [ ${#positional[@]} -le 3 ] || usage
fail() { echo "$0: $1" >&2; exit "${2:-1}"; }

[ -f "${positional[0]}" ] || fail "${positional[0]}: no such config file" 2
config=$(realpath "${positional[0]}")
shards=${positional[1]}
case "$shards" in ''|*[!0-9]*) fail "SHARDS $shards: expected a positive integer" 2;; esac
# Leading zeros are decimal (08 is 8), and more than 9 digits is out of range.
digits() { local d=${1#"${1%%[!0]*}"}; [ ${#d} -le 9 ] && echo "$((10#${d:-0}))" || echo 999999999; }
shards=$(digits "$shards")
[ "$shards" -gt 0 ] || fail "SHARDS ${positional[1]}: expected a positive integer" 2
root=$(realpath -m "${positional[2]:-results-slurm}")
submitted=()
if [ $only_set = 1 ]; then
  # Each item a shard index: no empty item (1, or 1,,2), each index once, in decimal.
  case "$only" in ""|,*|*,|*,,*) fail "--only $only: expected shard indices I[,J...]" 2;; esac
  IFS=, read -r -a picked <<<"$only"
  declare -A seen=()
  for i in "${picked[@]}"; do
    case "$i" in ''|*[!0-9]*) fail "--only $only: expected shard indices I[,J...]" 2;; esac
    n=$(digits "$i")
    [ "$n" -lt "$shards" ] || fail "--only $only: shard $i is out of range (0 to $((shards - 1)))" 2
    [ -n "${seen[$n]:-}" ] || submitted+=("$n")
    seen[$n]=1
  done
  array=$(IFS=,; echo "${submitted[*]}")
else
  for ((i = 0; i < shards; ++i)); do submitted+=("$i"); done
  array="0-$((shards - 1))"
fi
repo=$(cd "$(dirname "$0")/.." && pwd)
duskmap=${DUSKMAP_BIN:-$repo/build/experiments/duskmap}
[ -x "$duskmap" ] || fail "$duskmap: not built (run scripts/build.sh)"
command -v sbatch >/dev/null || fail "sbatch: not installed (a Slurm client is needed; scripts/slurm_local.sh starts a local cluster)"
jobs=${DUSKMAP_JOBS:-2}
mkdir -p "$root/logs"
# A resubmitted shard's earlier status goes now, so that it cannot stand for
# a task that is cancelled before it starts.
for i in "${submitted[@]}"; do rm -f "$root/logs/shard-$i.exit"; done
rm -f "$root/logs/report.exit"

# shellcheck disable=SC2086
array_id=$(sbatch --parsable ${SBATCH_ARGS:-} \
  --job-name=duskmap-matrix --array="$array" --cpus-per-task="$jobs" \
  --output="$root/logs/shard-%a.log" --open-mode=append \
  "$repo/scripts/slurm_shard.sh" "$duskmap" "$config" "$shards" "$root")
array_id=${array_id%%;*}
echo "submitted shards $array as array job $array_id"
# shellcheck disable=SC2086
report_id=$(sbatch --parsable ${SBATCH_ARGS:-} \
  --job-name=duskmap-report --dependency=afterany:"$array_id" \
  --output="$root/logs/report.log" \
  "$repo/scripts/slurm_merge.sh" "$duskmap" "$config" "$shards" "$root") ||
  fail "the merge job was not submitted (sbatch failed) but the array job $array_id was: scancel $array_id, or once it has ended run $(printf '%q ' "$repo/scripts/slurm_merge.sh" "$duskmap" "$config" "$shards" "$root")"
report_id=${report_id%%;*}
echo "submitted the merge as job $report_id"
echo "results: $root/shard-*/, logs: $root/logs/, report: $root/report/"
[ $wait = 1 ] || exit 0

# The merge job has ended once it has written its status, or once a working
# squeue no longer lists it as pending or running, or no longer knows it
# (then it was killed or cancelled before it wrote one). A failed squeue (a
# busy controller, a timeout) proves nothing and is tried again.
squeue_err=$(mktemp)
trap 'rm -f "$squeue_err"' EXIT
until [ -f "$root/logs/report.exit" ]; do
  if listed=$(squeue -h -j "$report_id" -t PD,R,CG,CF,S 2>"$squeue_err"); then
    [ -n "$listed" ] || break
  elif grep -q 'Invalid job id' "$squeue_err"; then
    break
  fi
  sleep 2
done
[ -f "$root/logs/report.exit" ] ||
  fail "the merge job $report_id ended without a status (killed or cancelled): read $root/logs/report.log"
rc=$(cat "$root/logs/report.exit")
if [ "$rc" != 0 ]; then
  grep -E '^(slurm_merge.sh|duskmap): ' "$root/logs/report.log" | tail -n "$((shards + 2))" >&2 || true
  fail "the merge job $report_id failed (status $rc): read $root/logs/report.log" "$rc"
fi
echo "merged: $root/report/"
