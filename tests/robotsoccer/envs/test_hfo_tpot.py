"""TPOT-RL as the half-field offense ball holder: features, the macro chosen, seeded training."""

from __future__ import annotations

import math

import numpy as np
import pytest

from learning.tpot import FAILURE, MISS, SUCCESS, TpotTable
from robotsoccer.envs.hfo import HalfFieldOffenseEnv
from robotsoccer.envs.hfo_eval import goal_rate
from robotsoccer.envs.hfo_tpot import (
    DRIBBLE_A,
    HOLDER_ACTIONS,
    PASS_A,
    SHOOT_A,
    Layout,
    TpotHolder,
    features,
    train_holder,
)
from robotsoccer.envs.macros import PASS_BASE, Macro


@pytest.fixture(scope="module")
def layout() -> Layout:
    return Layout.of(HalfFieldOffenseEnv("soccer_server", action="macro"))


def observation(
    layout: Layout,
    goal_m: float | None,
    mate: tuple[float, float] | None = None,
    foes: tuple[tuple[float, float], ...] = (),
) -> np.ndarray:
    """An attacker's vector: the goal at `goal_m` dead ahead, a teammate, opponents (m, rad)."""
    obs = np.zeros(len(layout.index), dtype=np.float32)
    get, length = layout.index, layout.length_m
    if goal_m is not None:
        obs[get["target_known"]], obs[get["target_distance"]] = 1.0, goal_m / length
        obs[get["target_cos"]] = 1.0
    slots = [("teammate0", mate)] if mate else []
    slots += [(f"opponent{i}", foe) for i, foe in enumerate(foes)]
    for slot, (d, a) in slots:
        obs[get[f"{slot}_seen"]], obs[get[f"{slot}_distance"]] = 1.0, d / length
        obs[get[f"{slot}_cos"]], obs[get[f"{slot}_sin"]] = math.cos(a), math.sin(a)
    return obs


def mask(pass_open: bool) -> np.ndarray:
    m = np.zeros(PASS_BASE + 2, dtype=np.int8)
    m[[Macro.AUTO, Macro.GO_HOME, Macro.SHOOT, Macro.DRIBBLE]] = 1
    if pass_open:
        m[PASS_BASE + 1] = 1  # PASS_2
    return m


def test_features_judge_range_path_and_lane(layout: Layout) -> None:
    near = 0.5 * layout.shoot_range_m
    assert features(layout, observation(layout, near), mask(False)) == (SUCCESS, SUCCESS, MISS)
    blocker = ((0.5 * layout.blocked_m, 0.1),)
    assert features(layout, observation(layout, near, foes=blocker), mask(False))[:2] == (
        FAILURE,
        FAILURE,
    )
    far = observation(layout, 2.0 * layout.shoot_range_m, mate=(15.0, 1.0))
    assert features(layout, far, mask(True)) == (MISS, SUCCESS, SUCCESS)
    lane = observation(layout, None, mate=(15.0, 1.0), foes=((7.0, 1.1),))
    assert features(layout, lane, mask(True)) == (MISS, SUCCESS, FAILURE)


def test_the_holder_plays_the_macro_of_its_best_action(layout: Layout) -> None:
    table = TpotTable.empty(1, actions=len(HOLDER_ACTIONS))
    table.q[0, SUCCESS, PASS_A] = 0.4
    holder = TpotHolder(table, layout)
    obs = observation(layout, 2.0 * layout.shoot_range_m, mate=(15.0, 1.0))
    assert holder(obs, mask(True)) == PASS_BASE + 1 and holder.last == (SUCCESS, PASS_A)
    table.q[0, SUCCESS, DRIBBLE_A] = 0.6
    assert holder(obs, mask(True)) == Macro.DRIBBLE
    table.q[0, MISS, SHOOT_A] = 0.9  # a MISS shot does not compete while SUCCESS actions exist
    assert holder(obs, mask(True)) == Macro.DRIBBLE
    with pytest.raises(ValueError, match="1 position x 3 actions"):
        TpotHolder(TpotTable.empty(11), layout)


def test_training_is_seeded_and_the_learned_holder_runs_through_the_harness() -> None:
    one = train_holder("soccer_server", 12, seed=5)
    two = train_holder("soccer_server", 12, seed=5)
    assert one.rewards > 0, "the holder must decide in 12 episodes to compare"
    assert np.array_equal(one.table.q, two.table.q) and np.array_equal(one.table.n, two.table.n)
    assert one.table.n.sum() == one.rewards
    env = HalfFieldOffenseEnv("soccer_server", action="macro")
    first = goal_rate(TpotHolder(one.table, Layout.of(env)), "soccer_server", 6, 0)
    again = goal_rate(TpotHolder(one.table, Layout.of(env)), "soccer_server", 6, 0)
    assert first.outcomes == again.outcomes and first.holder_choices > 0
