"""The command line on bad input: one line each (ERROR: for what stops it, WARNING: for a dump
cut within a frame), no traceback; and under a Python that lacks numpy, one line saying which
Python to use."""
import os
import pathlib
import shutil
import subprocess
import sys

import numpy as np
import pytest

from activegrain import write_dump

PYTHON_DIR = pathlib.Path(__file__).resolve().parents[2] / "python"


def activegrain(*argv, python=sys.executable, pythonpath=(), cwd=None):
    env = dict(os.environ, MPLBACKEND="Agg",
               PYTHONPATH=os.pathsep.join([*map(str, pythonpath), str(PYTHON_DIR)]))
    return subprocess.run([python, "-m", "activegrain", *map(str, argv)], capture_output=True, text=True,
                          env=env, cwd=cwd, timeout=120)


def one_line(done, prefix):
    """The single line of stderr, which starts with ``prefix``."""
    assert "Traceback" not in done.stderr, done.stderr
    lines = done.stderr.splitlines()
    assert len(lines) == 1 and lines[0].startswith(prefix), done.stderr
    return lines[0]


@pytest.fixture(scope="module")
def dumps(tmp_path_factory, short_run_frames):
    folder = tmp_path_factory.mktemp("dumps")
    write_dump(folder / "run.dump", short_run_frames)
    text = (folder / "run.dump").read_text()
    (folder / "killed.dump").write_text(text[:text.index("ITEM: TIMESTEP\n2000") + 300])
    (folder / "nocols.dump").write_text("ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n1\nITEM: BOX BOUNDS pp pp pp\n"
                                        "0 1\n0 1\n0 1\nITEM: ATOMS id type x y z\n1 1 0.5 0.5 0.5\n")
    return folder


def test_a_dump_cut_within_a_frame_gives_its_whole_frames_and_one_warning_line(dumps):
    done = activegrain("phase", dumps / "killed.dump", "--length-unit", "1e-3", "--timestep", "1e-4",
                       "--window", "0.1")
    assert done.returncode == 0, done.stderr
    line = one_line(done, "WARNING: activegrain phase: ")
    assert str(dumps / "killed.dump") in line and "its 2 whole frame(s), to step 1000" in line
    rows = done.stdout.splitlines()[1:]
    assert [r.split()[0] for r in rows] == ["0", "1000"]
    whole = activegrain("phase", dumps / "run.dump", "--length-unit", "1e-3", "--timestep", "1e-4", "--window", "0.1")
    assert whole.returncode == 0 and whole.stderr == "" and whole.stdout.splitlines()[1:3] == rows


@pytest.mark.parametrize("argv, status, message", [
    (["profile", "{dir}/none.dump"], 1,
     "ERROR: activegrain profile: {dir}/none.dump: No such file or directory"),
    (["phase", "{dir}", "--timestep", "1e-4"], 1, "ERROR: activegrain phase: {dir}: Is a directory"),
    (["profile", "{dir}/run.dump", "--geometry", "hexagon"], 2,
     "ERROR: activegrain profile: argument --geometry: invalid choice: 'hexagon'"),
    (["polar", "{dir}/run.dump", "--geometry", "annulus"], 1,
     "ERROR: activegrain polar: --geometry annulus needs --r-out"),
    (["phase", "{dir}/nocols.dump", "--timestep", "1e-4"], 1,
     "ERROR: activegrain phase: {dir}/nocols.dump: dump lacks column(s) mol, radius"),
    (["profile", "{dir}/run.dump", "--bins", "many"], 2,
     "ERROR: activegrain profile: argument --bins: invalid int value: 'many'"),
    (["hexagons", "{dir}/run.dump"], 2, "ERROR: activegrain: argument COMMAND: invalid choice: 'hexagons'"),
    ([], 2, "ERROR: activegrain: the following arguments are required: COMMAND"),
])
def test_bad_arguments_give_one_error_line(dumps, argv, status, message):
    done = activegrain(*(a.format(dir=dumps) for a in argv))
    assert done.returncode == status, done.stderr
    assert one_line(done, message.format(dir=dumps))
    assert done.stdout == ""


def test_without_numpy_one_line_names_the_python_to_use(tmp_path):
    """A Python without numpy (a pyenv or venv one): a numpy that cannot be imported shadows
    Debian's here."""
    from activegrain import _env
    blocker = tmp_path / "blocker" / "numpy"
    blocker.mkdir(parents=True)
    (blocker / "__init__.py").write_text("raise ModuleNotFoundError(\"No module named 'numpy'\", name='numpy')\n")
    done = activegrain("phase", "run.dump", pythonpath=[tmp_path / "blocker"], cwd=tmp_path)
    assert done.returncode == 1 and done.stdout == ""
    line = one_line(done, "ERROR: activegrain needs numpy, which ")
    assert _env.DEBIAN_PYTHON in line and "python3-numpy" in line
    # imported from one's own script: the same words in the ImportError
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([str(tmp_path / "blocker"), str(PYTHON_DIR)]))
    imported = subprocess.run([sys.executable, "-c", "import activegrain"], capture_output=True, text=True,
                              env=env, timeout=60)
    assert imported.returncode == 1
    assert imported.stderr.splitlines()[-1].startswith("ModuleNotFoundError: ERROR: activegrain needs numpy")


def test_the_line_for_another_python_says_to_run_debians():
    from activegrain import _env
    if not os.path.exists(_env.DEBIAN_PYTHON):
        pytest.skip("no Debian python3 here")
    real = sys.executable
    try:
        sys.executable = "/opt/venv/bin/python3"
        line = _env.missing_module_line("scipy.ndimage")
    finally:
        sys.executable = real
    assert line == ("ERROR: activegrain needs scipy, which /opt/venv/bin/python3 lacks: run it with Debian's "
                    f"python3, {_env.DEBIAN_PYTHON} -m activegrain ... (it sees the python3-* packages of "
                    "tools/debian-packages; apt install python3-scipy if it lacks them too)")


def python_without_numpy():
    """A python3 on PATH other than this one that cannot import numpy (pyenv's, say), or None."""
    found = shutil.which("python3")
    if found is None or os.path.realpath(found) == os.path.realpath(sys.executable):
        return None
    probe = subprocess.run([found, "-c", "import numpy"], capture_output=True, timeout=60)
    return found if probe.returncode != 0 else None


@pytest.mark.skipif(python_without_numpy() is None, reason="no python3 without numpy on PATH")
def test_a_python3_on_path_without_numpy():
    done = activegrain("--help", python=python_without_numpy())
    assert done.returncode == 1
    line = one_line(done, "ERROR: activegrain needs numpy, which ")
    assert "/usr/bin/python3 -m activegrain" in line
