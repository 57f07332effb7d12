"""Reading and writing LAMMPS text dumps of rods and beads.

Dump convention of the package (``dump ID all custom N file id mol type radius x y z
vx vy vz``, optionally ``ix iy iz``): beads have ``mol`` = 0, the atoms of a rod share
``mol`` = the rod's ID (> 0).

Frames are read through MDAnalysis (positions, velocities, box lengths, time step).
MDAnalysis drops the columns it has no use for and the boundary flags, so the static
per-atom columns (``mol``, ``type``, ``radius``) and the box bounds with their
``pp``/``ff`` flags are read from the first frame's header here. They do not change in
the simulations this package makes (no atoms are created or deleted, walls are fixed).
"""
import warnings
from dataclasses import dataclass, replace

import numpy as np

from .geometry import Box


@dataclass
class Frame:
    """One snapshot. Arrays are sorted by atom id; lengths in the dump's units
    divided by ``length_unit`` (see :func:`read_dump`)."""
    step: int
    time: float
    box: Box
    ids: np.ndarray
    mol: np.ndarray
    types: np.ndarray
    radius: np.ndarray
    pos: np.ndarray          # (N, 3)
    vel: np.ndarray = None   # (N, 3) or None

    @property
    def is_bead(self):
        return self.mol == 0

    def beads(self):
        """(positions (Nb, 2), radii (Nb,), velocities (Nb, 2) or None) of the beads."""
        m = self.is_bead
        v = None if self.vel is None else self.vel[m, :2]
        return self.pos[m, :2], self.radius[m], v

    def rods(self):
        """The rods of this frame as a :class:`activegrain.rods.RodSet`."""
        from .rods import RodSet
        return RodSet.from_frame(self)

    def scaled(self, factor):
        """A copy with every length (and velocity) multiplied by ``factor``."""
        return replace(self, box=self.box.scaled(factor), radius=self.radius * factor,
                       pos=self.pos * factor, vel=None if self.vel is None else self.vel * factor)

    def to_ase(self):
        """The frame as an :class:`ase.Atoms` (cell, pbc, ``mol`` and ``radius`` arrays)."""
        import ase
        atoms = ase.Atoms(numbers=np.ones(len(self.ids), int), positions=self.pos - self.box.lo,
                          cell=np.diag(self.box.lengths), pbc=self.box.periodic)
        atoms.set_array("mol", self.mol.copy())
        atoms.set_array("radius", self.radius.copy())
        atoms.set_array("id", self.ids.copy())
        if self.vel is not None:
            atoms.set_velocities(self.vel)
        return atoms


def _read_header(path):
    """Box bounds with boundary flags and the per-atom columns of the first frame."""
    with open(path) as f:
        lines = [f.readline() for _ in range(9)]
        if any(l.startswith(("ITEM: UNITS", "ITEM: TIME\n")) for l in lines):
            raise ValueError(f"{path}: dumps written with 'dump_modify units yes' or 'time yes' "
                             "are not supported (MDAnalysis expects the plain header)")
        if not lines[0].startswith("ITEM: TIMESTEP") or not lines[8].startswith("ITEM: ATOMS"):
            raise ValueError(f"{path}: not a LAMMPS text dump (ITEM: TIMESTEP / ITEM: ATOMS expected)")
        n = int(lines[3])
        flags = lines[4].split()[3:]
        if len(flags) < 3 or any(x in ("xy", "xz", "yz") for x in flags):
            if any(x in ("xy", "xz", "yz") for x in flags):
                raise ValueError(f"{path}: triclinic boxes are not supported")
            flags = ["pp", "pp", "pp"]
        bounds = np.array([[float(v) for v in lines[5 + k].split()[:2]] for k in range(3)])
        columns = lines[8].split()[2:]
        table = np.loadtxt(f, max_rows=n, ndmin=2)
    missing = [c for c in ("id", "mol", "radius") if c not in columns]
    if missing:
        raise ValueError(f"{path}: dump lacks column(s) {', '.join(missing)} "
                         "(need: id mol type radius x y z ...)")
    col = {c: table[:, i] for i, c in enumerate(columns)}
    order = np.argsort(col["id"])
    static = {c: col[c][order] for c in ("id", "mol", "radius")}
    static["type"] = col["type"][order] if "type" in col else np.ones(n)
    box = Box(tuple(bounds[:, 0]), tuple(bounds[:, 1]), tuple(f[0] == "p" for f in flags))
    return box, static, columns


def _universe(path, unwrap):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # MDAnalysis warns about its imports and guessed masses
        # MDAnalysis 2.4 imports the deprecated xdrlib after installing its own warning filters,
        # which override ours: import it first, here, so that the warning is not printed.
        try:
            import xdrlib  # noqa: F401
        except ImportError:
            pass
        import MDAnalysis as mda
        return mda.Universe(path, topology_format="LAMMPSDUMP", format="LAMMPSDUMP",
                            unwrap_images=unwrap)


def read_dump(path, length_unit=1.0, timestep=1.0, start=None, stop=None, every=None):
    """Yield the :class:`Frame` objects of a LAMMPS text dump.

    ``length_unit``: lengths (and velocities) are divided by it, e.g. ``1e-3`` to work
    in bead diameters when the dump is in metres. ``timestep``: time per MD step, so that
    ``frame.time = step * timestep``. ``start``, ``stop``, ``every`` slice the frames.
    """
    box, static, columns = _read_header(path)
    unwrap = all(c in columns for c in ("ix", "iy", "iz"))
    u = _universe(path, unwrap)
    lo = np.asarray(box.lo, float)
    ids = static["id"].astype(np.int64)
    mol = static["mol"].astype(np.int64)
    types = static["type"].astype(np.int64)
    for ts in u.trajectory[slice(start, stop, every)]:
        if not np.allclose(ts.dimensions[:3], box.lengths, rtol=1e-6):
            raise ValueError(f"{path}: the box changes at step {ts.data['step']}; "
                             "only fixed boxes are supported")
        pos = ts.positions.astype(np.float64) + lo  # MDAnalysis moves the box to the origin
        vel = ts.velocities.astype(np.float64) if ts.has_velocities else None
        step = int(ts.data["step"])
        # positions are kept wrapped (dumps may carry xu/yu/zu or image flags); rods and
        # trajectories are unwrapped by the minimum image where needed
        frame = Frame(step, step * timestep, box, ids, mol, types, static["radius"].copy(),
                      box.wrap(pos), vel)
        yield frame.scaled(1.0 / length_unit) if length_unit != 1.0 else frame


def count_frames(path):
    """Number of frames in a dump."""
    _read_header(path)
    return len(_universe(path, False).trajectory)


def read_frame(path, index=-1, **kw):
    """One frame of a dump (``index`` as in a Python list; -1 is the last)."""
    n = count_frames(path)
    if not -n <= index < n:
        raise ValueError(f"{path}: no frame {index} (the dump has {n})")
    index %= n
    return next(read_dump(path, start=index, stop=index + 1, **kw))


def write_dump(path, frames, append=False):
    """Write frames as a LAMMPS text dump in the package's convention.

    ``frames``: iterable of :class:`Frame`. Columns: ``id mol type radius x y z`` and
    ``vx vy vz`` when the frame has velocities. Used to make synthetic test data.
    """
    with open(path, "a" if append else "w") as f:
        for fr in frames:
            n = len(fr.ids)
            flags = " ".join("pp" if p else "ff" for p in fr.box.periodic)
            f.write(f"ITEM: TIMESTEP\n{fr.step}\nITEM: NUMBER OF ATOMS\n{n}\n"
                    f"ITEM: BOX BOUNDS {flags}\n")
            for k in range(3):
                f.write(f"{fr.box.lo[k]:.10g} {fr.box.hi[k]:.10g}\n")
            cols = ["id", "mol", "type", "radius", "x", "y", "z"]
            data = [fr.ids, fr.mol, fr.types, fr.radius, fr.pos[:, 0], fr.pos[:, 1], fr.pos[:, 2]]
            if fr.vel is not None:
                cols += ["vx", "vy", "vz"]
                data += [fr.vel[:, 0], fr.vel[:, 1], fr.vel[:, 2]]
            f.write("ITEM: ATOMS " + " ".join(cols) + "\n")
            table = np.column_stack(data)
            fmt = ["%d", "%d", "%d"] + ["%.10g"] * (len(cols) - 3)
            np.savetxt(f, table, fmt=fmt)


def write_extxyz(path, frames):
    """Write frames as extended XYZ through ase (cell, pbc, ``mol``, ``radius`` and
    velocities per atom), a format OVITO and VMD open directly."""
    import ase.io
    ase.io.write(path, [fr.to_ase() for fr in frames], format="extxyz")
