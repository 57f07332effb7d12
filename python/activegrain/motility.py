"""Single-rod motility: speed along the axis, mean squared displacement, persistence.

Rods perform a persistent random walk nose-first (Kumar et al. 2014: 3.6 mm/s mean,
2.5 mm/s s.d.). For a rod moving at speed v whose axis decorrelates as
<p(t).p(0)> = exp(-t/tau) (2D), the mean squared displacement is
MSD(t) = 2 v^2 tau^2 (t/tau - 1 + exp(-t/tau)): ballistic v^2 t^2 at t << tau,
diffusive 2 v^2 tau t at t >> tau.

A persistence time is measured only when the rods' headings have decorrelated within the lags
measured: a tau longer than the longest lag (at most half the tracked time by default) is the
extrapolation of the first slope of a curve that has not yet decayed by a factor e, and is
reported as unresolved (None, with an :class:`UnresolvedPersistenceWarning`), not as a number.
"""
import warnings
from dataclasses import dataclass

import numpy as np
from scipy.optimize import curve_fit


@dataclass
class RodTracks:
    """Rod trajectories: ``t`` (n_frames,), ``ids`` (n_rods,), ``centre`` unwrapped
    (n_frames, n_rods, 2), ``axis`` (n_frames, n_rods, 2), ``velocity`` or None."""
    t: np.ndarray
    ids: np.ndarray
    centre: np.ndarray
    axis: np.ndarray
    velocity: np.ndarray = None


def rod_tracks(frames):
    """Collect rod trajectories from frames (all with the same rods), unwrapping the
    centres across periodic boundaries by the minimum image between frames."""
    t, centres, axes, vels, ids, box = [], [], [], [], None, None
    for fr in frames:
        rods = fr.rods()
        if ids is None:
            ids, box = rods.ids, fr.box
        elif not np.array_equal(ids, rods.ids):
            raise ValueError(f"rod_tracks: the rods change at step {fr.step}")
        t.append(fr.time)
        centres.append(rods.centre)
        axes.append(rods.axis)
        vels.append(rods.velocity)
    if ids is None:
        raise ValueError("rod_tracks: no frames")
    c = np.array(centres)
    steps = box.minimum_image(np.diff(c, axis=0))
    c = np.concatenate([c[:1], c[0] + np.cumsum(steps, axis=0)])
    v = None if any(x is None for x in vels) else np.array(vels)
    return RodTracks(np.array(t), ids, c, np.array(axes), v)


def axial_speed(tracks, use_velocities=True):
    """Speed along the rod axis, v . p, per frame and rod (n_frames, n_rods).

    Uses the dumped velocities when present and ``use_velocities``; otherwise the centre
    displacement between frames (central differences), which averages out the vibration
    when frames are further apart than a drive period.
    """
    if use_velocities and tracks.velocity is not None:
        v = tracks.velocity
    else:
        v = np.gradient(tracks.centre, tracks.t, axis=0)
    return np.sum(v * tracks.axis, axis=-1)


def msd(centre, max_lag=None):
    """Time-averaged mean squared displacement of ``centre`` (n_frames, n_rods, 2) at
    lags 0..max_lag frames, averaged over rods. Returns (lags, msd)."""
    c = np.asarray(centre, float)
    if c.ndim == 2:
        c = c[:, None, :]
    n = len(c)
    max_lag = min(max_lag or n // 2, n - 1)
    lags = np.arange(max_lag + 1)
    out = np.array([np.mean(np.sum((c[k:] - c[:n - k]) ** 2, axis=-1)) for k in lags])
    return lags, out


def orientation_correlation(axis, max_lag=None):
    """<p(t+lag) . p(t)> averaged over t and rods. Returns (lags, correlation)."""
    p = np.asarray(axis, float)
    if p.ndim == 2:
        p = p[:, None, :]
    n = len(p)
    max_lag = min(max_lag or n // 2, n - 1)
    lags = np.arange(max_lag + 1)
    return lags, np.array([np.mean(np.sum(p[k:] * p[:n - k], axis=-1)) for k in lags])


def persistence_time(lag_t, correlation, floor=0.2):
    """tau from a least-squares fit of log C = -t/tau over the lags where C > ``floor``."""
    lag_t, correlation = np.asarray(lag_t, float), np.asarray(correlation, float)
    ok = correlation > floor
    stop = np.argmin(ok) if not ok.all() else len(ok)  # first lag below the floor
    t, c = lag_t[:stop], correlation[:stop]
    if len(t) < 2:
        raise ValueError("persistence_time: the correlation drops below the floor at the first lag")
    slope = np.sum(t * np.log(c)) / np.sum(t * t)  # line through C(0) = 1
    return float(-1.0 / slope)


def persistent_walk_msd(t, speed, tau):
    t = np.asarray(t, float)
    return 2 * speed ** 2 * tau ** 2 * (t / tau - 1 + np.exp(-t / tau))


def fit_persistent_walk(lag_t, msd_values):
    """Fit (speed, tau) of :func:`persistent_walk_msd` to a measured MSD curve."""
    lag_t, m = np.asarray(lag_t, float), np.asarray(msd_values, float)
    ok = lag_t > 0
    t, m = lag_t[ok], m[ok]
    v0 = np.sqrt(m[0]) / t[0]
    tau0 = max(t[-1] / 10, t[0])
    (v, tau), _ = curve_fit(lambda x, v, tau: np.log(persistent_walk_msd(x, v, tau)), t, np.log(m),
                            p0=(v0, tau0), bounds=([0, 1e-12 * t[0]], [np.inf, np.inf]))
    return float(v), float(tau)


class UnresolvedPersistenceWarning(UserWarning):
    """A persistence time longer than the longest lag measured: the track is too short for it."""


def length_unit_name(length_unit):
    """The unit of lengths read with ``length_unit`` from an SI dump (metres): mm for 1e-3."""
    return {1.0: "m", 1e-3: "mm", 1e-6: "um"}.get(length_unit, f"{length_unit:g} m")


def motility_summary(tracks, max_lag=None, use_velocities=True, length="mm", time="s"):
    """Speed along the axis (mean, s.d.), persistence time from the orientation correlation,
    and (speed, tau) fitted to the MSD, with the units of each (``units``: the tracks' units of
    ``length`` and ``time``, for the example decks' dumps read with ``length_unit=1e-3`` and
    their time step mm and s), the tracked time (``tracked_duration``) and the longest lag of the
    correlation and the MSD (``longest_lag``, ``max_lag`` frames, default half of them).

    A persistence time longer than ``longest_lag`` is not resolved by the tracks: it is None,
    its ``*_resolved`` flag False, and an :class:`UnresolvedPersistenceWarning` says so."""
    u = axial_speed(tracks, use_velocities)
    dt = float(np.median(np.diff(tracks.t)))
    lags, C = orientation_correlation(tracks.axis, max_lag)
    lags_m, M = msd(tracks.centre, max_lag)
    v_fit, tau_fit = fit_persistent_walk(lags_m * dt, M)
    longest = float(lags[-1] * dt)
    duration = float(tracks.t[-1] - tracks.t[0])
    summary = {"rods": len(tracks.ids), "frames": len(tracks.t), "tracked_duration": duration,
               "longest_lag": longest, "axial_speed_mean": float(u.mean()), "axial_speed_sd": float(u.std()),
               "msd_speed": v_fit}
    unresolved = []
    for name, tau in (("persistence_time", persistence_time(lags * dt, C)), ("msd_persistence_time", tau_fit)):
        resolved = tau <= longest
        summary[name] = tau if resolved else None
        summary[name + "_resolved"] = resolved
        if not resolved:
            unresolved.append(name)
    if unresolved:
        warnings.warn(f"persistence time not resolved ({' and '.join(unresolved)} null): longer than the longest "
                      f"lag, {longest:g} {time} (heading correlation {C[-1]:.2f} there), of {duration:g} {time} "
                      "tracked; track the rods over several persistence times", UnresolvedPersistenceWarning,
                      stacklevel=2)
    speed = f"{length}/{time}"
    summary["units"] = {"tracked_duration": time, "longest_lag": time, "axial_speed_mean": speed,
                        "axial_speed_sd": speed, "msd_speed": speed, "persistence_time": time,
                        "msd_persistence_time": time}
    return summary
