#!/usr/bin/env bash
# The CI regression check (quick profile): generates the quick dataset
# (configs/sunset_apartment.json with configs/quick/dataset_overrides.json),
# runs configs/quick_matrix.json, and compares its re-localization rates with
# the committed baseline results/quick/cells.csv; fails when any rate drops by
# more than TOLERANCE_PCT points (default 5). Never writes the baseline: see
# scripts/update_quick_baseline.sh.
#
#   scripts/quick_check.sh [--no-check]   (run only, e.g. to inspect the report)
set -euo pipefail
cd "$(dirname "$0")/.."
duskmap=./build/experiments/duskmap
[ -x "$duskmap" ] || { echo "$0: $duskmap: not built (run scripts/build.sh)" >&2; exit 1; }
mkdir -p build/quick
/usr/bin/python3 scripts/quick_dataset_config.py configs/sunset_apartment.json \
  configs/quick/dataset_overrides.json build/quick/sunset_quick.json
start=$(date +%s)
"$duskmap" generate --config build/quick/sunset_quick.json --output data/sunset_quick --overwrite
"$duskmap" run configs/quick_matrix.json --output out/quick --overwrite --jobs "$(nproc 2>/dev/null || echo 2)"
echo "quick profile: $(( $(date +%s) - start )) s (generation and matrix)"
if [ "${1:-}" != "--no-check" ]; then
  "$duskmap" check-rates --baseline results/quick/cells.csv --current out/quick/report/cells.csv \
    --tolerance-pct "${TOLERANCE_PCT:-5}"
fi
