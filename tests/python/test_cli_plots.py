"""Command line and figures on synthetic dumps."""
import io
import pathlib
import shutil

import numpy as np
import pytest
from PIL import Image

from activegrain import Box, plotting, synthetic as S, write_dump, read_frame, geometry_from_box
from activegrain.cli import main


@pytest.fixture(scope="module")
def condensed_dump(tmp_path_factory):
    path = tmp_path_factory.mktemp("dumps") / "condensed.dump"
    frames = []
    for i in range(3):
        fr = S.phase_configuration("condensed")
        fr.pos[:, :2] = fr.box.wrap(fr.pos[:, :2] + [2.0 * i, 0.0])
        fr.step = 1000 * i
        frames.append(fr.scaled(1e-3))  # in metres, like the simulations
    write_dump(path, frames)
    return str(path)


def run(argv):
    out = io.StringIO()
    rc = main(argv, out)
    return rc, out.getvalue()


def test_profile_command(condensed_dump, tmp_path):
    png = tmp_path / "p.png"
    rc, text = run(["profile", condensed_dump, "--length-unit", "1e-3", "--bins", "31", "--frame", "0",
                    "--plot", str(png)])
    assert rc == 0
    rows = np.array([l.split() for l in text.splitlines()[1:]], float)
    assert rows.shape == (31, 2)
    # bins of 4 d: x in [36, 92] is the close-packed lattice (pi/4) in frame 0
    dense = rows[(rows[:, 0] > 36) & (rows[:, 0] < 92), 1]
    assert np.allclose(dense, np.pi / 4, rtol=1e-6)
    assert png.stat().st_size > 1000


def test_phase_and_polar_commands(condensed_dump):
    rc, text = run(["phase", condensed_dump, "--length-unit", "1e-3", "--timestep", "1e-4", "--window", "0.2"])
    assert rc == 0
    lines = text.splitlines()
    head = lines[0].split()
    assert head[:3] == ["step", "time", "phase"] and len(lines) == 4
    assert all(l.split()[2] == "condensed" for l in lines[1:])
    # the layer moves 2 d per 0.1 s: 20 d/s, 4.4 rod lengths per second
    assert all(float(dict(zip(head, l.split()))["rod_speed"]) == pytest.approx(20 / 4.5, rel=0.01) for l in lines[1:])
    rc, text = run(["polar", condensed_dump, "--length-unit", "1e-3", "--frame", "-1"])
    head, row = text.splitlines()
    vals = dict(zip(head.split(), row.split()))
    assert float(vals["P"]) == pytest.approx(1.0)
    assert vals["step"] == "2000"


def test_snapshot_movie_kymograph(condensed_dump, tmp_path):
    for cmd, name in (("snapshot", "s.png"), ("movie", "m.gif"), ("kymograph", "k.png")):
        rc, text = run([cmd, condensed_dump, "--length-unit", "1e-3", "-o", str(tmp_path / name)])
        assert rc == 0, text
    gif = Image.open(tmp_path / "m.gif")
    assert gif.n_frames == 3
    if shutil.which("ffmpeg") is None:  # no encoder: a clear error, not a crash
        rc, _ = run(["movie", condensed_dump, "--length-unit", "1e-3", "-o", str(tmp_path / "m.mp4")])
        assert rc == 1


def test_theory_commands(tmp_path):
    rc, text = run(["theory", "growth", "--D_rho_sigma", "0.5", "--B", "-0.1", "--plot", str(tmp_path / "g.png")])
    assert rc == 0
    assert "condensation (A alpha rho0 + B u0 sigma0 > 0): True" in text
    assert "non-reciprocity condition: True" in text
    rc, text = run(["theory", "growth", "--D_rho", "0.05", "--D_sigma", "0.1", "--B", "0", "--a", "10",
                    "--table", "--n-k", "11", "--k-max", "2"])
    rows = np.array([l.split() for l in text.splitlines()[4:]], float)
    k = rows[:, 0]
    assert np.allclose(np.sort(rows[:, [1, 3]], axis=1)[:, 1], np.maximum(0.05 * k ** 2 - 0.01 * k ** 4, -0.1 * k ** 2),
                       atol=1e-6)
    rc, text = run(["theory", "pointforce", "--f", "2", "--rho0", "0.6"])
    assert rc == 0
    assert float(text.split("rho+ = ")[1].split()[0]) == pytest.approx(0.7314170, rel=1e-6)


def test_errors_are_reported_not_raised(tmp_path):
    bad = tmp_path / "bad.dump"
    bad.write_text("nothing here\n" * 10)
    rc, _ = run(["profile", str(bad)])
    assert rc == 1
    rc, _ = run(["phase", str(tmp_path / "missing.dump")])
    assert rc == 1


def test_snapshot_draws_periodic_images_of_straddling_rods():
    box = S.square_box(20)
    fr = S.make_frame(box, [(5.0, 5.0)], 0.5, [(0.5, 10.0), (10.0, 10.0)], [(1, 0), (0, 1)])
    fig = plotting.snapshot(fr, geometry_from_box(box))
    polys = fig.axes[0].collections[1]
    assert len(polys.get_paths()) == 3  # the straddling rod twice, the other once


def test_convert_to_extxyz_through_ase(condensed_dump, tmp_path):
    import ase.io
    out = tmp_path / "c.extxyz"
    rc, _ = run(["convert", condensed_dump, "--length-unit", "1e-3", "-o", str(out)])
    assert rc == 0
    images = ase.io.read(str(out), index=":")
    assert len(images) == 3
    ref = read_frame(condensed_dump, 2, length_unit=1e-3)
    assert np.allclose(images[2].positions, ref.pos - ref.box.lo, atol=1e-4)
    assert np.array_equal(images[2].get_array("mol"), ref.mol)
    assert list(images[0].pbc) == [True, False, False]


def test_map_command_table(condensed_dump, tmp_path):
    table = tmp_path / "m.txt"
    rc, _ = run(["map", condensed_dump, "--length-unit", "1e-3", "--frame", "0", "--bins", "31", "1",
                 "--species", "beads", "-o", str(table)])
    assert rc == 0
    phi = np.loadtxt(table, ndmin=2)
    assert phi.shape == (1, 31)
    rc, text = run(["profile", condensed_dump, "--length-unit", "1e-3", "--frame", "0", "--bins", "31"])
    prof = np.array([l.split() for l in text.splitlines()[1:]], float)[:, 1]
    assert np.allclose(phi[0], prof)  # a one-row map is the x profile
    rc, _ = run(["map", condensed_dump, "--length-unit", "1e-3", "-o", str(tmp_path / "m.png")])
    assert rc == 0 and (tmp_path / "m.png").stat().st_size > 1000


def test_profile_relative_to_layer_follows_the_moving_layer(condensed_dump):
    rc, text = run(["profile", condensed_dump, "--length-unit", "1e-3", "--relative-to-layer",
                    "--extent", "60", "--bins", "30", "--fit", "4", "56"])
    assert rc == 0, text
    lines = text.splitlines()
    rows = np.array([l.split() for l in lines[1:] if not l.startswith("#")], float)
    d, phi = rows[:, 0], rows[:, 1]
    # the layer moves by 2 d per frame; in its frame the close-packed block stays put
    assert np.allclose(phi[(d > 4) & (d < 60)], np.pi / 4, rtol=1e-6)
    assert np.all(phi[(d < -4) & (d > -24)] < 0.25)
    assert lines[-1].startswith("# eq. 5 fit:")
    rc, _ = run(["profile", condensed_dump, "--fit", "4", "56"])
    assert rc == 1  # --fit needs --relative-to-layer


def test_motility_command(tmp_path):
    import json
    rng = np.random.default_rng(11)
    box = S.square_box(40)
    frames = []
    for k in range(6):  # six rods, each its own walk
        t, c, p = S.persistent_walk(300, 0.05, 3.0, 1.0, rng, start=(6.0 * k + 3, 20.0))
        frames.append((c, p))
    dump = tmp_path / "walks.dump"
    write_dump(dump, [S.make_frame(box, [], 0.5, [f[0][i] for f in frames], [f[1][i] for f in frames],
                                   rod_vel=[3.0 * f[1][i] for f in frames], step=i).scaled(1e-3)
                      for i in range(300)])
    rc, text = run(["motility", str(dump), "--length-unit", "1e-3", "--timestep", "0.05", "--max-lag", "100"])
    assert rc == 0, text
    summary = json.loads(text)
    assert summary["axial_speed_mean"] == pytest.approx(3.0, rel=1e-3)
    assert summary["persistence_time"] == pytest.approx(1.0, rel=0.3)  # 6 short walks: noisy
    rc, text = run(["motility", str(dump), "--length-unit", "1e-3", "--timestep", "0.05", "--from-positions"])
    # finite differences over a turning path: biased low by about (1 - exp(-dt/tau))/2 ~ 2.5 %
    assert json.loads(text)["axial_speed_mean"] == pytest.approx(3.0, rel=0.05)


def test_motility_command_gives_units_and_flags_a_persistence_time_it_cannot_resolve(tmp_path, capsys):
    import json
    rng = np.random.default_rng(3)
    box = S.square_box(40)
    walks = [S.persistent_walk(76, 0.02, 3.6, 50.0, rng, start=(6.0 * k + 3, 20.0)) for k in range(6)]
    dump = tmp_path / "short.dump"     # 1.5 s of rods whose headings persist for 50 s
    write_dump(dump, [S.make_frame(box, [], 0.5, [w[1][i] for w in walks], [w[2][i] for w in walks],
                                   rod_vel=[3.6 * w[2][i] for w in walks], step=200 * i).scaled(1e-3)
                      for i in range(76)])
    rc, text = run(["motility", str(dump), "--length-unit", "1e-3", "--timestep", "1e-4"])
    assert rc == 0, text
    summary = json.loads(text)
    assert summary["tracked_duration"] == pytest.approx(1.5) and summary["units"]["tracked_duration"] == "s"
    assert summary["axial_speed_mean"] == pytest.approx(3.6, rel=1e-3) and summary["units"]["axial_speed_mean"] == "mm/s"
    assert summary["persistence_time"] is None and summary["persistence_time_resolved"] is False
    err = capsys.readouterr().err
    assert err.startswith("WARNING: activegrain motility: persistence time not resolved") and err.count("\n") == 1
    rc, text = run(["motility", str(dump)])       # metres and MD steps
    assert json.loads(text)["units"]["axial_speed_mean"] == "m/step"


def test_annulus_geometry_on_the_command_line(tmp_path):
    box = Box((-30.0, -30.0, 0.0), (30.0, 30.0, 1.12), (False, False, False))
    radii = np.arange(16.0, 27.5, 1.15)
    centres = np.column_stack([radii, np.zeros_like(radii)])
    axes = np.tile([0.0, 1.0], (len(radii), 1))
    ang = np.linspace(0.3, 2.5, 400)
    ring = 21.0 * np.column_stack([np.cos(ang), np.sin(ang)])  # beads only ahead of the layer
    fr = S.make_frame(box, ring, 0.5, centres, axes).scaled(1e-3)
    dump = tmp_path / "annulus.dump"
    write_dump(dump, [fr])
    geo = ["--geometry", "annulus", "--r-in", "0.015", "--r-out", "0.028", "--centre", "0", "0",
           "--length-unit", "1e-3"]
    rc, text = run(["profile", str(dump), "--coord", "theta", "--bins", "8"] + geo)
    assert rc == 0, text
    rows = np.array([l.split() for l in text.splitlines()[1:]], float)
    areas = 0.5 * (2 * np.pi / 8) * (28.0 ** 2 - 15.0 ** 2)
    assert np.sum(rows[:, 1]) * areas == pytest.approx(400 * np.pi * 0.25, rel=1e-5)  # 6 printed digits
    assert np.all(rows[rows[:, 0] > 3.0, 1] == 0)  # no beads past theta = 2.5 + a bead
    rc, text = run(["phase", str(dump), "--timestep", "1e-4"] + geo)     # one frame: its structure
    head, row = text.splitlines()
    vals = dict(zip(head.split(), row.split()))
    assert float(vals["P_tangential"]) == pytest.approx(1.0, abs=1e-3)
    assert float(vals["layer_contrast"]) > 0
    rc, text = run(["phase", str(dump), "--geometry", "annulus"])
    assert rc == 1  # an annulus needs its radius


def test_condensate_command(tmp_path):
    ann, before, after = S.trapped_condensate(turn=0.02)
    dump = tmp_path / "trap.dump"
    before.step, after.step = 0, 10000
    write_dump(dump, [before.scaled(1e-3), after.scaled(1e-3)])
    rc, text = run(["condensate", str(dump), "--geometry", "annulus", "--centre", "0", "0", "--r-in", "15e-3",
                    "--r-out", "28e-3", "--length-unit", "1e-3", "--timestep", "1e-4", "--threshold", "0.6"])
    assert rc == 0, text
    head, first, second = text.splitlines()
    row = dict(zip(head.split(), second.split()))
    assert float(row["time"]) == pytest.approx(1.0)
    assert (int(row["rods_at_start"]), int(row["rods_at_stop"])) == (10, 10)
    assert float(row["drift_speed"]) == pytest.approx(0.02 * 21.5, rel=0.05)  # d per s
    assert float(row["width_deg"]) == pytest.approx(np.degrees(1.7), abs=10)
    assert dict(zip(head.split(), first.split()))["drift_speed"] == "nan"  # no earlier frame
    # the rows sit 3.2 d (0.7 rod lengths) outside the arc's ends: a narrower reach misses them
    rc, text = run(["condensate", str(dump), "--geometry", "annulus", "--centre", "0", "0", "--r-in", "15e-3",
                    "--r-out", "28e-3", "--length-unit", "1e-3", "--timestep", "1e-4", "--threshold", "0.6",
                    "--reach", "0.4"])
    assert rc == 0, text
    row = dict(zip(head.split(), text.splitlines()[2].split()))
    assert (int(row["rods_at_start"]), int(row["rods_at_stop"])) == (0, 0)
    # both frames trapped (10 rods at each end, drift 0.43 d/s below 0.5); below 11 rods never
    rc, text = run(["condensate", str(dump), "--geometry", "annulus", "--centre", "0", "0", "--r-in", "15e-3",
                    "--r-out", "28e-3", "--length-unit", "1e-3", "--timestep", "1e-4", "--threshold", "0.6",
                    "--traps", "10", "--trap-drift", "0.5"])
    assert rc == 0, text
    assert text.splitlines()[-1] == "# trapped from 0 to 1 (1) (still trapped at the last frame)"
    rc, text = run(["condensate", str(dump), "--geometry", "annulus", "--centre", "0", "0", "--r-in", "15e-3",
                    "--r-out", "28e-3", "--length-unit", "1e-3", "--timestep", "1e-4", "--threshold", "0.6",
                    "--traps", "11"])
    assert text.splitlines()[-1] == "# never trapped"
    rc, _ = run(["condensate", str(dump), "--length-unit", "1e-3", "--r-out", "28e-3", "--lag", "0"])
    assert rc == 1
    rc, _ = run(["condensate", str(dump), "--length-unit", "1e-3", "--r-out", "28e-3", "--reach", "0"])
    assert rc == 1


def test_pictures_say_their_time_units_and_species(condensed_dump, tmp_path, monkeypatch):
    """Titles in seconds with the rods' polar order, axes in bead diameters, the noses marked (one
    dot per drawn rod, at its narrow end), profile and kymograph naming the same species."""
    import matplotlib.pyplot as plt
    figures = {}
    save = plt.Figure.savefig
    monkeypatch.setattr(plt.Figure, "savefig", lambda fig, path, **kw: (figures.__setitem__(
        pathlib.Path(path).name, fig), save(fig, path, **kw)))
    args = ["--length-unit", "1e-3", "--timestep", "1e-4"]
    assert run(["snapshot", condensed_dump, *args, "-o", str(tmp_path / "s.png")])[0] == 0
    ax = figures["s.png"].axes[0]
    assert ax.get_title().startswith("t = 0.20 s;  26 rods, polar order P = 1.00")
    assert (ax.get_xlabel(), ax.get_ylabel()) == ("x (d)", "y (d)")
    rods, noses = ax.collections[1], ax.collections[2]
    assert len(noses.get_offsets()) == len(rods.get_paths()) >= 26
    fr = read_frame(condensed_dump, -1, length_unit=1e-3)
    r = fr.rods()
    dots = np.asarray(noses.get_offsets())
    assert all(np.min(np.linalg.norm(dots - n, axis=1)) < 1e-9 for n in r.nose)   # the narrow ends
    assert run(["snapshot", condensed_dump, "--length-unit", "1e-3", "-o", str(tmp_path / "n.png")])[0] == 0
    assert figures["n.png"].axes[0].get_title().startswith("step 2000 (time unknown")
    assert run(["kymograph", condensed_dump, *args, "--species", "all", "-o", str(tmp_path / "k.png")])[0] == 0
    k = figures["k.png"].axes
    assert k[0].get_ylabel() == "time (s)" and k[1].get_ylabel() == "area fraction of beads and rods"
    assert run(["profile", condensed_dump, *args, "--species", "all", "--plot", str(tmp_path / "p.png")])[0] == 0
    p = figures["p.png"].axes[0]
    assert p.get_ylabel() == "area fraction of beads and rods" and p.get_xlabel() == "x (d)"
    assert p.get_title() == "mean over t = 0.00-0.20 s (3 frames)"
