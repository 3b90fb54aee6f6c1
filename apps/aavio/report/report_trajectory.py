"""The trajectory figures of `aavio report`: views against the ground truth, the error along the
path, position and orientation against time, errors over distance, velocity."""
import numpy as np
from matplotlib.collections import LineCollection

from report_common import colour, plt, roll_pitch_yaw_deg, save


def evaluated(runs):
    return [(k, run) for k, run in enumerate(runs) if run.get("evaluation")]


def plot_views(runs, view, data_dir):
    """Top and side views of every run (aligned) against the ground truth."""
    fig, axes = plt.subplots(1, 2, figsize=(14, 6))
    first = True
    for k, run in evaluated(runs):
        ev = run["evaluation"]
        gt, est = view.apply(ev["positions_gt"]), view.apply(ev["positions_est_aligned"])
        for ax, (a, b) in ((axes[0], (0, 1)), (axes[1], (0, 2))):
            if first:
                ax.plot(gt[:, a], gt[:, b], "k--", lw=1.5, label="ground truth")
                ax.plot(gt[0, a], gt[0, b], "ko", ms=5)
            ax.plot(est[:, a], est[:, b], color=colour(k), lw=1.2,
                    label="%s (%s-aligned)" % (run["name"], ev["align"]))
        first = False
    for ax, (a, b), title in ((axes[0], (0, 1), "from above"), (axes[1], (0, 2), "from the side")):
        ax.set_title("%s (%s-%s)" % (title, view.names[a], view.names[b]))
        ax.set_xlabel(view.names[a] + " [m]")
        ax.set_ylabel(view.names[b] + " [m]")
        ax.set_aspect("equal", adjustable="datalim")
        ax.grid(alpha=0.3)
    axes[0].legend(fontsize=9)
    return save(fig, data_dir, "views.png")


def plot_error_along_path(runs, view, data_dir):
    """Each run's path from above, coloured by its absolute error (as evo_ape --plot does)."""
    shown = evaluated(runs)[:3]
    fig, axes = plt.subplots(1, len(shown), figsize=(7 * len(shown), 6), squeeze=False)
    for ax, (k, run) in zip(axes[0], shown):
        ev = run["evaluation"]
        gt, est = view.apply(ev["positions_gt"]), view.apply(ev["positions_est_aligned"])
        ate = np.asarray(ev["ate_m"], dtype=float)
        scale, unit = (100.0, "cm") if ate.max() < 1.0 else (1.0, "m")
        ax.plot(gt[:, 0], gt[:, 1], "--", color="0.6", lw=1.2, label="ground truth")
        segments = np.stack([est[:-1, :2], est[1:, :2]], axis=1)
        lines = LineCollection(segments, cmap="viridis", linewidths=2.5)
        lines.set_array(scale * 0.5 * (ate[:-1] + ate[1:]))
        ax.add_collection(lines)
        ax.plot(est[0, 0], est[0, 1], "ko", ms=5, label="start")
        bar = fig.colorbar(lines, ax=ax, shrink=0.85)
        bar.set_label("absolute translation error [%s]" % unit)
        ax.set_title("%s: error along the path (from above, ATE rmse %.3f m)" % (
            run["name"], ev["ate_rmse_m"]))
        ax.set_xlabel(view.names[0] + " [m]")
        ax.set_ylabel(view.names[1] + " [m]")
        ax.set_aspect("equal", adjustable="datalim")
        ax.autoscale_view()
        ax.grid(alpha=0.3)
        ax.legend(fontsize=9, loc="best")
    return save(fig, data_dir, "error_along_path.png")


def plot_against_time(runs, data_dir):
    """x, y, z and roll, pitch, yaw of every run (aligned) and of the ground truth."""
    fig, axes = plt.subplots(3, 2, figsize=(14, 8.5), sharex=True)
    first = True
    for k, run in evaluated(runs):
        ev = run["evaluation"]
        t = np.asarray(ev["t_s"])
        series = [(np.asarray(ev["positions_gt"]), np.asarray(ev["positions_est_aligned"])),
                  (roll_pitch_yaw_deg(ev["q_gt_xyzw"]), roll_pitch_yaw_deg(ev["q_est_aligned_xyzw"]))]
        for column, (truth, estimate) in enumerate(series):
            for i in range(3):
                ax = axes[i][column]
                if first:
                    ax.plot(t, truth[:, i], "k--", lw=1.2, label="ground truth")
                ax.plot(t, estimate[:, i], color=colour(k), lw=1.0, label=run["name"])
        first = False
    for i, name in enumerate("xyz"):
        axes[i][0].set_ylabel("%s [m]" % name)
    for i, name in enumerate(("roll (about x)", "pitch (about y)", "yaw (about z)")):
        axes[i][1].set_ylabel("%s [deg]" % name)
    for ax in axes.flat:
        ax.grid(alpha=0.3)
    for ax in axes[2]:
        ax.set_xlabel("time from the first scored pose [s]")
    axes[0][0].set_title("position in the ground truth's world (estimates aligned)")
    axes[0][1].set_title("orientation (Z-Y-X Euler angles of the camera in that world)")
    axes[0][0].legend(fontsize=9)
    return save(fig, data_dir, "against_time.png")


def plot_errors_over_distance(runs, data_dir):
    """Relative errors over sub-trajectories of fixed length, and the absolute error in time."""
    fig, axes = plt.subplots(1, 3, figsize=(16, 4.8))
    width = 0.8 / max(1, len(runs))
    for k, run in evaluated(runs):
        ev = run["evaluation"]
        lengths = [r["length_m"] for r in ev["relative"]]
        for ax, key in ((axes[0], "trans_pct"), (axes[1], "rot_deg_per_m")):
            data = [r[key] if r[key] else [0.0] for r in ev["relative"]]
            pos = [i + (k - (len(runs) - 1) / 2) * width for i in range(len(lengths))]
            boxes = ax.boxplot(data, positions=pos, widths=width * 0.9, patch_artist=True,
                               showfliers=False)
            for box in boxes["boxes"]:
                box.set_facecolor(colour(k))
                box.set_alpha(0.6)
            ax.set_xticks(range(len(lengths)))
            ax.set_xticklabels(["%.2g" % l for l in lengths])
            ax.set_xlabel("sub-trajectory length [m]")
            ax.grid(alpha=0.3)
        axes[2].plot(ev["t_s"], ev["ate_m"], color=colour(k), lw=1.0, label=run["name"])
    axes[0].set_ylabel("relative translation error [%]")
    axes[0].set_title("translation error over distance")
    axes[1].set_ylabel("relative rotation error [deg/m]")
    axes[1].set_title("rotation error over distance")
    axes[2].set_xlabel("time from the first scored pose [s]")
    axes[2].set_ylabel("absolute translation error [m]")
    axes[2].set_title("absolute error against time")
    axes[2].grid(alpha=0.3)
    axes[2].legend(fontsize=9)
    return save(fig, data_dir, "errors_over_distance.png")


def velocity_series(ev, key):
    return np.array([v if v is not None else [np.nan] * 3 for v in ev[key]], dtype=float)


def plot_velocity(runs, data_dir):
    """Speed against time, and the velocity error (camera frame, as EvSLAM scores it)."""
    fig, axes = plt.subplots(1, 2, figsize=(14, 4.5), sharex=True)
    first = True
    for k, run in evaluated(runs):
        ev = run["evaluation"]
        t = np.asarray(ev["t_s"])
        v_gt, v_est = velocity_series(ev, "v_gt_body_mps"), velocity_series(ev, "v_est_body_mps")
        if first:
            axes[0].plot(t, np.linalg.norm(v_gt, axis=1), "k--", lw=1.2, label="ground truth")
        first = False
        auc = (ev.get("velocity") or {}).get("auc")
        axes[0].plot(t, np.linalg.norm(v_est, axis=1), color=colour(k), lw=1.0, label=run["name"])
        axes[1].plot(t, np.linalg.norm(v_est - v_gt, axis=1), color=colour(k), lw=1.0,
                     label="%s (EvSLAM AUC %s)" % (run["name"], "%.3f" % auc if auc else "-"))
    axes[0].set_ylabel("speed [m/s]")
    axes[0].set_title("speed of the camera")
    axes[1].set_ylabel("|v_est - v_gt| [m/s]")
    axes[1].set_title("velocity error (camera frame)")
    for ax in axes:
        ax.set_xlabel("time from the first scored pose [s]")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=9)
    return save(fig, data_dir, "velocity.png")
