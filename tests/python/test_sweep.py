"""The sweep driver's parts that need no LAMMPS: argument checks, progress line, majority
phase, table and phase diagram from given results, and, with a stand-in for lmp, runs killed
with SIGKILL (the run or the sweep), markers cut short, timeouts and resumes
(tests/integration/test_sweep.py runs it with LAMMPS)."""
import csv
import pathlib

import pytest

from activegrain import sweep as W


def config(tmp_path, **kw):
    deck = tmp_path / "in.deck"
    deck.write_text("# deck\n")
    args = dict(deck=deck, phi_b=[0.6, 0.7], phi_r=[0.03], seeds=[1], time=1.0, out=tmp_path / "out")
    args.update(kw)
    return W.SweepConfig(**args)


@pytest.mark.parametrize("kw, message", [
    (dict(phi_b=[]), "--phi-b: give at least one value"),
    (dict(phi_r=[-0.1]), "--phi-r -0.1: an area fraction must be in [0, 1)"),
    (dict(seeds=[0]), "positive and distinct"),
    (dict(time=-1.0), "--time -1.0"),
    (dict(ranks=0), "--ranks 0"),
    (dict(variables=[("seed", "3")]), "--var seed: set by the sweep itself"),
    (dict(geometry="annulus"), "--geometry annulus needs --r-out"),
    (dict(deck=pathlib.Path("/nonexistent/in.deck")), "not found"),
])
def test_bad_settings_are_refused(tmp_path, kw, message):
    with pytest.raises(ValueError, match=message.replace("[", r"\[").replace("(", r"\(").replace(")", r"\)")
                       .replace("+", r"\+")):
        config(tmp_path, **kw).check()


def test_grid_folders_and_command(tmp_path):
    cfg = config(tmp_path, phi_r=[0.03, 0.05], seeds=[1, 2], ranks=2, variables=[("Lx", "80e-3")])
    cfg.check()
    pts = W.points(cfg)
    assert len(pts) == 8 and pts[0] == (0.6, 0.03, 1) and pts[-1] == (0.7, 0.05, 2)
    folder = W.run_dir(cfg, *pts[0])
    assert folder.name == "phi_b0.6000_phi_r0.0300_seed1"
    cmd = W.command(cfg, 0.6, 0.03, 1, folder)
    assert cmd[0] == "mpirun" and cmd[cmd.index("-np") + 1] == "2"
    assert cmd[cmd.index("phi_b") + 1] == "0.6" and cmd[cmd.index("Lx") + 1] == "80e-3"
    assert W.command(config(tmp_path), 0.6, 0.03, 1, folder)[0] == "lmp"


def test_progress_line_estimates_the_time_left_from_finished_runs():
    assert W.progress_line(0, 4, [], 0) .endswith("0/4 runs, 0:00:00 elapsed, about ? left")
    line = W.progress_line(2, 4, [30.0, 90.0], 120)
    assert "[###############---------------] 2/4 runs" in line
    assert "0:02:00 elapsed, about 0:02:00 left" in line


def results():
    obs = dict(phi_total=0.8, P=0.1, segregation=0.0, active_layer_fraction=0.0, layer_contrast=0.0, mobility=0.2)
    rows = []
    for b, phases in ((0.6, ["isotropic", "isotropic", "flock"]), (0.86, ["jammed"] * 3)):
        for seed, ph in enumerate(phases, 1):
            rows.append(dict(phi_b=b, phi_r=0.03, seed=seed, phase=ph, phi_b_reached=b, phi_r_reached=0.03,
                             frames=5, wall_s=1.0, observables=obs))
    return rows


def test_majority_table_and_figure(tmp_path):
    maj = W.majority(results())
    assert maj[(0.6, 0.03)] == ("isotropic", 2, 3) and maj[(0.86, 0.03)] == ("jammed", 3, 3)
    W.write_table(results(), tmp_path)
    rows = list(csv.DictReader(open(tmp_path / "phases.csv")))
    assert len(rows) == 6 and rows[2]["phase"] == "flock" and float(rows[0]["mobility"]) == 0.2
    assert (tmp_path / "phases.txt").read_text().count("\n") == 7
    png = W.phase_diagram(results(), tmp_path / "d.png").read_bytes()
    assert png[:4] == b"\x89PNG"


# --- killed runs, resumes, markers: with a stand-in for lmp -----------------------------------

FAKE_LMP = '''#!{python}
"""Stands in for lmp: prints the deck's area-fraction line and copies a dump into -var out;
the point FAKE_LMP_KILL writes half of it, then is killed with SIGKILL, or with
FAKE_LMP_PIDFILE set writes its pid there and waits to be stopped."""
import os, signal, sys, time
args = sys.argv[1:]
var = {{args[i + 1]: args[i + 2] for i, a in enumerate(args) if a == "-var"}}
with open(os.environ["FAKE_LMP_CALLS"], "a") as f:
    f.write(var["phi_b"] + "\\n")
print(f"ActiveGrain create: phi_b = {{var['phi_b']}} (asked {{var['phi_b']}}), "
      f"phi_r = {{var['phi_r']}} (asked {{var['phi_r']}})", flush=True)
data = open(os.environ["FAKE_LMP_DUMP"]).read()
with open(os.path.join(var["out"], "run.dump"), "w") as out:
    if var["phi_b"] == os.environ.get("FAKE_LMP_KILL"):
        out.write(data[:len(data) // 2])
        out.flush()
        if os.environ.get("FAKE_LMP_PIDFILE"):
            with open(os.environ["FAKE_LMP_PIDFILE"] + ".tmp", "w") as f:
                f.write(str(os.getpid()))
            os.replace(os.environ["FAKE_LMP_PIDFILE"] + ".tmp", os.environ["FAKE_LMP_PIDFILE"])
            time.sleep(120)
        os.kill(os.getpid(), signal.SIGKILL)
    out.write(data)
'''


@pytest.fixture
def fake(tmp_path, monkeypatch, short_run_frames):
    """A sweep config whose lmp is FAKE_LMP; ``calls()`` lists the phi_b of each run made."""
    import sys
    from activegrain import write_dump
    write_dump(tmp_path / "template.dump", short_run_frames)
    lmp = tmp_path / "lmp"
    lmp.write_text(FAKE_LMP.format(python=sys.executable))
    lmp.chmod(0o755)
    monkeypatch.setenv("FAKE_LMP_DUMP", str(tmp_path / "template.dump"))
    monkeypatch.setenv("FAKE_LMP_CALLS", str(tmp_path / "calls"))
    monkeypatch.delenv("FAKE_LMP_KILL", raising=False)
    monkeypatch.delenv("FAKE_LMP_PIDFILE", raising=False)
    cfg = config(tmp_path, lmp=str(lmp), phi_b=[0.6, 0.7], phi_r=[0.03], seeds=[1], window=0.2)  # 0.2-s runs
    calls = lambda: (tmp_path / "calls").read_text().split() if (tmp_path / "calls").exists() else []
    return cfg, calls, monkeypatch


def sweep_quietly(cfg):
    import io
    return W.run_sweep(cfg, log=io.StringIO())


def ended(pid, wait=10.0):
    """Whether process ``pid`` ends (or is a zombie) within ``wait`` seconds."""
    import time
    stop = time.monotonic() + wait
    while True:
        try:
            state = pathlib.Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[0]
        except (FileNotFoundError, ProcessLookupError):
            return True
        if state in ("Z", "X"):
            return True
        if time.monotonic() > stop:
            return False
        time.sleep(0.05)


def test_a_point_killed_mid_run_is_rerun_and_finished_points_are_kept(fake):
    cfg, calls, env = fake
    env.setenv("FAKE_LMP_KILL", "0.7")
    with pytest.raises(RuntimeError, match=r"run phi_b0.7000_phi_r0.0300_seed1 failed \(killed by SIGKILL\)"):
        sweep_quietly(cfg)
    finished, killed = W.run_dir(cfg, 0.6, 0.03, 1), W.run_dir(cfg, 0.7, 0.03, 1)
    assert W.point_state(cfg, 0.6, 0.03, 1)[0] == "done"
    assert W.point_state(cfg, 0.7, 0.03, 1) == ("todo", None)          # never counted as done
    assert not (killed / W.RESULT).exists() and not (killed / W.RUN).exists()
    assert (killed / "run.dump").stat().st_size > 0                   # what it wrote before the kill
    before = (finished / W.RESULT).stat().st_mtime_ns
    env.delenv("FAKE_LMP_KILL")
    results, ran = sweep_quietly(cfg)
    assert ran == 1 and calls() == ["0.6", "0.7", "0.7"]               # the killed point alone again
    assert (finished / W.RESULT).stat().st_mtime_ns == before          # the finished one kept
    assert [r["phi_b"] for r in results] == [0.6, 0.7]
    assert results[1]["frames"] == results[0]["frames"] == 3           # a whole dump classified
    assert sweep_quietly(cfg)[1] == 0 and len(calls()) == 3


def test_a_sweep_killed_mid_run_stops_its_run_and_resumes(fake, tmp_path):
    """SIGKILL to the sweep itself: its run gets SIGTERM (no orphan writing into the folder that
    the resumed sweep starts afresh), the lock goes with the sweep, the resume reruns the point."""
    import os
    import signal
    import subprocess
    import sys
    import time
    cfg, calls, env = fake
    pidfile = tmp_path / "lmp.pid"
    env.setenv("FAKE_LMP_KILL", "0.7")
    env.setenv("FAKE_LMP_PIDFILE", str(pidfile))
    script = ("import pathlib, sys; from activegrain import sweep as W; "
              f"W.run_sweep(W.SweepConfig(deck=pathlib.Path({str(cfg.deck)!r}), phi_b=[0.6, 0.7], phi_r=[0.03], "
              f"seeds=[1], time=1.0, out=pathlib.Path({str(cfg.out)!r}), lmp={cfg.lmp!r}))")
    sweep = subprocess.Popen([sys.executable, "-c", script], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    lmp_pid = None
    try:
        stop = time.monotonic() + 120
        while not pidfile.exists():
            assert sweep.poll() is None and time.monotonic() < stop, "the sweep did not reach its second run"
            time.sleep(0.05)
        lmp_pid = int(pidfile.read_text())
        os.kill(sweep.pid, signal.SIGKILL)
        assert sweep.wait(timeout=30) == -signal.SIGKILL
        assert ended(lmp_pid), "the run of a killed sweep goes on"
    finally:
        if sweep.poll() is None:
            sweep.kill()
            sweep.wait()
        if lmp_pid is not None and not ended(lmp_pid, wait=0):
            os.kill(lmp_pid, signal.SIGKILL)
    assert W.point_state(cfg, 0.6, 0.03, 1)[0] == "done"
    assert W.point_state(cfg, 0.7, 0.03, 1) == ("todo", None)
    env.delenv("FAKE_LMP_KILL")
    results, ran = sweep_quietly(cfg)
    assert ran == 1 and calls() == ["0.6", "0.7", "0.7"] and results[1]["phase"]


def test_a_point_is_done_only_with_a_whole_marker(fake):
    """A folder left half-written (temporary marker, markers cut short or someone else's) is
    not done: without a whole run.json it is run again, with one it is classified again only."""
    cfg, calls, env = fake
    sweep_quietly(cfg)
    assert calls() == ["0.6", "0.7"]
    a, b = W.run_dir(cfg, 0.6, 0.03, 1), W.run_dir(cfg, 0.7, 0.03, 1)
    whole = (a / W.RESULT).read_text()
    # 0.6: its result cut short, its run whole -> classified again, not run
    (a / W.RESULT).write_text(whole[:len(whole) // 2])
    # 0.7: its run record cut short and only a temporary result -> run again
    (b / W.RESULT).rename(b / (W.RESULT + ".tmp"))
    (b / W.RUN).write_text((b / W.RUN).read_text()[:20])
    assert W.point_state(cfg, 0.6, 0.03, 1)[0] == "ran" and W.point_state(cfg, 0.7, 0.03, 1)[0] == "todo"
    results, ran = sweep_quietly(cfg)
    assert ran == 1 and calls() == ["0.6", "0.7", "0.7"]
    assert (a / W.RESULT).read_text() == whole
    # a result that is another point's does not count either
    (b / W.RESULT).write_text(whole)
    assert W.point_state(cfg, 0.7, 0.03, 1)[0] == "ran"


def test_a_run_whose_classification_fails_is_not_run_again(fake):
    cfg, calls, env = fake
    cfg.dump = "other.dump"
    with pytest.raises(RuntimeError, match="the deck wrote no other.dump"):
        sweep_quietly(cfg)
    assert W.point_state(cfg, 0.6, 0.03, 1)[0] == "ran"      # the run ended cleanly: kept
    cfg.dump = "run.dump"
    results, ran = sweep_quietly(cfg)
    assert ran == 1 and calls() == ["0.6", "0.7"]


def test_a_run_past_its_timeout_is_stopped_and_not_done(fake, tmp_path):
    import os
    import signal
    cfg, calls, env = fake
    env.setenv("FAKE_LMP_KILL", "0.6")
    env.setenv("FAKE_LMP_PIDFILE", str(tmp_path / "lmp.pid"))
    cfg.timeout = 3.0
    with pytest.raises(RuntimeError, match="stopped after --timeout 3 s"):
        sweep_quietly(cfg)
    lmp_pid = int((tmp_path / "lmp.pid").read_text())
    try:
        assert ended(lmp_pid, wait=1.0)
    finally:
        if not ended(lmp_pid, wait=0):
            os.kill(lmp_pid, signal.SIGKILL)
    assert W.point_state(cfg, 0.6, 0.03, 1) == ("todo", None)


def test_a_second_sweep_in_the_same_folder_is_refused(fake):
    import os
    cfg, calls, env = fake
    cfg.out.mkdir(parents=True)
    with W._lock(cfg.out):
        with pytest.raises(ValueError, match=f"another sweep \\(pid {os.getpid()}\\) is running in it"):
            sweep_quietly(cfg)
    assert calls() == []
    assert sweep_quietly(cfg)[1] == 2


def test_the_command_line_puts_a_failed_run_on_a_line_of_its_own(fake, tmp_path):
    import subprocess
    import sys
    cfg, calls, env = fake
    env.setenv("FAKE_LMP_KILL", "0.6")
    env.setenv("PYTHONPATH", str(pathlib.Path(W.__file__).parents[1]))
    done = subprocess.run([sys.executable, "-m", "activegrain", "sweep", str(cfg.deck), "--phi-b", "0.6",
                           "--phi-r", "0.03", "--seeds", "1", "--time", "1", "--out", str(cfg.out),
                           "--lmp", cfg.lmp], capture_output=True, text=True, timeout=120)
    assert done.returncode == 1 and "Traceback" not in done.stderr
    errors = [l for l in done.stderr.splitlines() if "ERROR" in l]
    assert len(errors) == 1 and errors[0].startswith(
        "ERROR: activegrain sweep: run phi_b0.6000_phi_r0.0300_seed1 failed (killed by SIGKILL)"), done.stderr
