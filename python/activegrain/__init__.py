"""ActiveGrain analysis: read LAMMPS dumps of vibrated rods and beads, measure area
fractions, polarization, phases and rod motility, plot them, and evaluate the paper's
coarse-grained theory (:mod:`activegrain.theory`)."""
from .geometry import Box, Channel, PeriodicBox, Rectangle, Annulus, geometry_from_box
from .io import Frame, read_dump, read_frame, write_dump

__all__ = ["Box", "Channel", "PeriodicBox", "Rectangle", "Annulus", "geometry_from_box",
           "Frame", "read_dump", "read_frame", "write_dump"]
