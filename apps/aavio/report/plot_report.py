"""aavio report: one html file, its figures embedded, from the data `aavio report` gathered.

Run by `aavio report` (which embeds this file and its report_*.py modules) as
    python3 plot_report.py DATA_DIR OUT_HTML
DATA_DIR holds run_<i>.json (one per run: name, folder, summary.json, config.yaml as key-value
pairs, the evaluation with aligned poses, velocities and errors, depth errors point by point and a
few depth maps as run_<i>_*.f32 float images) and timings_<i>.csv. The figures are drawn there
(matplotlib, Agg) and embedded in OUT_HTML as base64: the html file alone is the report.
"""
import base64
import csv
import html
import json
import os
import sys

from report_common import truth_view
from report_depth import plot_depth_errors, plot_depth_maps, plot_map_from_above
from report_run import plot_imu, plot_strips, plot_timing
from report_trajectory import (plot_against_time, plot_error_along_path, plot_errors_over_distance,
                               plot_velocity, plot_views)


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


def fmt(value, spec):
    return "-" if value is None else spec % value


def imu_of(run):
    config = run.get("config", {})
    mode = config.get("imu.mode", "?")
    if mode == "off":
        return "off"
    return "%s (bias %s)" % (mode, config.get("imu.bias_mode", "?"))


def table(head, rows):
    out = ('<div class="wide"><table><tr>' + "".join("<th>%s</th>" % html.escape(h) for h in head) +
           "</tr>\n")
    for r in rows:
        out += "<tr>" + "".join("<td>%s</td>" % html.escape(str(c)) for c in r) + "</tr>\n"
    return out + "</table></div>\n"


def summary_table(runs):
    head = ("run", "mode", "IMU", "data [s]", "real-time factor", "ticks ok / lost", "ATE [m]",
            "ATE [% of path]", "rotation [deg]", "RPE t [%]", "RPE R [deg/m]", "velocity AUC",
            "depth error [m]", "depth error [%]", "completeness [%]", "peak memory [MB]")
    rows = []
    for run in runs:
        s, ev = run["summary"], run.get("evaluation") or {}
        d = (run.get("depth") or {}).get("summary") or {}
        status = s.get("status", {})
        rows.append((run["name"], s.get("mode", "?"), imu_of(run), fmt(s.get("data_duration_s"), "%.2f"),
                     fmt(s.get("real_time_factor"), "%.2f"),
                     "%d / %d" % (status.get("ok", 0), status.get("lost", 0)),
                     fmt(ev.get("ate_rmse_m"), "%.4f"), fmt(ev.get("ate_percent_of_path"), "%.2f"),
                     fmt(ev.get("ate_rot_rmse_orientation_aligned_deg"), "%.2f"),
                     fmt(ev.get("rpe_trans_pct"), "%.3f"), fmt(ev.get("rpe_rot_deg_per_m"), "%.4f"),
                     fmt((ev.get("velocity") or {}).get("auc"), "%.3f"),
                     fmt(d.get("mean_m"), "%.3f"),
                     fmt(100.0 * d["relative"] if "relative" in d else None, "%.2f"),
                     fmt(100.0 * d["completeness"] if "completeness" in d else None, "%.1f"),
                     fmt(s.get("peak_rss_mb"), "%.0f")))
    return table(head, rows)


def config_differences(runs):
    """The configuration keys whose values differ between the runs."""
    if len(runs) < 2:
        return ""
    keys = sorted(set().union(*(run.get("config", {}).keys() for run in runs)))
    rows = []
    for key in keys:
        values = [run.get("config", {}).get(key, "-") for run in runs]
        if len(set(values)) > 1:
            rows.append([key] + values)
    if not rows:
        return "<p>The runs' configurations (config.yaml) are the same.</p>\n"
    return ("<h2>Configuration differences</h2>\n<p>The keys of config.yaml whose values differ "
            "between the runs (%d of %d keys).</p>\n" % (len(rows), len(keys)) +
            table(["key"] + [run["name"] for run in runs], rows))


def embed(path, caption):
    if not path:
        return ""
    with open(path, "rb") as f:
        data = base64.b64encode(f.read()).decode("ascii")
    return ('<figure><img alt="%s" src="data:image/png;base64,%s"><figcaption>%s</figcaption>'
            "</figure>\n" % (html.escape(caption), data, html.escape(caption)))


def figures(runs, data_dir):
    """(section, path, caption) of every figure the runs' data allow."""
    out = []
    if any(run.get("evaluation") for run in runs):
        view = truth_view(runs)
        out += [
            ("Trajectory", plot_views(runs, view, data_dir),
             "Estimated trajectories (aligned to the ground truth) from above and from the side. "
             "Axes: " + view.how + "."),
            ("Trajectory", plot_error_along_path(runs, view, data_dir),
             "The absolute error of each pose along the path, from above (same axes)."),
            ("Trajectory", plot_against_time(runs, data_dir),
             "Position and orientation against time in the ground truth's world."),
            ("Trajectory", plot_errors_over_distance(runs, data_dir),
             "Relative errors over sub-trajectories of fixed length (rpg_trajectory_evaluation: "
             "box = quartiles, whiskers = 1.5 IQR), and the absolute error against time."),
            ("Trajectory", plot_velocity(runs, data_dir),
             "Speed, and the error of the velocity in the camera frame (both from local fits of "
             "the poses over +-150 ms; EvSLAM's AUC over the relative velocity error)."),
        ]
    for k, run in enumerate(runs[:3]):
        out.append(("Depth", plot_depth_maps(run, data_dir, "depth_maps_%d.png" % k),
                    "%s: depth maps as written to depth/, beside the ground truth's nearest frame "
                    "(one depth scale per row), and the error of each point scored on that frame "
                    "where it falls in it." % run["name"]))
    out.append(("Depth", plot_depth_errors(runs, data_dir),
                "Depth error against true depth, and by the kind of edge the point lies on: on a "
                "depth discontinuity (true depths within one pixel differ by over 10 %: the point "
                "may take either side's depth), on a near-horizontal edge (parallel to the "
                "baseline: stereo matching is ill-posed there), or another edge."))
    cloud, convention = plot_map_from_above(runs, data_dir)
    out.append(("Depth", cloud, "The global map (map.ply) from above, coloured by height, with the "
                "estimated trajectory. Axes: " + convention + "."))
    out += [
        ("Run", plot_strips(runs, data_dir), "Event rate, tracking status per tick and map size."),
        ("Run", plot_imu(runs, data_dir),
         "What the runs estimated of the IMU (timings.csv): the gyroscope bias each tick's "
         "prediction used, and with imu.mode full the back-end's accelerometer bias (solid x, "
         "dashed y, dotted z) and how far its direction of gravity is from the one the run "
         "measured over its whole length (summary.json motion.gravity)."),
        ("Run", plot_timing(runs, data_dir),
         "Time per stage, and per tick against the real-time budget: tracking's thread must "
         "finish a tick within one tick interval, a mapping cycle (on its own thread) within one "
         "mapping period."),
    ]
    return [(section, path, caption) for section, path, caption in out if path]


def gravity_line(run):
    gravity = (run["summary"].get("motion") or {}).get("gravity")
    if not gravity:
        return "no gravity measured (no IMU, no extrinsic, or under 2 s of data)"
    down = gravity.get("down_world", [0, 0, 0])
    return "gravity measured over %.1f s: %.3f m/s^2 along (%.3f, %.3f, %.3f) in its world" % (
        gravity.get("span_s", 0.0), gravity.get("magnitude_m_s2", 0.0), *down)


def main():
    data_dir, out_html = sys.argv[1], sys.argv[2]
    runs = load_runs(data_dir)
    if not runs:
        sys.exit("plot_report.py: no run_0.json in " + data_dir)
    drawn = figures(runs, data_dir)
    parts = ["<!DOCTYPE html>\n<html><head><meta charset='utf-8'><title>aavio report: %s</title>" %
             html.escape(", ".join(run["name"] for run in runs)),
             "<style>body{font-family:sans-serif;margin:2em;max-width:1500px}"
             "table{border-collapse:collapse;font-size:0.9em;margin:1em 0}td,th{border:1px solid "
             "#bbb;padding:3px 8px;text-align:right}th{background:#eee}td:first-child{text-align:"
             "left}img{max-width:100%}figure{margin:1.5em 0}figcaption{color:#444}.wide{overflow-x:auto}</style>"
             "</head><body>",
             "<h1>aavio report</h1>", summary_table(runs), "<ul>"]
    for run in runs:
        s = run["summary"]
        parts.append("<li><b>%s</b>: %s; %s; sequence %s; %s</li>" % tuple(html.escape(str(x)) for x in (
            run["name"], run["dir"], s.get("version", "?"), s.get("sequence", "?"), gravity_line(run))))
    parts.append("</ul>")
    parts.append(config_differences(runs))
    section = None
    for name, path, caption in drawn:
        if name != section:
            parts.append("<h2>%s</h2>" % name)
            section = name
        parts.append(embed(path, caption))
    parts.append("<p>Definitions of every figure: docs/evaluation.md of aavio.</p></body></html>\n")
    with open(out_html, "w") as f:
        f.write("\n".join(parts))
    print("wrote %s (%d run(s), %d figure(s))" % (out_html, len(runs), len(drawn)))


if __name__ == "__main__":
    main()
