"""Calibrate the plates' roughness against single rods walking on bare plates (Kumar et al. 2014:
speed along the axis 3.6 +- 2.5 mm/s over 1-s windows, a persistent random walk, nose first).

For each roughness (fix wall/impulse `rough S L`), runs in.single-rod with one rod per run (no
neighbours, periodic 20 mm box) for several seeds, and prints one table row: the speed along the
rod's own axis over 1-s windows (mean and s.d. over all windows of all rods), the heading
autocorrelation time (C(t) = <cos(theta(t0 + t) - theta(t0))> fitted by exp(-t/tau) over lags up
to a third of the run), the mean-squared displacement at 1 and 10 s (or the longest lag) and its
local exponents, and the MSD of a persistent random walk at the mean speed along the axis with
heading time tau (2 v^2 tau^2 (t/tau - 1 + exp(-t/tau))), to compare with the measured one.
Usage, from this folder (minutes):
    python3 calibrate.py [--rough 0.04,0.05,0.06,0.07] [--length 5e-6] [--seeds 8] [--time 30] [--dt 1e-5] [--resting no]
                         [--tangential stick|"compliant R"] [--lmp PATH]
    python3 calibrate.py --figure out/trajectories.png --rough 0.06 --time 60   # and a few trajectories
"""
import argparse
import os

import numpy as np

import measure
import rodtrack

SETTLE = 0.5    # s: from rest to steady walking
WINDOW = 1.0    # s: the experiment's averaging window for the speed


def track(path, dt):
    """Per rod: times (s), in-plane COM (m), heading angle (rad) of the in-plane polar axis."""
    out = []
    for rows in rodtrack.read_local_dump(path).values():
        t = rows[:, 0] * dt
        keep = t >= SETTLE
        p = rodtrack.polar_axis(rows[keep, 4:8])
        out.append((t[keep] - t[keep][0], rows[keep, 1:3], np.unwrap(np.arctan2(p[:, 1], p[:, 0]))))
    return out


def window_speeds(t, r, theta):
    """Speed along the axis in consecutive 1-s windows: sum of in-plane steps . p / window."""
    step = np.diff(r, axis=0)
    along = step[:, 0] * np.cos(theta[:-1]) + step[:, 1] * np.sin(theta[:-1])
    per = int(round(WINDOW / (t[1] - t[0])))
    n = len(along) // per
    return along[:n * per].reshape(n, per).sum(axis=1) / WINDOW


def heading_correlation(t, theta, lags):
    """<cos(theta(t + lag) - theta(t))> over t, for lags in samples."""
    return np.array([np.cos(theta[k:] - theta[:len(theta) - k]).mean() for k in lags])


def msd(r, lags):
    return np.array([np.mean(np.sum((r[k:] - r[:len(r) - k]) ** 2, axis=1)) for k in lags])


def decay_time(lag, C):
    """tau of C = exp(-lag / tau), least squares on log C through the origin (where C > 0.2): the
    heading time even where the runs are shorter than it."""
    keep = C > 0.2
    return -np.sum(lag[keep] ** 2) / np.sum(lag[keep] * np.log(C[keep]))


def persistent_walk_msd(speed, tau, t):
    """2-D walk at constant speed whose heading decorrelates as exp(-t/tau)."""
    return 2 * speed ** 2 * tau ** 2 * (t / tau - 1 + np.exp(-t / tau))


def measure_roughness(lmp, rough, length, seeds, time, dt=1e-5, resting="no", tangential="stick"):
    tracks = []
    for seed in range(1, seeds + 1):
        tag = f"cal_S{rough:g}_L{length:g}_dt{dt:g}_r{resting}_t{tangential.replace(' ', '')}_s{seed}"
        measure.run_deck(lmp, tag, dt=dt, time=time + SETTLE, rough=rough, rough_length=length, seed=seed, nside=1,
                         resting=resting, tangential=tangential)
        tracks += track(os.path.join(measure.HERE, "out", f"rods_{tag}.local"), dt)
    sample = tracks[0][0][1]
    speeds = np.concatenate([window_speeds(*tr) for tr in tracks])
    lags = np.unique(np.round(np.logspace(0, np.log10(len(tracks[0][0]) / 3), 60)).astype(int))
    tau_lag = lags * sample
    C = np.mean([heading_correlation(t, th, lags) for t, _, th in tracks], axis=0)
    M = np.mean([msd(r, lags) for _, r, _ in tracks], axis=0)
    tau = decay_time(tau_lag, C)
    planar = np.mean([np.mean(np.linalg.norm(np.diff(r[::10], axis=0), axis=1)) / (10 * sample)
                      for _, r, _ in tracks])
    at = lambda s: np.interp(np.log(s), np.log(tau_lag), M)
    slope = lambda s: np.interp(np.log(s), np.log(tau_lag[1:]), np.diff(np.log(M)) / np.diff(np.log(tau_lag)))
    return dict(rough=rough, length=length, n=len(speeds), mean=speeds.mean(), sd=speeds.std(), tau=tau,
                planar=planar, msd1=at(1.0), msd10=at(min(10.0, tau_lag[-1])), slope01=slope(0.1),
                slope10=slope(min(10.0, tau_lag[-2])),
                prw10=persistent_walk_msd(speeds.mean(), tau, min(10.0, tau_lag[-1])), tracks=tracks)


def figure(result, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(5, 5))
    for t, r, theta in result["tracks"][:6]:
        xy = (r - r[0]) * 1e3
        ax.plot(xy[:, 0], xy[:, 1], lw=0.8)
        ax.plot(xy[-1, 0], xy[-1, 1], "k.", ms=3)
    ax.set_aspect("equal")
    ax.set_xlabel("x (mm)")
    ax.set_ylabel("y (mm)")
    ax.set_title(f"single rods, rough {result['rough']:g} (L {result['length'] * 1e3:g} mm), "
                 f"{result['tracks'][0][0][-1]:.0f} s")
    fig.tight_layout()
    fig.savefig(path, dpi=120)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--rough", default="0.04,0.05,0.06,0.07")
    ap.add_argument("--length", type=float, default=5e-6)
    ap.add_argument("--seeds", type=int, default=8)
    ap.add_argument("--time", type=float, default=30.0)
    ap.add_argument("--dt", type=float, default=1e-5)
    ap.add_argument("--resting", default="no", help="pair gran/impulse resting (yes, newton, no or a speed)")
    ap.add_argument("--tangential", default="stick", help='rod-plate tangential law: stick or "compliant R"')
    ap.add_argument("--lmp", default=measure.default_lmp())
    ap.add_argument("--figure", help="draw the trajectories of the first roughness into this file")
    a = ap.parse_args()
    print(f"Single rods on rough plates: {a.seeds} rods x {a.time:g} s each (after {SETTLE:g} s), dt {a.dt:g}, "
          f"resting {a.resting}, tangential {a.tangential}\n"
          "Experiment (Kumar et al. 2014): speed along axis 3.6 +- 2.5 mm/s, persistent random walk\n")
    print("| rms slope | corr. length (mm) | speed along axis, 1-s windows (mm/s) | s.d. (mm/s) | in-plane speed (mm/s) "
          "| heading time (s) | MSD 1 s (mm^2) | MSD 10 s (mm^2) | PRW MSD 10 s (mm^2) | MSD exponent 0.1 s / 10 s |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for i, rough in enumerate(float(s) for s in a.rough.split(",")):
        m = measure_roughness(a.lmp, rough, a.length, a.seeds, a.time, a.dt, a.resting, a.tangential)
        print(f"| {rough:g} | {a.length * 1e3:g} | {m['mean'] * 1e3:+.2f} | {m['sd'] * 1e3:.2f} | {m['planar'] * 1e3:.2f} "
              f"| {m['tau']:.2f} | {m['msd1'] * 1e6:.2f} | {m['msd10'] * 1e6:.1f} | {m['prw10'] * 1e6:.1f} "
              f"| {m['slope01']:.2f} / {m['slope10']:.2f} |", flush=True)
        if a.figure and i == 0:
            figure(m, a.figure)


if __name__ == "__main__":
    main()
