"""What the figures of `aavio report` share: colours, saving, rotations and the axis convention."""
import os

import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

COLOURS = ["tab:blue", "tab:orange", "tab:green", "tab:red", "tab:purple", "tab:brown"]


def colour(k):
    return COLOURS[k % len(COLOURS)]


def save(fig, data_dir, name):
    path = os.path.join(data_dir, name)
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)
    return path


def quaternion_matrix(q):
    """Rotation matrix of a quaternion given as x, y, z, w."""
    x, y, z, w = q / np.linalg.norm(q)
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                     [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                     [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])


def roll_pitch_yaw_deg(quaternions):
    """Z-Y-X Euler angles (roll about x, pitch about y, yaw about z) of x, y, z, w quaternions, in
    degrees, unwrapped along the sequence."""
    rpy = []
    for q in quaternions:
        R = quaternion_matrix(np.asarray(q, dtype=float))
        rpy.append([np.arctan2(R[2, 1], R[2, 2]), np.arcsin(np.clip(-R[2, 0], -1.0, 1.0)),
                    np.arctan2(R[1, 0], R[0, 0])])
    return np.degrees(np.unwrap(np.array(rpy).reshape(-1, 3), axis=0))


def levelling(up):
    """A rotation whose rows are the levelled axes (x_h, y_h, up): x_h is the world's x laid
    horizontal (its y where x is near vertical)."""
    z = np.asarray(up, dtype=float)
    z = z / np.linalg.norm(z)
    ref = np.array([1.0, 0.0, 0.0]) if abs(z[0]) < 0.9 else np.array([0.0, 1.0, 0.0])
    x = ref - ref.dot(z) * z
    x /= np.linalg.norm(x)
    return np.stack([x, np.cross(z, x), z])


def gravity_up(summary):
    """Up (against gravity) in the run's world, from summary.json motion.gravity, or None."""
    gravity = (summary.get("motion") or {}).get("gravity") or {}
    down = gravity.get("down_world")
    if isinstance(down, list) and len(down) == 3 and np.linalg.norm(down) > 0.5:
        return -np.asarray(down, dtype=float)
    return None


class View:
    """The one axis convention of every top and side view: looking down along gravity when a run
    measured it (x_h, y_h horizontal, `height` up), else the world's own axes (x, y, z)."""

    def __init__(self, rotation, names, how):
        self.rotation, self.names, self.how = rotation, names, how

    def apply(self, points):
        return np.asarray(points, dtype=float).reshape(-1, 3) @ self.rotation.T


def truth_view(runs):
    """The view of the ground truth's world: up from the first run that measured gravity, carried
    into that world by its alignment."""
    for run in runs:
        ev, up = run.get("evaluation"), gravity_up(run["summary"])
        if ev and up is not None and "alignment_R" in ev:
            up_gt = np.asarray(ev["alignment_R"], dtype=float) @ up
            return View(levelling(up_gt), ("x_h", "y_h", "height"),
                        "levelled by the gravity %s measured: top views look down along it, "
                        "x_h is the ground truth's x laid horizontal" % run["name"])
    return View(np.eye(3), ("x", "y", "z"),
                "the ground truth's world axes (no run measured gravity: top views look along -z)")


def run_view(run):
    """The view of a run's own world (its map): levelled by its gravity, else its first camera's
    frame with -y up (x right, z forward), else (a run in the ground truth's world) that world."""
    up = gravity_up(run["summary"])
    if up is not None:
        return View(levelling(up), ("x_h", "y_h", "height"), "levelled by the measured gravity")
    if run["summary"].get("mode") in ("full", "esvo"):
        return View(np.array([[1.0, 0, 0], [0, 0, 1.0], [0, -1.0, 0]]), ("x", "z", "-y"),
                    "the first camera's frame, -y up (no measured gravity)")
    return View(np.eye(3), ("x", "y", "z"), "the world's axes")
