r"""The paper's continuum theory in time: Python front end of the pseudo-spectral solver
``libactivegrain_continuum.so`` (``src/continuum``, through ctypes).

Fields rho (beads), sigma (rods) and P (polarization) on a periodic line or rectangle, with
the currents of :mod:`activegrain.theory` (the paper's eqs. 1-2; docs/continuum.rst); P slaved,
(a - K lap) P = A grad rho + B grad sigma (``tau = 0``), or relaxing,
tau dP/dt = -(a - K lap) P + A grad rho + B grad sigma. The diffusivity matrix must have
eigenvalues of positive real part (small D_rho, D_sigma suffice): without them growth rates stay
positive as k -> infinity and nothing converges with the grid.

The library is found through ``ACTIVEGRAIN_CONTINUUM_LIB`` (its path; ``build/activegrain-env.sh``
sets it), else in the repository's ``build*/lib`` folders.

.. code-block:: python

   from activegrain import continuum
   p = continuum.ContinuumParameters(rho0=1, sigma0=0.5, D_rho=0.2, D_sigma=0.2, D_rho_sigma=1,
                                     alpha=1, u0=1, A=1, a=1, K=1, proportional_cross_diffusion=True)
   run = continuum.simulate(p, n=512, length=100.0, dt=2.5e-3, t_end=600, frames=150)
   continuum.kymograph(run, "kymograph.png"); continuum.movie(run, "run.gif")
"""
import ctypes
import os
import pathlib
from dataclasses import dataclass, fields

import numpy as np

from . import theory

LIBRARY_ENV = "ACTIVEGRAIN_CONTINUUM_LIB"
LIBRARY_NAME = "libactivegrain_continuum.so"
ABI_VERSION = 1                     # AG_CONTINUUM_ABI_VERSION of activegrain_continuum.h
STATUS_OK, STATUS_BAD_ARGUMENT, STATUS_NOT_FINITE = 0, 1, 2


@dataclass
class ContinuumParameters(theory.LinearParameters):
    """The model's parameters (those of :class:`theory.LinearParameters`; rho0, sigma0 are
    the mean densities of the starts made here; the solver takes its means from the fields it
    is given), ``tau`` (0 slaves P to the gradients, > 0 lets it relax) and
    ``proportional_cross_diffusion`` (False: the paper's D_rho_sigma grad sigma; True: times
    rho/rho0, and D_sigma_rho grad rho times sigma/sigma0 -- the same linear theory, and beads
    are no longer pushed into negative density) and ``rho_close`` (0: constant D_rho; > 0: the
    bead diffusivity follows Henderson's hard-disk stiffness at area fraction rho/rho_close,
    D_rho at the mean -- the same linear theory, and condensates that stop at close packing)."""
    tau: float = 0.0
    proportional_cross_diffusion: bool = False
    rho_close: float = 0.0


class _Config(ctypes.Structure):
    _fields_ = [("dim", ctypes.c_int), ("nx", ctypes.c_int), ("ny", ctypes.c_int),
                ("lx", ctypes.c_double), ("ly", ctypes.c_double), ("dt", ctypes.c_double)] + \
               [(name, ctypes.c_double) for name in
                ("D_rho", "D_sigma", "D_rho_sigma", "D_sigma_rho", "alpha", "u0", "A", "B", "a", "K", "tau",
                 "rho_close")] + \
               [("proportional_cross_diffusion", ctypes.c_int)]


def find_library():
    """Path of the solver library: ``$ACTIVEGRAIN_CONTINUUM_LIB``, else the newest
    ``build*/lib/libactivegrain_continuum.so`` of this repository."""
    env = os.environ.get(LIBRARY_ENV)
    if env:
        if not os.path.isfile(env):
            raise FileNotFoundError(f"{LIBRARY_ENV}={env}: no such file")
        return env
    root = pathlib.Path(__file__).resolve().parents[2]
    found = sorted(root.glob(f"build*/lib/{LIBRARY_NAME}"), key=lambda p: p.stat().st_mtime)
    if not found:
        raise FileNotFoundError(
            f"{LIBRARY_NAME} not found: build it (tools/run-tests, or cmake -S src/continuum -B "
            f"build-continuum && cmake --build build-continuum) or set {LIBRARY_ENV} to its path")
    return str(found[-1])


_library = None


def _lib():
    global _library
    if _library is None:
        lib = ctypes.CDLL(find_library())
        lib.ag_continuum_abi_version.restype = ctypes.c_int
        if lib.ag_continuum_abi_version() != ABI_VERSION:
            raise RuntimeError(f"{LIBRARY_NAME}: interface version {lib.ag_continuum_abi_version()}, "
                               f"this module needs {ABI_VERSION}: rebuild it")
        lib.ag_continuum_last_error.restype = ctypes.c_char_p
        lib.ag_continuum_create.argtypes = [ctypes.POINTER(_Config), ctypes.POINTER(ctypes.c_void_p)]
        lib.ag_continuum_destroy.argtypes = [ctypes.c_void_p]
        lib.ag_continuum_destroy.restype = None
        pointer = ctypes.POINTER(ctypes.c_double)
        for name in ("ag_continuum_set_state", "ag_continuum_get_state"):
            getattr(lib, name).argtypes = [ctypes.c_void_p, pointer, pointer, pointer]
        lib.ag_continuum_step.argtypes = [ctypes.c_void_p, ctypes.c_int]
        lib.ag_continuum_time.argtypes = [ctypes.c_void_p, ctypes.POINTER(ctypes.c_double)]
        _library = lib
    return _library


def _check(status):
    if status == STATUS_OK:
        return
    message = _lib().ag_continuum_last_error().decode()
    if status == STATUS_BAD_ARGUMENT:
        raise ValueError(message)
    if status == STATUS_NOT_FINITE:
        raise FloatingPointError(message)
    raise RuntimeError(message)


def _pair(value, name, dim):
    v = np.atleast_1d(value)
    if v.size != dim:
        raise ValueError(f"{name}: needs {dim} value(s) for a {dim}D grid, got {v.size}")
    return v


class Solver:
    """One solver: grid ``n`` (int for 1D, (nx, ny) for 2D) of periodic ``length``
    (float or (lx, ly)), time step ``dt``. Fields are numpy arrays of shape (nx,) or (ny, nx)."""

    def __init__(self, params, n, length, dt):
        n_arr = np.atleast_1d(n)
        dim = n_arr.size
        if dim not in (1, 2):
            raise ValueError(f"n: one grid size (1D) or two (2D), got {n!r}")
        lengths = _pair(length, "length", dim)
        self.params, self.dim, self.dt = params, dim, float(dt)
        self.n = tuple(int(v) for v in n_arr)
        self.length = tuple(float(v) for v in lengths)
        self.shape = self.n if dim == 1 else (self.n[1], self.n[0])
        c = _Config(dim=dim, nx=self.n[0], ny=self.n[1] if dim == 2 else 1, lx=self.length[0],
                    ly=self.length[1] if dim == 2 else 1.0, dt=self.dt,
                    **{f[0]: float(getattr(params, f[0])) for f in _Config._fields_[6:-1]},
                    proportional_cross_diffusion=int(bool(params.proportional_cross_diffusion)))
        handle = ctypes.c_void_p()
        _check(_lib().ag_continuum_create(ctypes.byref(c), ctypes.byref(handle)))
        self._handle = handle

    @property
    def relaxed(self):
        return self.params.tau > 0

    def coordinates(self):
        """Grid coordinates: x (1D), or (x, y) 1D arrays (2D)."""
        axes = [np.arange(n) * L / n for n, L in zip(self.n, self.length)]
        return axes[0] if self.dim == 1 else tuple(axes)

    def _field(self, values, name):
        a = np.ascontiguousarray(values, dtype=float)
        if a.shape != self.shape:
            raise ValueError(f"{name}: shape {a.shape}, the grid is {self.shape}")
        return a

    @staticmethod
    def _ptr(a):
        return None if a is None else a.ctypes.data_as(ctypes.POINTER(ctypes.c_double))

    def set_state(self, rho, sigma, P=None):
        """Set the fields (projected on the dealiased modes) and restart the time at 0.
        ``P`` (shape (dim, *grid)) only when P relaxes (tau > 0); there it defaults to zero."""
        rho, sigma = self._field(rho, "rho"), self._field(sigma, "sigma")
        if self.relaxed and P is None:
            P = np.zeros((self.dim,) + self.shape)
        if P is not None:
            P = np.ascontiguousarray(P, dtype=float)
            if P.shape != (self.dim,) + self.shape:
                raise ValueError(f"P: shape {P.shape}, needs {(self.dim,) + self.shape}")
        _check(_lib().ag_continuum_set_state(self._handle, self._ptr(rho), self._ptr(sigma), self._ptr(P)))

    def state(self):
        """(rho, sigma, P) on the grid; P is the slaved polarization when tau = 0."""
        rho, sigma = np.empty(self.shape), np.empty(self.shape)
        P = np.empty((self.dim,) + self.shape)
        _check(_lib().ag_continuum_get_state(self._handle, self._ptr(rho), self._ptr(sigma), self._ptr(P)))
        return rho, sigma, P

    def step(self, steps=1):
        _check(_lib().ag_continuum_step(self._handle, int(steps)))

    @property
    def time(self):
        t = ctypes.c_double()
        _check(_lib().ag_continuum_time(self._handle, ctypes.byref(t)))
        return t.value

    def close(self):
        if getattr(self, "_handle", None) and _library is not None:
            _library.ag_continuum_destroy(self._handle)
            self._handle = None

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def __del__(self):
        self.close()


@dataclass
class Run:
    """Frames of a run: ``t`` (frames,), ``rho``, ``sigma`` (frames, *grid), ``P``
    (frames, dim, *grid), grid ``x`` (and ``y`` in 2D), the parameters."""
    params: ContinuumParameters
    length: tuple
    t: np.ndarray
    rho: np.ndarray
    sigma: np.ndarray
    P: np.ndarray
    x: np.ndarray
    y: np.ndarray = None

    @property
    def dim(self):
        return self.rho.ndim - 1


def random_start(params, shape, amplitude=1e-3, seed=0):
    """(rho, sigma): the means rho0, sigma0 plus uniform noise of relative amplitude
    ``amplitude``."""
    rng = np.random.default_rng(seed)
    rho = params.rho0 * (1 + amplitude * rng.uniform(-1, 1, shape))
    sigma = params.sigma0 * (1 + amplitude * rng.uniform(-1, 1, shape))
    return rho, sigma


def eigenmode_start(params, n, length, k_index, amplitude=1e-2):
    """(rho, sigma) on a 1D grid: the uniform state plus the fastest-growing eigenmode of
    :func:`theory.stability_matrix` at k = 2 pi k_index / length (a wave travelling in one
    direction where that eigenvalue is complex), of relative amplitude ``amplitude``."""
    k = 2 * np.pi * k_index / length
    lam, vectors = np.linalg.eig(theory.stability_matrix(k, params, expanded=False))
    best = np.flatnonzero(lam.real == lam.real.max())
    v = vectors[:, best[np.argmax(lam[best].imag)]]     # of a complex pair, the one with Im > 0
    v = v / np.abs(v).max()
    wave = np.exp(2j * np.pi * k_index * np.arange(n) / n)
    return params.rho0 + amplitude * params.rho0 * (v[0] * wave).real, \
        params.sigma0 + amplitude * params.rho0 * (v[1] * wave).real


def simulate(params, n, length, dt, t_end, frames=100, start=None, amplitude=1e-3, seed=0):
    """Run from ``start`` = (rho, sigma) (default :func:`random_start`) to ``t_end``, keeping
    ``frames`` + 1 equally spaced frames (the first at t = 0)."""
    if not t_end > 0:
        raise ValueError(f"t_end: must be positive, got {t_end}")
    if frames < 1:
        raise ValueError(f"frames: must be at least 1, got {frames}")
    steps = max(1, int(round(t_end / dt / frames)))
    with Solver(params, n, length, dt) as s:
        rho, sigma = start if start is not None else random_start(params, s.shape, amplitude, seed)
        s.set_state(rho, sigma)
        out = [s.state()]
        times = [s.time]
        for _ in range(frames):
            s.step(steps)
            out.append(s.state())
            times.append(s.time)
        coords = s.coordinates()
        x, y = (coords, None) if s.dim == 1 else coords
        return Run(params, s.length, np.array(times), np.array([o[0] for o in out]),
                   np.array([o[1] for o in out]), np.array([o[2] for o in out]), x, y)


def measured_growth_rate(params, length, k_index, n=64, dt=1e-3, t_end=2.0, amplitude=1e-7):
    """Re lambda of the fastest eigenmode at k = 2 pi k_index / length, measured in the 1D
    solver (slaved P): started on that eigenmode of :func:`theory.stability_matrix` (so any
    error there shows as a rate that is not constant), the growth of the mode's amplitude
    sqrt(|rho_k|^2 + |sigma_k|^2) over t_end."""
    if params.tau > 0:
        raise ValueError("tau: measured_growth_rate compares with the slaved theory (tau = 0)")
    k = 2 * np.pi * k_index / length
    lam, vectors = np.linalg.eig(theory.stability_matrix(k, params, expanded=False))
    v = vectors[:, int(np.argmax(lam.real))]
    with Solver(params, n, length, dt) as s:
        wave = np.exp(1j * k * s.coordinates())
        s.set_state(params.rho0 + amplitude * (v[0] * wave).real, params.sigma0 + amplitude * (v[1] * wave).real)

        def amplitude_now():
            rho, sigma, _ = s.state()
            return np.hypot(abs(np.fft.rfft(rho)[k_index]), abs(np.fft.rfft(sigma)[k_index]))
        a0 = amplitude_now()
        s.step(int(round(t_end / dt)))
        return float(np.log(amplitude_now() / a0) / s.time)


def bead_diffusivity(params, rho):
    """D_rho(rho) of the solver: D_rho, or with close packing D_rho times Henderson's hard-disk
    stiffness (:class:`theory.HendersonEOS`) at area fraction rho/rho_close over its value at
    rho0."""
    if params.rho_close <= 0:
        return params.D_rho * np.ones_like(np.asarray(rho, float))
    # HendersonEOS's eta = pi rho d^2 / 4: a disc diameter that puts eta = 1 at rho_close
    eos = theory.HendersonEOS(T=1.0, d=np.sqrt(4 / (np.pi * params.rho_close)))
    return params.D_rho * eos.stiffness(rho) / eos.stiffness(params.rho0)


# --------------------------------------------------------------------------- stability diagram

def classify(params, k_max=None, n_k=400):
    """'stable', 'stationary' (the fastest growing mode is real: condensation) or 'travelling'
    (complex: non-reciprocal, oscillatory) from the full linear dispersion relation on
    0 < k <= k_max (default 4 sqrt(a/K), and 4 times past the diffusive cut-off)."""
    if k_max is None:
        k_max = 4 * np.sqrt(params.a / params.K) if params.K > 0 else 10.0
    k = np.linspace(0, k_max, n_k)[1:]
    lam = theory.growth_rates(k, params, expanded=False)[:, 0]
    i = int(np.argmax(lam.real))
    if lam[i].real <= 0:
        return "stable"
    return "travelling" if abs(lam[i].imag) > 1e-9 * abs(lam[i]) else "stationary"


REGIMES = ("stable", "stationary", "travelling")


def stability_diagram(params, rho0, sigma0):
    """Regime index (REGIMES) on the grid rho0 x sigma0 (shape (len(sigma0), len(rho0)))."""
    out = np.zeros((len(sigma0), len(rho0)), int)
    for j, s in enumerate(sigma0):
        for i, r in enumerate(rho0):
            p = ContinuumParameters(**{**{f.name: getattr(params, f.name) for f in fields(params)},
                                       "rho0": float(r), "sigma0": float(s)})
            out[j, i] = REGIMES.index(classify(p))
    return out


# --------------------------------------------------------------------------- bands

def band_track(run, field="sigma"):
    """Position of the bands of a 1D run's ``field`` in each frame and their mean speed over
    the second half of the run. The bands are the field's strongest Fourier mode m (in the last
    frame); its phase, unwrapped in time, moves a crest by -d(phase)/k: robust where m equal
    bands share the box."""
    if run.dim != 1:
        raise ValueError("band_track: needs a 1D run")
    L = run.length[0]
    spectrum = np.fft.rfft(getattr(run, field), axis=1)
    m = 1 + int(np.argmax(np.abs(spectrum[-1, 1:])))
    k = 2 * np.pi * m / L
    pos = -np.unwrap(np.angle(spectrum[:, m])) / k
    half = len(run.t) // 2
    speed = np.polyfit(run.t[half:], pos[half:], 1)[0]
    return pos, float(speed)


def profile_ahead(run, frame=-1, field="sigma"):
    """(distance ahead of the band's maximum along its motion, rho there, sigma there) of a
    1D run's frame, over one period."""
    _, speed = band_track(run, field)
    x, L = run.x, run.length[0]
    peak = x[np.argmax(getattr(run, field)[frame])]
    d = np.mod((x - peak) * np.sign(speed or 1.0), L)
    order = np.argsort(d)
    return d[order], run.rho[frame][order], run.sigma[frame][order]


# --------------------------------------------------------------------------- pictures

def _plt():
    import matplotlib
    if not os.environ.get("DISPLAY"):
        matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt


def kymograph(run, path, field="rho", ax=None):
    """Space-time picture of a 1D run's ``field``."""
    if run.dim != 1:
        raise ValueError("kymograph: needs a 1D run")
    plt = _plt()
    fig, ax = (ax.figure, ax) if ax is not None else plt.subplots(figsize=(6, 4))
    values = getattr(run, field)
    im = ax.imshow(values, origin="lower", aspect="auto", cmap="viridis",
                   extent=[0, run.length[0], run.t[0], run.t[-1]])
    fig.colorbar(im, ax=ax, label={"rho": r"bead density $\rho$", "sigma": r"rod density $\sigma$"}[field])
    ax.set_xlabel("x")
    ax.set_ylabel("t")
    if path:
        fig.tight_layout()
        fig.savefig(path, dpi=120)
        plt.close(fig)
    return fig


def _draw(ax_rho, ax_sigma, run, i):
    if run.dim == 1:
        ax_rho.clear()
        ax_rho.plot(run.x, run.rho[i], label=r"$\rho$ (beads)")
        ax_rho.plot(run.x, run.sigma[i], label=r"$\sigma$ (rods)")
        ax_rho.set_ylim(min(run.rho.min(), run.sigma.min()), max(run.rho.max(), run.sigma.max()))
        ax_rho.set_xlabel("x")
        ax_rho.legend(loc="upper right")
        ax_rho.set_title(f"t = {run.t[i]:.4g}")
        return
    ext = [0, run.length[0], 0, run.length[1]]
    for ax, name, cmap in ((ax_rho, "rho", "viridis"), (ax_sigma, "sigma", "magma")):
        ax.clear()
        values = getattr(run, name)
        ax.imshow(values[i], origin="lower", extent=ext, cmap=cmap, vmin=values.min(), vmax=values.max())
        ax.set_title(rf"$\{name}$, t = {run.t[i]:.4g}")


def snapshot(run, path, frame=-1):
    """One frame: rho and sigma against x (1D), or both as images (2D)."""
    plt = _plt()
    if run.dim == 1:
        fig, ax = plt.subplots(figsize=(6, 3.5))
        axes = (ax, None)
    else:
        fig, axes = plt.subplots(1, 2, figsize=(9, 4))
    _draw(axes[0], axes[1], run, frame if frame >= 0 else len(run.t) + frame)
    fig.tight_layout()
    if path:
        fig.savefig(path, dpi=120)
        plt.close(fig)
    return fig


def movie(run, path, fps=10, dpi=80):
    """Animate the frames (GIF through Pillow; .mp4 where ffmpeg is installed)."""
    plt = _plt()
    from matplotlib import animation
    if run.dim == 1:
        fig, ax = plt.subplots(figsize=(6, 3.5))
        axes = (ax, None)
    else:
        fig, axes = plt.subplots(1, 2, figsize=(8, 3.8))
    anim = animation.FuncAnimation(fig, lambda i: _draw(axes[0], axes[1], run, i), frames=len(run.t))
    writer = animation.PillowWriter(fps=fps) if str(path).endswith(".gif") else animation.FFMpegWriter(fps=fps)
    anim.save(path, writer=writer, dpi=dpi)
    plt.close(fig)


def plot_stability_diagram(params, rho0, sigma0, path, ax=None):
    """The regimes (stable / condensation / travelling) in the (rho0, sigma0) plane."""
    plt = _plt()
    from matplotlib.colors import ListedColormap
    regimes = stability_diagram(params, rho0, sigma0)
    fig, ax = (ax.figure, ax) if ax is not None else plt.subplots(figsize=(5, 4))
    cmap = ListedColormap(["#dddddd", "#4c72b0", "#dd8452"])
    ax.pcolormesh(rho0, sigma0, regimes, cmap=cmap, vmin=-0.5, vmax=2.5, shading="nearest")
    for i, name in enumerate(REGIMES):
        ax.plot([], [], "s", color=cmap(i), label=name)
    ax.legend(loc="upper right", fontsize=8)
    ax.set_xlabel(r"$\rho_0$ (beads)")
    ax.set_ylabel(r"$\sigma_0$ (rods)")
    if path:
        fig.tight_layout()
        fig.savefig(path, dpi=120)
        plt.close(fig)
    return fig
