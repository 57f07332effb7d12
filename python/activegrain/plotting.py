"""Figures: snapshots (rods as tapered shapes, beads as discs), profiles, kymographs,
movies, the phase diagram of a sweep, and the theory's growth rates and point-force profile."""
import shutil

import numpy as np
import matplotlib
from matplotlib import animation
from matplotlib.collections import EllipseCollection, PolyCollection
from matplotlib.patches import Circle, Rectangle as RectPatch
import matplotlib.pyplot as plt

from .analysis import Phase
from .geometry import Annulus

# Marker, face and edge colour per phase, in the legend's order (open for the disordered ones).
PHASE_MARKERS = {Phase.ISOTROPIC: ("o", "none", "tab:gray"), Phase.FLOCK: ("^", "tab:blue", "tab:blue"),
                 Phase.SEGREGATED: ("s", "tab:orange", "tab:orange"), Phase.CONDENSED: ("*", "tab:red", "tab:red"),
                 Phase.JAMMED: ("X", "black", "black")}


def _periodic_copies(poly, box):
    """The polygon and its periodic images that poke into the box."""
    out = [poly]
    lo, hi, L = np.asarray(box.lo[:2]), np.asarray(box.hi[:2]), box.lengths[:2]
    for k in range(2):
        if not box.periodic[k]:
            continue
        extra = []
        for p in out:
            if p[:, k].min() < lo[k]:
                extra.append(p + L[k] * np.eye(2)[k])
            if p[:, k].max() > hi[k]:
                extra.append(p - L[k] * np.eye(2)[k])
        out += extra
    return out


def draw_snapshot(ax, frame, geometry=None, bead_color="0.55", rod_cmap="hsv", color_rods_by="angle"):
    """Draw beads as discs and rods as their tapered projected shapes.

    Rods are coloured by axis angle (``color_rods_by='angle'``) or plain dark red
    (None); periodic images of rods crossing the boundary are drawn too.
    Returns the rod PolyCollection.
    """
    xy, r, _ = frame.beads()
    if len(r):
        ax.add_collection(EllipseCollection(2 * r, 2 * r, np.zeros_like(r), units="xy", offsets=xy,
                                            offset_transform=ax.transData, facecolors=bead_color,
                                            edgecolors="none"))
    rods = frame.rods()
    polys, colors = [], []
    angle = np.mod(np.arctan2(rods.axis[:, 1], rods.axis[:, 0]), 2 * np.pi) / (2 * np.pi)
    cmap = matplotlib.colormaps[rod_cmap]
    for poly, a in zip(rods.outlines(), angle):
        for p in _periodic_copies(poly, frame.box):
            polys.append(p)
            colors.append(cmap(a) if color_rods_by == "angle" else (0.55, 0.05, 0.05, 1))
    pc = PolyCollection(polys, facecolors=colors, edgecolors="k", linewidths=0.3)
    ax.add_collection(pc)
    _draw_cell(ax, frame, geometry)
    ax.set_aspect("equal")
    return pc


def _draw_cell(ax, frame, geometry):
    lo, hi = np.asarray(frame.box.lo[:2]), np.asarray(frame.box.hi[:2])
    if isinstance(geometry, Annulus):
        for rad in (geometry.r_in, geometry.r_out):
            if rad > 0:
                ax.add_patch(Circle(geometry.centre, rad, fill=False, lw=1.5, color="k"))
        c, R = np.asarray(geometry.centre), geometry.r_out
        ax.set_xlim(c[0] - 1.02 * R, c[0] + 1.02 * R)
        ax.set_ylim(c[1] - 1.02 * R, c[1] + 1.02 * R)
        return
    ax.add_patch(RectPatch(lo, *(hi - lo), fill=False, lw=0.5, ls=":", color="k"))
    for k in range(2):  # walls: solid lines on non-periodic sides
        if not frame.box.periodic[k]:
            for v in (lo[k], hi[k]):
                if k == 0:
                    ax.plot([v, v], [lo[1], hi[1]], "k", lw=2)
                else:
                    ax.plot([lo[0], hi[0]], [v, v], "k", lw=2)
    ax.set_xlim(lo[0], hi[0])
    ax.set_ylim(lo[1], hi[1])


def snapshot(frame, geometry=None, path=None, width=10.0, title=None):
    """Figure of one frame; saved to ``path`` if given. Returns the figure."""
    L = frame.box.lengths[:2] if geometry is None else geometry.extent
    fig, ax = plt.subplots(figsize=(width, max(1.5, width * L[1] / L[0]) + 0.6))
    draw_snapshot(ax, frame, geometry)
    ax.set_title(title or f"step {frame.step}")
    fig.tight_layout()
    if path:
        fig.savefig(path, dpi=150)
    return fig


def plot_profiles(profiles, path=None, labels=None, ax=None):
    """Line plot of :class:`activegrain.analysis.Profile` objects."""
    fig = None
    if ax is None:
        fig, ax = plt.subplots(figsize=(7, 3.5))
    for i, p in enumerate(profiles):
        ax.step(p.centres, p.fraction, where="mid", label=labels[i] if labels else p.species)
    ax.set_xlabel(profiles[0].coord)
    ax.set_ylabel("area fraction")
    ax.legend()
    if fig is not None:
        fig.tight_layout()
        if path:
            fig.savefig(path, dpi=150)
    return fig or ax.figure


def plot_map(x_edges, y_edges, phi, path=None, label="area fraction"):
    """Image of a 2D area-fraction map (``phi[nx, ny]``; NaN outside the cell)."""
    L = (x_edges[-1] - x_edges[0], y_edges[-1] - y_edges[0])
    fig, ax = plt.subplots(figsize=(8, max(1.8, 8 * L[1] / L[0]) + 0.6))
    m = ax.pcolormesh(x_edges, y_edges, np.asarray(phi).T, cmap="viridis", vmin=0)
    fig.colorbar(m, ax=ax, label=label)
    ax.set_aspect("equal")
    fig.tight_layout()
    if path:
        fig.savefig(path, dpi=150)
    return fig


def kymograph(times, profiles, path=None, label="bead area fraction"):
    """Image of profiles (rows: times) against the profile coordinate."""
    fractions = np.array([p.fraction for p in profiles])
    e = profiles[0].edges
    fig, ax = plt.subplots(figsize=(7, 4))
    t = np.asarray(times, float)
    t_edges = np.concatenate([[t[0]], 0.5 * (t[1:] + t[:-1]), [t[-1]]]) if len(t) > 1 else [t[0] - 0.5, t[0] + 0.5]
    m = ax.pcolormesh(e, t_edges, fractions, shading="flat", cmap="viridis")
    fig.colorbar(m, ax=ax, label=label)
    ax.set_xlabel(profiles[0].coord)
    ax.set_ylabel("time")
    fig.tight_layout()
    if path:
        fig.savefig(path, dpi=150)
    return fig


def movie(frames, path, geometry=None, fps=10, width=8.0):
    """Animate frames (a list) into ``path``: .gif through Pillow (always available), .mp4
    through ffmpeg where it is installed."""
    frames = list(frames)
    if not frames:
        raise ValueError("movie: no frames")
    if path.endswith(".gif"):
        writer = animation.PillowWriter(fps=fps)
    elif shutil.which("ffmpeg") and animation.writers.is_available("ffmpeg"):
        writer = animation.FFMpegWriter(fps=fps)
    else:
        raise RuntimeError("movie: writing mp4 needs ffmpeg, which is not installed; write a .gif")
    fig = snapshot(frames[0], geometry, width=width)
    ax = fig.axes[0]

    def update(i):
        ax.clear()
        draw_snapshot(ax, frames[i], geometry)
        ax.set_title(f"step {frames[i].step}")
        return ax.collections

    anim = animation.FuncAnimation(fig, update, frames=len(frames), blit=False)
    anim.save(path, writer=writer)
    plt.close(fig)


def plot_growth_rates(k, rates, path=None, title=None):
    """Real (solid) and imaginary (dashed) parts of the growth rates lambda(k)."""
    fig, ax = plt.subplots(figsize=(6, 3.8))
    for i in range(rates.shape[-1]):
        ax.plot(k, rates[:, i].real, label=f"Re $\\lambda_{i + 1}$")
        if np.any(np.abs(rates[:, i].imag) > 0):
            ax.plot(k, rates[:, i].imag, "--", label=f"Im $\\lambda_{i + 1}$")
    ax.axhline(0, color="k", lw=0.5)
    ax.set_xlabel("k")
    ax.set_ylabel("growth rate")
    ax.legend()
    if title:
        ax.set_title(title)
    fig.tight_layout()
    if path:
        fig.savefig(path, dpi=150)
    return fig


def plot_point_force(x, curves, pf, path=None):
    """Density profiles around a moving point force: ``curves`` maps labels to rho(x)."""
    fig, ax = plt.subplots(figsize=(6, 3.8))
    for label, rho in curves.items():
        ax.plot(x, rho, label=label)
    ax.axvline(0, color="k", lw=0.5)
    ax.axhline(pf.rho_plus, color="0.5", ls=":", lw=1)
    ax.set_xlabel("x (from the force, positive ahead)")
    ax.set_ylabel(r"bead density $\rho$")
    ax.set_title(rf"$\rho_+$ = {pf.rho_plus:.3f}, $\ell_+$ = {pf.ell_plus:.3g}")
    ax.legend()
    fig.tight_layout()
    if path:
        fig.savefig(path, dpi=150)
    return fig


def phase_diagram(points, path, title=None):
    """Markers per phase on (phi_b, phi_r), as the paper's Figs. 2a and 3a. ``points``:
    {(phi_b, phi_r): (majority phase, seeds that show it, seeds)} (:func:`activegrain.sweep.majority`);
    a point where the seeds disagree shows its majority phase with ``k/n`` beside it."""
    fig, ax = plt.subplots(figsize=(6.0, 3.8))
    for phase, (marker, face, edge) in PHASE_MARKERS.items():
        xy = [k for k, v in points.items() if v[0] == phase]
        ax.scatter([p[0] for p in xy], [p[1] for p in xy], marker=marker, s=90, facecolors=face,
                   edgecolors=edge, linewidths=1.5, label=phase.value)
    for (b, r), (_, k, n) in points.items():
        if k < n:
            ax.annotate(f"{k}/{n}", (b, r), textcoords="offset points", xytext=(6, 6), fontsize=7)
    phi_b = [k[0] for k in points]
    phi_r = [k[1] for k in points]
    pad_b = 0.02 + 0.05 * (max(phi_b) - min(phi_b))
    pad_r = 0.005 + 0.05 * (max(phi_r) - min(phi_r))
    ax.set_xlim(min(phi_b) - pad_b, max(phi_b) + pad_b)
    ax.set_ylim(max(0.0, min(phi_r) - pad_r), max(phi_r) + pad_r)
    ax.set_xlabel(r"$\phi_b$")
    ax.set_ylabel(r"$\phi_r$")
    if title:
        ax.set_title(title, fontsize=9)
    ax.legend(fontsize=7, loc="center left", bbox_to_anchor=(1.0, 0.5), frameon=False)
    fig.tight_layout()
    fig.savefig(path, dpi=150)
    plt.close(fig)
    return path
