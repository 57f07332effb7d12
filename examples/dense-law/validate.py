"""Is a dense-contact law the physics channel-small's condensation was validated with?

Runs examples/channel/in.channel-small side by side on two builds, each with its own decks: OURS
(this checkout, with --ours-var settings, the candidate law) and BASE (a checkout of the
validated code, e.g. 57e4d5b with build/, at its decks' defaults: resting no), one rank a run,
--jobs runs at a time, resumably (a run with its dump and log complete is not run again). Each
run is classified by `activegrain phase` over 5-s windows, one frame a second.

  condensate   from states/channel-small-condensed-500s.data.gz, --seeds (the rough plates'
               seed), --time seconds: per run the mean number of rods in the layer, its speed
               along the channel (d/s; the layer's position unwrapped across the periodic x), the
               bead fractions ahead and behind, condensed frames; per side the seeds' mean and
               spread.
  formation    from the created state, seeds 2024 2 1, --time seconds: per run the onset, the
               first second from which at least 80 % of the next 25 s of frames are condensed,
               and the condensed frames after it.
  compression  examples/dense-law/in.compress (beads alone in a cell, a piston steps the area
               fraction through 0.80, 0.82, 0.84, 0.86), --seeds: per run and total the piston's
               mean pressure (N/m) over each hold after its first --settle seconds, with the
               standard error of its blocks; per side and total the seeds' mean, its standard
               error and the seeds' range.

Usage, from the repository root (hours of one core per side at the paper's lengths):
    /usr/bin/python3 examples/dense-law/validate.py condensate --base ../ag-57e4d5b --out RUN --time 100 --seeds 1 2 3
    /usr/bin/python3 examples/dense-law/validate.py formation --base ../ag-57e4d5b --out RUN --time 450
    /usr/bin/python3 examples/dense-law/validate.py compression --base ../ag-57e4d5b --out RUN --hold 10
--quick runs 2 s each (checks the script). --ours-var resting newton runs that law on our side;
--ours-lmp a frozen copy of our LAMMPS while the checkout is rebuilt; --totals 0.80 0.82 the
compression's totals only; --geometry channel its cell periodic along x (in.compress: the
rectangle's crystal jams between 0.82 and 0.84, the channel's stays one to 0.88).
"""
import argparse
import concurrent.futures
import os
import pathlib
import subprocess
import sys

import numpy as np

ROOT = pathlib.Path(__file__).resolve().parents[2]
STATE = "states/channel-small-condensed-500s.data.gz"
STATE_TIME = 500.0
LENGTH = 60.0                # the channel's period along x, d
ONSET_SPAN = 25.0            # s of frames after an onset
ONSET_SHARE = 0.8            # condensed share of them


def lmp_of(checkout):
    return str(pathlib.Path(checkout).resolve() / "build" / "lmp")


def run(side, lmp, checkout, deck_vars, out, seed, start, time):
    """One run of in.channel-small in its checkout's examples/channel (time: simulated seconds
    from start), or of our in.compress with this side's build (time None); returns its folder."""
    folder = pathlib.Path(out) / f"{side}-seed{seed}"
    log = folder / "log.lammps"
    if log.exists() and "Total wall time" in log.read_text():
        return folder
    folder.mkdir(parents=True, exist_ok=True)
    args = [lmp, "-var", "out", str(folder.resolve()), "-var", "seed", str(seed),
            "-log", str(log.resolve())]
    if time is None:
        args += ["-in", "in.compress"]
        cwd = ROOT / "examples" / "dense-law"
    else:
        args += ["-in", "in.channel-small", "-var", "time", repr(start + time), "-var", "dump", "1.0"]
        args += ["-var", "from", STATE] if start > 0 else []
        cwd = pathlib.Path(checkout) / "examples" / "channel"
    for name, *values in deck_vars:
        args += ["-var", name, *values]
    with open(folder / "screen.txt", "w") as screen:
        subprocess.run(args, cwd=cwd, stdout=screen, stderr=subprocess.STDOUT, check=True)
    return folder


def phases(folder):
    """activegrain phase's table of the run's dump: a dict of column arrays."""
    text = subprocess.run([str(ROOT / "build" / "bin" / "activegrain"), "phase", str(folder / "channel.dump"),
                           "--geometry", "channel", "--length-unit", "1e-3", "--timestep", "1e-4",
                           "--window", "5"], check=True, capture_output=True, text=True).stdout
    lines = [line.split() for line in text.splitlines() if line.strip()]
    header, rows = lines[0], lines[1:]
    table = {name: [row[k] for row in rows] for k, name in enumerate(header)}
    return {name: (np.array(values) if name == "phase" else np.array(values, float))
            for name, values in table.items()}


def condensate_row(table):
    frames = table["time"] > table["time"][0]    # the first frame's window is the run's start
    rods = (table["layer_fraction"] * table["n_rods"])[frames]
    position = np.unwrap(table["layer_position"][frames] * 2 * np.pi / LENGTH) * LENGTH / (2 * np.pi)
    speed = np.polyfit(table["time"][frames], position, 1)[0] if frames.sum() > 1 else np.nan
    return {"rods": rods.mean(), "speed": abs(speed), "ahead": table["phi_ahead"][frames].mean(),
            "behind": table["phi_behind"][frames].mean(),
            "condensed": f"{(table['phase'][frames] == 'condensed').sum()}/{frames.sum()}"}


def formation_row(table):
    condensed = table["phase"] == "condensed"
    times = table["time"]
    onset = next((t for k, t in enumerate(times) if condensed[k]
                  and condensed[(times >= t) & (times <= t + ONSET_SPAN)].mean() >= ONSET_SHARE), None)
    after = condensed[times >= onset] if onset is not None else condensed[:0]
    return {"onset": "none" if onset is None else f"{onset:.0f}",
            "condensed after": f"{after.sum()}/{after.size}", "last time": f"{times[-1]:.0f}"}


def compression_row(folder, settle):
    """Per total held: the piston's mean pressure over the hold after settle seconds, and the
    standard error of the mean of its blocks (N/m)."""
    step, pressure, total = np.loadtxt(folder / "piston.txt", unpack=True)
    time = step * 1e-4
    row = {}
    for held in (0.80, 0.82, 0.84, 0.86, 0.88):
        at = np.isclose(total, held, atol=1e-9)
        if not at.any():
            continue
        blocks = pressure[at & (time > time[at][0] + settle)]
        if blocks.size > 1:
            row[f"P at {held:.2f}"] = f"{blocks.mean():.4g}+-{blocks.std(ddof=1) / np.sqrt(blocks.size):.2g}"
    return row


def number(value):
    """A run's quantity as a number: a float, or a pressure's mean from its "mean+-error"; None for
    a count such as "48/100"."""
    if isinstance(value, float):
        return value
    return float(value.split("+-")[0]) if isinstance(value, str) and "+-" in value else None


def seeds_summary(rows, side, seeds):
    """Per numeric column: the mean over the seeds, its standard error and the seeds' range."""
    summary = {}
    for column in rows[(side, seeds[0])]:
        values = np.array([v for v in (number(rows[(side, seed)].get(column)) for seed in seeds) if v is not None])
        if values.size:
            error = values.std(ddof=1) / np.sqrt(values.size) if values.size > 1 else np.nan
            summary[column] = f"{values.mean():.4g} +- {error:.2g} ({values.min():.4g}-{values.max():.4g})"
    return summary


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("measurement", choices=["condensate", "formation", "compression"])
    ap.add_argument("--base", required=True, help="checkout of the validated code, with build/lmp")
    ap.add_argument("--out", required=True)
    ap.add_argument("--time", type=float, help="simulated seconds a run (condensate 100, formation 450)")
    ap.add_argument("--seeds", type=int, nargs="+")
    ap.add_argument("--ours-var", nargs=2, action="append", metavar=("NAME", "VALUE"),
                    help="a deck variable of our side, repeatable (default: resting yes)")
    ap.add_argument("--ours-lmp", help="our side's LAMMPS (default: this checkout's build/lmp), e.g. a frozen "
                    "copy while the checkout is rebuilt")
    ap.add_argument("--sides", nargs="+", choices=["ours", "base"], default=["ours", "base"])
    ap.add_argument("--totals", nargs="+", help="compression: the area fractions (default in.compress's)")
    ap.add_argument("--geometry", choices=["rectangle", "channel"], default="rectangle",
                    help="compression: the cell (in.compress)")
    ap.add_argument("--hold", type=float, default=10.0, help="compression: seconds at each total")
    ap.add_argument("--settle", type=float, default=2.0, help="compression: seconds of each hold left out")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--quick", action="store_true")
    args = ap.parse_args(argv)
    condensate, compression = args.measurement == "condensate", args.measurement == "compression"
    time = 2.0 if args.quick else args.time or (100.0 if condensate else 450.0)
    seeds = args.seeds or ([1, 2, 3] if condensate else [2024] if compression else [2024, 2, 1])
    ours_vars = args.ours_var or [("resting", "yes")]
    start = STATE_TIME if condensate else 0.0
    sides = {side: checkout for side, checkout in
             {"ours": (args.ours_lmp or lmp_of(ROOT), ROOT, ours_vars),
              "base": (lmp_of(args.base), pathlib.Path(args.base), [])}.items() if side in args.sides}
    if compression:
        compress_vars = ([("hold", "0.2"), ("ramp", "0.05"), ("block", "0.05"), ("totals", "0.80")]
                         if args.quick else [("hold", repr(args.hold)), ("ramp", "2.0"), ("block", "0.5")])
        compress_vars += [("totals", *args.totals)] if args.totals and not args.quick else []
        compress_vars += [("geometry", args.geometry)]
        sides = {side: (lmp, checkout, deck_vars + compress_vars) for side, (lmp, checkout, deck_vars) in sides.items()}
        time = None
    with concurrent.futures.ThreadPoolExecutor(args.jobs) as pool:
        jobs = {(side, seed): pool.submit(run, side, lmp, checkout, deck_vars, args.out, seed, start, time)
                for side, (lmp, checkout, deck_vars) in sides.items() for seed in seeds}
        folders = {key: job.result() for key, job in jobs.items()}
    settle = 0.05 if args.quick else args.settle
    row_of = ((lambda folder: compression_row(folder, settle)) if compression else
              (lambda folder: (condensate_row if condensate else formation_row)(phases(folder))))
    print(f"{args.measurement}: {'in.compress' if compression else f'{time:g} s a run'}; ours: {' '.join(f'{n} {v}' for n, v in ours_vars)}; "
          f"base: {pathlib.Path(args.base).resolve().name} at its defaults")
    rows = {key: row_of(folder) for key, folder in folders.items()}
    columns = list(next(iter(rows.values())))
    print("side  seed  " + "  ".join(f"{c:>15}" for c in columns))
    for (side, seed), row in rows.items():
        print(f"{side:5} {seed:5} " + "  ".join(f"{v:>15.3f}" if isinstance(v, float) else f"{v:>15}"
                                               for v in row.values()))
    if condensate or compression:
        for side in sides:
            print(f"{side:5} seeds' mean +- standard error (range): " + ", ".join(
                f"{c} {v}" for c, v in seeds_summary(rows, side, seeds).items()))
    return 0


if __name__ == "__main__":
    sys.exit(main())
