#!/usr/bin/env bash
# A disk that fills up in the middle of `aavio run` stops it with valid outputs: a clear error
# naming the file, exit code 1, and the trajectory, summary.json (saying what stopped the run),
# config.yaml and map.ply of what was done. The run's folder is on an 80 MB tmpfs of a private
# mount namespace (unshare; no root needed where user namespaces are allowed, skipped otherwise),
# filled once the run is mapping.
#   disk_full_test.sh AAVIO_BINARY SCRATCH_DIR
set -euo pipefail
aavio=$1
dir=$2
rm -rf "$dir"
mkdir -p "$dir/disk"
if ! unshare --user --map-root-user --mount true 2>/dev/null; then
  echo "SKIP: no private mount namespace here (unshare --user --mount)"
  exit 77
fi
"$aavio" simulate --preset rpg --duration 6 --out "$dir/seq" --quiet >/dev/null

export AAVIO=$aavio DIR=$dir
unshare --user --map-root-user --mount bash -euo pipefail -c '
mount -t tmpfs -o size=80m aavio_test "$DIR/disk"
"$AAVIO" run "$DIR/seq" --out "$DIR/disk/run" --quiet >"$DIR/run.log" 2>&1 &
pid=$!
for _ in $(seq 600); do
  n=$( (find "$DIR/disk/run/depth" -name "disparity_*" 2>/dev/null || true) | wc -l)
  [ "$n" -ge 2 ] && break
  kill -0 "$pid" 2>/dev/null || break
  sleep 0.1
done
dd if=/dev/zero of="$DIR/disk/filler" bs=1M 2>/dev/null || true  # until the disk is full
rc=0
wait "$pid" || rc=$?
cat "$DIR/run.log"
[ "$rc" -eq 1 ] || { echo "FAIL: exit code $rc, expected 1"; exit 1; }
grep -q "the disk is full\|disk full" "$DIR/run.log" || { echo "FAIL: no word of the full disk"; exit 1; }
grep -q "the run stopped there, after" "$DIR/run.log" || { echo "FAIL: no word of where it stopped"; exit 1; }
ls -a "$DIR/disk/run"
/usr/bin/python3 - "$DIR/disk/run" <<"PY"
import json, os, sys
run = sys.argv[1]
s = json.load(open(run + "/summary.json"))
print("summary: stopped_by %r, incomplete_outputs %r" % (s["stopped_by"], s.get("incomplete_outputs")))
assert "disk full" in s["stopped_by"] or "the disk is full" in s["stopped_by"], s["stopped_by"]
assert 0 < s["data_duration_s"] < 6.0, s["data_duration_s"]
lines = [l.split() for l in open(run + "/stamped_traj_estimate.txt") if not l.startswith("#")]
assert len(lines) == s["poses"] > 0, (len(lines), s["poses"])
assert all(len(l) == 8 for l in lines)
# map.ply: its header counts the vertices the file holds.
data = open(run + "/map.ply", "rb").read()
header, body = data.split(b"end_header\n", 1)
count = int([l for l in header.split(b"\n") if l.startswith(b"element vertex")][0].split()[2])
assert len(body) == 15 * count, (len(body), count)
left = [f for f in os.listdir(run) if f.endswith(".part") or f == ".aavio_reserve"]
assert not left, left
assert os.path.exists(run + "/config.yaml")
# depth/: every image its index lists, and no other (no half-written one).
indexed = [l.split()[1] for l in open(run + "/depth/timestamps.txt") if l[0].isdigit()]
print("depth/timestamps.txt lists %s" % indexed)
images = sorted(os.listdir(run + "/depth"))
assert images == sorted(["timestamps.txt"] + ["%s_%s.png" % (k, i) for i in indexed
                         for k in ("disparity", "inverse_depth")]), images
print("stopped by the full disk after %.2f s of data: %d poses, %d map points, summary valid"
      % (s["data_duration_s"], len(lines), count))
PY
'
echo "PASS"
