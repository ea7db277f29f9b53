"""The set play's attackers looking with the neck (issue 28 item 3): option ``look``."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from field_models.protocol import (
    LEFT,
    RIGHT,
    Action,
    ChangeView,
    Heard,
    Percept,
    PlayerRef,
    Say,
    SeenBall,
    SeenLandmark,
    SeenPlayer,
    Turn,
    TurnNeck,
)
from robotsoccer.cli.commands.setplay import setplay_request
from robotsoccer.cli.parser import build_parser
from robotsoccer.drills import make_drill
from robotsoccer.experiments.setplay import play_conditions
from robotsoccer.experiments.setplay_run import SetPlayRun
from robotsoccer.runs.runner import TrialSpec, build_trial, play
from robotsoccer.skills.pass_messages import INTENT, announce_text
from robotsoccer.skills.pass_receivers import ReceiverMind
from robotsoccer.skills.setplay_look import NeckAttacker
from robotsoccer.skills.team_look import NECK_MAX_RAD, NeckLook

ME = PlayerRef(LEFT, 2)
DEG = math.pi / 180.0
NECK_ACTIONS = (TurnNeck, ChangeView)


def _setplay(preset: str, *options: tuple[str, str], model: str = "soccer_server") -> TrialSpec:
    return TrialSpec("setplay", model, preset=preset, seed=4, drill_options=options)


def test_the_look_is_checked_and_body_is_the_default() -> None:
    with pytest.raises(ValueError, match=r"^unknown look 'eyes' \(known: body, neck\)$"):
        make_drill("setplay", {"look": "eyes"})
    assert make_drill("setplay", {}).options.look == "body"
    assert make_drill("setplay", {"look": "neck"}).options.look == "neck"


def test_the_command_line_and_the_study_pass_the_look_to_the_server_fields_only() -> None:
    args = build_parser().parse_args(["setplay", "--look", "neck", "--client", "cycle"])
    request = setplay_request(args)
    assert request.look == "neck"
    assert request.folder == Path("runs/setplay-cycle-neck-seed0")
    assert setplay_request(build_parser().parse_args(["setplay"])).look == "body"
    assert SetPlayRun((("soccer_server", "soccer_server_1996"),)).folder == Path(
        "runs/setplay-seed0"
    )  # a body run's folder is the one it always was
    with pytest.raises(SystemExit):
        build_parser().parse_args(["setplay", "--look", "eyes"])
    server = play_conditions(("soccer_server", "rcssserver_19"), None, 0, look="neck")
    assert all(dict(c.spec.drill_options)["look"] == "neck" for c in server)
    robots = play_conditions(("robot_physics", "small_size_1997"), None, 0, look="neck")
    assert all("look" not in dict(c.spec.drill_options) for c in robots)


def _decisions(spec: TrialSpec) -> dict[PlayerRef, list[tuple[Action, ...]]]:
    """Every decision of one play, by player."""
    rngs, drill, arena = build_trial(spec, 0)
    drill.setup(arena, rngs)
    minds = drill.minds(arena, rngs)
    sent: dict[PlayerRef, list[tuple[Action, ...]]] = {ref: [] for ref in minds}

    def log(percept: Percept, actions: tuple[Action, ...]) -> None:
        sent[percept.player].append(actions)

    play(arena, drill, minds, decisions=log)
    return sent


def _neck_actions(decisions: list[tuple[Action, ...]]) -> int:
    return sum(isinstance(a, NECK_ACTIONS) for actions in decisions for a in actions)


@pytest.mark.parametrize("client", ["see", "cycle"])
def test_the_attackers_look_with_the_neck_only_with_look_neck(client: str) -> None:
    body = _decisions(_setplay("rcssserver_19", ("client", client)))
    neck = _decisions(_setplay("rcssserver_19", ("client", client), ("look", "neck")))
    assert all(_neck_actions(d) == 0 for d in body.values())
    for ref, decisions in neck.items():
        if ref.team == LEFT:
            assert _neck_actions(decisions) > 0, ref
        else:
            assert _neck_actions(decisions) == 0, ref  # defenders keep layer 1's drill minds


def test_the_robots_accept_look_neck_and_play_as_with_the_body() -> None:
    plain = _setplay("small_size_1997", model="robot_physics")
    neck = _setplay("small_size_1997", ("look", "neck"), model="robot_physics")
    assert _decisions(plain) == _decisions(neck)


class _Probe:
    """A set-play mind that records what it was given and sends one decision."""

    reach_m = 1.0
    done = False

    def __init__(self, actions: tuple[Action, ...], seeking_goal: bool = False) -> None:
        self.actions = actions
        self.seeking_goal = seeking_goal
        self.seen: list[Percept] = []

    def act(self, percept: Percept) -> tuple[Action, ...]:
        self.seen.append(percept)
        return self.actions


def test_the_mind_reads_from_the_body_and_the_head_follows_the_ball() -> None:
    probe = _Probe((Say("x"), Turn(10 * DEG)))
    head = NeckLook()
    attacker = NeckAttacker(probe, head)
    raw = Percept(
        ME, 7, 7, SeenBall(20.0, 20 * DEG), (SeenPlayer(5.0, -10 * DEG, LEFT, 3),), (),
        (SeenLandmark("g r", 30.0, 0.0),), 30 * DEG,
    )  # fmt: skip
    actions = attacker.act(raw)
    given = probe.seen[0]
    assert given.neck_rad == 0.0 and head.neck_rad == 30 * DEG
    assert given.ball is not None and given.ball.angle_rad == pytest.approx(50 * DEG)
    assert given.players[0].angle_rad == pytest.approx(20 * DEG)
    assert given.landmarks[0].angle_rad == pytest.approx(30 * DEG)
    # The body turns 10°: the neck goes to the ball at 40° from the turned body, from 30°.
    assert actions[:2] == (Turn(10 * DEG), Say("x"))
    neck = actions[-1]
    assert isinstance(neck, TurnNeck) and neck.angle_rad == pytest.approx(10 * DEG)
    # Not seen since: looked at where it was (less the body's turn), then looked for.
    attacker.act(Percept(ME, 9, 9, None, neck_rad=40 * DEG))
    assert attacker.target(Percept(ME, 10, 10, None)) == pytest.approx(30 * DEG)
    assert attacker.target(Percept(ME, 40, 40, None)) is None


def test_a_ball_at_the_feet_is_looked_past_and_a_goal_looked_for_with_a_wide_view() -> None:
    attacker = NeckAttacker(_Probe(()), NeckLook())
    assert attacker.target(Percept(ME, 1, 1, SeenBall(0.5, 40 * DEG))) == 0.0
    seeker = NeckAttacker(_Probe((), seeking_goal=True), NeckLook())
    actions = seeker.act(Percept(ME, 1, 1, SeenBall(20.0, 0.0)))
    assert ChangeView("wide", "high") in actions
    assert not any(isinstance(a, Turn) for a in actions)


def _receiver(head: NeckLook | None) -> ReceiverMind:
    return ReceiverMind(
        ME.number, _Probe((Turn(1.0),)), unit_m=1.0, sensor_period_s=0.15, dt_s=0.1, slot=0,
        say_max_chars=None, head=head,
    )  # fmt: skip


def _waiting(ball_deg: float, neck_deg: float, tick: int) -> Percept:
    """The receiver's view from its head: the passer beside the ball, a defender."""
    b, n = ball_deg * DEG, neck_deg * DEG
    players = (SeenPlayer(18.0, b + 2 * DEG, LEFT, 1), SeenPlayer(9.0, b - 30 * DEG, RIGHT, 2))
    heard = (Heard(INTENT, PlayerRef(LEFT, 1), b, tick),) if tick == 1 else ()
    return Percept(ME, tick, tick, SeenBall(17.0, b), players, heard, (), n).body_relative()


def test_a_receiver_looking_with_the_neck_reports_without_turning_its_body() -> None:
    head = NeckLook()
    neck = _receiver(head)
    # The ball 60° off the body, the head straight: the body stays, the head is pointed.
    head.sensed(Percept(ME, 1, 1, None))
    assert neck.act(_waiting(60.0, 0.0, 1)) == ()
    # Next see: the head faces the ball (60° of neck): it reports, and never turned its body.
    head.sensed(Percept(ME, 3, 3, None, neck_rad=60 * DEG))
    actions = neck.act(_waiting(0.0, 60.0, 3))
    assert len(actions) == 1 and isinstance(actions[0], Say)
    # The report is the one a receiver whose body faces the ball says of the same view.
    body = _receiver(None)
    assert body.act(_waiting(60.0, 0.0, 1)) == (Turn(60 * DEG),)
    assert body.act(_waiting(0.0, 0.0, 3)) == actions
    # Beyond the neck's range the body turns.
    far = _receiver(NeckLook())
    turn = far.act(_waiting(100.0, 0.0, 1))
    assert turn == (Turn(100 * DEG),) and 100 * DEG > NECK_MAX_RAD


def test_a_chosen_receiver_looking_with_the_neck_faces_the_ball_once_then_intercepts() -> None:
    neck = _receiver(NeckLook())
    told = Heard(announce_text(ME.number), PlayerRef(LEFT, 1), 0.0, 5)
    ball = SeenBall(15.0, 40 * DEG)
    assert neck.act(Percept(ME, 5, 5, ball, heard=(told,))) == (Turn(40 * DEG),)
    assert neck.act(Percept(ME, 7, 7, ball)) == (Turn(1.0),)  # layer 1's decision
    body = _receiver(None)
    assert body.act(Percept(ME, 5, 5, ball, heard=(told,))) == (Turn(1.0),)
