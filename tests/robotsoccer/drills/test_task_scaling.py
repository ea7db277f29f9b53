"""The ``task`` scaling rule: closed forms, the reference field, and the robots' numbers."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from field_models.arena import BallLaw
from field_models.registry import field_facts, paper_field_facts
from robotsoccer.drills.intercept_plan import launch_plan, reference_flight
from robotsoccer.drills.task_scaling import (
    REACH_UNITS,
    lateral_wander,
    run_time_s,
    task_launch,
)


def test_run_time_is_the_ramp_then_top_speed() -> None:
    # 3 m/s² to 1.2 m/s: the ramp covers 0.24 m in 0.4 s.
    assert run_time_s(0.06, 3.0, 1.2) == pytest.approx(0.2)
    assert run_time_s(0.24, 3.0, 1.2) == pytest.approx(0.4)
    assert run_time_s(0.36, 3.0, 1.2) == pytest.approx(0.5)


@pytest.mark.parametrize(
    "ball", [BallLaw("constant", 0.01, decel_mps2=0.1), BallLaw("geometric", 0.1, 0.96)]
)
def test_lateral_wander_matches_a_simulated_noise_process(ball: BallLaw) -> None:
    speed, flight, period = 2.0, 1.0, 0.1
    rng = np.random.default_rng(0)
    times = np.arange(1, 10) * period
    total = ball.distance_in(speed, flight)
    remaining = np.array([total - ball.distance_in(speed, t) for t in times])
    deltas = rng.uniform(-1.0, 1.0, size=(200_000, len(times)))  # noise level 1
    simulated = float(np.std(deltas @ remaining))
    assert lateral_wander(ball, speed, flight, period) == pytest.approx(simulated, rel=0.01)


def test_on_the_papers_field_the_task_rule_is_the_literal_drill() -> None:
    facts = paper_field_facts()
    literal = launch_plan(facts, scaling="literal")
    task = launch_plan(facts, scaling="task")
    assert dataclasses.replace(task, scaling=literal.scaling) == literal
    assert task.decision_period_s == 0.0


@pytest.mark.parametrize("preset", ["small_size_1997", "vss", "small_size_fast"])
def test_the_robots_keep_the_references_reach_wander_and_decisions(preset: str) -> None:
    facts = field_facts("robot_physics", preset)
    reference = reference_flight()
    task = task_launch(facts, reference)
    plan = launch_plan(facts, scaling="task")
    # The ball takes the rule's time from the trigger to the defender ...
    assert plan.trigger_to_arrival_s == pytest.approx(task.after_trigger_s)
    # ... which is the latency plus the time to run the reach.
    latency = (facts.sensor_latency_s or 0.0) + facts.sensor_period_s
    run = run_time_s(
        REACH_UNITS * facts.unit_m, facts.player_accel_mps2, facts.player_top_speed_mps
    )
    assert task.after_trigger_s == pytest.approx(latency + run)
    # Decisions: whole sensor periods, within half a period's rounding of the reference's.
    periods = task.decision_period_s / facts.sensor_period_s
    assert periods == pytest.approx(round(periods)) and periods >= 1
    exact = task.after_trigger_s / reference.decisions / facts.sensor_period_s
    assert abs(periods - exact) <= 0.5 or periods == 1
    # Wander in touch distances: the nearest a whole tick of noise period allows.
    ticks = round(task.noise_period_s / facts.dt_s)
    error = abs(math.log(task.wander_touches / reference.wander_touches))
    for other in (ticks - 1, ticks + 1):
        if other >= 1:
            wander = lateral_wander(
                facts.ball, task.launch_speed_mps, task.flight_s, other * facts.dt_s
            )
            assert (
                abs(math.log(wander / facts.touch_distance_m / reference.wander_touches)) >= error
            )
    assert plan.noise_period_s == task.noise_period_s
    assert plan.decision_period_s == task.decision_period_s


def test_a_ball_that_cannot_make_the_flight_is_refused() -> None:
    facts = field_facts("robot_physics", "small_size_1997")
    sticky = dataclasses.replace(facts, ball=BallLaw("constant", facts.dt_s, decel_mps2=50.0))
    with pytest.raises(ValueError, match="launch speed"):
        task_launch(sticky, reference_flight())


def test_the_wander_sum_has_a_period_limit() -> None:
    from robotsoccer.drills.task_scaling import lateral_wander

    ball = BallLaw("constant", 1 / 240, decel_mps2=0.1)
    assert lateral_wander(ball, 1.0, 2.0, 0.1) > 0.0
    for flight_s, period_s in ((1e9, 0.1), (2.0, 1e-300), (float("inf"), 0.1), (2.0, 0.0)):
        with pytest.raises(ValueError, match="noise periods"):
            lateral_wander(ball, 1.0, flight_s, period_s)
