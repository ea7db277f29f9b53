"""The per-cycle interception defender (robotsoccer.skills.cycle) and the drill's client option."""

from __future__ import annotations

import dataclasses
import math

import pytest

from field_models.arena import FieldFacts, FieldOptions
from field_models.protocol import (
    RIGHT,
    Action,
    Dash,
    Percept,
    PlayerRef,
    SeenBall,
    SeenLandmark,
    Turn,
)
from field_models.registry import field_facts
from robotsoccer.drills.intercept import InterceptDrill
from robotsoccer.drills.intercept_batch import batch_reason
from robotsoccer.drills.intercept_plan import DEFENDER
from robotsoccer.runs.runner import DrillOption, TrialLoop, TrialSpec, build_trial, run_trial
from robotsoccer.skills.cycle import CycleDefenderMind, fit_ball
from robotsoccer.skills.localise import Localiser
from robotsoccer.skills.reversals import TurnReversals
from robotsoccer.skills.turn_policies import straight_policy

ME = PlayerRef(RIGHT, 1)
DEG = math.pi / 180.0
FACTS = field_facts("soccer_server", "rcssserver_19")


def percept(tick: int, distance: float | None, angle_deg: float = 0.0) -> Percept:
    ball = None if distance is None else SeenBall(distance, angle_deg * DEG)
    return Percept(ME, tick, tick, ball, (), (), ())


def test_facts_carry_the_servers_turn_inertia() -> None:
    assert FACTS.turn_inertia_s_per_m == pytest.approx(5.0 * 0.1)  # inertia_moment 5 per m/cycle
    robots = field_facts("robot_physics", None)
    assert robots.turn_inertia_s_per_m == 0.0


def test_faces_the_ball_before_the_trigger_without_empty_turns() -> None:
    mind = CycleDefenderMind(straight_policy, FACTS, 14.0)
    assert mind.act(percept(1, 24.0, 3.0)) == (Turn(3.0 * DEG),)  # standing: no inertia
    assert mind.act(percept(3, 20.0, 0.0)) == ()  # no (turn 0)
    assert not mind.triggered and mind.example is None


def test_trigger_records_the_papers_example_and_plans_a_dash_every_cycle() -> None:
    calls: list[tuple[float, float, float]] = []

    def policy(bd: float, ba: float, prev: float, prev_xy: object, xy: object) -> float:
        calls.append((bd, ba, prev))
        return 0.0

    mind = CycleDefenderMind(policy, FACTS, 14.0)
    mind.act(percept(1, 20.0))
    plan = mind.act(percept(3, 13.0))
    assert calls == [(13.0, 0.0, 20.0)] and mind.example == (13.0, 0.0, 20.0, 0.0)
    assert mind.triggered
    # A dash every cycle: the first at full power; the ball comes straight at it at 3.5 m a
    # cycle, so the meeting rule slows it to stand where the ball will be at a cycle end.
    assert plan[0] == Dash(100.0) and all(isinstance(action, Dash) for action in plan)
    assert len(plan) >= math.ceil(FACTS.sensor_period_s / FACTS.dt_s)  # up to the next see


def test_a_large_error_turns_with_the_moment_scaled_by_the_speed() -> None:
    mind = CycleDefenderMind(lambda *_: 0.0, FACTS, 14.0)
    mind.act(percept(1, 13.0))  # triggers; plans dashes
    plan = mind.act(percept(3, 11.0, 60.0))  # two dashes ran: the defender is moving
    turn = plan[0]
    assert isinstance(turn, Turn)
    speed = math.hypot(mind._vx, mind._vy)
    assert speed > 0.0
    assert turn.angle_rad == pytest.approx(60.0 * DEG * (1.0 + 5.0 * speed))
    first_dash = next(i for i, action in enumerate(plan) if isinstance(action, Dash))
    assert all(isinstance(action, Dash) for action in plan[first_dash:])  # turns, then dashes


def test_a_medium_error_with_few_cycles_left_dashes_toward_it_where_the_server_allows() -> None:
    def action(facts: FieldFacts, cycles: float) -> Action:
        mind = CycleDefenderMind(lambda *_: 0.0, facts, 14.0)
        return mind._turn_or_side_dash(30.0 * DEG, cycles, (0.0, 0.0, 0.0, 0.0, 0.0))

    # rate(30°) = 0.8: over 3 cycles 2.4 dashes' push beside 2 after a turn; over 10, 8 < 9.
    assert action(FACTS, 3.0) == Dash(100.0, 30.0 * DEG)
    assert action(FACTS, 10.0) == Turn(30.0 * DEG)
    paper = dataclasses.replace(FACTS, dash_rates=None)
    assert action(paper, 3.0) == Turn(30.0 * DEG)  # no directed dash: it turns


def test_the_meeting_rule_leaves_a_chase_that_would_not_touch_the_ball() -> None:
    mind = CycleDefenderMind(lambda *_: 0.0, FACTS, 14.0)
    mind.act(percept(1, 13.0, 0.0))
    mind.act(percept(2, 12.0, 0.0))
    # A ball 12 m away moving sideways fast: the chase's path never comes within a touch.
    state = (0.0, 0.0, 0.0, 0.0, 0.0)
    far_ball = (2, 12.0, 0.0, 0.0, 2.5)
    action = Dash(100.0)
    assert mind._meeting(state, far_ball, 0, action, 0.0) is action


def test_a_ball_not_seen_after_the_trigger_dashes() -> None:
    mind = CycleDefenderMind(straight_policy, FACTS, 14.0)
    assert mind.act(percept(1, None)) == ()
    mind.act(percept(2, 13.0))
    assert set(mind.act(percept(4, None))) == {Dash(100.0)}


def test_still_never_acts() -> None:
    mind = CycleDefenderMind(None, FACTS, 14.0)
    assert mind.act(percept(1, 10.0)) == () and mind.example is None


def test_fit_ball_recovers_a_noiseless_decaying_flight() -> None:
    decay, x, vx = 0.94, 0.0, 2.0
    sightings = []
    for tick in range(6):
        if tick in (1, 2, 4, 5):
            sightings.append((tick, x, -0.5 * x))
        x, vx = x + vx, vx * decay
    newest, bx, by, bvx, bvy = fit_ball(sightings, decay)
    velocity_at_5 = 2.0 * decay**5
    assert newest == 5
    assert (bx, by) == pytest.approx((sightings[-1][1], sightings[-1][2]))
    assert (bvx, bvy) == pytest.approx((velocity_at_5, -0.5 * velocity_at_5))


def test_dead_reckoning_follows_the_server_without_noise() -> None:
    spec = TrialSpec(
        "intercept",
        "soccer_server",
        "rcssserver_19",
        drill_options=(("behaviour", "straight"), ("client", "cycle")),
        field=FieldOptions(ball_noise=0.0, perfect_perception=True),
    )
    rngs, drill, arena = build_trial(spec, 3)
    drill.setup(arena, rngs)
    minds = drill.minds(arena, rngs)
    mind = minds[DEFENDER]
    assert isinstance(mind, CycleDefenderMind)
    start = arena.player_state(DEFENDER)
    errors: list[float] = []

    def observe(a: object, percepts: list[Percept]) -> None:
        if any(p.player == DEFENDER for p in percepts):
            now = arena.player_state(DEFENDER)
            c, s = math.cos(start.heading), math.sin(start.heading)
            x = start.x + c * mind._x - s * mind._y
            y = start.y + s * mind._x + c * mind._y
            errors.append(math.hypot(now.x - x, now.y - y))

    TrialLoop(arena, drill, minds, observe).run()
    assert errors and max(errors) < 0.35  # the server's movement noise (player_rand) only


def test_client_option_is_checked_and_the_cycle_client_leaves_the_batch() -> None:
    with pytest.raises(ValueError, match=r"unknown client 'every' \(known: see, cycle\)"):
        InterceptDrill(client="every")
    with pytest.raises(ValueError, match="client 'cycle'"):
        InterceptDrill(client="cycle", decision="lead")
    spec = TrialSpec("intercept", "soccer_server", "rcssserver_19")
    assert batch_reason(spec) is None
    cycle = TrialSpec(
        "intercept", "soccer_server", "rcssserver_19", drill_options=(("client", "cycle"),)
    )
    assert batch_reason(cycle) == "the batch plays the see-triggered client"
    result = run_trial(cycle, 0)
    assert result.label in ("SAVE", "GOAL", "MISS")


def test_see_is_the_default_client() -> None:
    spec = TrialSpec("intercept", "soccer_server", "soccer_server_1996")
    explicit = TrialSpec(
        "intercept", "soccer_server", "soccer_server_1996", drill_options=(("client", "see"),)
    )
    assert [run_trial(spec, i) for i in range(5)] == [run_trial(explicit, i) for i in range(5)]


# ----------------------------------------------------------------------------- steady turns


def _reversals(steady: bool) -> int:
    """Turns of more than 10° the other way from the player's last such turn, all players."""
    options: tuple[tuple[str, DrillOption], ...] = (
        ("left", "baseline"),
        ("right", "baseline"),
        ("half_time_s", 5.0),
    )
    if steady:
        options += (("steady_turns", True),)
    spec = TrialSpec("match", "soccer_server", "rcssserver_19_async", drill_options=options)
    rngs, drill, arena = build_trial(spec, 0)
    drill.setup(arena, rngs)
    minds = drill.minds(arena, rngs)
    counter = TurnReversals()
    for r in arena.players:
        counter.sample(r, arena.player_state(r).heading)

    def observe(a: object, percepts: list[Percept]) -> None:
        for r in arena.players:
            counter.sample(r, arena.player_state(r).heading)

    TrialLoop(arena, drill, minds, observe).run()
    return counter.count


def test_steady_turns_dither_less_in_a_server_match() -> None:
    assert _reversals(steady=True) < 0.5 * _reversals(steady=False)


def test_localiser_reckons_told_turns_until_two_landmarks_fix_the_heading() -> None:
    localiser = Localiser([("g l", -52.5, 0.0), ("g r", 52.5, 0.0)])
    both = (SeenLandmark("g l", 52.5, math.pi), SeenLandmark("g r", 52.5, 0.0))
    fixed = localiser.update(Percept(ME, 1, 1, None, (), (), both))
    assert fixed is not None
    assert (fixed.x, fixed.y, fixed.heading) == pytest.approx((0.0, 0.0, 0.0), abs=1e-9)
    localiser.turned(0.5)
    pose = localiser.update(Percept(ME, 2, 2, None, (), (), ()))
    assert pose is not None and pose.heading == pytest.approx(0.5)
    again = localiser.update(Percept(ME, 3, 3, None, (), (), ()))
    assert again is not None and again.heading == pytest.approx(0.5)  # told once, added once


def test_the_cycle_client_saves_more_than_the_see_client_on_rcssserver_19() -> None:
    def saves(client: str, behaviour: str) -> int:
        spec = TrialSpec(
            "intercept",
            "soccer_server",
            "rcssserver_19",
            drill_options=(("behaviour", behaviour), ("client", client)),
            field=FieldOptions(ball_noise=0.05),
        )
        return sum(run_trial(spec, i).label == "SAVE" for i in range(400))

    # 2000 trials (seed 0): analytic 21.6% and 81.7%, straight 13.8% and 46.4%.
    assert saves("cycle", "analytic") > saves("see", "analytic") + 100
    assert saves("cycle", "straight") > saves("see", "straight") + 60


def test_turn_reversals_count_only_big_turns_the_other_way() -> None:
    counter = TurnReversals()
    for heading_deg in (0, 15, 20, 5, 4, -8, 30, 31, 350):
        counter.sample("p", heading_deg * DEG)
    # Turns: +15 (left), +5 (small), -15 (reversal 1), -1, -12 (same way), +38 (reversal 2),
    # +1, -41 across the wrap (reversal 3).
    assert counter.count == 3
    counter.sample("q", 0.0)
    counter.sample("q", -20 * DEG)
    assert counter.count == 3  # another player's first big turn reverses nothing
    with pytest.raises(ValueError, match="min_turn_rad"):
        TurnReversals(-1.0)
