r"""The paper's coarse-grained theory.

**Linear stability** (paper eqs. 1-2). Bead density rho, rod density sigma, currents
J_rho = -D_rho grad rho - D_rhosigma grad sigma + alpha rho P,
J_sigma = -D_sigma grad sigma - D_sigmarho grad rho + u0 sigma P, and the polarization
slaved to the gradients, (a - K lap) P = A grad rho + B grad sigma. For a perturbation
~ exp(i k x + lambda t) about (rho0, sigma0), (delta rho, delta sigma) obeys
d/dt = M(k) with

    M_ij(k) = -D_ij k^2 + c_i g_j k^2 / (a + K k^2),   c = (rho0 alpha, sigma0 u0), g = (A, B),

D = [[D_rho, D_rhosigma], [D_sigmarho, D_sigma]]. Expanded to 4th order in k (deep in the
isotropic phase, a large) this is the paper's eqs. 1-2:
c_i g_j k^2 / a - c_i g_j K k^4 / a^2. The growth rates are the eigenvalues of M.

**Moving point force** (paper eqs. 3-5). gamma J = -d Pi(rho)/dx + f delta(x - v0 t):
Pi(rho+) - Pi(rho0) = f and, with Pi' frozen at rho+, rho(x > 0) = rho0 + (rho+ - rho0)
exp(-x / l+), l+ = Pi'(rho+) / (gamma v0) (x measured from the force, positive ahead).
:func:`steady_profile` solves the same steady problem without freezing Pi', and
:func:`solve_moving_force` integrates eq. 3 with the continuity equation in time.
"""
from dataclasses import dataclass

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq
from scipy.sparse import diags


# --------------------------------------------------------------------------- linear stability

@dataclass
class LinearParameters:
    rho0: float = 1.0
    sigma0: float = 0.05
    D_rho: float = 0.0
    D_sigma: float = 0.0
    D_rho_sigma: float = 0.0
    D_sigma_rho: float = 0.0
    alpha: float = 1.0
    u0: float = 1.0
    A: float = 1.0
    B: float = 0.0
    a: float = 10.0
    K: float = 1.0

    def __post_init__(self):
        if self.a <= 0:
            raise ValueError("theory: the isotropic-phase analysis needs a > 0")


def stability_matrix(k, p, expanded=True):
    """M(k) (shape (..., 2, 2)) of d(delta rho, delta sigma)/dt = M (delta rho, delta sigma).

    ``expanded=True``: the paper's eqs. 1-2 (4th order in k); False: the full
    1/(a + K k^2) response of the slaved polarization.
    """
    k2 = np.asarray(k, float)[..., None, None] ** 2
    D = np.array([[p.D_rho, p.D_rho_sigma], [p.D_sigma_rho, p.D_sigma]])
    cg = np.outer([p.rho0 * p.alpha, p.sigma0 * p.u0], [p.A, p.B])
    response = (1 / p.a - p.K * k2 / p.a ** 2) if expanded else 1 / (p.a + p.K * k2)
    return -D * k2 + cg * k2 * response


def growth_rates(k, p, expanded=True):
    """Both eigenvalues lambda(k) of M(k), shape (..., 2) complex, larger real part first.

    Closed form of a 2x2 matrix: tr/2 +- sqrt(tr^2/4 - det).
    """
    M = stability_matrix(k, p, expanded)
    tr = M[..., 0, 0] + M[..., 1, 1]
    det = M[..., 0, 0] * M[..., 1, 1] - M[..., 0, 1] * M[..., 1, 0]
    root = np.sqrt((tr * tr / 4 - det).astype(complex))
    return np.stack([tr / 2 + root, tr / 2 - root], axis=-1)


def condensation_condition(p):
    """Paper: with D_rho = D_sigma = D_sigmarho = 0, beads condense (a diffusively growing
    mode) when A alpha rho0 + B u0 sigma0 > 0. This is the trace of M; it decides alone
    when det M ~ A D_rhosigma u0 sigma0 >= 0 (otherwise a real mode grows regardless)."""
    return p.A * p.alpha * p.rho0 + p.B * p.u0 * p.sigma0 > 0


def nonreciprocity_condition(p):
    """Paper: with D_rho = D_sigma = D_sigmarho = 0, the modes are complex (travelling,
    non-reciprocal) when (A alpha rho0 - B u0 sigma0)^2 + 4 A B alpha rho0 u0 sigma0
    < 4 a A D_rhosigma u0 sigma0."""
    ar, bs = p.A * p.alpha * p.rho0, p.B * p.u0 * p.sigma0
    return (ar - bs) ** 2 + 4 * p.A * p.B * p.alpha * p.rho0 * p.u0 * p.sigma0 \
        < 4 * p.a * p.A * p.D_rho_sigma * p.u0 * p.sigma0


def fastest_mode(p, k_max=None, n=2001, expanded=True):
    """(k*, Re lambda(k*)) of the fastest-growing mode on 0 < k <= k_max (default
    2 sqrt(a/K), past which the expansion's k^4 terms dominate its k^2 terms)."""
    k_max = k_max or 2 * np.sqrt(p.a / p.K)
    k = np.linspace(0, k_max, n)[1:]
    lam = growth_rates(k, p, expanded)[:, 0].real
    i = int(np.argmax(lam))
    return float(k[i]), float(lam[i])


# --------------------------------------------------------------------------- equations of state

@dataclass
class HendersonEOS:
    """Henderson's (1975) hard-disk equation of state, Pi = rho T (1 + eta^2/8) / (1 - eta)^2,
    eta = pi rho d^2 / 4 (area fraction). ``T``: the (granular) temperature in energy
    units, ``d``: disc diameter; rho is a number per area."""
    T: float = 1.0
    d: float = 1.0

    @property
    def rho_max(self):
        return 4 / (np.pi * self.d ** 2)  # where Henderson's form diverges (eta = 1)

    def eta(self, rho):
        return np.pi * np.asarray(rho, float) * self.d ** 2 / 4

    def pressure(self, rho):
        e = self.eta(rho)
        return np.asarray(rho, float) * self.T * (1 + e * e / 8) / (1 - e) ** 2

    def stiffness(self, rho):
        """dPi/drho."""
        e = self.eta(rho)
        return self.T * ((1 + e * e / 8) / (1 - e) ** 2 + e * (e / 4) / (1 - e) ** 2
                         + e * 2 * (1 + e * e / 8) / (1 - e) ** 3)


@dataclass
class IdealEOS:
    """Pi = T rho: a constant stiffness, for which eq. 5's exponential is exact."""
    T: float = 1.0
    rho_max: float = np.inf

    def pressure(self, rho):
        return self.T * np.asarray(rho, float)

    def stiffness(self, rho):
        return self.T * np.ones_like(np.asarray(rho, float))


# --------------------------------------------------------------------------- moving point force

@dataclass
class PointForce:
    """Eqs. 4-5: ``rho_plus`` (just ahead of the force), ``rho_minus`` (= rho0 behind it),
    ``ell_plus`` = Pi'(rho+)/(gamma v0)."""
    f: float
    rho0: float
    gamma: float
    v0: float
    rho_plus: float
    ell_plus: float

    @property
    def rho_minus(self):
        return self.rho0

    def profile(self, x):
        """Eq. 5: rho0 behind (x < 0), rho0 + (rho+ - rho0) exp(-x/l+) ahead (x >= 0)."""
        x = np.asarray(x, float)
        ahead = self.rho0 + (self.rho_plus - self.rho0) * np.exp(-np.clip(x, 0, None) / self.ell_plus)
        return np.where(x >= 0, ahead, self.rho0)


def point_force(f, rho0, gamma, v0, eos=None):
    """Solve eq. 4 for rho+ (Pi(rho+) - Pi(rho0) = f) and give l+ of eq. 5."""
    eos = eos or HendersonEOS()
    if f <= 0 or gamma <= 0 or v0 <= 0:
        raise ValueError("point_force: f, gamma and v0 must be positive")
    target = eos.pressure(rho0) + f
    hi = rho0 + 1.0
    if np.isfinite(eos.rho_max):
        hi = eos.rho_max * (1 - 1e-14)
    else:
        while eos.pressure(hi) < target:
            hi = rho0 + 2 * (hi - rho0)
    rho_plus = brentq(lambda r: eos.pressure(r) - target, rho0, hi, xtol=1e-14, rtol=1e-13)
    return PointForce(f, rho0, gamma, v0, rho_plus, float(eos.stiffness(rho_plus) / (gamma * v0)))


def steady_profile(x, pf, eos=None):
    """Steady density ahead of the force without freezing Pi': in the frame moving with
    the force, gamma v0 (rho - rho0) = -Pi'(rho) drho/dx, rho(0+) = rho+ (x >= 0)."""
    eos = eos or HendersonEOS()
    x = np.asarray(x, float)
    if np.any(x < 0) or np.any(np.diff(x) <= 0):
        raise ValueError("steady_profile: x must be >= 0 and increasing")
    rhs = lambda _, r: -pf.gamma * pf.v0 * (r - pf.rho0) / eos.stiffness(r)
    sol = solve_ivp(rhs, (0.0, x[-1]), [pf.rho_plus], t_eval=x, method="LSODA", rtol=1e-10, atol=1e-13)
    return sol.y[0]


def solve_moving_force(f, rho0, gamma, v0, eos=None, behind=10.0, ahead=40.0, n=1000,
                       width=None, t_end=None):
    """Integrate eq. 3 with continuity in time, in the frame of the force.

    d rho/dt = d/dx [ v0 rho + Pi'(rho) (d rho/dx) / gamma - f delta_w(x) / gamma ] on
    x in [-behind, ahead] with rho = rho0 at both ends, starting from rho0; delta_w is a
    normalised Gaussian of width ``width`` (default 3 cells). Finite volumes, implicit
    (BDF) time stepping to ``t_end`` (default 4 crossings of the domain at v0).
    Returns (x, rho).
    """
    eos = eos or HendersonEOS()
    edges = np.linspace(-behind, ahead, n + 1)
    x = 0.5 * (edges[1:] + edges[:-1])
    h = edges[1] - edges[0]
    width = width or 3 * h
    force = f * np.exp(-0.5 * (edges[1:-1] / width) ** 2) / (np.sqrt(2 * np.pi) * width)

    def flux(rho):  # at interior faces: advection (upwind, beads move at -v0 here) + diffusion
        r = np.concatenate([[rho0], rho, [rho0]])
        face_rho = r[2:-1]  # upwind: material arrives from +x
        stiff = eos.stiffness(0.5 * (r[1:-2] + r[2:-1]))
        drho = (r[2:-1] - r[1:-2]) / h
        inner = v0 * face_rho + stiff * drho / gamma - force / gamma
        # boundary faces: Dirichlet rho0 half a cell outside
        left = v0 * rho[0] + eos.stiffness(rho0) * (rho[0] - rho0) / (h / 2) / gamma
        right = v0 * rho0 + eos.stiffness(rho0) * (rho0 - rho[-1]) / (h / 2) / gamma
        return np.concatenate([[left], inner, [right]])

    def rhs(_, rho):
        return np.diff(flux(rho)) / h  # d rho/dt = d(flux)/dx

    t_end = t_end or 4 * (behind + ahead) / v0
    sparsity = diags([1, 1, 1], [-1, 0, 1], shape=(n, n))
    sol = solve_ivp(rhs, (0, t_end), np.full(n, rho0), method="BDF", jac_sparsity=sparsity,
                    rtol=1e-7, atol=1e-10)
    if not sol.success:
        raise RuntimeError(f"solve_moving_force: time integration failed: {sol.message}")
    return x, sol.y[:, -1]
