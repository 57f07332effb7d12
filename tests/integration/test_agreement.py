"""One definition of each measured quantity, two implementations: compute polar/rod and compute
areafrac/chunk against python/activegrain on the same frame. The -small channel, box and annulus
decks and the 80 mm x 12 mm channel of issue 9 are created and run 10 steps on 1, 2 and 4 ranks
(the box and the channel on 8 too, where their polar order must also be that of 1 rank);
the last frame is dumped at full precision (%.12g) with the body column, the computes' output at
%.15g. Python must find the same rods (beads with molecule ID 0, whatever the rank count), the
same polar order |<p>| and <p> of the in-plane axes, nematic order and rod count (to 1e-6), and
the same per-bin bead and rod area fractions (to 1e-3) when it counts area per atom centre as the
compute does. An atom centred on a bin edge (to the dump's 12 digits: beads of the creation
lattice sit exactly on some edges of the channels' 1 mm slabs) may be counted on either side, so
its area is allowed in both bins.

Measured (4Feb2025 and 4Jul2026 alike, on 1, 2 and 4 ranks): |<p>|, <p>, S differ by at most
4e-12, rod counts are equal (12, 13, 10, 8 rods), bins without an atom on an edge differ by at
most 2e-11 (box), 4e-12 (channels), 1e-12 (annulus); 4 slabs of each channel hold beads on an
edge."""
import os
import pathlib
import subprocess

import numpy as np
import pytest

from mpi_launch import mpi_prefix

from activegrain import analysis, read_frame
from activegrain.geometry import Annulus, geometry_from_box

ROOT = pathlib.Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples"
LMP = os.environ.get("ACTIVEGRAIN_LMP", str(ROOT / "build" / "lmp"))
STEPS = 10
DT = 1.0e-4           # the decks' time step
ORDER_TOLERANCE = 1e-6
AREA_TOLERANCE = 1e-3
EDGE = 1e-9        # of a bin width: an atom this close to a bin edge is on it

# (folder, deck, variables, ID of the deck's compute areafrac/chunk, its bins)
CASES = {
    "channel": ("channel", "in.channel-small", [], "phi", ("x", 1e-3)),
    "box": ("box", "in.box-small", [], "phi", ("xy", 2e-3)),
    "annulus": ("annulus", "in.annulus-small", [], "radial", ("r", 1e-3)),
    "channel-80x12": ("channel", "in.channel", ["Lx", "80e-3", "Ly", "12e-3", "phi_b", "0.749", "phi_r", "0.03"],
                      "phi", ("x", 1e-3)),
}
ANNULUS_RADII = (6e-3, 20e-3)    # in.annulus-small

WRAPPER = """include {deck}
dump            agree all custom 1 {out}/agree.dump id mol type radius x y z f_rodsfix[4]
dump_modify     agree sort id format float %.12g colname f_rodsfix[4] body
fix             agree_order all ave/time 1 1 1 c_order[*] file {out}/order.txt format " %.15g"
fix             agree_bins all ave/time 1 1 1 c_{bins}[*] mode vector file {out}/bins.txt format " %.15g"
run             0 post no
"""


def run_case(name, ranks, out):
    folder, deck, variables, bins, _ = CASES[name]
    wrapper = out / "in.agree"
    wrapper.write_text(WRAPPER.format(deck=deck, out=out, bins=bins))
    var_args = [a for k, v in zip(variables[::2], variables[1::2]) for a in ("-var", k, v)]
    cmd = [*mpi_prefix(ranks), LMP, "-in", str(wrapper), "-var", "out", str(out), "-var", "time", str(STEPS * DT),
           "-log", str(out / "log.lammps"), *var_args]
    done = subprocess.run(cmd, cwd=EXAMPLES / folder, capture_output=True, text=True, timeout=120)
    assert done.returncode == 0 and "ERROR" not in done.stdout, done.stdout[-3000:] + done.stderr[-3000:]
    return out


def computes(out):
    """compute polar/rod's vector and compute areafrac/chunk's rows, at the dumped step."""
    order = np.loadtxt(out / "order.txt", ndmin=2)[-1]
    rows = [l.split() for l in (out / "bins.txt").read_text().splitlines() if l.strip() and not l.startswith("#")]
    nrows = int(rows[-1][0])    # chunk index of the last row
    table = np.array([[float(v) for v in r] for r in rows[-nrows:]])
    return order[1:], table[:, 1:]


def on_edges(q, edges, period):
    """Per point (coordinate q) and bin: (on one of the bin's edges, within the bin or on its
    edges). On an edge means within EDGE of it: to the dump's precision either side may count
    the point (the computes truncate (x - lo) / width in their own arithmetic)."""
    tolerance = EDGE * np.diff(edges)[None, :]
    on, within = np.zeros((len(q), len(edges) - 1), bool), np.zeros((len(q), len(edges) - 1), bool)
    for shift in [0.0] + ([-period, period] if period else []):
        qq = (q + shift)[:, None]
        on |= (np.abs(qq - edges[None, :-1]) <= tolerance) | (np.abs(qq - edges[None, 1:]) <= tolerance)
        within |= (qq >= edges[None, :-1] - tolerance) & (qq <= edges[None, 1:] + tolerance)
    return on, within


def python_bins(frame, name):
    """Bead and rod area fractions per chunk, in compute chunk/atom's order, counted per atom
    centre; and per chunk the fraction carried by atoms centred on one of its edges."""
    _, _, _, _, (coord, width) = CASES[name]
    box = frame.box
    along = [np.arange(box.lo[k], box.hi[k] + 0.5 * width, width) for k in (0, 1)]
    if coord == "r":
        geometry = Annulus(box, (0.0, 0.0), *ANNULUS_RADII)
        axes = [("r", np.arange(ANNULUS_RADII[0], ANNULUS_RADII[1] + 0.5 * width, width))]
    else:
        geometry = geometry_from_box(box)
        axes = [(c, along["xy".index(c)]) for c in coord]
    phi, on_edge = [], []
    for species in ("beads", "rods"):
        if coord == "xy":
            fraction = analysis.area_fraction_map(frame, geometry, along, species, count="centre")[2].ravel()
            area = np.outer(np.diff(along[0]), np.diff(along[1])).ravel()
        else:
            profile = analysis.area_fraction_profile(frame, geometry, coord, axes[0][1], species, count="centre")
            fraction, area = profile.fraction, geometry.bin_areas(coord, axes[0][1])
        xy, w = analysis.area_samples(frame, species, count="centre")
        edges = []
        for c, e in axes:
            period = box.lengths["xy".index(c)] if c in "xy" and geometry.is_periodic(c) else 0.0
            edges.append(on_edges(geometry.coordinate(xy, c), e, period))
        if len(edges) == 1:
            near = edges[0][0]
        else:    # on an edge of cell (i, j): on an x edge of column i within row j, or the reverse
            (on_x, in_x), (on_y, in_y) = edges
            near = ((on_x[:, :, None] & in_y[:, None, :]) | (in_x[:, :, None] & on_y[:, None, :])).reshape(len(w), -1)
        phi.append(fraction)
        on_edge.append((w[:, None] * near).sum(axis=0) / area)
    return np.column_stack(phi), np.column_stack(on_edge)


@pytest.fixture(scope="module")
def results(tmp_path_factory):
    cache = {}

    def get(name, ranks):
        if (name, ranks) not in cache:
            cache[name, ranks] = run_case(name, ranks, tmp_path_factory.mktemp(f"{name}-{ranks}"))
        return cache[name, ranks]
    return get


# On 8 ranks (4 x 2 sub-domains in the plane, rods across their corners) the channel and the box.
RUNS = [(name, ranks) for name in sorted(CASES) for ranks in (1, 2, 4)] + [("box", 8), ("channel", 8)]


@pytest.mark.parametrize("name,ranks", RUNS)
def test_python_and_computes_agree(results, name, ranks):
    out = results(name, ranks)
    frame = read_frame(str(out / "agree.dump"))
    # Beads are in no molecule and rods are the fix's bodies, on any number of ranks.
    assert np.array_equal(frame.mol > 0, frame.body > 0), frame.ids[(frame.mol > 0) != (frame.body > 0)]
    rods = frame.rods()
    by_mol = read_frame(str(out / "agree.dump"))
    by_mol.body = None
    assert len(by_mol.rods()) == len(rods)

    vector, table = computes(out)
    polar, px, py, _, nematic, count = vector
    measured = analysis.polarization(frame)
    assert measured["n_rods"] == count > 0
    assert abs(measured["P"] - polar) < ORDER_TOLERANCE
    assert abs(measured["Px"] - px) < ORDER_TOLERANCE and abs(measured["Py"] - py) < ORDER_TOLERANCE
    assert abs(measured["S"] - nematic) < ORDER_TOLERANCE

    phi, on_edge = python_bins(frame, name)
    assert phi.shape == table[:, :2].shape
    difference = np.abs(phi - table[:, :2])
    assert np.all(difference <= AREA_TOLERANCE + on_edge), (difference.max(), np.abs(difference - on_edge).max())


@pytest.mark.parametrize("name,ranks", [("box", 8), ("channel", 8)])
def test_polar_order_is_the_same_on_eight_ranks_as_on_one(results, name, ranks):
    """compute polar/rod's polar and nematic order and rod count after the 10 steps, 8 ranks
    against 1: the same rods, the order to ORDER_TOLERANCE."""
    one, many = computes(results(name, 1))[0], computes(results(name, ranks))[0]
    print(f"[ measured ] {name}: |<p>|, <p>, S, rods on {ranks} ranks {many[[0, 1, 2, 4, 5]]}, on 1 {one[[0, 1, 2, 4, 5]]}")
    assert many[5] == one[5] > 0
    assert np.abs(many[:5] - one[:5]).max() < ORDER_TOLERANCE
