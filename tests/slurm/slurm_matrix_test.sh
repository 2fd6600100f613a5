#!/usr/bin/env bash
# ctest slurm/QuickProfileOnLocalCluster (label slurm): the quick CI profile
# (configs/quick_matrix.json on the quick dataset, scripts/quick_check.sh) run
# through a real one-node Slurm cluster (scripts/slurm_local.sh) as a job array
# of 3 shards with a dependent merge job (scripts/slurm_matrix.sh), against
# the same matrix run in one process:
#   1. the first submission has shard 1 fail (its output path is a file, so
#      `duskmap run` exits 1) and shard 2 cancelled while it runs (scancel):
#      the merge names both, with their logs, writes no report, and shard 0's
#      results are left byte for byte;
#   2. shards 1 and 2 resubmitted alone (--only 1,2 --wait) complete the run;
#   3. the merged report's cells.csv, timeline.csv, consecutive.csv and
#      tables/*.csv are byte-identical to the one-process run's, except the two
#      tables of wall-clock times (tables/per_frame_timings*, timing_budget*).
# The cluster is brought down (each daemon by its PID) also on failure.
# Exits 77 (ctest SKIP_RETURN_CODE) when Slurm or munge is not installed, or
# when not run as root (slurmd runs jobs as their users).
#
#   tests/slurm/slurm_matrix_test.sh DUSKMAP_BINARY
set -euo pipefail
repo=$(cd "$(dirname "$0")/../.." && pwd)
duskmap=$(realpath "${1:?usage: $0 DUSKMAP_BINARY}")

source "$repo/tests/slurm/cluster_test_setup.sh" duskmap_slurm_test
export DUSKMAP_SLURM_PORTS="16917 16918"  # apart from a cluster slurm_local.sh runs by default
cleanup() {
  local rc=$?
  bash "$repo/scripts/slurm_local.sh" down "$state" || true
  if [ "${DUSKMAP_KEEP_TEST_TMP:-0}" = 1 ]; then echo "kept $tmp"; else rm -rf "$tmp"; fi
  exit $rc
}
trap cleanup EXIT
check() { echo "FAILED: $*" >&2; exit 1; }
start=$SECONDS

# The quick profile's dataset and matrix, with the paths made absolute.
/usr/bin/python3 "$repo/scripts/quick_dataset_config.py" "$repo/configs/sunset_apartment.json" \
  "$repo/configs/quick/dataset_overrides.json" "$tmp/sunset_quick.json"
"$duskmap" generate --config "$tmp/sunset_quick.json" --output "$tmp/data" >"$tmp/generate.log"
/usr/bin/python3 - "$repo/configs/quick_matrix.json" "$tmp/quick_matrix.json" "$tmp/data" <<'PY'
import json, os, sys
config = json.load(open(sys.argv[1]))
config["dataset"]["path"] = sys.argv[3]
config["engine_config"] = os.path.join(os.path.dirname(sys.argv[1]), config["engine_config"])
json.dump(config, open(sys.argv[2], "w"), indent=1)
PY
echo "dataset generated: $((SECONDS - start)) s"
"$duskmap" run "$tmp/quick_matrix.json" --output "$tmp/one" --jobs 2 --no-figures >"$tmp/one.log"
echo "one process: $((SECONDS - start)) s"

bash "$repo/scripts/slurm_local.sh" up "$state"
export SLURM_CONF="$state/slurm.conf"
export DUSKMAP_BIN="$duskmap" DUSKMAP_JOBS=2 DUSKMAP_REPORT_ARGS=--no-figures
root="$tmp/slurm"
mkdir -p "$root"
touch "$root/shard-1"  # shard 1 fails: its output folder is a file
submitted=$(bash "$repo/scripts/slurm_matrix.sh" "$tmp/quick_matrix.json" 3 "$root")
echo "$submitted"
array_id=$(sed -n 's/^submitted shards .* as array job \([0-9]*\)$/\1/p' <<<"$submitted")
report_id=$(sed -n 's/^submitted the merge as job \([0-9]*\)$/\1/p' <<<"$submitted")
[ -n "$array_id" ] && [ -n "$report_id" ] || check "no job ids in: $submitted"
# Shard 2 is killed a few seconds after it starts.
# A failed squeue (a busy controller) proves nothing: it is tried again.
until listed=$(squeue -h -j "${array_id}_2" -t R) && [ -n "$listed" ]; do
  if listed=$(squeue -h -j "${array_id}_2" -t PD,CF); then
    [ -n "$listed" ] || check "shard 2 ended before it could be cancelled"
  fi
  sleep 1
done
sleep 3
scancel "${array_id}_2"
# The merge has ended once it wrote its status, or once a working squeue no
# longer lists it (then the check below fails).
until [ -f "$root/logs/report.exit" ]; do
  if listed=$(squeue -h -j "$report_id" -t PD,R,CG,CF,S 2>/dev/null); then [ -n "$listed" ] || break; fi
  sleep 2
done
echo "first submission ended: $((SECONDS - start)) s"

[ -f "$root/logs/report.exit" ] || check "the merge job $report_id ended without a status: $(cat "$root/logs/report.log")"
[ "$(cat "$root/logs/report.exit")" = 1 ] || check "the merge of a failed run did not fail"
merge_log=$(cat "$root/logs/report.log")
grep -qF "shard 1 of 3 exited with status 1: read $root/logs/shard-1.log; resubmit it alone:" \
  <<<"$merge_log" || check "the merge does not name shard 1 and its log: $merge_log"
grep -qF "shard 2 of 3 did not finish (killed, cancelled or never started): read $root/logs/shard-2.log" \
  <<<"$merge_log" || check "the merge does not name the killed shard 2 and its log: $merge_log"
grep -qF -- "--only 1,2 resubmits the failed ones" <<<"$merge_log" || check "no resubmit hint: $merge_log"
[ ! -e "$root/report" ] || check "a report was written although shards failed"
grep -q "duskmap: error: .*shard-1" "$root/logs/shard-1.log" || check "shard 1's log does not say why"
[ "$(cat "$root/logs/shard-0.exit")" = 0 ] || check "shard 0 did not succeed"
shard0_before=$(cd "$root/shard-0" && find . -type f -exec sha256sum {} + | sort)

rm "$root/shard-1"
bash "$repo/scripts/slurm_matrix.sh" "$tmp/quick_matrix.json" 3 "$root" --only 1,2 --wait
echo "resubmission merged: $((SECONDS - start)) s"
shard0_after=$(cd "$root/shard-0" && find . -type f -exec sha256sum {} + | sort)
[ "$shard0_before" = "$shard0_after" ] || check "shard 0's results changed"

# The merged tables equal the one-process run's, byte for byte.
compared=0
for file in cells.csv timeline.csv consecutive.csv $(cd "$tmp/one/report" && ls tables/*.csv); do
  case "$file" in tables/per_frame_timings*|tables/timing_budget*) continue;; esac
  cmp "$tmp/one/report/$file" "$root/report/$file" || check "$file differs from the one-process run"
  compared=$((compared + 1))
done
[ "$(cd "$tmp/one/report" && ls tables)" = "$(cd "$root/report" && ls tables)" ] ||
  check "the merged report has other tables than the one-process run"
[ $compared -ge 10 ] || check "only $compared files compared"
echo "PASSED: $compared files byte-identical; $((SECONDS - start)) s"
