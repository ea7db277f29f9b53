"""The set play's attackers on the per-cycle client: runs go on, nothing dropped, turns noted."""

from __future__ import annotations

import math

import pytest

from field_models.protocol import LEFT, Action, Dash, Kick, Percept, PlayerRef, SeenBall, Turn
from field_models.registry import field_facts
from robotsoccer.drills.intercept_plan import LaunchPlan
from robotsoccer.drills.setplay import SetPlayDrill
from robotsoccer.drills.setplay_kicks import ball_sense
from robotsoccer.skills.ball_tracker import BallTracker
from robotsoccer.skills.cycle import CycleDefenderMind
from robotsoccer.skills.reckoning import BodyReckoner
from robotsoccer.skills.setplay_cycle import CycleAttacker, CycleIntercept
from robotsoccer.skills.turn_policies import straight_policy

ME = PlayerRef(LEFT, 2)
FACTS = field_facts("soccer_server", "soccer_server_1996")
TRIGGER_M = 14.0


class ScriptedMind:
    """A set-play mind that answers each see with the next scripted decision.

    A decision ``"meet"`` asks its layer 1 (as a receiver does) and returns what it gives.
    It notes its turns as the set-play minds do.
    """

    def __init__(self, script: list[tuple[Action, ...] | str], meet: CycleIntercept | None) -> None:
        sense = ball_sense(FACTS, _plan())
        self.heading = sense.heading()
        self.tracker = BallTracker(sense)
        self.reach_m = sense.reach_m
        self.done = False
        self.script = list(script)
        self.meet = meet

    def act(self, percept: Percept) -> tuple[Action, ...]:
        step = self.script.pop(0)
        if step == "meet":
            assert self.meet is not None
            actions = self.meet.act(percept)
        else:
            assert not isinstance(step, str)
            actions = step
        self.heading.note(actions, percept.tick)
        return actions


def _plan() -> LaunchPlan:
    return SetPlayDrill().plan(FACTS)


def _attacker(
    script: list[tuple[Action, ...] | str], *, meets: bool = False
) -> tuple[CycleAttacker, ScriptedMind]:
    model = CycleDefenderMind(straight_policy if meets else None, FACTS, TRIGGER_M)
    meet = CycleIntercept(model) if meets else None
    mind = ScriptedMind(script, meet)
    return CycleAttacker(mind, model, meet, FACTS), mind


def _see(tick: int, distance_m: float | None, angle_deg: float = 0.0) -> Percept:
    ball = None if distance_m is None else SeenBall(distance_m, math.radians(angle_deg))
    return Percept(ME, tick, tick, ball)


def _run_m(actions: tuple[Action, ...]) -> tuple[float, float]:
    """(the run, with the coast after it) of `actions` from rest [m]."""
    reckoner = BodyReckoner(FACTS)
    state = (0.0, 0.0, 0.0, 0.0, 0.0)
    for action in actions:
        state = reckoner.cycle(state, action)
    run = math.hypot(state[1], state[2])
    return run, run + reckoner.coast_m(state)


def test_a_far_run_dashes_every_cycle_until_the_next_see_and_one_more() -> None:
    client, _ = _attacker([(Dash(70.0),)])
    plan = client.act(_see(10, 30.0))
    # A see every 2.5 cycles on the 1996 preset: 3 cycles, and one in case it comes late.
    assert plan == (Dash(70.0),) * 4 == (Dash(70.0),) * client.plan_cycles
    assert client.commands_added == 3


def test_a_run_stops_short_of_the_ball_with_its_coast() -> None:
    client, mind = _attacker([(Turn(0.3), Dash(100.0))])
    distance = 6.0
    plan = client.act(_see(10, distance, 17.0))
    short = distance - mind.reach_m
    assert plan[:2] == (Turn(0.3), Dash(100.0)) and set(plan[1:]) == {Dash(100.0)}
    assert 2 < len(plan) < client.plan_cycles  # carried on, then cut short
    assert _run_m(plan)[1] <= short < _run_m((*plan, Dash(100.0)))[1]


@pytest.mark.parametrize(
    "decision",
    [(Turn(0.5),), (Kick(20.0, 0.0),), (Dash(0.0),), (Kick(10.0, 1.0), Turn(0.4))],
)
def test_kicks_turns_and_stands_are_sent_as_they_are(decision: tuple[Action, ...]) -> None:
    client, _ = _attacker([decision])
    assert client.act(_see(10, 30.0)) == decision


def test_an_empty_decision_keeps_what_is_left_of_the_plan() -> None:
    client, _ = _attacker([(Dash(80.0),), (), ()])
    plan = client.act(_see(10, 30.0))
    assert client.act(_see(12, 30.0)) == plan[2:]  # the see client would drop them
    assert client.act(_see(20, 30.0)) == ()  # all run: nothing left


class FixedPlanDefender(CycleDefenderMind):
    """The per-cycle defender, its plan at a see given (one with turns after its first command)."""

    def __init__(self, plan: tuple[Action, ...]) -> None:
        super().__init__(straight_policy, FACTS, TRIGGER_M)
        self.fixed = plan

    def decide(self, percept: Percept, sighting: object) -> tuple[Action, ...]:
        return self.fixed


def test_layer_1s_plan_is_sent_whole_and_its_later_turns_are_noted_once_run() -> None:
    plan = (Turn(0.1), Dash(100.0), Turn(0.4), Dash(100.0), Turn(-0.2), Dash(100.0))
    model = FixedPlanDefender(plan)
    meet = CycleIntercept(model)
    mind = ScriptedMind(["meet", (), (Dash(0.0),)], meet)
    client = CycleAttacker(mind, model, meet, FACTS)
    assert client.act(_see(10, 12.0)) == plan  # the mind got plan[0] only, and noted its turn
    assert mind.heading.rad == pytest.approx(0.1)
    assert client.act(_see(12, 12.0)) == plan[2:]  # cycles 11-12 ran plan[0:2]: no turn more
    assert mind.heading.rad == pytest.approx(0.1)
    client.act(_see(15, 12.0))  # cycles 13-15 ran plan[2:5]: two turns, noted for the mind
    assert mind.heading.rad == pytest.approx(0.1 + 0.4 - 0.2)


def test_the_meeting_plan_comes_from_the_world_model_within_the_trigger() -> None:
    client, _ = _attacker(["meet"], meets=True)
    first = client.act(_see(10, 12.0, 30.0))
    model = client.model
    assert model.triggered and len(first) == model.plan_cycles
    assert isinstance(first[0], Turn)  # straight: it faces the ball's bearing first
