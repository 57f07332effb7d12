"""Orientational order of the rods: polar and nematic order, the tangential polarization of an
annulus, and how rods point relative to the bead-density gradient."""
import numpy as np
from scipy import ndimage

from ..geometry import Annulus
from .area_fractions import area_fraction_map


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
    return cos, alignment_of(cos)


def alignment_of(cos):
    """The mean of the rods' cosines to the bead gradient where it is defined (NaN if nowhere)."""
    finite = np.isfinite(cos)
    return float(cos[finite].mean()) if finite.any() else float("nan")
