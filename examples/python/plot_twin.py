#!/usr/bin/env python3
"""Simulates a twin, runs the odometry on it from Python, evaluates it and plots the estimate
against the ground truth (top view and per-axis), with the events of one moment.

  PYTHONPATH=build/python python3 examples/python/plot_twin.py --out out/python_twin

With --trajectory FILE.txt (TUM) and --preset rpg|dsec|mvsec|tum_vie|vector the twin follows a
recorded camera path."""
import argparse
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import aavio  # noqa: E402


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--out", default="out/python_twin")
    parser.add_argument("--preset", default="mini")
    parser.add_argument("--trajectory", default="")
    parser.add_argument("--duration", type=float, default=3.0)
    parser.add_argument("--seed", type=int, default=1)
    args = parser.parse_args()

    sequence = aavio.simulate(os.path.join(args.out, "sequence"), preset=args.preset, seed=args.seed,
                              duration_s=args.duration, trajectory=args.trajectory, overwrite=True)
    seq = aavio.open_sequence(sequence)
    print("sequence %s: %.1f s, %dx%d px, baseline %.3f m" % (
        sequence, seq.duration_s, seq.rig["width"], seq.rig["height"], seq.rig["baseline_m"]))

    estimate = aavio.run(sequence)
    result = aavio.evaluate(estimate, seq.ground_truth)
    print("%d poses, %d tracked; ATE %.2f cm (%.2f %% of the path)" % (
        len(estimate), estimate.status.count("ok"), 100 * result["ate_rmse_m"], result["ate_percent_of_path"]))
    estimate.write(os.path.join(args.out, "trajectory.txt"))

    truth = aavio.read_trajectory(seq.ground_truth)
    # The estimate starts at the identity: express the truth in its first camera frame.
    t0 = np.searchsorted(truth.t_ns, estimate.t_ns[0])
    p_truth = truth.position - truth.position[t0]
    q = truth.quaternion[t0]
    R0 = quaternion_matrix(q)
    p_truth = p_truth @ R0  # R0^T p for each row
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.5))
    axes[0].plot(p_truth[:, 0], p_truth[:, 2], "k-", label="ground truth")
    axes[0].plot(estimate.position[:, 0], estimate.position[:, 2], "r-", label="aavio")
    axes[0].set_xlabel("x [m]"), axes[0].set_ylabel("z [m]"), axes[0].axis("equal"), axes[0].legend()
    axes[0].set_title("top view (first camera frame)")
    for k, name in enumerate("xyz"):
        axes[1].plot(truth.t_s - estimate.t_s[0], p_truth[:, k], "k-", lw=0.8)
        axes[1].plot(estimate.t_s - estimate.t_s[0], estimate.position[:, k], "-", label=name)
    axes[1].set_xlim(0, estimate.t_s[-1] - estimate.t_s[0]), axes[1].set_xlabel("t [s]"), axes[1].legend()
    axes[1].set_title("position (black: ground truth)")
    left, _, _ = seq.read(start_s=seq.duration_s / 2, duration_s=0.02)
    image = np.zeros((seq.rig["height"], seq.rig["width"]))
    np.add.at(image, (left["y"], left["x"]), np.where(left["polarity"] == 1, 1.0, -1.0))
    axes[2].imshow(image, cmap="bwr", vmin=-3, vmax=3)
    axes[2].set_title("left events, 20 ms at t = %.1f s" % (seq.duration_s / 2))
    fig.tight_layout()
    path = os.path.join(args.out, "twin.png")
    fig.savefig(path, dpi=100)
    print("wrote", path)


def quaternion_matrix(q):
    x, y, z, w = q
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                     [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                     [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])


if __name__ == "__main__":
    main()
