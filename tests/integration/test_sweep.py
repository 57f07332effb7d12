"""python3 -m activegrain sweep on a tiny grid of a tiny channel deck: it runs every point (one
of them on 2 MPI ranks), classifies it, writes the table and the phase diagram, resumes without
running finished points, classifies again a finished run whose result is gone, reruns a point
whose run was killed with SIGKILL mid-run, and refuses bad arguments."""
import csv
import json
import os
import pathlib
import subprocess
import sys

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
LMP = os.environ.get("ACTIVEGRAIN_LMP", str(ROOT / "build" / "lmp"))
DECK = ROOT / "examples" / "channel" / "in.channel-small"
# a 16 x 8 mm channel, 200 steps, a frame every 40: seconds per run
TINY = ["--var", "Lx", "16e-3", "--var", "Ly", "8e-3", "--var", "dump", "0.002", "--var", "profile", "0.005"]
PHASES = {"isotropic", "flock", "segregated", "condensed", "jammed"}


def sweep(out, *extra, ranks=1):
    env = dict(os.environ, PYTHONPATH=str(ROOT / "python"), MPLBACKEND="Agg")
    cmd = [sys.executable, "-m", "activegrain", "sweep", str(DECK), "--phi-b", "0.6", "0.7", "--phi-r", "0.06",
           "--seeds", "3", "--time", "0.01", "--out", str(out), "--lmp", LMP, "--ranks", str(ranks),
           "--frames", "3", *TINY, *extra]
    return subprocess.run(cmd, capture_output=True, text=True, timeout=600, env=env)


@pytest.fixture(scope="module")
def first(tmp_path_factory):
    out = tmp_path_factory.mktemp("sweep")
    return out, sweep(out, ranks=2)


def test_sweep_runs_every_point_and_classifies_it(first):
    out, done = first
    assert done.returncode == 0, done.stdout + done.stderr
    assert "2 run(s) made, 0 already done" in done.stdout
    assert "2/2 runs" in done.stderr and "left" in done.stderr      # the progress bar
    rows = list(csv.DictReader(open(out / "phases.csv")))
    assert [(float(r["phi_b"]), float(r["phi_r"]), int(r["seed"])) for r in rows] == [(0.6, 0.06, 3), (0.7, 0.06, 3)]
    for r in rows:
        assert r["phase"] in PHASES
        assert abs(float(r["phi_b_reached"]) - float(r["phi_b"])) <= 0.005
        assert abs(float(r["phi_r_reached"]) - float(r["phi_r"])) <= 0.005
        assert int(r["frames"]) == 3 and float(r["wall_s"]) > 0
        assert float(r["mobility"]) >= 0          # measured between frames, not left out
    result = json.loads((out / "phi_b0.6000_phi_r0.0600_seed3" / "result.json").read_text())
    assert result["command"][:3] == ["mpirun", *(["--allow-run-as-root"] if os.geteuid() == 0 else []), "-np"][:3]
    assert "-np" in result["command"] and "2" in result["command"]
    assert (out / "phases.txt").read_text().splitlines()[0].startswith("phi_b phi_r seed phase")
    png = (out / "phase_diagram.png").read_bytes()
    assert png[:8] == b"\x89PNG\r\n\x1a\n" and len(png) > 5000


def test_sweep_resumes_without_running_finished_points(first):
    out, _ = first
    marker = out / "phi_b0.7000_phi_r0.0600_seed3" / "result.json"
    before = marker.stat().st_mtime_ns
    again = sweep(out, ranks=2)
    assert again.returncode == 0, again.stderr
    assert "0 run(s) made, 2 already done" in again.stdout
    assert marker.stat().st_mtime_ns == before
    # a finished run whose result is gone (classifying it was cut short) is classified again, not run
    point = out / "phi_b0.6000_phi_r0.0600_seed3"
    log = (point / "log.lammps").stat().st_mtime_ns
    (point / "result.json").unlink()
    third = sweep(out)
    assert third.returncode == 0, third.stderr
    assert "0 run(s) made, 2 already done" in third.stdout and "1 finished run(s) to classify again" in third.stderr
    assert (point / "result.json").is_file() and (point / "log.lammps").stat().st_mtime_ns == log
    # a point whose run did not end cleanly (no run.json) is made again, on its own
    (point / "result.json").unlink()
    (point / "run.json").unlink()
    fourth = sweep(out)
    assert fourth.returncode == 0, fourth.stderr
    assert "1 run(s) made, 1 already done" in fourth.stdout
    assert marker.stat().st_mtime_ns == before


# Stands in for lmp: runs it, but the point phi_b 0.7 for 100 times the time, and a watcher kills
# it (the lmp process itself, SIGKILL) once its dump holds two frames: mid-run.
KILLING_LMP = """#!{python}
import glob, os, signal, sys, time
args = sys.argv[1:]
var = {{args[i + 1]: args[i + 2] for i, a in enumerate(args) if a == "-var"}}
if var["phi_b"] == "0.7":
    args[args.index("time") + 1] = repr(100 * float(var["time"]))
    lmp_pid = os.getpid()
    if os.fork() == 0:
        stop = time.monotonic() + 300
        while time.monotonic() < stop:
            dumps = glob.glob(os.path.join(var["out"], "*.dump"))
            if dumps and open(dumps[0]).read().count("ITEM: TIMESTEP") >= 2:
                with open(os.environ["KILLED_LOG"], "w") as f:
                    f.write(str(lmp_pid))
                os.kill(lmp_pid, signal.SIGKILL)
                break
            time.sleep(0.02)
        os._exit(0)
os.execv({lmp!r}, [{lmp!r}, *args])
"""


def test_a_point_killed_mid_run_is_rerun_and_finished_points_are_kept(tmp_path, monkeypatch):
    out = tmp_path / "killed"
    killing = tmp_path / "lmp"
    killing.write_text(KILLING_LMP.format(python=sys.executable, lmp=str(pathlib.Path(LMP).resolve())))
    killing.chmod(0o755)
    monkeypatch.setenv("KILLED_LOG", str(tmp_path / "killed.pid"))
    done = sweep(out, "--lmp", str(killing))
    assert (tmp_path / "killed.pid").is_file(), done.stderr        # it was killed, not finished
    assert done.returncode == 1
    errors = [l for l in done.stderr.splitlines() if "ERROR" in l]
    assert errors and errors[0].startswith("ERROR: activegrain sweep: run phi_b0.7000_phi_r0.0600_seed3 failed "
                                           "(killed by SIGKILL)"), done.stderr
    finished, killed = out / "phi_b0.6000_phi_r0.0600_seed3", out / "phi_b0.7000_phi_r0.0600_seed3"
    assert (finished / "result.json").is_file()
    assert not (killed / "result.json").exists() and not (killed / "run.json").exists()
    assert list(killed.glob("*.dump")), "the killed run wrote no frame"
    before = (finished / "result.json").stat().st_mtime_ns
    again = sweep(out)                                              # the plain lmp
    assert again.returncode == 0, again.stderr
    assert "1 run(s) made, 1 already done" in again.stdout
    assert (finished / "result.json").stat().st_mtime_ns == before
    rows = list(csv.DictReader(open(out / "phases.csv")))
    assert [r["phi_b"] for r in rows] == ["0.6", "0.7"] and all(int(r["frames"]) == 3 for r in rows)


@pytest.mark.parametrize("extra, message", [
    (["--phi-b", "1.2"], "--phi-b 1.2: an area fraction must be in [0, 1)"),
    (["--var", "phi_r", "0.1"], "--var phi_r: set by the sweep itself"),
    (["--ranks", "0"], "--ranks 0: at least 1"),
    (["--time", "0"], "--time 0.0: the run length must be positive"),
    (["--seeds", "1", "1"], "--seeds [1, 1]: positive and distinct"),
])
def test_bad_arguments_are_refused_before_any_run(tmp_path, extra, message):
    done = sweep(tmp_path / "bad", *extra)
    assert done.returncode == 1
    assert f"activegrain sweep: {message}" in done.stderr
    assert not (tmp_path / "bad").exists()


def test_a_deck_that_stops_with_an_error_is_reported(tmp_path):
    done = sweep(tmp_path / "err", "--var", "start", "nonsense")
    assert done.returncode == 1
    assert "activegrain sweep: run phi_b0.6000_phi_r0.0600_seed3 failed" in done.stderr
    assert "ERROR: in.create: start must be auto, lattice or grow, not nonsense" in done.stderr


def test_a_missing_deck_is_refused(tmp_path):
    env = dict(os.environ, PYTHONPATH=str(ROOT / "python"))
    done = subprocess.run([sys.executable, "-m", "activegrain", "sweep", str(tmp_path / "in.none"), "--phi-b", "0.6",
                           "--phi-r", "0.04", "--time", "1", "--out", str(tmp_path / "o")],
                          capture_output=True, text=True, env=env)
    assert done.returncode == 1 and "activegrain sweep: deck" in done.stderr and "not found" in done.stderr
