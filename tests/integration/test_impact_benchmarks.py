"""examples/impact-benchmarks/run.sh --short: the impact-level benchmarks of Chung and Ooi (2011)
with this package's stick law against the rigid-body answers, worked out here from the bodies'
inverse-mass matrix (not from the closed forms of the example's rigid_body.py), its compliant law,
and stock LAMMPS Hertz-Mindlin run beside them. Tolerances: tests 4-8, velocities to 1e-6 of the case's speed before
the impact, spins to 1e-6 of that speed over the radius; tests 1-3, restitution and energy ratio
to 1e-9."""
import os
import pathlib
import shutil
import subprocess

import numpy as np
import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
HERE = ROOT / "examples" / "impact-benchmarks"
LMP = os.environ.get("ACTIVEGRAIN_LMP", str(ROOT / "build" / "lmp"))
TOL = 1e-6

# the cases of run.sh: per test, sphere 1 (R, density) and the target (None: the plane), e, mu
SPHERES = {
    "test4": dict(R1=0.0025, rho1=4000.0, target=None, e=0.98, mu=0.092),
    "test5": dict(R1=1e-5, rho1=7850.0, target=None, e=1.0, mu=0.3),
    "test6": dict(R1=0.1, rho1=2700.0, target=None, e=0.5, mu=0.4),
    "test7": dict(R1=0.1, rho1=2700.0, target=(0.1, 2700.0), e=0.5, mu=0.4),
    "test8": dict(R1=0.1, rho1=2700.0, target=(0.5, 2.7e6), e=0.5, mu=0.4),
    "test8:equal-density": dict(R1=0.1, rho1=2700.0, target=(0.5, 2700.0), e=0.5, mu=0.4),
}


def initial(test, x):
    """Sphere 1's and sphere 2's (v, omega) before the impact, 3-vectors, for run.sh's X."""
    zero = np.zeros(3)
    if test == "test4":
        t = np.radians(x)
        return (np.array([3.9 * np.sin(t), 0, -3.9 * np.cos(t)]), zero), (zero, zero)
    if test == "test5":
        return (np.array([x, 0, -5.0]), zero), (zero, zero)
    spin = np.array([0, x, 0])
    if test == "test7":
        return (np.array([0, 0, -0.2]), spin), (np.array([0, 0, 0.2]), -spin)
    return (np.array([0, 0, -0.2]), spin), (zero, zero)     # tests 6 and 8


def cross_matrix(r):
    return np.array([[0, -r[2], r[1]], [r[2], 0, -r[0]], [-r[1], r[0], 0]])


def rigid_body(test, x):
    """Stronge's impact with Coulomb friction, stick if it can: sphere 1's (v, omega) after."""
    p = SPHERES[test]
    n = np.array([0.0, 0.0, 1.0])                       # the target's normal, towards sphere 1
    (v1, w1), (v2, w2) = initial(test.split(":")[0], x)
    m1 = p["rho1"] * 4 / 3 * np.pi * p["R1"] ** 3
    r1 = -p["R1"] * n                                   # sphere 1's centre to the contact point
    K = np.eye(3) / m1 - cross_matrix(r1) @ np.linalg.inv(0.4 * m1 * p["R1"] ** 2 * np.eye(3)) @ cross_matrix(r1)
    u = v1 + np.cross(w1, r1)
    if p["target"]:
        R2, rho2 = p["target"]
        m2 = rho2 * 4 / 3 * np.pi * R2 ** 3
        r2 = R2 * n
        K += np.eye(3) / m2 - cross_matrix(r2) @ np.linalg.inv(0.4 * m2 * R2 ** 2 * np.eye(3)) @ cross_matrix(r2)
        u -= v2 + np.cross(w2, r2)
    un = u @ n
    J = np.linalg.solve(K, -(1 + p["e"]) * un * n - (u - un * n))     # ends at -e un, no slip
    Jn, Jt = J @ n, J - (J @ n) * n
    if np.linalg.norm(Jt) > p["mu"] * Jn:                              # slides against the slip
        t = (u - un * n) / np.linalg.norm(u - un * n)
        d = n - p["mu"] * t
        J = -(1 + p["e"]) * un / (n @ K @ d) * d
    I1 = 0.4 * m1 * p["R1"] ** 2
    return v1 + J / m1, w1 + np.cross(r1, J) / I1


@pytest.fixture(scope="module")
def results(tmp_path_factory):
    """run.sh --short's lines, split into fields, and the text."""
    env = dict(os.environ, ACTIVEGRAIN_LMP=LMP)
    done = subprocess.run(["bash", str(HERE / "run.sh"), "--short"], cwd=tmp_path_factory.mktemp("impact"),
                          env=env, capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stdout[-3000:] + done.stderr[-3000:]
    lines = [line.split() for line in done.stdout.splitlines() if line and not line.startswith("#")]
    return lines, done.stdout


def normal_rows(lines, law):
    """Tests 1-3's lines of a law: (test, law, material, x, vin, vout, ratio, duration), all three tests."""
    normal = [f for f in lines if f[0] in ("test1", "test2", "test3") and f[1] == law]
    assert {f[0] for f in normal} == {"test1", "test2", "test3"}
    return normal


def oblique_rows(lines, test, law):
    return [[float(v) for v in f[2:]] for f in lines if f[0] == test and f[1] == law]


@pytest.mark.parametrize("test,law", [("test4", "stick"), ("test5", "stick"), ("test6", "stick"), ("test7", "stick"),
                                      ("test8", "stick"), ("test8", "stick:equal-density")])
def test_stick_law_is_the_rigid_body_answer(results, test, law):
    lines, _ = results
    rows = oblique_rows(lines, test, law)
    assert len(rows) == 3, rows                       # --short: three values of X
    key = test if law == "stick" else test + ":" + law.split(":")[1]
    R = SPHERES[key]["R1"]
    worst = 0.0
    for x, vx, vz, wy in rows:
        (v1, w1), _ = initial(test, x)
        scale = max(np.linalg.norm(v1), R * np.linalg.norm(w1))
        v, w = rigid_body(key, x)
        dv = max(abs(vx - v[0]), abs(vz - v[2])) / scale
        dw = abs(wy - w[1]) * R / scale
        worst = max(worst, dv, dw)
        assert dv < TOL and dw < TOL, (test, x, (vx, vz, wy), (v[0], v[2], w[1]))
    print(f"{test} {law}: largest difference {worst:.1e} of the speed scale")


def test_the_cases_stick_and_slide(results):
    """The short lists cross the sticking limit: test 4 sticks at 10 and 30 degrees (the contact
    point leaves with no tangential velocity) and slides at 60; test 6 sticks at 0.54 and 2 rad/s."""
    lines, _ = results
    rows = {x: (vx, vz, w) for x, vx, vz, w in oblique_rows(lines, "test4", "stick")}
    assert sorted(rows) == [10, 30, 60]
    for x in (10, 30):
        vx, vz, w = rows[x]
        assert abs(vx - 0.0025 * w) < 1e-12 * abs(vx)
    vx, vz, w = rows[60]
    assert vx - 0.0025 * w > 0.1
    rows = oblique_rows(lines, "test6", "stick")
    assert [abs(vx - 0.1 * w) < 1e-12 for x, vx, vz, w in rows] == [True, True, False]


def test_normal_impacts_keep_energy_and_restitution(results):
    lines, _ = results
    normal = normal_rows(lines, "stick")
    for test, law, material, x, vin, vout, ratio, duration in normal:
        e = float(x)
        assert abs(float(vout) / float(vin) - e) < 1e-9, (test, material, x, vout)
        assert abs(float(ratio) - e * e) < 1e-9, (test, material, x, ratio)
        assert float(duration) == 0.0                 # one impulse: no contact duration
    assert sorted(float(f[3]) for f in normal if f[0] == "test3") == [0.0, 0.5, 1.0]


def test_stock_hertz_mindlin_runs_and_reverses_the_contact_point(results):
    """Stock pair granular runs every oblique test; its elastic contact lasts Hertz's time (test 1
    and 2, within the 1/500 of it that the time step resolves); below the sticking limit its
    tangential spring sends the contact point back (test 4 at 10 degrees, test 6 at 2 rad/s),
    which the stick law cannot."""
    lines, _ = results
    for test in ("test4", "test5", "test6", "test7", "test8"):
        rows = oblique_rows(lines, test, "stock-mindlin")
        assert len(rows) == 3 and np.all(np.isfinite(rows)), (test, rows)
    for test in ("test1", "test2"):
        hertz = next(float(f[7]) for f in lines if f[0] == test and f[1] == "hertz")
        stock = next(float(f[7]) for f in lines if f[0] == test and f[1] == "stock-mindlin")
        assert abs(stock / hertz - 1) < 5e-3, (test, stock, hertz)
    x, vx, vz, w = oblique_rows(lines, "test4", "stock-mindlin")[0]
    assert x == 10 and vx - 0.0025 * w < -0.01       # incoming contact point moves +x
    x, vx, vz, w = oblique_rows(lines, "test6", "stock-mindlin")[1]
    assert x == 2 and vx - 0.1 * w > 0.01            # incoming contact point moves -x (0.1 * 2 m/s)


def test_compliant_law_keeps_restitution_and_reverses_like_stock(results):
    """The compliant law (tangential springs): the normal rebound is Stronge's, as the stick law's
    (tests 1-3: a sphere's normal does not couple to its tangents); in test 4 at 10 degrees its
    contact point leaves backwards, as stock's does, where the stick law's leaves at rest; at 60
    degrees (sliding all through) it is the stick law's answer (1e-4 of the speed)."""
    lines, _ = results
    for test, law, material, x, vin, vout, ratio, duration in normal_rows(lines, "compliant"):
        e = float(x)
        assert abs(float(vout) / float(vin) - e) < 1e-9, (test, material, x, vout)
        assert abs(float(ratio) - e * e) < 1e-9, (test, material, x, ratio)
    compliant = {row[0]: row[1:] for row in oblique_rows(lines, "test4", "compliant")}
    stick = {row[0]: row[1:] for row in oblique_rows(lines, "test4", "stick")}
    vx, vz, w = compliant[10]
    assert vx - 0.0025 * w < -0.01                   # incoming contact point moves +x
    assert np.allclose(compliant[60], stick[60], rtol=0, atol=1e-4 * 3.9 / np.array([1, 1, 0.0025]))
    for test in ("test5", "test6", "test7", "test8"):
        rows = oblique_rows(lines, test, "compliant")
        assert len(rows) == 3 and np.all(np.isfinite(rows)), (test, rows)


@pytest.mark.skipif(not shutil.which("/usr/bin/python3"), reason="no /usr/bin/python3")
def test_plot_draws_each_test(results, tmp_path):
    _, text = results
    (tmp_path / "results.txt").write_text(text)
    done = subprocess.run(["/usr/bin/python3", str(HERE / "plot.py"), str(tmp_path / "results.txt"), str(tmp_path)],
                          capture_output=True, text=True, timeout=300, env=dict(os.environ, MPLBACKEND="Agg"))
    assert done.returncode == 0, done.stderr[-3000:]
    for test in ("test3", "test4", "test5", "test6", "test7", "test8"):
        assert (tmp_path / f"{test}.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n", test
