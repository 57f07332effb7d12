"""The build: the lmp wrapper loads the plugin, and bad LAMMPS set-ups fail early with one clear line."""
import os
import pathlib
import subprocess
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
