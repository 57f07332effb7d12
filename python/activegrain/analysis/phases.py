"""The phase of a frame (jammed, condensed, segregated, flock, isotropic) from measured
observables, and the displacements between frames it uses."""
import enum
from dataclasses import dataclass, field

import numpy as np

from ..geometry import Annulus
from .area_fractions import area_fraction_map, global_area_fractions
from .layers import _from_layer, find_layers, layer_sides
from .order import polar_order, tangential_polarization


class Phase(str, enum.Enum):
    """The phases :func:`classify_phase` tells apart, in the order a tie between them is broken
    (a majority vote over frames or seeds picks the first of the phases counted most often). A
    phase compares equal to its name and prints as it."""
    ISOTROPIC = "isotropic"
    FLOCK = "flock"
    SEGREGATED = "segregated"
    CONDENSED = "condensed"
    JAMMED = "jammed"

    def __str__(self):
        return self.value

    __format__ = str.__format__


def majority_phase(counts):
    """The phase counted most often in ``counts`` ({phase: count}); ties go to the phase that
    comes first in :class:`Phase`."""
    order = list(Phase)
    return max(counts, key=lambda p: (counts[p], -order.index(Phase(p))))


@dataclass(frozen=True)
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
class PhaseResult:
    phase: Phase
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


def classify_phase(frame, geometry, thresholds=None, previous=None):
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

    ``thresholds``: a :class:`PhaseThresholds`, the defaults if None.
    """
    t = thresholds or PhaseThresholds()
    obs = phase_observables(frame, geometry, t, previous)
    if obs["phi_total"] >= t.jammed_fraction and obs["mobility"] < t.jammed_mobility:
        phase = Phase.JAMMED
    elif obs["n_active_layers"] > 0 and obs["active_layer_fraction"] >= t.layer_fraction:
        phase = Phase.CONDENSED
    elif obs["segregation"] >= t.segregation:
        phase = Phase.SEGREGATED
    elif obs["P"] >= t.polar_order and (previous is None or obs["rod_drift"] >= t.flock_drift):
        phase = Phase.FLOCK
    else:
        phase = Phase.ISOTROPIC
    return PhaseResult(phase, obs)
