"""The depth figures of `aavio report`: depth maps beside the ground truth and their error, the
depth error against true depth and edge kind, and the global map from above."""
import os
import sys

import numpy as np

from report_common import colour, plt, run_view, save

DISCONTINUITY, HORIZONTAL = 1, 2  # eval::ScoredDepthPoint::kind bits


def read_image(data_dir, frame, key):
    path = os.path.join(data_dir, frame[key])
    return np.fromfile(path, dtype=np.float32).reshape(frame["height"], frame["width"])


def plot_depth_maps(run, data_dir, name):
    """Rows of (estimate, ground truth, error) for a few depth maps of one run, one depth scale
    per row."""
    frames = ((run.get("depth") or {}).get("frames")) or []
    if not frames:
        return None
    aspect = frames[0]["height"] / frames[0]["width"]
    fig, axes = plt.subplots(len(frames), 3, figsize=(18, 5.2 * aspect * len(frames) + 0.8),
                             squeeze=False, layout="constrained")
    for row, frame in zip(axes, frames):
        estimate, truth = read_image(data_dir, frame, "estimate"), read_image(data_dir, frame, "truth")
        valid = truth[np.isfinite(truth)]
        lo, hi = (np.percentile(valid, [2, 98]) if valid.size else (0.5, 5.0))
        ys, xs = np.nonzero(np.isfinite(estimate))
        error = np.asarray(frame["error_m"], dtype=float)
        limit = max(np.percentile(np.abs(error), 95), 1e-3) if error.size else 0.1
        t = frame["t_ns"] * 1e-9
        for ax in row:
            ax.set_facecolor("0.12")
            ax.set_xlim(-0.5, frame["width"] - 0.5)
            ax.set_ylim(frame["height"] - 0.5, -0.5)
            ax.set_aspect("equal")
            ax.set_xticks([])
            ax.set_yticks([])
        shown = row[0].scatter(xs, ys, c=estimate[ys, xs], cmap="turbo_r", vmin=lo, vmax=hi, s=3,
                               marker="s", linewidths=0)
        row[0].set_title("estimate at %.2f s (%d pixels with depth)" % (t, len(xs)), fontsize=11)
        row[1].imshow(truth, cmap="turbo_r", vmin=lo, vmax=hi, interpolation="nearest")
        row[1].set_title("ground truth (frame %.3f s)" % (frame["truth_t_ns"] * 1e-9), fontsize=11)
        bar = fig.colorbar(shown, ax=row[:2].tolist(), shrink=0.9, pad=0.01)
        bar.set_label("depth [m]")
        errors = row[2].scatter(frame["u"], frame["v"], c=error, cmap="RdBu_r", vmin=-limit,
                                vmax=limit, s=3, marker="s", linewidths=0)
        row[2].set_title("error of the points scored on this frame (%d)" % len(error), fontsize=11)
        bar = fig.colorbar(errors, ax=row[2], shrink=0.9, pad=0.01)
        bar.set_label("estimate - truth [m] (red: too far)")
    fig.suptitle("%s: depth maps (left camera) beside the ground truth" % run["name"], fontsize=13)
    path = os.path.join(data_dir, name)
    fig.savefig(path, dpi=90)
    plt.close(fig)
    return path


def plot_depth_errors(runs, data_dir):
    """Relative depth error against true depth, and by edge kind."""
    scored = [(k, run) for k, run in enumerate(runs)
              if ((run.get("depth") or {}).get("points") or {}).get("z_gt_m")]
    if not scored:
        return None
    fig, axes = plt.subplots(1, 2, figsize=(15, 4.8))
    for k, run in scored:
        points = run["depth"]["points"]
        z_gt, z_est = np.asarray(points["z_gt_m"]), np.asarray(points["z_est_m"])
        relative = 100.0 * np.abs(z_est - z_gt) / z_gt
        edges = np.unique(np.percentile(z_gt, np.linspace(0, 100, 13)))
        centres, median, q25, q75 = [], [], [], []
        for a, b in zip(edges[:-1], edges[1:]):
            inside = relative[(z_gt >= a) & (z_gt <= b)]
            if inside.size >= 20:
                centres.append(0.5 * (a + b))
                q25.append(np.percentile(inside, 25))
                median.append(np.median(inside))
                q75.append(np.percentile(inside, 75))
        axes[0].plot(centres, median, "o-", color=colour(k), label="%s (median)" % run["name"])
        axes[0].fill_between(centres, q25, q75, color=colour(k), alpha=0.2)
        kind = np.asarray(points["kind"], dtype=int)
        groups = [("on a depth discontinuity", (kind & DISCONTINUITY) != 0, ":"),
                  ("near-horizontal edge", ((kind & HORIZONTAL) != 0) & ((kind & DISCONTINUITY) == 0),
                   "--"),
                  ("other edges", kind == 0, "-")]
        for label, mask, style in groups:
            if mask.sum() >= 20:
                axes[1].hist(relative[mask], bins=60, range=(0, 30), histtype="step", density=True,
                             lw=1.5, ls=style, color=colour(k),
                             label="%s, %s: %d points, mean %.1f %%" % (
                                 run["name"], label, mask.sum(), relative[mask].mean()))
    axes[0].set_xlabel("true depth [m] (bins of equal point count)")
    axes[0].set_ylabel("|estimate - truth| / truth [%]")
    axes[0].set_title("depth error against true depth (band: quartiles)")
    axes[1].set_xlabel("|estimate - truth| / truth [%] (over 30 % not drawn)")
    axes[1].set_ylabel("density")
    axes[1].set_title("depth error by the kind of edge the point lies on")
    for ax in axes:
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    return save(fig, data_dir, "depth_errors.png")


def read_ply(path):
    """map.ply as aavio writes it (binary little endian, float xyz + uchar rgb)."""
    with open(path, "rb") as f:
        vertices = 0
        while True:
            line = f.readline()
            if not line:
                return None
            line = line.decode("ascii", "replace").strip()
            if line.startswith("element vertex"):
                vertices = int(line.split()[2])
            if line == "end_header":
                break
        dtype = np.dtype([("x", "<f4"), ("y", "<f4"), ("z", "<f4"), ("r", "u1"), ("g", "u1"),
                          ("b", "u1")])
        return np.frombuffer(f.read(vertices * dtype.itemsize), dtype=dtype, count=vertices)


def read_positions(path):
    positions = []
    with open(path) as f:
        for line in f:
            fields = line.replace(",", " ").split()
            if len(fields) >= 4 and not line.startswith("#"):
                positions.append([float(v) for v in fields[1:4]])
    return np.array(positions, dtype=float).reshape(-1, 3)


def plot_map_from_above(runs, data_dir):
    """Each run's global map (map.ply) from above, coloured by height, with its trajectory."""
    shown = []
    for run in runs[:3]:
        ply = os.path.join(run["dir"], "map.ply")
        try:
            cloud = read_ply(ply) if os.path.exists(ply) else None
        except (OSError, ValueError) as e:  # a damaged map.ply costs this figure, not the report
            print("plot_report.py: %s: %s; the map is not drawn" % (ply, e), file=sys.stderr)
            cloud = None
        if cloud is not None and len(cloud) > 0:
            shown.append((run, cloud))
    if not shown:
        return None, ""
    fig, axes = plt.subplots(1, len(shown), figsize=(7.5 * len(shown), 6.5), squeeze=False)
    conventions = []
    for ax, (run, cloud) in zip(axes[0], shown):
        view = run_view(run)
        conventions.append("%s: %s" % (run["name"], view.how))
        xyz = view.apply(np.stack([cloud["x"], cloud["y"], cloud["z"]], axis=1))
        if len(xyz) > 200000:
            xyz = xyz[np.linspace(0, len(xyz) - 1, 200000).astype(int)]
        lo, hi = np.percentile(xyz[:, 2], [2, 98])
        points = ax.scatter(xyz[:, 0], xyz[:, 1], c=xyz[:, 2], cmap="viridis", vmin=lo, vmax=hi,
                            s=0.4 if len(xyz) > 50000 else 2.0, linewidths=0)
        bar = fig.colorbar(points, ax=ax, shrink=0.85)
        bar.set_label("%s [m]" % view.names[2])
        path = os.path.join(run["dir"], "stamped_traj_estimate.txt")
        trajectory = view.apply(read_positions(path)) if os.path.exists(path) else None
        if trajectory is not None and len(trajectory):
            ax.plot(trajectory[:, 0], trajectory[:, 1], "k-", lw=1.2, label="estimated trajectory")
            ax.plot(trajectory[0, 0], trajectory[0, 1], "ko", ms=5)
            ax.legend(fontsize=9, loc="upper right")
        ax.set_title("%s: map.ply from above (%d points)" % (run["name"], len(cloud)))
        ax.set_xlabel(view.names[0] + " [m]")
        ax.set_ylabel(view.names[1] + " [m]")
        ax.set_aspect("equal", adjustable="datalim")
        ax.grid(alpha=0.3)
    return save(fig, data_dir, "map_from_above.png"), "; ".join(conventions)
