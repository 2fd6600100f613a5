#!/usr/bin/env bash
# How cost grows with the map (issue 46, item 3; docs/experiments.md, "The
# lifelong apartment"): generate the lifelong apartment (54 sessions over 12
# days, about 7 GB, into data/lifelong) unless it is there, then map 1, 2, 3, 6,
# 12, 24 and 48 of its sessions, merged and reduced, re-localize six held-out
# sessions of later days on each map, and write the report with its scaling
# tables and figure (out/lifelong/report/). Not part of the main job.
# Run after scripts/build.sh. JOBS=N sets the jobs run at once (default: one
# per CPU).
set -euo pipefail
cd "$(dirname "$0")/.."
duskmap=./build/experiments/duskmap
if [[ ! -f data/lifelong/manifest.json ]]; then
  "$duskmap" generate --config configs/lifelong_apartment.json --output data/lifelong
fi
"$duskmap" run configs/lifelong_matrix.json --output out/lifelong --overwrite \
  --feature-cache out/feature_cache --jobs "${JOBS:-$(nproc 2>/dev/null || echo 2)}"
