"""aavio report: plots and a self-contained report.html from the data `aavio report` gathered.

Run by `aavio report` (which embeds this file) as
    python3 plot_report.py DATA_DIR OUT_HTML
DATA_DIR holds run_<i>.json (one per run: name, its folder, summary.json, evaluation, aligned
positions, relative errors, depth errors) and timings_<i>.csv; the depth pictures, map.ply and
the trajectory are read from the run folders. Plots go to DATA_DIR/*.png, and report.html embeds
them (base64), so the html file alone is the report. Headless: matplotlib's Agg backend.
"""
import base64
import csv
import html
import json
import os
import sys

import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

COLOURS = ["tab:blue", "tab:orange", "tab:green", "tab:red", "tab:purple", "tab:brown"]
STAGES = ["time_surface", "ts_derived", "aa_map", "sampling", "tracking", "matching", "depth_refinement",
          "fusion", "mapping_total"]


def load_runs(data_dir):
    runs, i = [], 0
    while os.path.exists(os.path.join(data_dir, "run_%d.json" % i)):
        with open(os.path.join(data_dir, "run_%d.json" % i)) as f:
            run = json.load(f)
        run["timings"] = []
        path = os.path.join(data_dir, "timings_%d.csv" % i)
        if os.path.exists(path):
            with open(path) as f:
                run["timings"] = list(csv.DictReader(f))
        runs.append(run)
        i += 1
    return runs


def save(fig, data_dir, name):
    path = os.path.join(data_dir, name)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def plot_trajectories(runs, data_dir):
    fig, axes = plt.subplots(1, 2, figsize=(12, 5.5))
    gt_drawn = False
    # The world frame may be z-up (motion capture) or the first camera's (y down, z forward): the
    # top view is the plane of the ground truth's two largest extents, the side view the largest
    # against the smallest.
    first = next(r["evaluation"]["positions_gt"] for r in runs if r.get("evaluation"))
    extent = [max(p[i] for p in first) - min(p[i] for p in first) for i in range(3)]
    order = sorted(range(3), key=lambda i: -extent[i])
    top, side = (order[0], order[1]), (order[0], order[2])
    for k, run in enumerate(runs):
        ev = run.get("evaluation")
        if not ev:
            continue
        gt, est = ev["positions_gt"], ev["positions_est_aligned"]
        for ax, (a, b), title in ((axes[0], top, "top view (%s-%s)" % ("xyz"[top[0]], "xyz"[top[1]])),
                                  (axes[1], side, "side view (%s-%s)" % ("xyz"[side[0]], "xyz"[side[1]]))):
            if not gt_drawn:
                ax.plot([p[a] for p in gt], [p[b] for p in gt], "k--", lw=1.5, label="ground truth")
            ax.plot([p[a] for p in est], [p[b] for p in est], color=COLOURS[k % 6], lw=1.2,
                    label="%s (%s-aligned)" % (run["name"], ev["align"]))
            ax.set_title(title)
            ax.set_xlabel("xyz"[a] + " [m]")
            ax.set_ylabel("xyz"[b] + " [m]")
            ax.set_aspect("equal", adjustable="datalim")
            ax.grid(alpha=0.3)
        gt_drawn = True
    axes[0].legend(fontsize=8)
    return save(fig, data_dir, "trajectory.png")


def plot_errors_over_distance(runs, data_dir):
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.5))
    width = 0.8 / max(1, len(runs))
    for k, run in enumerate(runs):
        ev = run.get("evaluation")
        if not ev:
            continue
        lengths = [r["length_m"] for r in ev["relative"]]
        for ax, key in ((axes[0], "trans_pct"), (axes[1], "rot_deg_per_m")):
            data = [r[key] if r[key] else [0.0] for r in ev["relative"]]
            pos = [i + (k - (len(runs) - 1) / 2) * width for i in range(len(lengths))]
            bp = ax.boxplot(data, positions=pos, widths=width * 0.9, patch_artist=True,
                            showfliers=False)
            for box in bp["boxes"]:
                box.set_facecolor(COLOURS[k % 6])
                box.set_alpha(0.6)
            ax.set_xticks(range(len(lengths)))
            ax.set_xticklabels(["%.1f" % l for l in lengths])
            ax.set_xlabel("distance travelled [m]")
            ax.grid(alpha=0.3)
        axes[2].plot(ev["distance_m"], ev["ate_m"], color=COLOURS[k % 6], label=run["name"])
    axes[0].set_ylabel("relative translation error [%]")
    axes[0].set_title("translation error over distance")
    axes[1].set_ylabel("relative rotation error [deg/m]")
    axes[1].set_title("rotation error over distance")
    axes[2].set_xlabel("distance travelled [m]")
    axes[2].set_ylabel("absolute translation error [m]")
    axes[2].set_title("ATE along the path")
    axes[2].grid(alpha=0.3)
    axes[2].legend(fontsize=8)
    return save(fig, data_dir, "errors_over_distance.png")


def plot_depth(runs, data_dir):
    if not any(run.get("depth_relative_errors") for run in runs):
        return None
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for k, run in enumerate(runs):
        rel = run.get("depth_relative_errors")
        if rel:
            ax.hist([100.0 * r for r in rel], bins=60, range=(0, 30), histtype="step", lw=1.5,
                    color=COLOURS[k % 6], density=True,
                    label="%s (mean %.2f %%)" % (run["name"], 100.0 * run["depth"]["relative"]))
    ax.set_xlabel("relative depth error |dz| / z [%] (values > 30 % not drawn)")
    ax.set_ylabel("density")
    ax.set_title("depth error against ground truth")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    return save(fig, data_dir, "depth_error.png")


STATUS_COLOURS = {"ok": "tab:green", "lost": "tab:red", "no_map": "0.75"}


def depth_pictures(run, count):
    """Up to `count` evenly spaced (time [s], path) of a run's depth/inverse_depth_*.png."""
    depth_dir = os.path.join(run["dir"], "depth")
    stamps = os.path.join(depth_dir, "timestamps.txt")
    if not os.path.exists(stamps):
        return []
    entries = []
    with open(stamps) as f:
        for line in f:
            fields = line.split()
            if len(fields) == 2 and not line.startswith("#"):
                path = os.path.join(depth_dir, "inverse_depth_%s.png" % fields[1])
                if os.path.exists(path):
                    entries.append((float(fields[0]), path))
    if len(entries) <= count:
        return entries
    return [entries[round(i * (len(entries) - 1) / (count - 1))] for i in range(count)]


def plot_depth_pictures(runs, data_dir):
    rows = [(run, depth_pictures(run, 5)) for run in runs[:3]]
    rows = [(run, pictures) for run, pictures in rows if pictures]
    if not rows:
        return None
    columns = max(len(p) for _, p in rows)
    fig, axes = plt.subplots(len(rows), columns, figsize=(3.2 * columns, 2.6 * len(rows)),
                             squeeze=False)
    for r, (run, pictures) in enumerate(rows):
        t0 = pictures[0][0]
        for c in range(columns):
            ax = axes[r][c]
            ax.axis("off")
            if c < len(pictures):
                ax.imshow(plt.imread(pictures[c][1]))
                ax.set_title("%s  %.1f s" % (run["name"], pictures[c][0] - t0), fontsize=8)
    return save(fig, data_dir, "depth_maps.png")


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
    return np.array(positions).reshape(-1, 3)


def plot_map_from_above(runs, data_dir):
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
        return None
    fig, axes = plt.subplots(1, len(shown), figsize=(6.5 * len(shown), 6), squeeze=False)
    for ax, (run, cloud) in zip(axes[0], shown):
        xyz = np.stack([cloud["x"], cloud["y"], cloud["z"]], axis=1)
        rgb = np.stack([cloud["r"], cloud["g"], cloud["b"]], axis=1) / 255.0
        if len(xyz) > 200000:
            keep = np.linspace(0, len(xyz) - 1, 200000).astype(int)
            xyz, rgb = xyz[keep], rgb[keep]
        trajectory_path = os.path.join(run["dir"], "stamped_traj_estimate.txt")
        trajectory = read_positions(trajectory_path) if os.path.exists(trajectory_path) else None
        # The world of the odometry is its first camera's frame (x right, y down, z forward): seen
        # from above is x-z. Runs in the ground truth's world: the plane of its two largest extents.
        if run["summary"].get("mode") in ("full", "esvo") or trajectory is None:
            a, b = 0, 2
        else:
            extent = trajectory.max(axis=0) - trajectory.min(axis=0)
            a, b = sorted(np.argsort(-extent)[:2])
        ax.scatter(xyz[:, a], xyz[:, b], c=rgb, s=0.3 if len(xyz) > 50000 else 2.0, linewidths=0)
        if trajectory is not None and len(trajectory):
            ax.plot(trajectory[:, a], trajectory[:, b], "k-", lw=1.2, label="estimated trajectory")
            ax.plot(trajectory[0, a], trajectory[0, b], "ko", ms=4)
            ax.legend(fontsize=8, loc="upper right")
        ax.set_title("%s: map.ply from above (%d points; red near, blue far)" % (run["name"], len(cloud)),
                     fontsize=9)
        ax.set_xlabel("xyz"[a] + " [m]")
        ax.set_ylabel("xyz"[b] + " [m]")
        ax.set_aspect("equal", adjustable="datalim")
        ax.grid(alpha=0.3)
    return save(fig, data_dir, "map_from_above.png")


def plot_strips(runs, data_dir):
    timed = [run for run in runs if run["timings"]]
    if not timed:
        return None
    fig, axes = plt.subplots(3, 1, figsize=(14, 6.5), sharex=True,
                             gridspec_kw={"height_ratios": [3, 0.5 + 0.5 * len(timed), 3]})
    for k, run in enumerate(timed):
        rows = run["timings"]
        t0 = float(rows[0]["t_s"])
        t = np.array([float(r["t_s"]) - t0 for r in rows])
        if "events" in rows[0]:
            events = np.array([float(r["events"]) for r in rows])
            dt = np.diff(np.concatenate([[t[0] - (t[1] - t[0] if len(t) > 1 else 0.01)], t]))
            axes[0].plot(t, events / np.maximum(dt, 1e-6) / 1e6, color=COLOURS[k % 6], lw=0.8,
                         label=run["name"])
        # The tracking status of each tick, one band per run.
        for status, colour in STATUS_COLOURS.items():
            ticks = [ti for ti, r in zip(t, rows) if r["status"] == status]
            width = (t[1] - t[0]) if len(t) > 1 else 0.01
            axes[1].broken_barh([(ti - width / 2, width) for ti in ticks], (k - 0.4, 0.8),
                                color=colour, label=status if k == 0 else None)
        # A tick lists the map it published; tracking uses that map until the next one.
        published = [float(r["map_points"]) for r in rows]
        in_use, current = [], 0.0
        for n in published:
            current = n if n > 0 else current
            in_use.append(current)
        axes[2].step(t, in_use, where="post", color=COLOURS[k % 6], lw=0.8, label=run["name"])
    axes[0].set_ylabel("events [M/s]")
    axes[0].set_title("event rate (both cameras), tracking status and map size over time")
    axes[0].grid(alpha=0.3)
    axes[0].legend(fontsize=8, loc="upper right")
    axes[1].set_yticks(range(len(timed)))
    axes[1].set_yticklabels([run["name"] for run in timed], fontsize=8)
    axes[1].set_ylim(-0.6, len(timed) - 0.4)
    axes[1].legend(fontsize=7, loc="lower left", bbox_to_anchor=(1.0, 0.0), frameon=False)
    axes[2].set_ylabel("points of the map tracked")
    axes[2].set_xlabel("data time [s]")
    axes[2].grid(alpha=0.3)
    return save(fig, data_dir, "strips.png")


def plot_timing(runs, data_dir):
    fig, axes = plt.subplots(1, 2, figsize=(14, 4.5))
    width = 0.8 / max(1, len(runs))
    for k, run in enumerate(runs):
        stages = run["summary"].get("stages", {})
        med = [stages.get(s, {}).get("median_ms", 0.0) for s in STAGES]
        p95 = [stages.get(s, {}).get("p95_ms", 0.0) for s in STAGES]
        pos = [i + (k - (len(runs) - 1) / 2) * width for i in range(len(STAGES))]
        axes[0].bar(pos, med, width * 0.9, color=COLOURS[k % 6], alpha=0.8, label=run["name"])
        axes[0].errorbar(pos, med, yerr=[[0] * len(med), [max(0.0, p - m) for p, m in zip(p95, med)]],
                         fmt="none", ecolor="k", capsize=2, lw=0.8)
        rows = run["timings"]
        if rows:
            t0 = float(rows[0]["t_s"])
            total = [float(r["time_surface_ms"]) + float(r["aa_ms"]) + float(r["sampling_ms"]) +
                     float(r["tracking_ms"]) + float(r["mapping_ms"]) for r in rows]
            axes[1].plot([float(r["t_s"]) - t0 for r in rows], total, color=COLOURS[k % 6], lw=0.7,
                         label=run["name"])
    axes[0].set_xticks(range(len(STAGES)))
    axes[0].set_xticklabels(STAGES, rotation=25, ha="right")
    axes[0].set_ylabel("ms (bar: median, whisker: p95)")
    axes[0].set_title("time per stage")
    axes[0].grid(axis="y", alpha=0.3)
    axes[0].legend(fontsize=8)
    axes[1].set_xlabel("data time [s]")
    axes[1].set_ylabel("ms per tick (all stages)")
    axes[1].set_title("processing time per tick")
    axes[1].grid(alpha=0.3)
    return save(fig, data_dir, "timing.png")


def fmt(value, spec):
    return "–" if value is None else spec % value


def summary_table(runs):
    head = ("run", "mode", "data [s]", "RTF", "ok / lost", "ATE [m]", "ATE [% path]",
            "RPE t [%]", "RPE R [deg/m]", "depth mean [m]", "depth rel. [%]", "completeness [%]",
            "peak RSS [MB]")
    rows = []
    for run in runs:
        s, ev, d = run["summary"], run.get("evaluation") or {}, run.get("depth") or {}
        status = s.get("status", {})
        rows.append((run["name"], s.get("mode", "?"), fmt(s.get("data_duration_s"), "%.2f"),
                     fmt(s.get("real_time_factor"), "%.2f"),
                     "%d / %d" % (status.get("ok", 0), status.get("lost", 0)),
                     fmt(ev.get("ate_rmse_m"), "%.4f"), fmt(ev.get("ate_percent_of_path"), "%.2f"),
                     fmt(ev.get("rpe_trans_pct"), "%.3f"), fmt(ev.get("rpe_rot_deg_per_m"), "%.4f"),
                     fmt(d.get("mean_m"), "%.3f"),
                     fmt(100.0 * d["relative"] if d else None, "%.2f"),
                     fmt(100.0 * d["completeness"] if d else None, "%.1f"),
                     fmt(s.get("peak_rss_mb"), "%.0f")))
    out = "<table><tr>" + "".join("<th>%s</th>" % html.escape(h) for h in head) + "</tr>\n"
    for r in rows:
        out += "<tr>" + "".join("<td>%s</td>" % html.escape(str(c)) for c in r) + "</tr>\n"
    return out + "</table>\n"


def embed(path, alt):
    if not path:
        return ""
    with open(path, "rb") as f:
        data = base64.b64encode(f.read()).decode("ascii")
    return '<figure><img alt="%s" src="data:image/png;base64,%s"><figcaption>%s</figcaption></figure>\n' % (
        html.escape(alt), data, html.escape(alt))


def main():
    data_dir, out_html = sys.argv[1], sys.argv[2]
    runs = load_runs(data_dir)
    if not runs:
        sys.exit("plot_report.py: no run_0.json in " + data_dir)
    figures = [
        (plot_trajectories(runs, data_dir) if any(r.get("evaluation") for r in runs) else None,
         "Estimated trajectories (aligned) against ground truth"),
        (plot_errors_over_distance(runs, data_dir) if any(r.get("evaluation") for r in runs) else None,
         "Relative errors over sub-trajectories of fixed distance (rpg_trajectory_evaluation), "
         "and the absolute error along the path"),
        (plot_depth_pictures(runs, data_dir),
         "Depth maps over the time surface they were made on (depth/inverse_depth_*.png; red "
         "near, blue far)"),
        (plot_map_from_above(runs, data_dir), "The global map (map.ply) seen from above, with the "
         "estimated trajectory"),
        (plot_strips(runs, data_dir), "Event rate, tracking status per tick and map size over time"),
        (plot_depth(runs, data_dir), "Relative depth error of the runs' depth maps"),
        (plot_timing(runs, data_dir), "Runtime per stage and per tick"),
    ]
    parts = ["<!DOCTYPE html>\n<html><head><meta charset='utf-8'><title>aavio report</title>",
             "<style>body{font-family:sans-serif;margin:2em;max-width:1400px}"
             "table{border-collapse:collapse;font-size:0.9em}td,th{border:1px solid #bbb;"
             "padding:3px 8px;text-align:right}th{background:#eee}img{max-width:100%}"
             "figure{margin:1.5em 0}figcaption{color:#555}</style></head><body>",
             "<h1>aavio report</h1>",
             "<p>%s</p>" % html.escape(", ".join("%s: %s" % (r["name"], r["dir"]) for r in runs)),
             summary_table(runs)]
    for run in runs:
        parts.append("<p><b>%s</b>: %s; sequence %s</p>" % (
            html.escape(run["name"]), html.escape(run["summary"].get("version", "")),
            html.escape(str(run["summary"].get("sequence", "")))))
    for path, caption in figures:
        parts.append(embed(path, caption))
    parts.append("<p>Definitions: docs/evaluation.md of aavio.</p></body></html>\n")
    with open(out_html, "w") as f:
        f.write("\n".join(parts))
    print("wrote %s (%d run(s), %d figure(s))" % (out_html, len(runs),
                                                  sum(1 for p, _ in figures if p)))


if __name__ == "__main__":
    main()
