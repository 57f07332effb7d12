"""examples/minimal/in.minimal, the complete deck of the docs: it runs on 1 and 2 ranks, keeps
its atoms and its 4 rods, and its rods walk nose first from vibration and friction alone; and the
README's commands for it, taken from the README itself, run as written and draw its picture."""
import os
import pathlib
import re
import shutil
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


README = ROOT / "README.md"


def readme_minimal_block():
    """The README's shell block that runs examples/minimal: its lines, as the README shows them."""
    blocks = re.findall(r"^```(?:sh|bash|console)?\n(.*?)^```", README.read_text(), re.S | re.M)
    found = [b for b in blocks if "examples/minimal" in b]
    assert len(found) == 1, "README.md: one code block that runs examples/minimal expected"
    return found[0].splitlines()


def test_readme_block_is_the_deck_and_a_picture_of_its_polar_order():
    lines = readme_minimal_block()
    assert any(re.match(r"source build/activegrain-env\.sh(\s|$)", l) for l in lines), lines
    assert any(re.match(r"cd examples/minimal && lmp -in in\.minimal(\s|$)", l) for l in lines), lines
    assert any(l.startswith("activegrain snapshot minimal.dump ") for l in lines), lines


def test_readme_commands_for_the_minimal_deck_run_as_written(tmp_path):
    """A copy of the repository's examples/minimal beside the build in use; the README's block,
    line for line, run by bash from the copy's root: the deck runs and the picture is drawn. The
    python3 first on PATH is not Debian's (it only exits 1), as under pyenv: the command activegrain
    runs Debian's all the same."""
    lines = readme_minimal_block()
    root = tmp_path / "repo"
    shutil.copytree(ROOT / "examples" / "minimal", root / "examples" / "minimal")
    (root / "build").symlink_to(pathlib.Path(LMP).resolve().parent)   # build/activegrain-env.sh, build/lmp, build/bin
    other = tmp_path / "other-python"
    other.mkdir()
    (other / "python3").write_text("#!/bin/sh\necho 'not the python3 of Debian' >&2\nexit 1\n")
    (other / "python3").chmod(0o755)
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "LAMMPS_PLUGIN_PATH")}
    env.update(PATH=os.pathsep.join([str(other), os.environ.get("PATH", "")]), MPLBACKEND="Agg")
    script = "set -eo pipefail\n" + "\n".join(lines) + "\n"
    done = subprocess.run(["bash", "-c", script], cwd=root, env=env, capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, script + done.stdout[-3000:] + done.stderr[-3000:]
    assert "ERROR" not in done.stdout and "Traceback" not in done.stderr, done.stdout[-2000:] + done.stderr
    assert done.stdout.count("Loaded 1 plugins from") == 1, done.stdout[:2000]    # lmp loads the plugin once
    out = root / "examples" / "minimal"
    assert (out / "minimal.dump").stat().st_size > 0
    picture = re.search(r"-o (\S+)", next(l for l in lines if "activegrain snapshot" in l)).group(1)
    png = out / picture
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and png.stat().st_size > 20000
    assert f"wrote {picture}" in done.stdout
    # the deck printed its rods' polar order (thermo: step time c_order ...) at its last step
    last = [l.split() for l in done.stdout.splitlines() if l.split()[:1] == ["10000"]]
    assert last and 0 <= float(last[-1][2]) <= 1, done.stdout[-2000:]
