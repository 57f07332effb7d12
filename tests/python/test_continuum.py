"""activegrain.continuum: the ctypes front end of the continuum solver library."""
import io
import os
import subprocess
import sys

import numpy as np
import pytest

from activegrain import cli, continuum as C, theory

# ctest sets ACTIVEGRAIN_CONTINUUM_LIB when the library is built (a missing file then fails);
# a build configured with -DACTIVEGRAIN_CONTINUUM=OFF has none to test
if C.LIBRARY_ENV not in os.environ:
    try:
        C.find_library()
    except FileNotFoundError as e:
        pytest.skip(str(e), allow_module_level=True)

RECIPROCAL = C.ContinuumParameters(rho0=1.0, sigma0=0.2, D_rho=0.1, D_sigma=0.1, D_rho_sigma=0.05,
                                   D_sigma_rho=0.02, alpha=1.0, u0=1.0, A=1.0, B=0.5, a=2.0, K=1.0)
NON_RECIPROCAL = C.ContinuumParameters(rho0=1.0, sigma0=0.5, D_rho=0.05, D_sigma=0.05, D_rho_sigma=1.0,
                                       alpha=1.0, u0=1.0, A=1.0, B=0.0, a=1.0, K=1.0,
                                       proportional_cross_diffusion=True)


def test_growth_rates_match_theory_py():
    """The solver's growth against theory.growth_rates (full response), several k."""
    L = 8 * np.pi
    for m in (1, 3, 6, 10):
        exact = theory.growth_rates(2 * np.pi * m / L, RECIPROCAL, expanded=False)[0].real
        measured = C.measured_growth_rate(RECIPROCAL, L, m, dt=2e-3, t_end=4.0)
        assert measured == pytest.approx(exact, rel=1e-3)


def test_mass_conserved_and_pattern_grows_1d_2d():
    for n, length in ((128, 50.0), ((32, 24), (20.0, 15.0))):
        run = C.simulate(NON_RECIPROCAL, n, length, 5e-3, 25.0, frames=4, amplitude=1e-2)
        axes = tuple(range(1, run.rho.ndim))
        assert np.allclose(run.rho.mean(axis=axes), run.rho[0].mean(), rtol=1e-13, atol=0)
        assert np.allclose(run.sigma.mean(axis=axes), run.sigma[0].mean(), rtol=1e-13, atol=0)
        assert np.ptp(run.rho[-1]) > 10 * np.ptp(run.rho[0])
        assert run.P.shape == (5, run.dim) + run.rho.shape[1:]


def test_relaxed_polarization_is_state():
    p = C.ContinuumParameters(**{**RECIPROCAL.__dict__, "tau": 0.5})
    with C.Solver(p, 32, 10.0, 1e-2) as s:
        x = s.coordinates()
        P = np.array([0.1 * np.cos(2 * np.pi * x / 10.0)])
        s.set_state(np.ones(32), np.full(32, 0.2), P)
        assert np.allclose(s.state()[2], P, atol=1e-14)
        s.step(10)
        assert s.time == pytest.approx(0.1)
        assert np.abs(s.state()[2]).max() < 0.1       # relaxing towards the (zero) slaved value


@pytest.mark.parametrize("change, name", [({"D_rho": 0.0, "D_sigma": 0.0}, "D_rho"), ({"K": -1.0}, "K"),
                                          ({"tau": -1.0}, "tau"), ({"rho_close": -1.0}, "rho_close")])
def test_bad_parameters_name_themselves(change, name):
    p = C.ContinuumParameters(**{**RECIPROCAL.__dict__, **change})
    with pytest.raises(ValueError, match=f"^{name}"):
        C.Solver(p, 32, 10.0, 1e-2)


def test_bad_grid_and_fields():
    with pytest.raises(ValueError, match="^dt"):
        C.Solver(RECIPROCAL, 32, 10.0, 0.0)
    with pytest.raises(ValueError, match="^length"):
        C.Solver(RECIPROCAL, (32, 32), 10.0, 1e-2)
    with C.Solver(RECIPROCAL, 32, 10.0, 1e-2) as s:
        with pytest.raises(ValueError, match="^rho"):
            s.set_state(np.ones(31), np.ones(32))
        with pytest.raises(ValueError, match="^P"):
            s.set_state(np.ones(32), np.ones(32), np.zeros((1, 32)))   # P is slaved here
        with pytest.raises(ValueError, match="set_state"):
            s.step(1)


def test_close_packing_stops_condensation():
    """Beads condense up to, never past, rho_close; the mean must lie below it."""
    p = C.ContinuumParameters(**{**RECIPROCAL.__dict__, "rho_close": 2.0, "proportional_cross_diffusion": True})
    run = C.simulate(p, 256, 50.0, 2.5e-3, 150.0, frames=3, amplitude=1e-2)
    assert 1.5 < run.rho[-1].max() < 2.0
    assert run.rho[-1].mean() == pytest.approx(run.rho[0].mean(), rel=1e-13)
    with C.Solver(p, 32, 10.0, 1e-2) as s:
        with pytest.raises(ValueError, match="^rho"):
            s.set_state(np.full(32, 2.5), np.full(32, 0.2))


def test_blow_up_raises():
    p = C.ContinuumParameters(**{**RECIPROCAL.__dict__, "D_rho": 0.01, "D_sigma": 0.01, "D_rho_sigma": 0.0,
                                 "D_sigma_rho": 0.0, "alpha": 5.0, "u0": 5.0, "B": 0.0, "a": 1.0, "sigma0": 1.0})
    x = np.arange(32) * 10.0 / 32
    with pytest.raises(FloatingPointError, match="smaller dt"):
        C.simulate(p, 32, 10.0, 0.2, 400.0, frames=1, start=(1 + 0.5 * np.cos(2 * np.pi * x / 10), np.ones(32)))


def test_missing_library_is_explained(monkeypatch, tmp_path):
    monkeypatch.setenv(C.LIBRARY_ENV, str(tmp_path / "nowhere.so"))
    with pytest.raises(FileNotFoundError, match=C.LIBRARY_ENV):
        C.find_library()


def test_regimes():
    assert C.classify(RECIPROCAL) == "stationary"
    assert C.classify(NON_RECIPROCAL) == "travelling"
    assert C.classify(C.ContinuumParameters(**{**RECIPROCAL.__dict__, "D_rho": 2.0, "D_sigma": 2.0})) == "stable"


def test_band_track_on_a_known_wave_train():
    """Three equal bands moving at -0.7 across the periodic boundary."""
    L, t = 30.0, np.linspace(0, 100, 101)
    x = np.arange(300) * L / 300
    sigma = 0.5 + 0.2 * np.cos(2 * np.pi * 3 * (x[None, :] + 0.7 * t[:, None]) / L)
    run = C.Run(NON_RECIPROCAL, (L,), t, 1 + 0 * sigma, sigma, np.zeros((101, 1, 300)), x)
    _, speed = C.band_track(run)
    assert speed == pytest.approx(-0.7, rel=1e-9)
    d, rho, s = C.profile_ahead(run)
    assert d[0] == 0 and np.all(np.diff(d) > 0) and s[0] == s.max()


def test_seeded_eigenmode_travels():
    p = C.ContinuumParameters(**{**NON_RECIPROCAL.__dict__, "D_rho": 0.2, "D_sigma": 0.2})
    L, n, m = 30.0, 128, 4
    lam = theory.growth_rates(2 * np.pi * m / L, p, expanded=False)[0]
    assert lam.real > 0 and lam.imag != 0
    run = C.simulate(p, n, L, 5e-3, 20.0, frames=20, start=C.eigenmode_start(p, n, L, m, amplitude=1e-4))
    _, speed = C.band_track(run)
    # still linear: crests move at the phase velocity -Im(lambda)/k of the seeded mode
    assert speed == pytest.approx(-lam.imag / (2 * np.pi * m / L), rel=1e-3)


def test_pictures_and_cli(tmp_path):
    run = C.simulate(NON_RECIPROCAL, 64, 20.0, 5e-3, 20.0, frames=3)
    C.kymograph(run, tmp_path / "k.png")
    C.snapshot(run, tmp_path / "s.png")
    C.movie(run, str(tmp_path / "m.gif"), fps=2)
    run2 = C.simulate(NON_RECIPROCAL, (16, 16), (8.0, 8.0), 5e-3, 2.0, frames=2)
    C.movie(run2, str(tmp_path / "m2.gif"), fps=2)
    for f in ("k.png", "s.png", "m.gif", "m2.gif"):
        assert (tmp_path / f).stat().st_size > 1000
    out = tmp_path / "run"
    argv = ["continuum", "--rho0", "1", "--sigma0", "0.5", "--D_rho", "0.05", "--D_sigma", "0.05",
            "--D_rho_sigma", "1", "--A", "1", "--a", "1", "--K", "1", "--proportional-cross-diffusion",
            "--n", "64", "--length", "20", "--dt", "0.005", "--t-end", "5", "--frames", "5",
            "--kymograph", str(out) + ".png", "--movie", str(out) + ".gif", "--save", str(out) + ".npz"]
    assert cli.main(argv) == 0
    saved = np.load(str(out) + ".npz")
    assert saved["rho"].shape == (6, 64)
    assert (tmp_path / "run.png").exists() and (tmp_path / "run.gif").exists()
    bad = subprocess.run([sys.executable, "-m", "activegrain", "continuum", "--D_rho", "0", "--D_sigma", "0"],
                         capture_output=True, text=True)
    assert bad.returncode == 1 and "activegrain continuum: D_rho" in bad.stderr


def test_continuum_runs_with_its_defaults_the_documented_travelling_case():
    """No options: docs/continuum.rst's non-reciprocal set as its figure kymograph_travelling.png ran it."""
    from dataclasses import asdict
    from activegrain.continuum_figures import NON_RECIPROCAL
    args = cli.build_parser().parse_args(["continuum"])
    assert {k: getattr(args, k) for k in asdict(NON_RECIPROCAL)} == asdict(NON_RECIPROCAL)
    assert (args.n, args.length, args.dt, args.t_end, args.frames, args.amplitude, args.seed) == \
        ([512], [100.0], 2.5e-3, 600.0, 150, 1e-2, 1)
    out = io.StringIO()
    assert cli.main(["continuum"], out) == 0
    lines = out.getvalue().splitlines()
    assert lines[0] == "regime (linear, full dispersion relation): travelling"
    assert lines[1].startswith("t = 600: rho in [")
