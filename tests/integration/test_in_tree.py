"""tools/install-in-tree: ActiveGrain as the package ACTIVEGRAIN of a user's LAMMPS tree.

The script's edits (idempotent, undone by --uninstall, nothing else touched), LAMMPS's CMake
offering PKG_ACTIVEGRAIN with its dependencies, the legacy make targets, and an lmp built in-tree
by LAMMPS's own CMake (cached: build_in_tree.sh) that runs the single-rod example with no plugin,
as the plugin build runs it."""
import os
import pathlib
import re
import shutil
import subprocess

import pytest

from test_build import plugin_styles

ROOT = pathlib.Path(__file__).resolve().parents[2]
INSTALL = ROOT / "tools" / "install-in-tree"
LAMMPS_SOURCE = pathlib.Path(os.environ.get("ACTIVEGRAIN_LAMMPS_SOURCE", ""))
LMP = os.environ.get("ACTIVEGRAIN_LMP", str(ROOT / "build" / "lmp"))
# The one LAMMPS release the suite builds an in-tree lmp of (the others: configure checks only).
BUILT_RELEASE = "4 Feb 2025"
STYLE_MACRO = {"pair": "PairStyle", "fix": "FixStyle", "compute": "ComputeStyle", "command": "CommandStyle"}



def lammps_version():
    """The suite's LAMMPS (ctest passes its tree), or None."""
    header = LAMMPS_SOURCE / "src" / "version.h"
    if not header.is_file():
        return None
    return re.search(r'#define LAMMPS_VERSION "(.*)"', header.read_text()).group(1)


pytestmark = pytest.mark.skipif(lammps_version() is None,
                                reason="ACTIVEGRAIN_LAMMPS_SOURCE names no LAMMPS tree (run through ctest)")


def run(cmd, timeout=300, **kw):
    return subprocess.run(cmd, capture_output=True, text=True, timeout=timeout, **kw)


@pytest.fixture
def tree(tmp_path):
    """A copy of the suite's LAMMPS tree, the parts the install script and CMake use."""
    copy = tmp_path / "lammps"
    copy.mkdir()
    for part in ("cmake", "src"):
        shutil.copytree(LAMMPS_SOURCE / part, copy / part, symlinks=True)
    yield copy
    shutil.rmtree(copy)    # 50 MB each: pytest keeps its last three runs' folders


def snapshot(tree):
    """Size and modification time of every file of the tree: any write shows."""
    return {p.relative_to(tree): (p.stat().st_size, p.stat().st_mtime_ns) for p in tree.rglob("*") if p.is_file()}


def changed_since(tree, before):
    now = snapshot(tree)
    return {p for p in set(now) | set(before) if now.get(p) != before.get(p)}


def install(tree, *args):
    out = run([str(INSTALL), *args, str(tree)])
    assert out.returncode == 0, out.stdout + out.stderr
    return out.stdout


EDITED = {pathlib.Path("cmake/CMakeLists.txt"), pathlib.Path("src/Makefile")}


def test_install_changes_only_what_it_says_and_uninstall_restores(tree):
    before = snapshot(tree)
    said = install(tree)
    changed = changed_since(tree, before)
    assert {p for p in changed if p.parts[:2] != ("src", "ACTIVEGRAIN")} == EDITED
    for line in ("src/ACTIVEGRAIN: ", "cmake/CMakeLists.txt: ACTIVEGRAIN added to STANDARD_PACKAGES; "
                 "added pkg_depends(ACTIVEGRAIN RIGID) pkg_depends(ACTIVEGRAIN GRANULAR)",
                 "src/Makefile: activegrain added to the PACKAGE list"):
        assert line in said

    # The package folder: every source but the plugin entry point, and the legacy Install.sh.
    ours = {p.name for p in (ROOT / "src" / "USER-ACTIVEGRAIN").iterdir()} - {"activegrainplugin.cpp"}
    assert {p.name for p in (tree / "src" / "ACTIVEGRAIN").iterdir()} == ours
    # One line each, in the list and before LAMMPS's own dependency lines.
    cmake = (tree / "cmake" / "CMakeLists.txt").read_text()
    packages = re.search(r"^set\(STANDARD_PACKAGES\n(.*?)\)", cmake, re.S | re.M).group(1).split()
    assert packages.count("ACTIVEGRAIN") == 1
    assert re.search(r"pkg_depends\(ACTIVEGRAIN RIGID\)\npkg_depends\(ACTIVEGRAIN GRANULAR\)\npkg_depends\(", cmake)

    installed = snapshot(tree)
    assert "nothing changed" in install(tree)
    assert snapshot(tree) == installed

    # An update touches only the files that differ.
    (tree / "src" / "ACTIVEGRAIN" / "ag_math.h").write_text("// edited by hand\n")
    (tree / "src" / "ACTIVEGRAIN" / "gone.cpp").write_text("")
    edited = snapshot(tree)
    said = install(tree)
    assert "1 files updated: ag_math.h" in said and "removed (no longer part of ActiveGrain): gone.cpp" in said
    assert changed_since(tree, edited) == {pathlib.Path("src/ACTIVEGRAIN/ag_math.h"),
                                           pathlib.Path("src/ACTIVEGRAIN/gone.cpp")}

    said = install(tree, "--uninstall")
    assert "src/ACTIVEGRAIN: removed" in said
    assert changed_since(tree, before) == EDITED
    for path in EDITED:
        assert (tree / path).read_bytes() == (LAMMPS_SOURCE / path).read_bytes()
    assert "nothing changed" in install(tree, "--uninstall")


def test_refuses_what_is_not_a_lammps_tree(tmp_path):
    out = run([str(INSTALL), str(tmp_path)])
    assert out.returncode != 0 and "ERROR: " in out.stderr and "not a LAMMPS source tree" in out.stderr
    assert not any(tmp_path.iterdir())


def test_every_plugin_style_is_declared_for_lammps_build():
    """In-tree, LAMMPS finds styles by their macros in the headers, not by the plugin entry point:
    each style the plugin registers has its macro (in a header named as LAMMPS's scan expects)."""
    declared = set()
    for header in (ROOT / "src" / "USER-ACTIVEGRAIN").glob("*.h"):
        for macro, name in re.findall(r"^(\w+Style)\(([^,]+),\w+\);", header.read_text(), re.M):
            if macro != "CommandStyle":
                assert header.name.startswith(macro[:-len("Style")].lower() + "_"), header.name
            declared.add((macro, name))
    assert declared == {(STYLE_MACRO[style], name) for style, name in plugin_styles()}


def test_legacy_make_installs_with_its_dependencies(tree):
    """make yes-activegrain refuses without RIGID or GRANULAR, told as LAMMPS's own Install.sh
    tell it (a file of each in src/ marks it installed; LAMMPS's yes-rigid takes tens of seconds)."""
    install(tree)
    src = tree / "src"
    markers = {"RIGID": src / "fix_rigid_small.cpp", "GRANULAR": src / "fix_pour.cpp"}
    for missing in markers:
        for package, marker in markers.items():
            marker.unlink(missing_ok=True)
            if package != missing:
                shutil.copy(src / package / marker.name, marker)
        out = run(["make", "yes-activegrain"], cwd=src)
        assert f"Must install {missing} package with ACTIVEGRAIN" in out.stdout
        assert not (src / "pair_gran_impulse.cpp").exists()
    shutil.copy(src / "GRANULAR" / "fix_pour.cpp", markers["GRANULAR"])
    out = run(["make", "yes-activegrain"], cwd=src)
    assert out.returncode == 0, out.stdout + out.stderr
    assert (src / "pair_gran_impulse.cpp").exists() and (src / "ag_contact_solver.cpp").exists()
    assert not (src / "activegrainplugin.cpp").exists()
    # The install script leaves a tree installed this way alone.
    out = run([str(INSTALL), str(tree)])
    assert out.returncode != 0 and "make no-activegrain" in out.stderr
    run(["make", "no-activegrain"], cwd=src)
    assert not (src / "pair_gran_impulse.cpp").exists()


def test_cmake_offers_the_package_and_enables_what_it_needs(tree):
    """Configure only (seconds), for the suite's LAMMPS: -D PKG_ACTIVEGRAIN=on alone enables RIGID
    and GRANULAR as pkg_depends does for LAMMPS's own packages, and our styles are registered."""
    install(tree)
    out = run(["cmake", "-S", str(tree / "cmake"), "-B", str(tree / "build"), "-DPKG_ACTIVEGRAIN=on",
               "-DBUILD_MPI=yes", "-DBUILD_OMP=no"])
    assert out.returncode == 0, out.stdout[-3000:] + out.stderr[-3000:]
    log = out.stderr.replace("\n  ", " ")
    for needed in ("RIGID", "GRANULAR"):
        assert f"The ACTIVEGRAIN package depends on the {needed} package" in log
    assert re.search(r"Enabled packages: ACTIVEGRAIN;GRANULAR;RIGID\n", out.stdout)
    styles = tree / "build" / "styles"
    for style, header in (("pair", "pair_gran_impulse.h"), ("fix", "fix_rigid_rod.h"),
                          ("fix", "fix_wall_impulse_region.h"), ("compute", "compute_polar_rod.h"),
                          ("command", "rod_template.h")):
        assert f'#include "{header}"' in (styles / f"style_{style}.h").read_text()


def run_single_rod(lmp, cwd):
    deck = ROOT / "examples" / "single-rod" / "in.single-rod"
    out = run([lmp, "-in", str(deck), "-var", "nside", "1", "-var", "time", "0.1", "-log", "log.lammps"],
              cwd=cwd, env=dict(os.environ, LAMMPS_PLUGIN_PATH=""))
    assert out.returncode == 0, out.stdout[-3000:] + out.stderr[-3000:]
    assert "ERROR" not in out.stdout
    return out.stdout


def last_thermo(stdout):
    rows = re.findall(r"^\s*(\d+(?:\s+\S+){5})\s*$", stdout.split("Step")[-1], re.M)
    return [float(x) for x in rows[-1].split()]


@pytest.mark.skipif(lammps_version() != BUILT_RELEASE, reason=f"an in-tree lmp is built of LAMMPS {BUILT_RELEASE} only")
def test_in_tree_lmp_runs_the_single_rod_example_without_plugin(tmp_path):
    built = run(["bash", str(ROOT / "tests" / "integration" / "build_in_tree.sh"), str(LAMMPS_SOURCE)],
                timeout=3600)
    assert built.returncode == 0, built.stderr[-3000:]
    lmp = built.stdout.strip().splitlines()[-1]

    help_text = run([lmp, "-h"], env=dict(os.environ, LAMMPS_PLUGIN_PATH="")).stdout
    packages = re.search(r"Installed packages:\s*\n\n(.*)\n", help_text).group(1).split()
    assert {"ACTIVEGRAIN", "RIGID", "GRANULAR"} <= set(packages) and "PLUGIN" not in packages
    for _, name in plugin_styles():
        if name[0].isupper():    # LAMMPS's help lists no internal style (upper-case name)
            continue
        assert re.search(rf"(^|\s){re.escape(name)}(\s|$)", help_text), name

    (tmp_path / "in-tree").mkdir()
    (tmp_path / "plugin").mkdir()
    in_tree = run_single_rod(lmp, tmp_path / "in-tree")
    assert "Loaded" not in in_tree and "plugin" not in in_tree
    plugin = run_single_rod(LMP, tmp_path / "plugin")
    # The same styles, the same run: the rod's energies after 0.1 s (20 vibration periods) agree.
    assert last_thermo(in_tree)[0] == last_thermo(plugin)[0] == 10000
    assert last_thermo(in_tree) == pytest.approx(last_thermo(plugin), rel=1e-6)
