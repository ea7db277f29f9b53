"""Soccer Server percepts: the text route equals the structured fast path; signs and units."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from field_models.protocol import Heard, Percept, PlayerRef, SeenBall, SeenLandmark, SeenPlayer
from field_models.soccer_server.hearing import HearInfo
from field_models.soccer_server.messages import parse_hear, parse_see, render_hear, render_see
from field_models.soccer_server.percepts import (
    heard_from_hear,
    percept_from_see,
    percept_from_state,
)
from field_models.soccer_server.sensing import Bodies, SeeInfo, SeenObject, observe
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
    info = observe(
        observer, Bodies(x, y, vx, vy, h), PLAYERS, 40, params, np.random.default_rng(seed)
    )
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
    st.sampled_from(["19", "1996", "8", "low", "perfect", "perfect_1996", "perfect_low"]),
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
        "perfect": SENSING_19.replace(perfect=True),
        "perfect_1996": SENSING_1996.replace(perfect=True),
        "perfect_low": SENSING_19.replace(perfect=True, view_quality="low"),
    }[era]
    state = (xs, ys, vs[:4], vs[4:], hs)
    slow = text_route(observer, state, params, seed, tick=40)  # the fast path: tick = time
    full = percept_from_state(
        observer, Bodies(*state), PLAYERS, 40, params, np.random.default_rng(seed), landmarks="all"
    )
    assert full == slow
    goals = percept_from_state(
        observer, Bodies(*state), PLAYERS, 40, params, np.random.default_rng(seed)
    )
    assert goals == only_goals(slow)
    lean = percept_from_state(
        observer, Bodies(*state), PLAYERS, 40, params, np.random.default_rng(seed), landmarks="none"
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
        slow = text_route(1, state, SENSING_19, seed, tick=40)
        fast = percept_from_state(
            1, Bodies(*state), PLAYERS, 40, SENSING_19, np.random.default_rng(seed)
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
        Bodies([10.0, 0.0], [3.0, 0.0], [0.0, 0.0], [0.0, 0.0], [0.0, 0.0]),
        PLAYERS[:1],
        0,
        SENSING_19,
        np.random.default_rng(0),
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
        Bodies([5.0, 0.0], [0.0, 0.0], [0.0, 0.0], [0.0, 0.0], [0.0, 0.0]),
        PLAYERS[:1],
        3,
        SENSING_1996,
        np.random.default_rng(0),
        heard=heard,
    )
    assert fast.heard == heard
    assert fast.tick == fast.observed_tick == 3  # reaches the client in the cycle it shows
    assert fast.ball == SeenBall(5.0, 0.0)  # 1996: no changes


# ----------------------------------------------------------------------------- perfect perception

PERFECT = SENSING_19.replace(perfect=True)


def perfect_scene() -> tuple[list[float], ...]:
    """Observer 1 at (-10, 5) facing 20°, moving; the ball, two players and a goal in view."""
    return (
        [3.0, -10.0, 4.0, 7.0],
        [2.0, 5.0, 9.5, 0.0],
        [0.7, 0.2, -0.1, 0.3],
        [-0.4, 0.1, 0.25, 0.0],
        [0.0, math.radians(20.0), 2.0, -1.0],
    )


def test_perfect_see_equals_the_true_geometry() -> None:
    x, y, vx, vy, h = perfect_scene()
    for seed in range(5):  # no draw changes anything: identity and changes are always there
        info = observe(1, Bodies(x, y, vx, vy, h), PLAYERS, 7, PERFECT, np.random.default_rng(seed))
        percept = percept_from_see(info, PLAYERS[0], 7, 7)
        assert percept.ball is not None and len(percept.players) == 2
        rows = {"b": 0, (PLAYERS[1].team, PLAYERS[1].number): 2, (PLAYERS[2].team, 1): 3}
        seen = [("b", percept.ball.distance_m, percept.ball.angle_rad)]
        seen += [((p.team, p.number), p.distance_m, p.angle_rad) for p in percept.players]
        for who, dist, ang in seen:
            i = rows[who]
            dx, dy = x[i] - x[1], y[i] - y[1]
            assert dist == pytest.approx(math.hypot(dx, dy), rel=1e-15)
            assert ang == pytest.approx(math.atan2(dy, dx) - h[1], abs=1e-14)
        # Distance change: relative velocity along the line of sight [m/cycle] -> m/s.
        dx, dy = x[0] - x[1], y[0] - y[1]
        d = math.hypot(dx, dy)
        wx, wy = vx[0] - vx[1], vy[0] - vy[1]
        assert percept.ball.distance_change_mps == pytest.approx((wx * dx + wy * dy) / d / 0.1)
        assert percept.ball.angle_change_radps == pytest.approx((dx * wy - dy * wx) / d**2 / 0.1)
        goal = percept.landmark("g r")  # at (52.5, 0)
        assert goal is not None
        assert goal.distance_m == pytest.approx(math.hypot(62.5, 5.0), rel=1e-15)
        assert goal.angle_rad == pytest.approx(math.atan2(-5.0, 62.5) - h[1], abs=1e-14)


def test_perfect_see_keeps_the_cone_and_the_far_details() -> None:
    x, y, vx, vy, h = perfect_scene()
    far = [*x[:3], 70.0]  # the opponent 80 m away: no number (nor changes) in a normal see
    info = observe(1, Bodies(far, y, vx, vy, h), PLAYERS, 7, PERFECT, np.random.default_rng(0))
    them = [o for o in info.objects if o.name == "p" and o.team == "right"]
    assert len(them) == 1 and them[0].unum == 1 and them[0].dist_change is not None
    normal = observe(1, Bodies(far, y, vx, vy, h), PLAYERS, 7, SENSING_19, np.random.default_rng(0))
    last = [o for o in normal.objects if o.name == "p"][-1]
    assert (last.team, last.unum, last.dist_change) == ("right", None, None)
    behind = [*x]
    behind[0] = -20.0  # the ball 10 m behind the observer: out of the cone in both
    info = observe(1, Bodies(behind, y, vx, vy, h), PLAYERS, 7, PERFECT, np.random.default_rng(0))
    assert info.find("b") is None and info.find("B") is None


def test_perfect_see_text_round_trips_exactly() -> None:
    x, y, vx, vy, h = perfect_scene()
    info = observe(1, Bodies(x, y, vx, vy, h), PLAYERS, 7, PERFECT, np.random.default_rng(3))
    text = render_see(info, PERFECT.protocol_version)
    assert parse_see(text) == info
    ball = info.find("b")
    assert ball is not None and isinstance(ball.direction, float)
    assert repr(ball.distance) in text  # exact, not %g's 6 digits
