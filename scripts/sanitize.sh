#!/usr/bin/env bash
# The tests under AddressSanitizer + UndefinedBehaviorSanitizer (clang), as CI runs them beside
# the Release build: builds ./build-sanitize (libraries, CLI, tests and the fuzz targets; not the
# Python module or the ROS node) and runs the unit tests and a short run of every fuzz target.
# A memory error, leak or undefined behaviour fails the test it happens in.
#
#   scripts/sanitize.sh                 unit tests + fuzz targets (20 s each)
#   scripts/sanitize.sh -R Calibration  extra arguments go to ctest
set -euo pipefail
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build_dir=${BUILD_DIR:-$repo/build-sanitize}
"$repo/scripts/setup.sh" --deps-only
cmake_args=(-S "$repo" -B "$build_dir" -DCMAKE_BUILD_TYPE=Release -DAAVIO_SANITIZE=ON
            -DAAVIO_FUZZ=ON -DAAVIO_BUILD_BENCHMARKS=OFF)
CC=clang CXX=clang++ cmake "${cmake_args[@]}"
cmake --build "$build_dir" -j "$(nproc 2>/dev/null || echo 2)"
cd "$build_dir"
# halt_on_error: the first report fails the test; UBSan prints the stack of each finding.
export ASAN_OPTIONS=detect_leaks=1:halt_on_error=1:strict_string_checks=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
ctest --output-on-failure -j "$(nproc 2>/dev/null || echo 2)" -L 'unit|fuzz' "$@"
