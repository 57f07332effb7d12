"""Reading and writing LAMMPS text dumps of rods and beads.

Dump convention of the package (what the example decks write)::

    dump ID all custom N file id mol type radius x y z vx vy vz f_rodsfix[4]
    dump_modify ID colname f_rodsfix[4] body

``body`` is fix rigid/rod's per-atom body ID: the ID of the atom's rod, 0 for a bead. Rods
are told apart by ``body`` where the dump has it, else by ``mol`` (beads 0, the atoms of a rod
share the rod's ID); either way every rod is checked to be one chain of overlapping spheres
(:meth:`activegrain.rods.RodSet.from_frame`). ``ix iy iz`` are optional; ``xu yu zu`` or
``xs ys zs`` may replace ``x y z``; ``type`` is optional.

Frames are parsed here, in double precision (a dump written with ``dump_modify format float
%.12g`` keeps 12 digits; MDAnalysis's reader would hold positions as float32, 1e-7 of the
box). The box must not change during a run and the header must be the plain one.
"""
import collections
import itertools
import warnings
from dataclasses import dataclass, replace

import numpy as np

from .geometry import Box


@dataclass
class Frame:
    """One snapshot. Arrays are sorted by atom id; lengths in the dump's units
    divided by ``length_unit`` (see :func:`read_dump`). ``body``: the atoms' rod IDs
    (fix rigid/rod's body ID, 0 for beads) when the dump has them, else None.
    ``length_unit``: the frame's unit of length in the dump's units, which for the decks' SI
    dumps are metres (1e-3 for a frame read with ``length_unit=1e-3``), kept for conversions
    (:func:`to_universe`)."""
    step: int
    time: float
    box: Box
    ids: np.ndarray
    mol: np.ndarray
    types: np.ndarray
    radius: np.ndarray
    pos: np.ndarray          # (N, 3)
    vel: np.ndarray = None   # (N, 3) or None
    body: np.ndarray = None  # (N,) or None
    length_unit: float = 1.0

    @property
    def rod_of_atom(self):
        """Per atom, the ID of its rod (0 for a bead): ``body`` if the dump has it, else ``mol``."""
        return self.mol if self.body is None else self.body

    @property
    def is_bead(self):
        return self.rod_of_atom == 0

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
                       pos=self.pos * factor, vel=None if self.vel is None else self.vel * factor,
                       length_unit=self.length_unit / factor)

    def to_ase(self):
        """The frame as an :class:`ase.Atoms` (cell, pbc, ``mol``, ``radius`` and, when
        known, ``body`` arrays)."""
        import ase
        atoms = ase.Atoms(numbers=np.ones(len(self.ids), int), positions=self.pos - self.box.lo,
                          cell=np.diag(self.box.lengths), pbc=self.box.periodic)
        atoms.set_array("mol", self.mol.copy())
        atoms.set_array("radius", self.radius.copy())
        atoms.set_array("id", self.ids.copy())
        if self.body is not None:
            atoms.set_array("body", self.body.copy())
        if self.vel is not None:
            atoms.set_velocities(self.vel)
        return atoms


_POSITION_COLUMNS = (("x", "y", "z"), ("xu", "yu", "zu"), ("xs", "ys", "zs"))


class TruncatedDumpWarning(UserWarning):
    """A dump ends within a frame (its run was killed while writing it, or is still writing):
    its whole frames are read, the partial one is left out."""


def _partial(line):
    """True for a line cut short by the end of the file."""
    return not line.endswith("\n")


def _frames_in(f, path, wanted=()):
    """Yield ``(index, step, box, columns, rows)`` for the whole frames of open dump ``f``,
    ``rows`` (the atom lines) only for an index in ``wanted``, else None. A frame cut short by
    the end of the file ends the iteration with ``(index, step, None, None, None)`` (``step``
    None when the cut is before it)."""
    index = 0
    for line in f:
        if _partial(line) and index and "ITEM: TIMESTEP\n".startswith(line):
            yield index, None, None, None, None        # cut within the next frame's first line
            return
        if not line.strip():
            continue
        if line.startswith(("ITEM: UNITS", "ITEM: TIME\n")):
            raise ValueError(f"{path}: dumps written with 'dump_modify units yes' or 'time yes' "
                             "are not supported (plain header expected)")
        if not line.startswith("ITEM: TIMESTEP"):
            raise ValueError(f"{path}: not a LAMMPS text dump (ITEM: TIMESTEP / ITEM: ATOMS expected)")
        head = [line] + [f.readline() for _ in range(8)]
        cut = next((k for k, h in enumerate(head) if _partial(h)), None)
        try:
            step = int(head[1]) if cut is None or cut > 1 else None
        except ValueError:
            raise ValueError(f"{path}: not a LAMMPS text dump (a step number after ITEM: TIMESTEP expected)") from None
        if cut is not None:
            yield index, step, None, None, None
            return
        if not head[8].startswith("ITEM: ATOMS"):
            raise ValueError(f"{path}: not a LAMMPS text dump (ITEM: TIMESTEP / ITEM: ATOMS expected)")
        flags = head[4].split()[3:]
        if any(x in ("xy", "xz", "yz") for x in flags):
            raise ValueError(f"{path}: triclinic boxes are not supported")
        if len(flags) < 3:
            flags = ["pp", "pp", "pp"]
        try:
            bounds = np.array([[float(v) for v in head[5 + k].split()[:2]] for k in range(3)])
            n = int(head[3])
        except ValueError:
            raise ValueError(f"{path}: frame at step {step}: not a LAMMPS text dump header "
                             "(atom count, box bounds)") from None
        box = Box(tuple(bounds[:, 0]), tuple(bounds[:, 1]), tuple(fl[0] == "p" for fl in flags))
        columns = head[8].split()[2:]
        if index in wanted:
            rows = list(itertools.islice(f, n))
            whole = len(rows) == n and not (n and _partial(rows[-1]))
        else:
            rows = None
            collections.deque(itertools.islice(f, max(n - 1, 0)), maxlen=0)   # skipped, fast
            last = f.readline() if n else "\n"
            whole = not _partial(last)
        if not whole:
            yield index, step, None, None, None
            return
        yield index, step, box, columns, rows
        index += 1


def _count(path):
    """(number of whole frames, cut, step of the last whole frame): ``cut`` is None for a dump
    that ends at the end of a frame, else the step of the frame the file ends within (-1 when
    the file ends before that frame's step)."""
    n, cut, last = 0, None, None
    with open(path) as f:
        for index, step, box, _, _ in _frames_in(f, path):
            if box is None:
                cut = step if step is not None else -1
                break
            n, last = index + 1, step
    return n, cut, last


def _frame(step, timestep, box, columns, rows, path):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DeprecationWarning)   # numpy: "could not be read to its end"
        table = np.fromstring(" ".join(rows), sep=" ") if rows else np.zeros(0)
    if table.size != len(rows) * len(columns):
        raise ValueError(f"{path}: frame at step {step}: its {len(rows)} atom rows are not "
                         f"{len(columns)} numbers each ({' '.join(columns)})")
    table = table.reshape(len(rows), len(columns))
    col = {c: table[:, i] for i, c in enumerate(columns)}
    missing = [c for c in ("id", "mol", "radius") if c not in col]
    xyz = next((names for names in _POSITION_COLUMNS if all(c in col for c in names)), None)
    if missing or xyz is None:
        raise ValueError(f"{path}: dump lacks column(s) {', '.join(missing) or 'x y z'} "
                         "(need: id mol type radius x y z ..., see activegrain.io)")
    order = np.argsort(col["id"], kind="stable")
    pos = np.column_stack([col[c][order] for c in xyz])
    if xyz[0] == "xs":
        pos = np.asarray(box.lo) + pos * box.lengths
    vel = np.column_stack([col[c][order] for c in ("vx", "vy", "vz")]) if "vx" in col else None
    as_int = lambda c: col[c][order].astype(np.int64)
    return Frame(step, step * timestep, box, as_int("id"), as_int("mol"),
                 as_int("type") if "type" in col else np.ones(len(order), np.int64),
                 col["radius"][order].copy(), box.wrap(pos), vel,
                 as_int("body") if "body" in col else None)


class Dump:
    """A LAMMPS text dump read frame by frame, as MDAnalysis's readers read a trajectory: its
    whole frames are counted once, on opening (``len(dump)``; a :class:`TruncatedDumpWarning` if
    it ends within a frame, ValueError if it holds none), and each frame is parsed when it is
    reached, the lines of the frames left out skipped unparsed, so that memory holds one frame
    whatever the length of the dump. ``length_unit`` and ``timestep`` as for :func:`read_dump`."""

    def __init__(self, path, length_unit=1.0, timestep=1.0):
        self.path, self.length_unit, self.timestep = path, length_unit, timestep
        self.n_frames = count_frames(path)

    def __len__(self):
        return self.n_frames

    def frames(self, start=None, stop=None, every=None):
        """Yield the frames that the slice ``start:stop:every`` selects, one at a time; reading
        stops after the last of them."""
        wanted = range(self.n_frames)[slice(start, stop, every)]
        if not wanted:
            return
        chosen, last = set(wanted), max(wanted)
        first_box = None
        with open(self.path) as f:
            for index, step, box, columns, rows in _frames_in(f, self.path, chosen):
                if index > last or box is None:      # past the selection, or a frame cut short
                    break
                first_box = first_box or box
                if not np.allclose(box.lengths, first_box.lengths, rtol=1e-6):
                    raise ValueError(f"{self.path}: the box changes at step {step}; only fixed boxes are supported")
                if index in chosen:
                    frame = _frame(step, self.timestep, box, columns, rows, self.path)
                    yield frame.scaled(1.0 / self.length_unit) if self.length_unit != 1.0 else frame

    def frame(self, index=-1):
        """One frame (``index`` as in a Python list; -1 is the last whole frame)."""
        if not -self.n_frames <= index < self.n_frames:
            raise ValueError(f"{self.path}: no frame {index} (the dump has {self.n_frames})")
        index %= self.n_frames
        return next(self.frames(index, index + 1))


def read_dump(path, length_unit=1.0, timestep=1.0, start=None, stop=None, every=None):
    """Yield the :class:`Frame` objects of a LAMMPS text dump, one at a time (:class:`Dump`).

    ``length_unit``: lengths (and velocities) are divided by it, e.g. ``1e-3`` to work
    in bead diameters when the dump is in metres. ``timestep``: time per MD step, so that
    ``frame.time = step * timestep``. ``start``, ``stop``, ``every`` slice the frames.
    Positions are wrapped into the box along periodic axes (rods are regrouped by the
    minimum image).

    A dump that ends within a frame (a run killed while writing it) is read up to its last
    whole frame, with a :class:`TruncatedDumpWarning` naming the file and the frames read.
    """
    yield from Dump(path, length_unit, timestep).frames(start, stop, every)


def count_frames(path):
    """Number of whole frames in a dump (a :class:`TruncatedDumpWarning` if it ends within a
    frame; ValueError if it holds no whole frame)."""
    n, cut, last = _count(path)
    if n == 0:
        if cut is not None:
            raise ValueError(f"{path}: no whole frame (the file ends within its first frame)")
        raise ValueError(f"{path}: no frames")
    if cut is not None:
        warnings.warn(f"{path}: ends within a frame (a run killed while writing it?): read its {n} "
                      f"whole frame(s), to step {last}, without the partial frame after it",
                      TruncatedDumpWarning, stacklevel=3)
    return n


def read_frame(path, index=-1, **kw):
    """One frame of a dump (``index`` as in a Python list; -1 is the last whole frame)."""
    return Dump(path, **kw).frame(index)


def write_dump(path, frames, append=False):
    """Write frames as a LAMMPS text dump in the package's convention.

    ``frames``: iterable of :class:`Frame`. Columns: ``id mol type radius x y z``,
    ``vx vy vz`` when the frame has velocities and ``body`` when it has rod IDs. Used to
    make synthetic test data.
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
            if fr.body is not None:
                cols.append("body")
                data.append(fr.body)
            f.write("ITEM: ATOMS " + " ".join(cols) + "\n")
            table = np.column_stack(data)
            fmt = ["%d", "%d", "%d"] + ["%.12g"] * (len(cols) - 3 - (fr.body is not None)) \
                + ["%d"] * (fr.body is not None)
            np.savetxt(f, table, fmt=fmt)


# The decks' densities (kg/m^3) by atom type: rods are types 1 (tail), 2 (body) and 3 (nose) of
# brass, beads type 4 of aluminium (examples/rods-and-beads/in.create, examples/minimal/in.minimal).
DECK_DENSITIES = {1: 8500.0, 2: 8500.0, 3: 8500.0, 4: 2700.0}

_AMU = 1.66053906660e-27        # kg
_ANGSTROM = 1e-10               # m
_PS = 1e-12                     # s


def atom_masses(frame, densities=None):
    """Per atom of an SI frame (any ``length_unit``), its mass in kg, as the decks give it.

    A bead's mass is its density times its sphere's volume (``set ... density``). A rod's atoms
    carry rod_template's point masses: the slabs of the solid tapered rod (a frustum) nearest to
    each sphere, tilted so that they sum to the solid's mass and centre on its centre of mass
    (:func:`activegrain.rods.frustum_point_masses`, rebuilt from the dumped radii and positions;
    the same as LAMMPS's per-atom masses to the dump's precision). ``densities``: {atom type:
    density in kg/m^3}, default :data:`DECK_DENSITIES` (rod types 1-3 brass 8500, bead type 4
    aluminium 2700); a rod's atoms must share one density.
    """
    from .rods import frustum_point_masses
    densities = DECK_DENSITIES if densities is None else densities
    missing = sorted(set(np.unique(frame.types).tolist()) - set(densities))
    if missing:
        raise ValueError(f"no density for atom type(s) {', '.join(map(str, missing))} "
                         f"(densities given for types {', '.join(map(str, sorted(densities)))})")
    unit = frame.length_unit                      # metres per frame length
    rho = np.array([densities[int(t)] for t in frame.types], float)
    radius = frame.radius * unit
    mass = rho * 4.0 / 3.0 * np.pi * radius ** 3
    rod = frame.rod_of_atom
    for rid in np.unique(rod[rod > 0]):
        atoms = np.flatnonzero(rod == rid)
        if np.ptp(rho[atoms]) > 0:
            raise ValueError(f"rod {rid}: its atoms' types {sorted(set(frame.types[atoms].tolist()))} "
                             "have different densities")
        x = frame.pos[atoms[0]] + frame.box.minimum_image(frame.pos[atoms] - frame.pos[atoms[0]])
        d = x - x.mean(axis=0)
        axis = np.linalg.svd(d, full_matrices=False)[2][0]
        mass[atoms] = frustum_point_masses(d @ axis * unit, radius[atoms], rho[atoms[0]])
    return mass


def to_universe(frames, dt=None, densities=None, shift_to_origin=False):
    """The frames of an SI dump (metres, seconds, kg; any ``length_unit``) as an in-memory
    :class:`MDAnalysis.Universe`, in MDAnalysis's units: positions, radii and box in Angstrom,
    velocities in Angstrom/ps, masses in amu, time in ps.

    * Topology: one residue per rod (resname ``ROD``, resid its rod ID, the ``body`` or ``mol``
      of its atoms) and one per bead (``BEAD``, resid 0); atom ``ids``, ``types``, ``radii`` and
      ``masses`` (``u.select_atoms("resname ROD")``, ``u.residues``, ``center_of_mass()``).
    * Masses (the dumps have no mass column) from the first frame's radii and ``densities``,
      {atom type: kg/m^3}, default the decks' (types 1-3 brass rods 8500, type 4 aluminium
      beads 2700): beads are solid spheres, rod atoms get rod_template's share of their solid
      tapered rod, as in the deck (:func:`atom_masses`).
    * Time: frame ``k`` is at ``step_k * dt`` (``dt``: the deck's time step in seconds, its
      ``timestep``), converted to ps; the frames must be equally spaced in steps. Without ``dt``
      the time of a frame is unknown: a warning says so and the trajectory's times are the MD
      step numbers, not ps.
    * Positions are the dump's, converted to Angstrom, not shifted: MDAnalysis's box spans
      [0, L) on each axis while the decks' boxes may start elsewhere (the plates' box below
      z = 0). ``shift_to_origin=True`` subtracts the box's lower corner from every position,
      so that they lie in MDAnalysis's box (for its wrapping and distance functions).
    * One trajectory frame per frame, velocities where the dump has them. MDAnalysis keeps
      positions as float32 (1e-7 of the box): the measurements of this package work on the
      frames themselves, in double precision.
    """
    with warnings.catch_warnings():
        # MDAnalysis 2.4 imports the deprecated xdrlib after installing its own warning filters,
        # which override ours: import it first, here, so that the warning is not printed.
        warnings.simplefilter("ignore", DeprecationWarning)
        try:
            import xdrlib  # noqa: F401
        except ImportError:
            pass
        import MDAnalysis
        from MDAnalysis.coordinates.memory import MemoryReader
    frames = list(frames)
    if not frames:
        raise ValueError("to_universe: no frames")
    first = frames[0]
    rod = first.rod_of_atom
    # A residue per rod, and per bead (told apart by the negated atom ID).
    key = np.where(rod > 0, rod, -first.ids)
    keys, resindex = np.unique(key, return_inverse=True)
    u = MDAnalysis.Universe.empty(len(first.ids), n_residues=len(keys), atom_resindex=resindex,
                                  trajectory=True)
    angstrom = lambda fr: fr.length_unit / _ANGSTROM          # Angstrom per frame length
    u.add_TopologyAttr("ids", first.ids)
    u.add_TopologyAttr("types", first.types.astype(str))
    u.add_TopologyAttr("radii", first.radius * angstrom(first))
    u.add_TopologyAttr("masses", atom_masses(first, densities) / _AMU)
    u.add_TopologyAttr("resids", np.maximum(keys, 0))
    u.add_TopologyAttr("resnames", np.where(keys > 0, "ROD", "BEAD"))
    positions = np.stack([((fr.pos - fr.box.lo) if shift_to_origin else fr.pos) * angstrom(fr)
                          for fr in frames])
    dimensions = np.array([list(np.asarray(fr.box.lengths) * angstrom(fr)) + [90.0, 90.0, 90.0]
                           for fr in frames])
    velocities = None
    if all(fr.vel is not None for fr in frames):
        # m/s = 1e10 Angstrom / 1e12 ps
        velocities = np.stack([fr.vel * fr.length_unit / _ANGSTROM * _PS for fr in frames])
    steps = np.array([fr.step for fr in frames], float)
    spacing = np.diff(steps)
    if len(spacing) and not np.allclose(spacing, spacing[0]):
        raise ValueError(f"to_universe: frames at steps {steps[:4].astype(int).tolist()}...: "
                         "MDAnalysis needs equally spaced frames")
    if dt is None:
        warnings.warn("to_universe: no dt (the deck's time step, in s) given: the trajectory's "
                      "times are MD step numbers, not ps", stacklevel=2)
        scale = 1.0
    else:
        scale = dt / _PS
    u.load_new(positions, format=MemoryReader, order="fac", dimensions=dimensions,
               velocities=velocities, dt=(spacing[0] if len(spacing) else 1.0) * scale,
               time_offset=steps[0] * scale)
    return u


def write_extxyz(path, frames):
    """Write frames (any iterable, taken one at a time) as extended XYZ through ase (cell, pbc,
    ``mol``, ``radius`` and velocities per atom), a format OVITO and VMD open directly. Returns the
    number of frames written."""
    import ase.io
    written = 0
    with open(path, "w") as f:
        for fr in frames:
            ase.io.write(f, fr.to_ase(), format="extxyz")
            written += 1
    return written


def run_frames(frames, single_frame, lag=0):
    """Yield ``single_frame(k, frame, previous)`` for the frames of ``frames`` (any iterable, taken
    one at a time), where ``previous`` is the frame ``lag`` places back (None when ``lag`` is 0 or
    there is none yet): the one loop over frames of the CLI, as MDAnalysis's ``AnalysisBase.run``
    calls ``_single_frame``. Only the last ``lag`` frames are held."""
    if lag < 0:
        raise ValueError(f"lag {lag} must be >= 0")
    held = collections.deque(maxlen=lag + 1)
    for k, frame in enumerate(frames):
        held.append(frame)
        yield single_frame(k, frame, held[0] if lag and len(held) > lag else None)
