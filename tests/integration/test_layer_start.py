"""The layer start of examples/rods-and-beads/in.create (`-var start layer`): the rods side by
side across the width in a row, all heading +x, the rest in rows behind it, beads in the rest of
the cell at the deck's bead fraction. Checked in channel-small's geometry (60 x 15 d, phi_b 0.75):
with phi_r 0.04 its 10 rods make one row at layer_x that spans the width (no gap between two rods
or a rod and a side wall lets a bead through), each rod's nose (type 3) straight ahead of its tail
(type 1) along +x; with phi_r 0.06 the 14 rods make a full front row of 12 and a second row of 2
a rod length behind it, here across the periodic boundary (layer_x near x = 0); the asked
fractions are reached and no two particles overlap. A start layer that cannot be built stops
with an ERROR naming in.create."""
import os
import pathlib
import re
import subprocess

import numpy as np
import pytest
from scipy.spatial import cKDTree

from activegrain import read_frame

ROOT = pathlib.Path(__file__).resolve().parents[2]
CREATE = ROOT / "examples" / "rods-and-beads"
LMP = os.environ.get("ACTIVEGRAIN_LMP", str(ROOT / "build" / "lmp"))
D = 1e-3
LX, LY = 60e-3, 15e-3
TAIL, NOSE, LENGTH, GAP = 1.1e-3, 0.7e-3, 4.5e-3, 0.1e-3
DECK = """variable geometry index channel
variable Lx index 60e-3
variable Ly index 15e-3
variable phi_b index 0.75
variable phi_r index 0.04
variable start index layer
include in.create
write_dump all custom ${out}/created.dump id mol type radius x y z f_rodsfix[4] &
  modify colname f_rodsfix[4] body format float %.15g
"""
REPORT = re.compile(r"ActiveGrain channel: phi_b = ([\d.]+) \(asked ([\d.]+)\), phi_r = ([\d.]+) \(asked ([\d.]+)\), "
                    r"(\d+) beads, (\d+) rods")


def create(out, *extra):
    deck = out / "in.layer-test"
    deck.write_text(DECK)
    return subprocess.run([LMP, "-in", str(deck), "-var", "out", str(out), "-log", "none", *extra],
                          cwd=CREATE, capture_output=True, text=True, timeout=600)


def created(out, *extra):
    done = create(out, *extra)
    assert done.returncode == 0 and "ERROR" not in done.stdout, done.stdout[-3000:]
    return done.stdout, read_frame(out / "created.dump", -1)


def rods_of(frame):
    """Per rod (sorted by body ID): tail centre, nose centre (the nose unwrapped next to its tail)."""
    L = frame.box.lengths[0]
    tails, noses = [], []
    for b in np.unique(frame.body[frame.body > 0]):
        mine = frame.body == b
        assert np.count_nonzero(mine) == 9
        tail = frame.pos[mine & (frame.types == 1)]
        nose = frame.pos[mine & (frame.types == 3)]
        assert len(tail) == 1 and len(nose) == 1
        d = nose[0] - tail[0]
        d[0] -= L * np.round(d[0] / L)               # minimum image along the periodic x
        tails.append(tail[0])
        noses.append(tail[0] + d)
    return np.array(tails), np.array(noses)


def assert_no_overlaps(frame):
    xyz, r, body = frame.pos, frame.radius, frame.body
    L = frame.box.lengths[0]
    images = np.concatenate([xyz + [s * L, 0, 0] for s in (-1, 0, 1)])
    worst = 0.0
    for i, j in cKDTree(images).query_pairs(2 * r.max()):
        a, b = i % len(xyz), j % len(xyz)
        if a == b or (body[a] > 0 and body[a] == body[b]):
            continue                     # an atom's own image, or two spheres of one rod
        worst = max(worst, r[a] + r[b] - np.linalg.norm(images[i] - images[j]))
    assert worst <= 1e-6 * D, worst
    assert np.all(xyz[:, 1] - r >= 0) and np.all(xyz[:, 1] + r <= LY)


def assert_headings_along_x(tails, noses):
    d = noses - tails
    heading = d[:, :2] / np.linalg.norm(d[:, :2], axis=1)[:, None]
    assert np.all(heading[:, 0] > 1 - 1e-9), heading    # nose straight ahead of the tail, towards +x
    assert np.allclose(d[:, 0], d[0, 0], atol=1e-12) and 0.75 * LENGTH < d[0, 0] < LENGTH - 0.5 * NOSE


def row_gaps(y):
    """The clearances of a row of rods with axes at heights y: between the walls and rods."""
    y = np.sort(y)
    return np.concatenate([[y[0] - 0.5 * TAIL], np.diff(y) - TAIL, [LY - y[-1] - 0.5 * TAIL]])


def assert_row_spans_width(y):
    """Rods evenly spread across the width, every clearance (between rods and at the walls) at
    least layer_gap and narrower than a bead."""
    gaps = row_gaps(y)
    assert np.allclose(gaps, gaps[0], atol=1e-12) and GAP - 1e-12 <= gaps[0] < D, gaps


def test_one_row_spans_the_width_heading_plus_x(tmp_path):
    stdout, frame = created(tmp_path)
    phi_b, asked_b, phi_r, asked_r, beads_reported, rods = REPORT.search(stdout).groups()
    assert abs(float(phi_b) - float(asked_b)) <= 0.005 and abs(float(phi_r) - float(asked_r)) <= 0.005
    assert int(rods) == 10 and "ActiveGrain grow" not in stdout
    assert "ActiveGrain layer: 10 rods heading +x in 1 row(s) of up to 12 across the width" in stdout
    tails, noses = rods_of(frame)
    assert_headings_along_x(tails, noses)
    centre_x = 0.5 * (tails[:, 0] + noses[:, 0])
    assert np.allclose(centre_x, 0.5 * LX, atol=1e-9)          # layer_x: the channel's middle
    assert np.allclose(tails[:, 1], noses[:, 1], atol=1e-12)
    assert_row_spans_width(tails[:, 1])
    rodset = frame.rods()                                      # python/activegrain reads the same headings
    assert len(rodset) == 10 and np.all(rodset.axis[:, 0] > 1 - 1e-9)
    assert_no_overlaps(frame)
    # the beads fill the rest of the cell: none between the rods of the row
    beads = frame.body == 0
    bx, by = frame.pos[beads, 0], frame.pos[beads, 1]
    assert np.count_nonzero(beads) == int(beads_reported)
    assert not np.any(np.abs(bx - 0.5 * LX) < 0.5 * LENGTH - D)
    assert np.count_nonzero(bx < 0.5 * LX - LENGTH) > 0 and np.count_nonzero(bx > 0.5 * LX + LENGTH) > 0


def test_second_row_behind_across_the_periodic_boundary(tmp_path):
    stdout, frame = created(tmp_path, "-var", "phi_r", "0.06", "-var", "layer_x", "3e-3")
    phi_b, asked_b, _, _, _, rods = REPORT.search(stdout).groups()
    assert abs(float(phi_b) - float(asked_b)) <= 0.005 and int(rods) == 14
    assert "ActiveGrain layer: 14 rods heading +x in 2 row(s) of up to 12 across the width" in stdout
    tails, noses = rods_of(frame)
    assert_headings_along_x(tails, noses)
    centre_x = 0.5 * (tails[:, 0] + noses[:, 0])
    front = np.isclose(centre_x, 3e-3, atol=1e-9)
    back = np.isclose(centre_x % LX, (3e-3 - LENGTH - GAP) % LX, atol=1e-9)  # wrapped to x near 58 mm
    assert front.sum() == 12 and back.sum() == 2
    assert_row_spans_width(tails[front, 1])
    assert np.allclose(row_gaps(tails[back, 1]), (LY - 2 * TAIL) / 3, atol=1e-12)    # spread evenly too
    assert_no_overlaps(frame)


@pytest.mark.parametrize("extra, message", [
    (["-var", "geometry", "annulus"], "ERROR: in.create: start layer needs a box, channel or rectangle, not an annulus"),
    (["-var", "phi_r", "0.7", "-var", "phi_b", "0.1"], "deeper than the cell: lower phi_r"),
    (["-var", "geometry", "rectangle", "-var", "layer_x", "2e-3"], "do not fit between the walls: move layer_x"),
])
def test_a_layer_that_cannot_be_built_is_refused(tmp_path, extra, message):
    done = create(tmp_path, *extra)
    assert done.returncode == 1 and message in done.stdout, done.stdout[-2000:]
