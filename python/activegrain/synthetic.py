"""Synthetic rod-and-bead configurations with known properties.

Used by the tests (known answers) and to draw the documentation figures without a
simulation. Lengths in bead diameters unless stated; rods are the paper's: 4.5 long,
tapered from 1.1 (tail) to 0.7 (nose), built from ``n_spheres`` overlapping spheres.
"""
from dataclasses import replace

import numpy as np
from scipy.spatial import cKDTree

from .geometry import Annulus, Box
from .io import Frame

ROD_LENGTH, ROD_TAIL, ROD_NOSE = 4.5, 1.1, 0.7


def rod_spheres(length=ROD_LENGTH, tail=ROD_TAIL, nose=ROD_NOSE, n_spheres=7):
    """Axial positions (about the tail-nose midpoint) and radii of a rod's spheres,
    tail first, so that the projected shape is ``length`` tip to tip."""
    rt, rn = tail / 2, nose / 2
    s = np.linspace(-length / 2 + rt, length / 2 - rn, n_spheres)
    s -= 0.5 * (s[0] + s[-1])
    return s, np.linspace(rt, rn, n_spheres)


def make_frame(box, bead_xy=(), bead_r=0.5, rod_centres=(), rod_axes=(), rod=None,
               bead_vel=None, rod_vel=None, step=0, time=None, z=0.5):
    """Assemble a :class:`Frame`: beads (mol 0, type 1) then rods (mol 1.., type 2), lengths in
    bead diameters of 1 mm (``length_unit`` 1e-3: ``frame.scaled(1e-3)`` is in metres).

    ``rod``: (s, r) from :func:`rod_spheres`; ``bead_vel``/``rod_vel``: (n, 2) velocities
    (rod velocity given to all its atoms), or None for a dump without velocities.
    """
    s, r = rod if rod is not None else rod_spheres()
    bead_xy = np.asarray(bead_xy, float).reshape(-1, 2)
    rod_centres = np.asarray(rod_centres, float).reshape(-1, 2)
    rod_axes = np.asarray(rod_axes, float).reshape(-1, 2)
    rod_axes = rod_axes / np.linalg.norm(rod_axes, axis=1)[:, None] if len(rod_axes) else rod_axes
    nb, nr, k = len(bead_xy), len(rod_centres), len(s)
    rod_xy = (rod_centres[:, None, :] + s[None, :, None] * rod_axes[:, None, :]).reshape(-1, 2)
    xy = box.wrap(np.concatenate([bead_xy, rod_xy]))
    pos = np.column_stack([xy, np.full(len(xy), z)])
    mol = np.concatenate([np.zeros(nb, int), np.repeat(np.arange(1, nr + 1), k)])
    radius = np.concatenate([np.broadcast_to(bead_r, (nb,)).astype(float), np.tile(r, nr)])
    vel = None
    if bead_vel is not None or rod_vel is not None:
        vb = np.zeros((nb, 2)) if bead_vel is None else np.asarray(bead_vel, float).reshape(nb, 2)
        vr = np.zeros((nr, 2)) if rod_vel is None else np.asarray(rod_vel, float).reshape(nr, 2)
        v2 = np.concatenate([vb, np.repeat(vr, k, axis=0)])
        vel = np.column_stack([v2, np.zeros(len(v2))])
    n = nb + nr * k
    return Frame(step, float(step if time is None else time), box, np.arange(1, n + 1), mol,
                 np.where(mol > 0, 2, 1), radius, pos, vel, length_unit=1e-3)   # d = 1 mm


def channel_box(length=249.0, width=31.0, height=1.12):
    return Box((0.0, 0.0, 0.0), (length, width, height), (True, False, False))


def square_box(length=249.0, height=1.12):
    return Box((0.0, 0.0, 0.0), (length, length, height), (True, True, False))


def lattice_beads(x0, x1, y0, y1, spacing):
    """Bead centres on a square lattice filling [x0, x1] x [y0, y1], one per cell of
    side ``spacing`` (cells fit exactly when the sides are multiples of it)."""
    nx, ny = int(round((x1 - x0) / spacing)), int(round((y1 - y0) / spacing))
    X, Y = np.meshgrid(x0 + spacing * (np.arange(nx) + 0.5), y0 + spacing * (np.arange(ny) + 0.5),
                       indexing="ij")
    return np.column_stack([X.ravel(), Y.ravel()])


def spacing_for(phi, r=0.5):
    """Square-lattice spacing giving bead area fraction ``phi``."""
    return float(np.sqrt(np.pi * r * r / phi))


def random_rods(n, region, rng, axes=None, min_distance=ROD_LENGTH + 0.2, tries=200000):
    """``n`` rod centres placed at random in ``region`` (x0, x1, y0, y1) at least
    ``min_distance`` apart (no rod overlap), with the given or random axes."""
    x0, x1, y0, y1 = region
    pts = []
    for _ in range(tries):
        if len(pts) == n:
            break
        c = rng.uniform((x0, y0), (x1, y1))
        if all(np.hypot(*(c - p)) >= min_distance for p in pts):
            pts.append(c)
    if len(pts) < n:
        raise ValueError(f"random_rods: could only place {len(pts)} of {n} rods")
    if axes is None:
        a = rng.uniform(0, 2 * np.pi, n)
        axes = np.column_stack([np.cos(a), np.sin(a)])
    return np.array(pts), np.asarray(axes, float).reshape(n, 2)


def remove_overlaps(bead_xy, box, rod_centres, rod_axes, bead_r=0.5, rod=None):
    """Drop the beads whose disc overlaps a rod sphere's disc (minimum image)."""
    s, r = rod if rod is not None else rod_spheres()
    keep = np.ones(len(bead_xy), bool)
    for c, p in zip(rod_centres, rod_axes):
        for si, ri in zip(s, r):
            d = box.minimum_image(bead_xy - (c + si * p))
            keep &= np.hypot(d[:, 0], d[:, 1]) >= bead_r + ri
    return bead_xy[keep]


def _row_of_rods(x, width, direction):
    ys = np.arange(1.0, width - 0.5, 1.15)  # side by side, tails (1.1 wide) just apart
    return np.column_stack([np.full(len(ys), x), ys]), np.tile([direction, 0.0], (len(ys), 1))


def phase_configuration(phase, seed=0, length=124.0, width=31.0, packing="lattice"):
    """A channel configuration built to be in ``phase``.

    isotropic: beads uniform (phi_b = 0.6), rods random positions and axes;
    flock: the same with all rods pointing +x (within +-15 degrees);
    segregated: rods crowded at random orientations into a bead-free quarter;
    condensed: one width-spanning row of rods pointing +x, beads close-packed ahead of
    it (phi_b = pi/4) and dilute (pi/16) elsewhere;
    trapped: two such rows pointing at each other with the close-packed beads between
    them (a condensed phase held by two active layers).

    ``packing='lattice'``: beads on square lattices with exactly these area fractions;
    ``'relaxed'``: disordered packings with the same area-fraction profile
    (:func:`relaxed_beads`).
    """
    rng = np.random.default_rng(seed)
    box = channel_box(length, width)
    uniform, dense, dilute = 0.6, np.pi / 4, np.pi / 16
    if phase in ("isotropic", "flock"):
        axes = None
        if phase == "flock":
            ang = rng.uniform(-np.pi / 12, np.pi / 12, 20)
            axes = np.column_stack([np.cos(ang), np.sin(ang)])
        centres, axes = random_rods(20, (0, length, 3, width - 3), rng, axes)
        regions = [(0, length, uniform)]
    elif phase == "segregated":
        centres, axes = random_rods(20, (2, length / 4, 3, width - 3), rng, None)
        regions = [(length / 4 + 3, length, uniform)]
    elif phase == "condensed":
        x0 = 30.0
        centres, axes = _row_of_rods(x0, width, 1.0)
        regions = [(0, x0 - 3, dilute), (x0 + 3, x0 + 63, dense), (x0 + 63, length, dilute)]
    elif phase == "trapped":
        x0, x1 = 30.0, 70.0
        (c0, a0), (c1, a1) = _row_of_rods(x0, width, 1.0), _row_of_rods(x1, width, -1.0)
        centres, axes = np.concatenate([c0, c1]), np.concatenate([a0, a1])
        regions = [(0, x0 - 3, dilute), (x0 + 3, x1 - 3, dense), (x1 + 3, length, dilute)]
    else:
        raise ValueError(f"unknown phase '{phase}'")
    if packing == "lattice":
        beads = np.concatenate([lattice_beads(a, b, 0, width, spacing_for(phi)) for a, b, phi in regions])
        beads = remove_overlaps(beads, box, centres, axes)
    elif packing == "relaxed":
        s, r = rod_spheres()
        spheres = (centres[:, None, :] + s[None, :, None] * axes[:, None, :]).reshape(-1, 2)
        phi_of_x = lambda x: sum(phi for a, b, phi in regions if a <= x < b)
        beads = relaxed_beads(rng, box, phi_of_x, spheres, np.tile(r, len(centres)))
    else:
        raise ValueError(f"unknown packing '{packing}' (lattice or relaxed)")
    return make_frame(box, beads, 0.5, centres, axes)


def hexagonal_beads(x0, x1, y0, y1, spacing=1.0):
    """Bead centres on a hexagonal lattice of ``spacing`` (1: touching beads of diameter 1,
    area fraction pi / (2 sqrt 3) = 0.907) filling [x0, x1] x [y0, y1], rows along x."""
    dy = spacing * np.sqrt(3) / 2
    rows = np.arange(y0, y1 + 1e-9, dy)
    return np.concatenate([np.column_stack([np.arange(x0 + (k % 2) * spacing / 2, x1 - spacing / 2 + 1e-9,
                                                      spacing), np.full_like(np.arange(x0 + (k % 2) * spacing / 2,
                                                      x1 - spacing / 2 + 1e-9, spacing), y)])
                           for k, y in enumerate(rows)])


def dense_configuration(seed=0, length=62.0, width=31.0, n_rods=10, spacing=1.001):
    """A channel packed like the paper's jammed corner: beads on a hexagonal lattice of
    ``spacing`` (total area fraction 0.853 at 1.001) around ``n_rods`` rods at random
    places and orientations (the beads they overlap removed)."""
    rng = np.random.default_rng(seed)
    box = channel_box(length, width)
    centres, axes = random_rods(n_rods, (3, length - 3, 3, width - 3), rng)
    beads = hexagonal_beads(0, length, 0.5, width - 0.5, spacing)
    return make_frame(box, remove_overlaps(beads, box, centres, axes), 0.5, centres, axes)


def displaced(frame, rms, seed=0, dt=1.0):
    """A copy of ``frame`` ``dt`` later whose beads have moved by Gaussian steps of rms length
    ``rms`` (rods unchanged): the next frame of a run with that bead mobility."""
    rng = np.random.default_rng(seed)
    pos = frame.pos.copy()
    beads = frame.is_bead
    pos[beads, :2] = frame.box.wrap(pos[beads, :2] + rng.normal(0, rms / np.sqrt(2), (beads.sum(), 2)))
    return replace(frame, pos=pos, step=frame.step + 1, time=frame.time + dt)


def trajectory(frame, times, rod_speed=0.0, bead_speed=0.0, rattle=0.0, period=0.3, seed=0, timestep=1e-4):
    """The frames at ``times`` (seconds) of a run that passes through ``frame`` at time 0: its
    rods move along their own axes (kept) at ``rod_speed``, each bead at ``bead_speed`` in a
    direction of its own (lengths per second), and every rod and bead rattles about that by
    ``rattle`` (round a circle of that radius in ``period`` s, each from a phase of its own).
    Positions are functions of time, so that frames at any ``times`` are samples of one run
    (their steps: time / ``timestep``)."""
    rng = np.random.default_rng(seed)
    rods = frame.rods()
    beads = frame.is_bead
    of_rod = np.searchsorted(rods.ids, frame.rod_of_atom[~beads])     # each rod atom's rod
    angle = rng.uniform(0, 2 * np.pi, beads.sum())
    heading = np.column_stack([np.cos(angle), np.sin(angle)])
    bead_phase, rod_phase = rng.uniform(0, 2 * np.pi, beads.sum()), rng.uniform(0, 2 * np.pi, len(rods))
    circle = lambda t, ph: rattle * np.column_stack([np.cos(2 * np.pi * t / period + ph) - np.cos(ph),
                                                     np.sin(2 * np.pi * t / period + ph) - np.sin(ph)])
    out = []
    for t in np.atleast_1d(np.asarray(times, float)):
        d = np.zeros((len(frame.ids), 2))
        d[beads] = bead_speed * t * heading + circle(t, bead_phase)
        d[~beads] = (rod_speed * t * rods.axis + circle(t, rod_phase))[of_rod]
        pos = frame.pos.copy()
        pos[:, :2] = frame.box.wrap(pos[:, :2] + d)
        out.append(replace(frame, pos=pos, step=int(round(t / timestep)), time=float(t)))
    return out


def relaxed_beads(rng, box, phi_of_x, obstacles=(), obstacle_r=(), r=0.5, sweeps=2000, tol=1e-3):
    """Beads drawn with local area fraction ``phi_of_x`` (inverse-CDF sampling along x),
    then pushed apart (at most ``sweeps`` sweeps) until no two overlap by more than
    ``tol`` times the diameter and none overlaps a fixed obstacle disc: a disordered,
    liquid-like packing with the requested profile (up to phi ~ 0.8)."""
    lo, L = np.asarray(box.lo[:2]), box.lengths[:2]
    xs = np.linspace(lo[0], lo[0] + L[0], 2001)
    dens = np.array([phi_of_x(x) for x in xs])
    n = int(round(np.trapz(dens, xs) * L[1] / (np.pi * r * r)))
    cdf = np.concatenate([[0], np.cumsum(0.5 * (dens[1:] + dens[:-1]) * np.diff(xs))])
    x = np.interp(rng.uniform(0, cdf[-1], n), cdf, xs)
    xy = np.column_stack([x, rng.uniform(lo[1] + r, lo[1] + L[1] - r, n)])
    obstacles = np.asarray(obstacles, float).reshape(-1, 2)
    obstacle_r = np.asarray(obstacle_r, float)
    for _ in range(sweeps):
        pts = np.concatenate([xy, obstacles])
        rad = np.concatenate([np.full(n, r), obstacle_r])
        # periodic axes wrap in the tree; a wall axis gets a box too large to wrap
        tree = cKDTree(box.wrap(pts) - lo, boxsize=[L[k] if box.periodic[k] else 11 * L[k] for k in range(2)])
        pairs = tree.query_pairs(2 * max(r, rad.max()), output_type="ndarray")
        d = box.minimum_image(pts[pairs[:, 1]] - pts[pairs[:, 0]])
        dist = np.linalg.norm(d, axis=1)
        overlap = rad[pairs[:, 0]] + rad[pairs[:, 1]] - dist
        i, j = pairs[:, 0], pairs[:, 1]
        hit = (overlap > tol * 2 * r) & ((i < n) | (j < n))  # obstacles may overlap each other
        if not hit.any():
            break
        i, j, d, dist, overlap = i[hit], j[hit], d[hit], dist[hit], overlap[hit]
        # a bead facing a fixed obstacle takes the whole push, two beads half each
        share = np.where((i < n) & (j < n), 0.5, 1.0)
        push = (share * (overlap + tol * 2 * r))[:, None] * d / np.maximum(dist, 1e-9)[:, None]
        move = np.zeros_like(pts)
        np.add.at(move, i, -push)
        np.add.at(move, j, push)
        xy += move[:n]
        for k in range(2):
            if not box.periodic[k]:
                xy[:, k] = np.clip(xy[:, k], lo[k] + r, lo[k] + L[k] - r)
        xy = box.wrap(xy)
    return xy


def persistent_walk(n_steps, dt, speed, tau, rng, start=(0.0, 0.0)):
    """Trajectory of a rod moving nose-first at ``speed`` whose axis angle diffuses with
    rotational diffusion 1/``tau`` (orientation correlation exp(-t/tau) in 2D).
    Returns (t, centres (n, 2), axes (n, 2))."""
    angle = np.cumsum(np.concatenate([[0.0], rng.normal(0, np.sqrt(2 * dt / tau), n_steps - 1)]))
    axes = np.column_stack([np.cos(angle), np.sin(angle)])
    steps = speed * dt * 0.5 * (axes[1:] + axes[:-1])
    centres = np.asarray(start) + np.concatenate([[[0.0, 0.0]], np.cumsum(steps, axis=0)])
    return dt * np.arange(n_steps), centres, axes


def trapped_condensate(turn=0.0):
    """A condensate trapped between two opposed rows of rods (the paper's Fig. 3): in an
    annulus of radii 15 and 28, beads dense for 0.3 < theta < 2.0 (sparse elsewhere), a radial
    row of rods at theta 0.15 heading counter-clockwise and one at 2.15 heading clockwise.
    Returns the annulus and two frames 1 apart in time, between which the dense beads (only)
    turn counter-clockwise by ``turn`` radians."""
    box = Box((-30.0, -30.0, 0.0), (30.0, 30.0, 1.12), (False, False, False))
    ann = Annulus(box, (0.0, 0.0), 15.0, 28.0)
    radii = np.arange(16.0, 27.5, 1.15)
    rows = [(0.15, 1.0), (2.15, -1.0)]
    centres = np.concatenate([np.column_stack([radii * np.cos(t), radii * np.sin(t)]) for t, _ in rows])
    axes = np.concatenate([np.tile([-s * np.sin(t), s * np.cos(t)], (len(radii), 1)) for t, s in rows])
    pts = lattice_beads(-30, 30, -30, 30, 1.0)
    r, th = ann.polar(pts)
    dense = (th > 0.3) & (th < 2.0)
    keep = (r > 15.5) & (r < 27.5) & (dense | ((th > 2.3) & (th < 6.1) & (np.arange(len(pts)) % 4 == 0)))
    beads = remove_overlaps(pts[keep], box, centres, axes)
    before = make_frame(box, beads, 0.5, centres, axes, time=0.0)
    _, th = ann.polar(beads)
    c, s = np.cos(turn), np.sin(turn)
    moved = np.where(((th > 0.3) & (th < 2.0))[:, None], beads @ np.array([[c, s], [-s, c]]), beads)
    after = make_frame(box, moved, 0.5, centres, axes, time=1.0)
    return ann, before, after
