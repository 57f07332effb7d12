"""Observables of one frame: area fractions, polarization, rods vs the bead gradient,
the density on both sides of a rod layer, and a phase classifier.

Area fractions count, per bin, projected area over the bin's area inside the cell, in one
of two ways (``count``):

* ``"covered"`` (default): the area that lies in the bin. Every particle's projected shape
  (a bead's disc, a rod's tapered union of discs, counted once) is cut into area quadrature
  points whose weights sum to the exact shape area. The quadrature spacing (``spacing``,
  default a quarter of the smallest particle radius) sets how sharply a particle edge is
  resolved, never the total area.
* ``"centre"``: compute areafrac/chunk's per-atom count. A bead's whole disc goes to the
  bin of its centre; a rod's exact area is split among its spheres (each sphere's part of
  the union where it is the widest, :func:`activegrain.rods.chain_area_shares`) and each
  part goes to the bin of that sphere's centre.

The two agree on any bin much larger than a particle, up to the particles cut by its edges.
"""
import warnings
from dataclasses import dataclass, field, replace

import numpy as np
from scipy import ndimage
from scipy.optimize import OptimizeWarning, curve_fit

from .geometry import Annulus
from .rods import disc_samples

SPECIES = ("beads", "rods", "all")


@dataclass
class Profile:
    coord: str
    species: str
    edges: np.ndarray
    fraction: np.ndarray

    @property
    def centres(self):
        return 0.5 * (self.edges[1:] + self.edges[:-1])


def default_spacing(frame):
    return 0.25 * float(frame.radius.min())


COUNTS = ("covered", "centre")


def area_samples(frame, species="beads", spacing=None, count="covered"):
    """Points carrying area ``(xy, weight)`` of the beads, the rods or both: area
    quadrature points (``count="covered"``) or the atoms' centres with their areas
    (``count="centre"``, see the module's docstring)."""
    if species not in SPECIES:
        raise ValueError(f"species must be one of {SPECIES}, got '{species}'")
    if count not in COUNTS:
        raise ValueError(f"count must be one of {COUNTS}, got '{count}'")
    spacing = spacing or default_spacing(frame)
    parts = []
    if species in ("beads", "all"):
        xy, r, _ = frame.beads()
        parts.append(disc_samples(xy, r, spacing) if count == "covered" else (xy, np.pi * r ** 2))
    if species in ("rods", "all"):
        rods = frame.rods()
        parts.append(rods.samples(spacing) if count == "covered" else rods.sphere_areas())
    xy = np.concatenate([p[0] for p in parts])
    return frame.box.wrap(xy), np.concatenate([p[1] for p in parts])


def _edges(geometry, coord, bins):
    if np.ndim(bins) == 0:
        lo, hi = geometry.coordinate_range(coord)
        return np.linspace(lo, hi, int(bins) + 1)
    return np.asarray(bins, float)


def _coordinate_in_range(geometry, xy, coord, edges):
    q = geometry.coordinate(xy, coord)
    if not geometry.is_periodic(coord):
        # area of a particle pressed a little into a wall stays in the edge bin
        q = np.clip(q, edges[0], edges[-1])
    return q


def area_fraction_profile(frame, geometry, coord="x", bins=50, species="beads", spacing=None,
                          count="covered"):
    """Area fraction in bins of ``coord`` ('x', 'y'; 'r', 'theta' for an annulus), counted
    as ``count`` says (module docstring)."""
    edges = _edges(geometry, coord, bins)
    xy, w = area_samples(frame, species, spacing, count)
    q = _coordinate_in_range(geometry, xy, coord, edges)
    covered, _ = np.histogram(q, edges, weights=w)
    return Profile(coord, species, edges, covered / geometry.bin_areas(coord, edges))


def area_fraction_map(frame, geometry, bins=(50, 10), species="beads", spacing=None, count="covered"):
    """2D map of the area fraction: ``(x_edges, y_edges, phi[nx, ny])``, counted as
    ``count`` says (module docstring).

    For an annulus the map covers its bounding square; each pixel's fraction is relative
    to the pixel's area inside the annulus (pixels wholly outside are NaN).
    """
    xe, ye = _edges(geometry, "x", bins[0]), _edges(geometry, "y", bins[1])
    xy, w = area_samples(frame, species, spacing, count)
    x = _coordinate_in_range(geometry, xy, "x", xe)
    y = _coordinate_in_range(geometry, xy, "y", ye)
    covered, _, _ = np.histogram2d(x, y, (xe, ye), weights=w)
    area = np.outer(np.diff(xe), np.diff(ye))
    if isinstance(geometry, Annulus):
        area = area * _inside_fraction(geometry, xe, ye)
    with np.errstate(invalid="ignore", divide="ignore"):
        phi = np.where(area > 1e-12 * area.max(), covered / area, np.nan)
    return xe, ye, phi


def _inside_fraction(geometry, xe, ye, sub=12):
    """Fraction of each pixel inside the cell, from a sub-grid of sub x sub points."""
    u = (np.arange(sub) + 0.5) / sub
    xs = (xe[:-1, None] + np.diff(xe)[:, None] * u).ravel()
    ys = (ye[:-1, None] + np.diff(ye)[:, None] * u).ravel()
    X, Y = np.meshgrid(xs, ys, indexing="ij")
    inside = geometry.contains(np.stack([X, Y], -1)).astype(float)
    return inside.reshape(len(xe) - 1, sub, len(ye) - 1, sub).mean(axis=(1, 3))


def global_area_fractions(frame, geometry):
    """(phi_b, phi_r): total projected areas over the cell area (exact shape areas)."""
    _, r, _ = frame.beads()
    rods = frame.rods()
    return (float(np.pi * np.sum(r ** 2) / geometry.area),
            float(rods.area.sum() / geometry.area) if len(rods) else 0.0)


# --------------------------------------------------------------------------- order

def polar_order(vectors):
    """(mean vector, magnitude) of the unit vectors of ``vectors`` (zero vectors skipped)."""
    v = np.asarray(vectors, float).reshape(-1, 2)
    n = np.linalg.norm(v, axis=1)
    v = v[n > 0] / n[n > 0, None]
    if len(v) == 0:
        return np.zeros(2), 0.0
    m = v.mean(axis=0)
    return m, float(np.linalg.norm(m))


def nematic_order(vectors):
    """|<exp(2 i theta)>| of the in-plane angles theta of ``vectors`` (zero vectors
    skipped): 1 for axes along one line whichever way they point, 0 for isotropic."""
    v = np.asarray(vectors, float).reshape(-1, 2)
    v = v[np.linalg.norm(v, axis=1) > 0]
    if len(v) == 0:
        return 0.0
    theta = np.arctan2(v[:, 1], v[:, 0])
    return float(np.hypot(np.cos(2 * theta).sum(), np.sin(2 * theta).sum()) / len(v))


def tangential_polarization(rods, annulus):
    """Mean of p . e_theta over the rods of an annulus (+1: all counter-clockwise)."""
    if len(rods) == 0:
        return 0.0
    return float(np.mean(np.sum(rods.axis * annulus.tangent(rods.centre), axis=1)))


def polarization(frame, geometry=None):
    """Polar order of rod axes and of rod and bead velocities.

    Returns a dict: ``P`` = |<p>|, ``Px``, ``Py``, ``S`` (nematic order
    |<exp(2 i theta)>|), ``n_rods``, ``P_tangential`` (annulus only),
    ``rod_velocity_order`` and ``bead_velocity_order`` (|<v/|v|>|, when the dump has
    velocities). p is each rod's in-plane polar axis, as compute polar/rod's.
    """
    rods = frame.rods()
    m, P = polar_order(rods.axis)
    out = {"n_rods": len(rods), "P": P, "Px": float(m[0]), "Py": float(m[1]),
           "S": nematic_order(rods.axis)}
    if isinstance(geometry, Annulus):
        out["P_tangential"] = tangential_polarization(rods, geometry)
    if rods.velocity is not None:
        out["rod_velocity_order"] = polar_order(rods.velocity)[1]
    _, _, vb = frame.beads()
    if vb is not None:
        out["bead_velocity_order"] = polar_order(vb)[1]
    return out


def smoothed_bead_field(frame, geometry, cell=None, smoothing=1.0):
    """Bead area-fraction map on pixels of size ~``cell`` (default 2 bead diameters),
    Gaussian-smoothed over ``smoothing`` pixels (periodic along periodic axes)."""
    _, r, _ = frame.beads()
    cell = cell or 4 * float(np.median(r))
    bins = tuple(max(1, int(round(L / cell))) for L in geometry.extent)
    xe, ye, phi = area_fraction_map(frame, geometry, bins, "beads")
    valid = np.isfinite(phi)
    modes = ["wrap" if geometry.is_periodic(c) else "nearest" for c in "xy"]
    # normalised convolution keeps the pixels outside an annulus from diluting the field
    num = ndimage.gaussian_filter(np.where(valid, phi, 0.0), smoothing, mode=modes)
    den = ndimage.gaussian_filter(valid.astype(float), smoothing, mode=modes)
    with np.errstate(invalid="ignore", divide="ignore"):
        field = np.where(valid, num / den, np.nan)
    return xe, ye, field


def _gradient(field, dx, dy, periodic):
    grads = []
    for k, (h, per) in enumerate(zip((dx, dy), periodic)):
        if field.shape[k] < 3:
            grads.append(np.zeros_like(field))
        elif per:
            grads.append((np.roll(field, -1, k) - np.roll(field, 1, k)) / (2 * h))
        else:
            grads.append(np.gradient(field, h, axis=k))
    return grads


def _pixel_of(edges, q):
    return np.clip(np.searchsorted(edges, q) - 1, 0, len(edges) - 2)


def rod_environment(frame, geometry, cell=None, smoothing=1.0):
    """Where the rods sit in the bead medium.

    Per rod, from the smoothed bead area fraction (:func:`smoothed_bead_field`) at its
    centre: ``phi_b`` (local bead area fraction), ``gradient`` ((n, 2), per unit length)
    and ``cos`` (cosine between the rod axis p and the gradient; NaN where the gradient
    vanishes). Returned as a dict of arrays.
    """
    rods = frame.rods()
    if len(rods) == 0:
        return {"phi_b": np.zeros(0), "gradient": np.zeros((0, 2)), "cos": np.zeros(0)}
    xe, ye, field = smoothed_bead_field(frame, geometry, cell, smoothing)
    f = np.nan_to_num(field, nan=np.nanmean(field))
    gx, gy = _gradient(f, xe[1] - xe[0], ye[1] - ye[0],
                       [geometry.is_periodic("x"), geometry.is_periodic("y")])
    i, j = _pixel_of(xe, rods.centre[:, 0]), _pixel_of(ye, rods.centre[:, 1])
    g = np.stack([gx[i, j], gy[i, j]], 1)
    norm = np.linalg.norm(g, axis=1)
    with np.errstate(invalid="ignore", divide="ignore"):
        cos = np.where(norm > 1e-12, np.sum(g * rods.axis, 1) / norm, np.nan)
    return {"phi_b": f[i, j], "gradient": g, "cos": cos}


def gradient_alignment(frame, geometry, cell=None, smoothing=1.0):
    """How rods point relative to the bead-density gradient.

    Returns ``(cos, mean_cos)``: per rod, the cosine of the angle between its axis p and
    the gradient of the smoothed bead area fraction at its centre (NaN where the gradient
    vanishes), and their mean. Positive: rods point from low to high bead density (the
    paper's A > 0).
    """
    cos = rod_environment(frame, geometry, cell, smoothing)["cos"]
    return cos, float(np.nanmean(cos)) if np.isfinite(cos).any() else float("nan")


# --------------------------------------------------------------------------- layers

@dataclass
class LayerSides:
    """A rod layer and the bead area fraction on both of its sides."""
    coord: str            # coordinate across the layer ('x', 'y' or 'theta')
    position: float       # layer position along coord
    direction: int        # +1 / -1: the side the layer's rods point to ("ahead")
    fraction_in_layer: float  # share of all rods in this layer
    alignment: float      # |<p>| of the layer's rods
    phi_ahead: float
    phi_behind: float

    @property
    def contrast(self):
        return self.phi_ahead - self.phi_behind


def _layer_coordinate(geometry, rods):
    """Across which coordinate to look for layers: theta in an annulus, x in a channel,
    in a box the axis the rods point along most (by |p|, so opposed layers count)."""
    if isinstance(geometry, Annulus):
        return "theta"
    if geometry.kind == "channel":
        return "x"
    return "xy"[int(np.argmax(np.mean(np.abs(rods.axis), axis=0)))]


def _along(geometry, rods, coord):
    """Each rod's axis component along increasing ``coord``."""
    if coord == "theta":
        return np.sum(rods.axis * geometry.tangent(rods.centre), axis=1)
    return rods.axis[:, "xy".index(coord)]


def find_layers(frame, geometry, max_layers=2, min_fraction=0.2, halfwidth=None, gap=None,
                window=None):
    """Find up to ``max_layers`` rod layers and the bead area fraction on both sides of each.

    Layers are searched across the coordinate the rods point along (x in a channel, theta
    in an annulus, the dominant axis of |p| in a box) as peaks of the rod-density
    histogram (bins of half a rod length), each refined by the mean position of the rods
    within ``halfwidth`` (default one rod length L) and kept if it holds at least
    ``min_fraction`` of the rods; the densest comes first, the next is searched among
    the remaining rods. A layer's direction is the sign of its own rods' mean axis
    component; ``phi_ahead`` / ``phi_behind`` are bead area fractions in windows of width
    ``window`` (default 5 L, at most half a period less the gap) starting ``gap`` (default L)
    ahead of / behind it. Lengths along theta are arc lengths at the annulus's mid radius.
    """
    rods = frame.rods()
    if len(rods) == 0:
        raise ValueError("layer_sides: the frame has no rods")
    L = float(np.median(rods.length))
    coord = _layer_coordinate(geometry, rods)
    to_q = 1.0 / geometry.length_per_unit(coord)
    halfwidth, gap, window = (halfwidth or L) * to_q, (gap or L) * to_q, (window or 5 * L) * to_q
    lo, hi = geometry.coordinate_range(coord)
    periodic = geometry.is_periodic(coord)
    period = hi - lo

    def rel(q, q0):
        d = q - q0
        return d - period * np.round(d / period) if periodic else d

    q = geometry.coordinate(rods.centre, coord)
    along = _along(geometry, rods, coord)
    xy, w = area_samples(frame, "beads")
    qb = geometry.coordinate(xy, coord)

    def window_fraction(position, sign):
        # Across a period shorter than 2 (gap + window) the windows would wrap onto each other
        # (and beyond the period no bead is counted): each keeps to its half of the period.
        width = min(window, 0.5 * period - gap) if periodic else window
        if width <= 0:
            return float("nan")
        a, b = sorted((position + sign * gap, position + sign * (gap + width)))
        if not periodic:
            a, b = max(a, lo), min(b, hi)
            if b <= a:
                return float("nan")
        d = rel(qb, position) * sign
        covered = w[(d > gap) & (d <= gap + (b - a))].sum()
        return float(covered / geometry.bin_areas(coord, np.array([a, b]))[0])

    free = np.ones(len(rods), bool)
    nb = max(3, int(round(period / (0.5 * L * to_q))))
    layers = []
    while len(layers) < max_layers and free.any():
        counts, edges = np.histogram(q[free], nb, (lo, hi))
        counts = ndimage.gaussian_filter1d(counts.astype(float), 1.0, mode="wrap" if periodic else "nearest")
        peak = 0.5 * (edges[:-1] + edges[1:])[np.argmax(counts)]
        near = free & (np.abs(rel(q, peak)) <= halfwidth)
        position = peak + (np.mean(rel(q[near], peak)) if near.any() else 0.0)
        if periodic:
            position = lo + np.mod(position - lo, period)
        members = free & (np.abs(rel(q, position)) <= halfwidth)
        if layers and members.mean() < min_fraction:
            break
        direction = 1 if along[members].sum() >= 0 else -1
        layers.append(LayerSides(coord, float(position), direction, float(members.mean()),
                                 polar_order(rods.axis[members])[1] if members.any() else 0.0,
                                 window_fraction(position, direction), window_fraction(position, -direction)))
        free &= ~members
    return layers


def _from_layer(geometry, layer, points):
    """The points' coordinate across ``layer`` less its position (minimum image where periodic)."""
    lo, hi = geometry.coordinate_range(layer.coord)
    d = geometry.coordinate(points, layer.coord) - layer.position
    if geometry.is_periodic(layer.coord):
        d -= (hi - lo) * np.round(d / (hi - lo))
    return d


def layer_sides(frame, geometry, halfwidth=None, gap=None, window=None):
    """The densest rod layer and the bead area fraction on both of its sides
    (:func:`find_layers` with one layer)."""
    return find_layers(frame, geometry, 1, halfwidth=halfwidth, gap=gap, window=window)[0]


def layer_drive(frame, geometry, layer=None, halfwidth=None):
    """How fast a rod layer moves along its direction, and how fast it drives the beads in it.

    ``layer``: a :class:`LayerSides` (default: the densest layer). Rods and beads whose centres
    lie within ``halfwidth`` (default one rod length L) of the layer; their mean velocity
    component along the layer's direction, in the frame's length units per time. The continuum
    theory's bead current is alpha rho P and its rods move at u0 P (docs/continuum.rst), so
    ``alpha`` = bead speed / |<p>| and ``u`` = rod speed / |<p>|, with |<p>| the layer's
    polar order. Needs a dump with velocities.
    """
    layer = layer or layer_sides(frame, geometry)
    rods = frame.rods()
    xy, _, vb = frame.beads()
    if vb is None or rods.velocity is None:
        raise ValueError("layer_drive: the dump has no velocities")
    L = float(np.median(rods.length))
    coord = layer.coord
    reach = (halfwidth or L) / geometry.length_per_unit(coord)

    def near(points):
        return np.abs(_from_layer(geometry, layer, points)) <= reach

    def forward(points, velocities):
        direction = geometry.tangent(points) if coord == "theta" else np.eye(2)["xy".index(coord)]
        return layer.direction * np.sum(velocities * direction, axis=-1)

    in_layer, members = near(xy), near(rods.centre)
    beads = float(np.mean(forward(xy[in_layer], vb[in_layer]))) if in_layer.any() else float("nan")
    rod_speed = float(np.mean(forward(rods.centre[members], rods.velocity[members])))
    order = layer.alignment
    return {"beads": beads, "rods": rod_speed, "alignment": order, "alpha": beads / order,
            "u": rod_speed / order, "beads_in_layer": int(in_layer.sum()), "rods_in_layer": int(members.sum())}


def layer_height_modes(frame, geometry, layer=None, modes=4):
    """The shape of a rod layer that spans a channel between side walls, as cosine modes.

    The rods whose centres lie within a rod length of ``layer`` (default: the densest layer);
    their offsets h along x from the layer's mean position, against their y across the channel of
    width W between its walls: a_n = (2 / N) sum_j h_j cos(q_n (y_j - y_wall)), q_n = n pi / W,
    n = 1..``modes``. Returns ``(q, a)`` (arrays, frame length units). A line of tension sigma at
    granular temperature T has sigma W q_n^2 <a_n^2> / 4 = T / 2 per mode, so
    W q_n^2 <a_n^2> / 2 over frames is the length T / sigma (:func:`interfacial_length`)."""
    layer = layer or layer_sides(frame, geometry)
    if layer.coord != "x" or geometry.is_periodic("y"):
        raise ValueError("layer_height_modes: for a layer across a channel with side walls in y")
    rods = frame.rods()
    L = float(np.median(rods.length))
    h = _from_layer(geometry, layer, rods.centre)
    member = np.abs(h) <= L
    h = h[member] - np.mean(h[member])
    y0, y1 = geometry.coordinate_range("y")
    y = rods.centre[member, 1] - y0
    q = np.arange(1, modes + 1) * np.pi / (y1 - y0)
    a = 2.0 / len(h) * np.cos(np.outer(q, y)) @ h
    return q, a


def interfacial_length(q, a, width):
    """T / sigma per mode from :func:`layer_height_modes` of many frames: ``a`` of shape
    (frames, modes); W q_n^2 <a_n^2> / 2 (equipartition of a line's capillary modes)."""
    return width * np.asarray(q) ** 2 * np.mean(np.asarray(a) ** 2, axis=0) / 2.0


def layer_profile(frame, geometry, layer=None, extent=None, bins=40, species="beads", spacing=None):
    """Area-fraction profile against the distance ahead of a rod layer.

    ``layer``: a :class:`LayerSides` (default: the densest layer of the frame). The
    distance is signed, positive on the side the layer's rods point to, in length units
    (arc length at the mid radius in an annulus), over [-extent, extent] (default: half
    the period, or the cell's extent). Averaging such profiles over frames follows a
    moving layer, which a lab-frame profile would smear out.
    """
    layer = layer or layer_sides(frame, geometry)
    coord = layer.coord
    lo, hi = geometry.coordinate_range(coord)
    arc = geometry.length_per_unit(coord)
    periodic = geometry.is_periodic(coord)
    extent = extent or 0.5 * (hi - lo) * arc
    edges = np.linspace(-extent, extent, int(bins) + 1)
    xy, w = area_samples(frame, species, spacing)
    d = _from_layer(geometry, layer, xy)
    covered, _ = np.histogram(d * layer.direction * arc, edges, weights=w)
    absolute = layer.position + layer.direction * edges / arc
    if not periodic:
        absolute = np.clip(absolute, lo, hi)
    area = np.abs(geometry.bin_areas(coord, absolute))
    with np.errstate(invalid="ignore", divide="ignore"):
        fraction = np.where(area > 0, covered / area, np.nan)
    return Profile("distance ahead of layer", species, edges, fraction)


def fit_layer_exponential(profile, start, stop=None):
    """Fit eq. 5's shape phi0 + (phi_plus - phi0) exp(-d / ell) to a :func:`layer_profile`
    for distances ``start`` <= d <= ``stop`` (default: to the end) ahead of the layer.
    Returns (phi_plus, ell, phi0), with phi_plus extrapolated to d = 0."""
    d, phi = profile.centres, profile.fraction
    ok = (d >= start) & (d <= (np.inf if stop is None else stop)) & np.isfinite(phi)
    d, phi = d[ok], phi[ok]
    if len(d) < 4:
        raise ValueError("fit_layer_exponential: fewer than 4 bins ahead of the layer")
    model = lambda x, a, ell, c: c + a * np.exp(-x / ell)
    p0 = (max(phi[0] - phi[-1], 1e-3), 0.3 * (d[-1] - d[0]) + 1e-9, phi[-1])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", OptimizeWarning)  # a flat profile has no covariance
        (a, ell, c), _ = curve_fit(model, d, phi, p0=p0, maxfev=20000)
    return float(c + a), float(ell), float(c)


# --------------------------------------------------------------------------- phases

@dataclass
class PhaseThresholds:
    """Thresholds of :func:`classify_phase` (see docs/python.rst for their reasons)."""
    polar_order: float = 0.5      # |<p>| above which rods count as aligned (flock)
    segregation: float = 0.3      # segregation index above which rods and beads demix
    layer_fraction: float = 0.5   # share of rods in active layers for an active interface
    layer_contrast: float = 0.1   # phi_b ahead minus behind a layer for it to be active
    layer_alignment: float = 0.5  # |<p>| of a layer's rods for it to be active
    jammed_fraction: float = 0.84  # phi_b + phi_r from which an arrested packing counts as jammed
    jammed_mobility: float = 0.1  # rms bead displacement between frames, in bead diameters, below
                                  # which the dynamics count as arrested
    flock_drift: float = 0.05     # rods' mean advance along their axes between frames, in rod
                                  # lengths, below which aligned rods are held still, not a flock


def segregation_index(frame, geometry, cell=None):
    """1 - (bead fraction where the rods are) / (mean bead fraction).

    Both fractions come from maps on pixels of ``cell`` (default two rod lengths); the
    bead fraction "where the rods are" is the rod-area-weighted mean over pixels. About
    0 for mixed rods and beads (slightly above 0: a rod excludes beads from its own
    area), towards 1 when rods sit in bead-free regions.
    """
    rods = frame.rods()
    cell = cell or 2 * float(np.median(rods.length))
    bins = tuple(max(1, int(round(L / cell))) for L in geometry.extent)
    _, _, pb = area_fraction_map(frame, geometry, bins, "beads")
    _, _, pr = area_fraction_map(frame, geometry, bins, "rods")
    ok = np.isfinite(pb) & np.isfinite(pr)
    mean_b = np.mean(pb[ok])
    if mean_b <= 0 or pr[ok].sum() <= 0:
        return 0.0
    at_rods = np.sum(pr[ok] * pb[ok]) / np.sum(pr[ok])
    return float(1 - at_rods / mean_b)


def _bead_displacements(frame, previous, caller):
    """The beads' displacements from ``previous`` to ``frame`` (matched by atom ID, minimum
    image), their positions in ``previous`` and their radii."""
    ids, prev_ids = frame.ids[frame.is_bead], previous.ids[previous.is_bead]
    if len(ids) != len(prev_ids) or np.any(ids != prev_ids):
        raise ValueError(f"{caller}: the two frames do not hold the same beads (atom IDs)")
    xy, r, _ = previous.beads()
    return frame.box.minimum_image(frame.beads()[0] - xy), xy, r


def rod_drift(frame, previous):
    """Mean advance of the rods along their own axes from ``previous`` to ``frame``, in units of
    the median rod length: each rod's centre displacement (minimum image) projected on its axis
    in ``previous``. The rods are matched by rod ID; rods in only one frame are left out, and
    NaN is returned if none is in both."""
    now, before = frame.rods(), previous.rods()
    common, i_now, i_before = np.intersect1d(now.ids, before.ids, return_indices=True)
    if len(common) == 0:
        return float("nan")
    d = frame.box.minimum_image(now.centre[i_now] - before.centre[i_before])
    advance = np.sum(d * before.axis[i_before], axis=1)
    return float(np.mean(advance) / np.median(before.length))


def bead_mobility(frame, previous):
    """Root-mean-square displacement of the beads from ``previous`` to ``frame``, in units of
    the median bead diameter (minimum image across periodic sides). The beads are matched by
    atom ID; both frames must hold the same beads."""
    if not np.any(frame.is_bead):
        raise ValueError("bead_mobility: the frame has no beads")
    d, _, r = _bead_displacements(frame, previous, "bead_mobility")
    return float(np.sqrt(np.mean(np.sum(d * d, axis=1))) / (2 * np.median(r)))


def layer_side_mobility(frame, previous, geometry, layer=None, window=5.0):
    """How mobile the beads are on each side of a rod layer (the paper's Fig. S1).

    The beads whose centres lie 1 to 1 + ``window`` rod lengths ahead of ``layer`` (default: the
    densest layer of ``previous``) and as far behind it in ``previous``, and their displacements
    to ``frame`` (matched by atom ID, minimum image). Returns per side the rms displacement less
    the side's mean (its drift), and that drift along the layer's direction, both in median bead
    diameters: ``ahead``, ``behind``, ``ahead_drift``, ``behind_drift``, and the beads counted
    (``n_ahead``, ``n_behind``). For channels and boxes (layers across x or y)."""
    layer = layer or layer_sides(previous, geometry)
    if layer.coord not in ("x", "y"):
        raise ValueError("layer_side_mobility: only for layers across x or y")
    axis = "xy".index(layer.coord)
    d, xy, r = _bead_displacements(frame, previous, "layer_side_mobility")
    diameter = 2 * np.median(r)
    L = float(np.median(previous.rods().length))
    s = layer.direction * _from_layer(geometry, layer, xy)
    out = {}
    for side, sel in (("ahead", (s >= L) & (s <= (1 + window) * L)),
                      ("behind", (s <= -L) & (s >= -(1 + window) * L))):
        dd = d[sel]
        drift = dd.mean(axis=0) if len(dd) else np.full(2, np.nan)
        out[side] = float(np.sqrt(np.mean(np.sum((dd - drift) ** 2, axis=1))) / diameter) if len(dd) else float("nan")
        out[side + "_drift"] = float(layer.direction * drift[axis] / diameter)
        out["n_" + side] = int(sel.sum())
    return out


@dataclass
class Arc:
    """An arc of an annulus: from angle ``start`` counter-clockwise over ``width`` (radians),
    with the bead area fraction inside it (``fraction``) and in the rest of the ring
    (``outside``, NaN when the arc is the whole ring)."""
    start: float
    width: float
    fraction: float
    outside: float

    @property
    def stop(self):
        return float(np.mod(self.start + self.width, 2 * np.pi))

    def offset(self, theta, end):
        """Signed angle from the arc's ``end`` ('start' or 'stop') to ``theta``, in (-pi, pi]."""
        return np.angle(np.exp(1j * (np.asarray(theta, float) - getattr(self, end))))

    def contains(self, theta):
        return np.mod(np.asarray(theta, float) - self.start, 2 * np.pi) < self.width


def dense_arc(frame, annulus, threshold=0.8, sectors=72):
    """The condensate of an annulus: the widest run of adjacent angular sectors (``sectors`` of
    them round the ring) whose bead area fraction exceeds ``threshold``, as an :class:`Arc`;
    None if no sector does. Beads whose centres lie beyond ``r_out`` (in the lobes of a
    scalloped wall) are left out, so that every sector is the same piece of ring."""
    if not isinstance(annulus, Annulus):
        raise ValueError("dense_arc: only for an annulus")
    r, _ = annulus.polar(frame.pos[:, :2])
    ring = ~(frame.is_bead & (r > annulus.r_out))
    if not ring.all():
        frame = replace(frame, **{k: getattr(frame, k)[ring] for k in
                                  ("ids", "mol", "types", "radius", "pos", "vel", "body")
                                  if getattr(frame, k) is not None})
    prof = area_fraction_profile(frame, annulus, "theta", sectors)
    dense = prof.fraction > threshold
    if not dense.any():
        return None
    if dense.all():
        return Arc(0.0, 2 * np.pi, float(prof.fraction.mean()), float("nan"))
    # walk once round from just after a sparse sector, so that no run is cut in two
    order = (int(np.argmin(dense)) + 1 + np.arange(sectors)) % sectors
    best, first, run = 0, 0, 0
    for j, k in enumerate(order):
        run = run + 1 if dense[k] else 0
        if run > best:
            best, first = run, order[j - run + 1]
    inside = np.mod(np.arange(sectors) - first, sectors) < best
    return Arc(float(prof.edges[first]), best * 2 * np.pi / sectors,
               float(prof.fraction[inside].mean()), float(prof.fraction[~inside].mean()))


def arc_drift(frame, previous, annulus, arc):
    """How far the beads inside ``arc`` in ``previous`` moved round the ring by ``frame``
    (matched by atom ID): their mean counter-clockwise angular displacement as an arc length
    at the mid radius. A condensate held in place drifts 0; NaN if the arc holds no bead."""
    d, xy, _ = _bead_displacements(frame, previous, "arc_drift")
    _, before = annulus.polar(xy)
    _, after = annulus.polar(xy + d)
    inside = arc.contains(before)
    if not inside.any():
        return float("nan")
    turned = np.angle(np.exp(1j * (after - before)))[inside]
    return float(np.mean(turned) * annulus.length_per_unit("theta"))


def capping_rods(frame, annulus, arc, reach=1.0):
    """The rods that press on the ends of ``arc``: centres within ``reach`` median rod lengths
    (arc length at the mid radius) of an end, on either side of it, heading into the arc
    (tangential component of the axis above 0.5). A layer pushes through the arc's less
    dense edge, so it can sit more than one rod length from the arc's end. Returns
    ``(at_start, at_stop)``: counter-clockwise rods at the start, clockwise ones at the stop.
    Both non-zero: the two opposed layers of the paper's trap (Fig. 3)."""
    rods = frame.rods()
    if len(rods.ids) == 0:
        return 0, 0
    reach = reach * float(np.median(rods.length))
    _, theta = annulus.polar(rods.centre)
    heading = np.sum(rods.axis * annulus.tangent(rods.centre), axis=1)
    radius = annulus.length_per_unit("theta")
    near_start = np.abs(arc.offset(theta, "start")) * radius <= reach
    near_stop = np.abs(arc.offset(theta, "stop")) * radius <= reach
    return int(np.sum(near_start & (heading > 0.5))), int(np.sum(near_stop & (heading < -0.5)))


@dataclass
class PhaseResult:
    phase: str
    observables: dict = field(default_factory=dict)


def phase_observables(frame, geometry, thresholds=None, previous=None):
    """The measured observables :func:`classify_phase` decides on.

    ``phi_total`` = phi_b + phi_r; with an earlier frame ``previous`` of the same run,
    ``mobility``: the beads' rms displacement since then in bead diameters
    (:func:`bead_mobility`; NaN without one), ``rod_drift``: the rods' mean advance along their
    axes since then in rod lengths (:func:`rod_drift`; NaN without one or without rods) and
    ``interval``, the time between the frames.

    Layer observables: those of the densest layer (``layer_*``, ``phi_ahead``,
    ``phi_behind``), and over up to two layers the number of *active* ones (aligned and
    with a bead contrast, per ``thresholds``) and the share of rods they hold
    (``active_layer_fraction``). Two active layers pointing at each other trap a condensate.
    """
    t = thresholds or PhaseThresholds()
    rods = frame.rods()
    phi_b, phi_r = global_area_fractions(frame, geometry)
    obs = {"phi_b": phi_b, "phi_r": phi_r, "phi_total": phi_b + phi_r, "n_rods": len(rods),
           "mobility": float("nan") if previous is None else bead_mobility(frame, previous),
           "interval": float("nan") if previous is None else frame.time - previous.time}
    if len(rods) == 0:  # beads only: nothing to order, segregate or layer
        obs.update(P=0.0, rod_drift=float("nan"), segregation=0.0, layer_fraction=0.0, layer_P=0.0, phi_ahead=float("nan"),
                   phi_behind=float("nan"), layer_contrast=0.0, layer_position=float("nan"),
                   layer_coord="", n_active_layers=0, active_layer_fraction=0.0)
        return obs
    obs["P"] = polar_order(rods.axis)[1]
    obs["rod_drift"] = float("nan") if previous is None else rod_drift(frame, previous)
    if isinstance(geometry, Annulus):
        obs["P_tangential"] = tangential_polarization(rods, geometry)
    obs["segregation"] = segregation_index(frame, geometry)
    layers = find_layers(frame, geometry)
    first = layers[0]
    obs.update(layer_fraction=first.fraction_in_layer, layer_P=first.alignment,
               phi_ahead=first.phi_ahead, phi_behind=first.phi_behind,
               layer_contrast=first.contrast, layer_position=first.position, layer_coord=first.coord)
    active = [l for l in layers if l.alignment >= t.layer_alignment and l.contrast >= t.layer_contrast]
    obs["n_active_layers"] = len(active)
    obs["active_layer_fraction"] = float(sum(l.fraction_in_layer for l in active))
    return obs


def classify_phase(frame, geometry, thresholds=PhaseThresholds(), previous=None):
    """Jammed / condensed (by an active interface) / segregated / flock / isotropic.

    Decided in this order on measured observables (:func:`phase_observables`):

    0. ``jammed`` (only with ``previous``, an earlier frame of the same run): the total area
       fraction phi_b + phi_r is at least ``jammed_fraction`` and the beads' rms
       displacement since ``previous`` is below ``jammed_mobility`` bead diameters (arrested
       dynamics; take frames far enough apart that a fluid's beads move further);
    1. ``condensed``: active layers (aligned, |<p>| >= ``layer_alignment``, with the bead
       fraction ahead exceeding the one behind by ``layer_contrast``; one layer, or two
       trapping a condensate) hold at least ``layer_fraction`` of the rods;
    2. ``segregated``: segregation index >= ``segregation``;
    3. ``flock``: rod polar order |<p>| >= ``polar_order``, and, with ``previous``, the rods
       advance along their axes by at least ``flock_drift`` rod lengths since then (aligned
       rods held still, e.g. stacked against a wall, are not a flock);
    4. ``isotropic`` otherwise.
    """
    obs = phase_observables(frame, geometry, thresholds, previous)
    t = thresholds
    if obs["phi_total"] >= t.jammed_fraction and obs["mobility"] < t.jammed_mobility:
        phase = "jammed"
    elif obs["n_active_layers"] > 0 and obs["active_layer_fraction"] >= t.layer_fraction:
        phase = "condensed"
    elif obs["segregation"] >= t.segregation:
        phase = "segregated"
    elif obs["P"] >= t.polar_order and (previous is None or obs["rod_drift"] >= t.flock_drift):
        phase = "flock"
    else:
        phase = "isotropic"
    return PhaseResult(phase, obs)
