"""Plot the in-plane trajectories of the rods of one in.single-rod run, with their polar axes.

    python3 plot_trajectory.py out/rods_default.local 1e-5 [trajectory.png]
Arrows (every 0.25 s) point from tail to nose: a rod walking nose-first moves along its arrows.
"""
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

import rodtrack


def main():
    if len(sys.argv) < 3:
        sys.exit("usage: plot_trajectory.py DUMP DT [PNG]")
    path, dt = sys.argv[1], float(sys.argv[2])
    png = sys.argv[3] if len(sys.argv) > 3 else "trajectory.png"
    rods = rodtrack.read_local_dump(path)
    speeds = rodtrack.summarize(path, dt)
    fig, ax = plt.subplots(figsize=(6, 6))
    for rid, rows in sorted(rods.items()):
        t = rows[:, 0] * dt
        x, y = (rows[:, 1] - rows[0, 1]) * 1e3, (rows[:, 2] - rows[0, 2]) * 1e3
        line, = ax.plot(x, y, lw=1, label=f"rod {rid}: {speeds[rid][0] * 1e3:+.2f} mm/s along axis")
        p = rodtrack.polar_axis(rows[:, 4:8])
        every = max(1, int(round(0.25 / (t[1] - t[0]))))
        ax.quiver(x[::every], y[::every], p[::every, 0], p[::every, 1], color=line.get_color(),
                  angles="xy", scale=25, width=0.004)
    ax.set_xlabel("x - x0 (mm)")
    ax.set_ylabel("y - y0 (mm)")
    ax.set_aspect("equal")
    ax.set_title("Rods between plates 1.12 mm apart, 200 Hz (arrows: tail to nose)")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(png, dpi=120)
    print(f"wrote {png}")


if __name__ == "__main__":
    main()
