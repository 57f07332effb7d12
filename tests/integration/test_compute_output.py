"""compute polar/rod and compute areafrac/chunk through LAMMPS's output commands, on 1 and 2 ranks."""
import os
import subprocess

import numpy as np
import pytest

LMP = os.environ["ACTIVEGRAIN_LMP"]
MPIRUN = os.environ.get("ACTIVEGRAIN_MPIRUN", "mpirun")

DECK = """
units si
atom_style sphere
atom_modify map array
boundary p p f
comm_modify vel yes cutoff 6e-3
fix molecule_ids all property/atom mol ghost yes
region box block 0 0.024 0 0.012 -1e-4 1.22e-3 units box
create_box 4 box
rod_template rod length 4.5e-3 tail 1.1e-3 nose 0.7e-3 spheres 9 density 8500 types 1 2 3
pair_style gran/impulse
pair_coeff * * 0.3 0.05
create_atoms 0 single 0.0050 0.003 5.6e-4 mol rod 11 units box rotate 0 0 0 1
create_atoms 0 single 0.0119 0.009 5.6e-4 mol rod 12 units box rotate 20 0 0 1
create_atoms 0 single 0.0235 0.003 5.6e-4 mol rod 13 units box rotate -20 0 0 1
create_atoms 4 single 0.016 0.003 5.6e-4 units box
create_atoms 4 single 0.004 0.009 5.6e-4 units box
set type 4 diameter 1e-3
set type 4 density 2700
group rods type 1 2 3
neigh_modify exclude molecule/intra rods
fix rods rods rigid/rod molecule mol rod
group beads type 4
fix beads beads nve/sphere
compute tsphere all temp/sphere
thermo_modify temp tsphere
compute order all polar/rod
compute slabs all chunk/atom bin/1d x lower 0.003 units box
compute phi all areafrac/chunk slabs
thermo_style custom step c_order c_order[5] c_order[6]
fix profile all ave/time 1 1 1 c_phi[*] mode vector file profile.dat
fix polar all ave/time 1 1 1 c_order[*] file polar.dat
dump table all local 1 rods.local c_order[1] c_order[2] c_order[5] c_order[6]
run 1
"""


def run_deck(tmp_path, np_):
    tmp_path.mkdir(parents=True, exist_ok=True)
    (tmp_path / "in.deck").write_text(DECK)
    cmd = [LMP, "-in", "in.deck", "-log", "log.lammps"]
    if np_ > 1:
        cmd = [MPIRUN, "--allow-run-as-root", "--oversubscribe", "-np", str(np_)] + cmd
    out = subprocess.run(cmd, cwd=tmp_path, capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stdout[-2000:] + out.stderr[-2000:]
    return tmp_path


def profile(path):
    rows = [l.split() for l in (path / "profile.dat").read_text().splitlines()
            if l.strip() and not l.startswith("#")]
    # Blocks of "step nrows" then nrows of "chunk phi_b phi_r n Px Py |P|": keep the last block.
    nrows = int(rows[-9][1]) if len(rows[-9]) == 2 else 8
    return np.array([[float(v) for v in r] for r in rows[-nrows:]])


def rod_table(path):
    lines = (path / "rods.local").read_text().splitlines()
    start = max(i for i, l in enumerate(lines) if l.startswith("ITEM: ENTRIES"))
    return np.array([[float(v) for v in l.split()] for l in lines[start + 1:]])


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    base = tmp_path_factory.mktemp("computes")
    return {n: run_deck(base / f"np{n}", n) for n in (1, 2)}


def test_profile_counts_every_rod_and_bead_once(runs):
    prof = profile(runs[1])
    assert prof.shape == (8, 7)
    bin_area = 0.003 * 0.012
    assert prof[:, 3].sum() == pytest.approx(3.0, abs=1e-6)                 # rods
    assert (prof[:, 1].sum() * bin_area) == pytest.approx(2 * np.pi * 0.5e-3 ** 2, rel=1e-6)   # %g output
    assert 0.0 < prof[:, 2].max() < 1.0
    assert np.all(prof[:, 6] <= 1.0 + 1e-12)


def test_rod_table_has_each_rod_once(runs):
    table = rod_table(runs[1])
    assert table.shape == (3, 4)
    np.testing.assert_allclose(sorted(table[:, 2]), sorted(np.cos(np.radians([0, 20, -20]))), atol=1e-6)   # px


def test_same_output_on_two_ranks(runs):
    np.testing.assert_allclose(profile(runs[2]), profile(runs[1]), rtol=1e-12, atol=1e-15)
    one, two = rod_table(runs[1]), rod_table(runs[2])
    np.testing.assert_allclose(sorted(map(tuple, two)), sorted(map(tuple, one)), rtol=1e-9)
    polar = [np.loadtxt(r / "polar.dat")[-1] for r in (runs[1], runs[2])]
    np.testing.assert_allclose(polar[1], polar[0], rtol=1e-12)
    assert polar[0][1] == pytest.approx(abs(1 + 2 * np.cos(np.radians(20))) / 3, rel=1e-6)
