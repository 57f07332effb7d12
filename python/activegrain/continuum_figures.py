"""Draw the figures of docs/continuum.rst with the continuum solver and print the numbers the
page quotes.

    python3 -m activegrain.continuum_figures docs/figures/continuum
"""
import os
import sys
import time
from dataclasses import replace

import numpy as np
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from . import continuum as C, theory as T  # noqa: E402

# Reciprocal: beads condense (A alpha rho0 + B u0 sigma0 > 0) and rods follow; real rates.
RECIPROCAL = C.ContinuumParameters(rho0=1.0, sigma0=0.2, D_rho=0.1, D_sigma=0.1, D_rho_sigma=0.05,
                                   D_sigma_rho=0.02, alpha=1.0, u0=1.0, A=1.0, B=0.5, a=2.0, K=1.0,
                                   proportional_cross_diffusion=True)
# Non-reciprocal: beads flee rods (D_rho_sigma), rods pursue beads (A > 0); complex rates.
NON_RECIPROCAL = C.ContinuumParameters(rho0=1.0, sigma0=0.5, D_rho=0.2, D_sigma=0.2, D_rho_sigma=1.0,
                                       D_sigma_rho=0.0, alpha=1.0, u0=1.0, A=1.0, B=0.0, a=1.0, K=1.0,
                                       proportional_cross_diffusion=True)


def dispersion_figure(path):
    """Growth rates: full relation, the paper's eqs. 1-2, and the solver's measured rates."""
    p, L = RECIPROCAL, 16 * np.pi
    k = np.linspace(0.01, 3.2, 300)
    fig, ax = plt.subplots(figsize=(5.5, 3.8))
    ax.plot(k, T.growth_rates(k, p, expanded=False)[:, 0].real, "k-", label="exact (slaved P)")
    ax.plot(k, T.growth_rates(k, p, expanded=True)[:, 0].real, "k--", label="paper eqs. 1-2 (4th order in k)")
    m = np.arange(2, 26, 2)
    measured = [C.measured_growth_rate(p, L, int(i), n=128, dt=2e-3, t_end=6.0) for i in m]
    ax.plot(2 * np.pi * m / L, measured, "o", color="C3", label="solver, measured")
    ax.axhline(0, color="0.7", lw=0.8)
    ax.set_ylim(-0.6, 0.45)
    ax.set_xlabel("k")
    ax.set_ylabel(r"Re $\lambda$")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    err = max(abs(mi - T.growth_rates(2 * np.pi * i / L, p, expanded=False)[0].real)
              / abs(T.growth_rates(2 * np.pi * i / L, p, expanded=False)[0].real) for i, mi in zip(m, measured))
    print(f"dispersion: largest relative error of the measured rates {err:.2e}")


def diagram_figure(path):
    rho0 = np.linspace(0.05, 2.0, 60)
    sigma0 = np.linspace(0.02, 1.0, 50)
    fig, axes = plt.subplots(1, 2, figsize=(9, 3.8))
    for ax, (name, p) in zip(axes, [("reciprocal couplings", RECIPROCAL), ("non-reciprocal couplings", NON_RECIPROCAL)]):
        C.plot_stability_diagram(p, rho0, sigma0, None, ax=ax)
        ax.plot(p.rho0, p.sigma0, "k*", ms=10)
        # the paper's non-reciprocity condition (its limit D_rho = D_sigma = D_sigma_rho = 0)
        R, S = np.meshgrid(rho0, sigma0)
        paper = np.vectorize(lambda r, s: T.nonreciprocity_condition(replace(p, rho0=r, sigma0=s)))(R, S)
        if paper.any() and not paper.all():
            ax.contour(rho0, sigma0, paper.astype(float), levels=[0.5], colors="k", linestyles="--")
            ax.plot([], [], "k--", label="paper's non-reciprocity\ncondition (D's = 0)")
            ax.legend(loc="upper right", fontsize=7)
        ax.set_title(name, fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def nonlinear_figures(outdir):
    out = lambda name: os.path.join(outdir, name)
    runs = {}
    # without a packing limit the condensing peaks sharpen without bound: with D_rho = 0.1 the run
    # ends near t = 21 (the same for dt / 5 and twice the points), with D_rho = 0.3 near t = 96
    for name, p, L, t_end, n, dt in [("condensation", replace(RECIPROCAL, D_rho=0.3), 100.0, 90.0, 512, 2.5e-3),
                                     ("close_packing", replace(RECIPROCAL, rho_close=2.5), 100.0, 600.0, 1024, 1e-3),
                                     ("travelling", NON_RECIPROCAL, 100.0, 600.0, 512, 2.5e-3)]:
        t0 = time.time()
        run = C.simulate(p, n, L, dt, t_end, frames=150, amplitude=1e-2, seed=1)
        print(f"{name}: 1D n {n}, {len(run.t)} frames to t = {t_end}: {time.time() - t0:.1f} s wall; "
              f"rho in [{run.rho.min():.2f}, {run.rho.max():.2f}], sigma in [{run.sigma.min():.2f}, "
              f"{run.sigma.max():.2f}]; mass drift {abs(run.rho[-1].mean() / run.rho[0].mean() - 1):.1e}")
        runs[name] = run
        fig, axes = plt.subplots(1, 2, figsize=(9, 3.6))
        C.kymograph(run, None, "rho", ax=axes[0])
        C.kymograph(run, None, "sigma", ax=axes[1])
        fig.tight_layout()
        fig.savefig(out(f"kymograph_{name}.png"), dpi=100)
        plt.close(fig)
    return runs


def band_figure(path):
    """A wave travelling one way (seeded by the complex eigenmode, before it turns into a
    standing pattern), beads jamming at rho_close: the bead profile ahead of the rod band
    against eq. 5's exponential, with the bead stiffness of these equations."""
    p, L, n, m = replace(NON_RECIPROCAL, rho_close=1.6), 30.0, 512, 4
    run = C.simulate(p, n, L, 1e-3, 200.0, frames=200, start=C.eigenmode_start(p, n, L, m))
    _, v0 = C.band_track(run)
    d, rho, sigma = C.profile_ahead(run)
    # the bead front ahead of the rods: from the bead maximum rho+ to the next minimum; its
    # length (rho+ - rho_min) / max |d rho/dx| (l itself for an exponential decay)
    spacing = L / m
    i0 = int(np.argmax(np.where(d < spacing, rho, -np.inf)))
    i1 = i0 + int(np.argmin(rho[i0:i0 + int(spacing / 2 / (d[1] - d[0]))]))
    ell = (rho[i0] - rho[i1]) / np.max(-np.gradient(rho[i0:i1 + 1], d[1] - d[0]))
    # eq. 5's l+ = Pi'(rho+) / (gamma v0) with the beads' stiffness of these equations: the
    # hard-disk one, Pi'/gamma = D_rho(rho+), and with the current alpha rho P of P slaved to the
    # beads' own gradient, Pi'/gamma = D_rho(rho+) - alpha A rho+ / a
    stiffness = C.bead_diffusivity(p, rho[i0])
    ell_hard = stiffness / abs(v0)
    ell_slaved = (stiffness - p.alpha * p.A * rho[i0] / p.a) / abs(v0)
    fig, ax = plt.subplots(figsize=(5.5, 3.8))
    ax.plot(d, rho, label=r"$\rho$ (beads)")
    ax.plot(d, sigma, label=r"$\sigma$ (rods)")
    x = d[i0] + np.linspace(0, spacing / 2, 100)
    for ell5, style, what in ((ell_hard, ":", r"D_\rho(\rho_+)"),
                              (ell_slaved, "-.", r"D_\rho(\rho_+) - \alpha A \rho_+/a")):
        ax.plot(x, rho[i1] + (rho[i0] - rho[i1]) * np.exp(-(x - d[i0]) / ell5), "k" + style, lw=1,
                label=rf"eq. 5, $\Pi'/\gamma = {what}$: $\ell_+$ = {ell5:.2f}")
    ax.set_xlim(0, 2 * spacing)
    ax.set_xlabel("distance ahead of the rod maximum (direction of motion)")
    ax.legend(fontsize=7, loc="lower right")
    ax.set_title(f"travelling wave, speed {abs(v0):.3f}, beads jam at {p.rho_close:g}; "
                 f"front length {ell:.2f}", fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    print(f"band: speed {abs(v0):.4f}, rho+ {rho[i0]:.3f}, rho_min {rho[i1]:.3f}, front length {ell:.3f}; eq. 5 with "
          f"D_rho(rho+) = {stiffness:.3f}: {ell_hard:.3f}; with D_rho(rho+) - alpha A rho+ / a: {ell_slaved:.3f}")
    return run


def two_d_figures(outdir):
    p = NON_RECIPROCAL
    t0 = time.time()
    # later the rings' bead edges sharpen below the grid (at t = 150: rho from -0.46 to 9.5)
    run = C.simulate(p, (128, 128), (40.0, 40.0), 2.5e-3, 100.0, frames=50, amplitude=1e-2, seed=3)
    print(f"2D: 128 x 128 to t = 100: {time.time() - t0:.1f} s wall; rho in [{run.rho.min():.2f}, "
          f"{run.rho.max():.2f}]; mass drift {abs(run.rho[-1].mean() / run.rho[0].mean() - 1):.1e}")
    C.snapshot(run, os.path.join(outdir, "snapshot_2d.png"))
    C.movie(replace(run, t=run.t[20:], rho=run.rho[20:], sigma=run.sigma[20:], P=run.P[20:]),
            os.path.join(outdir, "movie_2d.gif"), fps=5, dpi=60)


def main(outdir):
    os.makedirs(outdir, exist_ok=True)
    dispersion_figure(os.path.join(outdir, "dispersion.png"))
    diagram_figure(os.path.join(outdir, "diagram.png"))
    nonlinear_figures(outdir)
    band_figure(os.path.join(outdir, "band_profile.png"))
    two_d_figures(outdir)


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "docs/figures/continuum")
