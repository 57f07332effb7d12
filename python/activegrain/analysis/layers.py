"""Rod layers: where aligned rods gather across the cell, the bead area fraction on both sides of
a layer, the force it drives, its height modes and the bead profile across it."""
import warnings
from dataclasses import dataclass

import numpy as np
from scipy import ndimage
from scipy.optimize import OptimizeWarning, curve_fit

from ..geometry import Annulus
from .area_fractions import Profile, area_samples
from .order import polar_order


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
