"""The grow start of examples/rods-and-beads/in.create: where the lattice cannot hold the beads
(here a 16 x 8 mm channel at phi_b 0.75 with two rods, phi_r 0.06), `start auto` places them
smaller and grows them with the contacts on. Checked on 1 and 2 ranks: the asked fractions are
reached, no two particles (nor a bead and a side wall) overlap by more than 1e-3 bead diameters
in the dumped configuration, the rods are intact (in.check-rods passes inside in.create, and
python/activegrain finds two straight chains of nine spheres), and the lattice start alone
refuses this target. A target the lattice holds does not grow (the example decks' set-ups are
those of the lattice start)."""
import os
import pathlib
import re
import subprocess

import numpy as np
import pytest
from scipy.spatial import cKDTree

from mpi_launch import mpi_prefix

from activegrain import read_frame

ROOT = pathlib.Path(__file__).resolve().parents[2]
CREATE = ROOT / "examples" / "rods-and-beads"
LMP = os.environ.get("ACTIVEGRAIN_LMP", str(ROOT / "build" / "lmp"))
D = 1e-3
OVERLAP_TOLERANCE = 1e-3 * D
DECK = """variable geometry index channel
variable Lx index 16e-3
variable Ly index 8e-3
variable phi_b index 0.75
variable phi_r index 0.06
variable grow_phi index 0.65
include in.create
write_dump all custom ${out}/created.dump id mol type radius x y z f_rodsfix[4] &
  modify colname f_rodsfix[4] body format float %.15g
"""
REPORT = re.compile(r"ActiveGrain channel: phi_b = ([\d.]+) \(asked ([\d.]+)\), phi_r = ([\d.]+) \(asked ([\d.]+)\), "
                    r"(\d+) beads, (\d+) rods")


def create(out, ranks, *extra):
    deck = out / "in.grow-test"
    deck.write_text(DECK)
    return subprocess.run([*mpi_prefix(ranks), LMP, "-in", str(deck), "-var", "out", str(out), "-log", "none", *extra],
                          cwd=CREATE, capture_output=True, text=True, timeout=600)


@pytest.fixture(scope="module", params=[1, 2])
def grown(request, tmp_path_factory):
    out = tmp_path_factory.mktemp(f"grow-{request.param}")
    done = create(out, request.param)
    assert done.returncode == 0 and "ERROR" not in done.stdout, done.stdout[-3000:]
    return done.stdout, out


def test_grow_start_reaches_the_asked_fractions(grown):
    stdout, _ = grown
    assert "ActiveGrain grow:" in stdout                          # the lattice did not hold them
    m = REPORT.search(stdout)
    phi_b, asked_b, phi_r, asked_r, beads, rods = m.groups()
    assert abs(float(phi_b) - float(asked_b)) <= 0.005
    assert abs(float(phi_r) - float(asked_r)) <= 0.005 and int(rods) == 2
    grown_report = re.search(r"largest overlap after growing (\S+) d \(at most \S+\), settled for (\d+) steps", stdout)
    assert float(grown_report.group(1)) <= 1e-3
    assert 0 < int(grown_report.group(2)) < 2000        # the settling stopped once the overlaps were within


def test_grown_packing_has_no_overlaps_and_intact_rods(grown):
    _, out = grown
    frame = read_frame(out / "created.dump", -1)
    rods = frame.rods()                  # refuses a rod that is not one straight chain of spheres
    assert len(rods) == 2 and all(np.count_nonzero(frame.body == b) == 9 for b in np.unique(frame.body[frame.body > 0]))
    xyz, r, body = frame.pos, frame.radius, frame.body
    # minimum image along the periodic x only: a tree over x unwrapped by one period each side
    L = frame.box.lengths[0]
    images = np.concatenate([xyz + [s * L, 0, 0] for s in (-1, 0, 1)])
    tree = cKDTree(images)
    worst = 0.0
    for i, j in tree.query_pairs(2 * r.max()):
        a, b = i % len(xyz), j % len(xyz)
        if a == b or (body[a] > 0 and body[a] == body[b]):
            continue                     # an atom's own image, or two spheres of one rod
        gap = np.linalg.norm(images[i] - images[j]) - r[a] - r[b]
        worst = max(worst, -gap)
    assert worst <= OVERLAP_TOLERANCE, worst
    beads = body == 0
    y = xyz[beads, 1]
    assert np.all(y - r[beads] >= -OVERLAP_TOLERANCE) and np.all(y + r[beads] <= 8e-3 + OVERLAP_TOLERANCE)
    assert np.all(xyz[:, 2] - r >= -OVERLAP_TOLERANCE) and np.all(xyz[:, 2] + r <= 1.12e-3 + OVERLAP_TOLERANCE)


def test_lattice_start_refuses_what_the_grow_start_reaches(tmp_path):
    done = create(tmp_path, 1, "-var", "start", "lattice")
    assert done.returncode == 1
    assert re.search(r"ERROR: in\.create: phi_b 0\.75 needs \d+ beads, only \d+ fit \(start lattice", done.stdout)


def test_a_target_the_lattice_holds_is_not_grown(tmp_path):
    done = create(tmp_path, 1, "-var", "phi_b", "0.6")
    assert done.returncode == 0, done.stdout[-2000:]
    assert "ActiveGrain grow" not in done.stdout and REPORT.search(done.stdout)


@pytest.mark.parametrize("extra, message", [
    (["-var", "start", "compress"], "ERROR: in.create: start must be auto, lattice or grow, not compress"),
    (["-var", "grow_phi", "0.8"], "ERROR: in.create: the grow start places beads at grow_phi 0.8, which must be below phi_b 0.75"),
    (["-var", "grow_speed", "-0.1"], "ERROR: in.create: grow_speed -0.1 must be >= 0"),
])
def test_bad_start_settings_are_refused(tmp_path, extra, message):
    done = create(tmp_path, 1, *extra)
    assert done.returncode == 1 and message in done.stdout, done.stdout[-2000:]


def test_overlaps_left_after_settling_are_refused(tmp_path):
    # a packing grown cold keeps overlaps above 1e-30 d (a hot one can settle to none): the
    # settling runs all grow_settle steps, then stops
    done = create(tmp_path, 1, "-var", "grow_overlap", "1e-30", "-var", "grow_settle", "400",
                  "-var", "grow_speed", "0", "-var", "grow_e", "0.3", "-var", "grow_mu", "0.05")
    assert done.returncode == 1, done.stdout[-2000:]
    assert re.search(r"largest overlap after growing \S+ d \(at most 1e-30\), settled for 400 steps", done.stdout)
    assert re.search(r"ERROR: in\.create: phi_b 0\.75 with phi_r 0\.06 not reached by growing the beads: overlaps of \S+ d "
                     r"remain \(grow_overlap 1e-30\)", done.stdout)


def test_cold_growth_reaches_the_asked_fractions(tmp_path):
    # grow_speed 0: the beads grow at rest under a drag (the grow start before hot growth)
    done = create(tmp_path, 1, "-var", "grow_speed", "0", "-var", "grow_e", "0.3", "-var", "grow_mu", "0.05")
    assert done.returncode == 0 and "ERROR" not in done.stdout, done.stdout[-2000:]
    phi_b, asked_b = REPORT.search(done.stdout).groups()[:2]
    assert abs(float(phi_b) - float(asked_b)) <= 0.005


def test_hot_growth_reaches_the_jammed_corner(tmp_path):
    # a total of 0.86 in half of channel-small (30 x 15 d), past the ~0.855 at which a packing
    # grown at rest locks (examples/README.md); in seconds
    done = create(tmp_path, 1, "-var", "Lx", "30e-3", "-var", "Ly", "15e-3", "-var", "phi_b", "0.82", "-var", "phi_r", "0.04",
                  "-var", "grow_phi", "0.6")
    assert done.returncode == 0 and "ERROR" not in done.stdout, done.stdout[-2000:]
    phi_b, _, phi_r, _, _, rods = REPORT.search(done.stdout).groups()
    assert float(phi_b) + float(phi_r) >= 0.86 and int(rods) == 5
