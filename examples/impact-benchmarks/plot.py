"""Draw run.sh's results: /usr/bin/python3 plot.py RESULTS OUTDIR writes OUTDIR/test3.png ...
test8.png. Each figure: the stick law (markers), its rigid-body answer (rigid_body.py, a line),
the compliant law (triangles on a line), stock LAMMPS Hertz-Mindlin (squares on a line; both laws
for both of the test's materials where run) and, for
test 4, the experiment of Kharaz, Gorham and Salman (2001) (kharaz2001.dat)."""
import pathlib
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

HERE = pathlib.Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
import rigid_body  # noqa: E402

# (test) -> parameters the figures need: R, normal speed, X grid of the rigid-body line, X label
CASES = {
    "test4": dict(R=0.0025, xlabel="incidence from the normal (degrees)", grid=np.linspace(0.5, 89.5, 400),
                  first="aluminium oxide"),
    "test5": dict(R=1e-5, xlabel="tangential velocity before (m/s)", grid=np.linspace(0.05, 30, 600), first="steel"),
    "test6": dict(R=0.1, xlabel="omegay before (rad/s)", grid=np.geomspace(0.1, 25, 600), first="aluminium alloy"),
    "test7": dict(R=0.1, xlabel="omegay before (rad/s)", grid=np.geomspace(0.1, 25, 600), first="aluminium alloy"),
    "test8": dict(R=0.1, xlabel="omegay before (rad/s)", grid=np.geomspace(0.1, 25, 600), first="case A"),
}
STYLE = {"stick": dict(marker="o", ls="none", ms=6, mfc="none", color="C0"),
         "compliant": dict(marker="^", ls="-", ms=4, color="C4", lw=1),
         "stock-mindlin": dict(marker="s", ls="-", ms=4, color="C3", lw=1)}
# the second material or case of a law (open markers, dashed)
SECOND_COLOUR = {"stick": "C2", "compliant": "C9", "stock-mindlin": "C1"}


def read(path):
    """{(test, law): rows} from run.sh's lines; tests 1-3 keep their material in the key."""
    out = defaultdict(list)
    for line in pathlib.Path(path).read_text().splitlines():
        f = line.split()
        if not f or f[0].startswith("#"):
            continue
        if f[0] in ("test1", "test2", "test3"):
            out[(f[0], f[1], f[2])].append([float(v) for v in f[3:]])
        else:
            out[(f[0], f[1])].append([float(v) for v in f[2:]])
    return {k: np.array(v) for k, v in out.items()}


def style(law):
    base = law.split(":")[0]
    s = dict(STYLE.get(base, dict(marker="^", ls="-", ms=4, lw=1)))
    if ":" in law:   # the second material or case: open markers, dashed
        s.update(ls="--" if s.get("ls") != "none" else "none", mfc="none", color=SECOND_COLOUR.get(base, "C1"))
    return s


def label(law, first=""):
    """'stick (this package)', 'stock Hertz-Mindlin, nylon', ... for LAW or LAW:VARIANT."""
    base, _, variant = law.partition(":")
    name = {"stick": "stick (this package)", "compliant": "compliant (this package)",
            "stock-mindlin": "stock Hertz-Mindlin"}.get(base, base)
    what = variant.replace("-", " ") or first
    return f"{name}, {what}" if what and not (base == "stick" and not variant and first != "case A") else name


def test3(results, out):
    fig, ax = plt.subplots(figsize=(4.2, 3.4), constrained_layout=True)
    ax.plot([0, 1], [0, 1], "k-", lw=0.8, label="e out = e in")
    for key, rows in sorted(results.items()):
        if key[0] != "test3" or key[1] == "hertz":
            continue
        test, law, mat = key
        s = style(law if mat == "aluminium-oxide" else law + ":" + mat)
        ax.plot(rows[:, 0], rows[:, 2] / rows[:, 1], label=f"{label(law)}, {mat.replace('-', ' ')}", **s)
    ax.set(xlabel="restitution given", ylabel="separation / approach speed", title="test 3")
    ax.legend(fontsize=7)
    fig.savefig(out / "test3.png", dpi=90)
    plt.close(fig)


def oblique(results, test, out):
    case = CASES[test]
    R, grid = case["R"], case["grid"]
    laws = sorted({law for t, law, *_ in results if t == test})
    if not laws:
        return
    answer_laws = [law for law in laws if (test, law) in rigid_body.ANSWERS]
    ncol = 2 if test == "test7" else 3
    fig, axes = plt.subplots(1, ncol, figsize=(3.6 * ncol, 3.3), constrained_layout=True)
    if test == "test4":
        V = 3.9
        quantities = [("et = vx'/vx", lambda x, vx, vz, w: vx / (V * np.sin(np.radians(x)))),
                      ("omegay after (rad/s)", lambda x, vx, vz, w: w),
                      ("contact point's rebound angle (deg)", lambda x, vx, vz, w: np.degrees(np.arctan((vx - R * w) / vz)))]
    else:
        quantities = [("vx after (m/s)", lambda x, vx, vz, w: vx),
                      ("omegay after (rad/s)", lambda x, vx, vz, w: w),
                      ("(vx - R omegay) / vz after", lambda x, vx, vz, w: (vx - R * w) / vz)][:ncol]
    for k, (ax, (name, f)) in enumerate(zip(axes, quantities)):
        for law in answer_laws:
            ans = np.array([rigid_body.ANSWERS[(test, law)](x) for x in grid])
            ax.plot(grid, f(grid, ans[:, 0], ans[:, 1], ans[:, 2]), "k-" if ":" not in law else "k:", lw=0.9,
                    label="rigid body, stick" + ("" if ":" not in law else " (" + law.split(":")[1] + ")"))
        for law in laws:
            rows = results[(test, law)]
            ax.plot(rows[:, 0], f(rows[:, 0], rows[:, 1], rows[:, 2], rows[:, 3]), label=label(law, case["first"]),
                    **style(law))
        if test == "test4":
            exp = [line.split() for line in (HERE / "kharaz2001.dat").read_text().splitlines() if not line.startswith("#")]
            key = ("et", "omega", "rebound")[k]
            pts = np.array([[float(a), float(b)] for q, a, b in exp if q == key])
            ax.plot(pts[:, 0], pts[:, 1], "kD", ms=4, label="experiment (Kharaz et al. 2001)")
        if test != "test4" and test != "test5":
            ax.set_xscale("log")
        ax.set(xlabel=case["xlabel"], ylabel=name)
        ax.grid(alpha=0.3)
    axes[0].legend(fontsize=6.5)
    fig.suptitle(test.replace("test", "test "), fontsize=10)
    fig.savefig(out / f"{test}.png", dpi=90)
    plt.close(fig)


def differences(results):
    """Per test and stick law: the largest difference from the rigid-body answer, velocities in units
    of the case's speed before the impact and spins in units of that speed over the radius."""
    for (test, law), answer in rigid_body.ANSWERS.items():
        rows = results.get((test, law))
        if rows is None:
            continue
        R = CASES[test]["R"]
        worst = max(max(abs(vx - a[0]), abs(vz - a[1]), R * abs(w - a[2])) / rigid_body.speed_scale(test, x)
                    for (x, vx, vz, w), a in ((row, answer(row[0])) for row in rows))
        print(f"{test} {law}: {len(rows)} cases, largest difference from the rigid-body answer {worst:.1e}")
    for key, rows in sorted(results.items()):
        if key[0] in ("test1", "test2", "test3") and key[1] == "stick":
            worst = max(max(abs(vout / vin - x), abs(ratio - x * x)) for x, vin, vout, ratio, duration in rows)
            print(f"{key[0]} stick {key[2]}: largest difference of restitution and energy ratio {worst:.1e}")


def main(path, outdir):
    out = pathlib.Path(outdir)
    out.mkdir(parents=True, exist_ok=True)
    results = read(path)
    differences(results)
    test3(results, out)
    for test in CASES:
        oblique(results, test, out)
    print("wrote", " ".join(sorted(p.name for p in out.glob("test*.png"))))


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
