"""examples/minimal/in.minimal, the complete deck of the docs: it runs on 1 and 2 ranks, keeps
its atoms and its 4 rods, and its rods walk nose first from vibration and friction alone."""
import os
import pathlib
import re
import subprocess

import numpy as np
import pytest

from mpi_launch import mpi_prefix

ROOT = pathlib.Path(__file__).resolve().parents[2]
DECK = ROOT / "examples" / "minimal" / "in.minimal"
LMP = os.environ.get("ACTIVEGRAIN_LMP", str(ROOT / "build" / "lmp"))
BOX = 0.02             # the deck's periodic box, m
SETTLED = 0.3          # s: the rods have landed on the plate and started walking


def frames(dump):
    """(time step, {atom id: (type, body, x, y)}) per frame of the deck's dump."""
    out, lines = [], dump.read_text().splitlines()
    i = 0
    while i < len(lines):
        step, n = int(lines[i + 1]), int(lines[i + 3])
        cols = lines[i + 8].split()[2:]
        rows = [line.split() for line in lines[i + 9:i + 9 + n]]
        c = {name: k for k, name in enumerate(cols)}
        atoms = {int(r[c["id"]]): (int(r[c["type"]]), int(float(r[c["body"]])), float(r[c["x"]]), float(r[c["y"]]))
                 for r in rows}
        out.append((step, atoms))
        i += 9 + n
    return out


def wrap(d):
    return d - BOX * np.round(d / BOX)


def rods(atoms):
    """Per rod: its centre (the mean of its spheres, unwrapped from its tail) and its unit axis
    from tail (type 1) to nose (type 3), in the plane."""
    grouped = {}
    for kind, body, x, y in atoms.values():
        if body:
            grouped.setdefault(body, []).append((kind, np.array([x, y])))
    result = {}
    for body, spheres in grouped.items():
        tail = next(p for k, p in spheres if k == 1)
        nose = next(p for k, p in spheres if k == 3)
        centre = tail + np.mean([wrap(p - tail) for _, p in spheres], axis=0)
        axis = wrap(nose - tail)
        result[body] = (centre, axis / np.linalg.norm(axis))
    return result


@pytest.mark.parametrize("ranks", [1, 2])
def test_minimal_deck_runs_and_its_rods_walk_nose_first(tmp_path, ranks):
    done = subprocess.run([*mpi_prefix(ranks), LMP, "-in", str(DECK), "-log", str(tmp_path / "log.lammps")],
                          cwd=tmp_path, capture_output=True, text=True, timeout=600)
    assert done.returncode == 0 and "ERROR" not in done.stdout, done.stdout[-3000:] + done.stderr[-3000:]
    loop = re.search(r"Loop time of \S+ on (\d+) procs for 10000 steps with (\d+) atoms", done.stdout)
    assert loop and int(loop.group(1)) == ranks and int(loop.group(2)) == 260    # 4 rods of 9, 224 beads
    run = frames(tmp_path / "minimal.dump")
    assert len(run) == 11
    start = next(atoms for step, atoms in run if step * 1e-4 >= SETTLED)
    before, after = rods(start), rods(run[-1][1])
    assert sorted(before) == sorted(after) and len(before) == 4
    # Along its axis, each rod moved forward: nose first (the calibrated rods walk ~4 mm/s).
    forward = [np.dot(wrap(after[b][0] - before[b][0]), before[b][1]) for b in before]
    assert np.mean(forward) > 1e-3, forward
