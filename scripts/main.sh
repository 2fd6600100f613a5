#!/usr/bin/env bash
# The main job on a fresh machine: install, build, generate the default
# synthetic dataset, run the paper's experiment matrix on it and write the
# report (out/paper_matrix/report/report.md, tables and figures).
# JOBS=N sets the jobs run at once (default: one per CPU).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
./build/experiments/duskmap generate --config configs/sunset_apartment.json --output data/sunset \
  --overwrite --preview
# Extracted features are kept in out/feature_cache: a second main job with the same program and
# dataset extracts nothing (docs/experiments.md, --feature-cache).
./build/experiments/duskmap run configs/paper_matrix.json --output out/paper_matrix --overwrite \
  --feature-cache out/feature_cache --jobs "${JOBS:-$(nproc 2>/dev/null || echo 2)}"
