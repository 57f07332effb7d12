"""Figures as saved: a profile draws every bin over its whole width, and no text (label, tick
label, title, colour bar label) reaches past the figure's edge."""
import io

import matplotlib.lines
import matplotlib.pyplot as plt
import matplotlib.text
import numpy as np
import pytest

from activegrain import Box, analysis as A, geometry_from_box, plotting, synthetic as S
from activegrain.geometry import Annulus


def drawn_steps(ax):
    """The horizontal segments (x0, x1) of the lines and outlines drawn in ``ax``, in data units."""
    paths = []
    for line in ax.get_lines():
        x, y = line.get_data()
        paths.append(np.column_stack(matplotlib.lines.STEP_LOOKUP_MAP[line.get_drawstyle()](x, y)))
    paths += [patch.get_path().vertices for patch in ax.patches]
    segments = []
    for v in paths:
        flat = (v[1:, 1] == v[:-1, 1]) & (v[1:, 0] != v[:-1, 0])
        segments += [(min(a, b), max(a, b)) for a, b in zip(v[:-1][flat, 0], v[1:][flat, 0])]
    return sorted(segments)


def test_a_profile_draws_its_end_bins_at_full_width():
    edges = np.linspace(0.0, 10.0, 6)
    profile = A.Profile("x", "beads", edges, np.array([0.1, 0.3, 0.2, 0.5, 0.4]))
    fig = plotting.plot_profiles([profile])
    steps = drawn_steps(fig.axes[0])
    plt.close(fig)
    assert steps[0][0] == 0.0 and steps[-1][1] == 10.0
    assert np.allclose([b - a for a, b in steps], 2.0)
    assert np.allclose(np.array(steps).ravel(), np.repeat(edges, 2)[1:-1])


@pytest.fixture
def drawn_texts(monkeypatch):
    """Every text drawn, with its extent and the figure's, in pixels, as it was drawn."""
    drawn = []
    draw = matplotlib.text.Text.draw

    def spy(text, renderer):
        draw(text, renderer)
        if text.get_visible() and text.get_text():
            drawn.append((text.get_text(), text.get_window_extent(renderer), text.figure.bbox.frozen()))
    monkeypatch.setattr(matplotlib.text.Text, "draw", spy)
    return drawn


def frames_and_geometries():
    """A channel in bead diameters and in metres, and an annulus in metres (negative tick labels
    of three decimals: the widest)."""
    channel = S.phase_configuration("condensed")
    box = Box((-30.0, -30.0, 0.0), (30.0, 30.0, 1.12), (False, False, False))
    beads = S.lattice_beads(-30, 30, -30, 30, 1.05)
    r = np.hypot(*beads.T)
    ring = S.make_frame(box, beads[(r > 15.6) & (r < 27.4)], 0.5, [(20.0, 0.0)], [(0.0, 1.0)])
    for frame, scale in ((channel, 1.0), (channel, 1e-3), (ring, 1e-3)):
        f = frame.scaled(scale)
        if frame is ring:
            yield f, Annulus(f.box, (0.0, 0.0), 15.0 * scale, 28.0 * scale)
        else:
            yield f, geometry_from_box(f.box)


def figures(frame, geometry):
    unit = plotting.length_label(frame)
    coord = "theta" if isinstance(geometry, Annulus) else "x"
    profile = A.area_fraction_profile(frame, geometry, coord, 40, "all")
    yield "profile", plotting.plot_profiles([profile], unit=unit, labels=["beads and rods, mean of 3 frame(s)"],
                                            title="mean over t = 0.00-0.20 s (3 frames)")
    xe, ye, phi = A.area_fraction_map(frame, geometry, (60, 12), "all")
    yield "map", plotting.plot_map(xe, ye, phi, unit=unit, label="area fraction of beads and rods",
                                   title="mean over t = 0.00-0.20 s (3 frames)")
    yield "kymograph", plotting.kymograph([0, 1000, 2000], [profile] * 3, unit=unit, seconds=False)
    yield "snapshot", plotting.snapshot(frame, geometry)


@pytest.mark.parametrize("case", range(3))
def test_saved_figures_keep_every_text_inside(drawn_texts, case):
    frame, geometry = list(frames_and_geometries())[case]
    for name, fig in figures(frame, geometry):
        drawn_texts.clear()
        fig.savefig(io.BytesIO(), format="png", dpi=150)
        plt.close(fig)
        assert drawn_texts, name
        outside = [(text, e.bounds) for text, e, b in drawn_texts
                   if e.x0 < -0.5 or e.y0 < -0.5 or e.x1 > b.width + 0.5 or e.y1 > b.height + 0.5]
        assert outside == [], (name, frame.length_unit)
