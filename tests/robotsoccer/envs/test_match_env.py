"""The match and half-field offense environments: the API test, seeds, the match they pose."""

from __future__ import annotations

import warnings
from typing import Any

import numpy as np
import pytest
from pettingzoo.test import parallel_api_test

from field_models.protocol import LEFT, PlayerRef
from robotsoccer.envs import (
    HalfFieldOffenseEnv,
    MatchParallelEnv,
    half_field_offense_env,
    match_parallel_env,
)
from robotsoccer.envs.hfo import GOAL, OUT_OF_TIME, OUTCOMES
from robotsoccer.envs.hfo_eval import RandomHolder, goal_rate, handwritten
from robotsoccer.envs.macros import PASS_BASE, Macro, macro_names
from robotsoccer.runs.runner import TrialSpec, run_trial

FIELDS = ["soccer_server", "robot_physics"]
SHORT_HALF_S = {"soccer_server": 20.0, "robot_physics": 3.0}
"""Halves short enough for a test, long enough for many decisions [s]."""


def short_match(field_model: str, **options: Any) -> MatchParallelEnv:
    return match_parallel_env(field_model, players=2, half_time_s=SHORT_HALF_S[field_model],
                              **options)  # fmt: skip


def random_actions(env: Any, observations: dict[str, Any], rng: np.random.Generator) -> dict:
    """A seeded action for every live agent (an open macro where there is a mask)."""
    actions = {}
    for agent in env.agents:
        view = observations[agent]
        if isinstance(view, dict):
            actions[agent] = int(rng.choice(np.flatnonzero(view["action_mask"])))
        else:
            actions[agent] = env.action_space(agent).sample()
    return actions


def episode(env: Any, seed: int, action_seed: int = 0) -> list[Any]:
    """Everything an episode shows, with seeded random actions."""
    rng = np.random.default_rng(action_seed)
    env.action_space(env.possible_agents[0]).seed(action_seed)
    observations, infos = env.reset(seed=seed)
    out: list[Any] = [_plain(observations), infos]
    while env.agents:
        step = env.step(random_actions(env, observations, rng))
        observations = step[0]
        out.append([_plain(step[0]), *step[1:]])
    return out


def _plain(observations: dict[str, Any]) -> dict[str, Any]:
    return {
        a: {k: v.tolist() for k, v in o.items()} if isinstance(o, dict) else o.tolist()
        for a, o in observations.items()
    }


@pytest.mark.parametrize("field_model", FIELDS)
@pytest.mark.parametrize("action", ["commands", "macro"])
def test_the_match_passes_pettingzoos_parallel_api_test(
    field_model: str, action: str, capsys: pytest.CaptureFixture[str]
) -> None:
    env = short_match(field_model, action=action)
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # the test's complaints are warnings: none allowed
        parallel_api_test(env, num_cycles=100)
    assert "Passed Parallel API test" in capsys.readouterr().out
    assert env.possible_agents == ["left_1", "left_2", "right_1", "right_2"]


@pytest.mark.parametrize("field_model", FIELDS)
@pytest.mark.parametrize("action", ["primitives", "macro"])
def test_half_field_offense_passes_pettingzoos_parallel_api_test(
    field_model: str, action: str, capsys: pytest.CaptureFixture[str]
) -> None:
    env = half_field_offense_env(field_model, action=action, controlled="all")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        parallel_api_test(env, num_cycles=300)
    assert "Passed Parallel API test" in capsys.readouterr().out
    assert env.possible_agents == ["left_1", "left_2", "right_1", "right_2"]


@pytest.mark.parametrize("field_model", FIELDS)
def test_the_same_seed_and_actions_give_the_same_episode(field_model: str) -> None:
    hfo = half_field_offense_env(field_model, action="macro")
    first, again = episode(hfo, 3), episode(hfo, 3)
    assert first == again
    assert episode(hfo, 4) != first
    match = short_match(field_model, action="commands", controlled=["left_2"])
    assert episode(match, 5, action_seed=1) == episode(match, 5, action_seed=1)


@pytest.mark.parametrize("field_model", FIELDS)
def test_auto_for_every_player_is_the_match_drill_itself(field_model: str) -> None:
    """With AUTO everywhere every agent is its team mind: the episode is the drill's trial."""
    half = SHORT_HALF_S[field_model]
    env = match_parallel_env(field_model, players=2, half_time_s=half, action="macro")
    spec = TrialSpec(drill="match", field_model=field_model, seed=11,
                     drill_options=(("left", "baseline"), ("right", "baseline"), ("players", 2),
                                    ("half_time_s", half)))  # fmt: skip
    for index in range(2):
        _, infos = env.reset(seed=11 if index == 0 else None)
        goals = 0.0
        while env.agents:
            _, rewards, terms, truncs, infos = env.step(dict.fromkeys(env.agents, 0))
            goals += rewards["left_1"]
        result = run_trial(spec, index)
        info = infos["left_1"]
        assert (info["label"], info["reason"], info["tick"]) == (
            result.label,
            result.reason,
            result.ticks,
        )
        measures = dict(result.measures)
        assert goals == measures["goals_l"] - measures["goals_r"]  # goal terms, weight 1
        assert all(terms.values()) and not any(truncs.values())


@pytest.mark.parametrize("field_model", FIELDS)
def test_half_field_offense_ends_as_hfo_says(field_model: str) -> None:
    env = half_field_offense_env(field_model, action="macro", controlled="all")
    seen: set[str] = set()
    rng = np.random.default_rng(0)
    for seed in range(12):
        observations, infos = env.reset(seed=seed)
        assert {i["status"] for i in infos.values()} == {"IN_GAME"}
        while env.agents:
            for agent in env.agents:
                view = observations[agent]
                assert env.observation_space(agent).contains(view), agent
            actions = {a: 0 for a in env.agents}
            actions |= {a: random_actions(env, observations, rng)[a] for a in env.agents[:1]}
            observations, rewards, terms, truncs, infos = env.step(actions)
        status = infos["left_1"]["status"]
        seen.add(status)
        assert status in OUTCOMES
        assert all(truncs.values()) == (status == OUT_OF_TIME) != all(terms.values())
        assert rewards["left_1"] == (1.0 if status == GOAL else 0.0)
        assert rewards["right_1"] == -rewards["left_1"]
    assert len(seen) >= 2  # episodes end in more than one way


def test_the_holders_mask_opens_kicks_and_passes_to_teammates_it_sees() -> None:
    env = half_field_offense_env("soccer_server", action="macro", offense=3)
    names = macro_names(3)
    assert names[PASS_BASE:] == ("PASS_1", "PASS_2", "PASS_3")
    held = 0
    for seed in range(6):
        observations, _ = env.reset(seed=seed)
        while env.agents:
            for agent in env.agents:
                mask = observations[agent]["action_mask"]
                assert mask[Macro.AUTO] and mask[Macro.GO_HOME]
                own_pass = PASS_BASE + int(agent.split("_")[1]) - 1
                assert not mask[own_pass]  # never to itself
                if mask[Macro.SHOOT]:
                    held += 1
                    assert mask[Macro.DRIBBLE] and not mask[Macro.INTERCEPT]
                else:
                    assert not mask[PASS_BASE:].any() and not mask[Macro.DRIBBLE]
            observations, *_ = env.step(dict.fromkeys(env.agents, 0))
    assert held > 0


def test_right_agents_see_themselves_attack_plus_x() -> None:
    """The pose entries of a right-team agent are mirrored: at kick-off both face +x."""
    env = match_parallel_env("soccer_server", players=2, half_time_s=10.0)
    observations, _ = env.reset(seed=0)
    for _ in range(3):
        observations, *_ = env.step({a: np.zeros(8, np.float32) for a in env.agents})
    for agent in ("left_2", "right_2"):
        vector = observations[agent]
        assert vector[6] == 1.0  # localised
        assert vector[7] < 0.0 and vector[9] > 0.9  # own half, heading +x


def test_bad_options_and_actions_are_refused_in_one_line() -> None:
    cases: list[tuple[Any, dict[str, Any], str]] = [
        (MatchParallelEnv, {"action": "wheels"}, "unknown action"),
        (MatchParallelEnv, {"controlled": "nobody"}, "controlled must be"),
        (MatchParallelEnv, {"controlled": ["left_12"]}, "unknown agents"),
        (MatchParallelEnv, {"players": 4}, "players must be"),
        (MatchParallelEnv, {"reward_weights": {"shots": 1.0}}, "unknown reward term"),
        (HalfFieldOffenseEnv, {"offense": 0}, "offense must be"),
        (HalfFieldOffenseEnv, {"defense": 0, "goalie": False}, "needs a goalie"),
        (HalfFieldOffenseEnv, {"max_time_s": -1.0}, "max_time_s must be"),
        (HalfFieldOffenseEnv, {"render_mode": "window"}, "render_mode must be"),
    ]
    for cls, options, message in cases:
        with pytest.raises(ValueError, match=message) as error:
            cls("soccer_server", **options)
        assert "\n" not in str(error.value)
    env = half_field_offense_env("soccer_server", action="macro")
    with pytest.raises(RuntimeError, match="before reset"):
        env.step({})
    observations, infos = env.reset(seed=0)
    deciding = [a for a in env.agents if infos[a]["deciding"]]
    with pytest.raises(ValueError, match="got no action"):
        env.step({})
    closed = int(np.flatnonzero(observations[deciding[0]]["action_mask"] == 0)[0])
    for bad, message in ((closed, "not open"), (99, "must be in"), (0.5, "is a macro")):
        with pytest.raises(ValueError, match=message):
            env.step({**dict.fromkeys(env.agents, 0), deciding[0]: bad})
    with pytest.raises(ValueError, match="unknown agents"):
        env.step({**dict.fromkeys(env.agents, 0), "right_1": 0})
    env.step(dict.fromkeys(env.agents, 0))  # refused actions left the episode as it was


def test_goal_rates_are_reproducible_and_policies_only_choose_open_kicks() -> None:
    first = goal_rate(handwritten, "soccer_server", episodes=8, seed=2)
    assert first.episodes == 8 and sum(first.outcomes.values()) == 8
    assert goal_rate(handwritten, "soccer_server", episodes=8, seed=2) == first
    low, high = first.interval
    assert low <= first.rate <= high
    chooser = RandomHolder(0)
    mask = np.zeros(5 + 2, np.int8)
    mask[[Macro.AUTO, Macro.GO_HOME, Macro.SHOOT, Macro.DRIBBLE, PASS_BASE + 1]] = 1
    picks = {chooser(np.zeros(3, np.float32), mask) for _ in range(60)}
    assert picks == {Macro.SHOOT, Macro.DRIBBLE, PASS_BASE + 1}
    with pytest.raises(ValueError, match="goal_rate's own"):
        goal_rate(handwritten, "soccer_server", episodes=1, controlled="all")


@pytest.mark.parametrize("field_model", FIELDS)
def test_a_held_primitive_drives_the_player_and_frames_are_drawn(field_model: str) -> None:
    """FORWARD, held for ten steps, carries the agent's player forward; STOP keeps it."""
    moved = {}
    for action in (0, 1):  # STOP, FORWARD
        env = short_match(field_model, action="primitives", controlled=["left_2"],
                          render_mode="rgb_array")  # fmt: skip
        env.reset(seed=0)
        start = env._arena.truth().players[PlayerRef(LEFT, 2)] if env._arena else None
        for _ in range(10):
            env.step({"left_2": action})
        assert env._arena is not None and start is not None
        end = env._arena.truth().players[PlayerRef(LEFT, 2)]
        moved[action] = (end.x - start.x) / env.facts.unit_m
        frame = env.render()
        assert frame.ndim == 3 and frame.shape[2] == 3
    assert moved[0] == 0.0 and moved[1] > 2.0  # units: it ran, facing +x at kick-off


def test_the_match_and_hfo_environments_take_a_record_or_its_keywords() -> None:
    from robotsoccer.drills.match_options import MatchOptions, TeamKind
    from robotsoccer.envs.hfo import HfoTask

    by_keyword = MatchParallelEnv("soccer_server", players=2, half_time_s=10.0)
    record = MatchOptions(TeamKind.BASELINE, TeamKind.BASELINE, players=2, half_time_s=10.0)
    by_record = MatchParallelEnv("soccer_server", match=record)
    assert by_record.resolved == by_keyword.resolved  # one spec, resolved once
    assert by_keyword.resolved.spec.field.all_landmarks is True
    with pytest.raises(ValueError, match="not both"):
        MatchParallelEnv("soccer_server", match=record, players=2)
    task = HfoTask(offense=3, defense=0)
    hfo = HalfFieldOffenseEnv("soccer_server", task=task, perfect_perception=True)
    assert hfo.players == half_field_offense_env("soccer_server", offense=3, defense=0).players
    assert hfo.field_options.perfect_perception and hfo.counts == (3, 0, True)
    with pytest.raises(ValueError, match="not both"):
        HalfFieldOffenseEnv("soccer_server", task=task, offense=2)
    with pytest.raises(ValueError, match="goalie or at least one defender"):
        HfoTask(defense=0, goalie=False)
