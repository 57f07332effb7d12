"""Phase diagrams from runs of an example deck over a grid of (phi_b, phi_r) and seeds.

``activegrain sweep DECK --phi-b 0.6 0.7 --phi-r 0.03 --seeds 1 2 --time 20 --out DIR``
runs ``DECK`` (from its own folder, as the example decks expect) once per grid point and seed,
with ``-var phi_b``, ``-var phi_r``, ``-var seed``, ``-var time`` and ``-var out`` set and any
fixed ``--var NAME VALUE`` added, under ``mpirun -np RANKS`` (or directly for one rank). Each run
lives in its own folder ``DIR/phi_b<..>_phi_r<..>_seed<..>``; ``result.json`` there marks it done
and holds the area fractions the deck reached, the phase that
:func:`activegrain.analysis.classify_frames` gives the last frames of its dump (the majority
over them, each with its rates and averages over the ``window`` seconds of the run up to it)
with the observables, and its wall time. A second call skips the runs that are done
(an unfinished run's folder is started afresh), so an interrupted sweep resumes.

A point is done only when its run has ended cleanly and its result is written: ``run.json``
(the run's command, wall time and reached fractions) is written once LAMMPS has exited with
status 0 and no ERROR, ``result.json`` once the dump is classified, each to a temporary file
made durable and then renamed over the name, so that a marker is complete or absent, whenever
the sweep or its run is killed (SIGKILL included). A folder without ``run.json`` (a run killed,
timed out or failed) is run afresh; one with ``run.json`` but no readable ``result.json`` (the
classification failed or was cut short) is classified again without running the deck again.
A run gets SIGTERM when the sweep dies (Linux), so that no orphaned run writes into a folder
that a resumed sweep starts afresh, and a lock file in ``DIR`` keeps a second sweep out while
one runs there.

Progress goes to stderr with the time left estimated from the finished runs' wall times. At
the end the table (``phases.txt``, ``phases.csv``) and the phase diagram (``phase_diagram.png``,
markers per phase on phi_b and phi_r axes, as the paper's Figs. 2a and 3a) are written into
``DIR``.
"""
import csv
import ctypes
import fcntl
import itertools
import json
import os
import pathlib
import re
import shutil
import signal
import subprocess
import sys
import time
import warnings
from collections import Counter
from dataclasses import dataclass, field

import numpy as np

from . import analysis, io
from .geometry import geometry_from_box

RESULT = "result.json"     # the point is done: its run ended cleanly and was classified
RUN = "run.json"           # its run ended cleanly (exit 0, no ERROR): what classifying it needs
LOCK = ".sweep.lock"       # held by the sweep running in a folder
RUN_KEYS = ("phi_b", "phi_r", "seed", "phi_b_reached", "phi_r_reached", "wall_s", "command")
RESULT_KEYS = RUN_KEYS + ("phase", "phase_counts", "frames", "observables")
REACHED = re.compile(r"ActiveGrain \w+: phi_b = ([\d.]+) \(asked [^)]*\), phi_r = ([\d.]+) \(asked")
TABLE_KEYS = ("phi_b", "phi_r", "seed", "phase", "phi_b_reached", "phi_r_reached", "phi_total", "P", "P_mean",
              "rod_speed", "segregation", "active_layer_fraction", "layer_contrast", "mobility", "frames", "wall_s")


@dataclass
class SweepConfig:
    deck: pathlib.Path
    phi_b: list
    phi_r: list
    seeds: list
    time: float
    out: pathlib.Path
    ranks: int = 1
    variables: list = field(default_factory=list)   # [(name, value), ...]
    lmp: str = "lmp"
    mpirun: str = "mpirun"
    dump: str = None          # dump file name in a run's folder (default: its only *.dump)
    frames: int = 5           # last frames classified
    window: float = 1.0       # seconds of the run up to a frame over which its rates are taken
    timestep: float = 1e-4    # the deck's time step, s (the example decks'): frame times in seconds
    geometry: str = "auto"
    r_in: float = 0.0
    r_out: float = None
    length_unit: float = 1e-3
    timeout: float = None     # seconds per run

    def check(self):
        """ValueError naming the first bad setting."""
        if not self.deck.is_file():
            raise ValueError(f"deck {self.deck} not found")
        for name in ("phi_b", "phi_r", "seeds"):
            if not getattr(self, name):
                raise ValueError(f"--{name.replace('_', '-')}: give at least one value")
        for name in ("phi_b", "phi_r"):
            bad = [v for v in getattr(self, name) if not 0 <= v < 1]
            if bad:
                raise ValueError(f"--{name.replace('_', '-')} {bad[0]}: an area fraction must be in [0, 1)")
        if len(set(self.seeds)) != len(self.seeds) or any(s <= 0 for s in self.seeds):
            raise ValueError(f"--seeds {self.seeds}: positive and distinct (LAMMPS seeds)")
        if not self.time > 0:
            raise ValueError(f"--time {self.time}: the run length must be positive")
        if self.ranks < 1:
            raise ValueError(f"--ranks {self.ranks}: at least 1")
        if self.frames < 1:
            raise ValueError(f"--frames {self.frames}: at least 1")
        if not self.window > 0 or not self.timestep > 0:
            raise ValueError(f"--window {self.window} --timestep {self.timestep}: seconds, above 0")
        taken = {"phi_b", "phi_r", "seed", "time", "out"}
        for name, _ in self.variables:
            if name in taken:
                raise ValueError(f"--var {name}: set by the sweep itself (use --phi-b, --phi-r, --seeds, --time, --out)")
        if self.geometry == "annulus" and self.r_out is None:
            raise ValueError("--geometry annulus needs --r-out")


def points(cfg):
    """The runs of the sweep: (phi_b, phi_r, seed), phi_r slowest."""
    return [(b, r, s) for r, b, s in itertools.product(cfg.phi_r, cfg.phi_b, cfg.seeds)]


def run_dir(cfg, phi_b, phi_r, seed):
    return cfg.out / f"phi_b{phi_b:.4f}_phi_r{phi_r:.4f}_seed{seed}"


def command(cfg, phi_b, phi_r, seed, folder):
    lmp = [cfg.lmp, "-in", cfg.deck.name, "-log", str(folder / "log.lammps"),
           "-var", "phi_b", repr(phi_b), "-var", "phi_r", repr(phi_r), "-var", "seed", str(seed),
           "-var", "time", repr(cfg.time), "-var", "out", str(folder)]
    for name, value in cfg.variables:
        lmp += ["-var", name, value]
    if cfg.ranks == 1:
        return lmp
    root = ["--allow-run-as-root"] if hasattr(os, "geteuid") and os.geteuid() == 0 else []
    return [cfg.mpirun, *root, "-np", str(cfg.ranks), *lmp]


def _dump_of(cfg, folder):
    if cfg.dump:
        path = folder / cfg.dump
        if not path.is_file():
            raise RuntimeError(f"{folder}: the deck wrote no {cfg.dump}")
        return path
    dumps = sorted(folder.glob("*.dump"))
    if len(dumps) != 1:
        raise RuntimeError(f"{folder}: {len(dumps)} dump files, name the one to classify with --dump")
    return dumps[0]


def classify_run(cfg, dump):
    """Majority phase of the last ``cfg.frames`` frames (each with its window of ``cfg.window``
    seconds) and their mean observables."""
    run = io.Dump(dump, length_unit=cfg.length_unit, timestep=cfg.timestep)
    if len(run) < 2:
        raise RuntimeError(f"{dump}: {len(run)} frame, the phase needs frames over a window of time")
    first = max(0, len(run) - cfg.frames)
    u = cfg.length_unit
    geom = geometry_from_box(run.frame(0).box, cfg.geometry, None, cfg.r_in / u,
                             None if cfg.r_out is None else cfg.r_out / u)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", analysis.ShortRunWarning)
        try:    # the dump read once, holding only the frames of the windows still open
            results = analysis.classify_frames(run.frames(), geom, cfg.window, which=range(first, len(run)))
        except ValueError as e:
            raise RuntimeError(f"{dump}: {e}") from None
    for w in caught:        # with the run's name
        warnings.warn(f"{dump}: {w.message}", w.category, stacklevel=2)
    counts = Counter(r.phase.value for r in results)
    phase = analysis.majority_phase(counts)
    numeric = {k for k, v in results[0].observables.items() if isinstance(v, (int, float))}
    mean = {k: float(np.nanmean([r.observables[k] for r in results]))
            if np.isfinite([r.observables[k] for r in results]).any() else float("nan") for k in numeric}
    return phase, dict(counts), mean, len(results)


def write_json(path, data):
    """Write ``data`` as JSON to ``path`` atomically and durably: to a temporary file beside it,
    flushed to disk, then renamed over ``path``, so that ``path`` is the whole of it or absent
    (or its older whole self), whenever the writer is killed or the machine stops."""
    path = pathlib.Path(path)
    tmp = path.with_name(path.name + ".tmp")
    with open(tmp, "w") as f:
        f.write(json.dumps(data, indent=1))
        f.flush()
        os.fsync(f.fileno())
    os.replace(tmp, path)
    try:                                   # the rename itself to disk
        fd = os.open(path.parent, os.O_RDONLY)
    except OSError:
        return
    try:
        os.fsync(fd)
    except OSError:
        pass
    finally:
        os.close(fd)


def read_marker(path, keys, point):
    """The dict of marker ``path`` (``run.json`` or ``result.json``) if it is whole and is
    ``point``'s (phi_b, phi_r, seed), else None: a marker missing, cut short or someone else's
    does not make a point done."""
    try:
        data = json.loads(pathlib.Path(path).read_text())
    except (OSError, ValueError):
        return None
    if not isinstance(data, dict) or any(k not in data for k in keys):
        return None
    if (data["phi_b"], data["phi_r"], data["seed"]) != tuple(point):
        return None
    return data


def point_state(cfg, phi_b, phi_r, seed):
    """``("done", result)``, ``("ran", run record)`` (the run ended cleanly, its classification
    is missing) or ``("todo", None)`` (no run, or one that did not end cleanly)."""
    folder, point = run_dir(cfg, phi_b, phi_r, seed), (phi_b, phi_r, seed)
    result = read_marker(folder / RESULT, RESULT_KEYS, point)
    if result is not None:
        return "done", result
    run = read_marker(folder / RUN, RUN_KEYS, point)
    return ("ran", run) if run is not None else ("todo", None)


_PR_SET_PDEATHSIG = 1


def _end_with_parent():
    """``preexec_fn`` (Linux) that has the kernel send the run SIGTERM when the sweep dies, even
    by SIGKILL: mpirun passes it on to its ranks. Else a killed sweep leaves its run writing into
    a folder that the resumed sweep starts afresh."""
    libc = ctypes.CDLL(None, use_errno=True)
    parent = os.getpid()

    def preexec():
        libc.prctl(_PR_SET_PDEATHSIG, signal.SIGTERM, 0, 0, 0)
        if os.getppid() != parent:         # the sweep died before prctl took effect
            os._exit(1)
    return preexec


def _launch(cmd, cwd, screen, timeout, name):
    """Run ``cmd``; its exit status. Past ``timeout`` seconds it gets SIGTERM (mpirun passes it
    on to its ranks), SIGKILL 10 s later, and RuntimeError says so."""
    preexec = _end_with_parent() if sys.platform.startswith("linux") else None
    proc = subprocess.Popen(cmd, cwd=cwd, stdout=screen, stderr=subprocess.STDOUT, preexec_fn=preexec)
    try:
        return proc.wait(timeout=timeout)
    except subprocess.TimeoutExpired:
        proc.terminate()
        try:
            proc.wait(timeout=10)
        except subprocess.TimeoutExpired:
            proc.kill()
            proc.wait()
        raise RuntimeError(f"run {name} stopped after --timeout {timeout:g} s; "
                           "it is run afresh when the sweep is resumed") from None
    finally:
        if proc.poll() is None:            # an exception here (Ctrl-C): do not leave it running
            proc.terminate()
            proc.wait()


def simulate(cfg, phi_b, phi_r, seed):
    """Run the deck for one point in a fresh folder; its run record, written to ``run.json``
    only when LAMMPS exited with status 0 and printed no ERROR (RuntimeError otherwise)."""
    folder = run_dir(cfg, phi_b, phi_r, seed)
    if folder.exists():
        shutil.rmtree(folder)          # an unfinished run starts afresh
    folder.mkdir(parents=True)
    cmd = command(cfg, phi_b, phi_r, seed, folder)
    start = time.monotonic()
    with open(folder / "screen.txt", "w") as screen:
        code = _launch(cmd, cfg.deck.parent, screen, cfg.timeout, folder.name)
    wall = time.monotonic() - start
    text = (folder / "screen.txt").read_text(errors="replace")
    if code != 0 or "ERROR" in text:
        errors = [l for l in text.splitlines() if "ERROR" in l]
        how = f"killed by {signal.Signals(-code).name}" if code < 0 and -code in signal.valid_signals() \
            else f"exit {code}"
        raise RuntimeError(f"run {folder.name} failed ({how}): "
                           f"{errors[0] if errors else text[-500:]} (see {folder / 'screen.txt'}); "
                           "it is run afresh when the sweep is resumed")
    reached = REACHED.findall(text)
    run = {"phi_b": phi_b, "phi_r": phi_r, "seed": seed,
           "phi_b_reached": float(reached[-1][0]) if reached else float("nan"),
           "phi_r_reached": float(reached[-1][1]) if reached else float("nan"),
           "wall_s": wall, "command": cmd}
    write_json(folder / RUN, run)
    return run


def run_point(cfg, phi_b, phi_r, seed):
    """Run one point (unless its run ended cleanly before) and classify it (unless done);
    returns its result dict and whether the deck was run."""
    state, record = point_state(cfg, phi_b, phi_r, seed)
    if state == "done":
        return record, False
    folder = run_dir(cfg, phi_b, phi_r, seed)
    ran = state == "todo"
    run = simulate(cfg, phi_b, phi_r, seed) if ran else record
    phase, counts, obs, n = classify_run(cfg, _dump_of(cfg, folder))
    result = {"phi_b": phi_b, "phi_r": phi_r, "seed": seed, "phase": phase, "phase_counts": counts,
              "frames": n, "phi_b_reached": run["phi_b_reached"], "phi_r_reached": run["phi_r_reached"],
              "wall_s": run["wall_s"], "command": run["command"], "observables": obs}
    write_json(folder / RESULT, result)     # the point is done
    return result, ran


def _clock(seconds):
    seconds = int(round(seconds))
    return f"{seconds // 3600}:{seconds // 60 % 60:02d}:{seconds % 60:02d}"


def progress_line(done, total, walls, elapsed, width=30):
    """``[#####-----] 3/8 runs, 0:01:20 elapsed, about 0:02:10 left`` (time left from the mean
    wall time of the runs finished, or ``?`` before any)."""
    filled = int(round(width * done / total)) if total else width
    left = _clock(np.mean(walls) * (total - done)) if walls else "?"
    return f"[{'#' * filled}{'-' * (width - filled)}] {done}/{total} runs, {_clock(elapsed)} elapsed, about {left} left"


def table_rows(results):
    rows = []
    for r in results:
        row = {k: r.get(k, r["observables"].get(k, float("nan"))) for k in TABLE_KEYS}
        rows.append(row)
    return rows


def write_table(results, folder):
    rows = table_rows(results)
    with open(folder / "phases.csv", "w", newline="") as f:
        w = csv.DictWriter(f, TABLE_KEYS)
        w.writeheader()
        w.writerows(rows)
    with open(folder / "phases.txt", "w") as f:
        f.write(" ".join(TABLE_KEYS) + "\n")
        for row in rows:
            f.write(" ".join(f"{v:.6g}" if isinstance(v, float) else str(v) for v in row.values()) + "\n")
    return folder / "phases.txt", folder / "phases.csv"


def majority(results):
    """Per (phi_b, phi_r): the phase most of its seeds show, and the seed count behind it."""
    by_point = {}
    for r in results:
        by_point.setdefault((r["phi_b"], r["phi_r"]), []).append(r["phase"])
    out = {}
    for key, phases in by_point.items():
        counts = Counter(phases)
        phase = analysis.majority_phase(counts)
        out[key] = (phase, counts[phase], len(phases))
    return out


def phase_diagram(results, path, title=None):
    """The runs' phase diagram, one marker per (phi_b, phi_r) for the :func:`majority` of its
    seeds (drawn by :func:`activegrain.plotting.phase_diagram`); returns ``path``."""
    from . import plotting
    return plotting.phase_diagram(majority(results), path, title)


def _lock(folder):
    """Hold ``folder/.sweep.lock`` (released when this process ends, however it ends);
    ValueError when another sweep holds it."""
    f = open(folder / LOCK, "a+")
    try:
        fcntl.flock(f, fcntl.LOCK_EX | fcntl.LOCK_NB)
    except OSError:
        f.seek(0)
        holder = f.read().strip()
        f.close()
        raise ValueError(f"--out {folder}: another sweep{f' (pid {holder})' if holder else ''} is running "
                         "in it; wait for it to end or give another --out") from None
    f.seek(0)
    f.truncate()
    f.write(f"{os.getpid()}\n")
    f.flush()
    return f


def run_sweep(cfg, log=None):
    """Run (or resume) the sweep; returns the results in grid order and the number of runs
    made by this call. The time left is the mean wall time of the finished runs (from earlier
    calls too) times the runs still to make. Progress goes to ``log`` (default stderr)."""
    log = sys.stderr if log is None else log
    cfg.check()
    cfg.out.mkdir(parents=True, exist_ok=True)
    with _lock(cfg.out):
        return _run_sweep(cfg, log)


def _run_sweep(cfg, log):
    todo = points(cfg)
    states = {p: point_state(cfg, *p) for p in todo}
    results = {p: record for p, (state, record) in states.items() if state == "done"}
    pending = [p for p in todo if p not in results]
    walls = [r["wall_s"] for r in results.values()]
    if results:
        log.write(f"{len(results)} of {len(todo)} runs already done in {cfg.out}\n")
    again = sum(states[p][0] == "ran" for p in pending)
    if again:
        log.write(f"{again} finished run(s) to classify again (their result is missing)\n")
    start = time.monotonic()
    ran = 0
    try:
        for k, p in enumerate(pending):
            log.write("\r" + progress_line(k, len(pending), walls, time.monotonic() - start)
                      + f"  now phi_b {p[0]} phi_r {p[1]} seed {p[2]} ")
            log.flush()
            results[p], made = run_point(cfg, *p)
            ran += made
            walls.append(results[p]["wall_s"])
    except BaseException:
        log.write("\n")                   # an error goes on a line of its own
        raise
    log.write("\r" + progress_line(len(pending), len(pending), walls, time.monotonic() - start) + " " * 40 + "\n")
    ordered = [results[p] for p in todo]
    write_table(ordered, cfg.out)
    phase_diagram(ordered, cfg.out / "phase_diagram.png", title=cfg.deck.name)
    return ordered, ran
