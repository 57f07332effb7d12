"""ActiveGrain analysis: read LAMMPS dumps of vibrated rods and beads, measure area
fractions, polarization, phases and rod motility, plot them, and evaluate the paper's
coarse-grained theory (:mod:`activegrain.theory`)."""
import sys

from . import _env

try:
    from .geometry import Box, Channel, PeriodicBox, Rectangle, Annulus, geometry_from_box
    from .io import Dump, Frame, TruncatedDumpWarning, read_dump, read_frame, write_dump
except ModuleNotFoundError as e:
    if not _env.is_third_party(e.name):
        raise
    if sys.argv and sys.argv[0] == "-m":     # python3 -m activegrain: one line, no traceback
        sys.stderr.write(_env.missing_module_line(e.name) + "\n")
        sys.exit(1)
    raise ModuleNotFoundError(_env.missing_module_line(e.name), name=e.name) from None

__all__ = ["Box", "Channel", "PeriodicBox", "Rectangle", "Annulus", "geometry_from_box",
           "Dump", "Frame", "TruncatedDumpWarning", "read_dump", "read_frame", "write_dump"]
