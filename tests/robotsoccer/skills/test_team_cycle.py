"""Team minds on the per-cycle client (robotsoccer.skills.team_cycle) and its reckoning."""

from __future__ import annotations

import math

import pytest

from field_models.protocol import LEFT, Action, Dash, Percept, PlayerRef, SeenBall, Turn
from field_models.registry import field_facts
from robotsoccer.drills.match import MatchDrill
from robotsoccer.runs.runner import DrillOption, TrialSpec, build_trial, run_trial
from robotsoccer.skills.reckoning import BodyReckoner, BodyState
from robotsoccer.skills.team_cycle import CycleTeamMind

ME = PlayerRef(LEFT, 7)
DEG = math.pi / 180.0


def _match(preset: str, *extra: tuple[str, DrillOption], half_s: float = 5.0) -> TrialSpec:
    options: tuple[tuple[str, DrillOption], ...] = (
        ("left", "baseline"),
        ("right", "baseline"),
        ("half_time_s", half_s),
        *extra,
    )
    return TrialSpec("match", "soccer_server", preset, drill_options=options)


def _mind(preset: str = "soccer_server_1996") -> CycleTeamMind:
    """Player 7 of a per-cycle baseline team, as the match builds it."""
    rngs, drill, arena = build_trial(_match(preset, ("client", "cycle")), 0)
    drill.setup(arena, rngs)
    mind = drill.minds(arena, rngs)[ME]
    assert isinstance(mind, CycleTeamMind)
    return mind


def _ball(
    tick: int, distance: float, angle_deg: float = 0.0, observed: int | None = None
) -> Percept:
    seen = tick if observed is None else observed
    return Percept(ME, tick, seen, SeenBall(distance, angle_deg * DEG))


def _run(reckoner: BodyReckoner, actions: tuple[Action, ...]) -> float:
    state: BodyState = (0.0, 0.0, 0.0, 0.0, 0.0)
    for action in actions:
        state = reckoner.cycle(state, action)
    return math.hypot(state[1], state[2])


def test_the_reckoner_runs_the_servers_equations() -> None:
    facts = field_facts("soccer_server", "soccer_server_1996")
    reckoner = BodyReckoner(facts)
    push = facts.player_accel_mps2 * facts.dt_s**2
    one = reckoner.cycle((0.0, 0.0, 0.0, 0.0, 0.0), Dash(100.0))
    assert one[1] == pytest.approx(push) and one[3] == pytest.approx(push * reckoner.decay)
    state: BodyState = (0.0, 0.0, 0.0, 0.0, 0.0)
    for _ in range(40):  # the top speed caps the run
        state = reckoner.cycle(state, Dash(100.0))
    assert math.hypot(state[3], state[4]) <= reckoner.top_m * reckoner.decay + 1e-12
    coasted = state
    for _ in range(400):  # the coast is the geometric series of the decayed speed
        coasted = reckoner.cycle(coasted, None)
    assert coasted[1] - state[1] == pytest.approx(reckoner.coast_m(state))
    turned = reckoner.cycle((0.0, 0.0, 0.0, 0.5, 0.0), Turn(1.0))
    assert turned[0] == pytest.approx(1.0 / (1.0 + reckoner.inertia * 0.5))


def test_a_far_chase_dashes_every_cycle_until_the_next_see_and_one_more() -> None:
    mind = _mind()
    facts = field_facts("soccer_server", "soccer_server_1996")
    cycles = math.ceil(facts.sensor_period_s / facts.dt_s) + 1
    actions = mind.act(_ball(10, 30.0))
    assert mind.intent == "chase"
    assert actions == (Dash(100.0),) * cycles
    assert mind.commands_added == cycles - 1


def test_a_chase_turns_then_runs_and_stops_short_of_a_near_ball() -> None:
    mind = _mind()
    actions = mind.act(_ball(10, 4.0, 40.0))
    assert mind.intent == "chase"
    assert isinstance(actions[0], Turn)
    dashes = actions[1:]
    assert dashes and all(a == Dash(100.0) for a in dashes)
    # The run (reckoned from rest) stays within the ball less the kick reach.
    assert _run(mind._reckoner, actions) <= 4.0 - mind.setup.reach_m


def test_a_held_turn_keeps_the_plan_instead_of_dropping_it() -> None:
    mind = _mind()
    first = mind.act(_ball(10, 30.0, 90.0))
    assert isinstance(first[0], Turn) and len(first) > 2
    shown = 10 + mind.turns.settle_ticks(first[0].angle_rad)
    assert shown > 11
    # A see that predates the turn: the team mind holds (an empty decision); the client keeps
    # what is left of the plan.
    later = mind.act(_ball(11, 30.0, 90.0, observed=shown - 1))
    assert later == first[1:]


def test_the_client_is_checked_and_see_is_the_default() -> None:
    with pytest.raises(
        ValueError, match="client: expected one of see, cycle, left, right; got 'udp'"
    ):
        MatchDrill(left="baseline", right="baseline", client="udp")
    plain = _match("soccer_server_1996")
    assert run_trial(plain, 0) == run_trial(_match("soccer_server_1996", ("client", "see")), 0)


def test_the_robots_refuse_the_per_cycle_client() -> None:
    spec = TrialSpec(
        "match",
        "robot_physics",
        drill_options=(("left", "baseline"), ("right", "baseline"), ("client", "cycle")),
    )
    rngs, drill, arena = build_trial(spec, 0)
    drill.setup(arena, rngs)
    with pytest.raises(ValueError, match="client=cycle is the Soccer Server's"):
        drill.minds(arena, rngs)


def test_a_run_home_stops_dashing_where_the_coast_reaches_home(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    mind = _mind()
    mind.intent = "home"
    monkeypatch.setattr(mind, "_run_distance", lambda percept: 5.0)
    actions = mind._continued(_ball(10, 30.0), (Dash(80.0),))
    reckoner = mind._reckoner
    state: BodyState = (0.0, 0.0, 0.0, 0.0, 0.0)
    for action in actions:
        state = reckoner.cycle(state, action)
    assert 1 < len(actions) < mind._plan_cycles()
    assert state[1] + reckoner.coast_m(state) <= 5.0
    further = reckoner.cycle(state, Dash(80.0))
    assert further[1] + reckoner.coast_m(further) > 5.0


def test_a_ball_coming_at_the_chaser_is_met_as_layer_1s_per_cycle_defender_meets_it() -> None:
    mind = _mind()  # the baseline: straight, TA = 0
    mind.act(_ball(10, 12.0, 5.0))
    assert mind.intent == "chase" and not mind._meeting.triggered
    plan = mind.act(_ball(12, 9.0, 5.0))  # coming, within the trigger distance
    assert mind.intent == "intercept"
    assert mind._meeting.triggered and mind._meeting.turn_angle_rad == 0.0
    assert plan and all(isinstance(a, Dash | Turn) for a in plan)
    mind.act(_ball(14, 9.5, 5.0))  # no longer coming: the next ball met chooses TA afresh
    assert mind.intent == "chase" and not mind._meeting.triggered


def test_the_layered_team_meets_with_its_own_ta_rule() -> None:
    base = _mind()
    facts = field_facts("soccer_server", "soccer_server_1996")
    mind = CycleTeamMind(7, base.setup, facts=facts, interception=lambda *inputs: 0.3)
    mind.act(_ball(10, 12.0, 5.0))
    mind.act(_ball(12, 9.0, 5.0))
    assert mind.intent == "intercept" and mind._meeting.turn_angle_rad == pytest.approx(0.3)
