"""The phase of a run at each of its frames (jammed, condensed, segregated, flock, arrested,
isotropic) from measured observables: the frame's structure, and rates and time averages over
a window of the run in seconds, so that the verdict does not depend on how often the run was
dumped. Also the displacements between two frames the rates are made of."""
import collections
import enum
import warnings
from dataclasses import dataclass, field

import numpy as np

from ..geometry import Annulus
from .area_fractions import area_fraction_map, global_area_fractions
from .layers import _from_layer, find_layers, layer_sides
from .order import polar_order, tangential_polarization

WINDOW = 1.0
"""Default window of :func:`classify_frames`, in seconds: rates and time averages at a frame are
taken over the ``WINDOW`` seconds of the run up to it."""


class Phase(str, enum.Enum):
    """The phases :func:`classify_phase` tells apart, in the order a tie between them is broken
    (a majority vote over frames or seeds picks the first of the phases counted most often). A
    phase compares equal to its name and prints as it. ``ALIGNED`` is only the verdict on a
    single frame, which cannot tell a flock from arrested rods."""
    ISOTROPIC = "isotropic"
    FLOCK = "flock"
    ARRESTED = "arrested"
    SEGREGATED = "segregated"
    CONDENSED = "condensed"
    JAMMED = "jammed"
    ALIGNED = "aligned"

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
    """Thresholds of :func:`classify_phase` (see docs/python.rst for their reasons). Rates are
    per second: frames must carry times in seconds."""
    polar_order: float = 0.5      # time-averaged |<p>| from which rods count as aligned
    segregation: float = 0.3      # segregation index above which rods and beads demix
    layer_fraction: float = 0.5   # share of rods in active layers for an active interface
    layer_contrast: float = 0.1   # phi_b ahead minus behind a layer for it to be active
    layer_alignment: float = 0.5  # |<p>| of a layer's rods for it to be active
    jammed_fraction: float = 0.84  # phi_b + phi_r from which an arrested packing counts as jammed
    jammed_mobility: float = 0.1  # beads' rms displacement over the window per second, in bead
                                  # diameters per second, below which the beads count as arrested
    flock_speed: float = 0.05     # the rods' mean velocity along their mean heading, in rod lengths
                                  # per second, below which aligned rods are arrested, not a flock


class ShortRunWarning(UserWarning):
    """The run is shorter than the window: rates and averages are taken over the whole run."""


class SingleFrameWarning(UserWarning):
    """One frame only: classified by its structure (:func:`classify_phase` without a window)."""


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


_EDGE = 1e-6
"""Tolerance of a window's edges, relative to its length (frame times are steps times the time
step, not exact)."""


def _window_start(t, t_first, window):
    """Where the window of a frame at time ``t`` starts, in a run that starts at ``t_first``."""
    return max(t - window, t_first)


def _in_window(t, start, window):
    """Whether times ``t`` (a number or an array) lie in the window from ``start``."""
    eps = _EDGE * window
    return (t >= start - eps) & (t <= start + window + eps)


def window_of(times, k, window=WINDOW):
    """Indices of the frames in the window of frame ``k``: the frames whose times lie within the
    ``window`` seconds up to frame ``k`` ([t_k - window, t_k]); for a frame less than ``window``
    after the first, the first ``window`` seconds of the run instead (a window never reaches
    before the run); the whole run if it is shorter than ``window``. ``times``: the frames'
    times in seconds, in order."""
    times = np.asarray(times, float)
    if not window > 0:
        raise ValueError(f"window {window}: seconds, above 0")
    if np.any(np.diff(times) < 0):
        raise ValueError("the frames are not in time order")
    start = _window_start(times[k], times[0], window)
    return [int(j) for j in np.flatnonzero(_in_window(times, start, window))]


def _unwrapped(frames, positions):
    """Each row's displacement from the first frame to the last: the sum of the minimum-image
    displacements between consecutive frames."""
    total = np.zeros_like(positions[0])
    for fr, a, b in zip(frames[1:], positions[:-1], positions[1:]):
        total += fr.box.minimum_image(b - a)
    return total


def window_observables(frames, rods=None):
    """Rates and time averages over ``frames``, the frames of one run in a window (in time order,
    times in seconds; :func:`window_of`):

    ``window``: the seconds from the first frame to the last, over which the rates are taken;
    ``window_frames``: their number; ``P_mean``: the rods' polar order averaged over that time
    (trapezoidal rule); ``rod_speed``: the rods' mean velocity along their mean heading, in
    median rod lengths per second -- their mean displacement from the first frame to the last
    (each rod's summed over consecutive frames, minimum image) per second, projected on the
    direction of <p> at the first frame plus <p> at the last (positive: the rods move the way
    they point; a group that carries a few reversed rods along still moves forward);
    ``mobility``: the beads' rms displacement from the first frame to the last per second, in
    median bead diameters per second. Rods are matched by rod ID (those in every frame) and
    beads by atom ID. Rates need two frames at different times; with one they are NaN, and
    ``P_mean`` is that frame's polar order. ``rods``: the frames' :class:`RodSet` (computed if
    None)."""
    frames = list(frames)
    if not frames:
        raise ValueError("window_observables: no frames")
    rods = [fr.rods() for fr in frames] if rods is None else list(rods)
    times = np.array([fr.time for fr in frames], float)
    span = float(times[-1] - times[0])
    P = np.array([polar_order(r.axis)[1] if len(r) else 0.0 for r in rods])
    obs = {"window": span, "window_frames": len(frames),
           "P_mean": float(np.sum(0.5 * (P[1:] + P[:-1]) * np.diff(times)) / span) if span > 0 else float(P[-1]),
           "rod_speed": float("nan"), "mobility": float("nan")}
    if span <= 0:
        return obs
    if len(rods[0]):
        common = rods[0].ids
        for r in rods[1:]:
            common = np.intersect1d(common, r.ids)
        if len(common):
            at = [np.searchsorted(r.ids, common) for r in rods]      # a RodSet's IDs are sorted
            d = _unwrapped(frames, [r.centre[i] for r, i in zip(rods, at)]).mean(axis=0)
            heading = rods[0].axis[at[0]].mean(axis=0) + rods[-1].axis[at[-1]].mean(axis=0)
            norm = float(np.hypot(*heading))
            length = float(np.median(rods[0].length))
            obs["rod_speed"] = float(d @ heading / norm / length / span) if norm > 0 else 0.0
    beads = [fr.is_bead for fr in frames]
    if np.any(beads[0]):
        ids = frames[0].ids[beads[0]]
        for fr, b in zip(frames[1:], beads[1:]):
            if not np.array_equal(fr.ids[b], ids):
                raise ValueError(f"the frames at steps {frames[0].step} and {fr.step} do not hold the "
                                 "same beads (atom IDs)")
        d = _unwrapped(frames, [fr.pos[b, :2] for fr, b in zip(frames, beads)])
        diameter = 2 * float(np.median(frames[0].radius[beads[0]]))
        obs["mobility"] = float(np.sqrt(np.mean(np.sum(d * d, axis=1))) / diameter / span)
    return obs


def phase_observables(frame, geometry, thresholds=None, window=None, _rods=None):
    """The measured observables :func:`classify_phase` decides on.

    Of the frame itself (its structure): ``phi_b``, ``phi_r``, ``phi_total`` = phi_b + phi_r,
    ``n_rods``, the polar order ``P``, the ``segregation`` index, and the layer observables:
    those of the densest layer (``layer_*``, ``phi_ahead``, ``phi_behind``), and over up to two
    layers the number of *active* ones (aligned and with a bead contrast, per ``thresholds``)
    and the share of rods they hold (``active_layer_fraction``). Two active layers pointing at
    each other trap a condensate.

    Over ``window``, frames of the same run around it (:func:`window_of`; times in seconds):
    ``window``, ``window_frames``, ``P_mean``, ``rod_speed`` (rod lengths per second) and
    ``mobility`` (bead diameters per second), as :func:`window_observables` defines them.
    Without a window (a single frame) the rates are NaN and ``P_mean`` is ``P``. (``_rods``:
    the window frames' rod sets, when the caller has them.)
    """
    t = thresholds or PhaseThresholds()
    frames = [frame] if window is None else list(window)
    rods_of = list(_rods) if _rods is not None else [fr.rods() for fr in frames]
    rods = next((r for fr, r in zip(frames, rods_of) if fr is frame), None)
    rods = frame.rods() if rods is None else rods
    phi_b, phi_r = global_area_fractions(frame, geometry)
    obs = {"phi_b": phi_b, "phi_r": phi_r, "phi_total": phi_b + phi_r, "n_rods": len(rods),
           "P": polar_order(rods.axis)[1] if len(rods) else 0.0}
    obs.update(window_observables(frames, rods_of))
    if len(rods) == 0:  # beads only: nothing to order, segregate or layer
        obs.update(segregation=0.0, layer_fraction=0.0, layer_P=0.0, phi_ahead=float("nan"),
                   phi_behind=float("nan"), layer_contrast=0.0, layer_position=float("nan"),
                   layer_coord="", n_active_layers=0, active_layer_fraction=0.0)
        return obs
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


def decide_phase(obs, thresholds=None):
    """The phase that the observables ``obs`` (:func:`phase_observables`) give, in this order:

    1. ``jammed``: ``phi_total`` >= ``jammed_fraction`` and ``mobility`` < ``jammed_mobility``
       (dense and arrested; never without a window, whose mobility is NaN);
    2. ``condensed``: active layers hold at least ``layer_fraction`` of the rods;
    3. ``segregated``: ``segregation`` >= ``segregation``;
    4. ``P_mean`` >= ``polar_order``: ``flock`` if ``rod_speed`` >= ``flock_speed``, ``arrested``
       if below, ``aligned`` if it is NaN (one frame: flock or arrested cannot be told);
    5. ``isotropic`` otherwise.
    """
    t = thresholds or PhaseThresholds()
    if obs["phi_total"] >= t.jammed_fraction and obs["mobility"] < t.jammed_mobility:
        return Phase.JAMMED
    if obs["n_active_layers"] > 0 and obs["active_layer_fraction"] >= t.layer_fraction:
        return Phase.CONDENSED
    if obs["segregation"] >= t.segregation:
        return Phase.SEGREGATED
    if obs["P_mean"] >= t.polar_order:
        if not np.isfinite(obs["rod_speed"]):
            return Phase.ALIGNED
        return Phase.FLOCK if obs["rod_speed"] >= t.flock_speed else Phase.ARRESTED
    return Phase.ISOTROPIC


def classify_phase(frame, geometry, thresholds=None, window=None):
    """Jammed / condensed (by an active interface) / segregated / flock / arrested / isotropic.

    ``window``: the frames of the same run over which the rates and the time average of the
    polar order are taken (in time order, times in seconds, ``frame`` among them; usually the
    frames of :func:`window_of`, as :func:`classify_frames` gives them). Decided on
    :func:`phase_observables` by :func:`decide_phase`:

    1. ``jammed``: the total area fraction is at least ``jammed_fraction`` and the beads' rms
       displacement over the window is below ``jammed_mobility`` bead diameters per second;
    2. ``condensed``: active layers (aligned, |<p>| >= ``layer_alignment``, with the bead
       fraction ahead exceeding the one behind by ``layer_contrast``; one layer, or two
       trapping a condensate) hold at least ``layer_fraction`` of the rods;
    3. ``segregated``: segregation index >= ``segregation``;
    4. the polar order averaged over the window is at least ``polar_order``: ``flock`` when the
       rods advance along their axes by at least ``flock_speed`` rod lengths per second,
       ``arrested`` (aligned and held still, e.g. pressed against a wall) when slower;
    5. ``isotropic`` otherwise.

    Without a window the frame alone is classified by what one frame shows: never jammed (no
    mobility), and aligned rods (|<p>| >= ``polar_order``) are ``aligned``, not flock or arrested.
    ``thresholds``: a :class:`PhaseThresholds`, the defaults if None.
    """
    t = thresholds or PhaseThresholds()
    obs = phase_observables(frame, geometry, t, window)
    return PhaseResult(decide_phase(obs, t), obs)


def iter_phases(frames, geometry, window=WINDOW, thresholds=None, which=None):
    """Yield ``(k, frame, PhaseResult)`` for the frames ``which`` of a run (indices from 0;
    default: all), in the run's order, each as soon as the frames of its window have been read:
    the loop of :func:`classify_frames`, with its windows, verdicts, warnings and errors.

    ``frames``: any iterable of the run's frames (a dump's :meth:`activegrain.io.Dump.frames`, a
    list), taken one at a time; only the frames of the windows still open are held (a deque, with
    their rod sets), so that memory does not grow with the length of the run, and reading stops
    after the window of the last frame in ``which``."""
    if not window > 0:
        raise ValueError(f"window {window}: seconds, above 0")
    wanted = None if which is None else set(which)
    if wanted and min(wanted) < 0:
        raise ValueError(f"frame {min(wanted)}: the frames of a run read as it comes are counted from 0")
    last_wanted = None if wanted is None else max(wanted, default=-1)
    held = collections.deque()      # (index, frame) of the windows still open, in time order
    rods = {}                       # the held frames' rod sets, by index, each made once
    pending = collections.deque()   # (index, window start) of the wanted frames not yet classified
    t_first = t_last = None
    largest_gap = 0.0

    def rods_of(j, frame):
        if j not in rods:
            rods[j] = frame.rods()
        return rods[j]

    def classified(k, start):
        members = [(j, fr) for j, fr in held if _in_window(fr.time, start, window)]
        frame = next(fr for j, fr in held if j == k)
        if members[-1][1].time <= members[0][1].time:
            raise ValueError(f"the {window:g} s window of the frame at step {frame.step} holds no other "
                             f"frame: frames are up to {largest_gap:g} s apart; give a window of at least "
                             f"{largest_gap:g} s (--window) or dump more often")
        obs = phase_observables(frame, geometry, thresholds, [fr for _, fr in members],
                                [rods_of(j, fr) for j, fr in members])
        return k, frame, PhaseResult(decide_phase(obs, thresholds), obs)

    k = -1
    for k, frame in enumerate(frames):
        t = frame.time
        if t_first is None:
            t_first = t
        elif t < t_last:
            raise ValueError("the frames are not in time order")
        else:
            largest_gap = max(largest_gap, t - t_last)
        t_last = t
        while pending and not _in_window(t, pending[0][1], window):     # its window is whole
            yield classified(*pending.popleft())
        held.append((k, frame))
        if wanted is None or k in wanted:
            pending.append((k, _window_start(t, t_first, window)))
        # the windows still to come start no earlier than the first pending one's (with none
        # pending, than the current frame's): the frames before it are in none of them
        oldest = pending[0][1] if pending else _window_start(t, t_first, window)
        while held[0][1].time < oldest - _EDGE * window:
            rods.pop(held.popleft()[0], None)
        if last_wanted is not None and k >= last_wanted and not pending:
            return
    n = k + 1
    if n == 0:
        raise ValueError("no frames to classify")
    beyond = sorted(j for j in wanted or () if j >= n)
    if beyond:
        raise ValueError(f"no frame {beyond[0]} (the run has {n})")
    if n == 1:
        warnings.warn(f"a single frame (step {held[0][1].step}): classified by what one frame shows, its "
                      "structure (no rates: never jammed, and aligned rods are 'aligned', not flock or "
                      "arrested)", SingleFrameWarning, stacklevel=3)
        for k, _ in pending:
            yield k, held[0][1], classify_phase(held[0][1], geometry, thresholds)
        return
    if t_last - t_first < window * (1 - _EDGE):
        warnings.warn(f"the run spans {t_last - t_first:g} s, less than the {window:g} s window: "
                      "rates and averages over the whole run", ShortRunWarning, stacklevel=3)
    while pending:
        yield classified(*pending.popleft())


def classify_frames(frames, geometry, window=WINDOW, thresholds=None, which=None):
    """The phase of a run at its frames ``which`` (indices into ``frames``; default: all), each
    with its window of ``window`` seconds (:func:`window_of`) from all of ``frames``: the same
    run, in time order, times in seconds. Returns a list of :class:`PhaseResult`, in the order of
    ``which``.

    The verdict at a frame depends on the run, not on which frames are classified: thin the
    output with ``which``, not ``frames``. A window must hold two frames: ValueError where it
    holds only its own frame (frames further apart than ``window``); a :class:`ShortRunWarning`
    where the run is shorter than ``window`` (its rates are then over the whole run). A single
    frame is classified by what it shows (:func:`classify_phase` without a window), with a
    :class:`SingleFrameWarning`.

    ``frames`` may be a list or any iterable, such as the frames of a dump as
    :class:`activegrain.io.Dump` reads them, which is read once, holding only the frames of the
    windows still open (:func:`iter_phases`); ``which`` then counts from 0 (a list also takes
    negative indices)."""
    if hasattr(frames, "__len__") and which is not None and len(frames):
        which = [k % len(frames) for k in which]
    results = {k: result for k, _, result in iter_phases(frames, geometry, window, thresholds, which)}
    return [results[k] for k in (sorted(results) if which is None else which)]
