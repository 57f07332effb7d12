"""examples/own-deck/in.own-deck, the worked example of docs/own_deck.rst: a 40 x 20 mm cell,
periodic in x, side walls along y, 12 rods heading +y, beads at area fraction 0.70, made by
in.create with -var orient angle -var heading 90 -var rods 12. It runs on 1 and 2 ranks, keeps
its atoms and rods, creates the bead fraction asked to within half a bead, starts every rod at the
heading asked and keeps every particle between the walls; and in.create refuses an orient it does
not know, orient angle without a heading (or with one that is not a number) and orient angle with
the layer start, each with an ERROR that names the variable."""
import math
import os
import pathlib
import re
import subprocess

import numpy as np
import pytest

from mpi_launch import mpi_prefix

ROOT = pathlib.Path(__file__).resolve().parents[2]
OWN_DECK = ROOT / "examples" / "own-deck"
CHANNEL = ROOT / "examples" / "channel"
LMP = os.environ.get("ACTIVEGRAIN_LMP", str(ROOT / "build" / "lmp"))
LX, LY = 40e-3, 20e-3        # the deck's cell, m: periodic in x, walls at y = 0 and LY
PHI_B, RODS, HEADING = 0.70, 12, 90.0
BEAD_AREA = math.pi * 0.5e-3 ** 2
# in.create fills a lattice that holds more beads than asked (cut around the rods) and deletes
# random ones down to round(phi_b A / bead area): the fraction is the asked one to half a bead.
HALF_BEAD = 0.5 * BEAD_AREA / (LX * LY)          # 4.9e-4
ANGLE = 0.01                 # degrees: a rod's heading from the dump's 6 digits (1e-8 m on 4 mm)
WALL_OVERLAP = 1e-5          # m, a hundredth of a bead: the most a particle may press into a wall
REPORT = re.compile(r"ActiveGrain channel: phi_b = (\S+) \(asked (\S+)\), phi_r = \S+ \(asked \S+\), (\d+) beads, (\d+) rods")
LOOP = re.compile(r"Loop time of \S+ on (\d+) procs for (\d+) steps with (\d+) atoms")


def frames(dump):
    """Per frame of the deck's dump: an array of rows (id, type, radius, x, y, body), sorted by id."""
    out, lines = [], dump.read_text().splitlines()
    i = 0
    while i < len(lines):
        n = int(lines[i + 3])
        c = {name: k for k, name in enumerate(lines[i + 8].split()[2:])}
        rows = np.array([[float(v) for v in line.split()] for line in lines[i + 9:i + 9 + n]])
        out.append(rows[:, [c["id"], c["type"], c["radius"], c["x"], c["y"], c["body"]]])
        i += 9 + n
    return out


def headings(frame):
    """Per rod (by body ID): its heading in degrees from +x, the in-plane direction from its tail
    sphere (type 1) to its nose sphere (type 3), across the periodic x."""
    result = {}
    for body in np.unique(frame[frame[:, 5] > 0, 5]):
        spheres = frame[frame[:, 5] == body]
        tail, nose = spheres[spheres[:, 1] == 1][0, 3:5], spheres[spheres[:, 1] == 3][0, 3:5]
        dx, dy = nose - tail
        dx -= LX * round(dx / LX)
        result[int(body)] = math.degrees(math.atan2(dy, dx))
    return result


def own_deck(out, ranks=1, *extra):
    done = subprocess.run([*mpi_prefix(ranks), LMP, "-in", "in.own-deck", "-var", "out", str(out),
                           "-log", str(out / "log.lammps"), *extra],
                          cwd=OWN_DECK, capture_output=True, text=True, timeout=600)
    assert done.returncode == 0 and "ERROR" not in done.stdout, done.stdout[-3000:] + done.stderr[-3000:]
    return done.stdout


@pytest.mark.parametrize("ranks", [1, 2])
def test_own_deck_keeps_its_rods_heading_plus_y_between_the_walls_at_the_bead_fraction_asked(tmp_path, ranks):
    stdout = own_deck(tmp_path, ranks)
    loop = LOOP.findall(stdout)[-1]
    assert loop == (str(ranks), "20000", "821"), loop        # 2 s; 713 beads and 12 rods of 9 spheres
    reached, asked, beads, rods = REPORT.search(stdout).groups()
    assert float(asked) == PHI_B and abs(float(reached) - PHI_B) <= HALF_BEAD and int(rods) == RODS
    run = frames(tmp_path / "own-deck.dump")
    assert len(run) == 21                                     # every 0.1 s
    created = run[0]
    is_bead = created[:, 1] == 4
    assert is_bead.sum() == int(beads) == 713
    # the created state's bead fraction, from the beads' discs: the one asked, to half a bead
    assert abs(np.sum(np.pi * created[is_bead, 2] ** 2) / (LX * LY) - PHI_B) <= HALF_BEAD
    started = headings(created)
    assert len(started) == RODS and all(abs(a - HEADING) < ANGLE for a in started.values()), started
    for frame in run:
        assert np.array_equal(frame[:, 0], created[:, 0])     # no atom lost
        assert len(headings(frame)) == RODS
        y, radius = frame[:, 4], frame[:, 2]
        assert (y - radius).min() >= -WALL_OVERLAP and (y + radius).max() <= LY + WALL_OVERLAP


def test_in_create_starts_the_rods_at_any_heading_asked(tmp_path):
    """A heading of -30 degrees and 5 rods, the system created and not run."""
    stdout = own_deck(tmp_path, 1, "-var", "heading", "-30", "-var", "rods", "5", "-var", "time", "0")
    assert REPORT.search(stdout).group(4) == "5"
    started = headings(frames(tmp_path / "own-deck.dump")[0])
    assert len(started) == 5 and all(abs(a + 30) < ANGLE for a in started.values()), started


@pytest.mark.parametrize("words, error", [
    (["-var", "orient", "angle"], "orient angle needs -var heading A"),
    (["-var", "orient", "angle", "90"], "orient angle needs -var heading A"),     # a two-valued orient
    (["-var", "orient", "angle", "-var", "heading", "north"], "heading north is not a number"),
    (["-var", "orient", "sideways"], "orient must be random, tangential or angle (with -var heading A), not sideways"),
    (["-var", "orient", "90"], "orient must be random, tangential or angle (with -var heading A), not 90"),
    (["-var", "orient", "angle", "-var", "heading", "90", "-var", "start", "layer"],
     "start layer heads its rods +x: orient angle (heading 90) is for the other starts"),
], ids=["no heading", "two-word orient", "heading not a number", "unknown orient", "orient a number",
        "with start layer"])
def test_in_create_refuses_a_heading_it_cannot_use_naming_the_variable(tmp_path, words, error):
    done = subprocess.run([LMP, "-in", "in.channel-small", "-var", "out", str(tmp_path), "-log", "none", *words],
                          cwd=CHANNEL, capture_output=True, text=True, timeout=120)
    assert done.returncode == 1, done.stdout[-3000:] + done.stderr[-3000:]
    errors = [line for line in done.stdout.splitlines() if "ERROR" in line]
    assert len(errors) == 1 and errors[0].startswith(f"ERROR: in.create: {error}"), errors
    assert "Loop time" not in done.stdout                     # stopped before any run
