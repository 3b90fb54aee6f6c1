#!/usr/bin/env bash
# Fuzzing campaigns: builds the libFuzzer targets (fuzz/, clang + AddressSanitizer + UBSan) into
# ./build-fuzz and runs each for a while, growing its corpus in build-fuzz/fuzz/<target>/corpus
# from the committed seeds (fuzz/corpus/<target>). Prints executions, coverage and findings.
#
#   scripts/fuzz.sh                          every target, 10 minutes each, one after the other
#   scripts/fuzz.sh --seconds 60 text rosbag two targets, a minute each
#   scripts/fuzz.sh --list                   the targets
# A finding is saved as build-fuzz/fuzz/<target>/crash-* (or leak-, timeout-, oom-); replay it
# with build-fuzz/bin/<target>_fuzzer FILE.
set -euo pipefail
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build_dir=${BUILD_DIR:-$repo/build-fuzz}
seconds=600
targets=()
all=(dsec_h5 rosbag text aedat4 prophesee_raw ros2_bag calibration config decompression)
while (($#)); do
  case "$1" in
    --seconds) seconds=$2; shift 2 ;;
    --list) printf '%s\n' "${all[@]}"; exit 0 ;;
    -h|--help) sed -n '2,11p' "$0"; exit 0 ;;
    -*) echo "fuzz.sh: unknown option '$1' (try --help)" >&2; exit 2 ;;
    *) targets+=("$1"); shift ;;
  esac
done
((${#targets[@]})) || targets=("${all[@]}")

"$repo/scripts/setup.sh" --deps-only
CC=clang CXX=clang++ cmake -S "$repo" -B "$build_dir" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DAAVIO_SANITIZE=ON -DAAVIO_FUZZ=ON -DAAVIO_BUILD_BENCHMARKS=OFF >/dev/null
cmake --build "$build_dir" -j "$(nproc)" --target "${targets[@]/%/_fuzzer}"

status=0
printf '%-14s %10s %9s %8s %8s  %s\n' target executions exec/s coverage corpus findings
for t in "${targets[@]}"; do
  work=$build_dir/fuzz/$t
  mkdir -p "$work/corpus"
  log=$work/campaign.log
  rc=0
  "$build_dir/bin/${t}_fuzzer" -max_total_time="$seconds" -timeout=20 -rss_limit_mb=2560 \
    -print_final_stats=1 -artifact_prefix="$work/" "$work/corpus" "$repo/fuzz/corpus/$t" \
    >"$log" 2>&1 || rc=$?
  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log" | tail -1)
  cov=$(grep -o 'cov: [0-9]*' "$log" | tail -1 | cut -d' ' -f2)
  corpus=$(find "$work/corpus" -type f | wc -l)
  findings=$(find "$work" -maxdepth 1 -type f \( -name 'crash-*' -o -name 'leak-*' -o -name 'timeout-*' -o -name 'oom-*' \) | wc -l)
  printf '%-14s %10s %9s %8s %8s  %s\n' "$t" "${runs:-?}" "${rate:-?}" "${cov:-?}" "$corpus" "$findings"
  if [ "$rc" -ne 0 ] || [ "$findings" -ne 0 ]; then
    status=1
    echo "  $t: exit code $rc; see $log" >&2
  fi
done
exit $status
