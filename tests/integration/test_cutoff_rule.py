"""The ghost cutoff rule (src/USER-ACTIVEGRAIN/ghost_cutoff.h): the value that fix rigid/rod quotes on
one rank for a cutoff too small for a rod runs unchanged on 2, 4 and 8 ranks (8 oversubscribed;
tests/lammps/test_mpi_cutoff_rule.cpp checks 1, 2 and 4 in-process)."""
import os
import pathlib
import re
import subprocess

import pytest

from mpi_launch import mpi_prefix

ROOT = pathlib.Path(__file__).resolve().parents[2]
LMP = os.environ.get("ACTIVEGRAIN_LMP", str(ROOT / "build" / "lmp"))

# Four paper rods in a periodic box, moving, no gravity.
DECK = """units si
atom_style sphere
atom_modify map array
fix molecule_ids all property/atom mol ghost yes
boundary p p p
region box block -6e-3 6e-3 -6e-3 6e-3 -6e-3 6e-3
create_box 3 box
comm_modify vel yes cutoff ${cutoff}
neighbor 5e-4 bin
rod_template rod length 4.5e-3 tail 1.1e-3 nose 0.7e-3 spheres 9 density 8500 types 1 2 3
create_atoms 0 single -3e-3 -3e-3 0 mol rod 1 units box rotate 0 0 0 1
create_atoms 0 single 3e-3 -3e-3 0 mol rod 2 units box rotate 90 0 0 1
create_atoms 0 single -3e-3 3e-3 0 mol rod 3 units box rotate 45 0 0 1
create_atoms 0 single 3e-3 3e-3 0 mol rod 4 units box rotate 135 0 1 0
velocity all create 1e-6 4928 mom yes rot yes dist gaussian
pair_style gran/impulse
pair_coeff * * 0.3 0.05
fix rods all rigid/rod molecule mol rod
timestep 1e-5
thermo_style custom step
run 200 post no
"""


def run(tmp_path, ranks, cutoff):
    deck = tmp_path / "in.cutoff"
    deck.write_text(DECK)
    return subprocess.run([*mpi_prefix(ranks), LMP, "-in", str(deck), "-var", "cutoff", str(cutoff), "-log", "none"],
                          cwd=tmp_path, capture_output=True, text=True, timeout=120)


@pytest.fixture(scope="module")
def quoted(tmp_path_factory):
    done = run(tmp_path_factory.mktemp("quote"), 1, "1e-3")
    m = re.search(r"ERROR: Fix rigid/rod: rod extent \S+ exceeds the ghost cutoff \S+: use comm_modify cutoff (\S+) "
                  r"\(valid on any number of ranks\)", done.stdout)
    assert m, done.stdout[-2000:]
    return m.group(1)


@pytest.mark.parametrize("ranks", [1, 2, 4, 8])
def test_the_cutoff_quoted_on_one_rank_runs_on_any_number_of_ranks(tmp_path, quoted, ranks):
    done = run(tmp_path, ranks, quoted)
    assert done.returncode == 0 and "ERROR" not in done.stdout, done.stdout[-2000:] + done.stderr[-2000:]
    assert f"on {ranks} procs for 200 steps" in done.stdout
