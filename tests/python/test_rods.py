"""Rod regrouping and the exact projected area of a chain of discs."""
import numpy as np
import pytest
from scipy.integrate import quad

from activegrain import synthetic as S
from activegrain.geometry import Box
from activegrain.io import Frame
from activegrain.rods import chain_area, chain_area_shares, chain_halfwidth, chain_samples, disc_samples


def lens_union(r, d):
    """Union of two equal discs at distance d: 2 pi r^2 minus their lens."""
    lens = 2 * r * r * np.arccos(d / (2 * r)) - 0.5 * d * np.sqrt(4 * r * r - d * d)
    return 2 * np.pi * r * r - lens


def test_chain_area_known_cases():
    assert chain_area([0.0], [0.7]) == pytest.approx(np.pi * 0.49, rel=1e-12)
    assert chain_area([0.0, 5.0], [1.0, 2.0]) == pytest.approx(5 * np.pi, rel=1e-12)  # disjoint
    assert chain_area([1.0, 1.0], [0.5, 0.5]) == pytest.approx(np.pi / 4, rel=1e-12)  # coincident
    assert chain_area([0.0, 0.3], [1.0, 0.2]) == pytest.approx(np.pi, rel=1e-12)  # one inside the other
    for d in (0.1, 0.9, 1.7):
        assert chain_area([0.0, d], [1.0, 1.0]) == pytest.approx(lens_union(1.0, d), rel=1e-12)


def test_chain_area_of_tapered_rod_against_quadrature():
    s, r = S.rod_spheres()
    b = np.sort(np.concatenate([s - r, s + r]))
    ref, _ = quad(lambda x: 2 * chain_halfwidth(x, s, r), b[0], b[-1], points=b[1:-1], limit=500)
    assert chain_area(s, r) == pytest.approx(ref, rel=1e-7)
    # counted once: well below the sum of the overlapping discs
    assert chain_area(s, r) < 0.85 * np.sum(np.pi * r ** 2)


def test_chain_samples_lie_inside_and_carry_exact_area():
    s, r = S.rod_spheres()
    a, w, weight = chain_samples(s, r, 0.05)
    assert weight.sum() == pytest.approx(chain_area(s, r), rel=1e-12)
    assert np.all(np.abs(w) <= chain_halfwidth(a, s, r) + 1e-12)
    # first moment: centroid shifted to the broad tail (negative s)
    assert np.sum(a * weight) / weight.sum() < 0
    xy, wt = disc_samples([[1.0, 2.0], [3.0, 4.0]], [0.5, 0.25], 0.05)
    assert wt.sum() == pytest.approx(np.pi * (0.25 + 0.0625), rel=1e-12)
    assert np.allclose(np.sum(xy * wt[:, None], 0) / wt.sum(),
                       (0.25 * np.array([1, 2]) + 0.0625 * np.array([3, 4])) / 0.3125)


def test_rodset_tail_nose_axis_for_random_orientations():
    rng = np.random.default_rng(3)
    box = Box((0.0, 0.0, 0.0), (30.0, 30.0, 1.12), (True, True, False))
    centres = rng.uniform(0, 30, (40, 2))  # many straddle the periodic boundaries
    ang = rng.uniform(0, 2 * np.pi, 40)
    axes = np.column_stack([np.cos(ang), np.sin(ang)])
    fr = S.make_frame(box, [], 0.5, centres, axes)
    # shuffle the atom order: regrouping must not depend on it
    perm = rng.permutation(len(fr.ids))
    fr.ids, fr.mol, fr.types, fr.radius, fr.pos = (fr.ids[perm], fr.mol[perm], fr.types[perm],
                                                   fr.radius[perm], fr.pos[perm])
    rods = fr.rods()
    assert len(rods) == 40
    assert np.allclose(rods.axis, axes, atol=1e-12)
    d = box.minimum_image(rods.centre - centres)
    assert np.allclose(d, 0, atol=1e-9)
    assert np.allclose(rods.length, S.ROD_LENGTH)
    assert np.allclose(rods.area, chain_area(*S.rod_spheres()))
    s, r = S.rod_spheres()
    assert np.allclose(box.minimum_image(rods.nose - rods.tail), (s[-1] - s[0]) * axes)


def test_rod_without_taper_is_rejected():
    box = Box((0.0, 0.0, 0.0), (30.0, 30.0, 1.12), (True, True, False))
    fr = S.make_frame(box, [], 0.5, [(10, 10)], [(1, 0)], rod=(np.array([-1.0, 0.0, 1.0]), np.full(3, 0.5)))
    with pytest.raises(ValueError, match="polarity"):
        fr.rods()


def test_axis_from_shuffled_spheres_with_equal_tail_radii():
    box = Box((0.0, 0.0, 0.0), (30.0, 30.0, 1.12), (True, True, False))
    s = np.array([-2.0, -1.4, -0.7, 0.0, 0.7, 1.4, 2.0])
    r = np.array([0.55, 0.55, 0.5, 0.45, 0.42, 0.38, 0.35])  # two equal spheres at the tail
    p = np.array([np.cos(2.0), np.sin(2.0)])
    fr = S.make_frame(box, [], 0.5, [(29.5, 0.2)], [p], rod=(s, r))
    perm = np.random.default_rng(0).permutation(len(s))
    fr.radius, fr.pos = fr.radius[perm], fr.pos[perm]
    rods = fr.rods()
    assert np.allclose(rods.axis[0], p, atol=1e-12)
    assert np.allclose(box.minimum_image(rods.tail[0] - (np.array([29.5, 0.2]) - 2.0 * p)), 0, atol=1e-9)


def power_cell_shares(c, r):
    """Reference split of a disc chain: disc k's part inside its power-diagram cell, the
    slab between radical lines, integrated numerically (compute areafrac/chunk's rule)."""
    out = []
    for k in range(len(c)):
        lo, hi = -np.inf, np.inf
        for j in range(len(c)):
            if j != k:
                radical = 0.5 * (c[k] + c[j]) + 0.5 * (r[j] ** 2 - r[k] ** 2) / (c[k] - c[j])
                lo, hi = (max(lo, radical), hi) if c[k] > c[j] else (lo, min(hi, radical))
        a, b = max(lo, c[k] - r[k]), min(hi, c[k] + r[k])
        out.append(quad(lambda x: 2 * np.sqrt(max(r[k] ** 2 - (x - c[k]) ** 2, 0)), a, b)[0] if b > a else 0.0)
    return np.array(out)


def test_chain_area_shares_are_the_power_diagram_cells():
    s, r = S.rod_spheres(n_spheres=9)
    shares = chain_area_shares(s, r)
    assert shares.sum() == pytest.approx(chain_area(s, r), rel=1e-12)
    np.testing.assert_allclose(shares, power_cell_shares(s, r), rtol=1e-9)
    rng = np.random.default_rng(5)
    c, rr = np.sort(rng.uniform(0, 3, 6)), rng.uniform(0.3, 0.8, 6)
    np.testing.assert_allclose(chain_area_shares(c, rr), power_cell_shares(c, rr), rtol=1e-8, atol=1e-12)


def _with(frame, **changes):
    fields = {k: getattr(frame, k) for k in ("step", "time", "box", "ids", "mol", "types", "radius", "pos", "vel", "body")}
    fields.update(changes)
    return Frame(**fields)


def test_rods_are_told_apart_by_body_not_by_stale_molecule_ids():
    box = Box((0.0, 0.0, 0.0), (40.0, 12.0, 1.12), (True, False, False))
    fr = S.make_frame(box, [(5, 3), (30, 9), (31, 9)], 0.5, [(10, 6), (20, 6)], [(1, 0), (0, 1)])
    body = np.where(fr.mol > 0, 100 + fr.mol, 0)   # body IDs differ from molecule IDs
    mol = fr.mol.copy()
    mol[1:3] = 2                                  # two beads far away carry rod 2's molecule ID
    stale = _with(fr, mol=mol)
    with pytest.raises(ValueError, match=r"rod 2 \(mol 2: atoms 2, 3, 11, .*\) is not one chain"):
        stale.rods()
    rods = _with(stale, body=body).rods()
    assert rods.ids.tolist() == [101, 102]
    np.testing.assert_allclose(rods.axis, [(1, 0), (0, 1)], atol=1e-12)
    assert len(_with(stale, body=body).beads()[1]) == 3


@pytest.mark.parametrize("defect, message", [("off_line", "not on one line"), ("gap", "a gap of"),
                                             ("bump", "radii do not shrink")])
def test_a_rod_that_is_not_one_chain_is_an_error(defect, message):
    box = Box((0.0, 0.0, 0.0), (30.0, 30.0, 1.12), (True, True, False))
    fr = S.make_frame(box, [], 0.5, [(10, 10), (20, 20)], [(1, 0), (0, 1)])
    pos, radius = fr.pos.copy(), fr.radius.copy()
    k = 3 + len(S.rod_spheres()[0])       # the fourth sphere of the second rod
    if defect == "off_line":
        pos[k, 0] += 0.1
    elif defect == "gap":
        pos[k + 1:, 1] += 1.5                 # the nose half slides away along the axis
    else:
        radius[k] = 0.6
    with pytest.raises(ValueError, match=f"rod 2 .*{message}"):
        _with(fr, pos=pos, radius=radius).rods()


def test_sphere_areas_are_the_rod_split_at_the_sphere_centres():
    box = Box((0.0, 0.0, 0.0), (30.0, 30.0, 1.12), (True, True, False))
    fr = S.make_frame(box, [], 0.5, [(0.5, 10)], [(1, 0)])   # across the periodic boundary
    xy, area = fr.rods().sphere_areas()
    s, r = S.rod_spheres()
    np.testing.assert_allclose(area, chain_area_shares(s, r), rtol=1e-12)
    np.testing.assert_allclose(xy, box.wrap(np.column_stack([0.5 + s, np.full(len(s), 10.0)])), atol=1e-12)
