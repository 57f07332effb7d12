"""Figures: snapshots (rods as tapered shapes, beads as discs), profiles, kymographs,
movies, the phase diagram of a sweep, and the theory's growth rates and point-force profile.

Every figure is laid out by matplotlib's constrained layout, which makes room for its labels,
tick labels, titles and colour bars whatever their length (no label is cut off at the edge)."""
import itertools
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
                 Phase.JAMMED: ("X", "black", "black"), Phase.ARRESTED: ("v", "tab:purple", "tab:purple"),
                 Phase.ALIGNED: ("^", "none", "tab:blue")}
_RARE_PHASES = (Phase.ARRESTED, Phase.ALIGNED)   # in a phase diagram's key only where they occur


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


# How the figures name the area fractions of analysis.SPECIES.
SPECIES_LABELS = {"beads": "beads", "rods": "rods", "all": "beads and rods"}
HEADING_CMAP = "hsv"          # cyclic: a rod's heading angle, 0 (+x) to 360 degrees


def length_label(frame):
    """The unit of a frame's lengths for axis labels: ``d`` (bead diameters) when its beads'
    median diameter is 1, else the length in metres (the decks' SI dumps, ``frame.length_unit``)."""
    _, r, _ = frame.beads()
    if len(r) and abs(2 * float(np.median(r)) - 1.0) < 0.02:
        return "d"
    return "m" if frame.length_unit == 1.0 else f"{frame.length_unit:g} m"


def coord_label(coord, unit):
    """Axis label of a profile coordinate (x, y, r in ``unit``; theta in radians)."""
    return r"$\theta$ (rad)" if coord == "theta" else f"{coord} ({unit})"


def seconds_text(t):
    """A time in seconds for a title: 1.00, 12.5, 203."""
    return f"{t:.2f}" if abs(t) < 10 else (f"{t:.1f}" if abs(t) < 100 else f"{t:.0f}")


def frame_title(frame, seconds=True, polar=True):
    """``t = 2.00 s`` (``seconds``: ``frame.time`` is in seconds; else the MD step, and a note that
    the time is unknown), with the rods' number and polar order P = |<p>| (``polar``)."""
    text = f"t = {seconds_text(frame.time)} s" if seconds else f"step {frame.step} (time unknown: no time step given)"
    if polar:
        rods = frame.rods()
        if len(rods):
            mean = rods.axis.mean(axis=0)
            text += (f";  {len(rods)} rods, polar order P = {np.hypot(*mean):.2f}, mean heading "
                     f"{round(float(np.degrees(np.arctan2(mean[1], mean[0])))) % 360}\u00b0")
    return text


def draw_snapshot(ax, frame, geometry=None, bead_color="0.6", rod_cmap=HEADING_CMAP, color_rods_by="angle",
                  nose_color="k"):
    """Draw beads as discs and rods as their tapered projected shapes, the nose (the narrow end,
    which leads: the rods walk nose first) marked by a dot.

    Rods are coloured by heading, the angle of their axis p from tail to nose (``color_rods_by=
    'angle'``, cyclic colour map ``rod_cmap``; :func:`draw_heading_wheel` is its key) or plain
    dark red (None); periodic images of rods crossing the boundary are drawn too.
    Returns the rod PolyCollection.
    """
    xy, r, _ = frame.beads()
    if len(r):
        ax.add_collection(EllipseCollection(2 * r, 2 * r, np.zeros_like(r), units="xy", offsets=xy,
                                            offset_transform=ax.transData, facecolors=bead_color,
                                            edgecolors="none"))
    rods = frame.rods()
    polys, colors, noses, nose_r = [], [], [], []
    angle = np.mod(np.arctan2(rods.axis[:, 1], rods.axis[:, 0]), 2 * np.pi) / (2 * np.pi)
    cmap = matplotlib.colormaps[rod_cmap]
    for poly, a, nose, s, rr in zip(rods.outlines(), angle, rods.nose, rods.sphere_s, rods.sphere_r):
        for p in _periodic_copies(poly, frame.box):
            polys.append(p)
            colors.append(cmap(a) if color_rods_by == "angle" else (0.55, 0.05, 0.05, 1))
            noses.append(nose + p[0] - poly[0])
            nose_r.append(0.6 * rr[np.argmax(s)])
    pc = PolyCollection(polys, facecolors=colors, edgecolors="k", linewidths=0.3)
    ax.add_collection(pc)
    if noses and nose_color:
        nr = np.array(nose_r)
        ax.add_collection(EllipseCollection(2 * nr, 2 * nr, np.zeros_like(nr), units="xy",
                                            offsets=np.array(noses), offset_transform=ax.transData,
                                            facecolors=nose_color, edgecolors="none"))
    _draw_cell(ax, frame, geometry)
    ax.set_aspect("equal")
    return pc


def draw_heading_wheel(ax, rod_cmap=HEADING_CMAP):
    """The key to the rods' colours: a ring coloured by heading angle, with a rod pointing +x."""
    th = np.linspace(0, 2 * np.pi, 181)
    ring = np.linspace(0.62, 1.0, 2)
    T, R = np.meshgrid(th, ring)
    ax.pcolormesh(R * np.cos(T), R * np.sin(T), np.tile((th[:-1] + th[1:]) / 2, (1, 1)),
                  cmap=rod_cmap, vmin=0, vmax=2 * np.pi, shading="flat")
    ax.annotate("", xy=(0.5, 0), xytext=(-0.45, 0),
                arrowprops=dict(arrowstyle="-|>", color="k", lw=1.2, shrinkA=0, shrinkB=0))
    for deg, (x, y), ha in ((0, (1.12, 0), "left"), (90, (0, 1.12), "center"), (180, (-1.12, 0), "right"),
                            (270, (0, -1.12), "center")):
        ax.text(x, y, f"{deg}\u00b0", ha=ha, va="bottom" if deg == 90 else ("top" if deg == 270 else "center"),
                fontsize=7)
    ax.set_title("heading,\nnose (dot) first", fontsize=8)
    ax.set_xlim(-1.6, 1.6)
    ax.set_ylim(-1.5, 1.5)
    ax.set_aspect("equal")
    ax.axis("off")


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


def snapshot(frame, geometry=None, path=None, width=10.0, title=None, seconds=True, dpi=150):
    """Figure of one frame from above: beads grey, rods tapered, coloured by heading, nose
    marked, with the key to the colours beside it; axes in the frame's lengths (bead diameters d
    for frames read with their bead diameter as ``length_unit``). Title: :func:`frame_title`
    (time in seconds when ``seconds``, the rods' polar order) unless ``title`` is given. Saved to
    ``path`` if given. Returns the figure."""
    L = frame.box.lengths[:2] if geometry is None else geometry.extent
    height = max(2.0, (width - 1.2) * L[1] / L[0]) + 0.9
    fig = plt.figure(figsize=(width, height), layout="constrained")
    grid = fig.add_gridspec(1, 2, width_ratios=[width - 1.2, 1.2])
    ax = fig.add_subplot(grid[0])
    draw_snapshot(ax, frame, geometry)
    unit = length_label(frame)
    ax.set_xlabel(f"x ({unit})")
    ax.set_ylabel(f"y ({unit})")
    ax.set_title(title or frame_title(frame, seconds), fontsize=10)
    draw_heading_wheel(fig.add_subplot(grid[1]))
    if path:
        fig.savefig(path, dpi=dpi)
    return fig


def plot_profiles(profiles, path=None, labels=None, ax=None, unit="d", title=None):
    """Step plot of :class:`activegrain.analysis.Profile` objects against their coordinate (in
    ``unit``), each bin drawn over its whole width (the end bins too), the area fraction's species
    named on the axis."""
    fig = None
    if ax is None:
        fig, ax = plt.subplots(figsize=(7, 3.5), layout="constrained")
    for i, p in enumerate(profiles):
        ax.stairs(p.fraction, p.edges, baseline=None,
                  label=labels[i] if labels else SPECIES_LABELS.get(p.species, p.species))
    ax.set_xlabel(coord_label(profiles[0].coord, unit))
    species = {p.species for p in profiles}
    one = species.pop() if len(species) == 1 else None
    ax.set_ylabel(f"area fraction of {SPECIES_LABELS.get(one, one)}" if one else "area fraction")
    if title:
        ax.set_title(title, fontsize=10)
    ax.legend()
    if fig is not None and path:
        fig.savefig(path, dpi=150)
    return fig or ax.figure


def plot_map(x_edges, y_edges, phi, path=None, label="area fraction", unit="d", title=None):
    """Image of a 2D area-fraction map (``phi[nx, ny]``; NaN outside the cell), axes in ``unit``."""
    L = (x_edges[-1] - x_edges[0], y_edges[-1] - y_edges[0])
    fig, ax = plt.subplots(figsize=(8, max(1.8, 8 * L[1] / L[0]) + 0.9), layout="constrained")
    m = ax.pcolormesh(x_edges, y_edges, np.asarray(phi).T, cmap="viridis", vmin=0)
    fig.colorbar(m, ax=ax, label=label)
    ax.set_xlabel(f"x ({unit})")
    ax.set_ylabel(f"y ({unit})")
    if title:
        ax.set_title(title, fontsize=10)
    ax.set_aspect("equal")
    if path:
        fig.savefig(path, dpi=150)
    return fig


def kymograph(times, profiles, path=None, label=None, unit="d", seconds=True, title=None):
    """Image of profiles (rows: times) against the profile coordinate (in ``unit``); the colour
    bar names the area fraction's species (``label`` overrides it); time in seconds
    (``seconds``) or MD steps."""
    fractions = np.array([p.fraction for p in profiles])
    e = profiles[0].edges
    fig, ax = plt.subplots(figsize=(7, 4), layout="constrained")
    t = np.asarray(times, float)
    t_edges = np.concatenate([[t[0]], 0.5 * (t[1:] + t[:-1]), [t[-1]]]) if len(t) > 1 else [t[0] - 0.5, t[0] + 0.5]
    m = ax.pcolormesh(e, t_edges, fractions, shading="flat", cmap="viridis")
    species = profiles[0].species
    fig.colorbar(m, ax=ax, label=label or f"area fraction of {SPECIES_LABELS.get(species, species)}")
    ax.set_xlabel(coord_label(profiles[0].coord, unit))
    ax.set_ylabel("time (s)" if seconds else "MD step")
    if title:
        ax.set_title(title, fontsize=10)
    if path:
        fig.savefig(path, dpi=150)
    return fig


def movie(frames, path, geometry=None, fps=10, width=8.0, seconds=True):
    """Animate frames (any iterable, each drawn when it comes) into ``path``, each drawn as
    :func:`snapshot` draws it: .gif through Pillow (always available; it keeps the drawn images
    until it writes the file), .mp4 through ffmpeg where it is installed (each image piped to it
    when drawn). Returns the number of frames."""
    frames = iter(frames)
    first = next(frames, None)
    if first is None:
        raise ValueError("movie: no frames")
    if path.endswith(".gif"):
        writer = animation.PillowWriter(fps=fps)
    elif shutil.which("ffmpeg") and animation.writers.is_available("ffmpeg"):
        writer = animation.FFMpegWriter(fps=fps)
    else:
        raise RuntimeError("movie: writing mp4 needs ffmpeg, which is not installed; write a .gif")
    fig = snapshot(first, geometry, width=width, seconds=seconds)
    ax = fig.axes[0]
    xlabel, ylabel = ax.get_xlabel(), ax.get_ylabel()
    count = 0
    with writer.saving(fig, path, dpi=fig.dpi):
        for frame in itertools.chain([first], frames):
            ax.clear()
            draw_snapshot(ax, frame, geometry)
            ax.set_xlabel(xlabel)
            ax.set_ylabel(ylabel)
            ax.set_title(frame_title(frame, seconds), fontsize=10)
            writer.grab_frame()
            count += 1
    plt.close(fig)
    return count


def plot_growth_rates(k, rates, path=None, title=None):
    """Real (solid) and imaginary (dashed) parts of the growth rates lambda(k)."""
    fig, ax = plt.subplots(figsize=(6, 3.8), layout="constrained")
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
    if path:
        fig.savefig(path, dpi=150)
    return fig


def plot_point_force(x, curves, pf, path=None):
    """Density profiles around a moving point force: ``curves`` maps labels to rho(x)."""
    fig, ax = plt.subplots(figsize=(6, 3.8), layout="constrained")
    for label, rho in curves.items():
        ax.plot(x, rho, label=label)
    ax.axvline(0, color="k", lw=0.5)
    ax.axhline(pf.rho_plus, color="0.5", ls=":", lw=1)
    ax.set_xlabel("x (from the force, positive ahead)")
    ax.set_ylabel(r"bead density $\rho$")
    ax.set_title(rf"$\rho_+$ = {pf.rho_plus:.3f}, $\ell_+$ = {pf.ell_plus:.3g}")
    ax.legend()
    if path:
        fig.savefig(path, dpi=150)
    return fig


def phase_diagram(points, path, title=None):
    """Markers per phase on (phi_b, phi_r), as the paper's Figs. 2a and 3a. ``points``:
    {(phi_b, phi_r): (majority phase, seeds that show it, seeds)} (:func:`activegrain.sweep.majority`);
    a point where the seeds disagree shows its majority phase with ``k/n`` beside it."""
    fig, ax = plt.subplots(figsize=(6.0, 3.8), layout="constrained")
    for phase, (marker, face, edge) in PHASE_MARKERS.items():
        xy = [k for k, v in points.items() if v[0] == phase]
        if phase in _RARE_PHASES and not xy:
            continue
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
    fig.savefig(path, dpi=150)
    plt.close(fig)
    return path
