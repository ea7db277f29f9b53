"""Soccer Server percepts: the text route equals the structured fast path; signs and units."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from field_models.protocol import Heard, Percept, PlayerRef, SeenBall, SeenLandmark, SeenPlayer
from field_models.soccer_server.messages import parse_hear, parse_see, render_hear, render_see
from field_models.soccer_server.percepts import (
    heard_from_hear,
    percept_from_see,
    percept_from_state,
)
from field_models.soccer_server.sensing import HearInfo, SeeInfo, SeenObject, observe
from field_models.soccer_server.sensing_params import SENSING_19, SENSING_1996, SensingParams

PLAYERS = (PlayerRef("left", 1), PlayerRef("left", 2), PlayerRef("right", 1))

coord_x = st.floats(-56.0, 56.0, allow_nan=False)
coord_y = st.floats(-37.0, 37.0, allow_nan=False)
speed = st.floats(-2.5, 2.5, allow_nan=False)
angle = st.floats(-math.pi, math.pi, allow_nan=False)


def text_route(
    observer: int,
    state: tuple[list[float], ...],
    params: SensingParams,
    seed: int,
    tick: int,
) -> Percept:
    """observe (full, with landmarks) -> render -> parse -> percept."""
    x, y, vx, vy, h = state
    info = observe(observer, x, y, vx, vy, h, PLAYERS, 40, params, np.random.default_rng(seed))
    text = render_see(info, params.protocol_version)
    parsed = parse_see(text)
    return percept_from_see(parsed, PLAYERS[observer - 1], tick, parsed.time)


@settings(max_examples=250, deadline=None)
@given(
    st.lists(coord_x, min_size=4, max_size=4),
    st.lists(coord_y, min_size=4, max_size=4),
    st.lists(speed, min_size=8, max_size=8),
    st.lists(angle, min_size=4, max_size=4),
    st.integers(1, 3),
    st.integers(0, 2**32 - 1),
    st.sampled_from(["19", "1996", "8", "low"]),
)
def test_text_route_equals_fast_path(
    xs: list[float],
    ys: list[float],
    vs: list[float],
    hs: list[float],
    observer: int,
    seed: int,
    era: str,
) -> None:
    params = {
        "19": SENSING_19,
        "1996": SENSING_1996,
        "8": SENSING_19.replace(
            protocol_version=8, team_far_length_m=40.0, team_too_far_length_m=60.0
        ),
        "low": SENSING_19.replace(view_quality="low"),
    }[era]
    state = (xs, ys, vs[:4], vs[4:], hs)
    slow = text_route(observer, state, params, seed, tick=42)
    full = percept_from_state(
        observer,
        *state,
        PLAYERS,
        40,
        params,
        np.random.default_rng(seed),
        tick=42,
        landmarks="all",
    )
    assert full == slow
    goals = percept_from_state(
        observer, *state, PLAYERS, 40, params, np.random.default_rng(seed), tick=42
    )
    assert goals == only_goals(slow)
    lean = percept_from_state(
        observer,
        *state,
        PLAYERS,
        40,
        params,
        np.random.default_rng(seed),
        tick=42,
        landmarks="none",
    )
    assert lean == dataclasses.replace(slow, landmarks=())


def only_goals(percept: Percept) -> Percept:
    marks = tuple(m for m in percept.landmarks if m.name in ("g l", "g r"))
    return dataclasses.replace(percept, landmarks=marks)


def test_fast_path_sees_something_and_matches_on_a_busy_scene() -> None:
    # Everyone close together in front of observer 1: ball and both others in view.
    state = (
        [5.0, 0.0, 8.0, 25.0],
        [0.5, 0.0, -1.0, 2.0],
        [0.4, 0.1, 0.0, -0.3],
        [0.1, 0.0, 0.2, 0.0],
        [0.0, 0.1, 2.0, -1.0],
    )
    matches = 0
    for seed in range(50):
        slow = text_route(1, state, SENSING_19, seed, tick=9)
        fast = percept_from_state(
            1, *state, PLAYERS, 40, SENSING_19, np.random.default_rng(seed), tick=9
        )
        assert fast == only_goals(slow)
        assert fast.landmark("g r") is not None and len(slow.landmarks) > 5
        assert fast.ball is not None and len(fast.players) == 2
        matches += fast.players[1].number is not None  # 25 m: the number fades
    assert 0 < matches < 50


def test_angles_become_ccw_radians_and_rates_per_second() -> None:
    info = SeeInfo(
        40,
        (
            SeenObject("b", 11.0, -27, 0.666, -2.3),
            SeenObject("p", 21.0, 19, None, None, "usa", 2),
            SeenObject("p", 55.0, 0),
            SeenObject("f c", 11.1, -27, 0.0, 0.0),
        ),
    )
    me = PlayerRef("usa", 1)
    percept = percept_from_see(info, me, tick=41, observed_tick=40)
    assert percept.ball == SeenBall(11.0, math.radians(27.0), 0.666 / 0.1, math.radians(2.3) / 0.1)
    assert percept.players == (
        SeenPlayer(21.0, math.radians(-19.0), "usa", 2),
        SeenPlayer(55.0, 0.0, None, None),
    )
    assert (percept.tick, percept.observed_tick, percept.player) == (41, 40, me)
    assert percept.landmarks == (SeenLandmark("f c", 11.1, math.radians(27.0)),)


def test_ball_to_the_left_is_at_a_positive_angle() -> None:
    fast = percept_from_state(
        1,
        [10.0, 0.0],
        [3.0, 0.0],
        [0.0, 0.0],
        [0.0, 0.0],
        [0.0, 0.0],
        PLAYERS[:1],
        0,
        SENSING_19,
        np.random.default_rng(0),
        tick=0,
    )
    assert fast.ball is not None
    assert fast.ball.angle_rad == pytest.approx(math.radians(17.0))  # atan2(3, 10) = 16.7 deg
    assert fast.ball.distance_m == 10.0  # 10.44 m: ln -> 2.3 -> 9.97 -> 10.0


def test_felt_ball_behind_and_low_quality() -> None:
    behind = percept_from_see(SeeInfo(1, (SeenObject("B", 1.5, 180),)), PLAYERS[0], 1, 1)
    assert behind.ball == SeenBall(1.5, -math.pi)
    low = percept_from_see(SeeInfo(1, (SeenObject("b", None, 10),)), PLAYERS[0], 1, 1)
    assert low.ball is None


def test_figure_4_percepts() -> None:
    me = PlayerRef("usa", 1)
    first = parse_see(
        "(see 124 ((goal r) 20.1 34) ((flag r t) 47.5 -4) ((flag p r t) 30.3 -24) "
        "((flag p r c) 10.1 -20) ((ball) 11 0) ((player usa 2) 21 19) ((player usa 3) 21 -11) "
        "((player brazil 1) 17 35) ((line r) 40 -26))"
    )
    percept = percept_from_see(first, me, 124, 124)
    assert percept.ball == SeenBall(11.0, 0.0)
    assert [(p.team, p.number) for p in percept.players] == [
        ("usa", 2),
        ("usa", 3),
        ("brazil", 1),
    ]
    assert percept.players[2].angle_rad == pytest.approx(-math.radians(35.0))
    assert [m.name for m in percept.landmarks] == ["g r", "f r t", "f p r t", "f p r c"]
    assert percept.landmark("g r") == SeenLandmark("g r", 20.1, -math.radians(34.0))
    later = parse_see(
        "(see 149 ((goal r) 13.6 9) ((ball) 13.5 5 0) ((player usa 2) 12.8 -14) "
        "((player brazil 1) 11 18) ((line r) 14 -73))"
    )
    ball = percept_from_see(later, me, 149, 149).ball
    assert ball == SeenBall(13.5, -math.radians(5.0), 0.0, None)


def test_heard_entries() -> None:
    me = PlayerRef("usa", 1)
    assert heard_from_hear(parse_hear("(hear 138 18 shoot the ball)"), me) == Heard(
        "shoot the ball", None, -math.radians(18.0), 138
    )
    assert heard_from_hear(parse_hear("(hear 141 self shooting now)"), me) == Heard(
        "shooting now", me, None, 141
    )
    assert heard_from_hear(parse_hear("(hear 150 referee goal_l_1)"), me) == Heard(
        "goal_l_1", None, None, 150
    )
    modern = HearInfo(7, "player", "pass", -45, "our", 2)
    assert heard_from_hear(parse_hear(render_hear(modern, 19)), me) == Heard(
        "pass", PlayerRef("usa", 2), math.radians(45.0), 7
    )
    assert heard_from_hear(HearInfo(7, "player", None, None, "opp"), me) is None


def test_percept_carries_heard_messages() -> None:
    heard = (Heard("go", None, 0.5, 3),)
    fast = percept_from_state(
        1,
        [5.0, 0.0],
        [0.0, 0.0],
        [0.0, 0.0],
        [0.0, 0.0],
        [0.0, 0.0],
        PLAYERS[:1],
        3,
        SENSING_1996,
        np.random.default_rng(0),
        tick=4,
        heard=heard,
    )
    assert fast.heard == heard
    assert fast.ball == SeenBall(5.0, 0.0)  # 1996: no changes
