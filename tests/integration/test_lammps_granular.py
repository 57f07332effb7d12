"""LAMMPS's own 3-D granular example, examples/pour/in.pour, with pair gran/impulse and fix
wall/impulse substituted (examples/lammps-granular/in.pour), shortened: grains poured into an
empty box after the run's setup meet each other and the floor (the neighbor cutoff comes from
fix pour's radius), spin, and none leaves the box during the chute stage."""
import os
import pathlib
import re
import subprocess

ROOT = pathlib.Path(__file__).resolve().parents[2]
LMP = os.environ.get("ACTIVEGRAIN_LMP", str(ROOT / "build" / "lmp"))
THERMO = re.compile(r"^\s+(\d+)\s+(\d+)\s+(\S+)\s+(\S+)\s+(\S+)\s+(\S+)\s+(\S+)\s+(\S+)\s*$", re.M)


def test_poured_grains_collide_spin_and_stay_in_the_box(tmp_path):
    steps = 4000
    done = subprocess.run([LMP, "-in", str(ROOT / "examples" / "lammps-granular" / "in.pour"),
                           "-var", "steps", str(steps), "-var", "resolution", "20",
                           "-log", str(tmp_path / "log.lammps")],
                          cwd=tmp_path, capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stdout[-3000:] + done.stderr[-3000:]
    assert "ERROR" not in done.stdout
    rows = [tuple(float(v) for v in m.groups()) for m in THERMO.finditer(done.stdout)]
    # step atoms ke erotate vol contacts substeps largest-overlap
    last = rows[-1]
    assert last[0] == 2 * steps
    assert last[1] == 804                   # two insertions by step 4000, none lost since
    assert last[4] == 6600                  # the box did not grow
    assert max(r[5] for r in rows) > 50     # contacts found
    assert last[3] > 1.0                    # grains spin (stock at this point: about 50)
    assert 0 < max(r[7] for r in rows) < 0.01    # overlaps below 1% of a diameter
