"""The example decks: each small variant sets up the requested area fractions (as compute
areafrac/chunk measures them) and runs a few hundred steps on 1 and 2 ranks without losing atoms."""
import os
import pathlib
import re
import subprocess

import pytest

from mpi_launch import mpi_prefix

ROOT = pathlib.Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples"
LMP = os.environ.get("ACTIVEGRAIN_LMP", str(ROOT / "build" / "lmp"))
STEPS = 200           # four vibration periods at the decks' dt: beads and rods meet the plates and each other
DT = 1.0e-4           # the decks' time step
TOLERANCE = 0.005

# (example folder, deck, extra variables, the name the deck reports under)
DECKS = {
    "box": ("box", "in.box-small", [], "box"),
    "annulus": ("annulus", "in.annulus-small", [], "annulus"),
    "annulus-floral": ("annulus", "in.annulus-small", ["-var", "floral", "yes"], "annulus"),
    "annulus-tangential": ("annulus", "in.annulus-small", ["-var", "orient", "tangential"], "annulus"),
    "channel": ("channel", "in.channel-small", [], "channel"),
    # (phi_b 0.65: the lattice holds it; the deck's 0.75 takes the slower grow start)
    "rectangle": ("box", "in.rectangle-small", ["-var", "phi_b", "0.65"], "rectangle"),
}

SETUP = re.compile(r"ActiveGrain (\w+): .*phi_b = ([\d.]+) \(asked ([\d.]+)\), "
                   r"phi_r = ([\d.]+) \(asked ([\d.]+)\), (\d+) beads, (\d+) rods")
LOOP = re.compile(r"Loop time of \S+ on (\d+) procs for (\d+) steps with (\d+) atoms")


def run_deck(name, ranks, out):
    folder, deck, extra, _ = DECKS[name]
    cmd = [*mpi_prefix(ranks), LMP, "-in", deck, "-var", "out", str(out),
           "-var", "time", str(STEPS * DT), "-log", str(out / "log.lammps"), *extra]
    done = subprocess.run(cmd, cwd=EXAMPLES / folder, capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stdout[-3000:] + done.stderr[-3000:]
    assert "ERROR" not in done.stdout, done.stdout[-3000:]
    return done.stdout


@pytest.fixture(scope="module")
def outputs(tmp_path_factory):
    """Each deck's screen output on 1 and 2 ranks, run once for all tests."""
    cache = {}

    def get(name, ranks):
        if (name, ranks) not in cache:
            out = tmp_path_factory.mktemp(f"{name}-{ranks}")
            cache[name, ranks] = run_deck(name, ranks, out)
        return cache[name, ranks]
    return get


def setup_report(stdout, name):
    found = [m for m in SETUP.finditer(stdout) if m.group(1) == DECKS[name][3]]
    assert len(found) == 1, stdout[-3000:]
    m = found[0]
    return dict(phi_b=float(m.group(2)), asked_b=float(m.group(3)), phi_r=float(m.group(4)),
                asked_r=float(m.group(5)), beads=int(m.group(6)), rods=int(m.group(7)))


@pytest.mark.parametrize("ranks", [1, 2])
@pytest.mark.parametrize("name", sorted(DECKS))
def test_requested_area_fractions(outputs, name, ranks):
    report = setup_report(outputs(name, ranks), name)
    assert report["rods"] > 0 and report["beads"] > 0
    assert abs(report["phi_b"] - report["asked_b"]) <= TOLERANCE, report
    assert abs(report["phi_r"] - report["asked_r"]) <= TOLERANCE, report


@pytest.mark.parametrize("ranks", [1, 2])
@pytest.mark.parametrize("name", sorted(DECKS))
def test_run_completes_without_losing_atoms(outputs, name, ranks):
    stdout = outputs(name, ranks)
    report = setup_report(stdout, name)
    loops = [tuple(map(int, m.groups())) for m in LOOP.finditer(stdout)]
    procs, steps, atoms = loops[-1]
    assert (procs, steps) == (ranks, STEPS)
    rod_atoms = 9 * report["rods"]
    assert atoms == report["beads"] + rod_atoms
    assert f"run completed with {report['beads']} beads and {rod_atoms} rod atoms" in stdout


@pytest.mark.parametrize("name", sorted(DECKS))
def test_same_system_on_1_and_2_ranks(outputs, name):
    assert setup_report(outputs(name, 1), name) == setup_report(outputs(name, 2), name)


# Beads given a rod's molecule ID after creation, as LAMMPS left them on 2 ranks (issue 9). The
# rigid fix is replaced around `set`: LAMMPS 4Jul2026's set command crashes on a rigid fix that
# has been set up (it checks the atoms it is about to select before selecting them).
CHECK_DECK = """variable geometry index channel
variable Lx index 30e-3
variable Ly index 10e-3
variable phi_b index 0.7
include in.create
unfix rodsfix
set group beads mol 1
fix rodsfix rods rigid/rod molecule mol rod
run 0 post no
include in.check-rods
"""


def test_creation_check_stops_on_beads_with_a_rod_molecule_id(tmp_path):
    """in.check-rods, which in.create runs, stops with an ERROR when beads carry a rod's ID."""
    deck = tmp_path / "in.corrupt"
    deck.write_text(CHECK_DECK)
    done = subprocess.run([LMP, "-in", str(deck), "-var", "out", str(tmp_path), "-log", "none"],
                          cwd=EXAMPLES / "rods-and-beads", capture_output=True, text=True, timeout=120)
    assert done.returncode == 1
    assert "ERROR: in.check-rods:" in done.stdout and "have a molecule ID but are in no rod" in done.stdout, \
        done.stdout[-2000:]
    assert done.stdout.count("ERROR") == 1    # the creation itself passed the check


POLYDISPERSE_DECK = """variable geometry index channel
variable Lx index 30e-3
variable Ly index 10e-3
variable phi_b index 0.6
variable phi_r index 0.02
include in.create
variable spread atom (2*radius/${d}-1)^2
variable mass_error atom abs(mass/(2700*PI/6*(2*radius)^3)-1)
compute spread beads reduce sum v_spread
compute mass_error beads reduce max v_mass_error
thermo_style custom step c_spread c_mass_error
run 0 post no
print "polydispersity $(sqrt(c_spread/count(beads)):%.6f) mass error $(c_mass_error:%.3g)"
write_dump beads custom ${out}/beads.dump x y radius modify format float %.15g
"""


def polydisperse(out, ranks, polydisp):
    deck = out / "in.polydisperse"
    deck.write_text(POLYDISPERSE_DECK)
    return subprocess.run([*mpi_prefix(ranks), LMP, "-in", str(deck), "-var", "out", str(out),
                           "-var", "polydisp", str(polydisp), "-log", "none"],
                          cwd=EXAMPLES / "rods-and-beads", capture_output=True, text=True, timeout=120)


def test_polydisperse_beads_have_the_asked_spread_and_masses_on_any_number_of_ranks(tmp_path):
    """-var polydisp 0.05: bead diameters spread by 5 % rms, masses follow them, and a lattice site
    gets the same bead on 1 and 2 ranks (sizes are hashed from the site, not drawn per rank)."""
    radius_at_site = []
    for ranks in (1, 2):
        out = tmp_path / f"np{ranks}"
        out.mkdir()
        done = polydisperse(out, ranks, 0.05)
        assert done.returncode == 0 and "ERROR" not in done.stdout, done.stdout[-2000:]
        m = re.search(r"polydispersity ([\d.]+) mass error (\S+)", done.stdout)
        assert m, done.stdout[-2000:]
        assert abs(float(m.group(1)) - 0.05) < 0.005
        assert float(m.group(2)) < 1e-12
        rows = (out / "beads.dump").read_text().splitlines()[9:]
        radius_at_site.append({(round(float(x), 9), round(float(y), 9)): float(r)
                               for x, y, r in (row.split() for row in rows)})
    # Ranks delete different random beads to hit the count; the beads both keep are equal.
    common = radius_at_site[0].keys() & radius_at_site[1].keys()
    assert len(common) > 150
    assert all(radius_at_site[0][site] == radius_at_site[1][site] for site in common)


@pytest.mark.parametrize("polydisp", [-0.01, 0.3])
def test_polydispersity_out_of_range_is_an_error(tmp_path, polydisp):
    done = polydisperse(tmp_path, 1, polydisp)
    assert done.returncode == 1
    assert f"ERROR: in.create: polydisp {polydisp} must be in [0, 0.3)" in done.stdout, done.stdout[-2000:]


THERMO = re.compile(r"^\s+(\d+)\s+([\d.e+-]+)\s+([\d.e+-]+)\s+([\d.e+-]+)\s+(\d+)\s+([\d.e+-]+)\s+[\d.e+-]+(?:[ \t]+[\d.e+-]+)*[ \t]*$", re.M)


def channel_thermo(out, ranks, *extra):
    """step -> (time, polar order, nematic order, rods, the beads' <v^2> (their temperature)) of a
    channel-small run to 0.06 s (in.channel's thermo: Step Time P nematic rods beads_v2(mm2/s2) CPU ...)."""
    done = subprocess.run([*mpi_prefix(ranks), LMP, "-in", "in.channel-small", "-var", "out", str(out),
                           "-var", "time", "0.06", "-var", "dump", "0.005", "-log", "none", *extra],
                          cwd=EXAMPLES / "channel", capture_output=True, text=True, timeout=120)
    assert done.returncode == 0 and "ERROR" not in done.stdout, done.stdout[-3000:]
    return {int(m.group(1)): tuple(float(v) for v in m.groups()[1:]) for m in THERMO.finditer(done.stdout)}


@pytest.mark.parametrize("ranks", [1, 2])
def test_channel_continues_from_its_restart_file(tmp_path, ranks):
    """-var continue: the channel deck goes on from a restart file written during a run (0.05 s, step
    500), with the file's time and the run's end time, as the uninterrupted run (to round-off: the
    atoms come back in another order, so sums differ in their last bits, which the bed's chaotic
    collisions amplify within hundreds of steps)."""
    whole = channel_thermo(tmp_path / "whole", ranks)
    restart = tmp_path / "whole" / "channel.restart.1"
    assert restart.exists()
    continued = channel_thermo(tmp_path / "continued", ranks, "-var", "continue", str(restart))
    assert sorted(continued) == [500, 550, 600]    # from the file's step to the asked end time
    for step in (500, 550):
        assert continued[step][0] == pytest.approx(step * DT, rel=1e-12)    # the simulation time
        assert continued[step][1:] == pytest.approx(whole[step][1:], rel=1e-6), step


def test_channel_continued_at_another_time_step_ends_at_the_asked_time(tmp_path):
    """-var continue with -var dt twice the run's: the run goes on from the file's time (0.05 s, step
    500) to the asked end time at the new step (50 steps of 2e-4 s to 0.06 s), not to the step
    number that the end time would be at the old one."""
    channel_thermo(tmp_path / "whole", 1)
    restart = tmp_path / "whole" / "channel.restart.1"
    continued = channel_thermo(tmp_path / "continued", 1, "-var", "continue", str(restart), "-var", "dt", "2e-4")
    assert sorted(continued) == [500, 525, 550]
    assert continued[550][0] == pytest.approx(0.06, rel=1e-12)


# A bead thrown at a cusp of the scalloped wall, where a lobe meets the rim. LAMMPS's union region
# drops the contacts there (both circles' nearest points lie inside the other circle): without the
# posts that round the cusps the bead flies through the wall and is lost.
CUSP_DECK = """variable geometry index annulus
variable R_in index 6e-3
variable R_out index 20e-3
variable floral index yes
variable lobe index 2e-3
variable phi_b index 0.02
variable phi_r index 0.003
include in.create
# The cusp P where lobe 1 (centre C) meets the rim, and the axis of the wall's tooth there: the sum
# of the rim's and the lobe's outward normals at P. The bead starts 1.5 mm from P on that axis and
# flies along it, so that both circles' nearest points lie inside the other circle.
variable theta equal 2*PI/${nlobes}
variable cusp equal ${theta}+2*asin(${lobe}/(2*${R_out}))
variable px equal ${R_out}*cos(${cusp})
variable py equal ${R_out}*sin(${cusp})
variable ax0 equal cos(${cusp})+(${px}-${R_out}*cos(${theta}))/${lobe}
variable ay0 equal sin(${cusp})+(${py}-${R_out}*sin(${theta}))/${lobe}
variable ax equal ${ax0}/sqrt(${ax0}^2+${ay0}^2)
variable ay equal ${ay0}/sqrt(${ax0}^2+${ay0}^2)
variable xs equal ${px}-1.5e-3*${ax}
variable ys equal ${py}-1.5e-3*${ay}
# (the rigid fix is replaced around delete_atoms, create_atoms and set, as in CHECK_DECK)
unfix rodsfix
region clear sphere ${xs} ${ys} $(v_r+1e-5) 2e-3 units box
group near region clear
group cleared intersect near beads
delete_atoms group cleared compress no
create_atoms 4 single ${xs} ${ys} $(v_r+1e-5) units box
group near region clear    # (adds the new bead to the group)
group type4 type 4
group thrown intersect near type4
group beads type 4
set group thrown diameter ${d}
set group thrown density 2700
set group thrown mol 0
fix rodsfix rods rigid/rod molecule mol rod
velocity thrown set $(0.4*v_ax) $(0.4*v_ay) 0 units box
timestep 1e-4
thermo 100
run 300
print "bead at $(xcm(thrown,x)) $(xcm(thrown,y)) $(count(thrown))"
"""


@pytest.mark.parametrize("ranks", [1, 2])
def test_a_bead_thrown_at_a_cusp_of_the_scalloped_wall_stays_in_the_cell(tmp_path, ranks):
    """0.4 m/s at a cusp, head on: it bounces back, still inside the cell (no atom lost)."""
    deck = tmp_path / "in.cusp"
    deck.write_text(CUSP_DECK)
    done = subprocess.run([*mpi_prefix(ranks), LMP, "-in", str(deck), "-var", "out", str(tmp_path),
                           "-log", "none"],
                          cwd=EXAMPLES / "rods-and-beads", capture_output=True, text=True, timeout=120)
    assert done.returncode == 0 and "ERROR" not in done.stdout, done.stdout[-3000:]
    m = re.search(r"bead at (\S+) (\S+) (\S+)", done.stdout)
    x, y = float(m.group(1)), float(m.group(2))
    assert int(float(m.group(3))) == 1
    assert (x * x + y * y) ** 0.5 < 20e-3 - 0.5e-3    # thrown back into the ring
