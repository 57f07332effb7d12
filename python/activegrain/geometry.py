"""Simulation cells: the box of a dump and the shapes of the paper's cells.

A :class:`Box` is the LAMMPS box (bounds + which sides are periodic). The
cell geometries that analysis needs on top of it:

* :class:`Channel`   -- periodic along x, walls at y = ylo and y = yhi;
* :class:`PeriodicBox` -- periodic in x and y (the paper's square box);
* :class:`Rectangle` -- walls on all four sides;
* :class:`Annulus`   -- centre, inner and outer radius (walls are circles).

All lengths are in the units of the frame they describe.
"""
from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class Box:
    """Orthogonal box: ``lo``/``hi`` are (x, y, z) bounds, ``periodic`` flags per axis."""
    lo: tuple
    hi: tuple
    periodic: tuple = (True, True, False)

    @property
    def lengths(self):
        return np.asarray(self.hi, float) - np.asarray(self.lo, float)

    def minimum_image(self, d):
        """Apply the minimum-image convention to displacements ``d`` (..., 2 or 3)."""
        d = np.array(d, dtype=float)
        L = self.lengths
        for k in range(d.shape[-1]):
            if self.periodic[k]:
                d[..., k] -= L[k] * np.round(d[..., k] / L[k])
        return d

    def wrap(self, x):
        """Wrap positions (..., 2 or 3) into the box along periodic axes."""
        x = np.array(x, dtype=float)
        lo, L = np.asarray(self.lo, float), self.lengths
        for k in range(x.shape[-1]):
            if self.periodic[k]:
                x[..., k] = lo[k] + np.mod(x[..., k] - lo[k], L[k])
        return x

    def scaled(self, factor):
        return Box(tuple(np.asarray(self.lo) * factor), tuple(np.asarray(self.hi) * factor),
                   self.periodic)


@dataclass(frozen=True)
class Geometry:
    """Base class: a cell inside (or equal to) a box."""
    box: Box

    kind = "box"

    @property
    def area(self):
        L = self.box.lengths
        return float(L[0] * L[1])

    def contains(self, xy):
        xy = np.asarray(xy, float)
        lo, hi = np.asarray(self.box.lo, float), np.asarray(self.box.hi, float)
        return np.all((xy >= lo[:2]) & (xy <= hi[:2]), axis=-1)

    def coordinate(self, xy, name):
        """Coordinate ``name`` ('x', 'y', or 'r'/'theta' for an annulus) of points ``xy``."""
        xy = np.asarray(xy, float)
        if name == "x":
            return xy[..., 0]
        if name == "y":
            return xy[..., 1]
        raise ValueError(f"{self.kind}: unknown coordinate '{name}' (use x or y)")

    def coordinate_range(self, name):
        if name not in ("x", "y"):
            raise ValueError(f"{self.kind}: unknown coordinate '{name}' (use x or y)")
        k = "xy".index(name)
        return float(self.box.lo[k]), float(self.box.hi[k])

    def is_periodic(self, name):
        return name in ("x", "y") and bool(self.box.periodic["xy".index(name)])

    @property
    def extent(self):
        """(width, height) of the cell's bounding rectangle."""
        return self.box.lengths[:2]

    def length_per_unit(self, name):
        """Length per unit of coordinate ``name`` (the mid radius for an annulus's theta)."""
        return 1.0

    def bin_areas(self, name, edges):
        """Area of the cell between consecutive ``edges`` of coordinate ``name``."""
        k = "xy".index(name)
        other = self.box.lengths[1 - k]
        return np.diff(edges) * other

    def scaled(self, factor):
        return type(self)(self.box.scaled(factor))


class PeriodicBox(Geometry):
    kind = "box"


class Channel(Geometry):
    kind = "channel"


class Rectangle(Geometry):
    kind = "rectangle"


@dataclass(frozen=True)
class Annulus(Geometry):
    """Annular cell: ``centre`` (x, y), inner radius ``r_in`` (0 for a disc), outer ``r_out``."""
    centre: tuple = (0.0, 0.0)
    r_in: float = 0.0
    r_out: float = 1.0

    kind = "annulus"

    def __post_init__(self):
        if not 0 <= self.r_in < self.r_out:
            raise ValueError(f"annulus: need 0 <= r_in < r_out, got {self.r_in}, {self.r_out}")

    @property
    def area(self):
        return float(np.pi * (self.r_out ** 2 - self.r_in ** 2))

    def polar(self, xy):
        d = np.asarray(xy, float) - np.asarray(self.centre, float)
        return np.hypot(d[..., 0], d[..., 1]), np.mod(np.arctan2(d[..., 1], d[..., 0]), 2 * np.pi)

    def contains(self, xy):
        r, _ = self.polar(xy)
        return (r >= self.r_in) & (r <= self.r_out)

    def coordinate(self, xy, name):
        if name in ("x", "y"):
            return Geometry.coordinate(self, xy, name)
        r, theta = self.polar(xy)
        if name == "r":
            return r
        if name == "theta":
            return theta
        raise ValueError(f"annulus: unknown coordinate '{name}' (use r, theta, x or y)")

    def coordinate_range(self, name):
        if name == "r":
            return float(self.r_in), float(self.r_out)
        if name == "theta":
            return 0.0, 2 * np.pi
        if name in ("x", "y"):
            c = self.centre["xy".index(name)]
            return c - self.r_out, c + self.r_out
        raise ValueError(f"annulus: unknown coordinate '{name}' (use r, theta, x or y)")

    def is_periodic(self, name):
        return name == "theta"

    @property
    def extent(self):
        return np.full(2, 2.0 * self.r_out)

    def length_per_unit(self, name):
        return 0.5 * (self.r_in + self.r_out) if name == "theta" else 1.0

    def tangent(self, xy):
        """Unit vectors e_theta (counter-clockwise) at points ``xy``."""
        d = np.asarray(xy, float) - np.asarray(self.centre, float)
        return np.stack([-d[..., 1], d[..., 0]], -1) / np.linalg.norm(d, axis=-1)[..., None]

    def bin_areas(self, name, edges):
        edges = np.asarray(edges, float)
        if name == "r":
            e = np.clip(edges, self.r_in, self.r_out)
            return np.pi * np.diff(e ** 2)
        if name == "theta":
            return 0.5 * np.diff(edges) * (self.r_out ** 2 - self.r_in ** 2)
        # a Cartesian strip of the annulus: exact from the area of a disc left of a line
        c = self.centre["xy".index(name)]
        u = edges - c
        return np.diff(_disc_area_below(u, self.r_out) - _disc_area_below(u, self.r_in))

    def scaled(self, factor):
        return Annulus(self.box.scaled(factor), tuple(np.asarray(self.centre) * factor),
                       self.r_in * factor, self.r_out * factor)


def _disc_area_below(u, r):
    """Area of the disc of radius ``r`` (centred at 0) with coordinate < ``u``."""
    if r == 0:
        return np.zeros_like(np.asarray(u, float))
    t = np.clip(np.asarray(u, float) / r, -1.0, 1.0)
    return r * r * (np.arcsin(t) + t * np.sqrt(1 - t * t) + np.pi / 2)


def geometry_from_box(box, kind="auto", centre=None, r_in=None, r_out=None):
    """Build the cell geometry of a dump.

    ``kind='auto'`` reads it from the box's boundary flags: periodic x and y is a
    periodic box, periodic x only a channel, none a rectangle. An annulus cannot be
    seen from the box: pass ``kind='annulus'`` with ``r_out`` (and ``r_in``, ``centre``,
    which default to 0 and the box centre).
    """
    px, py = bool(box.periodic[0]), bool(box.periodic[1])
    if kind == "auto":
        if px and py:
            kind = "box"
        elif px and not py:
            kind = "channel"
        elif not px and not py:
            kind = "rectangle"
        else:
            raise ValueError("geometry: a box periodic in y only is not a supported cell "
                             "(channels run along x)")
    if kind == "box":
        return PeriodicBox(box)
    if kind == "channel":
        return Channel(box)
    if kind == "rectangle":
        return Rectangle(box)
    if kind == "annulus":
        if r_out is None:
            raise ValueError("geometry annulus: r_out is required")
        if centre is None:
            centre = tuple(0.5 * (np.asarray(box.lo[:2]) + np.asarray(box.hi[:2])))
        return Annulus(box, tuple(centre), float(r_in or 0.0), float(r_out))
    raise ValueError(f"geometry: unknown kind '{kind}' (auto, box, channel, rectangle, annulus)")
