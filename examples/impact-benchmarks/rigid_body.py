"""Rigid-body answers of the stick law (Stronge's impact with Coulomb friction, a contact that can
stick ends with no slip) for the Chung and Ooi benchmarks, in the decks' frame: normal along z,
tangential along x, spin about y (LAMMPS omegay), sphere 1 coming down onto a plane or onto
sphere 2 below it. Solid spheres (I = 0.4 m R^2).

With J the impulse on sphere 1 at its lowest point, the contact point's velocity relative to the
target, u = (v1x - R1 w1 - v2x - R2 w2, v1z - v2z), changes by
    du_z = J_z / m*,    du_x = 7/2 J_x / m*,    m* = m1 m2 / (m1 + m2)   (m* = m1 on a plane),
the 7/2 = 1 + R^2 m / I for each sphere. The normal impulse is J_z = -(1 + e) m* u_z; the contact
sticks (u_x ends at 0, J_x = -2/7 m* u_x) when that needs no more than mu J_z, that is when
|u_x| <= 7/2 mu (1 + e) |u_z|; otherwise it slides: J_x = -mu J_z sign(u_x). For two spheres the
slip keeps its direction during the impact, so Stronge's energetic restitution is Newton's."""
import math


def sphere_mass(R, rho):
    return rho * 4.0 / 3.0 * math.pi * R ** 3


def stick(v1x, v1z, w1, R1, m1, e, mu, v2x=0.0, v2z=0.0, w2=0.0, R2=0.0, m2=math.inf):
    """Sphere 1's (vx, vz, omegay) and sphere 2's after the impact; m2 = inf: a fixed plane."""
    mstar = m1 if math.isinf(m2) else m1 * m2 / (m1 + m2)
    ux = v1x - R1 * w1 - (v2x + R2 * w2)
    uz = v1z - v2z
    Jz = -(1.0 + e) * mstar * uz
    Jx = -2.0 / 7.0 * mstar * ux
    if abs(Jx) > mu * Jz:
        Jx = -mu * Jz * math.copysign(1.0, ux)
    one = (v1x + Jx / m1, v1z + Jz / m1, w1 - 2.5 * Jx / (m1 * R1))
    if math.isinf(m2):
        return one, (0.0, 0.0, 0.0)
    return one, (v2x - Jx / m2, v2z - Jz / m2, w2 - 2.5 * Jx / (m2 * R2))


def sticking_limit(e, mu):
    """|u_x| / |u_z| below which the contact sticks: 7/2 mu (1 + e)."""
    return 3.5 * mu * (1.0 + e)


# The benchmarks' cases as run.sh runs them: X -> initial state; the answer for sphere 1.
def test4(theta_deg, V=3.9, R=0.0025, rho=4000.0, e=0.98, mu=0.092):
    t = math.radians(theta_deg)
    return stick(V * math.sin(t), -V * math.cos(t), 0.0, R, sphere_mass(R, rho), e, mu)[0]


def test5(vt, Vn=5.0, R=1e-5, rho=7850.0, e=1.0, mu=0.3):
    return stick(vt, -Vn, 0.0, R, sphere_mass(R, rho), e, mu)[0]


def test6(w, Vn=0.2, R=0.1, rho=2700.0, e=0.5, mu=0.4):
    return stick(0.0, -Vn, w, R, sphere_mass(R, rho), e, mu)[0]


def test7(w, Vn=0.2, R=0.1, rho=2700.0, e=0.5, mu=0.4):
    m = sphere_mass(R, rho)
    return stick(0.0, -Vn, w, R, m, e, mu, v2z=Vn, w2=-w, R2=R, m2=m)[0]


def test8(w, Vn=0.2, R1=0.1, rho1=2700.0, R2=0.5, rho2=2.7e6, e=0.5, mu=0.4):
    return stick(0.0, -Vn, w, R1, sphere_mass(R1, rho1), e, mu, R2=R2, m2=sphere_mass(R2, rho2))[0]


def speed_scale(test, x):
    """The case's speed before the impact, max(|v1|, R1 |omega1|): what differences are measured in."""
    if test == "test4":
        return 3.9
    if test == "test5":
        return math.hypot(5.0, x)
    return max(0.2, 0.1 * abs(x))


# LAW (or LAW:VARIANT) of run.sh's lines -> the answer's function
ANSWERS = {
    ("test4", "stick"): test4,
    ("test5", "stick"): test5,
    ("test6", "stick"): test6,
    ("test7", "stick"): test7,
    ("test8", "stick"): test8,
    ("test8", "stick:equal-density"): lambda w: test8(w, rho2=2700.0),
}
