"""States (examples/README.md, "States"): a deck given -var continue RESTART -var state PREFIX writes
the system as a gzipped data file PREFIX-<seconds>s.data.gz whose first line holds the exact time,
and -var from FILE continues from it: the clock at the state's time, the same atoms and rods, and
the run's first values those the state was written with (a continuation of the physics, not bit for
bit: later values drift apart as chaotic collisions amplify the lost half impulses of the state's
last step). On channel-small, 0.05 s written, continued to 0.06 s, on 1 and 2 ranks. The header also
records the physics the state was made with (seed, commit, MPI ranks, pair gran/impulse's settings,
the plates' rod friction, restitution and roughness); a continuation under other settings warns of
each and goes on; a header without them (an older state) reads as before."""
import gzip
import os
import pathlib
import re
import subprocess

import pytest

from mpi_launch import mpi_prefix

ROOT = pathlib.Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples"
LMP = os.environ.get("ACTIVEGRAIN_LMP", str(ROOT / "build" / "lmp"))
DT = 1.0e-4           # the decks' time step
STATE_STEP = 500      # channel.restart.1 of a run dumping every 0.005 s (restart files every 10 dumps)
END = 0.06
MAX_STATE_BYTES = 5_000_000

# Step Time P nematic rods beads_v2(mm2/s2) CPU, then the soak columns (in.channel's thermo: polar and
# nematic order, rods, the beads' mean squared velocity)
THERMO = re.compile(r"^\s+(\d+)\s+([\d.e+-]+)\s+([\d.e+-]+)\s+([\d.e+-]+)\s+(\d+)\s+([\d.e+-]+)\s+[\d.e+-]+(?:[ \t]+[\d.e+-]+)*[ \t]*$", re.M)
WROTE = re.compile(r"^ActiveGrain state: wrote (\S+) \(time (\S+) s, step (\d+), (\d+) beads, (\d+) rods\)$", re.M)
CONTINUING = re.compile(r"^ActiveGrain state: continuing from (\S+) at time (\S+) s, step (\d+)$", re.M)
HEADER = re.compile(r"^ActiveGrain state: time (\S+) s step (\d+) geometry channel ")
LOOP = re.compile(r"Loop time of \S+ on (\d+) procs for (\d+) steps with (\d+) atoms")
COMPLETED = re.compile(r"run completed with (\d+) beads and (\d+) rod atoms")


def channel(out, ranks, *extra):
    """channel-small to END (or only what -var state asks), dumping every 0.005 s: its screen output."""
    done = subprocess.run([*mpi_prefix(ranks), LMP, "-in", "in.channel-small", "-var", "out", str(out),
                           "-var", "time", str(END), "-var", "dump", "0.005", "-log", "none", *extra],
                          cwd=EXAMPLES / "channel", capture_output=True, text=True, timeout=120)
    assert done.returncode == 0 and "ERROR" not in done.stdout, done.stdout[-3000:] + done.stderr[-2000:]
    return done.stdout


def thermo(stdout):
    """step -> (time, polar order, nematic order, rods, the beads' <v^2> (their temperature))"""
    return {int(m.group(1)): tuple(float(v) for v in m.groups()[1:]) for m in THERMO.finditer(stdout)}


def dump_frames(path):
    """step -> {atom id: {column: value}} of a LAMMPS text dump."""
    frames, lines, i = {}, path.read_text().splitlines(), 0
    while i < len(lines):
        if lines[i].startswith("ITEM: TIMESTEP"):
            step, n, columns = int(lines[i + 1]), int(lines[i + 3]), lines[i + 8].split()[2:]
            rows = (dict(zip(columns, map(float, row.split()))) for row in lines[i + 9:i + 9 + n])
            frames[step] = {int(row["id"]): row for row in rows}
            i += 9 + n
        else:
            i += 1
    return frames


def rods_of(frame):
    """rod body ID -> its sorted atom IDs (dump column body, 0 for a bead)."""
    rods = {}
    for atom, row in frame.items():
        if row["body"] > 0:
            rods.setdefault(int(row["body"]), []).append(atom)
    return {body: sorted(atoms) for body, atoms in rods.items()}


def rod_velocities(frame, rods):
    """rod body ID -> the mean velocity of its atoms (a fixed function of the body's velocity and spin)."""
    return {body: [sum(frame[a][c] for a in atoms) / len(atoms) for c in ("vx", "vy", "vz")]
            for body, atoms in rods.items()}


def read_state(path):
    """(first line, {section: rows}) of a gzipped data file."""
    with gzip.open(path, "rt") as f:
        lines = f.read().splitlines()
    sections, current = {}, None
    for line in lines[1:]:
        words = line.split()
        if not words:
            continue
        if words[0] in ("Atoms", "Velocities", "Molecules"):
            current = sections.setdefault(words[0], [])
        elif current is not None and words[0].isdigit():
            current.append(words)
    return lines[0], sections


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    """For a number of ranks: the uninterrupted run, the state written from its restart file at
    0.05 s, and the continuation from that state (all on that number of ranks), run once."""
    cache = {}

    def get(ranks):
        if ranks not in cache:
            base = tmp_path_factory.mktemp(f"states-{ranks}")
            whole = channel(base / "whole", ranks)
            restart = base / "whole" / "channel.restart.1"
            assert restart.exists()
            (base / "states").mkdir()
            wrote = channel(base / "write", ranks, "-var", "continue", str(restart),
                            "-var", "state", str(base / "states" / "channel-small"))
            m = WROTE.search(wrote)
            assert m, wrote[-3000:]
            state = pathlib.Path(m.group(1))
            continued = channel(base / "continued", ranks, "-var", "from", str(state))
            cache[ranks] = dict(base=base, whole=whole, wrote=wrote, wrote_match=m, state=state,
                                continued=continued)
        return cache[ranks]
    return get


@pytest.mark.parametrize("ranks", [1, 2])
def test_a_state_is_a_small_gzipped_data_file_named_by_its_time_with_the_exact_time_first(runs, ranks):
    r = runs(ranks)
    state, m = r["state"], r["wrote_match"]
    assert state == r["base"] / "states" / "channel-small-0.05s.data.gz"
    assert 0 < state.stat().st_size < MAX_STATE_BYTES
    assert "ActiveGrain channel: run completed" not in r["wrote"]    # writing a state stops the deck
    title, sections = read_state(state)
    header = HEADER.match(title)
    assert header, title
    assert float(header.group(1)) == STATE_STEP * DT    # the exact double of the time
    assert header.group(1) == m.group(2) and int(header.group(2)) == int(m.group(3)) == STATE_STEP
    atoms = int(LOOP.findall(r["whole"])[-1][2])
    assert len(sections["Atoms"]) == len(sections["Velocities"]) == len(sections["Molecules"]) == atoms
    assert all(len(row) == 7 for row in sections["Velocities"])    # velocities and spins
    # the molecule IDs make the rods: 10 rods of 9 atoms, beads in none
    molecules = {}
    for atom, mol in sections["Molecules"]:
        if int(mol) > 0:
            molecules.setdefault(int(mol), []).append(int(atom))
    assert len(molecules) == int(m.group(5)) == 10
    assert all(len(atoms) == 9 for atoms in molecules.values())
    rods = rods_of(dump_frames(r["base"] / "whole" / "channel.dump")[STATE_STEP])
    assert sorted(sorted(a) for a in molecules.values()) == sorted(rods.values())


@pytest.mark.parametrize("ranks", [1, 2])
def test_a_continuation_starts_at_the_states_time_and_ends_at_the_asked_time(runs, ranks):
    r = runs(ranks)
    m = CONTINUING.search(r["continued"])
    assert m, r["continued"][-3000:]
    assert m.group(2) == r["wrote_match"].group(2)    # the header's time, to all its digits
    assert int(m.group(3)) == STATE_STEP
    continued = thermo(r["continued"])
    assert sorted(continued) == [500, 550, 600]
    for step in continued:
        assert continued[step][0] == pytest.approx(step * DT, rel=1e-12)
    assert continued[600][0] == pytest.approx(END, rel=1e-12)


@pytest.mark.parametrize("ranks", [1, 2])
def test_a_continuation_keeps_every_atom_and_the_same_rods(runs, ranks):
    r = runs(ranks)
    loops = LOOP.findall(r["continued"])
    atoms = {int(n) for _, _, n in LOOP.findall(r["whole"])}
    assert len(atoms) == 1 and {int(n) for _, _, n in loops} == atoms
    assert COMPLETED.findall(r["continued"]) == COMPLETED.findall(r["whole"])
    whole = dump_frames(r["base"] / "whole" / "channel.dump")
    continued = dump_frames(r["base"] / "continued" / "channel.dump")
    assert sorted(continued) == [500, 550, 600]
    rods = rods_of(whole[STATE_STEP])
    assert len(rods) == 10
    for step in continued:    # the same body IDs, each with the same atoms, all along
        assert rods_of(continued[step]) == rods, step


@pytest.mark.parametrize("ranks", [1, 2])
def test_a_continuation_goes_on_from_the_states_positions_and_velocities(runs, ranks):
    """The first frame and thermo line of the continuation are those of the uninterrupted run at
    the state's step (to the dump's 6 digits); the rods keep moving as they were; later values stay
    close (loosely: the continuation re-solves the contacts of its first step)."""
    r = runs(ranks)
    whole = dump_frames(r["base"] / "whole" / "channel.dump")[STATE_STEP]
    first = dump_frames(r["base"] / "continued" / "channel.dump")[STATE_STEP]
    assert first.keys() == whole.keys()
    for atom, row in whole.items():
        for c in ("x", "y", "z", "vx", "vy", "vz"):
            assert first[atom][c] == pytest.approx(row[c], rel=1e-5, abs=1e-9), (atom, c)
    rods = rods_of(whole)
    before, after = rod_velocities(whole, rods), rod_velocities(first, rods)
    assert max(abs(v[0]) + abs(v[1]) for v in before.values()) > 1e-3    # rods walking in the plane
    for body in rods:
        assert after[body] == pytest.approx(before[body], rel=1e-5, abs=1e-8), body
    uninterrupted, continued = thermo(r["whole"]), thermo(r["continued"])
    assert continued[500][1:] == pytest.approx(uninterrupted[500][1:], rel=1e-6)
    for step in (550, 600):
        time, polar, nematic, rods_counted, temperature = continued[step]
        assert polar == pytest.approx(uninterrupted[step][1], abs=0.02), step
        assert nematic == pytest.approx(uninterrupted[step][2], abs=0.02), step
        assert rods_counted == uninterrupted[step][3] == 10
        assert temperature == pytest.approx(uninterrupted[step][4], rel=0.1), step


NOT_A_STATE = """LAMMPS data file via write_data, version 4 Feb 2025, timestep = 500, units = si

1 atoms
4 atom types
"""


@pytest.mark.parametrize("ranks", [1, 2])
@pytest.mark.parametrize("kind", ["missing", "plain data file", "gzipped data file"])
def test_a_bad_state_stops_with_an_error_naming_the_deck_and_the_variable(tmp_path, kind, ranks):
    path = tmp_path / {"missing": "missing.data.gz", "plain data file": "other.data",
                       "gzipped data file": "other.data.gz"}[kind]
    if kind == "plain data file":
        path.write_text(NOT_A_STATE)
    elif kind == "gzipped data file":
        with gzip.open(path, "wt") as f:
            f.write(NOT_A_STATE)
    done = subprocess.run([*mpi_prefix(ranks), LMP, "-in", "in.channel-small", "-var", "out", str(tmp_path / "out"),
                           "-var", "from", str(path), "-log", "none"],
                          cwd=EXAMPLES / "channel", capture_output=True, text=True, timeout=60)
    assert done.returncode == 1, done.stdout[-2000:] + done.stderr[-2000:]
    errors = [line for line in done.stdout.splitlines() if "ERROR" in line]
    expected = "no such file" if kind == "missing" else "is not an ActiveGrain state"
    assert errors and errors[0].startswith(f"ERROR: in.create: -var from {path}"), done.stdout[-2000:]
    assert expected in errors[0]
    assert "Created" not in done.stdout and "Loop time" not in done.stdout    # stopped before any system


def with_molecule_ids(source, target, change):
    """The gzipped state `source` written to `target` with change(atom_id -> mol, types) applied to its
    Molecules section (types: atom ID -> type)."""
    with gzip.open(source, "rt") as f:
        lines = f.read().splitlines()
    _, sections = read_state(source)
    types = {int(row[0]): int(row[1]) for row in sections["Atoms"]}
    mols = {int(row[0]): int(row[1]) for row in sections["Molecules"]}
    change(mols, types)
    out, current = [], None
    for line in lines:
        words = line.split()
        if words and words[0] in ("Atoms", "Velocities", "Molecules"):
            current = words[0]
        elif current == "Molecules" and words and words[0].isdigit():
            line = f"{words[0]} {mols[int(words[0])]}"
        out.append(line)
    with gzip.open(target, "wt") as f:
        f.write("\n".join(out) + "\n")
    return target


def first_rod_atom(mols, types):
    return min(a for a, t in types.items() if t != 4)


def drop_id(mols, types):
    mols[first_rod_atom(mols, types)] = 0


def other_rods_id(mols, types):
    atom = first_rod_atom(mols, types)
    mols[atom] = max(m for a, m in mols.items() if m != mols[atom])


@pytest.mark.parametrize("ranks", [1, 2])
@pytest.mark.parametrize("kind, expected", [
    ("missing", "ERROR: in.create: -var from {path}: 1 rod atoms (types 1 to 3) have no molecule ID (0)"),
    ("inconsistent", "ERROR: Fix rigid/rod: molecule ID")])
def test_a_state_with_missing_or_inconsistent_molecule_ids_is_refused_with_the_reason(runs, tmp_path, kind,
                                                                                      expected, ranks):
    path = with_molecule_ids(runs(1)["state"], tmp_path / f"{kind}.data.gz",
                             drop_id if kind == "missing" else other_rods_id)
    done = subprocess.run([*mpi_prefix(ranks), LMP, "-in", "in.channel-small", "-var", "out", str(tmp_path / "out"),
                           "-var", "from", str(path), "-var", "time", str(END), "-log", "none"],
                          cwd=EXAMPLES / "channel", capture_output=True, text=True, timeout=120)
    assert done.returncode != 0, done.stdout[-2000:] + done.stderr[-2000:]
    errors = [line for line in done.stdout.splitlines() if line.startswith("ERROR")]
    assert errors and errors[0].startswith(expected.format(path=path)), done.stdout[-2000:]
    assert "Loop time" not in done.stdout


# The physics in.write-state records after the geometry, as in.create's defaults set them.
DEFAULT_PHYSICS = {"seed": "2024", "resolution": "50", "window": "5e-6", "resting": "no",
                   "mu_rod_plate": "0.03", "e_rod_plate": "0.1", "rough": "0.06", "rough_length": "5e-6"}
MADE_BY = re.compile(r"^ActiveGrain state: made by commit (\S+) on (\S+) MPI ranks; this run: commit (\S+) on (\d+) MPI ranks$", re.M)
NOT_RECORDED = "does not record the physics it was made with"


def physics(title):
    """The key value pairs of a state's header after its geometry (Lx, Ly, ..., seed, commit, ...)."""
    words = title.split()
    pairs = words[words.index("geometry") + 2:]
    assert len(pairs) % 2 == 0, title
    return dict(zip(pairs[::2], pairs[1::2]))


def warnings(stdout):
    return [line for line in stdout.splitlines() if line.startswith("WARNING: in.create")]


@pytest.mark.parametrize("ranks", [1, 2])
def test_a_state_records_the_physics_it_was_made_with(runs, ranks):
    """Written from a restart file: the deck's settings, the commit and the run's ranks unknown
    (neither -var commit nor -var ranks given; LAMMPS does not tell a restart file's rank count)."""
    recorded = physics(read_state(runs(ranks)["state"])[0])
    assert {key: recorded[key] for key in DEFAULT_PHYSICS} == DEFAULT_PHYSICS
    assert recorded["commit"] == recorded["ranks"] == "unknown"
    assert (recorded["Lx"], recorded["Ly"], recorded["phi_b"], recorded["phi_r"]) == ("60e-3", "15e-3", "0.75", "0.04")


@pytest.mark.parametrize("ranks", [1, 2])
def test_a_created_state_records_its_ranks_the_commit_given_and_the_settings_changed(tmp_path, ranks):
    (tmp_path / "states").mkdir()
    wrote = channel(tmp_path / "write", ranks, "-var", "state", str(tmp_path / "states" / "created"),
                    "-var", "commit", "abc1234", "-var", "resting", "yes", "-var", "mu_rod_plate", "0.003",
                    "-var", "seed", "7")
    state = pathlib.Path(WROTE.search(wrote).group(1))
    recorded = physics(read_state(state)[0])
    assert recorded == {"Lx": "60e-3", "Ly": "15e-3", "R_in": "25e-3", "R_out": "60e-3", "phi_b": "0.75",
                        "phi_r": "0.04", **DEFAULT_PHYSICS, "seed": "7", "commit": "abc1234",
                        "ranks": str(ranks), "resting": "yes", "mu_rod_plate": "0.003"}
    # written again from it (-var from, -var state): its commit and ranks are kept, -var ranks overrides
    again = channel(tmp_path / "again", 1, "-var", "from", str(state), "-var", "state", str(tmp_path / "states" / "again"),
                    "-var", "resting", "yes", "-var", "mu_rod_plate", "0.003", "-var", "seed", "7")
    assert warnings(again) == []
    assert physics(read_state(pathlib.Path(WROTE.search(again).group(1)))[0]) == recorded
    told = channel(tmp_path / "told", 1, "-var", "from", str(state), "-var", "state", str(tmp_path / "states" / "told"),
                   "-var", "resting", "yes", "-var", "mu_rod_plate", "0.003", "-var", "seed", "7", "-var", "ranks", "4")
    assert physics(read_state(pathlib.Path(WROTE.search(told).group(1)))[0])["ranks"] == "4"


@pytest.mark.parametrize("ranks", [1, 2])
def test_a_continuation_at_the_states_physics_warns_of_nothing_and_says_who_made_it(runs, ranks):
    continued = runs(ranks)["continued"]
    assert warnings(continued) == []
    assert NOT_RECORDED not in continued
    assert MADE_BY.search(continued).groups() == ("unknown", "unknown", "unknown", str(ranks))


@pytest.mark.parametrize("ranks", [1, 2])
def test_a_continuation_under_other_physics_warns_of_each_difference_and_goes_on(runs, tmp_path, ranks):
    """-var resting yes and -var seed 7 against the state's no and 2024: a WARNING naming each, the run
    completes; the window written otherwise (5.0e-6 against 5e-6) is the same number, no warning."""
    r = runs(ranks)
    out = channel(tmp_path / "other", ranks, "-var", "from", str(r["state"]), "-var", "resting", "yes",
                  "-var", "seed", "7", "-var", "window", "5.0e-6", "-var", "commit", "abc1234")
    assert warnings(out) == [
        f"WARNING: in.create: -var from {r['state']}: state made with seed 2024, this run has seed 7",
        f"WARNING: in.create: -var from {r['state']}: state made with resting no, this run has resting yes"]
    assert MADE_BY.search(out).groups() == ("unknown", "unknown", "abc1234", str(ranks))
    assert COMPLETED.findall(out) == COMPLETED.findall(r["whole"])
    assert sorted(thermo(out)) == [500, 550, 600]


@pytest.mark.parametrize("ranks", [1, 2])
def test_an_older_header_without_the_physics_still_reads(runs, tmp_path, ranks):
    """The header cut after the seed (as states were written before the physics was recorded): the
    continuation says that the physics is not recorded and is the same run as from the full header."""
    r = runs(1)
    with gzip.open(r["state"], "rt") as f:
        title, rest = f.read().split("\n", 1)
    old = title[:title.index(" commit ")]
    assert old.endswith(" seed 2024") and HEADER.match(old)
    path = tmp_path / "old-0.05s.data.gz"
    with gzip.open(path, "wt") as f:
        f.write(old + "\n" + rest)
    out = channel(tmp_path / "old", ranks, "-var", "from", str(path))
    assert warnings(out) == []
    assert f"ActiveGrain state: {path} {NOT_RECORDED}" in out
    assert not MADE_BY.search(out)
    m = CONTINUING.search(out)
    assert m and m.group(2) == r["wrote_match"].group(2) and int(m.group(3)) == STATE_STEP
    assert thermo(out)[500][1:] == pytest.approx(thermo(r["continued"])[500][1:], rel=1e-6)
    assert COMPLETED.findall(out) == COMPLETED.findall(r["whole"])


STATES = sorted(EXAMPLES.glob("*/states/*.data.gz"))


@pytest.mark.parametrize("path", STATES, ids=[p.name for p in STATES])
def test_every_shipped_state_records_its_physics(path):
    recorded = physics(read_state(path)[0])
    assert set(DEFAULT_PHYSICS) | {"commit", "ranks"} <= set(recorded), path
    assert recorded["resting"] in ("yes", "no")
    assert recorded["ranks"] in ("1", "2")
