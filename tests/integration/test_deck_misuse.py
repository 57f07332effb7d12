"""Bad or silent input to the paper decks gets a clear message (examples/README.md): a continuation
whose -var time is not after the time it starts from says that there is nothing to run; a state
file cut short or damaged stops with an ERROR naming it, before read_data's "Unexpected end of data
file"; a channel run prints no WARNING (no thermo_modify lost to a later thermo_style) and names
its thermo columns, with the beads' mean squared velocity in mm^2/s^2 in place of a kelvin
temperature."""
import gzip
import os
import pathlib
import re
import subprocess

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
CHANNEL = ROOT / "examples" / "channel"
LMP = os.environ.get("ACTIVEGRAIN_LMP", str(ROOT / "build" / "lmp"))
STATE = CHANNEL / "states" / "channel-small-condensed-500s.data.gz"    # 500 s, 949 atoms
LOOP = re.compile(r"Loop time of \S+ on \d+ procs for (\d+) steps with (\d+) atoms")
COLUMNS = "Step Time P nematic rods beads_v2(mm2/s2) CPU Atoms v_overlap_d f_ledger[1] f_ledger[2] f_ledger[3] f_ledger[4]"


def channel(out, *extra):
    """channel-small (1 rank), dumping every 0.001 s: (return code, screen output)."""
    done = subprocess.run([LMP, "-in", "in.channel-small", "-var", "out", str(out), "-var", "dump", "0.001",
                           "-log", "none", *extra], cwd=CHANNEL, capture_output=True, text=True, timeout=120)
    return done.returncode, done.stdout + done.stderr


@pytest.fixture(scope="module")
def fresh(tmp_path_factory):
    """channel-small created and run to 0.002 s (20 steps): its output folder and screen output."""
    out = tmp_path_factory.mktemp("fresh")
    code, stdout = channel(out, "-var", "time", "0.002")
    assert code == 0 and "ERROR" not in stdout, stdout[-3000:]
    return out, stdout


def test_a_channel_run_warns_of_nothing_and_names_its_columns(fresh):
    _, stdout = fresh
    assert "WARNING" not in stdout, [l for l in stdout.splitlines() if "WARNING" in l]
    header = [l.split() for l in stdout.splitlines() if l.split()[:2] == ["Step", "Time"]]
    assert header == [COLUMNS.split()]
    rows = [l.split() for l in stdout.splitlines() if re.match(r"^\s+(10|20)\s+0\.00[12]\s", l)]
    assert len(rows) == 2
    for row in rows:
        polar, nematic, rods, v2 = (float(v) for v in row[2:6])
        assert 0 <= polar <= 1 and 0 <= nematic <= 1 and rods == 10
        # beads shaken by plates at 5 cm/s peak speed: <v^2> of order 1e3 to 1e4 mm^2/s^2
        assert 10 < v2 < 1e6, row


def test_a_state_continued_to_an_earlier_time_says_there_is_nothing_to_run(tmp_path):
    code, stdout = channel(tmp_path / "run", "-var", "from", str(STATE), "-var", "time", "400")
    assert code == 0, stdout[-3000:]
    assert "WARNING: in.channel: -var time 400 is not after the state's time 500: nothing to run" in stdout
    assert stdout.count("WARNING") == 1
    assert LOOP.findall(stdout)[-1] == ("0", "949")
    # a -var time after the state's: no warning, and the steps up to it
    code, stdout = channel(tmp_path / "on", "-var", "from", str(STATE), "-var", "time", "500.0003")
    assert code == 0 and "WARNING" not in stdout, stdout[-3000:]
    assert LOOP.findall(stdout)[-1] == ("3", "949")


def test_a_restart_file_continued_to_an_earlier_time_says_there_is_nothing_to_run(fresh, tmp_path):
    out, _ = fresh
    code, stdout = channel(tmp_path, "-var", "continue", str(out / "channel.restart.final"), "-var", "time", "0.001")
    assert code == 0, stdout[-3000:]
    assert "WARNING: in.channel: -var time 0.001 is not after the state's time 0.002: nothing to run" in stdout
    assert LOOP.findall(stdout)[-1][0] == "0"


def cut(path, data, keep):
    path.write_bytes(data[:keep])
    return path


@pytest.mark.parametrize("kind", ["gzipped, cut in half", "gzipped, its first kilobyte", "plain, cut in half",
                                  "plain, cut in its last section"])
def test_a_state_cut_short_stops_with_an_error_naming_it(tmp_path, kind):
    plain = gzip.decompress(STATE.read_bytes())
    if kind.startswith("gzipped"):
        data = STATE.read_bytes()
        state = cut(tmp_path / "cut.data.gz", data, len(data) // 2 if "half" in kind else 1000)
        expected = (f"ERROR: in.create: -var from {state}: cannot be read to its end (gzip finds it cut short "
                    f"or damaged)")
    else:
        state = cut(tmp_path / "cut.data", plain, len(plain) // 2 if "half" in kind else len(plain) - 20)
        found = 0 if "half" in kind else 945
        expected = (f"ERROR: in.create: -var from {state}: incomplete: molecule IDs (its last section) for "
                    f"{found} of the 949 atoms its header counts")
    code, stdout = channel(tmp_path / "run", "-var", "from", str(state), "-var", "time", "600")
    assert code == 1, stdout[-3000:]
    assert expected in stdout, stdout[-3000:]
    assert "Unexpected end of data file" not in stdout and stdout.count("ERROR") == 1
