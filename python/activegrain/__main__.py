"""``python3 -m activegrain``, and the command ``activegrain`` (the build's bin/activegrain and
pyproject.toml's console script both call :func:`main`)."""
import sys


def main(argv=None):
    """Run the command line and return its exit status; a Python that lacks a package the command
    needs gets one ERROR line and status 1."""
    from . import _env
    try:
        from .cli import main as cli_main
    except ModuleNotFoundError as e:
        if not _env.is_third_party(e.name):
            raise
        sys.stderr.write(_env.missing_module_line(e.name) + "\n")
        return 1
    return cli_main(argv)


if __name__ == "__main__":
    sys.exit(main())
