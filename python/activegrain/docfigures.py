"""Draw the figures of docs/python.rst from synthetic data.

    python3 -m activegrain.docfigures docs/figures/python
"""
import os
import sys

import numpy as np
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from . import analysis as A, motility as M, plotting, synthetic as S, theory as T  # noqa: E402
from .geometry import Annulus, Box, geometry_from_box  # noqa: E402


def condensed_channel(rng, shift=0.0, length=160.0, width=31.0):
    """A rod monolayer at x = 30 + shift pushing beads: phi_b follows eq. 5's exponential
    ahead (from 0.78 down to 0.45) and is 0.45 elsewhere."""
    box = S.channel_box(length, width)
    x_layer = 30.0
    ys = np.arange(1.0, width - 0.5, 1.15)
    ang = rng.normal(0, 0.08, len(ys))
    axes = np.column_stack([np.cos(ang), np.sin(ang)])
    centres = np.column_stack([x_layer + rng.normal(0, 0.3, len(ys)), ys])
    s, r = S.rod_spheres()
    spheres = (centres[:, None, :] + s[None, :, None] * axes[:, None, :]).reshape(-1, 2)
    phi = lambda x: (0.45 + 0.33 * np.exp(-(x - x_layer - 3) / 25.0) if x > x_layer + 2.5 else
                     (0.0 if x > x_layer - 3 else 0.45))
    beads = S.relaxed_beads(rng, box, phi, spheres, np.tile(r, len(ys)))
    return S.make_frame(box, box.wrap(beads + [shift, 0.0]), 0.5, centres + [shift, 0.0], axes)


def main(outdir):
    os.makedirs(outdir, exist_ok=True)
    out = lambda name: os.path.join(outdir, name)
    rng = np.random.default_rng(1)
    fr = condensed_channel(rng)
    g = geometry_from_box(fr.box)

    plotting.snapshot(fr, g, out("snapshot.png"), title="synthetic condensed channel: " + plotting.frame_title(fr)
                      .split(";  ")[1])
    plt.close("all")

    pb = A.area_fraction_profile(fr, g, "x", 40, "beads")
    pr = A.area_fraction_profile(fr, g, "x", 40, "rods")
    fig = plotting.plot_profiles([pb, pr], labels=["beads", "rods"])
    fig.axes[0].set_title("area fractions of the beads and of the rods along the channel")
    fig.savefig(out("profile.png"), dpi=150)
    plt.close("all")

    xe, ye, phi = A.area_fraction_map(fr, g, (80, 15), "all")
    plotting.plot_map(xe, ye, phi, out("map.png"), label="area fraction (all)")
    plt.close("all")

    frames = [condensed_channel(np.random.default_rng(2), shift=4.0 * i) for i in range(12)]
    for i, f in enumerate(frames):
        f.time, f.step = 10.0 * i, 1000 * i
        f.pos[:, :2] = f.box.wrap(f.pos[:, :2])
    profiles = [A.area_fraction_profile(f, g, "x", 40, "beads") for f in frames]
    plotting.kymograph([f.time for f in frames], profiles, out("kymograph.png"))
    plt.close("all")
    plotting.movie(frames[::2], out("movie.gif"), g, fps=4, width=5)

    lp = [A.layer_profile(f, g, extent=80.0, bins=40) for f in frames]
    avg = A.Profile(lp[0].coord, "beads", lp[0].edges, np.mean([p.fraction for p in lp], axis=0))
    phi_plus, ell, phi0 = A.fit_layer_exponential(avg, 4.0)
    fig = plotting.plot_profiles([avg], labels=["beads, mean over 12 frames"])
    d = np.linspace(4.0, 80.0, 200)
    fig.axes[0].plot(d, phi0 + (phi_plus - phi0) * np.exp(-d / ell), "k--",
                     label=rf"fit: $\phi_+$={phi_plus:.2f}, $\ell$={ell:.1f}, $\phi_0$={phi0:.2f}")
    fig.axes[0].legend()
    fig.axes[0].set_xlabel("distance ahead of the rod layer (d)")
    fig.savefig(out("layer_profile.png"), dpi=150)
    plt.close("all")

    # rods in a bead gradient: alignment of p with grad phi_b
    gbox = S.channel_box(120, 40)
    gphi = lambda x: 0.25 + 0.5 * x / 120
    centres, _ = S.random_rods(25, (10, 110, 4, 36), rng)
    ang = rng.normal(0, 0.6, 25)
    axes = np.column_stack([np.cos(ang), np.sin(ang)])
    s, r = S.rod_spheres()
    spheres = (centres[:, None, :] + s[None, :, None] * axes[:, None, :]).reshape(-1, 2)
    gfr = S.make_frame(gbox, S.relaxed_beads(rng, gbox, gphi, spheres, np.tile(r, 25)), 0.5, centres, axes)
    gg = geometry_from_box(gbox)
    xe, ye, field = A.smoothed_bead_field(gfr, gg, smoothing=2.0)
    cos, mean_cos = A.gradient_alignment(gfr, gg, smoothing=2.0)
    pol = A.polarization(gfr, gg)
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(11, 3.6), gridspec_kw={"width_ratios": [3, 1]})
    m = a1.pcolormesh(xe, ye, field.T, cmap="Greys", vmin=0, vmax=0.9)
    fig.colorbar(m, ax=a1, label="smoothed bead area fraction")
    a1.quiver(gfr.rods().centre[:, 0], gfr.rods().centre[:, 1], gfr.rods().axis[:, 0], gfr.rods().axis[:, 1],
              cos, cmap="coolwarm_r", clim=(-1, 1), scale=25, width=0.006)
    a1.set_aspect("equal")
    a1.set_title(f"rod axes (arrows) on the bead field: P = {pol['P']:.2f}")
    a2.hist(cos, bins=np.linspace(-1, 1, 11))
    a2.set_xlabel(r"cos($\mathbf{p}$, $\nabla\phi_b$)")
    a2.set_title(f"mean {mean_cos:.2f}")
    fig.tight_layout()
    fig.savefig(out("polar.png"), dpi=130)
    plt.close("all")

    box = Box((-30.0, -30.0, 0.0), (30.0, 30.0, 1.12), (False, False, False))
    ann = Annulus(box, (0.0, 0.0), 15.0, 28.0)
    pts = S.lattice_beads(-30, 30, -30, 30, 1.05)
    r, th = ann.polar(pts)
    keep = (r > 15.6) & (r < 27.4) & (((th > 0.2) & (th < 2.5)) | (rng.uniform(size=len(pts)) < 0.45))
    radii = np.arange(16.1, 27.3, 1.15)
    centres = np.column_stack([radii, np.zeros_like(radii)])
    axes = np.tile([0.0, 1.0], (len(radii), 1))
    afr = S.make_frame(box, S.remove_overlaps(pts[keep], box, centres, axes), 0.5, centres, axes)
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(10, 4.6))
    plotting.draw_snapshot(a1, afr, ann)
    a1.set_xlabel("x (d)")
    a1.set_ylabel("y (d)")
    pt = A.area_fraction_profile(afr, ann, "theta", 36, "beads")
    a2.stairs(pt.fraction, pt.edges, baseline=None, label="beads")
    a2.set_xlabel(r"$\theta$ (rad)")
    a2.set_ylabel("area fraction of beads")
    lay = A.layer_sides(afr, ann)
    a2.set_title(f"ahead {lay.phi_ahead:.2f}, behind {lay.phi_behind:.2f}")
    fig.tight_layout()
    fig.savefig(out("annulus.png"), dpi=130)
    plt.close("all")

    fig, axs = plt.subplots(5, 1, figsize=(8, 11.8))
    for ax, phase in zip(axs, ("isotropic", "flock", "segregated", "condensed", "trapped")):
        pf = S.phase_configuration(phase, seed=3)
        # the last frame of a second in which the rods advanced along their axes at 2 d/s
        window = S.trajectory(pf, [-1.0, 0.0], rod_speed=2.0, bead_speed=0.3)
        res = A.classify_phase(window[-1], geometry_from_box(pf.box), window=window)
        plotting.draw_snapshot(ax, pf, geometry_from_box(pf.box))
        o = res.observables
        ax.set_title(f"built as {phase}: classified {res.phase}  (P={o['P']:.2f}, "
                     f"S={o['segregation']:.2f}, layers {o['n_active_layers']} with "
                     f"{o['active_layer_fraction']:.2f}, contrast {o['layer_contrast']:.2f})", fontsize=9)
    fig.tight_layout()
    fig.savefig(out("phases.png"), dpi=120)
    plt.close("all")

    cos_rng = np.random.default_rng(5)
    walks = [S.persistent_walk(2000, 0.02, 3.6, 2.0, cos_rng) for _ in range(30)]
    tracks = M.RodTracks(walks[0][0], np.arange(30), np.stack([w[1] for w in walks], 1),
                         np.stack([w[2] for w in walks], 1))
    lags, msd = M.msd(tracks.centre, 800)
    v, tau = M.fit_persistent_walk(lags * 0.02, msd)
    lc, C = M.orientation_correlation(tracks.axis, 800)
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(10, 3.8))
    a1.loglog(lags[1:] * 0.02, msd[1:], "o", ms=2, label="measured")
    a1.loglog(lags[1:] * 0.02, M.persistent_walk_msd(lags[1:] * 0.02, v, tau), label=f"fit v={v:.2f}, tau={tau:.2f}")
    a1.set_xlabel("lag time (s)")
    a1.set_ylabel("MSD (mm$^2$)")
    a1.legend()
    a2.plot(lc * 0.02, C, label="<p(t).p(0)>")
    tp = M.persistence_time(lc * 0.02, C)
    a2.plot(lc * 0.02, np.exp(-lc * 0.02 / tp), "--", label=f"exp(-t/{tp:.2f})")
    a2.set_xlabel("lag time (s)")
    a2.legend()
    fig.suptitle("synthetic rods: v = 3.6 mm/s, tau = 2 s")
    fig.tight_layout()
    fig.savefig(out("motility.png"), dpi=130)
    plt.close("all")

    p = T.LinearParameters(rho0=1.0, sigma0=0.05, D_rho=0.02, D_sigma=0.0, D_rho_sigma=0.5,
                           D_sigma_rho=0.0, alpha=1.0, u0=1.0, A=1.0, B=-0.1, a=10.0, K=1.0)
    k = np.linspace(0, 2 * np.sqrt(p.a / p.K), 300)
    plotting.plot_growth_rates(k, T.growth_rates(k, p), out("growth_rates.png"),
                               title="unstable and non-reciprocal: travelling modes")
    plt.close("all")

    eos = T.HendersonEOS()
    pfc = T.point_force(2.0, 0.6, 1.0, 1.0, eos)
    x, rho = T.solve_moving_force(2.0, 0.6, 1.0, 1.0, eos, behind=10.0, ahead=100.0, n=1100)
    xa = np.linspace(0, 100, 400)
    fig = plotting.plot_point_force(x, {"eq. 3 in time (steady state)": rho}, pfc)
    ax = fig.axes[0]
    ax.plot(xa, pfc.profile(xa), "--", label="eq. 5 (exponential)")
    ax.plot(xa, T.steady_profile(xa, pfc, eos), ":", label="steady ODE, Henderson EOS")
    ax.legend()
    fig.savefig(out("point_force.png"), dpi=150)
    plt.close("all")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "figures")
