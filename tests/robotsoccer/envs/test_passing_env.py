"""The pass drill as a PettingZoo parallel environment: the API test, seeds, the drill it poses."""

from __future__ import annotations

import warnings
from typing import Any

import numpy as np
import pytest
from pettingzoo.test import parallel_api_test

from learning.pass_features import ATTRIBUTE_NAMES
from robotsoccer.envs import PassParallelEnv, pass_parallel_env
from robotsoccer.envs.pass_episode import RECEIVER_SLOTS
from robotsoccer.runs.runner import TrialSpec, run_trial

FIELDS = ["soccer_server", "robot_physics"]
HEAD = 4  # the pass drill's data: receiver, confidence, candidates, reports, then attributes


def zero_turns(env: PassParallelEnv) -> dict[str, Any]:
    """TA = 0 for every live agent but the passer (the drill's ``straight`` interceptors)."""
    return {a: np.zeros(1, dtype=np.float32) for a in env.agents if a != "passer"}


def play(env: PassParallelEnv, slot: int | None, seed: int | None = None) -> list[Any]:
    """One episode: a pass to `slot` (None: the first in view), every interceptor with TA = 0."""
    obs, infos = env.reset(seed=seed)
    history: list[Any] = [obs, infos]
    first = int(np.argmax(obs["passer"]["action_mask"]))
    actions: dict[str, Any] = {"passer": first if slot is None else slot}
    while env.agents:
        step = env.step(actions)
        history.append(step)
        actions = zero_turns(env)
    return history


def final_info(history: list[Any]) -> dict[str, Any]:
    return history[-1][4]["passer"]


@pytest.mark.parametrize("field_model", FIELDS)
def test_pettingzoos_parallel_api_test_passes(
    field_model: str, capsys: pytest.CaptureFixture[str]
) -> None:
    env = pass_parallel_env(field_model)
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # the test's complaints are warnings: none allowed
        parallel_api_test(env, num_cycles=50)
    assert "Passed Parallel API test" in capsys.readouterr().out
    still = pass_parallel_env(field_model, defenders="still")
    assert still.possible_agents == ["passer", "receiver"]
    parallel_api_test(still, num_cycles=50)


@pytest.mark.parametrize("field_model", FIELDS)
def test_observations_lie_in_their_spaces_and_rewards_follow_the_label(field_model: str) -> None:
    env = pass_parallel_env(field_model)
    for episode in range(6):
        obs, infos = env.reset(seed=episode)
        assert [a for a in env.agents if infos[a]["deciding"]] == ["passer"]
        assert obs["passer"]["action_mask"].any()
        for agent in env.agents:
            assert env.observation_space(agent).contains(obs[agent]), agent
        actions: dict[str, Any] = {"passer": int(np.argmax(obs["passer"]["action_mask"]))}
        while env.agents:
            obs, rewards, terms, truncs, infos = env.step(actions)
            for agent, info in infos.items():
                assert env.observation_space(agent).contains(obs[agent]), agent
                if info["deciding"]:
                    assert agent != "passer" and obs[agent][0] > 0.0  # BD at its trigger
            actions = zero_turns(env)
        label = infos["passer"]["label"]
        assert all(terms.values()) and not any(truncs.values())
        assert rewards["passer"] == rewards["receiver"] == (1.0 if label == "SUCCESS" else 0.0)
        assert rewards["defender_1"] == (1.0 if label == "FAILURE" else 0.0)
        assert infos["receiver"]["player"] in {str(ref) for ref in RECEIVER_SLOTS}


@pytest.mark.parametrize("field_model", FIELDS)
def test_the_drills_closest_chooser_and_straight_interceptors_are_reproduced(
    field_model: str,
) -> None:
    env = pass_parallel_env(field_model)
    spec = TrialSpec(drill="pass", field_model=field_model, seed=5).with_options(chooser="closest")
    obs, infos = env.reset(seed=5)
    compared = 0
    for _ in range(6):
        view = obs["passer"]
        distance = np.where(view["action_mask"] == 1, view["observation"][:, 0], np.inf)
        slot = int(np.argmin(distance))  # "passer receiver distance", the closest chooser's rule
        actions: dict[str, Any] = {"passer": slot}
        while env.agents:
            *_, end = env.step(actions)
            actions = zero_turns(env)
        trial = run_trial(spec, infos["passer"]["trial"])
        obs, infos = env.reset()
        if np.count_nonzero(distance == distance[slot]) > 1:
            continue  # a tie (quantised distances): the drill breaks it in its own order
        compared += 1
        assert (end["passer"]["label"], end["passer"]["ticks"]) == (trial.label, trial.ticks)
        assert int(trial.data[0]) == RECEIVER_SLOTS[slot].number
        # The passer's observation holds the attributes the drill recorded for that receiver.
        recorded = np.array(trial.data[HEAD:])
        assert len(recorded) == len(ATTRIBUTE_NAMES)
        np.testing.assert_array_equal(view["known"][slot], ~np.isnan(recorded))
        np.testing.assert_allclose(
            view["observation"][slot], np.nan_to_num(recorded), rtol=1e-6, atol=1e-4
        )
    assert compared >= 4


def test_seeds_follow_gymnasium() -> None:
    def episodes(env: PassParallelEnv, seed: int) -> list[Any]:
        return [play(env, None, seed)] + [play(env, None) for _ in range(3)]

    def same(a: Any, b: Any) -> bool:
        if isinstance(a, dict):
            return a.keys() == b.keys() and all(same(a[k], b[k]) for k in a)
        if isinstance(a, list | tuple):
            return len(a) == len(b) and all(same(x, y) for x, y in zip(a, b, strict=True))
        if isinstance(a, np.ndarray):
            return bool(np.array_equal(a, b))
        return bool(a == b)

    env, twin = pass_parallel_env("soccer_server"), pass_parallel_env("soccer_server")
    a, b, again = episodes(env, 3), episodes(twin, 3), episodes(env, 3)
    assert same(a, b) and same(a, again)
    assert not same(a[0][0], a[1][0])  # the stream moves on
    assert not same(a[0][0], play(env, None, 4)[0])


def test_the_agents_actions_change_outcomes() -> None:
    env = pass_parallel_env("soccer_server")
    changed = 0
    for seed in range(30):  # the same trial played with each receiver the passer can choose
        mask = env.reset(seed=seed)[0]["passer"]["action_mask"]
        labels = {final_info(play(env, slot, seed))["label"] for slot in np.flatnonzero(mask)}
        changed += len(labels) > 1
    assert changed >= 5
    changed = 0
    for seed in range(12):  # the same pass, the receiver turning by three TAs
        labels = set()
        for ta in (-1.2, 0.0, 1.2):
            obs, infos = env.reset(seed=seed)
            actions: dict[str, Any] = {"passer": int(np.argmax(obs["passer"]["action_mask"]))}
            while env.agents:
                *_, infos = env.step(actions)
                actions = zero_turns(env) | {"receiver": np.array([ta], dtype=np.float32)}
            labels.add(infos["passer"]["label"])
        changed += len(labels) > 1
    assert changed >= 3


def test_invalid_actions_raise_and_leave_the_decision_open() -> None:
    env = pass_parallel_env("soccer_server")
    with pytest.raises(RuntimeError, match="reset"):
        env.step({"passer": 0})
    seed = next(s for s in range(200) if not env.reset(seed=s)[0]["passer"]["action_mask"].all())
    mask = env.reset(seed=seed)[0]["passer"]["action_mask"]
    hidden, seen = int(np.flatnonzero(mask == 0)[0]), int(np.flatnonzero(mask)[0])
    with pytest.raises(ValueError, match="not in the passer's view"):
        env.step({"passer": hidden})
    for bad in (3, -1, 1.5, True, "left2", np.array([0])):
        with pytest.raises(ValueError, match="receiver slot"):
            env.step({"passer": bad})
    with pytest.raises(ValueError, match="no action"):
        env.step({"receiver": np.zeros(1, dtype=np.float32)})
    with pytest.raises(ValueError, match="unknown agents"):
        env.step({"passer": seen, "goalie": 0})
    *_, infos = env.step({"passer": seen})  # the decision was still open
    while not env.agents:  # a trial without an interceptor's decision: play the next
        *_, infos = env.step({"passer": int(np.argmax(env.reset()[0]["passer"]["action_mask"]))})
    deciding = [a for a in env.agents if infos[a]["deciding"]]
    assert deciding and "passer" not in deciding
    for bad in (np.array([np.nan]), np.array([2.0]), np.zeros(2), "left"):
        with pytest.raises(ValueError, match="TA"):
            env.step(dict.fromkeys(deciding, bad))
    while env.agents:
        env.step(zero_turns(env))
    with pytest.raises(RuntimeError, match="ended"):
        env.step({})
    with pytest.raises(ValueError, match="agents' decisions"):
        pass_parallel_env("soccer_server", chooser="closest")
    with pytest.raises(ValueError, match="render_mode"):
        PassParallelEnv(render_mode="video")
    with pytest.raises(ValueError, match="unknown agent"):
        env.action_space("goalie")
