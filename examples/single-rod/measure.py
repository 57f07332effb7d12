"""Single-rod speed tables on flat plates (the deterministic model): time step, plate friction and
restitution, drive, spheres.

Runs in.single-rod (4 rods far apart per run, several seeds) and prints mean and spread of the
speed along the rods' own axes. Long: minutes. Usage, from this folder:
    python3 measure.py [dt|friction|restitution|drive|spheres|ranks|order|all] [--lmp PATH] [--seeds N]
"""
import argparse
import os
import subprocess
import sys

import numpy as np

import rodtrack

HERE = os.path.dirname(os.path.abspath(__file__))

def default_lmp():
    return os.environ.get("ACTIVEGRAIN_LMP", os.path.join(HERE, "..", "..", "build", "lmp"))


def run_deck(lmp, tag, dt=1e-5, time=2.0, np_ranks=1, mpirun="mpirun", **vars_):
    """Run in.single-rod; the rods' dump is out/rods_<tag>.local."""
    os.makedirs(os.path.join(HERE, "out"), exist_ok=True)
    cmd = [lmp, "-in", "in.single-rod", "-log", "none", "-screen", "none", "-var", "tag", tag,
           "-var", "dt", repr(dt), "-var", "time", repr(time)]
    for k, v in vars_.items():
        cmd += ["-var", k, str(v)]
    if np_ranks > 1:
        cmd = [mpirun, "--oversubscribe", "-np", str(np_ranks)] + cmd
    subprocess.run(cmd, cwd=HERE, check=True)


def run(lmp, tag, dt=1e-5, **kw):
    """Speeds along the own axis of the rods of one run of in.single-rod."""
    run_deck(lmp, tag, dt=dt, **kw)
    res = rodtrack.summarize(os.path.join(HERE, "out", f"rods_{tag}.local"), dt)
    return [v[0] for v in res.values()]


def speeds(lmp, label, seeds, **kw):
    """Mean, s.d. and number of the rods' speeds over seeds; flat plates unless kw set rough (the
    tables are the deterministic model's; calibrate.py measures on rough plates)."""
    kw.setdefault("rough", 0)
    s = []
    for seed in range(1, seeds + 1):
        s += run(lmp, f"{label}_s{seed}", seed=seed, **kw)
    s = np.array(s) * 1e3
    return s.mean(), s.std(), len(s)


def table(title, column, rows):
    print(f"\n{title}\n| {column} | speed along axis (mm/s) | s.d. (mm/s) | rods |\n|---|---|---|---|")
    for value, (mean, sd, n) in rows:
        print(f"| {value} | {mean:+.3f} | {sd:.3f} | {n} |")
    sys.stdout.flush()


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("what", nargs="?", default="all")  # ranks needs mpirun (as root: OMPI_ALLOW_RUN_AS_ROOT*)
    ap.add_argument("--lmp", default=default_lmp())
    ap.add_argument("--seeds", type=int, default=3)
    ap.add_argument("--time", type=float, default=2.0)
    a = ap.parse_args()
    L, S, T = a.lmp, a.seeds, a.time
    what = a.what
    if what in ("dt", "all"):
        table("Time step (paper parameters, A = 0.04 mm)", "dt (s)",
              [(dt, speeds(L, f"dt{dt:g}", S, dt=dt, time=T)) for dt in (1e-6, 2e-6, 5e-6, 1e-5, 2e-5, 5e-5, 1e-4, 2e-4)])
    if what in ("friction", "all"):
        table("Rod-plate friction (e_wall 0.1, dt 1e-5)", "mu_wall",
              [(mu, speeds(L, f"mu{mu:g}", S, mu_wall=mu, time=T)) for mu in (0.0, 0.01, 0.03, 0.1, 0.3)])
    if what in ("restitution", "all"):
        table("Rod-plate restitution (mu_wall 0.03, dt 1e-5)", "e_wall",
              [(e, speeds(L, f"e{e:g}", S, e_wall=e, time=T)) for e in (0.0, 0.1, 0.3, 0.5, 0.8)])
    if what in ("drive", "all"):
        table("Drive amplitude (f = 200 Hz, dt 1e-5)", "A (m)",
              [(A, speeds(L, f"A{A:g}", S, amplitude=A, time=T)) for A in (4.0e-5, 4.35e-5)])
        table("Taper (dt 1e-5)", "tail/nose (m)",
              [(f"{t}/{n}", speeds(L, f"taper{t}", S, tail=t, nose=n, time=T))
               for t, n in (("1.1e-3", "0.7e-3"), ("0.7e-3", "1.1e-3"), ("0.9e-3", "0.9e-3"))])
    if what in ("spheres", "all"):
        table("Spheres per rod (dt 1e-5)", "spheres",
              [(n, speeds(L, f"n{n}", S, spheres=n, time=T)) for n in (6, 9, 17)])
    if what in ("order", "all"):
        table("Contact order and impact resolution (pair gran/impulse, dt 1e-5)", "solver",
              [(label, speeds(L, f"order_{label.split()[1]}", S, time=T, **kw)) for label, kw in (
                  ("order shuffle", {"order": "shuffle"}), ("order tag", {"order": "tag"}),
                  ("order reverse", {"order": "reverse"}),
                  ("resolution 100", {"resolution": 100}), ("resolution 1000", {"resolution": 1000}))])
    if what in ("ranks", "all"):
        table("MPI ranks (rods on sub-domain and periodic edges, dt 1e-5)", "ranks",
              [(p, speeds(L, f"np{p}", S, np_ranks=p, shift=-10e-3, time=T)) for p in (1, 2, 4)])


if __name__ == "__main__":
    main()
