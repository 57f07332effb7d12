"""The build: the lmp wrapper loads the plugin, and bad LAMMPS set-ups fail early with one clear line."""
import ast
import os
import pathlib
import re
import shutil
import subprocess
import sys
import textwrap

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
LMP = os.environ.get("ACTIVEGRAIN_LMP", str(ROOT / "build" / "lmp"))
MPIRUN = os.environ.get("ACTIVEGRAIN_MPIRUN", "mpirun")


def run(cmd, **kw):
    return subprocess.run(cmd, capture_output=True, text=True, timeout=300, **kw)


def plugin_styles():
    """(style, name) pairs the plugin source registers."""
    styles = []
    for src in (ROOT / "src" / "USER-ACTIVEGRAIN").glob("*plugin.cpp"):
        style = None
        for line in src.read_text().splitlines():
            line = line.strip()
            if line.startswith("plugin.style ="):
                style = line.split('"')[1]
            elif line.startswith("plugin.name =") and style:
                styles.append((style, line.split('"')[1]))
    return styles


def test_help_lists_plugin_styles():
    out = run([LMP, "-h"])
    assert out.returncode == 0, out.stderr
    assert "Plugin styles" in out.stdout
    for style, name in plugin_styles():
        assert f"{style} style plugin {name}" in out.stdout


def test_plugin_autoloads_under_mpirun(tmp_path):
    deck = tmp_path / "in.list"
    deck.write_text("plugin list\n")
    out = run([MPIRUN, "-np", "2", LMP, "-in", str(deck), "-log", "none"], cwd=tmp_path)
    assert out.returncode == 0, out.stderr
    assert out.stdout.count("Loaded 1 plugins from") == 1   # rank 0 speaks for both


def test_plugin_load_command_works_without_autoload(tmp_path):
    plugin = os.environ["ACTIVEGRAIN_PLUGIN"]
    deck = tmp_path / "in.load"
    deck.write_text(f"plugin load {plugin}\nplugin list\n")
    env = dict(os.environ, LAMMPS_PLUGIN_PATH=str(tmp_path))   # nothing to auto-load there
    out = run([LMP, "-in", str(deck), "-log", "none"], cwd=tmp_path, env=env)
    assert out.returncode == 0, out.stderr
    for style, name in plugin_styles():
        assert f"{style} style plugin {name}" in out.stdout


# --- bad LAMMPS set-ups: one ERROR line, before any long build ------------------------------

def tools_error(tmp_path, **env):
    full = dict(os.environ, ACTIVEGRAIN_CACHE=str(tmp_path / "cache"),
                ACTIVEGRAIN_BUILD_DIR=str(tmp_path / "build"), **env)
    out = run(["bash", str(ROOT / "tools" / "run-tests")], env=full)
    assert out.returncode != 0
    errors = [l for l in out.stderr.splitlines() if "ERROR" in l]
    assert len(errors) == 1, out.stderr
    assert not (tmp_path / "build" / "CMakeCache.txt").exists()
    return errors[0]


def fake_lammps_tree(path, version):
    (path / "src").mkdir(parents=True)
    (path / "cmake").mkdir()
    (path / "cmake" / "CMakeLists.txt").write_text("# fake\n")
    (path / "src" / "version.h").write_text(f'#define LAMMPS_VERSION "{version}"\n')
    return path


def test_missing_source_dir(tmp_path):
    msg = tools_error(tmp_path, LAMMPS_SOURCE_DIR=str(tmp_path / "nowhere"))
    assert "LAMMPS_SOURCE_DIR" in msg and "does not exist" in msg


def test_not_a_lammps_tree(tmp_path):
    (tmp_path / "empty").mkdir()
    msg = tools_error(tmp_path, LAMMPS_SOURCE_DIR=str(tmp_path / "empty"))
    assert "is not a LAMMPS tree" in msg


def test_too_old_lammps(tmp_path):
    tree = fake_lammps_tree(tmp_path / "old", "29 Sep 2021")
    msg = tools_error(tmp_path, LAMMPS_SOURCE_DIR=str(tree))
    assert "too old" in msg and "2Aug2023" in msg


def test_unknown_release(tmp_path):
    msg = tools_error(tmp_path, ACTIVEGRAIN_LAMMPS="1Jan1999")
    assert "unknown ACTIVEGRAIN_LAMMPS" in msg


def test_no_way_to_fetch(tmp_path):
    msg = tools_error(tmp_path, ACTIVEGRAIN_APT_SOURCES=str(tmp_path / "no.sources"))
    assert "LAMMPS_SOURCE_DIR" in msg


@pytest.mark.parametrize("missing", ["PLUGIN", "RIGID"])
def test_host_lammps_without_required_package(tmp_path, missing):
    """CMake refuses a LAMMPS built without PLUGIN or RIGID, naming the package."""
    tree = fake_lammps_tree(tmp_path / "lammps", "4 Feb 2025")
    prefix = tmp_path / "prefix"
    (prefix / "bin").mkdir(parents=True)
    (prefix / "lib").mkdir()
    (prefix / "lib" / "liblammps.so").write_text("")
    packages = " ".join(p for p in ["EXTRA-FIX", "GRANULAR", "MOLECULE", "PLUGIN", "RIGID"] if p != missing)
    lmp = prefix / "bin" / "lmp"
    lmp.write_text(textwrap.dedent(f"""\
        #!/bin/sh
        echo "Large-scale Atomic/Molecular Massively Parallel Simulator - 4 Feb 2025"
        echo "Installed packages:"; echo; echo "{packages}"; echo
        """))
    lmp.chmod(0o755)
    out = run(["cmake", "-S", str(ROOT), "-B", str(tmp_path / "build"), f"-DLAMMPS_SOURCE_DIR={tree}",
               f"-DLAMMPS_INSTALL_DIR={prefix}"])
    assert out.returncode != 0
    assert f"built without the {missing} package" in out.stderr.replace("\n  ", " ")


# --- system packages: complete, and a missing one is named in one ERROR line ------------------

def package_table():
    """(package, probe kind, probe name, needed-by) rows of tools/debian-packages."""
    rows = []
    for line in (ROOT / "tools" / "debian-packages").read_text().splitlines():
        if line.strip() and not line.lstrip().startswith("#"):
            rows.append(tuple(line.split()))
    return rows


def test_every_find_package_has_a_debian_package():
    """Each find_package of our CMake files (and LAMMPS's FFTW3, which the build selects) is listed."""
    needed = {"FFTW3"}
    for f in [ROOT / "CMakeLists.txt", *ROOT.glob("cmake/*.cmake"), *ROOT.glob("tests/**/CMakeLists.txt")]:
        needed |= set(re.findall(r"find_package\(\s*(\w+)", f.read_text()))
    assert "-DFFT=FFTW3" in (ROOT / "tools" / "common.sh").read_text()
    listed = {row[3].split(":", 1)[1] for row in package_table() if row[3].startswith("cmake:")}
    assert needed <= listed, f"not in tools/debian-packages: {needed - listed}"


def third_party_imports():
    """Top-level modules imported by the repository's Python that are neither stdlib nor ours."""
    ours = {"activegrain"} | {p.stem for p in ROOT.rglob("*.py")}
    found = set()
    for f in ROOT.rglob("*.py"):
        if "build" in f.relative_to(ROOT).parts[0]:
            continue
        for node in ast.walk(ast.parse(f.read_text())):
            if isinstance(node, ast.Import):
                found |= {a.name.split(".")[0] for a in node.names}
            elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
                found.add(node.module.split(".")[0])
    return {m for m in found if m not in sys.stdlib_module_names and m not in ours}


def test_every_python_import_has_a_debian_package():
    listed = {row[2] for row in package_table() if row[1] == "python"}
    imports = third_party_imports()
    assert {"numpy", "MDAnalysis", "ase"} <= imports     # the scan sees what we know we use
    assert imports <= listed, f"not in tools/debian-packages: {imports - listed}"


def shim(tmp_path, **scripts):
    """A folder of stand-in commands, to put first on PATH."""
    bin_dir = tmp_path / "shim"
    bin_dir.mkdir(exist_ok=True)
    for name, body in scripts.items():
        (bin_dir / name).write_text("#!/bin/sh\n" + body + "\n")
        (bin_dir / name).chmod(0o755)
    return bin_dir


MISSING_SETS = {"test libraries": "libgtest-dev libgmock-dev", "MPI": "openmpi-bin libopenmpi-dev",
                "FFTW": "libfftw3-dev"}


@pytest.mark.parametrize("what", list(MISSING_SETS))
def test_missing_package_without_root(tmp_path, what):
    bin_dir = shim(tmp_path, id='[ "$1" = -u ] && echo 1000 || exec /usr/bin/id "$@"', sudo="exit 1",
                   **{"apt-get": "echo apt-get must not run >&2; exit 100"})
    msg = tools_error(tmp_path, ACTIVEGRAIN_ASSUME_MISSING=MISSING_SETS[what],
                      PATH=f"{bin_dir}:{os.environ['PATH']}")
    assert MISSING_SETS[what] in msg and "root" in msg


@pytest.mark.parametrize("what", list(MISSING_SETS))
def test_missing_package_not_in_apt(tmp_path, what):
    bin_dir = shim(tmp_path, id='[ "$1" = -u ] && echo 0 || exec /usr/bin/id "$@"',
                   **{"apt-get": '[ "$1" = update ] || [ "$2" = update ] || [ "$3" = update ] && exit 0; exit 100',
                      "apt-cache": 'echo "N: Unable to locate package $2" >&2'})
    msg = tools_error(tmp_path, ACTIVEGRAIN_ASSUME_MISSING=MISSING_SETS[what],
                      PATH=f"{bin_dir}:{os.environ['PATH']}")
    assert "not found by apt" in msg and MISSING_SETS[what] in msg


def test_missing_package_without_apt(tmp_path):
    """A machine without apt-get (not Debian): told what to install, nothing attempted."""
    tools = ["bash", "dirname", "nproc", "id", "cat", "c++", "cc1plus", "mpirun", "mpicxx", "cmake", "make",
             "ccache", "xz", "g++", "mkdir"]
    bin_dir = tmp_path / "bin"
    bin_dir.mkdir()
    for t in tools:
        if shutil.which(t):
            (bin_dir / t).symlink_to(shutil.which(t))
    msg = tools_error(tmp_path, ACTIVEGRAIN_ASSUME_MISSING="libfftw3-dev", PATH=str(bin_dir))
    assert "libfftw3-dev" in msg and "no apt-get" in msg
