"""The interception drill's robot-native options: goal-mouth shots, speed ranges, the lead."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from field_models.registry import field_facts
from robotsoccer.drills.intercept import InterceptDrill
from robotsoccer.drills.intercept_batch import batch_reason
from robotsoccer.runs.pool import run_trials
from robotsoccer.runs.runner import TrialSpec, build_trial, run_trial
from tests.robotsoccer.skills.test_intercept import net_file

ROBOT_LEAD = (
    ("shot", "goal_mouth"),
    ("scaling", "task"),
    ("launch", "coach"),
    ("launch_speed_mps", 0.6),
    ("launch_speed_max_mps", 1.2),
    ("decision", "lead"),
)


def robot_spec(seed: int = 4, **options: str | float) -> TrialSpec:
    spec = TrialSpec(
        drill="intercept", field_model="robot_physics", preset="small_size_1997_arc", seed=seed
    )
    return spec.with_options(**dict(ROBOT_LEAD), **options).with_field(ball_noise=0.05)


def launched(spec: TrialSpec, index: int) -> tuple[float, float, float, float, float]:
    rngs, drill, arena = build_trial(spec, index)
    drill.setup(arena, rngs)
    x, y, _, vx, vy = arena.ball_state()
    return x, y, vx, vy, arena.facts.pitch.half_length_m


def test_goal_mouth_shots_head_between_the_posts_at_speeds_in_the_range() -> None:
    spec = robot_spec()
    half_goal = 0.25
    for index in range(40):
        x, y, vx, vy, line = launched(spec, index)
        crossing = y + (line - x) * vy / vx
        assert abs(crossing) < half_goal
        assert 0.6 <= math.hypot(vx, vy) <= 1.2


def test_the_paper_drill_draws_the_same_placements_as_before() -> None:
    plain = TrialSpec(drill="intercept", field_model="robot_physics", seed=4)
    x, y, vx, vy, _ = launched(plain, 3)
    turned = plain.with_options(decision="turn", shot="defender")
    assert launched(turned, 3)[:4] == (x, y, vx, vy)


def test_the_lead_defender_records_its_lead_and_saves_more_than_standing_still() -> None:
    straight = [run_trial(robot_spec(behaviour="straight"), i) for i in range(60)]
    random = [run_trial(robot_spec(behaviour="random"), i) for i in range(60)]
    still = [run_trial(robot_spec(behaviour="still"), i) for i in range(60)]
    drill = InterceptDrill(**dict(ROBOT_LEAD))
    plan_flight = drill.plan_for(field_facts("robot_physics", "small_size_1997_arc")).arrival_time_s
    assert 0.5 < plan_flight < 1.0  # the middle speed's flight over 25 units (0.65 m)
    leads = [r.data[3] for r in random if r.data]
    assert len(leads) > 50 and all(0.0 <= t <= plan_flight for t in leads)
    assert all(r.data[3] == 0.0 for r in straight if r.data)

    def saves(results: list) -> int:
        return sum(r.label == "SAVE" for r in results)

    assert saves(straight) > saves(still)


def test_a_touched_goal_mouth_shot_that_stays_out_is_a_save() -> None:
    results = [run_trial(robot_spec(behaviour="analytic"), i) for i in range(60)]
    reasons = {r.reason for r in results if r.label == "SAVE"}
    assert any(reason.startswith("deflected by the defender") for reason in reasons)


def test_lead_trials_are_the_same_whatever_the_worker_count() -> None:
    spec = robot_spec(behaviour="analytic")
    one = run_trials(spec, 24, workers=1, progress=False)
    two = run_trials(spec, 24, workers=2, progress=False)
    assert one == two


def test_the_lead_runs_on_the_soccer_server_with_every_flag_in_view() -> None:
    spec = TrialSpec(drill="intercept", field_model="soccer_server", seed=2).with_options(
        decision="lead", behaviour="analytic"
    )
    results = [run_trial(spec, i) for i in range(30)]
    assert sum(r.label == "SAVE" for r in results) > 10
    assert all(len(r.data) == 4 for r in results if r.data)


def test_nets_of_the_other_decision_and_bad_options_are_refused(tmp_path: Path) -> None:
    turn_net = net_file(tmp_path / "turn.npz", preset="small_size_1997_arc", field="robot_physics")
    with pytest.raises(ValueError, match="decides the turn, this run's decision is 'lead'"):
        run_trial(robot_spec(behaviour="net", model=str(turn_net)), 0)
    with pytest.raises(ValueError, match="has no lookup table"):
        InterceptDrill(behaviour="lookup", model="t.json", decision="lead")
    with pytest.raises(ValueError, match="launch_speed_max_mps needs"):
        InterceptDrill(launch_speed_mps=1.2, launch_speed_max_mps=0.6)
    with pytest.raises(ValueError, match="decision"):
        InterceptDrill(decision="dive")


def test_the_batch_engine_sends_the_new_options_to_the_one_trial_path() -> None:
    server = TrialSpec(drill="intercept", field_model="soccer_server", seed=1)
    assert batch_reason(server) is None
    assert "lead" in (batch_reason(server.with_options(decision="lead")) or "")
    assert "defender" in (batch_reason(server.with_options(shot="goal_mouth")) or "")
