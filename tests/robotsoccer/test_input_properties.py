"""Property tests of the inputs above the field models (issue 30), sized for CI.

Environment actions and seeds, command-line option values and game-log lines either work or
raise the documented error (ValueError; argparse's ArgumentTypeError); nothing else.
"""

from __future__ import annotations

import argparse
import math
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from hypothesis.extra import numpy as hnp

from robotsoccer import cli
from robotsoccer.envs import InterceptVectorEnv, pass_parallel_env
from robotsoccer.envs.checks import checked_seed, checked_turns
from robotsoccer.envs.intercept import InterceptEnv
from robotsoccer.options import MAX_COUNT, MAX_SEED, MAX_SIMULATED_S
from robotsoccer.replay.rcg_read import read_rcg

QUICK = settings(
    max_examples=40, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture]
)
N_ENVS = 3

any_float = st.floats(allow_nan=True, allow_infinity=True, width=64)
seeds = st.one_of(
    st.none(),
    st.integers(-(2**70), 2**70),
    st.integers(0, 2**64 - 1),
    st.floats(),
    st.booleans(),
    st.text(max_size=5),
)


@settings(max_examples=300, deadline=None)
@given(seeds)
def test_a_seed_is_gymnasiums_or_a_value_error(seed: object) -> None:
    try:
        checked = checked_seed(seed)
    except ValueError:
        assert not (type(seed) is int and 0 <= seed <= MAX_SEED)
        return
    assert checked == seed and (seed is None or 0 <= checked <= MAX_SEED)  # type: ignore[operator]


@settings(max_examples=300, deadline=None)
@given(
    hnp.arrays(np.float64, hnp.array_shapes(min_dims=0, max_dims=3, max_side=5), elements=any_float)
)
def test_actions_are_n_finite_turns_or_a_value_error(actions: np.ndarray) -> None:
    try:
        turns = checked_turns(actions, N_ENVS)
    except ValueError:
        right = actions.shape in ((N_ENVS, 1), (N_ENVS,))
        assert not right or not np.isfinite(actions).all()
        return
    assert turns.shape == (N_ENVS,) and np.isfinite(turns).all()


@pytest.fixture(scope="module")
def vector_env() -> InterceptVectorEnv:
    env = InterceptVectorEnv(N_ENVS)
    env.reset(seed=0)
    return env


@QUICK
@given(
    hnp.arrays(
        np.float64,
        st.sampled_from([(N_ENVS, 1), (N_ENVS,), (2 * N_ENVS,), (0,), (N_ENVS, 2), ()]),
        elements=st.one_of(any_float, st.floats(-2.0, 2.0)),
    )
)
def test_the_vector_env_plays_finite_actions_of_its_shape_and_refuses_the_rest(
    vector_env: InterceptVectorEnv, actions: np.ndarray
) -> None:
    try:
        obs, rewards, *_ = vector_env.step(actions)
    except ValueError:
        assert actions.shape not in ((N_ENVS, 1), (N_ENVS,)) or not np.isfinite(actions).all()
        return
    assert vector_env.observation_space.contains(obs) and set(rewards) <= {0.0, 1.0}


@settings(max_examples=15, deadline=None)
@given(seeds)
def test_every_env_takes_gymnasiums_seeds_and_refuses_the_rest(seed: object) -> None:
    valid = seed is None or (type(seed) is int and 0 <= seed <= MAX_SEED)
    for reset in (
        InterceptEnv("soccer_server").reset,
        pass_parallel_env("soccer_server").reset,
        InterceptVectorEnv(1).reset,
    ):
        try:
            reset(seed=seed)  # type: ignore[operator]
        except ValueError:
            assert not valid
        else:
            assert valid


# ----------------------------------------------------------------------------- options

OPTIONS = [
    (cli._noise, 0.0, 1.0),
    (cli._positive_float, 0.0, MAX_SIMULATED_S),
    (cli._positive_int, 1, MAX_COUNT),
    (cli._index, 0, MAX_SEED),
]
option_text = st.one_of(
    st.text(max_size=12),
    st.floats().map(repr),
    st.integers(-(10**25), 10**25).map(str),
    st.sampled_from(["1e308", "1e-300", "inf", "nan", "10" * 30, "0x10", "1_000"]),
)


@settings(max_examples=300, deadline=None)
@given(st.sampled_from(range(len(OPTIONS))), option_text)
def test_a_number_option_is_in_its_bounds_or_refused(which: int, text: str) -> None:
    parse, low, high = OPTIONS[which]
    try:
        value = parse(text)
    except argparse.ArgumentTypeError:
        return
    assert math.isfinite(value) and low <= value <= high


# ----------------------------------------------------------------------------- game logs

HEAD = "ULG5\n(server_param (simulator_step {step}))\n(playmode 1 play_on)\n"
SHOW = "(show {t} ((b) {a} {b} 0 0) ((l 1) 0 0x1 {c} {d} 0 0 {e} 0 (v h 90) (s 1 1 1) (c 0)))\n"
token = st.one_of(
    st.floats(allow_nan=False, allow_infinity=False).map(repr),
    st.sampled_from(["1e999", "-1e999", "inf", "nan", "1" + "0" * 400, "0", "-0", "1e-400"]),
    st.integers(-(10**20), 10**20).map(str),
)


@pytest.fixture(scope="module")
def folder(tmp_path_factory: pytest.TempPathFactory) -> Path:
    return tmp_path_factory.mktemp("logs")


@QUICK
@given(st.lists(token, min_size=7, max_size=7))
def test_a_game_log_reads_to_finite_frames_or_is_refused(folder: Path, t: list[str]) -> None:
    path = folder / "game.rcg"
    path.write_text(HEAD.format(step=t[0]) + SHOW.format(t=t[1][:25].lstrip("-") or "1",
                    a=t[2], b=t[3], c=t[4], d=t[5], e=t[6]))  # fmt: skip
    try:
        game = read_rcg(path)
    except ValueError as err:
        assert "\n" not in str(err) and "game.rcg:" in str(err)
        return
    for frame in game.frames:
        truth = frame.truth
        states = [truth.ball, *truth.players.values()]
        assert math.isfinite(truth.time_s)
        assert all(math.isfinite(v) for s in states for v in (s.x, s.y, s.heading, s.vx, s.vy))
