"""The figures of `aavio report` about how a run went: event rate, tracking status and map size,
the IMU's estimates, and time against the real-time budget."""
import numpy as np

from report_common import colour, gravity_up, plt, save

STATUS_COLOURS = {"ok": "tab:green", "imu": "tab:olive", "lost": "tab:red", "no_map": "0.75"}
STAGES = ["time_surface", "ts_derived", "aa_map", "sampling", "tracking", "matching",
          "depth_refinement", "fusion", "mapping_total"]


def column(rows, key):
    """A timings.csv column as floats (NaN where empty or absent)."""
    return np.array([float(r[key]) if r.get(key) not in (None, "") else np.nan for r in rows])


def times(rows):
    t = column(rows, "t_s")
    return t - t[0]


def plot_strips(runs, data_dir):
    timed = [(k, run) for k, run in enumerate(runs) if run["timings"]]
    if not timed:
        return None
    fig, axes = plt.subplots(3, 1, figsize=(14, 7), sharex=True,
                             gridspec_kw={"height_ratios": [3, 0.5 + 0.5 * len(timed), 3]})
    for row, (k, run) in enumerate(timed):
        rows = run["timings"]
        t = times(rows)
        width = (t[1] - t[0]) if len(t) > 1 else 0.01
        if "events" in rows[0]:
            axes[0].plot(t, column(rows, "events") / width / 1e6, color=colour(k), lw=0.8,
                         label=run["name"])
        for status, shade in STATUS_COLOURS.items():
            ticks = [ti for ti, r in zip(t, rows) if r["status"] == status]
            axes[1].broken_barh([(ti - width / 2, width) for ti in ticks], (row - 0.4, 0.8),
                                color=shade, label=status if row == 0 else None)
        # A tick lists the map it published; tracking uses that map until the next one.
        in_use, current = [], 0.0
        for n in column(rows, "map_points"):
            current = n if n > 0 else current
            in_use.append(current)
        axes[2].step(t, in_use, where="post", color=colour(k), lw=0.8, label=run["name"])
    axes[0].set_ylabel("events, both cameras [M/s]")
    axes[0].set_title("event rate, tracking status and map size over time")
    axes[0].legend(fontsize=9, loc="upper right")
    axes[1].set_yticks(range(len(timed)))
    axes[1].set_yticklabels([run["name"] for _, run in timed], fontsize=9)
    axes[1].set_ylim(-0.6, len(timed) - 0.4)
    axes[1].legend(fontsize=8, loc="lower left", bbox_to_anchor=(1.0, 0.0), frameon=False)
    axes[2].set_ylabel("points of the map tracked")
    axes[2].set_xlabel("data time from the run's start [s]")
    for ax in (axes[0], axes[2]):
        ax.grid(alpha=0.3)
    return save(fig, data_dir, "strips.png")


def plot_imu(runs, data_dir):
    """The gyroscope bias each tick used and, where the IMU back-end ran, its accelerometer bias
    and gravity."""
    shown = [(k, run) for k, run in enumerate(runs) if run["timings"] and "gyro_bias_x" in run["timings"][0]]
    shown = [(k, run) for k, run in shown
             if np.nanmax(np.abs(np.stack([column(run["timings"], "gyro_bias_" + a) for a in "xyz"])))
             > 0 or np.isfinite(column(run["timings"], "accel_bias_x")).any()]
    if not shown:
        return None
    fig, axes = plt.subplots(1, 3, figsize=(16, 4.5), sharex=True)
    styles = {"x": "-", "y": "--", "z": ":"}
    for k, run in shown:
        rows = run["timings"]
        t = times(rows)
        for a in "xyz":
            axes[0].plot(t, np.degrees(column(rows, "gyro_bias_" + a)), styles[a], color=colour(k),
                         lw=1.0, label="%s %s" % (run["name"], a))
            axes[1].plot(t, column(rows, "accel_bias_" + a), styles[a], color=colour(k), lw=1.0,
                         label="%s %s" % (run["name"], a))
        # Gravity: how far the back-end's direction is from the one the whole run measured
        # (summary.json motion.gravity), else from its own last.
        gravity = np.stack([column(rows, "gravity_" + a) for a in "xyz"], axis=1)
        solved = np.isfinite(gravity).all(axis=1)
        if solved.any():
            up = gravity_up(run["summary"])
            reference = -up if up is not None else gravity[solved][-1]
            reference = reference / np.linalg.norm(reference)
            cosine = gravity[solved] @ reference / np.linalg.norm(gravity[solved], axis=1)
            axes[2].plot(t[solved], np.degrees(np.arccos(np.clip(cosine, -1.0, 1.0))),
                         color=colour(k), lw=1.0, label="%s (from %s)" % (
                             run["name"], "the run's measured gravity" if up is not None
                             else "its last estimate"))
    axes[0].set_ylabel("gyroscope bias [deg/s]")
    axes[0].set_title("gyroscope bias used (IMU frame)")
    axes[1].set_ylabel("accelerometer bias [m/s^2]")
    axes[1].set_title("accelerometer bias (IMU back-end)")
    axes[2].set_ylabel("angle [deg]")
    axes[2].set_title("direction of gravity (IMU back-end)")
    for ax in axes:
        ax.set_xlabel("data time from the run's start [s]")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7, ncol=2)
    return save(fig, data_dir, "imu.png")


def tick_budget_ms(run, rows):
    rate = run.get("config", {}).get("time_surface.rate_hz")
    if rate:
        return 1000.0 / float(rate)
    t = column(rows, "t_s")
    return 1000.0 * float(np.median(np.diff(t))) if len(t) > 1 else None


def plot_timing(runs, data_dir):
    fig, axes = plt.subplots(1, 2, figsize=(15, 4.8))
    width = 0.8 / max(1, len(runs))
    budgets = set()
    for k, run in enumerate(runs):
        stages = run["summary"].get("stages", {})
        med = [stages.get(s, {}).get("median_ms", 0.0) for s in STAGES]
        p95 = [stages.get(s, {}).get("p95_ms", 0.0) for s in STAGES]
        pos = [i + (k - (len(runs) - 1) / 2) * width for i in range(len(STAGES))]
        axes[0].bar(pos, med, width * 0.9, color=colour(k), alpha=0.8, label=run["name"])
        axes[0].errorbar(pos, med, yerr=[[0] * len(med), [max(0.0, p - m) for p, m in zip(p95, med)]],
                         fmt="none", ecolor="k", capsize=2, lw=0.8)
        rows = run["timings"]
        if not rows:
            continue
        t = times(rows)
        # Tracking's thread: the representation and the registration of every tick; mapping cycles
        # run beside it on their own thread, one per mapping period.
        tracking = sum(np.nan_to_num(column(rows, key))
                       for key in ("time_surface_ms", "aa_ms", "sampling_ms", "tracking_ms"))
        axes[1].plot(t, tracking, color=colour(k), lw=0.7, label="%s: tracking thread per tick" % run["name"])
        mapping = column(rows, "mapping_ms")
        cycles = mapping > 0
        axes[1].plot(t[cycles], mapping[cycles], "x", color=colour(k), ms=4,
                     label="%s: mapping cycle" % run["name"])
        budget = tick_budget_ms(run, rows)
        if budget and budget not in budgets:
            budgets.add(budget)
            axes[1].axhline(budget, color="k", ls="--", lw=1.0,
                            label="real-time budget of a tick (%.3g ms)" % budget)
        rate = run.get("config", {}).get("mapping.rate_hz")
        if rate and 1000.0 / float(rate) not in budgets:
            budgets.add(1000.0 / float(rate))
            axes[1].axhline(1000.0 / float(rate), color="0.4", ls=":", lw=1.0,
                            label="real-time budget of a mapping cycle (%.3g ms)" % (1000.0 / float(rate)))
    axes[0].set_xticks(range(len(STAGES)))
    axes[0].set_xticklabels(STAGES, rotation=25, ha="right")
    axes[0].set_ylabel("ms (bar: median, whisker: p95)")
    axes[0].set_title("time per stage")
    axes[0].grid(axis="y", alpha=0.3)
    axes[0].legend(fontsize=9)
    axes[1].set_xlabel("data time from the run's start [s]")
    axes[1].set_ylabel("ms")
    axes[1].set_title("processing time against the real-time budget")
    axes[1].grid(alpha=0.3)
    axes[1].legend(fontsize=8)
    return save(fig, data_dir, "timing.png")
