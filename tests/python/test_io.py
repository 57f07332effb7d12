"""Dump reading/writing: round trip, units, image flags, rods across the boundary."""
import numpy as np
import pytest

from activegrain import read_dump, read_frame, write_dump, geometry_from_box, Box
from activegrain.io import to_universe
from activegrain import synthetic as S
from activegrain.geometry import Channel, PeriodicBox, Rectangle, Annulus


def test_round_trip_with_units_and_velocities(tmp_path):
    rng = np.random.default_rng(1)
    box = S.channel_box(40, 10)
    beads = S.lattice_beads(0, 40, 0, 10, 2.0)
    centres, axes = S.random_rods(3, (5, 35, 3, 7), rng)
    frames = []
    for step in (0, 500):
        fr = S.make_frame(box, beads, 0.5, centres, axes, bead_vel=rng.normal(size=(len(beads), 2)),
                          rod_vel=rng.normal(size=(3, 2)), step=step)
        frames.append(fr.scaled(1e-3))  # metres, as the simulations write them
    path = tmp_path / "d.dump"
    write_dump(path, frames)
    back = list(read_dump(str(path), length_unit=1e-3, timestep=2e-6))
    assert [f.step for f in back] == [0, 500]
    assert back[1].time == pytest.approx(500 * 2e-6)
    assert back[0].box.periodic == (True, False, False)
    assert np.allclose(back[0].box.hi, (40, 10, 1.12))
    ref = frames[1].scaled(1e3)
    assert np.array_equal(back[1].mol, ref.mol)
    assert np.allclose(back[1].radius, ref.radius)
    assert np.allclose(back[1].pos, ref.pos, atol=1e-9)
    assert np.allclose(back[1].vel, ref.vel, atol=1e-9)
    rods = back[1].rods()
    assert np.allclose(rods.axis, axes, atol=1e-5)
    assert isinstance(geometry_from_box(back[0].box), Channel)


def test_image_flags_and_rod_straddling_the_boundary(tmp_path):
    box = Box((0.0, 0.0, 0.0), (20.0, 20.0, 1.12), (True, True, False))
    s, r = S.rod_spheres()
    # rod centred on x = 0 pointing +x: half of it sits across the periodic boundary
    lines = ["ITEM: TIMESTEP", "7", "ITEM: NUMBER OF ATOMS", str(len(s) + 1),
             "ITEM: BOX BOUNDS pp pp ff", "0 20", "0 20", "0 1.12",
             "ITEM: ATOMS id mol type radius x y z ix iy iz"]
    lines.append("1 0 1 0.5 25.0 3.0 0.5 0 0 0")  # unwrapped position + image 0: wrapped on read
    for i, (x, ri) in enumerate(zip(s, r)):
        img = -1 if x < 0 else 0
        lines.append(f"{i + 2} 5 2 {ri} {x} 10.0 0.5 {img} 0 0")  # x unwrapped in image -1
    path = tmp_path / "img.dump"
    path.write_text("\n".join(lines) + "\n")
    fr = read_frame(str(path))
    assert fr.step == 7
    assert 0 <= fr.pos[0, 0] < 20 and fr.pos[0, 0] == pytest.approx(5.0, abs=1e-5)
    rods = fr.rods()
    assert rods.ids.tolist() == [5]
    assert np.allclose(rods.axis[0], (1, 0), atol=1e-6)
    assert np.allclose(box.minimum_image(rods.centre[0] - (0.0, 10.0)), 0, atol=1e-5)
    assert 0 <= rods.centre[0, 0] < 20
    assert rods.length[0] == pytest.approx(S.ROD_LENGTH, rel=1e-6)


def test_unwrapped_coordinate_columns_are_wrapped(tmp_path):
    p = tmp_path / "xu.dump"
    p.write_text("ITEM: TIMESTEP\n3\nITEM: NUMBER OF ATOMS\n2\nITEM: BOX BOUNDS pp ff pp\n"
                 "-5 5\n0 4\n0 1\nITEM: ATOMS id mol type radius xu yu zu\n"
                 "2 0 1 0.5 13.0 2.0 0.5\n1 0 1 0.5 -6.0 1.0 0.5\n")
    fr = read_frame(str(p))
    assert np.allclose(fr.pos[:, :2], [(4.0, 1.0), (3.0, 2.0)], atol=1e-5)  # sorted by id, wrapped in x
    assert fr.box.lo == (-5.0, 0.0, 0.0) and fr.vel is None


def test_missing_columns_and_not_a_dump(tmp_path):
    p = tmp_path / "bad.dump"
    p.write_text("ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n1\nITEM: BOX BOUNDS pp pp pp\n"
                 "0 1\n0 1\n0 1\nITEM: ATOMS id type x y z\n1 1 0.5 0.5 0.5\n")
    with pytest.raises(ValueError, match="mol"):
        read_frame(str(p))
    t = tmp_path / "time.dump"
    t.write_text("ITEM: UNITS\nsi\nITEM: TIME\n0\nITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n1\n"
                 "ITEM: BOX BOUNDS pp pp pp\n0 1\n0 1\n0 1\nITEM: ATOMS id mol type radius x y z\n"
                 "1 0 1 0.5 0.5 0.5 0.5\n")
    with pytest.raises(ValueError, match="dump_modify"):
        read_frame(str(t))
    q = tmp_path / "junk.txt"
    q.write_text("hello\n" * 20)
    with pytest.raises(ValueError, match="not a LAMMPS text dump"):
        read_frame(str(q))


def test_geometries_from_box_flags():
    pp = Box((0, 0, 0), (10, 10, 1), (True, True, False))
    pf = Box((0, 0, 0), (10, 10, 1), (True, False, False))
    ff = Box((0, 0, 0), (10, 10, 1), (False, False, False))
    assert isinstance(geometry_from_box(pp), PeriodicBox)
    assert isinstance(geometry_from_box(pf), Channel)
    assert isinstance(geometry_from_box(ff), Rectangle)
    a = geometry_from_box(ff, "annulus", r_in=2, r_out=5)
    assert isinstance(a, Annulus) and a.centre == (5.0, 5.0)
    assert a.area == pytest.approx(np.pi * 21)
    with pytest.raises(ValueError, match="r_out"):
        geometry_from_box(ff, "annulus")
    with pytest.raises(ValueError, match="periodic in y only"):
        geometry_from_box(Box((0, 0, 0), (1, 1, 1), (False, True, False)))


def test_to_ase_keeps_cell_and_molecules():
    fr = S.make_frame(S.channel_box(30, 10), S.lattice_beads(0, 30, 0, 10, 2.0), 0.5,
                      [(15, 5)], [(0, 1)])
    atoms = fr.to_ase()
    assert len(atoms) == len(fr.ids)
    assert np.allclose(atoms.cell.lengths(), (30, 10, 1.12))
    assert list(atoms.pbc) == [True, False, False]
    assert np.array_equal(atoms.get_array("mol"), fr.mol)


def test_body_column_and_full_precision(tmp_path):
    box = S.channel_box(40, 10)
    fr = S.make_frame(box, [(3.0, 2.0)], 0.5, [(20.123456789012, 5.0)], [(np.cos(0.3), np.sin(0.3))])
    fr.body = np.where(fr.mol > 0, 77, 0)
    fr = fr.scaled(1e-3)
    path = tmp_path / "body.dump"
    write_dump(path, [fr])
    assert "ITEM: ATOMS id mol type radius x y z body" in path.read_text()
    back = read_frame(str(path))
    assert np.array_equal(back.body, fr.body)
    np.testing.assert_allclose(back.pos, fr.pos, rtol=1e-11, atol=1e-15)   # double precision
    assert back.rods().ids.tolist() == [77]


def test_frames_as_an_mdanalysis_universe():
    """Rods become residues (resid = rod ID), beads residues of their own; positions per frame."""
    rng = np.random.default_rng(3)
    box = S.channel_box(40, 10)
    beads = S.lattice_beads(0, 40, 0, 10, 2.0)
    centres, axes = S.random_rods(3, (5, 35, 3, 7), rng)
    frames = [S.make_frame(box, beads, 0.5, centres + shift, axes, step=100 * k).scaled(1e-3)
              for k, shift in enumerate((0.0, 0.5))]
    u = to_universe(frames, dt=1e-4, densities={1: 2700, 2: 8500})
    rods = frames[0].rods()
    assert u.atoms.n_atoms == len(frames[0].ids)
    assert len(u.select_atoms("resname ROD").residues) == len(rods.ids) == 3
    assert len(u.select_atoms("resname BEAD").residues) == int(np.sum(frames[0].is_bead))
    assert sorted(u.select_atoms("resname ROD").residues.resids) == sorted(rods.ids)
    assert u.trajectory.n_frames == 2
    u.trajectory[1]
    assert np.allclose(u.atoms.positions, frames[1].pos * 1e10, rtol=1e-6)     # m -> Angstrom
    assert np.allclose(u.dimensions[:3], np.asarray(frames[1].box.lengths) * 1e10)


# One rod of examples/minimal/in.minimal (rod_template rod length 4.5e-3 tail 1.1e-3 nose 0.7e-3
# spheres 9 density 8500, types 1 2 3) and two aluminium beads (d 1 mm, type 4), with the masses
# LAMMPS gave them (a dump of that deck with the mass column): columns id mol type radius mass x y z.
DECK_ATOMS = """\
1 1 1 0.000526596 5.90267e-06 0.00319644 0.005 0.00056
2 1 2 0.000506556 3.16011e-06 0.00364733 0.005 0.00056
3 1 2 0.000486517 2.88522e-06 0.00409822 0.005 0.00056
4 1 2 0.000466477 2.62504e-06 0.00454911 0.005 0.00056
5 1 2 0.000446437 2.37926e-06 0.005 0.005 0.00056
6 1 2 0.000426398 2.14757e-06 0.00545089 0.005 0.00056
7 1 2 0.000406358 1.92968e-06 0.00590178 0.005 0.00056
8 1 2 0.000386319 1.72527e-06 0.00635267 0.005 0.00056
9 1 3 0.000366279 1.97932e-06 0.00680356 0.005 0.00056
37 0 4 0.0005 1.41372e-06 0.000625 0.000625 0.0005125
38 0 4 0.0005 1.41372e-06 0.001875 0.000625 0.0005125
"""


def deck_dump(path, steps=(20000, 21000, 22000), rotate=0.0):
    """A dump of DECK_ATOMS in the decks' format (SI, box from z = -1 mm, velocities, body), its
    rod turned by ``rotate`` about its centre; returns the LAMMPS masses."""
    table = np.loadtxt(DECK_ATOMS.splitlines())
    xy = table[:, 5:7].copy()
    c = np.array([0.005, 0.005])
    rod = table[:, 2] < 4
    rot = np.array([[np.cos(rotate), -np.sin(rotate)], [np.sin(rotate), np.cos(rotate)]])
    xy[rod] = c + (xy[rod] - c) @ rot.T
    with open(path, "w") as f:
        for k, step in enumerate(steps):
            f.write(f"ITEM: TIMESTEP\n{step}\nITEM: NUMBER OF ATOMS\n{len(table)}\n"
                    "ITEM: BOX BOUNDS pp pp ff\n0 0.02\n0 0.02\n-0.001 0.0022\n"
                    "ITEM: ATOMS id mol type radius x y z vx vy vz body\n")
            for row, (x, y) in zip(table, xy):
                f.write(f"{int(row[0])} {int(row[1])} {int(row[2])} {row[3]:.9g} {x + 1e-4 * k:.9g} "
                        f"{y:.9g} {row[7]:.9g} 0.003 -0.002 0.001 {5 if row[2] < 4 else 0}\n")
    return table[:, 4]


@pytest.mark.parametrize("rotate", [0.0, 2.0])
def test_deck_masses_from_radii_and_densities(tmp_path, rotate):
    """Beads: 2700 kg/m^3 spheres; rod atoms: rod_template's shares of the brass frustum, as LAMMPS."""
    from activegrain.io import atom_masses
    lammps = deck_dump(tmp_path / "d.dump", rotate=rotate)
    for unit in (1.0, 1e-3):
        fr = read_frame(str(tmp_path / "d.dump"), 0, length_unit=unit)
        m = atom_masses(fr)
        np.testing.assert_allclose(m, lammps, rtol=2e-5)
    assert m[:9].sum() == pytest.approx(24.73e-6, rel=1e-3)    # docs/rod_template.rst's 24.73 mg
    m2 = atom_masses(fr, densities={1: 1000, 2: 1000, 3: 1000, 4: 1000})
    np.testing.assert_allclose(m2 / m, [1 / 8.5] * 9 + [1 / 2.7] * 2)
    with pytest.raises(ValueError, match="no density for atom type.* 4"):
        atom_masses(fr, densities={1: 8500, 2: 8500, 3: 8500})
    with pytest.raises(ValueError, match="rod 5: .*different densities"):
        atom_masses(fr, densities={1: 8500, 2: 8500, 3: 7000, 4: 2700})


def test_universe_in_mdanalysis_units(tmp_path):
    """Angstrom, Angstrom/ps, amu and ps; positions as in the dump unless shifted on request."""
    lammps = deck_dump(tmp_path / "d.dump")
    frames = list(read_dump(str(tmp_path / "d.dump"), length_unit=1e-3))
    u = to_universe(frames, dt=1e-4)
    np.testing.assert_allclose(u.atoms.masses, lammps / 1.66053906660e-27, rtol=2e-5)
    assert [ts.time for ts in u.trajectory] == pytest.approx([2.0e12, 2.1e12, 2.2e12])   # steps x 1e-4 s
    assert u.trajectory.dt == pytest.approx(0.1e12)
    u.trajectory[2]
    ref = read_frame(str(tmp_path / "d.dump"), 2)
    np.testing.assert_allclose(u.atoms.positions, ref.pos * 1e10, rtol=1e-6)
    assert u.atoms.positions[:, 2].min() > 0 and u.atoms.positions[0, 2] == pytest.approx(5.6e6)
    np.testing.assert_allclose(u.atoms.velocities, np.tile([3e-5, -2e-5, 1e-5], (11, 1)), rtol=1e-6)   # 1 m/s = 0.01 A/ps
    np.testing.assert_allclose(u.dimensions, [2e8, 2e8, 3.2e7, 90, 90, 90], rtol=1e-6)
    np.testing.assert_allclose(u.atoms.radii[-1], 5e6)
    shifted = to_universe(frames, dt=1e-4, shift_to_origin=True)
    np.testing.assert_allclose(shifted.atoms.positions[:, 2], ref.pos[:, 2] * 1e10 + 1e7, rtol=1e-6)
    com = u.select_atoms("resname ROD").center_of_mass()          # the solid rod's, 1.922 mm from the tail
    tail_face = (ref.pos[0] - [ref.radius[0], 0, 0]) * 1e10
    assert com[0] - tail_face[0] == pytest.approx(1.922e7, rel=1e-3)


def test_universe_without_dt_says_its_times_are_steps(tmp_path):
    deck_dump(tmp_path / "d.dump")
    frames = list(read_dump(str(tmp_path / "d.dump")))
    with pytest.warns(UserWarning, match="no dt .*MD step numbers, not ps"):
        u = to_universe(frames)
    assert [ts.time for ts in u.trajectory] == [20000, 21000, 22000]
    deck_dump(tmp_path / "e.dump", steps=(0, 1000, 3000))
    with pytest.raises(ValueError, match="equally spaced"):
        to_universe(read_dump(str(tmp_path / "e.dump")), dt=1e-4)


def three_frames(path):
    """A dump of three frames (steps 0, 100, 200) in metres; its text."""
    rng = np.random.default_rng(5)
    box = S.channel_box(30, 10)
    beads = S.lattice_beads(0, 30, 0, 10, 2.0)
    centres, axes = S.random_rods(2, (5, 25, 3, 7), rng)
    write_dump(path, [S.make_frame(box, beads, 0.5, centres + 0.1 * k, axes, step=100 * k).scaled(1e-3)
                      for k in range(3)])
    return path.read_text()


def cut_points(text):
    """Where a killed run can leave a dump of three frames: (name, length kept)."""
    third = text.index("ITEM: TIMESTEP\n200")
    rows = text.index("ITEM: ATOMS", third)
    rows = text.index("\n", rows) + 1
    return [("within the third frame's first line", third + 7),
            ("after its ITEM: TIMESTEP", third + len("ITEM: TIMESTEP\n")),
            ("within its box bounds", text.index("ITEM: BOX BOUNDS", third) + 30),
            ("after its header", rows),
            ("within an atom row", rows + 200),
            ("within its last row", len(text) - 3),
            ("at its last row's newline", len(text) - 1)]


@pytest.mark.parametrize("where", range(7))
def test_a_dump_cut_within_a_frame_is_read_to_its_last_whole_frame(tmp_path, where):
    """A run killed while writing its dump: the whole frames, a warning naming the file and how
    many; the same for read_dump, read_frame and count_frames."""
    from activegrain.io import TruncatedDumpWarning, count_frames
    whole = tmp_path / "whole.dump"
    text = three_frames(whole)
    name, keep = cut_points(text)[where]
    cut = tmp_path / "cut.dump"
    cut.write_text(text[:keep])
    expected = list(read_dump(str(whole), length_unit=1e-3))[:2]
    with pytest.warns(TruncatedDumpWarning) as caught:
        frames = list(read_dump(str(cut), length_unit=1e-3))
    assert len(caught) == 1, name
    message = str(caught[0].message)
    assert str(cut) in message and "its 2 whole frame(s), to step 100" in message, message
    assert [f.step for f in frames] == [0, 100], name
    for got, want in zip(frames, expected):
        assert np.array_equal(got.ids, want.ids) and np.array_equal(got.pos, want.pos)
    with pytest.warns(TruncatedDumpWarning, match="2 whole frame"):
        assert read_frame(str(cut)).step == 100           # -1: the last whole frame
    with pytest.warns(TruncatedDumpWarning):
        assert count_frames(str(cut)) == 2


def test_a_whole_dump_reads_without_warning_and_one_cut_in_its_first_frame_is_refused(tmp_path):
    import warnings
    whole = tmp_path / "whole.dump"
    text = three_frames(whole)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert [f.step for f in read_dump(str(whole))] == [0, 100, 200]
    cut = tmp_path / "first.dump"
    cut.write_text(text[:text.index("ITEM: ATOMS") + 100])
    with pytest.raises(ValueError, match="no whole frame"):
        list(read_dump(str(cut)))


def test_rows_that_do_not_match_the_columns_are_named(tmp_path):
    p = tmp_path / "rows.dump"
    p.write_text("ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n2\nITEM: BOX BOUNDS pp pp pp\n"
                 "0 1\n0 1\n0 1\nITEM: ATOMS id mol type radius x y z\n1 0 1 0.5 0.5 0.5 0.5\n2 0 C 0.5 0.5 0.5\n")
    with pytest.raises(ValueError, match=r"frame at step 0: its 2 atom rows are not 7 numbers each"):
        read_frame(str(p))
