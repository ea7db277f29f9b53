"""The neck and the view modes on the Soccer Server model (spec §2.2, §3.1; issue 28)."""

from __future__ import annotations

import math

import pytest

from field_models.arena import COMMAND_COUNTERS
from field_models.protocol import (
    LEFT,
    RIGHT,
    ChangeView,
    Dash,
    Percept,
    PlayerRef,
    Turn,
    TurnNeck,
    wrap_angle,
)
from field_models.seeding import TrialRngs
from field_models.soccer_server import model as server_model
from field_models.soccer_server.arena import SoccerServerArena
from field_models.soccer_server.params import load_server_preset
from field_models.soccer_server.percepts import percept_from_state
from field_models.soccer_server.sensing import Bodies, observe
from field_models.soccer_server.sensing_params import SENSING_19

A, B = PlayerRef(LEFT, 1), PlayerRef(RIGHT, 1)
DEG = math.pi / 180.0


def arena(preset: str = "soccer_server_1996", trace: bool = False) -> SoccerServerArena:
    loaded = load_server_preset(preset).replace_dynamics(player_rand=0.0, ball_rand=0.0)
    facts = server_model.facts(loaded)
    a = SoccerServerArena(loaded, facts, (A, B), TrialRngs.for_trial(0, 0), trace=trace)
    a.place_player(A, -10.0, 0.0, 0.0)
    a.place_player(B, 10.0, 5.0, math.pi)
    a.place_ball(0.0, 20.0)  # 63° left of A's body: out of its normal view
    return a


def run(a: SoccerServerArena, cycles: int) -> list[Percept]:
    out: list[Percept] = []
    for _ in range(cycles):
        out += [p for p in a.step() if p.player == A]
    return out


def test_the_neck_turns_at_the_step_within_its_range_beside_a_body_command() -> None:
    a = arena()
    a.submit(A, (TurnNeck(60 * DEG), Turn(20 * DEG), Dash(100.0)))
    assert a.model.neck[1] == 0.0  # committed at the step, as the server does
    a.step()
    assert a.model.neck[1] == pytest.approx(60 * DEG)
    assert a.player_state(A).heading == pytest.approx(20 * DEG)  # the turn ran as well
    a.step()
    assert a.player_state(A).speed > 0.0  # and the dash after it
    a.submit(A, (TurnNeck(60 * DEG), TurnNeck(-30 * DEG)))  # the first of a cycle wins
    a.step()
    assert a.model.neck[1] == pytest.approx(90 * DEG)  # maxneckang
    counts = a.command_tally()[A].counts
    assert counts[COMMAND_COUNTERS.index("turn_neck")] == 2
    assert counts[COMMAND_COUNTERS.index("turn")] == 1


def test_the_neck_moment_and_angle_follow_the_presets_limits() -> None:
    loaded = load_server_preset("rcssserver_19").replace_dynamics(
        maxneckang_rad=30 * DEG, maxneckmoment_rad=20 * DEG, minneckmoment_rad=-20 * DEG
    )
    a = SoccerServerArena(loaded, server_model.facts(loaded), (A, B), TrialRngs.for_trial(0, 0))
    a.submit(A, (TurnNeck(-50 * DEG),))  # our -50° is the server's +50°: moment clamped to 20
    a.step()
    assert a.model.neck[1] == pytest.approx(-20 * DEG)
    a.submit(A, (TurnNeck(80 * DEG),))  # the server's -80, clamped to -20: back to 0
    a.step()
    assert a.model.neck[1] == pytest.approx(0.0, abs=1e-12)
    for _ in range(3):
        a.submit(A, (TurnNeck(-80 * DEG),))
        a.step()
    assert a.model.neck[1] == pytest.approx(-30 * DEG)  # server maxneckang 30 (clockwise)


def test_a_see_looks_along_body_plus_neck() -> None:
    x, y, vx, vy = [0.0, 0.0, 10.0], [20.0, 0.0, 5.0], [0.0] * 3, [0.0] * 3
    players = (A, B)
    turned = observe(1, Bodies(x, y, vx, vy, [0.0, 0.7, 3.0]), players, 5, SENSING_19, _rng())
    necked = observe(
        1,
        Bodies(x, y, vx, vy, [0.0, 0.2, 3.0], neck=[0.0, 0.5, 0.0]),
        players,
        5,
        SENSING_19,
        _rng(),
    )
    assert necked == turned  # flags, goals, ball, player and lines: all from the head
    zero = observe(
        1, Bodies(x, y, vx, vy, [0.0, 0.2, 3.0], neck=[0.0] * 3), players, 5, SENSING_19, _rng()
    )
    assert zero == observe(1, Bodies(x, y, vx, vy, [0.0, 0.2, 3.0]), players, 5, SENSING_19, _rng())


def test_a_seen_players_head_direction_is_its_body_plus_neck() -> None:
    x, y, zero = [50.0, 0.0, 10.0], [0.0, 0.0, 0.0], [0.0] * 3
    heading = [0.0, 0.0, math.pi]
    plain = observe(
        1, Bodies(x, y, zero, zero, heading), (A, B), 1, SENSING_19, _rng(), landmarks="none"
    )
    necked = observe(
        1,
        Bodies(x, y, zero, zero, heading, neck=[0.0, 0.0, -0.5]),
        (A, B),
        1,
        SENSING_19,
        _rng(),
        landmarks="none",
    )
    before, after = plain.find("p"), necked.find("p")
    assert before is not None and after is not None
    assert after.body_dir == before.body_dir == before.head_dir
    # Our -0.5 rad (clockwise) is the server's +28.6°: the head at -180 + 28.6.
    assert after.head_dir == round(math.degrees(wrap_angle(before.head_dir * DEG + 0.5)))


def test_percepts_carry_the_neck_and_body_relative_undoes_it() -> None:
    a = arena()
    before = run(a, 5)
    assert all(p.ball is None and p.neck_rad == 0.0 for p in before)  # the ball is out of view
    a.submit(A, (TurnNeck(60 * DEG),))
    after = run(a, 5)
    assert after and all(p.neck_rad == pytest.approx(60 * DEG) for p in after)
    ball = after[-1].ball
    assert ball is not None and ball.angle_rad == pytest.approx(3 * DEG, abs=1.5 * DEG)
    body = after[-1].body_relative()
    assert body.neck_rad == 0.0 and body.ball is not None
    assert body.ball.angle_rad == pytest.approx(math.atan2(20.0, 10.0), abs=1.5 * DEG)


def test_the_text_route_gives_the_fast_paths_percept_with_a_neck() -> None:
    fast, text = arena(), arena(trace=True)
    for a in (fast, text):
        a.submit(A, (TurnNeck(-40 * DEG), Turn(50 * DEG)))
    for _ in range(6):
        got = fast.step(), text.step()
        for p, q in zip(*got, strict=True):
            assert (p.neck_rad, p.ball, p.players) == (q.neck_rad, q.ball, q.players)
            assert {m.name: m for m in q.landmarks if m.name in ("g l", "g r")} == {
                m.name: m for m in p.landmarks
            }


def test_change_view_sets_one_players_cone_and_see_interval() -> None:
    a = arena()  # 1996: a see every 250 ms at normal width
    normal = [p.tick for p in run(a, 20)]
    a.submit(A, (ChangeView("wide", "high"),))
    wide = [p.tick for p in run(a, 20)]
    b_ticks = []
    a.submit(A, (ChangeView("narrow", "high"),))
    for _ in range(20):
        b_ticks += [p.tick for p in a.step() if p.player == B]
    assert len(normal) == 8 and len(wide) == 4  # 250 ms, then 500 ms
    assert len(b_ticks) == 8  # the other player's sees keep their interval
    assert a.command_tally()[A].counts[COMMAND_COUNTERS.index("change_view")] == 2


def test_a_wide_view_sees_what_the_normal_one_does_not() -> None:
    a = arena()
    assert all(p.ball is None for p in run(a, 5))
    a.submit(A, (ChangeView("wide", "high"),))
    seen = run(a, 10)
    assert seen and all(p.ball is not None for p in seen)


@pytest.mark.parametrize("preset", ["soccer_server_1996", "rcssserver_19", "rcssserver_19_async"])
def test_the_sees_keep_their_timing_until_a_view_changes(preset: str) -> None:
    plain, changed = arena(preset), arena(preset)
    for _ in range(7):  # mid-way through the timer's pattern
        plain.step(), changed.step()
    changed.submit(B, (ChangeView("normal", "high"),))  # a change to the same view
    for _ in range(60):
        assert [p.tick for p in plain.step()] == [p.tick for p in changed.step()]


def _rng():  # type: ignore[no-untyped-def]
    return TrialRngs.for_trial(3, 0)["sensing"]


def test_percept_from_state_takes_the_neck() -> None:
    x, y, zero = [5.0, 0.0, 10.0], [5.0, 0.0, 0.0], [0.0] * 3
    p = percept_from_state(
        1,
        Bodies(x, y, zero, zero, [0.0, 0.0, 0.0], neck=[0.0, 0.3, 0.0]),
        (A, B),
        1,
        SENSING_19,
        _rng(),
    )
    assert p.neck_rad == 0.3
    assert p.ball is not None and p.ball.angle_rad == pytest.approx(math.pi / 4 - 0.3, abs=DEG)
