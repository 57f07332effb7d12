"""Area-fraction profiles and maps on configurations with known area fractions."""
import numpy as np
import pytest
from scipy.integrate import quad

from activegrain import analysis as A, synthetic as S
from activegrain.geometry import Annulus, Box, geometry_from_box
from activegrain.rods import chain_area, chain_area_shares, chain_halfwidth


def test_lattice_gives_its_area_fraction_in_every_bin():
    box = S.channel_box(60, 12)
    a = 1.5  # square lattice: phi = pi r^2 / a^2
    fr = S.make_frame(box, S.lattice_beads(0, 60, 0, 12, a), 0.5)
    g = geometry_from_box(box)
    phi = np.pi * 0.25 / a ** 2
    for coord, n in (("x", 40), ("y", 8)):  # bins aligned with lattice cells
        p = A.area_fraction_profile(fr, g, coord, n, "beads")
        assert np.allclose(p.fraction, phi, rtol=1e-9)
    xe, ye, m = A.area_fraction_map(fr, g, (20, 4))
    assert np.allclose(m, phi, rtol=1e-9)
    assert A.global_area_fractions(fr, g)[0] == pytest.approx(phi)


def test_step_profile_and_periodic_wrap():
    box = S.channel_box(40, 10)
    dense = S.lattice_beads(0, 20, 0, 10, 1.0)       # phi = pi/4
    dilute = S.lattice_beads(20, 40, 0, 10, 2.0)     # phi = pi/16
    beads = np.concatenate([dense, dilute])
    beads[:, 0] = np.mod(beads[:, 0] + 10.0, 40.0)  # shift by 10: the dense block wraps
    fr = S.make_frame(box, beads, 0.5)
    p = A.area_fraction_profile(fr, geometry_from_box(box), "x", 8)
    expect = np.array([np.pi / 16] * 2 + [np.pi / 4] * 4 + [np.pi / 16] * 2)
    assert np.allclose(p.fraction, expect, rtol=1e-9)


def test_single_rod_profile_follows_its_tapered_width():
    box = S.channel_box(20, 6)
    s, r = S.rod_spheres()
    fr = S.make_frame(box, [], 0.5, [(10.0, 3.0)], [(1.0, 0.0)])
    edges = np.linspace(10 - 2.5, 10 + 2.5, 21)
    p = A.area_fraction_profile(fr, geometry_from_box(box), "x", edges, "rods", spacing=0.002)
    covered = p.fraction * 6 * np.diff(edges)
    expect = [quad(lambda x: 2 * chain_halfwidth(x - 10, s, r), a, b, limit=200)[0]
              for a, b in zip(edges[:-1], edges[1:])]
    # a bin edge can cut at most one slice (spacing x rod width) the wrong way
    assert np.allclose(covered, expect, atol=0.002 * 1.1)
    assert covered.sum() == pytest.approx(sum(expect), rel=1e-9)
    assert covered[:10].sum() > covered[10:].sum()  # the broad tail is at -x


def test_rods_and_beads_add_up_and_rods_counted_once():
    rng = np.random.default_rng(5)
    box = S.channel_box(50, 20)
    centres, axes = S.random_rods(12, (0, 50, 3, 17), rng)
    beads = S.remove_overlaps(S.lattice_beads(0, 50, 0, 20, 1.25), box, centres, axes)
    fr = S.make_frame(box, beads, 0.5, centres, axes)
    g = geometry_from_box(box)
    pb = A.area_fraction_profile(fr, g, "x", 10, "beads")
    pr = A.area_fraction_profile(fr, g, "x", 10, "rods")
    pa = A.area_fraction_profile(fr, g, "x", 10, "all")
    assert np.allclose(pa.fraction, pb.fraction + pr.fraction)
    phi_b, phi_r = A.global_area_fractions(fr, g)
    assert np.mean(pr.fraction) == pytest.approx(phi_r, rel=1e-9)
    assert phi_r == pytest.approx(12 * fr.rods().area[0] / 1000, rel=1e-12)
    assert np.all(pa.fraction <= 0.91)  # no double counting: never above close packing


def test_annulus_radial_and_angular_profiles():
    box = Box((-10.0, -10.0, 0.0), (10.0, 10.0, 1.12), (False, False, False))
    g = Annulus(box, (0.0, 0.0), 4.0, 9.0)
    n = 60
    ang = 2 * np.pi * np.arange(n) / n
    ring = 6.0 * np.column_stack([np.cos(ang), np.sin(ang)])  # 60 beads on a ring of radius 6
    fr = S.make_frame(box, ring, 0.25)
    pr = A.area_fraction_profile(fr, g, "r", 10, "beads")
    covered = pr.fraction * g.bin_areas("r", pr.edges)
    assert covered.sum() == pytest.approx(n * np.pi * 0.0625, rel=1e-12)
    assert np.all(covered[(pr.edges[1:] <= 5.75) | (pr.edges[:-1] >= 6.25)] == 0)
    pt = A.area_fraction_profile(fr, g, "theta", 12, "beads")
    assert np.allclose(pt.fraction, n * np.pi * 0.0625 / g.area, rtol=1e-2)
    # Cartesian strips of an annulus add up to its area
    assert g.bin_areas("x", np.linspace(-9, 9, 37)).sum() == pytest.approx(g.area, rel=1e-12)
    xe, ye, m = A.area_fraction_map(fr, g, (20, 20))
    assert np.isnan(m[10, 10]) and np.isnan(m[0, 0])  # the inner block and the corner
    assert np.nanmax(m) > 0


def test_bad_species_rejected():
    fr = S.make_frame(S.channel_box(10, 5), [(5, 2)], 0.5)
    with pytest.raises(ValueError, match="species"):
        A.area_fraction_profile(fr, geometry_from_box(fr.box), "x", 5, "grains")
    with pytest.raises(ValueError, match="coordinate"):
        A.area_fraction_profile(fr, geometry_from_box(fr.box), "r", 5)


def test_centre_count_puts_each_atom_area_in_its_centre_bin():
    box = S.channel_box(20, 10)
    geom = geometry_from_box(box)
    # a bead across the edge x = 5 with its centre left of it; a rod across x = 10
    fr = S.make_frame(box, [(4.8, 2.0)], 0.5, [(10.3, 6.0)], [(1, 0)])
    edges = np.arange(0.0, 20.1, 5.0)
    centre = A.area_fraction_profile(fr, geom, "x", edges, "all", count="centre")
    covered = A.area_fraction_profile(fr, geom, "x", edges, "beads")
    bin_area = 5.0 * 10.0
    bead, rod = np.pi * 0.25, chain_area(*S.rod_spheres())
    assert centre.fraction[0] * bin_area == pytest.approx(bead, rel=1e-12)          # whole disc left
    assert 0 < covered.fraction[1] * bin_area < bead                                  # part of it right
    assert centre.fraction.sum() * bin_area == pytest.approx(bead + rod, rel=1e-12)
    s, r = S.rod_spheres()
    left = chain_area_shares(s, r)[10.3 + s < 10].sum()
    assert centre.fraction[1] * bin_area == pytest.approx(left, rel=1e-12)
    # bins much larger than the particles: both counts agree
    one = [0.0, 20.0]
    assert A.area_fraction_profile(fr, geom, "x", one, "all", count="centre").fraction == \
        pytest.approx(A.area_fraction_profile(fr, geom, "x", one, "all").fraction, rel=1e-12)
    with pytest.raises(ValueError, match="count"):
        A.area_fraction_profile(fr, geom, "x", edges, "all", count="bins")
