"""TPOT-RL's table, update, choice, reward and file (learning/tpot.py)."""

from __future__ import annotations

import zipfile
from pathlib import Path

import numpy as np
import pytest

from learning.tpot import (
    ALPHA_MIN,
    FAILURE,
    MISS,
    N_ACTIONS,
    SUCCESS,
    Experience,
    TpotTable,
    choose,
    epsilon_at,
    load_table,
    reward,
    save_table,
    update,
)


def test_early_updates_are_sample_means_then_the_step_stays_at_alpha_min() -> None:
    table = TpotTable.empty(2)
    for r in (1.0, 0.0, 0.5):
        update(table, Experience(2, SUCCESS, 3, r))
    assert table.q[1, SUCCESS, 3] == pytest.approx(0.5)  # (1 + 0 + 0.5) / 3
    assert table.n[1, SUCCESS, 3] == 3
    assert np.count_nonzero(table.q) == 1  # no other entry moved
    toy = TpotTable.empty(1)
    steps = round(1.0 / ALPHA_MIN)
    for _ in range(steps):  # 1/n >= alpha_min: the mean of zeros
        update(toy, Experience(1, FAILURE, 0, 0.0))
    update(toy, Experience(1, FAILURE, 0, 1.0))  # now alpha = alpha_min
    assert toy.q[0, FAILURE, 0] == pytest.approx(ALPHA_MIN)


def test_a_two_armed_toy_learns_the_better_destination_and_its_value() -> None:
    """Deterministic rewards 0.2 and 0.8 for destinations 1 and 5 (both SUCCESS, the rest
    FAILURE): epsilon-greedy learns Q = the rewards and then picks destination 5."""
    table = TpotTable.empty(1)
    features = [FAILURE] * N_ACTIONS
    features[1] = features[5] = SUCCESS
    payoff = {1: 0.2, 5: 0.8}
    rng = np.random.default_rng(0)
    for step in range(200):
        a = choose(table, 1, features, rng, epsilon=epsilon_at(step, 200, 0.5, 0.05))
        assert a in payoff  # only SUCCESS actions compete
        update(table, Experience(1, SUCCESS, a, payoff[a]))
    assert table.q[0, SUCCESS, 1] == pytest.approx(0.2)
    assert table.q[0, SUCCESS, 5] == pytest.approx(0.8)
    assert choose(table, 1, features, rng) == 5


def test_choice_without_a_success_considers_every_action_and_is_seeded() -> None:
    table = TpotTable.empty(3)
    table.q[2, MISS, 6] = 0.4
    features = [MISS] * N_ACTIONS
    assert choose(table, 3, features, np.random.default_rng(1)) == 6
    # all-zero values: a tie among every action, broken by the seeded draw
    picks = [choose(table, 1, features, np.random.default_rng(s)) for s in range(40)]
    again = [choose(table, 1, features, np.random.default_rng(s)) for s in range(40)]
    assert picks == again and len(set(picks)) > 1
    with pytest.raises(ValueError, match="epsilon"):
        choose(table, 1, features, np.random.default_rng(0), epsilon=1.5)
    with pytest.raises(ValueError, match="one feature per action"):
        choose(table, 1, [SUCCESS], np.random.default_rng(0))
    with pytest.raises(ValueError, match="uniform number"):
        choose(table, 4, features, np.random.default_rng(0))


def test_the_reward_follows_goals_in_time_and_the_ball_s_mean_advance() -> None:
    field = {"own_goal_x": -52.5, "opponent_goal_x": 52.5, "horizon_s": 30.0}
    assert reward(0.0, [], goal=1, goal_after_s=0.0, **field) == pytest.approx(1.0)
    assert reward(0.0, [], goal=1, goal_after_s=30.0, **field) == pytest.approx(0.5)
    assert reward(0.0, [], goal=-1, goal_after_s=10.0, **field) == pytest.approx(-0.75)
    # half way to the opponents' goal on average: +0.5; a quarter back toward ours: -0.25
    assert reward(0.0, [20.0, 32.5], **field) == pytest.approx(0.5)
    assert reward(10.0, [-5.625, -5.625], **field) == pytest.approx(-0.25)
    assert reward(10.0, [], **field) == 0.0
    with pytest.raises(ValueError, match="ahead"):
        reward(0.0, [1.0], own_goal_x=5.0, opponent_goal_x=-5.0)


def test_epsilon_runs_linearly_from_start_to_end() -> None:
    assert epsilon_at(0, 11, 0.3, 0.05) == pytest.approx(0.3)
    assert epsilon_at(10, 11, 0.3, 0.05) == pytest.approx(0.05)
    assert epsilon_at(5, 11, 0.3, 0.05) == pytest.approx(0.175)
    with pytest.raises(ValueError):
        epsilon_at(11, 11, 0.3, 0.05)


def test_a_table_round_trips_with_its_provenance(tmp_path: Path) -> None:
    table = TpotTable.empty(11, {"seed": 4, "tree_digest": "abc"})
    update(table, Experience(7, SUCCESS, 2, 0.3))
    path = save_table(table, tmp_path / "t.npz")
    back = load_table(path)
    assert np.array_equal(back.q, table.q) and np.array_equal(back.n, table.n)
    assert back.provenance == {"seed": 4, "tree_digest": "abc"}
    assert back.digest() == table.digest()


def test_a_corrupt_or_foreign_table_is_refused(tmp_path: Path) -> None:
    table = TpotTable.empty(2)
    path = save_table(table, tmp_path / "t.npz")
    with np.load(path, allow_pickle=False) as data:
        header = str(data["header"])
        q = data["q"].copy()
    q[0, 0, 0] = 0.5  # a changed value: the digest no longer matches
    tampered = tmp_path / "tampered.npz"
    np.savez(tampered, q=q, n=table.n, header=np.array(header))
    with pytest.raises(ValueError, match="digest"):
        load_table(tampered)
    truncated = tmp_path / "truncated.npz"
    truncated.write_bytes(path.read_bytes()[:100])
    with pytest.raises(ValueError, match="not a TPOT-RL table"):
        load_table(truncated)
    pickled = tmp_path / "pickled.npz"
    np.savez(pickled, q=np.array([{"a": 1}], dtype=object), n=table.n, header=np.array(header))
    with pytest.raises(ValueError, match="not a TPOT-RL table"):
        load_table(pickled)
    foreign = tmp_path / "foreign.npz"
    with zipfile.ZipFile(foreign, "w") as z:
        z.writestr("other.npy", b"")
    with pytest.raises(ValueError, match="not a TPOT-RL table"):
        load_table(foreign)
    wrong = tmp_path / "wrong.npz"
    np.savez(wrong, q=np.zeros((2, 3, 7)), n=np.zeros((2, 3, 7), dtype=np.int64),
             header=np.array(header))  # fmt: skip
    with pytest.raises(ValueError, match=r"features or actions|Q table"):
        load_table(wrong)
    with pytest.raises(ValueError, match="finite"):
        TpotTable(np.full((1, 3, 8), np.nan), np.zeros((1, 3, 8), dtype=np.int64))


def test_a_table_may_hold_another_number_of_actions_and_its_file_says_so(tmp_path: Path) -> None:
    table = TpotTable.empty(1, {"seed": 3}, actions=3)
    assert table.actions == 3 and table.q.shape == (1, 3, 3)
    assert choose(table, 1, [MISS, SUCCESS, MISS], np.random.default_rng(0)) == 1
    with pytest.raises(ValueError, match="one feature per action"):
        choose(table, 1, [SUCCESS] * N_ACTIONS, np.random.default_rng(0))
    update(table, Experience(1, SUCCESS, 2, 0.5))
    with pytest.raises(ValueError, match=r"outside 0\.\.2"):
        update(table, Experience(1, SUCCESS, 3, 0.5))
    path = save_table(table, tmp_path / "t.npz")
    assert load_table(path).actions == 3
    with pytest.raises(ValueError, match="actions must be >= 1"):
        TpotTable.empty(1, actions=0)


def test_the_loss_penalty_falls_linearly_to_nothing_at_the_horizon() -> None:
    from learning.tpot import HORIZON_S, loss_penalty

    assert loss_penalty(0.5, 0.0) == pytest.approx(0.5)
    assert loss_penalty(0.5, HORIZON_S / 2) == pytest.approx(0.25)
    assert loss_penalty(0.5, HORIZON_S) == 0.0 and loss_penalty(0.5, 2 * HORIZON_S) == 0.0
    with pytest.raises(ValueError, match="penalty"):
        loss_penalty(-0.1, 1.0)
