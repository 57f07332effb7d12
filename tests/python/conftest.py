import os
import pathlib
import sys

import matplotlib
import pytest

matplotlib.use("Agg")
# the checkout's package, as ctest's PYTHONPATH gives it, also under a plain pytest (for the
# Pythons that tests start too)
PYTHON_DIR = str(pathlib.Path(__file__).resolve().parents[2] / "python")
sys.path.insert(0, PYTHON_DIR)
os.environ["PYTHONPATH"] = os.pathsep.join(filter(None, [PYTHON_DIR, os.environ.get("PYTHONPATH")]))


@pytest.fixture(scope="session")
def short_run_frames():
    """Three isotropic frames of a 40 x 20 mm cell, 1000 steps apart (SI lengths), for dumps."""
    from activegrain import synthetic as S
    frames = []
    for k in range(3):
        fr = S.phase_configuration("isotropic", length=40.0, width=20.0)
        fr.step = 1000 * k
        frames.append(fr.scaled(1e-3))
    return frames
