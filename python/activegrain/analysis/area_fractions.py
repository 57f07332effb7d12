"""Area fractions of one frame: profiles, maps and the totals of the cell.

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
from dataclasses import dataclass

import numpy as np

from ..geometry import Annulus
from ..rods import disc_samples

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
