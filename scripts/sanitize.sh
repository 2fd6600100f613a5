#!/usr/bin/env bash
# Builds the test suites with AddressSanitizer (+ LeakSanitizer) and
# UndefinedBehaviorSanitizer into build-sanitize/ (RelWithDebInfo, the root
# CMakeLists' DUSKMAP_SANITIZE option, every UB finding fatal) and runs ctest
# there; any sanitizer report fails the test that hit it.
#
#   scripts/sanitize.sh [CTEST_REGEX]    e.g. scripts/sanitize.sh 'core/|map/'
#
# With a regex whose alternatives all start with a suite name ("map/",
# "^io/Tum"), only those suites are built; otherwise everything is.
# scripts/test.sh runs it (whole suite) when DUSKMAP_SANITIZE=1. Slow: see
# docs/real_data.md, "Sanitizers".
set -euo pipefail
cd "$(dirname "$0")/.."
regex="${1:-}"
jobs=$(nproc 2>/dev/null || echo 2)
build=build-sanitize
suites="core io synthetic datasets features vocabulary retrieval registration graph map engine eval experiment cli"

cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DDUSKMAP_BUILD_BENCH=OFF \
  -DDUSKMAP_SANITIZE=address,undefined -DCMAKE_CXX_FLAGS=-fno-sanitize-recover=all \
  > "$build.configure.log" 2>&1 || { cat "$build.configure.log"; exit 1; }
rm -f "$build.configure.log"

targets=()
if [ -n "$regex" ]; then
  IFS='|' read -r -a alternatives <<< "$regex"
  for alternative in "${alternatives[@]}"; do
    suite="${alternative#^}"
    suite="${suite%%/*}"
    if [[ " $suites " == *" $suite "* && "$alternative" == *"/"* ]]; then
      [[ " ${targets[*]:-} " == *" ${suite}_tests "* ]] || targets+=("${suite}_tests")
    else
      targets=()  # not a suite prefix: build everything
      break
    fi
  done
fi
if [ ${#targets[@]} -gt 0 ]; then
  cmake --build "$build" -j"$jobs" --target "${targets[@]}"
else
  cmake --build "$build" -j"$jobs"
fi

export ASAN_OPTIONS="${ASAN_OPTIONS:-halt_on_error=1:detect_leaks=1}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-halt_on_error=1:print_stacktrace=1}"
ctest_args=(--test-dir "$build" --output-on-failure -j"$jobs")
[ -n "$regex" ] && ctest_args+=(-R "$regex")
ctest "${ctest_args[@]}"
