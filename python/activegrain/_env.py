"""Which Python runs the package: one line for a Python that lacks a module it needs.

Imports nothing outside the standard library (it must work where numpy is missing)."""
import os
import sys

DEBIAN_PYTHON = "/usr/bin/python3"

# what the package imports that Python itself does not have, by top-level module
THIRD_PARTY = {"numpy", "scipy", "matplotlib", "PIL", "MDAnalysis", "ase"}


def is_third_party(module_name):
    return bool(module_name) and module_name.split(".")[0] in THIRD_PARTY


def missing_module_line(module_name):
    """``ERROR: ...`` (one line, no newline) for a Python that lacks ``module_name``: Debian's
    python3 sees the python3-* packages that tools/debian-packages lists; pyenv, conda or venv
    Pythons do not."""
    top = module_name.split(".")[0]
    package = f"python3-{top.lower()}"
    exe = sys.executable or "this python"
    try:
        debian = os.path.samefile(exe, DEBIAN_PYTHON)
    except OSError:
        debian = False
    if debian or not os.path.exists(DEBIAN_PYTHON):
        return (f"ERROR: activegrain needs {top}, which {exe} lacks: install Debian's {package} "
                f"(apt install {package}; tools/debian-packages lists all the package needs)")
    return (f"ERROR: activegrain needs {top}, which {exe} lacks: run it with Debian's python3, "
            f"{DEBIAN_PYTHON} -m activegrain ... (it sees the python3-* packages of tools/debian-packages; "
            f"apt install {package} if it lacks them too)")
