"""Plot bench/dense.sh's table: CPU microseconds per atom-step against the total area fraction.

    bench/dense.sh | tee dense.txt && /usr/bin/python3 bench/plot_dense.py dense.txt dense.png
"""
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt

LABELS = {"impacts": "resting no (compliant impacts)", "resting": "resting yes", "base": "baseline build (its fluid only)"}


def read_table(path):
    """Sides and rows {side: [(total, us)]}; the fluid row's total is phi_b + phi_r."""
    sides, rows = [], {}
    for line in open(path):
        words = line.split()
        if not words or words[0].startswith("#"):
            continue
        if words[0] == "total":
            sides = [w.split(":")[0] for w in words[4::2]]
            rows = {s: [] for s in sides}
            continue
        total = float(words[1]) + float(words[2]) if words[0] == "fluid" else float(words[0])
        for side, value in zip(sides, words[4::2]):
            if value != "-":
                rows[side].append((total, float(value)))
    return rows


def main(table, image):
    rows = read_table(table)
    fig, ax = plt.subplots(figsize=(5.5, 3.8))
    for side, points in rows.items():
        points.sort()
        ax.plot([p[0] for p in points], [p[1] for p in points], "o-", label=LABELS.get(side, side))
    ax.set_yscale("log")
    ax.set_xlabel("total area fraction (beads + rods)")
    ax.set_ylabel("CPU us per atom-step")
    ax.set_title("in.channel-small, 30 x 15 d, 0.1 s per packing, 1 rank", fontsize=9)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(image, dpi=120)


if __name__ == "__main__":
    main(*sys.argv[1:3])
