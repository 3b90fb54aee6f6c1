#!/usr/bin/env bash
# Ctrl-C in the middle of `aavio run` stops it with valid outputs: exit code 130, summary.json
# says "interrupted" and how far it got, the trajectory so far is a TUM file, and a second run
# into the folder is refused as for any earlier run.
#   interrupt_test.sh AAVIO_BINARY SCRATCH_DIR
set -euo pipefail
aavio=$1
dir=$2
rm -rf "$dir"
mkdir -p "$dir"
"$aavio" simulate --preset rpg --duration 6 --out "$dir/seq" --quiet >/dev/null

"$aavio" run "$dir/seq" --out "$dir/run" --quiet >"$dir/run.log" 2>&1 &
pid=$!
# Interrupt once the run has written depth maps (it is mapping and tracking by then).
for _ in $(seq 600); do
  n=$( (find "$dir/run/depth" -name 'disparity_*' 2>/dev/null || true) | wc -l)
  [ "$n" -ge 2 ] && break
  kill -0 "$pid" 2>/dev/null || break
  sleep 0.1
done
kill -INT "$pid"
rc=0
wait "$pid" || rc=$?
cat "$dir/run.log"
[ "$rc" -eq 130 ] || { echo "FAIL: exit code $rc, expected 130"; exit 1; }
grep -q '^interrupted: ' "$dir/run.log" || { echo "FAIL: the run did not say it was interrupted"; exit 1; }

/usr/bin/python3 - "$dir/run" <<'PY'
import json, sys
run = sys.argv[1]
s = json.load(open(run + '/summary.json'))
assert s['interrupted'] is True, s['interrupted']
assert 0 < s['data_duration_s'] < 6.0, s['data_duration_s']
lines = [l.split() for l in open(run + '/stamped_traj_estimate.txt') if not l.startswith('#')]
assert len(lines) == s['poses'] > 0, (len(lines), s['poses'])
assert all(len(l) == 8 for l in lines)
stamps = [float(l[0]) for l in lines]
assert stamps == sorted(stamps)
print('interrupted after %.2f s of data: %d poses, summary and trajectory valid' % (s['data_duration_s'], len(lines)))
PY

rc=0
"$aavio" run "$dir/seq" --out "$dir/run" --quiet >"$dir/again.log" 2>&1 || rc=$?
[ "$rc" -eq 1 ] && grep -q 'holds the outputs of an earlier run' "$dir/again.log" ||
  { echo "FAIL: a second run into the folder was not refused"; cat "$dir/again.log"; exit 1; }
echo "PASS"
