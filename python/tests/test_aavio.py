"""The aavio Python module on a simulated twin: sequences as numpy arrays, the odometry on a
sequence and on arrays (the same trajectory as `aavio run`, bit for bit), evaluation, a run's
outputs, and clear errors for bad input."""
import os
import subprocess
import sys

import numpy as np
import pytest

import aavio

TMP = os.environ.get("AAVIO_TEST_TMP_DIR", "/tmp/aavio_python_test")
AAVIO_BIN = os.environ.get("AAVIO_BIN", "aavio")


@pytest.fixture(scope="module")
def twin():
    """A 1.5 s mini twin (typical sensor, seed 3) and `aavio run`'s folder for it."""
    out = os.path.join(TMP, "twin")
    sequence = aavio.simulate(out, preset="mini", seed=3, duration_s=1.5, overwrite=True)
    run_dir = os.path.join(TMP, "run")
    subprocess.run([AAVIO_BIN, "run", sequence, "--out", run_dir, "--quiet", "--overwrite"], check=True,
                   stdout=subprocess.DEVNULL)
    return sequence, run_dir


def test_sequence_as_numpy_arrays(twin):
    seq = aavio.open_sequence(twin[0])
    assert seq.rig["width"] == 160 and seq.rig["height"] == 120
    assert 0.14 < seq.rig["baseline_m"] < 0.16
    assert seq.has_imu and seq.ground_truth.endswith("groundtruth.txt")
    assert seq.duration_s == pytest.approx(1.5, abs=0.01)
    left, right, imu = seq.read()
    assert left.dtype == aavio.EVENT_DTYPE and imu.dtype == aavio.IMU_DTYPE
    assert len(left) > 100000 and len(right) > 100000
    assert np.all(np.diff(left["t_ns"]) >= 0)
    assert left["x"].max() < 160 and left["y"].max() < 120
    assert set(np.unique(left["polarity"])) == {0, 1}
    assert imu["gyro_rad_s"].shape == (len(imu), 3)
    # Packets cover the same events, in order, within their bounds.
    count = 0
    for packet in seq.packets(packet_s=0.1, start_s=0.5, duration_s=0.5):
        assert np.all(packet["left"]["t_ns"] >= packet["t_begin_ns"])
        assert np.all(packet["left"]["t_ns"] < packet["t_end_ns"])
        count += len(packet["left"])
    window = (left["t_ns"] >= seq.start_ns + 500_000_000) & (left["t_ns"] < seq.start_ns + 1_000_000_000)
    assert count == np.count_nonzero(window)


def test_run_gives_aavio_runs_trajectory(twin):
    sequence, run_dir = twin
    trajectory = aavio.run(sequence)
    cli = aavio.load_run(run_dir)["trajectory"]
    assert len(trajectory) == len(cli) == 150
    assert np.array_equal(trajectory.t_ns, cli.t_ns)
    # The CLI's file holds 9 decimals: the same poses to that precision.
    assert np.allclose(trajectory.position, cli.position, atol=1e-9, rtol=0)
    assert trajectory.status.count("ok") > 120


def test_odometry_on_arrays_in_random_chunks_is_the_same(twin):
    seq = aavio.open_sequence(twin[0])
    left, right, imu = seq.read()
    whole = aavio.run(twin[0])
    odo = aavio.Odometry(seq.calibration, seq.start_ns)
    assert odo.preset == "indoor" and "baseline" in odo.preset_reason
    rng = np.random.default_rng(5)
    cursors = {"left": 0, "right": 0, "imu": 0}
    arrays = {"left": left, "right": right, "imu": imu}
    while any(cursors[k] < len(arrays[k]) for k in arrays):
        k = rng.choice(list(arrays))
        n = int(rng.integers(1, 30 if k == "imu" else 5000))
        chunk = arrays[k][cursors[k]:cursors[k] + n]
        cursors[k] += len(chunk)
        if k == "imu":
            odo.push_imu(chunk)
        else:
            odo.push_events(k, chunk)
    odo.finish(seq.end_ns)
    assert np.array_equal(odo.trajectory.t_ns, whole.t_ns)
    assert np.array_equal(odo.trajectory.position, whole.position)
    stats = odo.stats
    assert stats["events_processed"] == (len(left), len(right))
    assert stats["skipped_ticks"] == 0 and stats["maps"] > 5
    assert 0 < stats["latency_median_ms"] <= stats["latency_p99_ms"]


def test_evaluate_and_load_run(twin):
    sequence, run_dir = twin
    seq = aavio.open_sequence(sequence)
    trajectory = aavio.run(sequence)
    result = aavio.evaluate(trajectory, seq.ground_truth)
    cli = aavio.load_run(run_dir)
    summary = cli["summary"]
    assert result["ate_rmse_m"] == pytest.approx(summary["accuracy"]["ate_rmse_m"], rel=1e-6)
    assert result["ate_rmse_m"] < 0.05 and result["pairs"] == 150
    assert cli["map_points"].shape[1] == 3 and len(cli["map_points"]) > 1000
    assert "mapping:" in cli["config"]
    assert os.path.isdir(cli["depth_dir"])


def test_bad_input_raises_with_the_fix(twin, tmp_path):
    with pytest.raises(FileNotFoundError):
        aavio.open_sequence(str(tmp_path / "missing.yaml"))
    seq = aavio.open_sequence(twin[0])
    with pytest.raises(ValueError, match="mapping.rate_hz"):
        aavio.Odometry(seq.calibration, seq.start_ns, set={"mapping.rate_hz": -1})
    with pytest.raises(ValueError, match="did you mean"):
        aavio.run(twin[0], set=["mapping.rat_hz=10"])
    odo = aavio.Odometry(seq.calibration, seq.start_ns)
    events = np.zeros(2, dtype=aavio.EVENT_DTYPE)
    events["t_ns"] = [seq.start_ns + 2000, seq.start_ns + 1000]
    with pytest.raises(ValueError, match="left event at t = .* comes after"):
        odo.push_events("left", events)
    with pytest.raises(ValueError, match="'left' or 'right'"):
        odo.push_events("middle", events[:1])
    with pytest.raises(ValueError, match="packet_s"):
        next(iter(seq.packets(packet_s=0)))
    with pytest.raises(TypeError, match="a list of 'key=value' strings, got an item 1"):
        aavio.run(twin[0], set=[1, 2, 3])
    with pytest.raises(TypeError, match="the path of a TUM trajectory file, got None"):
        aavio.evaluate(None, None)
    with pytest.raises(ValueError, match="is a device, not a file"):
        aavio.read_trajectory("/dev/zero")


def test_without_numpy_the_import_error_names_it():
    # numpy made unimportable in a fresh interpreter: the error says what is missing and how to
    # install it, instead of pybind11's "initialization failed".
    code = "import sys; sys.modules['numpy'] = None; import aavio"
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                       env=dict(os.environ))
    assert r.returncode != 0
    assert "aavio needs numpy, which this Python (" in r.stderr, r.stderr
    assert "pip install numpy" in r.stderr and "python3-numpy" in r.stderr, r.stderr
