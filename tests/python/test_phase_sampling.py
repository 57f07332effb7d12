"""The phase classifier's verdict is a property of the run, not of how often it was dumped.

``data/channel-small-510s.npz``: 10 s of a real run, the condensed channel-small state
continued from 500 s with a frame every 0.05 s (only what the classifier reads: atom IDs, rod
IDs, radii and x, y to the dump's 0.1 um; z is left out)::

    cd examples/channel && lmp -in in.channel-small -var out RUN \\
        -var from states/channel-small-condensed-500s.data.gz -var time 510 -var dump 0.05 -var profile 5.0
    PYTHONPATH=python python3 tests/python/test_phase_sampling.py RUN/channel.dump tests/python/data/channel-small-510s.npz

The run sampled every 0.05, 0.1, 0.5 and 1 s must give the same verdict on the frames the four
share and the same rates; synthetic runs check the edge cases (one frame, rods at rest, aligned
rods held still, sampling)."""
import pathlib
import sys
import warnings

import numpy as np
import pytest

from activegrain import analysis as A, synthetic as S, write_dump
from activegrain.cli import main
from activegrain.geometry import Box, geometry_from_box
from activegrain.io import Frame

FIXTURE = pathlib.Path(__file__).resolve().parent / "data" / "channel-small-510s.npz"
UNIT = 1e-7                 # the fixture's positions: integers of 0.1 um, as the dump's digits
SAMPLINGS = (0.05, 0.1, 0.5, 1.0)


def make_fixture(dump, out):
    """The fixture from a dump of the run (metres, step 1e-4 s): positions as integer steps of
    0.1 um from frame to frame (first frame absolute), compressed."""
    from activegrain import read_dump
    frames = list(read_dump(dump))
    f0 = frames[0]
    q = np.round(np.array([f.pos[:, :2] for f in frames]) / UNIT).astype(np.int64)
    np.savez_compressed(out, step=np.array([f.step for f in frames]), lo=np.array(f0.box.lo),
                        hi=np.array(f0.box.hi), periodic=np.array(f0.box.periodic), ids=f0.ids, mol=f0.mol,
                        types=f0.types, radius=f0.radius, body=f0.body,
                        xy=np.diff(q, axis=0, prepend=0).astype(np.int32))


def load_fixture(timestep=1e-4):
    """The fixture's frames in bead diameters (d = 1 mm), times in seconds."""
    z = np.load(FIXTURE)
    box = Box(tuple(z["lo"]), tuple(z["hi"]), tuple(bool(p) for p in z["periodic"]))
    xy = np.cumsum(z["xy"].astype(np.int64), axis=0) * UNIT
    frames = []
    for step, pos in zip(z["step"], xy):
        pos3 = np.column_stack([box.wrap(pos), np.full(len(pos), 0.5e-3)])
        fr = Frame(int(step), int(step) * timestep, box, z["ids"], z["mol"], z["types"], z["radius"], pos3,
                   None, z["body"], 1.0)
        frames.append(fr.scaled(1e3))
    return frames


@pytest.fixture(scope="module")
def run():
    return load_fixture()


def shared_times(samplings, times):
    """The frames (times) that samplings every ``s`` seconds of ``times`` all hold."""
    keep = [np.isclose(np.round((times - times[0]) / s) * s, times - times[0], atol=1e-6) for s in samplings]
    return np.flatnonzero(np.logical_and.reduce(keep))


def test_the_fixture_is_the_run(run):
    assert len(run) == 201
    assert run[0].time == pytest.approx(500.0) and run[-1].time == pytest.approx(510.0)
    assert np.allclose(np.diff([f.time for f in run]), 0.05)
    rods = run[0].rods()
    assert len(rods) == 10 and np.sum(run[0].is_bead) == 859
    assert FIXTURE.stat().st_size < 2e6


def test_one_run_sampled_every_0_05_0_1_0_5_and_1_s_gives_the_same_phases_and_rates(run):
    times = np.array([f.time for f in run])
    shared = shared_times(SAMPLINGS, times)
    assert len(shared) == 11          # 500, 501, ..., 510 s
    geom = geometry_from_box(run[0].box)
    verdicts, obs = {}, {}
    for s in SAMPLINGS:
        k = int(round(s / 0.05))
        frames = run[::k]               # the run as a dump every s seconds would hold it
        res = A.classify_frames(frames, geom, window=1.0, which=[i // k for i in shared])
        verdicts[s] = [r.phase for r in res]
        obs[s] = res
    agree = np.mean([len({verdicts[s][j] for s in SAMPLINGS}) == 1 for j in range(len(shared))])
    assert agree >= 0.9, verdicts
    for s in SAMPLINGS[1:]:
        for fine, coarse in zip(obs[0.05], obs[s]):
            for name in ("rod_speed", "mobility"):
                assert coarse.observables[name] == pytest.approx(fine.observables[name], rel=0.1), (s, name)
            assert coarse.observables["P_mean"] == pytest.approx(fine.observables["P_mean"], abs=0.02)
            assert coarse.observables["window"] == pytest.approx(1.0)
    # what the run shows: a polar group of rods moving along its heading at a sixth of a rod length
    # per second, beads fluid (0.6-0.8 d/s); condensed when the layer's contrast is above 0.1
    speeds = [r.observables["rod_speed"] for r in obs[0.05]]
    assert 0.1 < min(speeds) and max(speeds) < 0.3
    assert {p.value for p in verdicts[0.05]} <= {"flock", "condensed"}


def test_the_phase_command_gives_every_frame_the_same_verdict_whatever_every(run, tmp_path):
    # the first 3 s of the run, dumped every 0.05 s (in metres) and every 0.5 s
    dumps = {}
    for s, k in ((0.05, 1), (0.5, 10)):
        dumps[s] = tmp_path / f"every{s}.dump"
        write_dump(dumps[s], [f.scaled(1e-3) for f in run[:61:k]])
    tables = {}
    for name, argv in {"all": [dumps[0.05]], "every 10": [dumps[0.05], "--every", "10"],
                       "0.5 s": [dumps[0.5]], "last": [dumps[0.05], "--frame", "-1"]}.items():
        out = __import__("io").StringIO()
        assert main(["phase", str(argv[0]), *map(str, argv[1:]), "--length-unit", "1e-3", "--timestep", "1e-4"],
                    out) == 0
        lines = out.getvalue().splitlines()
        head = lines[0].split()
        tables[name] = {row[0]: dict(zip(head, row)) for row in (l.split() for l in lines[1:])}
    assert len(tables["all"]) == 61 and len(tables["every 10"]) == len(tables["0.5 s"]) == 7
    assert list(tables["last"].values()) == [tables["all"]["5030000"]]     # --frame -1: with its window
    for step, row in tables["0.5 s"].items():
        for other in ("all", "every 10"):
            assert tables[other][step]["phase"] == row["phase"], step
            assert float(tables[other][step]["rod_speed"]) == pytest.approx(float(row["rod_speed"]), rel=1e-6)


# ---------------------------------------------------------------------------- synthetic runs

def _flock():
    return S.phase_configuration("flock", seed=1)      # 20 rods within +-15 degrees of +x, P 0.98


@pytest.mark.parametrize("speed", [0.3, 3.0])          # d/s: 0.07 and 0.7 rod lengths per second
def test_a_flock_is_a_flock_at_every_sampling_and_from_its_first_frame(speed):
    fr = _flock()
    geom = geometry_from_box(fr.box)
    for s in SAMPLINGS:
        frames = S.trajectory(fr, np.arange(0.0, 4.0 + 1e-9, s), rod_speed=speed, bead_speed=0.3, rattle=0.05)
        res = A.classify_frames(frames, geom, which=[0, 1] + [int(round(t / s)) for t in (2.0, 4.0)])
        assert {r.phase for r in res} == {"flock"}, s
        for r in res:   # the rods' speed along their mean heading, in rod lengths (4.5 d) per second,
            # to their rattle (at most 0.1 d / 4.5 d per rod in a 1 s window, 20 rods at random phases)
            assert r.observables["rod_speed"] == pytest.approx(speed / 4.5, rel=0.03, abs=0.008)
            assert r.observables["mobility"] == pytest.approx(0.3, rel=0.25)


def test_aligned_rods_at_rest_are_arrested_not_a_flock_from_the_first_frame_on():
    fr = _flock()
    frames = S.trajectory(fr, np.arange(0.0, 3.0 + 1e-9, 0.1), rattle=0.02)      # beads and rods rattle
    res = A.classify_frames(frames, geometry_from_box(fr.box))
    assert [r.phase for r in res] == ["arrested"] * len(frames)
    assert all(abs(r.observables["rod_speed"]) < 0.01 for r in res)


def test_aligned_rods_pressed_still_against_a_wall_are_arrested_not_isotropic():
    # as in rectangle-small: rods against the wall x = 40, pointing into it (P 0.9-1), beads
    # between and around them rattling in place
    box = Box((0.0, 0.0, 0.0), (40.0, 20.0, 1.12), (False, False, False))
    g = geometry_from_box(box)
    ys = np.arange(2.0, 19.0, 3.0)
    for spread in (0.0, 0.35, 0.5):
        ang = spread * np.sin(np.arange(len(ys)) * 2.1)
        axes = np.column_stack([np.cos(ang), np.sin(ang)])
        centres = np.column_stack([np.full(len(ys), 37.6), ys])
        beads = S.remove_overlaps(S.lattice_beads(0, 40, 0, 20, 1.25), box, centres, axes)
        fr = S.make_frame(box, beads, 0.5, centres, axes)
        P = A.polarization(fr)["P"]
        assert 0.9 < P <= 1.0
        frames = S.trajectory(fr, np.arange(0.0, 2.0 + 1e-9, 0.25), bead_speed=0.0, rattle=0.01)
        for s_frames in (frames, frames[::4]):           # 0.25 s and 1 s apart
            res = A.classify_frames(s_frames, g)
            assert {r.phase for r in res} == {"arrested"}, (spread, P)


def test_a_single_frame_is_classified_by_what_it_shows():
    fr = _flock()
    g = geometry_from_box(fr.box)
    res = A.classify_phase(fr, g)
    assert res.phase == "aligned"              # flock or arrested: one frame cannot tell
    assert np.isnan(res.observables["rod_speed"]) and np.isnan(res.observables["mobility"])
    assert res.observables["P_mean"] == res.observables["P"]
    # structure is what a frame shows
    for phase in ("isotropic", "segregated", "condensed"):
        c = S.phase_configuration(phase, seed=1)
        assert A.classify_phase(c, geometry_from_box(c.box)).phase == phase
    # a dense packing is never jammed on one frame: arrest takes time
    dense = S.dense_configuration()
    assert A.classify_phase(dense, geometry_from_box(dense.box)).phase != "jammed"
    with pytest.warns(A.SingleFrameWarning, match="single frame"):
        assert [r.phase for r in A.classify_frames([fr], g)] == ["aligned"]


def test_the_phase_command_on_one_frame_warns_and_says_aligned(tmp_path, capsys):
    dump = tmp_path / "one.dump"
    write_dump(dump, [_flock().scaled(1e-3)])
    out = __import__("io").StringIO()
    assert main(["phase", str(dump), "--length-unit", "1e-3", "--timestep", "1e-4"], out) == 0
    head, row = out.getvalue().splitlines()
    assert dict(zip(head.split(), row.split()))["phase"] == "aligned"
    assert capsys.readouterr().err.startswith("WARNING: activegrain phase: a single frame (step 0)")


@pytest.mark.parametrize("argv, message", [
    ([], "ERROR: activegrain phase: --timestep is needed: the phase is decided on rates and time averages "
         "in seconds"),
    (["--timestep", "1e-4", "--lag", "1"], "ERROR: activegrain phase: --lag is gone"),
    (["--timestep", "1e-4", "--window", "0"], "ERROR: activegrain phase: --window 0.0: seconds, above 0"),
    (["--timestep", "1e-4", "--window", "0.5"], "the 0.5 s window of the frame at step 0 holds no other "
                                                "frame: frames are up to 1 s apart"),
])
def test_the_phase_command_refuses_what_it_cannot_measure(tmp_path, capsys, argv, message):
    fr = _flock()
    dump = tmp_path / "run.dump"
    write_dump(dump, [f.scaled(1e-3) for f in S.trajectory(fr, [0.0, 1.0, 2.0], rod_speed=3.0)])
    assert main(["phase", str(dump), "--length-unit", "1e-3", *argv], __import__("io").StringIO()) == 1
    err = capsys.readouterr().err
    assert err.startswith("ERROR: activegrain phase: ") and message in err and err.count("\n") == 1


def test_windows_are_seconds_up_to_the_frame_and_within_the_run():
    t = np.arange(0.0, 5.0 + 1e-9, 0.25)
    assert A.window_of(t, 12, 1.0) == [8, 9, 10, 11, 12]                 # 2-3 s
    assert A.window_of(t, 1, 1.0) == [0, 1, 2, 3, 4]                     # the run's first second
    assert A.window_of(t[:3], 2, 1.0) == [0, 1, 2]                       # a run shorter than the window
    with pytest.warns(A.ShortRunWarning, match="less than the 1 s window"):
        frames = S.trajectory(_flock(), [0.0, 0.25, 0.5], rod_speed=3.0)
        assert A.classify_frames(frames, geometry_from_box(frames[0].box))[0].observables["window"] == 0.5
    with pytest.raises(ValueError, match="not in time order"):
        A.window_of(t[::-1], 0, 1.0)


def test_the_old_rule_per_frame_interval_is_what_the_rates_replace():
    # rods at 0.7 rod lengths per second advance 0.035 rod lengths in 0.05 s, below the old 0.05
    # per frame interval: sampled every 0.05 s the old rule called this flock isotropic, every
    # 0.1 s a flock; as a rate it is 0.7 L/s at both
    fr = _flock()
    for s in (0.05, 0.1):
        frames = S.trajectory(fr, np.arange(0.0, 2.0 + 1e-9, s), rod_speed=0.7 * 4.5)
        assert A.rod_drift(frames[1], frames[0]) == pytest.approx(0.7 * s, rel=0.03)
        r = A.classify_frames(frames, geometry_from_box(fr.box), which=[-1])[0]
        assert r.phase == "flock" and r.observables["rod_speed"] == pytest.approx(0.7, rel=0.03)


if __name__ == "__main__":      # python3 test_phase_sampling.py RUN/channel.dump OUT.npz
    make_fixture(*sys.argv[1:3])
