#!/usr/bin/env bash
# The main job on a fresh machine: install, build, then run duskmap's default
# pipeline on the embedded synthetic dataset.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
./build/experiments/duskmap generate --config configs/sunset_apartment.json --output data/sunset --overwrite --preview
