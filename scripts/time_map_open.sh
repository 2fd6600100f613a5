#!/usr/bin/env bash
# How long a saved map takes to open and localize its first frame, as a user
# meets it: the process wall of `duskmap localize` on a copy of one session
# that holds its first frame only (images linked, not copied), and where that
# time goes (the job summary's map load, localizer setup and index restore, the
# frame's own stages). Issue 46, item 4; docs/engine.md, "Opening a map".
#
#   scripts/time_map_open.sh MAP_DB DATASET SESSION [RUNS]
#
# Prints one line per run: wall_s load_s setup_s restore_s frame_ms.
set -euo pipefail
if [[ $# -lt 3 ]]; then
  echo "usage: $0 MAP_DB DATASET SESSION [RUNS]" >&2
  exit 2
fi
map=$1 dataset=$2 session=$3 runs=${4:-3}
duskmap=${DUSKMAP:-"$(dirname "$0")/../build/experiments/duskmap"}
[[ -f $map ]] || { echo "$map: no such map file" >&2; exit 1; }
[[ -f $dataset/manifest.json ]] || { echo "$dataset: not a duskmap dataset (no manifest.json)" >&2; exit 1; }
[[ -d $dataset/$session ]] || { echo "$dataset: no session '$session'" >&2; exit 1; }

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
one="$work/dataset"
mkdir -p "$one/$session"
/usr/bin/python3 - "$dataset/manifest.json" "$one/manifest.json" "$session" <<'PY'
import json, sys
manifest = json.load(open(sys.argv[1]))
manifest["sessions"] = [s for s in manifest["sessions"] if s["folder"] == sys.argv[3]]
json.dump(manifest, open(sys.argv[2], "w"), indent=1)
PY
src="$dataset/$session"
for entry in "$src"/*; do
  name=$(basename "$entry")
  case $name in
    *.txt) { grep '^#' "$entry" || true; grep -m 1 -v '^#' "$entry"; } > "$one/$session/$name" ;;
    *) ln -s "$(realpath "$entry")" "$one/$session/$name" ;;
  esac
done

for ((run = 1; run <= runs; ++run)); do
  start=$(date +%s.%N)
  "$duskmap" localize --map "$map" --dataset "$one" --session "$session" \
    --summary "$work/summary.json" --records "$work/frames.jsonl" > "$work/log" 2>&1 \
    || { cat "$work/log" >&2; exit 1; }
  end=$(date +%s.%N)
  /usr/bin/python3 - "$work/summary.json" "$work/frames.jsonl" "$start" "$end" <<'PY'
import json, sys
summary = json.load(open(sys.argv[1]))
frame = json.loads(open(sys.argv[2]).readline())
times = frame.get("timings_ms", {})
print(f"wall_s {float(sys.argv[4]) - float(sys.argv[3]):.3f}  load_s {summary['map_load_s']:.3f}  "
      f"setup_s {summary['localizer_setup_s']:.3f}  restore_s {summary['index_restore_s']:.3f}  "
      f"frame_ms {times.get('total', float('nan')):.0f}  "
      + " ".join(f"{k} {v:.0f}" for k, v in times.items() if k != "total"))
PY
done
