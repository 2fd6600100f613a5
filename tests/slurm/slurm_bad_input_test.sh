#!/usr/bin/env bash
# ctest slurm/MatrixBadInput (label slurm; needs no Slurm): the bad input of
# scripts/slurm_matrix.sh and scripts/slurm_merge.sh, each a one-line error
# that submits nothing and leaves every shard's results as they were:
#   - SHARDS not a positive integer, --only out of range or not indices (1, 1,,2
#     and "" too), no config;
#   - --only 01,1 submits shard 1 once (with a stand-in sbatch) and removes its old
#     status; a merge that sbatch refuses names the array job already submitted;
#   - a merge with a shard missing (no status: never ran, or killed) and one that
#     exited non-zero: one line per shard with its index and log, and no report;
#     the resubmit command it prints quotes a path with a space.
#
#   tests/slurm/slurm_bad_input_test.sh DUSKMAP_BINARY
set -euo pipefail
repo=$(cd "$(dirname "$0")/../.." && pwd)
duskmap=$(realpath "${1:?usage: $0 DUSKMAP_BINARY}")
tmp=$(mktemp -d "${TMPDIR:-/tmp}/duskmap_slurm_bad_input_test.XXXXXX")
trap 'rc=$?; rm -rf "$tmp"; exit $rc' EXIT
check() { echo "FAILED: $*" >&2; exit 1; }
echo '{}' >"$tmp/config.json"
root="$tmp/results"

# expect_error EXIT_CODE NEEDLE COMMAND...: one line on stderr holding NEEDLE.
expect_error() {
  local code=$1 needle=$2 rc=0
  shift 2
  "$@" >"$tmp/out" 2>"$tmp/err" || rc=$?
  [ "$rc" -eq "$code" ] || check "$*: exit $rc, not $code: $(cat "$tmp/err")"
  [ "$(wc -l <"$tmp/err")" -eq 1 ] || check "$*: not one line: $(cat "$tmp/err")"
  grep -qF -- "$needle" "$tmp/err" || check "$*: '$needle' missing in: $(cat "$tmp/err")"
}
matrix() { DUSKMAP_BIN="$duskmap" bash "$repo/scripts/slurm_matrix.sh" "$@"; }
expect_error 2 "--only 5: shard 5 is out of range (0 to 2)" matrix "$tmp/config.json" 3 "$root" --only 5
expect_error 2 "--only 1,3: shard 3 is out of range (0 to 2)" matrix "$tmp/config.json" 3 "$root" --only 1,3
expect_error 2 "--only 1,x: expected shard indices" matrix "$tmp/config.json" 3 "$root" --only 1,x
expect_error 2 "--only 1,: expected shard indices" matrix "$tmp/config.json" 3 "$root" --only 1,
expect_error 2 "--only 1,,2: expected shard indices" matrix "$tmp/config.json" 3 "$root" --only 1,,2
expect_error 2 "--only : expected shard indices" matrix "$tmp/config.json" 3 "$root" --only ""
expect_error 2 "SHARDS 0: expected a positive integer" matrix "$tmp/config.json" 0 "$root"
expect_error 2 "SHARDS 2x: expected a positive integer" matrix "$tmp/config.json" 2x "$root"
expect_error 2 "$tmp/none.json: no such config file" matrix "$tmp/none.json" 3 "$root"
[ ! -e "$root" ] || check "a refused submission created $root"

# --only 01,1 is shard 1 once: the array is "1", shard 1's old status goes and
# shard 0's stays. The merge's sbatch failing names the array job already
# submitted. (sbatch is a stand-in that logs its arguments.)
mkdir -p "$tmp/bin" "$root/logs"
cat >"$tmp/bin/sbatch" <<'SH'
#!/bin/sh
echo "$*" >>"$FAKE_SBATCH_LOG"
n=$(wc -l <"$FAKE_SBATCH_LOG")
[ "$n" -le "$FAKE_SBATCH_OK" ] || { echo "sbatch: error: refused" >&2; exit 1; }
echo "$((100 + n));cluster"
SH
chmod +x "$tmp/bin/sbatch"
fake_matrix() { PATH="$tmp/bin:$PATH" FAKE_SBATCH_LOG="$tmp/sbatch.log" FAKE_SBATCH_OK=$1 matrix "${@:2}"; }
echo 0 >"$root/logs/shard-0.exit"
echo 1 >"$root/logs/shard-1.exit"
fake_matrix 2 "$tmp/config.json" 3 "$root" --only 01,1 >"$tmp/out" || check "--only 01,1 refused"
grep -q -- "--array=1 " "$tmp/sbatch.log" || check "--only 01,1 is not --array=1: $(cat "$tmp/sbatch.log")"
grep -qxF "submitted shards 1 as array job 101" "$tmp/out" || check "--only 01,1: $(cat "$tmp/out")"
grep -qxF "submitted the merge as job 102" "$tmp/out" || check "--only 01,1: $(cat "$tmp/out")"
[ ! -e "$root/logs/shard-1.exit" ] || check "--only 01 left shard 1's old status"
[ -e "$root/logs/shard-0.exit" ] || check "--only 01 removed shard 0's status"
rm "$tmp/sbatch.log"
rc=0
fake_matrix 1 "$tmp/config.json" 3 "$root" --only 2 >"$tmp/out" 2>"$tmp/err" || rc=$?
[ "$rc" -eq 1 ] || check "a refused merge submission: exit $rc"
grep -qxF "submitted shards 2 as array job 101" "$tmp/out" || check "the array job is not named first: $(cat "$tmp/out")"
grep -qF "the merge job was not submitted (sbatch failed) but the array job 101 was: scancel 101" "$tmp/err" ||
  check "the refused merge: $(cat "$tmp/err")"
rm -rf "$root" "$tmp/sbatch.log"

# The merge: shard 0 finished, shard 1 exited 1, shard 2 never finished.
mkdir -p "$root/logs" "$root/shard-0" "$root/shard-1"
echo results >"$root/shard-0/run.json"
echo partial >"$root/shard-1/run.json"
echo 0 >"$root/logs/shard-0.exit"
echo 1 >"$root/logs/shard-1.exit"
rc=0
bash "$repo/scripts/slurm_merge.sh" "$duskmap" "$tmp/config.json" 3 "$root" 2>"$tmp/err" || rc=$?
[ "$rc" -eq 1 ] || check "merge over failed shards: exit $rc"
[ "$(cat "$root/logs/report.exit")" = 1 ] || check "the merge's status is not recorded"
grep -qxF "slurm_merge.sh: shard 1 of 3 exited with status 1: read $root/logs/shard-1.log; resubmit it alone: scripts/slurm_matrix.sh $tmp/config.json 3 $root --only 1" \
  "$tmp/err" || check "shard 1: $(cat "$tmp/err")"
grep -qxF "slurm_merge.sh: shard 2 of 3 did not finish (killed, cancelled or never started): read $root/logs/shard-2.log; resubmit it alone: scripts/slurm_matrix.sh $tmp/config.json 3 $root --only 2" \
  "$tmp/err" || check "shard 2: $(cat "$tmp/err")"
grep -qF "no report: 2 of 3 shards failed; the other shards' results are kept (--only 1,2 resubmits the failed ones)" \
  "$tmp/err" || check "summary: $(cat "$tmp/err")"
[ "$(wc -l <"$tmp/err")" -eq 3 ] || check "not one line per failed shard and a summary: $(cat "$tmp/err")"
[ ! -e "$root/report" ] || check "a report was written"
# The resubmit command quotes its paths.
spaced="$tmp/with space"
mkdir -p "$spaced/logs"
echo 0 >"$spaced/logs/shard-0.exit"
bash "$repo/scripts/slurm_merge.sh" "$duskmap" "$tmp/config.json" 2 "$spaced" 2>"$tmp/err" && check "merge with shard 1 missing passed"
grep -qF "resubmit it alone: scripts/slurm_matrix.sh $(printf %q "$tmp/config.json") 2 $(printf %q "$spaced") --only 1" "$tmp/err" ||
  check "unquoted resubmit command: $(cat "$tmp/err")"
[ "$(cat "$root/shard-0/run.json")" = results ] && [ "$(cat "$root/shard-1/run.json")" = partial ] ||
  check "the shards' results changed"
echo PASSED
