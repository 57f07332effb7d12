"""A run continued from restart files written on 2 ranks goes on, on 1 and on 4 ranks, as the
uninterrupted 2-rank run: channel-small to 0.06 s, continued from its restart file at 0.05 s (step
500). The quantities compared are the channel's thermo output (polar and nematic order, rods, rod
temperature), at the file's step and 50 and 100 steps on, to 1e-6 (the tolerance of
test_examples.py's same-rank continuation): every island is solved whole on any number of ranks
(docs/pair_gran_impulse.rst, parallel runs), so the trajectories differ only by round-off (another
number of ranks sums a ghost atom's contact forces in another order), which the bed's collisions
amplify over many more steps."""
import pytest

from test_examples import channel_thermo, DT


@pytest.fixture(scope="module")
def written_on_two_ranks(tmp_path_factory):
    base = tmp_path_factory.mktemp("restart-2")
    whole = channel_thermo(base / "whole", 2)
    restart = base / "whole" / "channel.restart.1"
    assert restart.exists()
    return whole, restart


@pytest.mark.parametrize("ranks", [1, 4])
def test_a_restart_written_on_two_ranks_continues_on_other_rank_counts(tmp_path, written_on_two_ranks, ranks):
    whole, restart = written_on_two_ranks
    continued = channel_thermo(tmp_path / "continued", ranks, "-var", "continue", str(restart))
    assert sorted(continued) == [500, 550, 600]
    for step in (500, 550, 600):
        assert continued[step][0] == pytest.approx(step * DT, rel=1e-12)
    for step in (500, 550, 600):
        assert continued[step][1:] == pytest.approx(whole[step][1:], rel=1e-6), (step, continued[step], whole[step])
    print(f"{ranks} ranks: bit for bit at 500: {continued[500] == whole[500]}, at 550: {continued[550] == whole[550]}, "
          f"at 600: {continued[600] == whole[600]} ({continued[600]} against {whole[600]})")
