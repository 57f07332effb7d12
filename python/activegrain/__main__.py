import sys

from . import _env

try:
    from .cli import main
except ModuleNotFoundError as e:
    if not _env.is_third_party(e.name):
        raise
    sys.stderr.write(_env.missing_module_line(e.name) + "\n")
    sys.exit(1)

sys.exit(main())
