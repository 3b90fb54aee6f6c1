#!/usr/bin/env bash
# The installed package works for a program outside this repository's build: installs the build
# into a scratch prefix, builds examples/ against it alone (find_package(aavio)), and checks that
# stream_sequence, fed packet by packet, gives `aavio run`'s trajectory bit for bit, and that in
# real-time mode it processes every event it was given.
#   installed_package_test.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
build=$1
source=$2
scratch=$build/test_tmp/installed_package
rm -rf "$scratch"
mkdir -p "$scratch"
cmake --install "$build" --prefix "$scratch/prefix" > "$scratch/install.log"
cmake -S "$source/examples" -B "$scratch/examples" -DCMAKE_PREFIX_PATH="$scratch/prefix" \
  -DCMAKE_BUILD_TYPE=Release > "$scratch/configure.log"
cmake --build "$scratch/examples" -j 2 > "$scratch/build.log"

aavio=$scratch/prefix/bin/aavio
"$aavio" simulate --preset mini --duration 1.5 --seed 3 --out "$scratch/sequence" > /dev/null
"$aavio" run "$scratch/sequence/sequence.yaml" --out "$scratch/run" --quiet > /dev/null
"$scratch/examples/stream_sequence" "$scratch/sequence/sequence.yaml" --out "$scratch/live.txt" \
  2> "$scratch/live.log"
if ! cmp "$scratch/run/stamped_traj_estimate.txt" "$scratch/live.txt"; then
  echo "stream_sequence's trajectory differs from aavio run's" >&2
  exit 1
fi
"$scratch/examples/stream_sequence" "$scratch/sequence/sequence.yaml" --real-time \
  --out "$scratch/live_rt.txt" 2> "$scratch/live_rt.log"
# "events L + R pushed, L + R processed": nothing dropped.
if ! grep -Eq 'events ([0-9]+) \+ ([0-9]+) pushed, \1 \+ \2 processed' "$scratch/live_rt.log"; then
  echo "real-time streaming lost events:" >&2
  cat "$scratch/live_rt.log" >&2
  exit 1
fi
echo "installed package: example built, trajectory identical to aavio run; real time: $(grep -o '[0-9]* ticks run, [0-9]* skipped' "$scratch/live_rt.log")"
