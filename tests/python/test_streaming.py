"""Dumps are analysed as they are read, a frame at a time: the phase classifier holds the frames of
its open windows only, so that memory does not grow with the length of the dump."""
import io
import tracemalloc

import numpy as np
import pytest

from activegrain import Dump, analysis as A, geometry_from_box, synthetic as S, write_dump
from activegrain.cli import main

TIMESTEP = 1e-4


@pytest.fixture(scope="module")
def run():
    """8 s of a 40 x 20 d cell, dumped every 0.1 s (times in seconds)."""
    return S.trajectory(S.phase_configuration("isotropic", length=40.0, width=20.0), np.arange(80) * 0.1,
                        rod_speed=1.0, bead_speed=0.3, rattle=0.05, timestep=TIMESTEP)


def test_the_phase_command_holds_the_same_memory_for_a_dump_four_times_longer(run, tmp_path):
    peaks, last_rows = {}, {}
    for n in (20, 80):
        dump = tmp_path / f"run{n}.dump"
        write_dump(dump, [f.scaled(1e-3) for f in run[:n]])
        out = io.StringIO()
        tracemalloc.start()
        try:
            assert main(["phase", str(dump), "--length-unit", "1e-3", "--timestep", str(TIMESTEP),
                         "--window", "0.2", "--frame", "-1"], out) == 0
            peaks[n] = tracemalloc.get_traced_memory()[1]
        finally:
            tracemalloc.stop()
        last_rows[n] = out.getvalue().splitlines()[1].split()
    # a frame takes 0.1 MB here (0.3 MB while parsed) and the classification's maps 4 MB: the 60
    # frames more of the longer dump, held, would raise the peak by a factor 1.4
    assert peaks[80] < 1.2 * peaks[20], peaks
    assert last_rows[20][0] == str(run[19].step) and last_rows[80][0] == str(run[79].step)


def test_a_dump_is_parsed_frame_by_frame_as_it_is_read(run, tmp_path):
    dump = tmp_path / "bad.dump"
    write_dump(dump, [f.scaled(1e-3) for f in run[:4]])
    text = dump.read_text().split("ITEM: TIMESTEP\n")
    lines = text[3].splitlines(keepends=True)
    lines[9] = "1 1 1 not-a-number 0 0 0 0 0 0 0\n"          # the third frame's first atom row
    dump.write_text("ITEM: TIMESTEP\n".join(text[:3] + ["".join(lines)] + text[4:]))
    reader = Dump(str(dump), length_unit=1e-3, timestep=TIMESTEP)
    assert len(reader) == 4 and reader.frame(1).step == run[1].step     # counted, not parsed
    frames = reader.frames()
    assert [next(frames).step for _ in range(2)] == [run[0].step, run[1].step]
    with pytest.raises(ValueError, match=f"frame at step {run[2].step}"):
        next(frames)


def test_the_classifier_reads_a_run_once_up_to_the_last_window_it_needs(run):
    geom = geometry_from_box(run[0].box)
    read = []

    def frames():
        for fr in run:
            read.append(fr.step)
            yield fr
    which = [2, 5]
    streamed = A.classify_frames(frames(), geom, window=0.2, which=which)
    # frame 5's window, 0.3-0.5 s, is whole once the frame at 0.6 s is read
    assert len(read) == 7
    listed = A.classify_frames(run[:10], geom, window=0.2, which=which)
    assert [r.phase for r in streamed] == [r.phase for r in listed]
    assert [r.observables for r in streamed] == [r.observables for r in listed]
