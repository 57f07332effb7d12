"""Single-rod motility on synthetic persistent random walks with known speed and tau."""
import numpy as np
import pytest

from activegrain import motility as M, synthetic as S, read_dump, write_dump


def test_ballistic_msd_and_constant_axial_speed():
    t = np.arange(50) * 0.1
    c = np.column_stack([3.0 * t, np.zeros_like(t)])
    lags, m = M.msd(c, 20)
    assert np.allclose(m, (3.0 * 0.1 * lags) ** 2)
    lags, C = M.orientation_correlation(np.tile([0.0, 1.0], (50, 1)), 10)
    assert np.allclose(C, 1.0)


def test_persistent_walk_speed_and_persistence_time():
    rng = np.random.default_rng(4)
    speed, tau, dt = 3.6, 2.0, 0.02
    walks = [S.persistent_walk(3000, dt, speed, tau, rng) for _ in range(40)]
    t = walks[0][0]
    centre = np.stack([w[1] for w in walks], axis=1)
    axis = np.stack([w[2] for w in walks], axis=1)
    tracks = M.RodTracks(t, np.arange(40), centre, axis)
    summary = M.motility_summary(tracks, max_lag=1000)
    assert summary["axial_speed_mean"] == pytest.approx(speed, rel=0.01)  # finite differences
    assert summary["persistence_time"] == pytest.approx(tau, rel=0.1)
    assert summary["msd_speed"] == pytest.approx(speed, rel=0.1)
    assert summary["msd_persistence_time"] == pytest.approx(tau, rel=0.15)


def test_tracks_from_dump_unwrap_periodic_boundaries(tmp_path):
    rng = np.random.default_rng(7)
    box = S.square_box(30)
    t, centre, axis = S.persistent_walk(200, 0.05, 4.0, 20.0, rng, start=(20.0, 15.0))
    frames = [S.make_frame(box, [(1.0, 1.0)], 0.5, [c], [p], rod_vel=[4.0 * p], step=i, time=None)
              for i, (c, p) in enumerate(zip(centre, axis))]
    path = tmp_path / "walk.dump"
    write_dump(path, frames)
    tracks = M.rod_tracks(read_dump(str(path), timestep=0.05))
    wrapped = np.array([fr.rods().centre[0] for fr in frames])
    assert np.abs(np.diff(wrapped, axis=0)).max() > 25  # it does cross the boundary
    assert np.allclose(tracks.centre[:, 0], centre, atol=1e-3)  # unwrapped over the boundaries
    assert np.allclose(M.axial_speed(tracks), 4.0, atol=1e-4)   # from the dumped velocities
    from_positions = M.axial_speed(tracks, use_velocities=False)
    assert np.allclose(from_positions[1:-1], 4.0, rtol=0.01)    # chord vs arc of a curving path
    assert tracks.t[-1] == pytest.approx(199 * 0.05)


def test_persistence_time_needs_correlated_data():
    with pytest.raises(ValueError, match="floor"):
        M.persistence_time([0.0, 1.0, 2.0], [1.0, 0.0, 0.0])


def test_every_quantity_has_its_unit():
    rng = np.random.default_rng(2)
    walks = [S.persistent_walk(500, 0.02, 3.6, 1.0, rng) for _ in range(10)]
    tracks = M.RodTracks(walks[0][0], np.arange(10), np.stack([w[1] for w in walks], 1),
                         np.stack([w[2] for w in walks], 1))
    summary = M.motility_summary(tracks, length="mm", time="s")
    measured = {k for k, v in summary.items() if isinstance(v, float)}
    assert measured == set(summary["units"]) - {k for k, v in summary.items() if v is None}
    assert summary["units"]["axial_speed_mean"] == summary["units"]["msd_speed"] == "mm/s"
    assert summary["units"]["persistence_time"] == summary["units"]["tracked_duration"] == "s"
    assert summary["tracked_duration"] == pytest.approx(499 * 0.02)
    assert summary["longest_lag"] == pytest.approx(250 * 0.02)            # half the frames
    assert summary["persistence_time_resolved"] and summary["msd_persistence_time_resolved"]
    assert M.length_unit_name(1e-3) == "mm" and M.length_unit_name(1.0) == "m"


def test_a_persistence_time_longer_than_the_track_is_unresolved_not_a_number():
    # rods that keep their heading for 50 s, tracked for 1.5 s: their heading has barely turned
    rng = np.random.default_rng(5)
    walks = [S.persistent_walk(76, 0.02, 3.6, 50.0, rng) for _ in range(20)]
    tracks = M.RodTracks(walks[0][0], np.arange(20), np.stack([w[1] for w in walks], 1),
                         np.stack([w[2] for w in walks], 1))
    with pytest.warns(M.UnresolvedPersistenceWarning, match="longer than the longest lag, 0.76 s"):
        summary = M.motility_summary(tracks)
    assert summary["persistence_time"] is None and summary["persistence_time_resolved"] is False
    assert summary["msd_persistence_time"] is None and summary["msd_persistence_time_resolved"] is False
    assert summary["axial_speed_mean"] == pytest.approx(3.6, rel=0.01)   # the speed is measured
    assert summary["msd_speed"] == pytest.approx(3.6, rel=0.05)
