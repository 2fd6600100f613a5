#!/usr/bin/env bash
# The merge job of scripts/slurm_matrix.sh (it runs once every shard task has
# ended, whether it succeeded or not; it can also be run by hand): checks
# that every shard finished with status 0 (ROOT/logs/shard-i.exit, written by
# scripts/slurm_shard.sh), then runs `duskmap report` over the shard folders
# into ROOT/report. A shard that failed or never finished is one line naming
# its index, why, its log and the command that resubmits it alone; no report
# is written then, and every shard's results stay as they are.
#
#   slurm_merge.sh DUSKMAP CONFIG SHARDS ROOT
#
# Its own exit status goes to ROOT/logs/report.exit (read by slurm_matrix.sh
# --wait). DUSKMAP_REPORT_ARGS adds options to `duskmap report` (--no-figures).
set -uo pipefail
if [ $# -ne 4 ]; then
  echo "usage: $0 DUSKMAP CONFIG SHARDS ROOT" >&2
  exit 2
fi
duskmap=$1 config=$2 shards=$3 root=$4
mkdir -p "$root/logs"
status="$root/logs/report.exit"
rm -f "$status"
finish() {
  echo "$1" >"$status.tmp-$$" && mv "$status.tmp-$$" "$status"
  exit "$1"
}

failed=()
for ((i = 0; i < shards; ++i)); do
  log="$root/logs/shard-$i.log"
  if [ ! -f "$root/logs/shard-$i.exit" ]; then
    why="did not finish (killed, cancelled or never started)"
  else
    rc=$(cat "$root/logs/shard-$i.exit")
    [ "$rc" = 0 ] && continue
    why="exited with status $rc"
  fi
  failed+=("$i")
  echo "slurm_merge.sh: shard $i of $shards $why: read $log; resubmit it alone:" \
    "$(printf 'scripts/slurm_matrix.sh %q %q %q --only %s' "$config" "$shards" "$root" "$i")" >&2
done
if [ ${#failed[@]} -gt 0 ]; then
  list=$(IFS=,; echo "${failed[*]}")
  echo "slurm_merge.sh: no report: ${#failed[@]} of $shards shards failed; the other shards' results are kept (--only $list resubmits the failed ones)" >&2
  finish 1
fi

dirs=()
for ((i = 0; i < shards; ++i)); do dirs+=("$root/shard-$i"); done
# shellcheck disable=SC2086
"$duskmap" report "$config" --results "${dirs[@]}" --output "$root/report" ${DUSKMAP_REPORT_ARGS:-}
finish $?
