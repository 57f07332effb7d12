"""Polarization, rods vs the bead gradient, layer sides and the phase classifier."""
import numpy as np
import pytest
from scipy.spatial import cKDTree

from activegrain import analysis as A, synthetic as S
from activegrain.geometry import Annulus, Box, geometry_from_box


def _rods_frame(axes, rng, box=None):
    box = box or S.square_box(200)
    n = len(axes)
    centres = rng.uniform(0, box.lengths[0], (n, 2))
    return S.make_frame(box, [], 0.5, centres, axes)


def test_aligned_rods_have_full_polarization_random_rods_none():
    rng = np.random.default_rng(0)
    fr = _rods_frame(np.tile([np.cos(0.7), np.sin(0.7)], (50, 1)), rng)
    pol = A.polarization(fr)
    assert pol["P"] == pytest.approx(1.0)
    assert (pol["Px"], pol["Py"]) == pytest.approx((np.cos(0.7), np.sin(0.7)))
    ang = rng.uniform(0, 2 * np.pi, 2000)
    fr = _rods_frame(np.column_stack([np.cos(ang), np.sin(ang)]), rng)
    assert A.polarization(fr)["P"] < 3 / np.sqrt(2000)
    # nematic but not polar: half the rods reversed
    axes = np.tile([1.0, 0.0], (100, 1))
    axes[::2] *= -1
    assert A.polarization(_rods_frame(axes, rng))["P"] == pytest.approx(0.0, abs=1e-12)
    assert A.polarization(_rods_frame(axes, rng))["S"] == pytest.approx(1.0)


def test_nematic_order_of_known_sets():
    assert A.nematic_order([(1, 0), (-1, 0), (0, 0)]) == pytest.approx(1.0)      # zero vector skipped
    assert A.nematic_order([(1, 0), (0, 1)]) == pytest.approx(0.0, abs=1e-12)     # perpendicular axes
    assert A.nematic_order([(1, 0), (1, 1)]) == pytest.approx(np.cos(np.pi / 4))  # 45 degrees apart


def test_velocity_order_and_tangential_polarization():
    box = Box((-10.0, -10.0, 0.0), (10.0, 10.0, 1.12), (False, False, False))
    ann = Annulus(box, (0.0, 0.0), 3.0, 9.0)
    ang = np.linspace(0, 2 * np.pi, 12, endpoint=False)
    centres = 6 * np.column_stack([np.cos(ang), np.sin(ang)])
    e_theta = np.column_stack([-np.sin(ang), np.cos(ang)])
    fr = S.make_frame(box, [(0.0, 7.5)], 0.5, centres, e_theta, bead_vel=[(1.0, 0.0)], rod_vel=2 * e_theta)
    pol = A.polarization(fr, ann)
    assert pol["P_tangential"] == pytest.approx(1.0)
    assert pol["P"] == pytest.approx(0.0, abs=1e-12)  # all around the ring: no net vector
    assert pol["bead_velocity_order"] == pytest.approx(1.0)
    assert pol["rod_velocity_order"] == pytest.approx(0.0, abs=1e-12)
    fr2 = S.make_frame(box, [], 0.5, centres, -e_theta)
    assert A.polarization(fr2, ann)["P_tangential"] == pytest.approx(-1.0)


@pytest.mark.parametrize("sign", [1, -1])
def test_rods_relative_to_bead_gradient(sign):
    rng = np.random.default_rng(2)
    box = S.channel_box(120, 30)
    # bead density rising along x: strips of decreasing lattice spacing
    beads = np.concatenate([S.lattice_beads(x0, x0 + 24, 0, 30, a)
                            for x0, a in zip(range(0, 120, 24), (3.0, 2.4, 2.0, 1.5, 1.2))])
    centres, _ = S.random_rods(10, (30, 90, 4, 26), rng)
    axes = np.tile([sign, 0.0], (10, 1))
    fr = S.make_frame(box, S.remove_overlaps(beads, box, centres, axes), 0.5, centres, axes)
    cos, mean = A.gradient_alignment(fr, geometry_from_box(box), smoothing=3.0)
    assert sign * mean > 0.8
    env = A.rod_environment(fr, geometry_from_box(box), smoothing=3.0)
    # local bead fraction rises with x like the strips (0.09 at x ~ 12 ... 0.55 at x ~ 108)
    order = np.argsort(centres[:, 0])
    assert np.corrcoef(centres[order, 0], env["phi_b"][order])[0, 1] > 0.8
    assert np.all(env["gradient"][:, 0] > 0)


def test_layer_sides_measure_both_densities():
    fr = S.phase_configuration("condensed")
    layer = A.layer_sides(fr, geometry_from_box(fr.box))
    assert layer.coord == "x" and layer.direction == 1
    assert layer.position == pytest.approx(30.0, abs=0.1)
    assert layer.fraction_in_layer == 1.0
    assert layer.phi_ahead == pytest.approx(np.pi / 4, rel=1e-6)   # lattice spacing 1
    assert layer.phi_behind == pytest.approx(np.pi / 16, rel=0.1)  # lattice spacing 2
    # mirrored: rods point -x, the dense side is at -x
    fr.pos[:, 0] = fr.box.wrap(np.column_stack([124.0 - fr.pos[:, 0], fr.pos[:, 1]]))[:, 0]
    mirrored = A.layer_sides(fr, geometry_from_box(fr.box))
    assert mirrored.direction == -1
    assert mirrored.phi_ahead == pytest.approx(np.pi / 4, rel=1e-6)


def test_layer_sides_in_a_period_shorter_than_both_windows():
    # A 40 x 40 periodic box (box-small) with a uniform bed: the default windows (gap L plus
    # 5 L on each side, 54 in all) would wrap past half the period; both sides must still read
    # the bed's own fraction (before the windows were capped they read 0.69 of it).
    box = Box((0.0, 0.0, 0.0), (40.0, 40.0, 1.12), (True, True, False))
    axes = np.tile([1.0, 0.0], (6, 1))
    centres = np.column_stack([np.full(6, 20.0), np.linspace(5.0, 35.0, 6)])
    beads = S.remove_overlaps(S.lattice_beads(0, 40, 0, 40, 1.25), box, centres, axes)
    fr = S.make_frame(box, beads, 0.5, centres, axes)
    layer = A.layer_sides(fr, geometry_from_box(box))
    phi = np.pi / 4 / 1.25 ** 2    # the lattice's own fraction (beads are gone only at the rods)
    assert layer.coord == "x"
    assert layer.phi_ahead == pytest.approx(phi, rel=0.05)
    assert layer.phi_behind == pytest.approx(phi, rel=0.05)


def _classify_moving(fr, thresholds=None, geometry=None):
    """``fr`` classified as the last frame of a run whose rods advanced along their axes at 2 d/s
    (0.44 rod lengths per second) and whose beads moved at 0.3 d/s over the second before it."""
    window = S.trajectory(fr, [-1.0, 0.0], rod_speed=2.0, bead_speed=0.3)
    return A.classify_phase(window[-1], geometry or geometry_from_box(fr.box), thresholds, window=window)


@pytest.mark.parametrize("seed", [0, 1, 2])
@pytest.mark.parametrize("phase", ["isotropic", "flock", "segregated", "condensed"])
def test_classifier_recognises_constructed_phases(phase, seed):
    fr = S.phase_configuration(phase, seed=seed)
    assert _classify_moving(fr).phase == phase
    # one frame shows the structure; aligned rods might be a flock or held still
    assert A.classify_phase(fr, geometry_from_box(fr.box)).phase == ("aligned" if phase == "flock" else phase)


@pytest.mark.parametrize("phase", ["isotropic", "flock", "segregated", "condensed", "trapped"])
def test_classifier_on_disordered_packings(phase):
    fr = S.phase_configuration(phase, seed=7, packing="relaxed")
    xy, r, _ = fr.beads()
    tree = cKDTree(xy - fr.box.lo[:2], boxsize=[fr.box.lengths[0], 1e3])  # periodic along x
    assert len(tree.query_pairs(0.99)) == 0  # a real packing: no overlapping beads
    expect = "condensed" if phase == "trapped" else phase
    assert _classify_moving(fr).phase == expect


def test_two_opposed_layers_trap_a_condensate():
    fr = S.phase_configuration("trapped")
    g = geometry_from_box(fr.box)
    layers = A.find_layers(fr, g)
    assert len(layers) == 2
    assert sorted((l.position, l.direction) for l in layers) == [(30.0, 1), (70.0, -1)]
    for l in layers:
        assert l.fraction_in_layer == pytest.approx(0.5)
        assert l.phi_ahead == pytest.approx(np.pi / 4, rel=1e-6)
        assert l.phi_behind == pytest.approx(np.pi / 16, rel=0.1)
    res = A.classify_phase(fr, g)
    assert res.phase == "condensed"
    assert res.observables["n_active_layers"] == 2
    assert res.observables["P"] == pytest.approx(0.0, abs=1e-12)  # no net polarization
    # with one layer's rods turned around, that layer pushes into the dilute side: not active
    rods = fr.rods()
    flipped = S.make_frame(fr.box, fr.beads()[0], 0.5, rods.centre, np.tile([1.0, 0.0], (len(rods), 1)))
    assert A.phase_observables(flipped, g)["n_active_layers"] == 1


def test_classifier_thresholds_are_what_decides():
    fr = S.phase_configuration("flock")
    res = _classify_moving(fr)
    assert res.phase == "flock"
    P, speed = res.observables["P_mean"], res.observables["rod_speed"]
    assert _classify_moving(fr, A.PhaseThresholds(polar_order=min(1.0, P + 0.01))).phase == "isotropic"
    assert _classify_moving(fr, A.PhaseThresholds(flock_speed=speed + 0.01)).phase == "arrested"


def test_condensed_layer_in_an_annulus():
    box = Box((-30.0, -30.0, 0.0), (30.0, 30.0, 1.12), (False, False, False))
    ann = Annulus(box, (0.0, 0.0), 15.0, 28.0)
    # a radial row of rods at theta = 0 pointing counter-clockwise; beads dense for 0 < theta < 2
    radii = np.arange(16.0, 27.5, 1.15)
    centres = np.column_stack([radii, np.zeros_like(radii)])
    axes = np.tile([0.0, 1.0], (len(radii), 1))
    pts = S.lattice_beads(-30, 30, -30, 30, 1.0)
    r, th = ann.polar(pts)
    inside = (r > 15.5) & (r < 27.5)
    keep = inside & (((th > 0.15) & (th < 2.0)) | ((th > 2.0) & (np.arange(len(pts)) % 4 == 0)))
    beads = S.remove_overlaps(pts[keep], box, centres, axes)
    fr = S.make_frame(box, beads, 0.5, centres, axes)
    res = A.classify_phase(fr, ann)
    assert res.observables["layer_coord"] == "theta"
    prof = A.layer_profile(fr, ann, bins=36)  # arc lengths at the mid radius, full turn
    arc = 0.5 * (ann.r_in + ann.r_out)
    areas = 0.5 * np.diff(prof.edges) / arc * (ann.r_out ** 2 - ann.r_in ** 2)
    assert np.sum(prof.fraction * areas) == pytest.approx(len(beads) * np.pi * 0.25, rel=1e-9)
    assert np.mean(prof.fraction[(prof.centres > 3) & (prof.centres < 20)]) > 0.6
    assert res.observables["phi_ahead"] > res.observables["phi_behind"] + 0.3
    assert res.phase == "condensed"


def test_beads_only_frame_is_isotropic_and_has_no_layer():
    box = S.channel_box(40, 10)
    fr = S.make_frame(box, S.lattice_beads(0, 40, 0, 10, 1.2), 0.5)
    g = geometry_from_box(box)
    assert A.classify_phase(fr, g).phase == "isotropic"
    assert A.polarization(fr)["n_rods"] == 0
    assert np.isnan(A.gradient_alignment(fr, g)[1])
    with pytest.raises(ValueError, match="no rods"):
        A.layer_sides(fr, g)


def _strip_beads(d_edges, phi_target, x_layer, width, length):
    """Beads in strips [d_k, d_k+1) at distance d ahead of x_layer: 4 columns per 4-wide
    strip, rows chosen to approach phi_target(d); returns beads and the exact fractions."""
    beads, exact = [], []
    for a, b in zip(d_edges[:-1], d_edges[1:]):
        w = b - a
        n_rows = int(min(np.floor(width), round(phi_target(0.5 * (a + b)) * w * width / (np.pi / 4) / w)))
        xs = x_layer + a + (np.arange(int(w)) + 0.5)
        ys = (np.arange(n_rows) + 0.5) * width / n_rows
        X, Y = np.meshgrid(xs, ys)
        beads.append(np.column_stack([np.mod(X.ravel(), length), Y.ravel()]))
        exact.append(int(w) * n_rows * np.pi / 4 / (w * width))
    return np.concatenate(beads), np.array(exact)


def test_profile_ahead_of_a_layer_and_exponential_fit():
    length, width, x_layer, ell = 120.0, 31.0, 30.0, 10.0
    target = lambda d: 0.35 + 0.4 * np.exp(-(d - 4) / ell) if d > 0 else 0.35
    ahead = np.arange(4.0, 60.0, 4.0)
    behind = -ahead[::-1]
    b1, e1 = _strip_beads(ahead, target, x_layer, width, length)
    b2, e2 = _strip_beads(behind, target, x_layer, width, length)
    ys = np.arange(1.0, width - 0.5, 1.15)
    centres = np.column_stack([np.full(len(ys), x_layer), ys])
    box = S.channel_box(length, width)
    fr = S.make_frame(box, np.concatenate([b1, b2]), 0.5, centres, np.tile([1.0, 0.0], (len(ys), 1)))
    g = geometry_from_box(box)
    prof = A.layer_profile(fr, g, extent=60.0, bins=30)
    d = prof.centres
    assert np.allclose(prof.fraction[(d > 4) & (d < 56)], e1, rtol=1e-9)
    assert np.allclose(prof.fraction[(d < -4) & (d > -56)], e2, rtol=1e-9)
    phi_plus, ell_fit, phi0 = A.fit_layer_exponential(prof, 4.0, 56.0)
    assert ell_fit == pytest.approx(ell, rel=0.1)
    assert phi0 == pytest.approx(0.35, abs=0.02)
    assert phi_plus == pytest.approx(0.35 + 0.4 * np.exp(4 / ell), abs=0.05)
    # mirrored (layer pointing -x): the same profile ahead
    mirrored = S.make_frame(box, np.column_stack([np.mod(2 * x_layer - fr.beads()[0][:, 0], length),
                                                  fr.beads()[0][:, 1]]), 0.5, centres,
                            np.tile([-1.0, 0.0], (len(ys), 1)))
    assert np.allclose(A.layer_profile(mirrored, g, extent=60.0, bins=30).fraction, prof.fraction, rtol=1e-9)


def test_layer_along_y_in_a_periodic_box():
    box = S.square_box(60)
    xs = np.arange(1.0, 59.5, 1.15)
    centres = np.column_stack([xs, np.full(len(xs), 20.0)])
    axes = np.tile([0.0, -1.0], (len(xs), 1))  # pointing -y: the dense side is below
    beads = np.concatenate([S.lattice_beads(0, 60, 0, 17, 1.0), S.lattice_beads(0, 60, 23, 60, 2.0)])
    fr = S.make_frame(box, S.remove_overlaps(beads, box, centres, axes), 0.5, centres, axes)
    layer = A.layer_sides(fr, geometry_from_box(box))
    assert (layer.coord, layer.direction) == ("y", -1)
    assert layer.position == pytest.approx(20.0)
    # behind: 11 whole dilute rows in y 24.5..47
    assert layer.phi_behind == pytest.approx(11 * 30 * np.pi / 4 / (22.5 * 60))
    # ahead: y 15.5 down to -7, wrapping into 53..60: 15.5 dense rows of 60, 3 dilute rows of 30
    assert layer.phi_ahead == pytest.approx((15.5 * 60 + 3 * 30) * np.pi / 4 / (22.5 * 60), rel=2e-3)


def test_layer_windows_are_clipped_at_walls_of_a_rectangle():
    box = Box((0.0, 0.0, 0.0), (40.0, 20.0, 1.12), (False, False, False))
    ys = np.arange(1.0, 19.5, 1.15)
    centres = np.column_stack([np.full(len(ys), 30.0), ys])
    axes = np.tile([1.0, 0.0], (len(ys), 1))
    beads = np.concatenate([S.lattice_beads(33, 40, 0, 20, 1.0), S.lattice_beads(0, 27, 0, 20, 2.0)])
    fr = S.make_frame(box, S.remove_overlaps(beads, box, centres, axes), 0.5, centres, axes)
    g = geometry_from_box(box)
    layer = A.layer_sides(fr, g)
    assert layer.coord == "x" and layer.direction == 1
    # the window ahead (34.5..57) ends at the wall x = 40: the fraction is over 34.5..40 only
    assert layer.phi_ahead == pytest.approx(np.pi / 4, rel=0.05)
    assert layer.phi_behind == pytest.approx(np.pi / 16, rel=0.05)
    # beads pressed slightly into a wall keep their whole area in the edge bin
    fr2 = S.make_frame(box, [(0.3, 10.0), (39.8, 10.0)], 0.5)
    p = A.area_fraction_profile(fr2, g, "x", 4)
    assert np.sum(p.fraction * g.bin_areas("x", p.edges)) == pytest.approx(2 * np.pi * 0.25)


# --------------------------------------------------------------------------- jammed

def test_bead_mobility_is_the_rms_displacement_in_bead_diameters():
    fr = S.dense_configuration()
    moved = S.displaced(fr, 0.3, seed=4)
    assert A.bead_mobility(moved, fr) == pytest.approx(0.3, rel=0.05)   # ~1500 beads
    assert A.bead_mobility(fr, fr) == 0.0
    with pytest.raises(ValueError, match="same beads"):
        A.bead_mobility(S.phase_configuration("isotropic"), fr)


def test_dense_arrested_packing_is_jammed_and_only_that():
    fr = S.dense_configuration()
    geom = geometry_from_box(fr.box)
    obs = A.phase_observables(fr, geom)
    assert obs["phi_total"] >= 0.85 and obs["phi_r"] > 0.01
    # arrested: beads rattle by 2 % of a diameter in a second
    later = S.displaced(fr, 0.02, seed=1, dt=1.0)
    res = A.classify_phase(later, geom, window=[fr, later])
    assert res.phase == "jammed" and res.observables["mobility"] < 0.03
    assert res.observables["window"] == 1.0
    # the same displacement over 0.1 s is 0.2 d/s: mobile, not jammed
    sooner = S.displaced(fr, 0.02, seed=1, dt=0.1)
    res = A.classify_phase(sooner, geom, window=[fr, sooner])
    assert res.phase != "jammed" and res.observables["mobility"] == pytest.approx(0.2, rel=0.05)
    # the same packing with beads that move half a diameter in a second is not
    moved = S.displaced(fr, 0.5, seed=1)
    assert A.classify_phase(moved, geom, window=[fr, moved]).phase != "jammed"
    # without a window there is no mobility to decide on
    res = A.classify_phase(fr, geom)
    assert res.phase != "jammed" and np.isnan(res.observables["mobility"])
    # a packing below the jammed fraction with still beads is not jammed either
    t = A.PhaseThresholds(jammed_fraction=obs["phi_total"] + 0.01)
    assert A.classify_phase(later, geom, t, window=[fr, later]).phase != "jammed"


def test_still_dilute_beads_are_not_jammed():
    fr = S.phase_configuration("isotropic")
    geom = geometry_from_box(fr.box)
    later = S.displaced(fr, 0.01, seed=2)
    res = A.classify_phase(later, geom, window=[fr, later])
    assert res.phase == "isotropic" and res.observables["phi_total"] < 0.7


def test_layer_drive_measures_the_beads_and_rods_it_moves():
    # A width-spanning row at x = 30 in a 124 x 31 channel, rods tilted +-60 degrees in turn
    # (polar order cos 60 = 0.5 along +x); beads within a rod length of it move at 2 along x,
    # the others stand still; the rods move at 3.
    box = Box((0.0, 0.0, 0.0), (124.0, 31.0, 1.12), (True, False, False))
    angle = np.radians(60.0)
    axes = np.array([[np.cos(angle), (-1) ** k * np.sin(angle)] for k in range(8)])
    centres = np.column_stack([np.full(8, 30.0), np.linspace(2.0, 29.0, 8)])
    beads = S.remove_overlaps(S.lattice_beads(0, 124, 0, 31, 1.5), box, centres, axes)
    bead_vel = np.where(np.abs(beads[:, :1] - 30.0) <= 4.5, [2.0, 0.7], [0.0, 0.0])
    fr = S.make_frame(box, beads, 0.5, centres, axes, bead_vel=bead_vel, rod_vel=np.tile([3.0, 0.0], (8, 1)))
    drive = A.layer_drive(fr, geometry_from_box(box))
    assert drive["alignment"] == pytest.approx(0.5, rel=1e-9)
    assert drive["beads"] == pytest.approx(2.0, rel=1e-12)
    assert drive["alpha"] == pytest.approx(4.0, rel=1e-9)
    assert drive["u"] == pytest.approx(6.0, rel=1e-9)
    assert drive["rods_in_layer"] == 8 and drive["beads_in_layer"] > 50
    with pytest.raises(ValueError):
        A.layer_drive(S.make_frame(box, beads, 0.5, centres, axes), geometry_from_box(box))


def test_layer_side_mobility_separates_a_crystal_pushed_ahead_from_a_fluid_behind():
    # A row at x = 30 pointing +x in a 124 x 31 channel; between the frames the beads ahead all
    # move by 0.3 along x (no motion against each other), those behind by a random jitter of
    # known rms about a drift of 0.1.
    box = Box((0.0, 0.0, 0.0), (124.0, 31.0, 1.12), (True, False, False))
    centres = np.column_stack([np.full(8, 30.0), np.linspace(2.0, 29.0, 8)])
    axes = np.tile([1.0, 0.0], (8, 1))
    beads = S.remove_overlaps(S.lattice_beads(0, 124, 0, 31, 1.5), box, centres, axes)
    before = S.make_frame(box, beads, 0.5, centres, axes)
    layer = A.layer_sides(before, geometry_from_box(box))
    L = float(np.median(before.rods().length))
    s = beads[:, 0] - layer.position
    s -= 124.0 * np.round(s / 124.0)
    ahead, behind = (s >= L) & (s <= 6 * L), (s <= -L) & (s >= -6 * L)
    jitter = np.random.default_rng(3).normal(0.0, 0.2, size=beads.shape)
    moved = beads + np.where(ahead[:, None], [0.3, 0.0], 0.0) + np.where(behind[:, None], jitter + [0.1, 0.0], 0.0)
    after = S.make_frame(box, moved, 0.5, centres, axes)
    m = A.layer_side_mobility(after, before, geometry_from_box(box))
    assert layer.direction == 1
    assert m["n_ahead"] == ahead.sum() > 50 and m["n_behind"] == behind.sum() > 50
    assert m["ahead"] == pytest.approx(0.0, abs=1e-9)
    assert m["ahead_drift"] == pytest.approx(0.3, rel=1e-9)
    j = jitter[behind] - jitter[behind].mean(axis=0)
    assert m["behind"] == pytest.approx(np.sqrt(np.mean(np.sum(j * j, axis=1))), rel=1e-9)
    assert m["behind_drift"] == pytest.approx(0.1 + jitter[behind, 0].mean(), rel=1e-9)


def test_layer_height_modes_recover_a_cosine_shaped_row():
    # Ten rods across a 124 x 31 channel (walls in y) at y_j = (j + 1/2) W / 10, their centres at
    # x = 30 + 0.8 cos(pi y / W) + 0.3 cos(3 pi y / W): modes 1 and 3 exactly, none else.
    box = Box((0.0, 0.0, 0.0), (124.0, 31.0, 1.12), (True, False, False))
    y = (np.arange(10) + 0.5) * 3.1
    x = 30.0 + 0.8 * np.cos(np.pi * y / 31.0) + 0.3 * np.cos(3 * np.pi * y / 31.0)
    beads = S.remove_overlaps(S.lattice_beads(0, 124, 0, 31, 1.5), box, np.column_stack([x, y]),
                              np.tile([1.0, 0.0], (10, 1)))
    fr = S.make_frame(box, beads, 0.5, np.column_stack([x, y]), np.tile([1.0, 0.0], (10, 1)))
    q, a = A.layer_height_modes(fr, geometry_from_box(box), modes=4)
    assert q == pytest.approx(np.arange(1, 5) * np.pi / 31.0, rel=1e-12)
    assert a == pytest.approx([0.8, 0.0, 0.3, 0.0], abs=1e-9)
    # Equipartition: modes of rms a_n = sqrt(2 T / (sigma W)) / q_n give T / sigma in every mode.
    length = A.interfacial_length(q, np.array([np.sqrt(2 * 1.9 / 31.0) / q, -np.sqrt(2 * 1.9 / 31.0) / q]), 31.0)
    assert length == pytest.approx(np.full(4, 1.9), rel=1e-12)
    with pytest.raises(ValueError):
        A.layer_height_modes(fr, geometry_from_box(Box((0.0, 0.0, 0.0), (124.0, 31.0, 1.12), (True, True, False))))


def test_aligned_rods_held_still_are_not_a_flock():
    fr = S.phase_configuration("flock")
    g = geometry_from_box(fr.box)
    rods = fr.rods()
    L = float(np.median(rods.length))

    def advanced(by):  # every rod moved ``by`` rod lengths along its own axis, 1 s later
        return S.make_frame(fr.box, fr.beads()[0], 0.5, rods.centre + by * L * rods.axis, rods.axis, time=1.0)

    def classify(later):
        return A.classify_phase(later, g, window=[fr, later])
    moving = classify(advanced(0.3))
    assert moving.phase == "flock" and moving.observables["rod_speed"] == pytest.approx(0.3 * np.mean(
        rods.axis @ (rods.axis.mean(axis=0) / np.linalg.norm(rods.axis.mean(axis=0)))))
    assert A.rod_drift(advanced(0.3), fr) == pytest.approx(0.3)      # along each rod's own axis
    # the same rods pressed still, e.g. stacked into a corner (rectangle-small): arrested
    still = classify(advanced(0.0))
    assert still.phase == "arrested" and still.observables["rod_speed"] == pytest.approx(0.0, abs=1e-12)
    # pushed backwards is not a flock's motion either
    assert classify(advanced(-0.3)).phase == "arrested"
    # without a window there is no speed to decide on: one frame shows aligned rods
    assert np.isnan(A.classify_phase(fr, g).observables["rod_speed"])
    assert A.classify_phase(fr, g).phase == "aligned"


def test_dense_arc_its_drift_and_the_rods_capping_it():
    ann, before, after = S.trapped_condensate(turn=0.02)
    arc = A.dense_arc(before, ann, threshold=0.6, sectors=72)
    step = 2 * np.pi / 72
    assert arc.start == pytest.approx(0.3, abs=step) and arc.stop == pytest.approx(2.0, abs=step)
    assert arc.fraction > 0.65 and arc.outside < 0.3
    assert A.capping_rods(before, ann, arc) == (10, 10)
    # rotated by 0.02 rad counter-clockwise: arc length 0.02 at the mid radius 21.5
    assert A.arc_drift(after, before, ann, arc) == pytest.approx(0.02 * 21.5, rel=0.05)
    held = A.arc_drift(before, before, ann, arc)
    assert held == 0.0
    # an arc on the sparse side holds beads that did not move
    assert A.arc_drift(after, before, ann, A.Arc(3.0, 1.0, 0.2, 0.5)) == 0.0
    # reversed rods cap nothing
    flipped = S.make_frame(before.box, before.beads()[0], 0.5, before.rods().centre, -before.rods().axis)
    assert A.capping_rods(flipped, ann, arc) == (0, 0)


def test_dense_arc_wraps_round_and_needs_an_annulus():
    ann, before, _ = S.trapped_condensate()
    xy = before.beads()[0]
    turned = xy @ np.array([[np.cos(5.0), np.sin(5.0)], [-np.sin(5.0), np.cos(5.0)]])  # dense 5.3 to 7.0
    fr = S.make_frame(before.box, turned, 0.5)
    arc = A.dense_arc(fr, ann, threshold=0.6)
    assert arc.contains(0.0) and arc.contains(5.5) and not arc.contains(3.0)
    assert arc.width == pytest.approx(1.7, abs=2 * np.pi / 72)
    assert A.dense_arc(fr, ann, threshold=0.99) is None
    # beads in the lobes of a scalloped wall (centres beyond r_out) are not the ring's
    lobe = np.array([[29.0 * np.cos(a), 29.0 * np.sin(a)] for a in np.linspace(3.2, 3.4, 8)])
    lobed = S.make_frame(before.box, np.concatenate([turned, lobe]), 0.5)
    assert A.dense_arc(lobed, ann, threshold=0.6) == arc
    with pytest.raises(ValueError, match="only for an annulus"):
        A.dense_arc(fr, geometry_from_box(S.channel_box(40, 10)))


def test_trap_spans_join_short_gaps_and_end_where_a_layer_leaves_or_the_arc_moves():
    t = np.arange(12.0)
    start = [0, 4, 4, 4, 1, 4, 4, 4, 4, 4, 0, 0]      # frame 4: a layer lost rods for a moment
    stop = [5, 5, 5, 5, 5, 5, 5, 5, 5, 5, 5, 5]
    drift = [np.nan, 0.1, -0.2, 0.1, 0.1, 0.0, 0.1, 0.9, 0.1, 0.1, 0.1, 0.1]   # frame 7: pushed round
    assert A.trap_spans(t, start, stop, drift, min_rods=3, max_drift=0.3, max_gap=2.0) == [(1.0, 9.0)]
    # a shorter allowed gap splits the span where it missed
    assert A.trap_spans(t, start, stop, drift, min_rods=3, max_drift=0.3, max_gap=1.0) == [(1.0, 3.0), (5.0, 6.0),
                                                                                            (8.0, 9.0)]
    assert A.trap_spans(t, start, stop, drift, min_rods=6) == []
