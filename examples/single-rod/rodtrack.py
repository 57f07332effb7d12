"""Read the per-rod dump of in.single-rod and measure how each rod walks.

The polar axis p (tail -> nose) of a rod is its body x axis: p = R(q) (1, 0, 0).
Speed along the axis: sum over samples of (r(t+dt) - r(t)) . p(t) in the plate (x, y) plane,
divided by the elapsed time (after a settling time). Positive = nose first.
"""
import sys

import numpy as np


def read_local_dump(path):
    """Return {rod id: array of rows [t_index, xu, yu, zu, qw, qi, qj, qk, vx, vy, vz]}."""
    rods = {}
    frame = -1
    with open(path) as f:
        lines = iter(f)
        for line in lines:
            if line.startswith("ITEM: TIMESTEP"):
                step = int(next(lines))
                frame += 1
            elif line.startswith("ITEM: ENTRIES"):
                continue
            elif line.startswith("ITEM: NUMBER OF ENTRIES"):
                int(next(lines))
            elif line.startswith("ITEM: BOX BOUNDS"):
                for _ in range(3):
                    next(lines)
            elif line.startswith("ITEM"):
                continue
            else:
                v = line.split()
                rods.setdefault(int(v[0]), []).append([step] + [float(x) for x in v[1:]])
    return {k: np.array(v) for k, v in rods.items()}


def polar_axis(q):
    """First column of the rotation matrix of unit quaternions q = (w, i, j, k), shape (n, 4)."""
    w, x, y, z = q.T
    return np.stack([w * w + x * x - y * y - z * z, 2 * (x * y + w * z), 2 * (x * z - w * y)], axis=1)


def rod_speeds(rows, dt, settle=0.1):
    """Speed along the own axis, mean in-plane speed over 0.1 s windows, tilt (deg), duration."""
    t = rows[:, 0] * dt
    keep = t >= settle
    t, r, p = t[keep], rows[keep, 1:4], polar_axis(rows[keep, 4:8])
    step = np.diff(r[:, :2], axis=0)
    p_xy = p[:-1, :2] / np.linalg.norm(p[:-1, :2], axis=1)[:, None]
    along = np.sum(step * p_xy, axis=1).sum() / (t[-1] - t[0])
    stride = max(1, int(round(0.1 / (t[1] - t[0]))))
    coarse = r[::stride, :2]
    planar = np.linalg.norm(np.diff(coarse, axis=0), axis=1).mean() / (t[stride] - t[0])
    tilt = np.degrees(np.arcsin(np.abs(p[:, 2]))).mean()
    return along, planar, tilt, t[-1] - t[0]


def summarize(path, dt, settle=0.1):
    rods = read_local_dump(path)
    return {rid: rod_speeds(rows, dt, settle) for rid, rows in sorted(rods.items())}


if __name__ == "__main__":
    if len(sys.argv) < 3:
        sys.exit("usage: rodtrack.py DUMP DT [SETTLE]")
    settle = float(sys.argv[3]) if len(sys.argv) > 3 else 0.1
    res = summarize(sys.argv[1], float(sys.argv[2]), settle)
    for rid, (along, planar, tilt, T) in res.items():
        print(f"rod {rid}: speed along own axis {along * 1e3:+.3f} mm/s, in-plane speed {planar * 1e3:.3f} mm/s,"
              f" mean tilt {tilt:.2f} deg over {T:.2f} s")
    a = np.array([v[0] for v in res.values()])
    print(f"mean speed along axis {a.mean() * 1e3:+.3f} mm/s, s.d. {a.std() * 1e3:.3f} mm/s over {len(a)} rods")
