"""Command line: ``python3 -m activegrain {profile,map,polar,phase,condensate,motility,snapshot,kymograph,movie,convert,theory,continuum,sweep} ...``.

Every dump command takes the cell geometry (``--geometry``; auto reads the box flags:
pp pp = periodic box, pp ff = channel, ff ff = rectangle; an annulus needs ``--r-out``),
``--length-unit`` (e.g. 1e-3 to work in bead diameters from a dump in metres) and
``--timestep`` (time per MD step).

A bad argument or input prints one line, ``ERROR: activegrain COMMAND: ...`` (exit status 2 for
a command line that does not parse, else 1); a dump that ends within a frame (a killed
run) is read to its last whole frame with a line ``WARNING: activegrain COMMAND: ...``.
"""
import argparse
import json
import os
import pathlib
import shutil
import subprocess
import sys
import warnings

import numpy as np

from . import _env, analysis, io, motility, theory
from .geometry import geometry_from_box


def _add_dump_args(p):
    p.add_argument("dump", help="LAMMPS text dump (id mol type radius x y z [vx vy vz])")
    p.add_argument("--geometry", default="auto", choices=["auto", "box", "channel", "rectangle", "annulus"])
    p.add_argument("--centre", type=float, nargs=2, help="annulus centre (default: box centre)")
    p.add_argument("--r-in", type=float, default=0.0, help="annulus inner radius")
    p.add_argument("--r-out", type=float, help="annulus outer radius")
    p.add_argument("--length-unit", type=float, default=1.0, help="divide lengths by this")
    p.add_argument("--timestep", type=float, default=1.0, help="time per MD step")
    p.add_argument("--frame", type=int, default=None,
                   help="only this frame (python index, -1 = last); default all")
    p.add_argument("--every", type=int, default=None, help="every n-th frame")


def _frames(args):
    kw = dict(length_unit=args.length_unit, timestep=args.timestep)
    if args.frame is not None:
        return [io.read_frame(args.dump, args.frame, **kw)]
    return list(io.read_dump(args.dump, every=args.every, **kw))


def _geometry(args, frame):
    u = args.length_unit
    return geometry_from_box(frame.box, args.geometry,
                             None if args.centre is None else tuple(np.asarray(args.centre) / u),
                             args.r_in / u, None if args.r_out is None else args.r_out / u)


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
    frames = _frames(args)
    geom = _geometry(args, frames[0])
    if args.relative_to_layer:
        profiles = io.run_frames(frames, lambda k, fr, previous: analysis.layer_profile(
            fr, geom, extent=args.extent, bins=args.bins, species=args.species))
        name = "distance_ahead_of_layer"
    else:
        profiles = io.run_frames(frames, lambda k, fr, previous: analysis.area_fraction_profile(
            fr, geom, args.coord, args.bins, args.species, count=args.count))
        name = args.coord
    mean = np.mean([p.fraction for p in profiles], axis=0)
    avg = analysis.Profile(profiles[0].coord, args.species, profiles[0].edges, mean)
    _print_table([{name: float(c), "area_fraction": float(v)} for c, v in zip(avg.centres, mean)], out)
    if args.fit is not None:
        phi_plus, ell, phi0 = analysis.fit_layer_exponential(avg, args.fit[0], args.fit[1])
        out.write(f"# eq. 5 fit: phi_plus {phi_plus:.6g} ell {ell:.6g} phi0 {phi0:.6g}\n")
    if args.plot:
        from . import plotting
        plotting.plot_profiles([avg], args.plot, labels=[f"{args.species}, mean of {len(frames)} frame(s)"])


def cmd_map(args, out):
    frames = _frames(args)
    geom = _geometry(args, frames[0])
    maps = io.run_frames(frames, lambda k, fr, previous: analysis.area_fraction_map(
        fr, geom, tuple(args.bins), args.species, count=args.count))
    xe, ye = maps[0][0], maps[0][1]
    phi = np.mean([m[2] for m in maps], axis=0)
    if args.output.endswith(".txt") or args.output.endswith(".csv"):
        np.savetxt(args.output, phi.T, fmt="%.6g",
                   header=f"{args.species} area fraction, rows y ({ye[0]:g}..{ye[-1]:g}), "
                          f"columns x ({xe[0]:g}..{xe[-1]:g}), mean of {len(frames)} frame(s)")
    else:
        from . import plotting
        plotting.plot_map(xe, ye, phi, args.output, label=f"{args.species} area fraction")
    out.write(f"wrote {args.output}\n")


def cmd_polar(args, out):
    frames = _frames(args)
    geom = _geometry(args, frames[0])

    def single_frame(k, fr, previous):
        row = {"step": fr.step, "time": fr.time}
        row.update(analysis.polarization(fr, geom))
        env = analysis.rod_environment(fr, geom)
        row["gradient_alignment"] = analysis.alignment_of(env["cos"])
        row["phi_b_at_rods"] = float(env["phi_b"].mean()) if len(env["phi_b"]) else float("nan")
        return row
    _print_table(io.run_frames(frames, single_frame), out)


def cmd_phase(args, out):
    if args.lag < 0:
        raise ValueError(f"--lag {args.lag}: frames back, 0 or more")
    frames = _frames(args)
    geom = _geometry(args, frames[0])

    def single_frame(k, fr, previous):
        res = analysis.classify_phase(fr, geom, previous=previous)
        row = {"step": fr.step, "phase": res.phase.value}
        row.update({name: v for name, v in res.observables.items() if name != "layer_coord"})
        return row
    _print_table(io.run_frames(frames, single_frame, lag=args.lag), out)


def cmd_condensate(args, out):
    if args.lag < 1:
        raise ValueError(f"--lag {args.lag}: frames back, 1 or more")
    if args.reach <= 0:
        raise ValueError(f"--reach {args.reach}: rod lengths, above 0")
    frames = _frames(args)
    geom = _geometry(args, frames[0])
    arcs = io.run_frames(frames, lambda k, fr, previous: analysis.dense_arc(fr, geom, args.threshold, args.sectors))

    def single_frame(k, fr, before):
        row = {"step": fr.step, "time": fr.time}
        arc = arcs[k]
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
    _print_table(io.run_frames(frames, single_frame, lag=args.lag), out)


def cmd_motility(args, out):
    tracks = motility.rod_tracks(_frames(args))
    summary = motility.motility_summary(tracks, args.max_lag, use_velocities=not args.from_positions)
    out.write(json.dumps(summary, indent=1) + "\n")


def cmd_snapshot(args, out):
    from . import plotting
    fr = io.read_frame(args.dump, args.frame if args.frame is not None else -1,
                       length_unit=args.length_unit, timestep=args.timestep)
    plotting.snapshot(fr, _geometry(args, fr), args.output)
    out.write(f"wrote {args.output}\n")


def cmd_kymograph(args, out):
    from . import plotting
    frames = _frames(args)
    geom = _geometry(args, frames[0])
    profiles = io.run_frames(frames, lambda k, fr, previous: analysis.area_fraction_profile(
        fr, geom, args.coord, args.bins, "beads"))
    plotting.kymograph([fr.time for fr in frames], profiles, args.output)
    out.write(f"wrote {args.output}\n")


def cmd_movie(args, out):
    from . import plotting
    frames = _frames(args)
    plotting.movie(frames, args.output, _geometry(args, frames[0]), fps=args.fps)
    out.write(f"wrote {args.output} ({len(frames)} frames)\n")


def cmd_convert(args, out):
    frames = _frames(args)
    io.write_extxyz(args.output, frames)
    out.write(f"wrote {args.output} ({len(frames)} frames)\n")


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
    cfg = sweep.SweepConfig(
        deck=pathlib.Path(args.deck).resolve(), phi_b=args.phi_b, phi_r=args.phi_r, seeds=args.seeds,
        time=args.time, out=pathlib.Path(args.out).resolve(), ranks=args.ranks,
        variables=[tuple(v) for v in args.var or []], lmp=args.lmp, mpirun=args.mpirun, dump=args.dump,
        frames=args.frames, lag=args.lag, geometry=args.geometry, r_in=args.r_in, r_out=args.r_out,
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
        name = self.prog.replace("python3 -m ", "")
        self.exit(2, f"ERROR: {name}: {message} (see {self.prog} --help)\n")


def build_parser():
    ap = _Parser(prog="python3 -m activegrain", description=__doc__,
                 formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = ap.add_subparsers(dest="command", required=True)

    p = sub.add_parser("profile", help="area-fraction profile (mean over the frames)")
    _add_dump_args(p)
    p.add_argument("--coord", default="x", choices=["x", "y", "r", "theta"])
    p.add_argument("--bins", type=int, default=50)
    p.add_argument("--species", default="beads", choices=analysis.SPECIES)
    p.add_argument("--count", default="covered", choices=analysis.COUNTS,
                   help="covered: area where it lies; centre: per atom centre, as compute areafrac/chunk")
    p.add_argument("--relative-to-layer", action="store_true",
                   help="profile against the distance ahead of each frame's densest rod layer")
    p.add_argument("--extent", type=float, help="with --relative-to-layer: largest |distance|")
    p.add_argument("--fit", type=float, nargs=2, metavar=("START", "STOP"),
                   help="with --relative-to-layer: fit eq. 5's exponential between these distances")
    p.add_argument("--plot", help="also save a plot (png/pdf)")
    p.set_defaults(func=cmd_profile)

    p = sub.add_parser("map", help="2D area-fraction map (png, or .txt/.csv table)")
    _add_dump_args(p)
    p.add_argument("--bins", type=int, nargs=2, default=[60, 12], metavar=("NX", "NY"))
    p.add_argument("--species", default="beads", choices=analysis.SPECIES)
    p.add_argument("--count", default="covered", choices=analysis.COUNTS,
                   help="covered: area where it lies; centre: per atom centre, as compute areafrac/chunk")
    p.add_argument("-o", "--output", required=True)
    p.set_defaults(func=cmd_map)

    p = sub.add_parser("polar", help="rod polarization, velocity order, alignment with the bead gradient")
    _add_dump_args(p)
    p.set_defaults(func=cmd_polar)

    p = sub.add_parser("phase", help="classify each frame: isotropic/flock/segregated/condensed/jammed")
    _add_dump_args(p)
    p.add_argument("--lag", type=int, default=1,
                   help="bead mobility (jammed) and rod drift (flock) against the frame this many frames earlier (0: none)")
    p.set_defaults(func=cmd_phase)

    p = sub.add_parser("condensate", help="annulus: the dense arc, its drift round the ring, the rods pressing on its ends")
    _add_dump_args(p)
    p.add_argument("--threshold", type=float, default=0.8, help="bead area fraction of a dense sector")
    p.add_argument("--sectors", type=int, default=72, help="angular sectors round the ring")
    p.add_argument("--lag", type=int, default=1, help="drift against the frame this many frames earlier")
    p.add_argument("--reach", type=float, default=1.0,
                   help="rods pressing on an end: centres within this many rod lengths of it")
    p.set_defaults(func=cmd_condensate)

    p = sub.add_parser("motility", help="rod speed along the axis, MSD fit, persistence time")
    _add_dump_args(p)
    p.add_argument("--from-positions", action="store_true",
                   help="speeds from centre displacements between frames, not dumped velocities")
    p.add_argument("--max-lag", type=int, help="largest lag (frames) for MSD and correlation")
    p.set_defaults(func=cmd_motility)

    p = sub.add_parser("snapshot", help="draw one frame")
    _add_dump_args(p)
    p.add_argument("-o", "--output", required=True)
    p.set_defaults(func=cmd_snapshot)

    p = sub.add_parser("kymograph", help="bead profile against time")
    _add_dump_args(p)
    p.add_argument("--coord", default="x", choices=["x", "y", "r", "theta"])
    p.add_argument("--bins", type=int, default=100)
    p.add_argument("-o", "--output", required=True)
    p.set_defaults(func=cmd_kymograph)

    p = sub.add_parser("movie", help="animate the frames (.gif; .mp4 needs ffmpeg)")
    _add_dump_args(p)
    p.add_argument("-o", "--output", required=True)
    p.add_argument("--fps", type=int, default=10)
    p.set_defaults(func=cmd_movie)

    p = sub.add_parser("convert", help="write the frames as extended XYZ (through ase)")
    _add_dump_args(p)
    p.add_argument("-o", "--output", required=True)
    p.set_defaults(func=cmd_convert)

    p = sub.add_parser("theory", help="linear stability (growth) or moving point force (pointforce)")
    p.add_argument("model", choices=["growth", "pointforce"])
    for name, fld in theory.LinearParameters.__dataclass_fields__.items():
        p.add_argument(f"--{name}", type=float, default=fld.default,
                       help="bead density (growth: rho0; pointforce: far from the force, number per area)"
                       if name == "rho0" else "growth: model parameter")
    p.add_argument("--k-max", type=float, default=None, help="growth: largest k (default 2 sqrt(a/K))")
    p.add_argument("--n-k", type=int, default=400)
    p.add_argument("--full", action="store_true", help="growth: unexpanded 1/(a + K k^2) response")
    p.add_argument("--table", action="store_true", help="growth: print k and both growth rates")
    p.add_argument("--f", type=float, default=1.0, help="pointforce: force f")
    p.add_argument("--gamma", type=float, default=1.0, help="pointforce: drag per bead")
    p.add_argument("--v0", type=float, default=1.0, help="pointforce: speed of the force")
    p.add_argument("--T", type=float, default=1.0, help="pointforce: temperature of the hard-disk EOS")
    p.add_argument("--d", type=float, default=1.0, help="pointforce: disc diameter")
    p.add_argument("--plot", help="save a plot")
    p.set_defaults(func=cmd_theory)

    p = sub.add_parser("continuum", help="run the continuum theory (FFTW solver): pictures, movie, fields")
    for name, fld in theory.LinearParameters.__dataclass_fields__.items():
        p.add_argument(f"--{name}", type=float, default=fld.default,
                       help="mean density" if name in ("rho0", "sigma0") else "model parameter")
    p.add_argument("--tau", type=float, default=0.0, help="P relaxation time (0: P slaved)")
    p.add_argument("--rho_close", type=float, default=0.0,
                   help="bead density of close packing (hard-disk stiffness; 0: constant D_rho)")
    p.add_argument("--proportional-cross-diffusion", action="store_true",
                   help="cross-diffusion times the moving species' density (keeps densities positive)")
    p.add_argument("--n", type=int, nargs="+", default=[256], help="grid points: NX (1D) or NX NY (2D)")
    p.add_argument("--length", type=float, nargs="+", default=[100.0], help="box: LX (1D) or LX LY")
    p.add_argument("--dt", type=float, default=5e-3)
    p.add_argument("--t-end", type=float, default=100.0)
    p.add_argument("--frames", type=int, default=100)
    p.add_argument("--amplitude", type=float, default=1e-3, help="relative noise of the uniform start")
    p.add_argument("--seed", type=int, default=0)
    p.add_argument("--save", help="write t, x, y, rho, sigma, P (.npz)")
    p.add_argument("--kymograph", help="space-time picture (1D) or last frame (2D), png")
    p.add_argument("--movie", help="animation (.gif)")
    p.add_argument("--fps", type=int, default=10)
    p.set_defaults(func=cmd_continuum)

    p = sub.add_parser("sweep", help="run a deck over a (phi_b, phi_r) grid and seeds: phase table and diagram",
                       description="Run DECK (from its folder) for every phi_b x phi_r x seed with mpirun, "
                       "resumably (a run's folder with result.json is skipped), classify the last frames "
                       "of each run's dump and write phases.txt, phases.csv and phase_diagram.png into --out.")
    p.add_argument("deck", help="LAMMPS input deck taking -var phi_b phi_r seed time out (the example decks)")
    p.add_argument("--phi-b", type=float, nargs="+", required=True, help="bead area fractions")
    p.add_argument("--phi-r", type=float, nargs="+", required=True, help="rod area fractions")
    p.add_argument("--seeds", type=int, nargs="+", default=[2024], help="seeds (one run each per point)")
    p.add_argument("--time", type=float, required=True, help="simulated time per run (-var time)")
    p.add_argument("--out", required=True, help="folder of the sweep (one sub-folder per run)")
    p.add_argument("--var", nargs=2, action="append", metavar=("NAME", "VALUE"),
                   help="a fixed deck variable, repeatable (e.g. --var Lx 80e-3)")
    p.add_argument("--ranks", type=int, default=1, help="MPI ranks per run (mpirun -np)")
    p.add_argument("--lmp", default=_default_lmp(), help="LAMMPS executable with the plugin (default: "
                   "$ACTIVEGRAIN_LMP, lmp on PATH, or build/lmp)")
    p.add_argument("--mpirun", default="mpirun")
    p.add_argument("--timeout", type=float, help="seconds allowed per run")
    p.add_argument("--dump", help="dump file a run writes (default: the only *.dump in its folder)")
    p.add_argument("--frames", type=int, default=5, help="classify this many last frames (majority)")
    p.add_argument("--lag", type=int, default=1, help="bead mobility (jammed) and rod drift (flock) against the frame this many earlier")
    p.add_argument("--geometry", default="auto", choices=["auto", "box", "channel", "rectangle", "annulus"])
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
        if issubclass(category, io.TruncatedDumpWarning):
            sys.stderr.write(f"WARNING: {name}: {message}\n")
        else:
            show(message, category, *rest, **kw)
    with warnings.catch_warnings():
        warnings.showwarning = one_line
        warnings.simplefilter("always", io.TruncatedDumpWarning)     # each dump's, every call
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
