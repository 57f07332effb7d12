"""The sweep driver's parts that need no LAMMPS: argument checks, progress line, majority
phase, table and phase diagram from given results (tests/integration/test_sweep.py runs it)."""
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
