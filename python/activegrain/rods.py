"""Rods regrouped from their atoms, and the projected shape of a chain of spheres.

A rod is a chain of overlapping spheres along its axis with radii decreasing from the
tail (largest) to the nose (smallest). Seen from above it is the union of its spheres'
discs: a tapered shape with rounded ends. Because the disc centres lie on one line, the
union's half-width at axial position ``s`` is the upper envelope
``h(s) = max_i sqrt(r_i^2 - (s - s_i)^2)`` and its area ``2 * integral h(s) ds`` is
exact piece by piece (:func:`chain_area`).
"""
from dataclasses import dataclass

import numpy as np


def chain_halfwidth(s, centres, radii):
    """Half-width h(s) of the union of discs centred at ``centres`` on the axis."""
    s = np.asarray(s, float)[..., None]
    c, r = np.asarray(centres, float), np.asarray(radii, float)
    return np.sqrt(np.clip(r * r - (s - c) ** 2, 0, None)).max(axis=-1)


def _chain_breakpoints(c, r):
    pts = list(c - r) + list(c + r)
    for i in range(len(c)):
        for j in range(i + 1, len(c)):
            if c[i] != c[j]:  # where the two circles' upper arcs cross
                pts.append((r[i] ** 2 - r[j] ** 2 + c[j] ** 2 - c[i] ** 2) / (2 * (c[j] - c[i])))
    lo, hi = (c - r).min(), (c + r).max()
    return np.unique(np.clip(pts, lo, hi))


def chain_area_shares(centres, radii):
    """The union of discs whose centres lie on a line, split into one share per disc.

    Between consecutive breakpoints (disc ends and pairwise arc crossings) one disc forms
    the upper envelope; its slice area is integrated analytically and given to that disc
    (the first of equal ones). Disc k's share is thus the union's part where disc k is the
    widest: its cell of the discs' power diagram, the split compute areafrac/chunk makes.
    """
    c, r = np.asarray(centres, float), np.asarray(radii, float)
    shares = np.zeros(len(c))
    b = _chain_breakpoints(c, r)
    for s0, s1 in zip(b[:-1], b[1:]):
        mid = 0.5 * (s0 + s1)
        w = r * r - (mid - c) ** 2
        i = int(np.argmax(w))
        if w[i] <= 0:
            continue  # a gap between discs that do not overlap

        def prim(u, ri=r[i]):  # integral of 2*sqrt(r^2 - u^2)
            t = np.clip(u / ri, -1, 1)
            return ri * ri * (np.arcsin(t) + t * np.sqrt(1 - t * t))
        shares[i] += prim(s1 - c[i]) - prim(s0 - c[i])
    return shares


def chain_area(centres, radii):
    """Exact area of the union of discs whose centres lie on a line
    (the sum of :func:`chain_area_shares`)."""
    return float(chain_area_shares(centres, radii).sum())


def chain_samples(centres, radii, spacing):
    """Area quadrature points of a chain's projected shape in its own frame.

    Returns ``(s, w, weight)``: axial and transverse coordinates and the area carried
    by each point. The shape is cut into slices of width ~``spacing`` along the axis;
    each slice gets points spread evenly over its exact width ``2 h(s)``. Weights are
    normalised to the exact :func:`chain_area`, so an area is never counted twice.
    """
    c, r = np.asarray(centres, float), np.asarray(radii, float)
    lo, hi = (c - r).min(), (c + r).max()
    n_s = max(2, int(np.ceil((hi - lo) / spacing)))
    ds = (hi - lo) / n_s
    s_mid = lo + ds * (np.arange(n_s) + 0.5)
    h = chain_halfwidth(s_mid, c, r)
    n_w = np.maximum(1, np.ceil(2 * h / spacing).astype(int))
    s = np.repeat(s_mid, n_w)
    slot = np.arange(n_w.sum()) - np.repeat(np.cumsum(n_w) - n_w, n_w)
    hw, nw = np.repeat(h, n_w), np.repeat(n_w, n_w)
    w = hw * (-1 + (2 * slot + 1) / nw)
    weight = 2 * hw * ds / nw
    weight *= chain_area(c, r) / weight.sum()
    return s, w, weight


def chain_outline(centres, radii, n=24):
    """Closed outline (s, w) of a chain's projected shape, tail end first."""
    c, r = np.asarray(centres, float), np.asarray(radii, float)
    lo, hi = (c - r).min(), (c + r).max()
    # cosine spacing puts points where the rounded ends curve fastest
    s = lo + (hi - lo) * 0.5 * (1 - np.cos(np.linspace(0, np.pi, n)))
    h = chain_halfwidth(s, c, r)
    return np.concatenate([s, s[::-1]]), np.concatenate([h, -h[::-1]])


def _chain_error(centres, radii):
    """Why spheres (3-D ``centres``, unwrapped, and ``radii``) are not one rod, or None.

    A rod is one straight chain: all centres on one line (within 1% of the smallest
    radius), each sphere overlapping the next one along it, radii not growing from the
    tail (the widest end) to the nose.
    """
    if len(radii) < 2 or np.ptp(radii) <= 1e-9 * radii.max():
        return "needs at least two spheres with a larger tail than nose radius to tell its polarity"
    d = centres - centres.mean(axis=0)
    u = np.linalg.svd(d, full_matrices=False)[2][0]
    s = d @ u
    off_line = np.linalg.norm(d - s[:, None] * u, axis=1).max()
    if off_line > 0.01 * radii.min():
        return f"is not one chain of spheres: its sphere centres are not on one line ({off_line:.3g} off it)"
    k = np.argsort(s, kind="stable")
    gaps = np.diff(s[k]) - (radii[k][1:] + radii[k][:-1])
    if np.any(gaps >= 0):
        return f"is not one chain of overlapping spheres: a gap of {gaps.max():.3g} between two"
    taper = np.diff(radii[k]) * np.sign(np.sum(s * (radii - radii.mean())))
    if np.any(taper < -1e-9 * radii.max()):
        return "is not one tapered chain: its radii do not shrink monotonically from one end to the other"
    return None


@dataclass
class RodSet:
    """Rods of one frame, in the xy plane.

    ``ids``: rod IDs (the dump's ``body``, else ``mol``); ``centre``: middle of the
    tail-nose sphere segment, wrapped into the box; ``axis``: the polar axis p, the unit
    in-plane direction of the rod's axis from tail (widest sphere) to nose (narrowest);
    ``tail``/``nose``: centres of the end spheres (unwrapped with the rod); ``velocity``:
    mean velocity of the rod's atoms (that of their centroid, for a rigid body) or None;
    ``sphere_s``/``sphere_r``: per rod, the spheres' axial positions relative to
    ``centre`` in the plane and their radii; ``sphere_xy``: per rod, the spheres'
    centres wrapped into the box.
    """
    ids: np.ndarray
    centre: np.ndarray
    axis: np.ndarray
    tail: np.ndarray
    nose: np.ndarray
    velocity: np.ndarray
    sphere_s: list
    sphere_r: list
    sphere_xy: list

    def __len__(self):
        return len(self.ids)

    @property
    def length(self):
        """Tip-to-tip length of each rod's projected shape."""
        return np.array([(s + r).max() - (s - r).min() for s, r in zip(self.sphere_s, self.sphere_r)])

    @property
    def area(self):
        """Exact projected area of each rod."""
        return np.array([chain_area(s, r) for s, r in zip(self.sphere_s, self.sphere_r)])

    def sphere_areas(self):
        """Per sphere of every rod, its centre (M, 2) and its share (M,) of its rod's
        projected area (:func:`chain_area_shares`): how compute areafrac/chunk bins rods."""
        xy = [np.zeros((0, 2))] + list(self.sphere_xy)
        shares = [np.zeros(0)] + [chain_area_shares(s, r) for s, r in zip(self.sphere_s, self.sphere_r)]
        return np.concatenate(xy), np.concatenate(shares)

    @classmethod
    def from_frame(cls, frame):
        """The rods of a :class:`activegrain.io.Frame`, grouped by ``frame.rod_of_atom``.

        Raises ValueError naming the rod and its atoms if a rod's atoms are not one chain
        of overlapping spheres (e.g. beads carrying a rod's molecule ID).
        """
        box = frame.box
        rod_id = frame.rod_of_atom
        m = rod_id > 0
        rid, pos, rad, atom = rod_id[m], frame.pos[m], frame.radius[m], frame.ids[m]
        vel = None if frame.vel is None else frame.vel[m, :2]
        order = np.argsort(rid, kind="stable")
        rid, pos, rad, atom = rid[order], pos[order], rad[order], atom[order]
        vel = None if vel is None else vel[order]
        ids, starts = np.unique(rid, return_index=True)
        ends = np.append(starts[1:], len(rid))
        by = "body" if frame.body is not None else "mol"
        centre, axis, tail, nose, velocity, ss, rr, xys = [], [], [], [], [], [], [], []
        for a, b in zip(starts, ends):
            r = rad[a:b]
            x3 = pos[a] + box.minimum_image(pos[a:b] - pos[a])  # rods may straddle a periodic boundary
            why = _chain_error(x3, r)
            if why is not None:
                shown = ", ".join(map(str, atom[a:b][:12])) + (", ..." if b - a > 12 else "")
                raise ValueError(f"rod {rid[a]} ({by} {rid[a]}: atoms {shown}) {why}")
            # p: the in-plane direction of the line through the centres, towards the
            # shrinking radii (robust to sphere order and to equal radii at one end)
            x = x3[:, :2]
            d = x - x.mean(axis=0)
            p = np.linalg.svd(d, full_matrices=False)[2][0]
            if np.sum((d @ p) * (r - r.mean())) > 0:
                p = -p
            s = d @ p
            t, n = x[np.argmin(s)], x[np.argmax(s)]
            mid = 0.5 * (t + n)
            centre.append(mid)
            axis.append(p)
            tail.append(t)
            nose.append(n)
            ss.append((x - mid) @ p)
            rr.append(r.copy())
            xys.append(box.wrap(x))
            if vel is not None:
                velocity.append(vel[a:b].mean(axis=0))
        centre = np.array(centre).reshape(-1, 2)
        wrapped = box.wrap(centre)
        shift = wrapped - centre
        return cls(ids, wrapped, np.array(axis).reshape(-1, 2), np.array(tail).reshape(-1, 2) + shift,
                   np.array(nose).reshape(-1, 2) + shift,
                   np.array(velocity).reshape(-1, 2) if vel is not None else None, ss, rr, xys)

    def samples(self, spacing):
        """Area quadrature points (xy (M, 2), weight (M,)) of all rods' projected shapes."""
        pts, wts = [np.zeros((0, 2))], [np.zeros(0)]
        for c, p, s, r in zip(self.centre, self.axis, self.sphere_s, self.sphere_r):
            a, w, weight = chain_samples(s, r, spacing)
            normal = np.array([-p[1], p[0]])
            pts.append(c + a[:, None] * p + w[:, None] * normal)
            wts.append(weight)
        return np.concatenate(pts), np.concatenate(wts)

    def outlines(self, n=24):
        """World-frame outline polygons (list of (k, 2) arrays), not wrapped."""
        out = []
        for c, p, s, r in zip(self.centre, self.axis, self.sphere_s, self.sphere_r):
            a, w = chain_outline(s, r, n)
            normal = np.array([-p[1], p[0]])
            out.append(c + a[:, None] * p + w[:, None] * normal)
        return out


def disc_samples(centres, radii, spacing):
    """Area quadrature points of discs (same scheme as :func:`chain_samples`)."""
    centres, radii = np.asarray(centres, float).reshape(-1, 2), np.asarray(radii, float)
    if len(radii) == 0:
        return np.zeros((0, 2)), np.zeros(0)
    n = max(2, int(np.ceil(2 * radii.max() / spacing)))
    s, w, weight = chain_samples([0.0], [1.0], 2.0 / n)  # unit disc template
    pts = centres[:, None, :] + radii[:, None, None] * np.stack([s, w], axis=-1)[None]
    return pts.reshape(-1, 2), (radii[:, None] ** 2 * weight[None]).ravel()


def frustum_point_masses(axial, radii, density):
    """The point masses rod_template gives a rod's spheres, from their axial positions and radii.

    rod_template (docs/rod_template.rst) makes each sphere's radius the local radius of a solid
    frustum whose end spheres touch its end faces, and gives each sphere the mass of the frustum
    slab nearest to it (between the midpoints to its neighbours, the end ones out to the faces),
    tilted linearly along the axis so that the masses sum to the solid's mass and their centre
    is the solid's centre of mass. The frustum is rebuilt here from the spheres (radius linear
    in the axial position, faces one end radius beyond the end centres), so that the masses are
    those of the deck for a rod read back from a dump. ``axial`` in any order and direction;
    masses in ``density`` times the cube of the length unit of ``axial`` and ``radii``.
    """
    s, r = np.asarray(axial, float), np.asarray(radii, float)
    order = np.argsort(s, kind="stable")
    slope = np.polyfit(s, r, 1)[0] if np.ptp(s) > 0 else 0.0
    if slope > 0:                      # measure x from the tail (the wide end)
        order = order[::-1]
    x = np.abs(s[order] - s[order[0]]) + r[order[0]]
    rr = r[order]
    length = x[-1] + rr[-1]
    k = -abs(slope)
    a = rr[0] - k * x[0]               # radius at the tail face
    b = a + k * length                 # at the nose face
    volume = np.pi * length * (a * a + a * b + b * b) / 3.0
    mass = density * volume
    com = length * (a * a + 2 * a * b + 3 * b * b) / (4 * (a * a + a * b + b * b))
    edges = np.concatenate([[0.0], 0.5 * (x[1:] + x[:-1]), [length]])
    r0, r1 = a + k * edges[:-1], a + k * edges[1:]
    m = density * np.pi * np.diff(edges) * (r0 * r0 + r0 * r1 + r1 * r1) / 3.0
    x_w = np.sum(m * x) / mass
    spread = np.sum(m * (x - x_w) ** 2)
    m = m * (1.0 + mass * (com - x_w) / spread * (x - x_w))
    out = np.empty_like(m)
    out[order] = m
    return out
