"""Command line: ``activegrain COMMAND ...``, COMMAND one of profile, map, polar, phase,
condensate, motility, snapshot, kymograph, movie, convert, theory, continuum, sweep.

Every dump command takes the cell geometry (``--geometry``; auto reads the box flags:
pp pp = periodic box, pp ff = channel, ff ff = rectangle; an annulus needs ``--r-out``),
``--length-unit`` (1e-3 to work in bead diameters d from the example decks' dumps, in metres)
and ``--timestep`` (the deck's time step in seconds, 1e-4 in the example decks; without it,
times are MD steps; ``phase``, whose rates are per second, needs it). Each command's
``--help`` gives its options, their defaults and examples.

A bad argument or input prints one line, ``ERROR: activegrain COMMAND: ...`` (exit status 2 for
a command line that does not parse, else 1); a dump that ends within a frame (a killed
run) is read to its last whole frame with a line ``WARNING: activegrain COMMAND: ...`` (both
on stderr).
"""
import argparse
import itertools
import json
import os
import pathlib
import re
import shutil
import subprocess
import sys
import textwrap
import warnings

import numpy as np

from . import _env, analysis, io, motility, theory
from .geometry import geometry_from_box


# The model parameters of activegrain.theory.LinearParameters (docs/continuum.rst, the paper's
# eqs. 1-2): currents J_rho = -D_rho grad rho - D_rho_sigma grad sigma + alpha rho P,
# J_sigma = -D_sigma grad sigma - D_sigma_rho grad rho + u0 sigma P, (a - K lap) P = A grad rho + B grad sigma.
_PARAMETER_HELP = {
    "rho0": "mean bead density", "sigma0": "mean rod density",
    "D_rho": "bead diffusivity", "D_sigma": "rod diffusivity",
    "D_rho_sigma": "beads' cross-diffusion down the rod gradient",
    "D_sigma_rho": "rods' cross-diffusion down the bead gradient",
    "alpha": "bead current along P per bead (alpha rho P)", "u0": "rod speed along P (u0 sigma P)",
    "A": "polarization by the bead gradient (A grad rho)", "B": "polarization by the rod gradient (B grad sigma)",
    "a": "P's restoring rate, > 0 (the isotropic phase)", "K": "P's stiffness (K lap P)"}

# continuum's defaults: the non-reciprocal set of docs/continuum.rst ("Travelling patterns"),
# continuum_figures.NON_RECIPROCAL.
CONTINUUM_DEFAULTS = dict(rho0=1.0, sigma0=0.5, D_rho=0.2, D_sigma=0.2, D_rho_sigma=1.0, D_sigma_rho=0.0,
                          alpha=1.0, u0=1.0, A=1.0, B=0.0, a=1.0, K=1.0)


def _add_dump_args(p, one_frame=False):
    p.add_argument("dump", help="LAMMPS text dump (id mol type radius x y z [vx vy vz] [body])")
    p.add_argument("--geometry", default="auto", choices=["auto", "box", "channel", "rectangle", "annulus"],
                   help="cell geometry (auto: from the box's boundary flags; an annulus needs --r-out)")
    p.add_argument("--centre", type=float, nargs=2, metavar=("X", "Y"),
                   help="annulus centre, dump units (default: the box centre)")
    p.add_argument("--r-in", type=float, default=0.0, help="annulus inner radius, dump units")
    p.add_argument("--r-out", type=float, help="annulus outer radius, dump units")
    p.add_argument("--length-unit", type=float, default=1.0,
                   help="divide the dump's lengths by this: 1e-3 gives bead diameters d for the example "
                        "decks' dumps (metres, d = 1 mm)")
    p.add_argument("--timestep", type=float, default=None,
                   help="the deck's time step in seconds (1e-4 in the example decks): times in seconds "
                        "(default: none, times are MD steps)")
    if one_frame:
        p.add_argument("--frame", type=int, default=-1, help="the frame (Python index, -1 = the last)")
        return
    p.add_argument("--frame", type=int, default=None,
                   help="only this frame (Python index, -1 = the last; default: all frames)")
    p.add_argument("--every", type=int, default=None, help="every n-th frame (default: every frame)")


def _timestep(args):
    """The time per MD step for reading: --timestep, else 1 (times are then step numbers)."""
    return 1.0 if args.timestep is None else args.timestep


def _check_every(args):
    if args.every is not None and args.every < 1:
        raise ValueError(f"--every {args.every}: 1 or more")


def _frames(args):
    """The frames that --frame and --every choose, each read from the dump when the analysis
    reaches it (never the whole dump in memory)."""
    _check_every(args)
    dump = io.Dump(args.dump, length_unit=args.length_unit, timestep=_timestep(args))
    return iter([dump.frame(args.frame)]) if args.frame is not None else dump.frames(every=args.every)


def _peek(frames):
    """(the first of ``frames``, an iterator over all of them, the first included)."""
    first = next(frames)
    return first, itertools.chain([first], frames)


def _geometry(args, frame):
    u = args.length_unit
    return geometry_from_box(frame.box, args.geometry,
                             None if args.centre is None else tuple(np.asarray(args.centre) / u),
                             args.r_in / u, None if args.r_out is None else args.r_out / u)


class _TimeSpan:
    """The number of frames analysed and their first and last times, noted as they pass, for a
    figure's title."""

    def __init__(self):
        self.count, self.first, self.last = 0, None, None

    def add(self, frame):
        self.count += 1
        self.first = frame.time if self.first is None else self.first
        self.last = frame.time

    def title(self, args):
        """The title: t = 2.00 s for one frame, else mean over t = 0.00-2.00 s (41 frames)."""
        unit = " s" if args.timestep is not None else " (MD steps)"
        from .plotting import seconds_text as text
        if self.count == 1:
            return f"t = {text(self.first)}{unit}"
        return f"mean over t = {text(self.first)}-{text(self.last)}{unit} ({self.count} frames)"


def _running_mean(frames, measure, values):
    """Over ``frames``, one at a time: the first frame's ``measure(frame)``, the mean over the
    frames of the array ``values(measure(frame))``, kept as a running sum, and their
    :class:`_TimeSpan`."""
    first, total, span = None, None, _TimeSpan()
    for fr in frames:
        measured = measure(fr)
        if first is None:
            first, total = measured, np.array(values(measured), float)
        else:
            total += values(measured)
        span.add(fr)
    return first, total / span.count, span


def _print_table(rows, out):
    """Whitespace-separated table; a column missing in a row (e.g. no rods) prints nan."""
    keys = list(dict.fromkeys(k for r in rows for k in r))
    out.write(" ".join(keys) + "\n")
    for r in rows:
        vals = (r.get(k, float("nan")) for k in keys)
        out.write(" ".join(f"{v:.6g}" if isinstance(v, float) else str(v) for v in vals) + "\n")


def cmd_profile(args, out):
    if args.fit is not None and not args.relative_to_layer:
        raise ValueError("--fit needs --relative-to-layer")
    first, frames = _peek(_frames(args))
    geom = _geometry(args, first)
    if args.relative_to_layer:
        measure = lambda fr: analysis.layer_profile(fr, geom, extent=args.extent, bins=args.bins,
                                                    species=args.species)
        name = "distance_ahead_of_layer"
    else:
        measure = lambda fr: analysis.area_fraction_profile(fr, geom, args.coord, args.bins, args.species,
                                                            count=args.count)
        name = args.coord
    profile, mean, span = _running_mean(frames, measure, lambda p: p.fraction)
    avg = analysis.Profile(profile.coord, args.species, profile.edges, mean)
    _print_table([{name: float(c), "area_fraction": float(v)} for c, v in zip(avg.centres, mean)], out)
    if args.fit is not None:
        phi_plus, ell, phi0 = analysis.fit_layer_exponential(avg, args.fit[0], args.fit[1])
        out.write(f"# eq. 5 fit: phi_plus {phi_plus:.6g} ell {ell:.6g} phi0 {phi0:.6g}\n")
    if args.plot:
        from . import plotting
        label = f"{plotting.SPECIES_LABELS[args.species]}, mean of {span.count} frame(s)"
        plotting.plot_profiles([avg], args.plot, labels=[label], unit=plotting.length_label(first),
                               title=span.title(args))


def cmd_map(args, out):
    first, frames = _peek(_frames(args))
    geom = _geometry(args, first)
    (xe, ye, _), phi, span = _running_mean(frames, lambda fr: analysis.area_fraction_map(
        fr, geom, tuple(args.bins), args.species, count=args.count), lambda m: m[2])
    if args.output.endswith(".txt") or args.output.endswith(".csv"):
        np.savetxt(args.output, phi.T, fmt="%.6g",
                   header=f"{args.species} area fraction, rows y ({ye[0]:g}..{ye[-1]:g}), "
                          f"columns x ({xe[0]:g}..{xe[-1]:g}), mean of {span.count} frame(s)")
    else:
        from . import plotting
        plotting.plot_map(xe, ye, phi, args.output, unit=plotting.length_label(first),
                          label=f"area fraction of {plotting.SPECIES_LABELS[args.species]}",
                          title=span.title(args))
    out.write(f"wrote {args.output}\n")


def cmd_polar(args, out):
    first, frames = _peek(_frames(args))
    geom = _geometry(args, first)

    def single_frame(k, fr, previous):
        row = {"step": fr.step, "time": fr.time}
        row.update(analysis.polarization(fr, geom))
        env = analysis.rod_environment(fr, geom)
        row["gradient_alignment"] = analysis.alignment_of(env["cos"])
        row["phi_b_at_rods"] = float(env["phi_b"].mean()) if len(env["phi_b"]) else float("nan")
        return row
    _print_table(list(io.run_frames(frames, single_frame)), out)


_LAG_GONE = ("--lag is gone: the phase is measured over a window of time, not a number of frames back "
             "(--window SECONDS, default {:g} s)")


def cmd_phase(args, out):
    if args.lag is not None:
        raise ValueError(_LAG_GONE.format(analysis.WINDOW))
    if args.timestep is None:
        raise ValueError("--timestep is needed: the phase is decided on rates and time averages in seconds "
                         "(the rods' speed, the beads' mobility, over --window seconds); give the deck's "
                         "time step (1e-4 in the example decks)")
    if not args.window > 0:
        raise ValueError(f"--window {args.window}: seconds, above 0")
    _check_every(args)
    # every frame of the dump, read as the windows reach it; --frame and --every choose the frames classified
    dump = io.Dump(args.dump, length_unit=args.length_unit, timestep=args.timestep)
    if args.frame is not None:
        if not -len(dump) <= args.frame < len(dump):
            raise ValueError(f"{args.dump}: no frame {args.frame} (the dump has {len(dump)})")
        which = [args.frame % len(dump)]
    else:
        which = range(0, len(dump), args.every or 1)
    first, frames = _peek(dump.frames())
    rows = []
    try:
        for k, frame, res in analysis.iter_phases(frames, _geometry(args, first), args.window, which=which):
            row = {"step": frame.step, "time": frame.time, "phase": res.phase.value}
            row.update({name: v for name, v in res.observables.items() if name != "layer_coord"})
            rows.append(row)
    except ValueError as e:      # the classifier's errors name the dump (the reader's name it already)
        text = str(e)
        raise ValueError(text if text.startswith(f"{args.dump}: ") else f"{args.dump}: {text}") from None
    _print_table(rows, out)


def cmd_condensate(args, out):
    if args.lag < 1:
        raise ValueError(f"--lag {args.lag}: frames back, 1 or more")
    if args.reach <= 0:
        raise ValueError(f"--reach {args.reach}: rod lengths, above 0")
    first, frames = _peek(_frames(args))
    geom = _geometry(args, first)
    arcs = []       # every frame's arc (small), for the drift against the frame --lag back

    def single_frame(k, fr, before):
        row = {"step": fr.step, "time": fr.time}
        arc = analysis.dense_arc(fr, geom, args.threshold, args.sectors)
        arcs.append(arc)
        if arc is not None:
            at_start, at_stop = analysis.capping_rods(fr, geom, arc, args.reach)
            row.update(start_deg=float(np.degrees(arc.start)), width_deg=float(np.degrees(arc.width)),
                       phi_inside=arc.fraction, phi_outside=arc.outside,
                       rods_at_start=at_start, rods_at_stop=at_stop)
            # the drift of the beads that were in the earlier frame's arc
            if before is not None and arcs[k - args.lag] is not None:
                row["drift_speed"] = (analysis.arc_drift(fr, before, geom, arcs[k - args.lag])
                                      / (fr.time - before.time))
        return row
    rows = list(io.run_frames(frames, single_frame, lag=args.lag))
    _print_table(rows, out)
    if args.traps is not None:
        column = lambda name: [r.get(name, float("nan")) for r in rows]
        spans = analysis.trap_spans(column("time"), np.nan_to_num(column("rods_at_start")),
                                    np.nan_to_num(column("rods_at_stop")), column("drift_speed"),
                                    args.traps, args.trap_drift, args.trap_gap)
        for first, last in spans:
            held = " (still trapped at the last frame)" if last == rows[-1]["time"] else ""
            out.write(f"# trapped from {first:g} to {last:g} ({last - first:g}){held}\n")
        if not spans:
            out.write("# never trapped\n")


def cmd_motility(args, out):
    tracks = motility.rod_tracks(_frames(args))
    summary = motility.motility_summary(tracks, args.max_lag, use_velocities=not args.from_positions,
                                        length=motility.length_unit_name(args.length_unit),
                                        time="s" if args.timestep is not None else "step")
    out.write(json.dumps(summary, indent=1) + "\n")


def cmd_snapshot(args, out):
    from . import plotting
    fr = io.read_frame(args.dump, args.frame, length_unit=args.length_unit, timestep=_timestep(args))
    plotting.snapshot(fr, _geometry(args, fr), args.output, seconds=args.timestep is not None, dpi=args.dpi)
    out.write(f"wrote {args.output}\n")


def cmd_kymograph(args, out):
    from . import plotting
    first, frames = _peek(_frames(args))
    geom = _geometry(args, first)
    times, profiles = [], []       # a row per frame (small), not the frames
    for fr in frames:
        times.append(fr.time)
        profiles.append(analysis.area_fraction_profile(fr, geom, args.coord, args.bins, args.species))
    plotting.kymograph(times, profiles, args.output, unit=plotting.length_label(first),
                       seconds=args.timestep is not None)
    out.write(f"wrote {args.output}\n")


def cmd_movie(args, out):
    from . import plotting
    first, frames = _peek(_frames(args))
    count = plotting.movie(frames, args.output, _geometry(args, first), fps=args.fps,
                           seconds=args.timestep is not None)
    out.write(f"wrote {args.output} ({count} frames)\n")


def cmd_convert(args, out):
    count = io.write_extxyz(args.output, _frames(args))
    out.write(f"wrote {args.output} ({count} frames)\n")


def cmd_theory(args, out):
    if args.model == "growth":
        names = [f for f in theory.LinearParameters.__dataclass_fields__]
        p = theory.LinearParameters(**{n: getattr(args, n) for n in names})
        k = np.linspace(0, args.k_max or 2 * np.sqrt(p.a / p.K), args.n_k)
        lam = theory.growth_rates(k, p, expanded=not args.full)
        out.write(f"condensation (A alpha rho0 + B u0 sigma0 > 0): {theory.condensation_condition(p)}\n")
        out.write(f"non-reciprocity condition: {theory.nonreciprocity_condition(p)}\n")
        ks, ls = theory.fastest_mode(p, args.k_max, expanded=not args.full)
        out.write(f"fastest mode: k = {ks:.6g}, Re lambda = {ls:.6g}\n")
        if args.table:
            _print_table([{"k": float(ki), "re1": float(l[0].real), "im1": float(l[0].imag),
                           "re2": float(l[1].real), "im2": float(l[1].imag)} for ki, l in zip(k, lam)], out)
        if args.plot:
            from . import plotting
            plotting.plot_growth_rates(k, lam, args.plot)
    else:
        eos = theory.HendersonEOS(T=args.T, d=args.d)
        pf = theory.point_force(args.f, args.rho0, args.gamma, args.v0, eos)
        out.write(f"rho+ = {pf.rho_plus:.8g}  (area fraction {float(eos.eta(pf.rho_plus)):.6g})\n")
        out.write(f"rho- = {pf.rho_minus:.8g}\nl+ = {pf.ell_plus:.8g}\n")
        if args.plot:
            from . import plotting
            x = np.linspace(0, 5 * pf.ell_plus, 400)
            plotting.plot_point_force(x, {"eq. 5 (exponential)": pf.profile(x),
                                          "steady eq. 3 (Henderson)": theory.steady_profile(x, pf, eos)},
                                      pf, args.plot)


def cmd_continuum(args, out):
    from . import continuum
    names = [f for f in continuum.ContinuumParameters.__dataclass_fields__ if f != "proportional_cross_diffusion"]
    p = continuum.ContinuumParameters(**{n: getattr(args, n) for n in names},
                                      proportional_cross_diffusion=args.proportional_cross_diffusion)
    n = args.n[0] if len(args.n) == 1 else tuple(args.n)
    length = args.length[0] if len(args.length) == 1 else tuple(args.length)
    run = continuum.simulate(p, n, length, args.dt, args.t_end, frames=args.frames, amplitude=args.amplitude,
                             seed=args.seed)
    out.write(f"regime (linear, full dispersion relation): {continuum.classify(p)}\n")
    out.write(f"t = {run.t[-1]:.6g}: rho in [{run.rho[-1].min():.6g}, {run.rho[-1].max():.6g}], "
              f"sigma in [{run.sigma[-1].min():.6g}, {run.sigma[-1].max():.6g}]\n")
    if args.save:
        np.savez_compressed(args.save, t=run.t, x=run.x, y=run.y if run.y is not None else np.empty(0),
                            rho=run.rho, sigma=run.sigma, P=run.P)
        out.write(f"wrote {args.save}\n")
    if args.kymograph:
        (continuum.kymograph if run.dim == 1 else continuum.snapshot)(run, args.kymograph)
        out.write(f"wrote {args.kymograph}\n")
    if args.movie:
        continuum.movie(run, args.movie, fps=args.fps)
        out.write(f"wrote {args.movie}\n")


def cmd_sweep(args, out):
    from . import sweep
    if args.lag is not None:
        raise ValueError(_LAG_GONE.format(analysis.WINDOW))
    cfg = sweep.SweepConfig(
        deck=pathlib.Path(args.deck).resolve(), phi_b=args.phi_b, phi_r=args.phi_r, seeds=args.seeds,
        time=args.time, out=pathlib.Path(args.out).resolve(), ranks=args.ranks,
        variables=[tuple(v) for v in args.var or []], lmp=args.lmp, mpirun=args.mpirun, dump=args.dump,
        frames=args.frames, window=args.window, timestep=args.timestep, geometry=args.geometry, r_in=args.r_in, r_out=args.r_out,
        length_unit=args.length_unit, timeout=args.timeout)
    results, ran = sweep.run_sweep(cfg)
    out.write(f"{ran} run(s) made, {len(results) - ran} already done; "
              f"wrote {cfg.out / 'phases.txt'}, phases.csv, phase_diagram.png\n")
    for r in results:
        out.write(f"phi_b {r['phi_b']:g} phi_r {r['phi_r']:g} seed {r['seed']}: {r['phase']}\n")


def _default_lmp():
    """$ACTIVEGRAIN_LMP, else lmp on PATH, else the build's wrapper next to this package."""
    if os.environ.get("ACTIVEGRAIN_LMP"):
        return os.environ["ACTIVEGRAIN_LMP"]
    if shutil.which("lmp"):
        return "lmp"
    return str(pathlib.Path(__file__).resolve().parents[2] / "build" / "lmp")


class _Parser(argparse.ArgumentParser):
    """argparse with one line for a bad command line, not the usage block."""

    def error(self, message):
        self.exit(2, f"ERROR: {self.prog}: {message} (see {self.prog} --help)\n")


# reST roles in docstrings: :func:`name`, :class:`~package.module.Name`, :py:meth:`title <target>`
_REST_ROLE = re.compile(r":(?:[a-z]+:)+`([^`]*)`")


def _plain_text(text):
    """reST markup of a docstring or help string as the terminal shows it: ``code`` and `text`
    as their text, a role such as :func:`name` as its name (``~a.b.c`` as c, ``title <target>``
    as title)."""
    def role(match):
        target = match.group(1).split(" <")[0]
        return target.rsplit(".", 1)[-1] if target.startswith("~") else target
    return _REST_ROLE.sub(role, text).replace("``", "").replace("`", "")


class _Formatter(argparse.RawDescriptionHelpFormatter):
    """Descriptions and examples as written, in plain text (no reST markup: the description of the
    command line is this module's docstring); each option's default after its help, where it has
    one (not for flags, and not for options whose absence the help explains)."""

    def _fill_text(self, text, width, indent):
        return super()._fill_text(_plain_text(text), width, indent)

    def _get_help_string(self, action):
        text = _plain_text(action.help or "")
        if ("%(default)" not in text and action.option_strings and action.default is not None
                and action.default is not False and action.default is not argparse.SUPPRESS
                and not isinstance(action, argparse._HelpAction)):
            text += " (default: %(default)s)"
        return text


# The example decks' dumps: SI, the beads' diameter 1 mm, time step 1e-4 s.
_DUMP_EXAMPLE_ARGS = "--length-unit 1e-3 --timestep 1e-4"


def _command(sub, name, summary, description, examples, dump=True, one_frame=False):
    """A subcommand with its one-line summary (in the command list), description, examples and,
    for dump commands, the common dump options."""
    p = sub.add_parser(name, help=summary, description=textwrap.fill(description, 90), formatter_class=_Formatter,
                       epilog="examples:\n" + "\n".join("  activegrain " + e for e in examples))
    if dump:
        _add_dump_args(p, one_frame)
    return p


def build_parser():
    ap = _Parser(prog="activegrain", description=__doc__, formatter_class=_Formatter,
                 epilog="activegrain COMMAND --help: the command's options, defaults and examples.")
    sub = ap.add_subparsers(dest="command", required=True, metavar="COMMAND")
    ex = _DUMP_EXAMPLE_ARGS

    p = _command(sub, "profile", "area-fraction profile along a coordinate (mean over the frames)",
                 "Area fraction covered by the beads, the rods or both (--species) in bins along x, y, r "
                 "or theta, averaged over the frames; printed as a table (coordinate, area_fraction), "
                 "optionally drawn (--plot). With --relative-to-layer the coordinate is the distance "
                 "ahead of each frame's densest rod layer, and --fit fits the paper's eq. 5 "
                 "exponential to it.",
                 [f"profile out/channel.dump {ex} --coord x --plot profile.png > profile.txt",
                  f"profile out/channel.dump {ex} --relative-to-layer --extent 30 --fit 2 25"])
    p.add_argument("--coord", default="x", choices=["x", "y", "r", "theta"],
                   help="coordinate of the bins (r, theta: about the annulus centre)")
    p.add_argument("--bins", type=int, default=50, help="number of bins")
    p.add_argument("--species", default="beads", choices=analysis.SPECIES,
                   help="whose area: beads, rods, or all (beads and rods)")
    p.add_argument("--count", default="covered", choices=analysis.COUNTS,
                   help="covered: area where it lies; centre: per atom centre, as compute areafrac/chunk")
    p.add_argument("--relative-to-layer", action="store_true",
                   help="profile against the distance ahead of each frame's densest rod layer")
    p.add_argument("--extent", type=float, help="with --relative-to-layer: largest |distance| "
                   "(default: half the cell)")
    p.add_argument("--fit", type=float, nargs=2, metavar=("START", "STOP"),
                   help="with --relative-to-layer: fit eq. 5's exponential between these distances")
    p.add_argument("--plot", help="also draw the profile into this file (png, pdf)")
    p.set_defaults(func=cmd_profile)

    p = _command(sub, "map", "2D area-fraction map (png, or .txt/.csv table)",
                 "Area fraction of the beads, the rods or both on a grid of NX x NY cells, averaged "
                 "over the frames: an image (png, pdf) or, for a .txt or .csv output, a table "
                 "(rows y, columns x; NaN outside the cell).",
                 [f"map out/channel.dump {ex} --bins 60 15 -o map.png",
                  f"map out/channel.dump {ex} --species all --frame -1 -o map.txt"])
    p.add_argument("--bins", type=int, nargs=2, default=[60, 12], metavar=("NX", "NY"), help="cells along x and y")
    p.add_argument("--species", default="beads", choices=analysis.SPECIES,
                   help="whose area: beads, rods, or all (beads and rods)")
    p.add_argument("--count", default="covered", choices=analysis.COUNTS,
                   help="covered: area where it lies; centre: per atom centre, as compute areafrac/chunk")
    p.add_argument("-o", "--output", required=True, help="image (png, pdf) or table (.txt, .csv)")
    p.set_defaults(func=cmd_map)

    p = _command(sub, "polar", "rods' polar order per frame, velocity order, alignment with the bead gradient",
                 "Per frame: the rods' polar order P = |<p>| (p: a rod's unit axis from tail to nose, "
                 "as compute polar/rod), its components, the nematic order S, the order of the rods' "
                 "and beads' velocities, the rods' alignment with the gradient of the bead area "
                 "fraction and the bead fraction around the rods. A table, one row per frame.",
                 [f"polar out/channel.dump {ex} --every 10 > polar.txt",
                  "polar minimal.dump --length-unit 1e-3 --timestep 1e-4 --frame -1"])
    p.set_defaults(func=cmd_polar)

    p = _command(sub, "phase", "classify each frame: isotropic, flock, arrested, segregated, condensed or jammed",
                 "The phase of the run at each frame (activegrain.analysis.classify_frames), from the "
                 "frame's structure and from rates and time averages over the --window seconds of the "
                 "run up to it, so that it does not depend on how often the run was dumped: jammed "
                 "(dense, beads arrested), condensed (a polar rod layer with denser beads ahead holds "
                 "most rods), segregated, flock (aligned and advancing), arrested (aligned, held still) "
                 "or isotropic; a table with the phase and its observables, one row per frame. Needs "
                 "--timestep. The windows use every frame of the dump; --every and --frame only choose "
                 "the frames classified.",
                 [f"phase out/channel.dump {ex} --every 10 > phase.txt",
                  f"phase run/box.dump {ex} --geometry box --window 2 --frame -1"])
    p.add_argument("--window", type=float, default=analysis.WINDOW,
                   help="seconds of the run up to a frame over which the rods' speed, the beads' mobility "
                        "and the mean polar order are taken (the first seconds of the run for a frame "
                        "less than this after its start)")
    p.add_argument("--lag", type=int, default=None, help=argparse.SUPPRESS)
    helps = {"--timestep": "the deck's time step in seconds (1e-4 in the example decks); needed: the rates "
                           "are per second",
             "--frame": "classify only this frame (Python index, -1 = the last), with its window from the "
                        "frames before it (default: all frames)",
             "--every": "classify every n-th frame, each with its window from all frames (default: every frame)"}
    for action in p._actions:
        if action.option_strings and action.option_strings[0] in helps:
            action.help = helps[action.option_strings[0]]
    p.set_defaults(func=cmd_phase)

    p = _command(sub, "condensate", "annulus: the dense arc, its drift round the ring, the rods pressing on its ends",
                 "In an annulus: per frame, the arc of sectors where the bead area fraction exceeds "
                 "--threshold, its width, the fractions inside and outside it, the rods pressing on "
                 "its two ends and the drift of its beads since an earlier frame.",
                 [f"condensate run/annulus.dump {ex} --geometry annulus --centre 0 0 --r-in 15e-3 "
                  "--r-out 28e-3"])
    p.add_argument("--threshold", type=float, default=0.8, help="bead area fraction of a dense sector")
    p.add_argument("--sectors", type=int, default=72, help="angular sectors round the ring")
    p.add_argument("--lag", type=int, default=1, help="drift against the frame this many frames earlier")
    p.add_argument("--reach", type=float, default=1.0,
                   help="rods pressing on an end: centres within this many rod lengths of it")
    p.add_argument("--traps", type=int, metavar="N",
                   help="after the table, the spans of time in which at least N rods press on each end "
                        "and the arc drifts no faster than --trap-drift (one line each, '# trapped from ...')")
    p.add_argument("--trap-drift", type=float, default=0.3,
                   help="--traps: the fastest drift of a trapped arc (dump length units, after "
                        "--length-unit, per time unit)")
    p.add_argument("--trap-gap", type=float, default=5.0,
                   help="--traps: trapped frames at most this far apart in time are one span")
    p.set_defaults(func=cmd_condensate)

    p = _command(sub, "motility", "rods' speed along their axes, mean square displacement, persistence time",
                 "Track the rods over the frames: their speed along their own axes (mean and spread), "
                 "a persistent random walk fitted to their mean square displacement, and the heading "
                 "correlation time; printed as JSON, with the unit of each quantity under \"units\": "
                 "lengths in mm for --length-unit 1e-3 (the dump's metres divided by it; m for 1), "
                 "times in s with --timestep, else in MD steps. A persistence time longer than the "
                 "longest lag (\"longest_lag\", --max-lag frames) is not resolved by the run: it is "
                 "null, its flag (\"persistence_time_resolved\", \"msd_persistence_time_resolved\") false, "
                 "and a WARNING line says so. Needs frames close "
                 "enough that rods move less than half the box between them.",
                 [f"motility out/rod.dump {ex}",
                  f"motility out/rod.dump {ex} --from-positions --max-lag 200"])
    p.add_argument("--from-positions", action="store_true",
                   help="speeds from centre displacements between frames, not dumped velocities")
    p.add_argument("--max-lag", type=int, help="largest lag (frames) for MSD and correlation "
                   "(default: half the frames)")
    p.set_defaults(func=cmd_motility)

    p = _command(sub, "snapshot", "draw one frame: rods tapered, coloured by heading, nose marked; the polar order",
                 "Draw one frame from above: beads grey, rods as their tapered shapes coloured by "
                 "heading (the colour wheel beside it is the key) with the nose, the narrow leading "
                 "end, marked by a dot; the title gives the time (with --timestep, in seconds), the "
                 "number of rods and their polar order P = |<p>|. Axes in bead diameters d when "
                 "--length-unit is the bead diameter (1e-3 for the example decks).",
                 [f"snapshot out/channel.dump {ex} --frame -1 -o snapshot.png",
                  f"snapshot minimal.dump {ex} --frame -1 -o snapshot.png"], one_frame=True)
    p.add_argument("-o", "--output", required=True, help="image file (png, pdf, svg)")
    p.add_argument("--dpi", type=int, default=150, help="resolution of a png, dots per inch (the figure is 10 inches wide)")
    p.set_defaults(func=cmd_snapshot)

    p = _command(sub, "kymograph", "area-fraction profile against time",
                 "The area fraction of the beads, the rods or both (--species) in bins along a "
                 "coordinate, frame by frame: an image with the coordinate across and time (with "
                 "--timestep, in seconds) up.",
                 [f"kymograph out/channel.dump {ex} --coord x -o kymograph.png",
                  f"kymograph out/channel.dump {ex} --species all --every 5 -o kymograph.png"])
    p.add_argument("--coord", default="x", choices=["x", "y", "r", "theta"],
                   help="coordinate of the bins (r, theta: about the annulus centre)")
    p.add_argument("--bins", type=int, default=100, help="number of bins")
    p.add_argument("--species", default="beads", choices=analysis.SPECIES,
                   help="whose area: beads, rods, or all (beads and rods)")
    p.add_argument("-o", "--output", required=True, help="image file (png, pdf)")
    p.set_defaults(func=cmd_kymograph)

    p = _command(sub, "movie", "animate the frames as snapshots (.gif; .mp4 needs ffmpeg)",
                 "Animate the frames, each drawn as the snapshot command draws it.",
                 [f"movie out/channel.dump {ex} --every 4 -o channel.gif"])
    p.add_argument("-o", "--output", required=True, help=".gif (Pillow) or .mp4 (ffmpeg)")
    p.add_argument("--fps", type=int, default=10, help="frames per second")
    p.set_defaults(func=cmd_movie)

    p = _command(sub, "convert", "write the frames as extended XYZ (through ase), for OVITO and VMD",
                 "Write the frames as extended XYZ through ase: cell, periodicity, positions (shifted "
                 "so that the box starts at 0, as ase's cell does), velocities, and per atom its "
                 "molecule ID, radius and rod (body) ID.",
                 [f"convert out/channel.dump {ex} -o channel.extxyz"])
    p.add_argument("-o", "--output", required=True, help="extended XYZ file")
    p.set_defaults(func=cmd_convert)

    p = _command(sub, "theory", "the paper's linear theory: growth rates (growth) or a moving point force (pointforce)",
                 "growth: the growth rates of the uniform rod-bead mixture, the condensation and "
                 "non-reciprocity conditions and the fastest mode (paper eqs. 1-2; --full for the "
                 "unexpanded response; docs/continuum.rst). pointforce: the bead density ahead of "
                 "a point force f moving at v0 through beads of the hard-disk equation of state "
                 "(paper eqs. 3-5): rho+, rho- and the decay length l+.",
                 ["theory growth --D_rho_sigma 0.5 --B -0.1 --plot growth.png",
                  "theory pointforce --f 2 --rho0 0.6 --plot pointforce.png"], dump=False)
    p.add_argument("model", choices=["growth", "pointforce"], help="which calculation")
    for name, fld in theory.LinearParameters.__dataclass_fields__.items():
        p.add_argument(f"--{name}", type=float, default=fld.default,
                       help="bead density (growth: rho0; pointforce: far from the force, number per area)"
                       if name == "rho0" else f"growth: {_PARAMETER_HELP[name]}")
    p.add_argument("--k-max", type=float, default=None, help="growth: largest k (default: 2 sqrt(a/K))")
    p.add_argument("--n-k", type=int, default=400, help="growth: number of k values")
    p.add_argument("--full", action="store_true", help="growth: unexpanded 1/(a + K k^2) response")
    p.add_argument("--table", action="store_true", help="growth: print k and both growth rates")
    p.add_argument("--f", type=float, default=1.0, help="pointforce: force f")
    p.add_argument("--gamma", type=float, default=1.0, help="pointforce: drag per bead")
    p.add_argument("--v0", type=float, default=1.0, help="pointforce: speed of the force")
    p.add_argument("--T", type=float, default=1.0, help="pointforce: temperature of the hard-disk EOS")
    p.add_argument("--d", type=float, default=1.0, help="pointforce: disc diameter")
    p.add_argument("--plot", help="draw the growth rates or the density profile into this file")
    p.set_defaults(func=cmd_theory)

    p = _command(sub, "continuum", "run the continuum theory in time (FFTW solver): fields, kymograph, movie",
                 "Integrate the paper's continuum equations for the bead density rho, the rod density "
                 "sigma and the polarization P on a periodic line (--n NX) or rectangle (--n NX NY) "
                 "from a uniform state with small noise (docs/continuum.rst). The defaults are that "
                 "page's non-reciprocal set (travelling patterns: beads flee rods, rods pursue beads) "
                 "on 512 points, L = 100, to t = 600, the run of its figure "
                 "kymograph_travelling.png (a few seconds).",
                 ["continuum --kymograph travelling.png",
                  "continuum --sigma0 0.2 --D_rho 0.3 --D_sigma 0.1 --D_rho_sigma 0.05 --D_sigma_rho 0.02 "
                  "--B 0.5 --a 2 --t-end 90 --kymograph condensation.png",
                  "continuum --n 128 128 --length 40 40 --t-end 100 --kymograph last.png --save run.npz"],
                 dump=False)
    for name, fld in theory.LinearParameters.__dataclass_fields__.items():
        p.add_argument(f"--{name}", type=float, default=CONTINUUM_DEFAULTS[name], help=_PARAMETER_HELP[name])
    p.add_argument("--tau", type=float, default=0.0, help="P relaxation time (0: P slaved)")
    p.add_argument("--rho_close", type=float, default=0.0,
                   help="bead density of close packing (hard-disk stiffness; 0: constant D_rho)")
    p.add_argument("--proportional-cross-diffusion", action=argparse.BooleanOptionalAction, default=True,
                   help="cross-diffusion times the moving species' density (keeps densities positive; "
                        "--no-proportional-cross-diffusion: the paper's constant one)")
    p.add_argument("--n", type=int, nargs="+", default=[512], help="grid points: NX (1D) or NX NY (2D)")
    p.add_argument("--length", type=float, nargs="+", default=[100.0], help="box: LX (1D) or LX LY")
    p.add_argument("--dt", type=float, default=2.5e-3, help="time step")
    p.add_argument("--t-end", type=float, default=600.0, help="time at the end of the run")
    p.add_argument("--frames", type=int, default=150, help="frames kept (for --save, --kymograph, --movie)")
    p.add_argument("--amplitude", type=float, default=1e-2, help="relative noise of the uniform start")
    p.add_argument("--seed", type=int, default=1, help="seed of the noise")
    p.add_argument("--save", help="write t, x, y, rho, sigma, P (.npz)")
    p.add_argument("--kymograph", help="space-time picture (1D) or last frame (2D), png")
    p.add_argument("--movie", help="animation (.gif)")
    p.add_argument("--fps", type=int, default=10, help="movie: frames per second")
    p.set_defaults(func=cmd_continuum)

    p = _command(sub, "sweep", "run a deck over a (phi_b, phi_r) grid and seeds: phase table and diagram",
                 "Run DECK (from its folder) for every phi_b x phi_r x seed with mpirun, "
                 "resumably (a run's folder with result.json is skipped), classify the last frames "
                 "of each run's dump and write phases.txt, phases.csv and phase_diagram.png into --out.",
                 ["sweep examples/channel/in.channel-small --phi-b 0.5 0.65 0.75 --phi-r 0.04 --time 60 "
                  "--out sweep1 --ranks 2",
                  "sweep examples/box/in.box-small --phi-b 0.7 0.8 --phi-r 0.03 --seeds 1 2 --time 100 "
                  "--out sweep2 --var Lx 80e-3"], dump=False)
    p.add_argument("deck", help="LAMMPS input deck taking -var phi_b phi_r seed time out (the example decks)")
    p.add_argument("--phi-b", type=float, nargs="+", required=True, help="bead area fractions")
    p.add_argument("--phi-r", type=float, nargs="+", required=True, help="rod area fractions")
    p.add_argument("--seeds", type=int, nargs="+", default=[2024], help="seeds (one run each per point)")
    p.add_argument("--time", type=float, required=True, help="simulated time per run, s (-var time)")
    p.add_argument("--out", required=True, help="folder of the sweep (one sub-folder per run)")
    p.add_argument("--var", nargs=2, action="append", metavar=("NAME", "VALUE"),
                   help="a fixed deck variable, repeatable (e.g. --var Lx 80e-3)")
    p.add_argument("--ranks", type=int, default=1, help="MPI ranks per run (mpirun -np)")
    p.add_argument("--lmp", default=_default_lmp(), help="LAMMPS executable with the plugin "
                   "($ACTIVEGRAIN_LMP, lmp on PATH, or build/lmp)")
    p.add_argument("--mpirun", default="mpirun", help="MPI launcher")
    p.add_argument("--timeout", type=float, help="seconds allowed per run (default: no limit)")
    p.add_argument("--dump", help="dump file a run writes (default: the only *.dump in its folder)")
    p.add_argument("--frames", type=int, default=5, help="classify this many last frames (majority)")
    p.add_argument("--window", type=float, default=analysis.WINDOW,
                   help="seconds of the run up to a frame over which its rates and averages are taken")
    p.add_argument("--timestep", type=float, default=1e-4,
                   help="the deck's time step, s (the example decks'): frame times in seconds")
    p.add_argument("--lag", type=int, default=None, help=argparse.SUPPRESS)
    p.add_argument("--geometry", default="auto", choices=["auto", "box", "channel", "rectangle", "annulus"],
                   help="cell geometry (auto: from the box's boundary flags)")
    p.add_argument("--r-in", type=float, default=0.0, help="annulus inner radius (dump units)")
    p.add_argument("--r-out", type=float, help="annulus outer radius (dump units)")
    p.add_argument("--length-unit", type=float, default=1e-3, help="divide dump lengths by this (metres -> d)")
    p.set_defaults(func=cmd_sweep)
    return ap


def _error_text(e):
    """One line for an error met by a command."""
    if isinstance(e, OSError) and e.filename is not None and e.strerror:
        return f"{e.filename}: {e.strerror}"         # not "[Errno 2] No such file or directory: 'x'"
    return " ".join(str(e).split()) or type(e).__name__


# What a command warns of, each in one line on stderr (not Python's warning with its source line).
_ONE_LINE_WARNINGS = (io.TruncatedDumpWarning, analysis.ShortRunWarning, analysis.SingleFrameWarning,
                     motility.UnresolvedPersistenceWarning)


def main(argv=None, out=None):
    """Run the command line; returns the exit status (0, 1 for an error met by the command; a
    bad command line exits with status 2)."""
    parser = build_parser()
    args = parser.parse_args(argv)
    name = f"activegrain {args.command}"
    if getattr(args, "geometry", None) == "annulus" and args.r_out is None:   # before reading a dump
        sys.stderr.write(f"ERROR: {name}: --geometry annulus needs --r-out\n")
        return 1
    show = warnings.showwarning

    def one_line(message, category, *rest, **kw):
        if issubclass(category, _ONE_LINE_WARNINGS):
            sys.stderr.write(f"WARNING: {name}: {message}\n")
        else:
            show(message, category, *rest, **kw)
    with warnings.catch_warnings():
        warnings.showwarning = one_line
        for category in _ONE_LINE_WARNINGS:
            warnings.simplefilter("always", category)     # each dump's, every call
        try:
            args.func(args, out or sys.stdout)
        except ModuleNotFoundError as e:
            if not _env.is_third_party(e.name):
                raise
            sys.stderr.write(_env.missing_module_line(e.name) + "\n")
            return 1
        except (ValueError, RuntimeError, OSError, FloatingPointError, subprocess.TimeoutExpired) as e:
            sys.stderr.write(f"ERROR: {name}: {_error_text(e)}\n")
            return 1
    return 0
