"""examples/dense-law/in.compress, the crystal's pressure against its area fraction: in both cells
the piston reaches the total asked and holds it, pressing on the beads (its pressure positive, of
the order the vibrated bed gives: mN/m), and moves along the cell's axis (a piston moved along
the wrong axis leaves the beads unpressed); a geometry it does not know is an ERROR naming it."""
import os
import pathlib
import subprocess

import numpy as np
import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
DECK_DIR = ROOT / "examples" / "dense-law"
LMP = os.environ.get("ACTIVEGRAIN_LMP", str(ROOT / "build" / "lmp"))
TOTAL = 0.80
# A short schedule: 0.05 s to the total, held 0.3 s, rows of 0.05 s.
SHORT = ["-var", "ramp", "0.05", "-var", "hold", "0.3", "-var", "block", "0.05", "-var", "totals", str(TOTAL)]


def compress(geometry, out):
    done = subprocess.run([LMP, "-in", "in.compress", "-var", "geometry", geometry, "-var", "out", str(out),
                           "-log", str(out / "log.lammps"), *SHORT],
                          cwd=DECK_DIR, capture_output=True, text=True, timeout=300)
    return done


@pytest.mark.parametrize("geometry", ["rectangle", "channel"])
def test_piston_reaches_the_total_and_presses(tmp_path, geometry):
    done = compress(geometry, tmp_path)
    assert done.returncode == 0, done.stdout[-3000:] + done.stderr[-3000:]
    assert f"ActiveGrain compress: holding area fraction {TOTAL}" in done.stdout
    step, pressure, total = np.loadtxt(tmp_path / "piston.txt", unpack=True)
    held = np.isclose(total, TOTAL, atol=1e-9)
    assert held.sum() >= 5, total
    assert np.all(pressure[held] > 2e-4) and np.all(pressure[held] < 2e-2), pressure[held]


def test_unknown_geometry_is_an_error(tmp_path):
    done = compress("box", tmp_path)
    assert done.returncode != 0
    assert "ERROR: in.compress: geometry must be rectangle or channel, not box" in done.stdout
