#!/usr/bin/env bash
# Installs, builds and runs every test (ctest), then the CI regression check on
# re-localization rates (scripts/quick_check.sh); exits non-zero on any failure.
# DUSKMAP_SANITIZE=1 also runs the suite under ASan and UBSan (scripts/sanitize.sh,
# build-sanitize/); off by default: it takes hours on 2 cores.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
python3 scripts/check_docs.py build  # the docs name only what exists, and the right test count
# Functions stay short: the CLI's at most 60 lines, the library's at most 80 (issue 45).
python3 scripts/function_lengths.py experiments --max 60
python3 scripts/function_lengths.py slam --max 80
jobs=$(nproc 2>/dev/null || echo 2)
ctest --test-dir build --output-on-failure -j"$jobs"
bash scripts/quick_check.sh
if [ "${DUSKMAP_SANITIZE:-0}" = 1 ]; then
  bash scripts/sanitize.sh
fi
