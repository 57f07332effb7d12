"""The condensate of an annulus: its dense arc, the arc's drift round the ring and the rods that
press on its ends (the trap of the paper's Fig. 3)."""
from dataclasses import dataclass, replace

import numpy as np

from ..geometry import Annulus
from .area_fractions import area_fraction_profile
from .phases import _bead_displacements


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


def trap_spans(times, rods_at_start, rods_at_stop, drift, min_rods=3, max_drift=0.3, max_gap=5.0):
    """The spans of time in which a condensate is trapped (the paper's Fig. 3c): per frame, at
    least ``min_rods`` rods press on each end of the arc and its beads drift round the ring no
    faster than ``max_drift`` (length per time; NaN drift, as in a first frame, counts as held).
    Trapped frames at most ``max_gap`` apart in time are one span (a layer that loses a few
    rods for a moment does not end it). Returns ``[(first, last), ...]``: the times of
    each span's first and last trapped frame."""
    times = np.asarray(times, float)
    drift = np.asarray(drift, float)
    held = ((np.asarray(rods_at_start) >= min_rods) & (np.asarray(rods_at_stop) >= min_rods)
            & ~(np.abs(drift) > max_drift))
    spans = []
    for t in times[held]:
        if spans and t - spans[-1][1] <= max_gap + 1e-9 * max(1.0, abs(t)):
            spans[-1][1] = t
        else:
            spans.append([t, t])
    return [(float(a), float(b)) for a, b in spans]
