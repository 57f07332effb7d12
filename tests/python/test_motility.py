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
