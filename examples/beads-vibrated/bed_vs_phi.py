"""The bead bed against its area fraction: agitation, bond order and mobility (beads alone).

Runs in.beads-vibrated (periodic, paper parameters, plates rough with the given rms slope) at
each bead area fraction phi_b and prints one table row: the rms horizontal bead speed as a
fraction of the plate speed A omega in the first and the last third of the run (steady, or
decaying), the bond-orientational order |<psi6>| (global, over all beads, six nearest
neighbours in the plane), the mean local |psi6_j|, the exponent eta6 of the decay of the bond
order correlation g6(r) ~ r^-eta6 (hard disks: a fluid decays exponentially, the hexatic with
eta6 <= 1/4, a crystal not at all) and the beads' mean-squared displacement over 1 s and over
the last half of the run in units of d^2 (a crystal stays well below 1).
Usage, from this folder (minutes per point):
    python3 bed_vs_phi.py [--phi 0.55,0.65,0.7,0.75,0.8,0.85] [--rough 0.01] [--time 10] [--lmp PATH]
"""
import argparse
import os
import subprocess
import tempfile

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
D = 1e-3                        # bead diameter (m)
A_OMEGA = 4e-5 * 2 * np.pi * 200   # plate speed amplitude (m/s)
FRAME = 0.1                     # s between frames


def run(lmp, phi, rough, length, time, nx, ny, dt=1e-5, resting="no", seed=4928):
    """Frames (list of (positions unwrapped (n,2), velocities (n,2))) and the box (Lx, Ly)."""
    every = int(round(FRAME / dt))
    with tempfile.TemporaryDirectory() as tmp:
        deck = os.path.join(tmp, "in.bed")
        dump = os.path.join(tmp, "bed.dump")
        with open(deck, "w") as f:
            f.write(f"variable steps index 0\ninclude {HERE}/in.beads-vibrated\n"
                    f"dump bed all custom {every} {dump} id xu yu vx vy\n"
                    "dump_modify bed sort id format float %.9g\nthermo 100000\n"
                    f"run {int(round(time / dt))}\n")
        subprocess.run([lmp, "-in", deck, "-log", "none", "-screen", "none", "-var", "phi", repr(phi),
                        "-var", "rough", repr(rough), "-var", "rough_length", repr(length),
                        "-var", "nx", str(nx), "-var", "ny", str(ny), "-var", "dt", repr(dt), "-var", "resting", resting, "-var", "seed", str(seed)],
                       check=True)
        return read_dump(dump)


def read_dump(path):
    frames, box = [], None
    with open(path) as f:
        lines = f.read().split("\n")
    i = 0
    while i < len(lines) and lines[i]:
        n = int(lines[i + 3])
        bounds = [list(map(float, lines[i + 5 + k].split()[:2])) for k in range(2)]
        box = np.array([b[1] - b[0] for b in bounds])
        data = np.array([list(map(float, l.split())) for l in lines[i + 9:i + 9 + n]])
        frames.append((data[:, 1:3], data[:, 3:5]))
        i += 9 + n
    return frames, box


def psi6(r, box):
    """Per-bead psi6 = mean over its six nearest in-plane neighbours of exp(6 i angle)."""
    d = r[None, :, :] - r[:, None, :]
    d -= box * np.round(d / box)
    dist = np.hypot(d[..., 0], d[..., 1])
    np.fill_diagonal(dist, np.inf)
    nn = np.argsort(dist, axis=1)[:, :6]
    rows = np.arange(len(r))[:, None]
    return np.exp(6j * np.arctan2(d[rows, nn, 1], d[rows, nn, 0])).mean(axis=1), d, dist


def g6_exponent(r, box):
    """eta6 of g6(r) = <psi6_j psi6_k*> over pairs at distance r ~ r^-eta6, fitted from 2 d to L/2."""
    p, _, dist = psi6(r, box)
    corr = np.real(p[:, None] * np.conj(p[None, :]))
    edges = np.linspace(2 * D, box.min() / 2, 12)
    centres, g = [], []
    for lo, hi in zip(edges[:-1], edges[1:]):
        sel = (dist >= lo) & (dist < hi)
        if sel.any():
            centres.append(0.5 * (lo + hi))
            g.append(corr[sel].mean())
    centres, g = np.array(centres), np.array(g)
    if np.any(g <= 0):
        return np.inf    # decays to noise: fluid
    return -np.polyfit(np.log(centres), np.log(g), 1)[0]


def measure(frames, box):
    n = len(frames)
    vh = np.array([np.sqrt(np.mean(np.sum(v ** 2, axis=1))) for _, v in frames]) / A_OMEGA
    late = frames[n // 2:]
    local = [psi6(r % box, box)[0] for r, _ in late[::5]]
    glob = np.mean([abs(p.mean()) for p in local])
    loc = np.mean([np.abs(p).mean() for p in local])
    eta = np.median([g6_exponent(r % box, box) for r, _ in late[::10]])
    lag1 = int(round(1.0 / FRAME))
    msd1 = np.mean([np.mean(np.sum((frames[k + lag1][0] - frames[k][0]) ** 2, axis=1))
                    for k in range(n // 2, n - lag1)]) / D ** 2
    msd_half = np.mean(np.sum((frames[-1][0] - frames[n // 2][0]) ** 2, axis=1)) / D ** 2
    third = max(1, n // 3)
    return dict(vh_first=vh[1:third].mean(), vh_last=vh[-third:].mean(), psi6=glob, psi6_local=loc, eta6=eta,
                msd1=msd1, msd_half=msd_half)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--phi", default="0.55,0.65,0.7,0.72,0.75,0.8,0.85")
    ap.add_argument("--rough", type=float, default=0.01)
    ap.add_argument("--length", type=float, default=1e-3)
    ap.add_argument("--time", type=float, default=10.0)
    ap.add_argument("--nx", type=int, default=24)
    ap.add_argument("--ny", type=int, default=14)
    ap.add_argument("--dt", type=float, default=1e-5)
    ap.add_argument("--seed", type=int, default=4928, help="the deck's seed (the beads' start heights)")
    ap.add_argument("--resting", default="no", help="pair gran/impulse resting (yes, newton, no or a speed)")
    ap.add_argument("--lmp", default=os.environ.get("ACTIVEGRAIN_LMP", os.path.join(HERE, "..", "..", "build", "lmp")))
    a = ap.parse_args()
    print(f"Beads alone, {2 * a.nx * a.ny} beads, rough {a.rough:g} (L {a.length * 1e3:g} mm), {a.time:g} s, dt {a.dt:g}, resting {a.resting}\n")
    print("| phi_b | v_h/(A omega), first third | last third | abs(psi6) | local abs(psi6_j) | eta6 | MSD 1 s (d^2) "
          "| MSD last half (d^2) |\n|---|---|---|---|---|---|---|---|")
    for phi in (float(s) for s in a.phi.split(",")):
        m = measure(*run(a.lmp, phi, a.rough, a.length, a.time, a.nx, a.ny, a.dt, a.resting, a.seed))
        print(f"| {phi:g} | {m['vh_first']:.4f} | {m['vh_last']:.4f} | {m['psi6']:.2f} | {m['psi6_local']:.2f} "
              f"| {m['eta6']:.2f} | {m['msd1']:.3g} | {m['msd_half']:.3g} |", flush=True)


if __name__ == "__main__":
    main()
