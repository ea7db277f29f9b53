"""Team minds that look with the neck and view modes (issue 28): `look=neck`."""

from __future__ import annotations

import math

import pytest

from field_models.protocol import (
    LEFT,
    ChangeView,
    Percept,
    PlayerRef,
    SeenBall,
    SeenLandmark,
    SeenPlayer,
    Turn,
    TurnNeck,
)
from robotsoccer.drills.match import MatchDrill
from robotsoccer.runs.runner import DrillOption, TrialLoop, TrialSpec, build_trial, run_trial
from robotsoccer.skills.reversals import TurnReversals
from robotsoccer.skills.team_look import NECK_MAX_RAD, NeckLook, look_target

ME = PlayerRef(LEFT, 4)
DEG = math.pi / 180.0


def test_body_relative_turns_every_direction_by_the_neck() -> None:
    p = Percept(
        ME, 5, 5, SeenBall(10.0, 0.2, 1.0, 0.1), (SeenPlayer(5.0, -0.1, LEFT, 2),), (),
        (SeenLandmark("g r", 40.0, 3.0),), 0.5,
    )  # fmt: skip
    body = p.body_relative()
    assert body.neck_rad == 0.0 and body.tick == 5
    assert body.ball == SeenBall(10.0, 0.7, 1.0, 0.1)
    assert body.players[0].angle_rad == pytest.approx(0.4)
    assert body.landmarks[0].angle_rad == pytest.approx(3.5 - 2 * math.pi)  # wrapped
    plain = Percept(ME, 5, 5, None)
    assert plain.body_relative() is plain


def test_the_neck_follows_the_ball_through_the_body_turn_and_scans_without_it() -> None:
    head = NeckLook()
    actions = head.look((Turn(30 * DEG),), 50 * DEG)
    assert actions[0] == Turn(30 * DEG) and len(actions) == 2
    neck = actions[1]
    assert isinstance(neck, TurnNeck) and neck.angle_rad == pytest.approx(20 * DEG)
    head.neck_rad = 20 * DEG
    assert head.look((), 20.5 * DEG) == ()  # under a degree: nothing sent
    assert head.look((), 170 * DEG)[-1] == TurnNeck(NECK_MAX_RAD - 20 * DEG)  # clipped
    scan = head.look((), None)
    assert scan[0] == ChangeView("wide", "high") and isinstance(scan[1], TurnNeck)
    head.neck_rad = -NECK_MAX_RAD
    assert head.look((), None) == (TurnNeck(2 * NECK_MAX_RAD),)  # the other end; view kept
    assert head.look((), 0.0) == (ChangeView("normal", "high"), TurnNeck(NECK_MAX_RAD))


def test_a_remembered_ball_is_looked_at_a_while_then_looked_for() -> None:
    from robotsoccer.skills.localise import Pose

    pose = Pose(0.0, 0.0, math.pi / 2)
    recent = Percept(ME, 12, 12, None)
    assert look_target(recent, pose, (10.0, 10.0), 10) == pytest.approx(-math.pi / 4)
    assert look_target(Percept(ME, 30, 30, None), pose, (10.0, 10.0), 10) is None
    assert look_target(recent, None, (10.0, 10.0), 10) is None


def test_an_unknown_look_is_refused_naming_the_allowed_ones() -> None:
    with pytest.raises(ValueError, match="look: expected one of body, neck; got 'eyes'"):
        MatchDrill(left="baseline", right="baseline", look="eyes")


def _match(preset: str, *extra: tuple[str, DrillOption]) -> TrialSpec:
    options: tuple[tuple[str, DrillOption], ...] = (
        ("left", "baseline"),
        ("right", "baseline"),
        ("half_time_s", 5.0),
        *extra,
    )
    return TrialSpec("match", "soccer_server", preset, drill_options=options)


def test_looking_with_the_body_is_the_default_and_changes_nothing() -> None:
    plain = _match("soccer_server_1996")
    explicit = _match("soccer_server_1996", ("look", "body"))
    assert run_trial(plain, 0) == run_trial(explicit, 0)


def _reversals(spec: TrialSpec) -> int:
    rngs, drill, arena = build_trial(spec, 0)
    drill.setup(arena, rngs)
    minds = drill.minds(arena, rngs)
    counter = TurnReversals()

    def observe(a: object, percepts: list[Percept]) -> None:
        for r in arena.players:
            counter.sample(r, arena.player_state(r).heading)

    observe(arena, [])
    TrialLoop(arena, drill, minds, observe).run()
    return counter.count


@pytest.mark.parametrize("preset", ["soccer_server_1996", "rcssserver_19"])
def test_looking_with_the_neck_dithers_less_than_steady_turns(preset: str) -> None:
    steady = _reversals(_match(preset, ("steady_turns", True)))
    neck = _reversals(_match(preset, ("look", "neck")))
    assert neck < 0.75 * steady
