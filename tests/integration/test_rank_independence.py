"""One physics on any number of ranks: 10 steps of a dense packing end with the same velocities on
1, 2, 4 and 8 ranks, to the solve's round-off, with the processor grid cut through the packing's
islands (in x and in y). An island whose contacts are found on several ranks is solved whole
(docs/pair_gran_impulse.rst, "Parallel runs"); solved in pieces, the jammed corner's velocities
differed by up to 2.3e-2 m/s after 10 steps on 2 ranks. The states are the shipped ones:
channel-small's jammed corner (one island spanning the packing; also with resting newton) and its
condensate (a rod layer pushing a bead crystal)."""
import os

import numpy as np
import pytest

from test_examples import EXAMPLES, LMP
from mpi_launch import mpi_prefix
import subprocess

# The processor grid of each rank count: cuts along x and, from 4 ranks on, along y too.
GRIDS = {1: (1, 1), 2: (2, 1), 4: (2, 2), 8: (4, 2)}
STATES = {
    "jammed-corner": ["-var", "Lx", "30e-3", "-var", "phi_b", "0.8203", "-var", "phi_r", "0.0414",
                      "-var", "from", "states/channel-small-jammed-corner-0s.data.gz", "-var", "time", "0.001"],
    "condensed": ["-var", "from", "states/channel-small-condensed-500s.data.gz", "-var", "time", "500.001"],
}
# The jammed corner again with pair gran/impulse's resting newton (its expansion and energy bound).
STATES["jammed-corner-newton"] = STATES["jammed-corner"] + ["-var", "resting", "newton"]
TOLERANCE = 1e-5    # m/s (the bound; an island solved whole agrees to round-off)

WRAPPER = """processors ${px} ${py} 1
include in.channel-small
write_dump all custom ${out}/final.dump id vx vy vz omegax omegay omegaz modify format float %.17g sort id
"""


def final_velocities(tmp_path, state, ranks):
    out = tmp_path / f"{state}-{ranks}"
    out.mkdir()
    deck = tmp_path / "in.wrapper"
    deck.write_text(WRAPPER)
    px, py = GRIDS[ranks]
    done = subprocess.run([*mpi_prefix(ranks), LMP, "-in", str(deck), "-var", "out", str(out), "-var", "px", str(px),
                           "-var", "py", str(py), "-var", "dump", "1", "-var", "profile", "0.1", "-log", "none",
                           *STATES[state]],
                          cwd=EXAMPLES / "channel", capture_output=True, text=True, timeout=600)
    assert done.returncode == 0 and "ERROR" not in done.stdout, done.stdout[-3000:] + done.stderr[-2000:]
    lines = (out / "final.dump").read_text().splitlines()
    start = lines.index(next(line for line in lines if line.startswith("ITEM: ATOMS"))) + 1
    return np.loadtxt(lines[start:])


@pytest.fixture(scope="module")
def one_rank(tmp_path_factory):
    base = tmp_path_factory.mktemp("one-rank")
    return {state: final_velocities(base, state, 1) for state in STATES}


@pytest.mark.parametrize("state", list(STATES))
@pytest.mark.parametrize("ranks", [2, 4, 8])
def test_ten_steps_of_a_dense_packing_end_alike_on_any_number_of_ranks(tmp_path, one_rank, state, ranks):
    reference = one_rank[state]
    found = final_velocities(tmp_path, state, ranks)
    assert np.array_equal(found[:, 0], reference[:, 0])    # the same atoms
    speeds = np.abs(reference[:, 1:4]).max()
    difference = np.abs(found[:, 1:4] - reference[:, 1:4]).max()
    print(f"{state} on {ranks} ranks: largest velocity difference {difference:.3g} m/s "
          f"(largest velocity component {speeds:.3g} m/s)")
    assert speeds > 1e-3    # the packing moves: a difference could show
    assert difference <= TOLERANCE
