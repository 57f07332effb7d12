"""The build: the lmp wrapper loads the plugin, and bad LAMMPS set-ups fail early with one clear line."""
import ast
import os
import pathlib
import re
import shutil
import subprocess
import sys
import textwrap
import zipfile

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


# --- the environment file and the activegrain command -----------------------------------------

BUILD = pathlib.Path(LMP).resolve().parent            # lmp, activegrain-env.sh and bin/ of the build in use
ENV_SCRIPT = BUILD / "activegrain-env.sh"


def sourced(tmp_path, commands, **env):
    """bash with the build's environment file sourced (twice, as a user's shell may), running
    commands; with a python3 first on PATH that is not Debian's (it only exits 1) and none of the
    test's PYTHONPATH, LAMMPS_PLUGIN_PATH or continuum library."""
    bin_dir = shim(tmp_path, python3="echo 'not the python3 of Debian' >&2; exit 1")
    full = {k: v for k, v in os.environ.items()
            if k not in ("PYTHONPATH", "LAMMPS_PLUGIN_PATH", "ACTIVEGRAIN_CONTINUUM_LIB")}
    full.update(PATH=f"{bin_dir}:{os.environ['PATH']}", MPLBACKEND="Agg", **env)
    script = f"set -e\nsource '{ENV_SCRIPT}'\nsource '{ENV_SCRIPT}'\n{commands}\n"
    return run(["bash", "-c", script], cwd=tmp_path, env=full)


def test_activegrain_command_runs_with_another_python3_first_on_path(tmp_path):
    out = sourced(tmp_path, "! python3 -c pass 2>/dev/null\n"        # the fake one answers python3
                            "command -v activegrain\nactivegrain --help\nactivegrain theory growth --help")
    assert out.returncode == 0, out.stdout[-2000:] + out.stderr[-2000:]
    assert out.stdout.splitlines()[0] == str(BUILD / "bin" / "activegrain")
    assert "snapshot" in out.stdout and "sweep" in out.stdout and "--D_rho" in out.stdout
    assert out.stderr == ""


def test_activegrain_command_needs_no_environment_file(tmp_path):
    """bin/activegrain alone: its shebang is Debian's python3 (where there is one), it puts this
    source tree's python/ on the path and names the build's continuum solver."""
    wrapper = BUILD / "bin" / "activegrain"
    text = wrapper.read_text()
    if os.path.exists("/usr/bin/python3"):
        assert text.splitlines()[0] == "#!/usr/bin/python3"
    assert f'sys.path.insert(0, "{ROOT / "python"}")' in text
    if (BUILD / "lib" / "libactivegrain_continuum.so").exists():
        assert f'"ACTIVEGRAIN_CONTINUUM_LIB", "{BUILD / "lib" / "libactivegrain_continuum.so"}"' in text
    bin_dir = shim(tmp_path, python3="exit 1")
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    out = run([str(wrapper), "polar", "--help"], cwd=tmp_path, env=dict(env, PATH=f"{bin_dir}:{env['PATH']}"))
    assert out.returncode == 0 and "--length-unit" in out.stdout, out.stderr


def test_lmp_after_the_environment_file_loads_the_plugin_once(tmp_path):
    """The environment file and the lmp wrapper both name the plugin folder; LAMMPS loads it once."""
    (tmp_path / "in.list").write_text("plugin list\n")
    out = sourced(tmp_path, 'echo "$LAMMPS_PLUGIN_PATH"\nlmp -in in.list -log none\n'
                            f"{MPIRUN} -np 2 lmp -in in.list -log none")
    assert out.returncode == 0, out.stdout[-2000:] + out.stderr[-2000:]
    assert out.stdout.splitlines()[0] == str(BUILD / "plugins")          # listed once, sourced twice
    assert out.stdout.count("Loaded 1 plugins from") == 2, out.stdout     # once per run
    for style, name in plugin_styles():
        assert len(re.findall(rf"^ *\d+: {style} style plugin {re.escape(name)}$", out.stdout, re.M)) == 2


def test_pyproject_declares_the_package_and_the_command(tmp_path):
    """python/pyproject.toml builds offline with setuptools into a wheel of the whole package whose
    console script activegrain calls activegrain.__main__:main, the function bin/activegrain calls."""
    src = tmp_path / "src"
    shutil.copytree(ROOT / "python", src, ignore=shutil.ignore_patterns("__pycache__", "build", "*.egg-info"))
    out = run(["/usr/bin/python3" if os.path.exists("/usr/bin/python3") else sys.executable, "-c",
               "import sys; from setuptools import build_meta; print(build_meta.build_wheel(sys.argv[1]))",
               str(tmp_path / "dist")], cwd=src)
    assert out.returncode == 0, out.stderr[-3000:]
    with zipfile.ZipFile(tmp_path / "dist" / out.stdout.splitlines()[-1]) as wheel:
        names = set(wheel.namelist())
        info = next(n.split("/")[0] for n in names if n.endswith(".dist-info/METADATA"))
        scripts = wheel.read(f"{info}/entry_points.txt").decode()
    package = {str(p.relative_to(ROOT / "python")) for p in (ROOT / "python" / "activegrain").rglob("*.py")}
    assert package <= names, package - names
    assert re.search(r"^\[console_scripts\]\nactivegrain = activegrain\.__main__:main$", scripts, re.M), scripts
    assert "from activegrain.__main__ import main" in (BUILD / "bin" / "activegrain").read_text()
