"""The interception drill (paper Figure 6): scaling, scripted labels on both models, recording."""

from __future__ import annotations

import dataclasses
import math
from typing import Any

import pytest

from field_models.arena import Arena, FieldOptions
from field_models.protocol import Action, BodyState, Percept, PlayerRef
from field_models.registry import field_facts, make_arena
from field_models.seeding import TrialRngs
from robotsoccer.drills import DRILLS, make_drill
from robotsoccer.drills.intercept import InterceptDrill
from robotsoccer.drills.intercept_plan import DEFENDER, SHOOTER, decision_ticks, launch_plan
from robotsoccer.runs.runner import TrialSpec, play, run_trial
from robotsoccer.skills.intercept import AimedShooterMind

MODELS = {"soccer_server": "soccer_server_1996", "robot_physics": "small_size_1997"}


def arena_for(field_model: str, drill: InterceptDrill, seed: int = 0, noise: float = 0.0) -> Arena:
    rngs = TrialRngs.for_trial(seed, 0)
    options = FieldOptions(ball_noise=noise)
    return make_arena(field_model, MODELS[field_model], drill.players(), rngs, options)


def launched(field_model: str, aim_offset_deg: float, bearing_deg: float = 0.0) -> str:
    """Label of a coach-launched ball (no noise) at an idle defender, 25 units away."""
    drill = InterceptDrill(launch="coach", aim_offset_deg=aim_offset_deg)
    arena = arena_for(field_model, drill)
    plan = drill.plan(arena)
    drill.place(arena, plan, 25.0 * plan.unit_m, math.radians(bearing_deg))
    verdict = play(arena, drill, minds={})
    return f"{verdict.label}: {verdict.reason}"


# ----------------------------------------------------------------------------- scaling


def test_server_geometry_and_launch_numbers_by_hand() -> None:
    plan = launch_plan(field_facts("soccer_server", "soccer_server_1996"))
    assert (plan.unit_m, plan.defender_x_m, plan.trigger_distance_m) == (1.0, 48.5, 14.0)
    assert (plan.min_distance_m, plan.max_distance_m, plan.launch) == (20.0, 30.0, "shooter")
    # A power-100 kick: 1.6 m/cycle, decay 0.96 -> 25 m after ln(0.375)/ln(0.96) = 24.03 cycles.
    assert plan.launch_speed_mps == pytest.approx(16.0)
    assert plan.arrival_time_s == pytest.approx(0.1 * math.log(0.375) / math.log(0.96))
    assert plan.arrival_updates == pytest.approx(plan.arrival_time_s / 0.25)
    assert plan.kickable_distance_m == pytest.approx(0.8 + 0.085 + 1.0)


def test_robot_launch_matches_the_servers_sensor_updates() -> None:
    server = launch_plan(field_facts("soccer_server"))
    plan = launch_plan(field_facts("robot_physics", "small_size_1997"))
    unit = 2.74 / 105.0
    assert plan.unit_m == pytest.approx(unit)
    assert plan.defender_x_m == pytest.approx(1.37 - 4 * unit)
    assert plan.trigger_distance_m == pytest.approx(14 * unit)
    assert plan.launch == "coach" and plan.kickable_distance_m is None
    assert plan.arrival_updates == pytest.approx(server.arrival_updates)
    time = server.arrival_updates / 30.0
    assert plan.arrival_time_s == pytest.approx(time)
    assert plan.launch_speed_mps == pytest.approx(25 * unit / time + 0.5 * 0.10 * time)
    assert 2.0 < plan.launch_speed_mps < 2.1


@pytest.mark.parametrize("field_model", sorted(MODELS))
def test_the_ball_covers_the_mean_distance_in_the_planned_time(field_model: str) -> None:
    drill = InterceptDrill(launch="coach")
    arena = arena_for(field_model, drill)
    plan = drill.plan(arena)
    pitch, dt = arena.facts.pitch, arena.facts.dt_s
    arena.place_player(DEFENDER, 0.0, -0.4 * pitch.width_m, 0.0)  # out of the way
    arena.place_player(SHOOTER, 0.1 * pitch.length_m, -0.4 * pitch.width_m, 0.0)
    start = -0.45 * pitch.length_m
    arena.place_ball(start, 0.0, plan.launch_speed_mps, 0.0)
    while arena.ball_state().x - start < plan.mean_distance_m:
        arena.step()
    assert arena.tick * dt == pytest.approx(plan.arrival_time_s, abs=1.01 * dt)


def test_a_shooter_launch_on_kickerless_robots_is_refused() -> None:
    with pytest.raises(ValueError, match="no kick"):
        launch_plan(field_facts("robot_physics"), launch="shooter")
    with pytest.raises(ValueError, match="unknown launch"):
        launch_plan(field_facts("soccer_server"), launch="catapult")
    with pytest.raises(ValueError, match="literal drill needs a kick"):
        launch_plan(field_facts("robot_physics"), scaling="literal")


# ----------------------------------------------------------------------------- labels


@pytest.mark.parametrize("field_model", sorted(MODELS))
def test_a_ball_launched_straight_at_the_idle_defender_is_a_save(field_model: str) -> None:
    assert launched(field_model, 0.0) == "SAVE: ball moving back toward the shooter"
    assert launched(field_model, 0.0, bearing_deg=-40.0).startswith("SAVE")


@pytest.mark.parametrize(("field_model", "aim"), [("soccer_server", 5.0), ("robot_physics", 10.0)])
def test_a_ball_past_the_defender_between_the_posts_is_a_goal(field_model: str, aim: float) -> None:
    # Passes the defender 2.2 units (server) / 4.4 units (robots) wide, inside the posts.
    assert launched(field_model, aim) == "GOAL: ball past the defender, heading between the posts"
    assert launched(field_model, -aim).startswith("GOAL")


@pytest.mark.parametrize(("field_model", "aim"), [("soccer_server", 20.0), ("robot_physics", 25.0)])
def test_a_ball_past_the_defender_wide_of_the_posts_is_a_miss(field_model: str, aim: float) -> None:
    assert launched(field_model, aim) == "MISS: ball past the defender, heading wide"


@pytest.mark.parametrize("field_model", sorted(MODELS))
def test_a_ball_that_stops_short_is_a_miss_on_timeout(field_model: str) -> None:
    drill = InterceptDrill(launch="coach", max_time_s=3.0)
    arena = arena_for(field_model, drill)
    plan = drill.plan(arena)
    drill.place(arena, plan, 25.0 * plan.unit_m, 0.0)
    ball = arena.ball_state()
    arena.place_ball(ball.x, ball.y, 0.1 * ball.vx, 0.1 * ball.vy)
    verdict = play(arena, drill, minds={})
    assert (verdict.label, verdict.reason) == ("MISS", "ball stopped short")


@pytest.mark.parametrize(
    ("y", "label", "why"),
    [(2.0, "GOAL", "into the goal between the posts"), (10.0, "MISS", "end line wide")],
)
def test_server_ball_at_the_goal_line(y: float, label: str, why: str) -> None:
    drill = InterceptDrill(launch="coach")
    arena = arena_for("soccer_server", drill)
    drill.place(arena, drill.plan(arena), 25.0, 0.0)
    arena.place_player(DEFENDER, 0.0, -20.0, 0.0)
    arena.place_ball(52.3, y, 0.5, 0.0)  # wholly over the line x = 52.585 in the next cycle
    drill.start_judging(arena)
    verdict = play(arena, drill, minds={})
    assert verdict.label == label and why in verdict.reason


def test_server_goal_restarted_by_the_referee_is_a_goal() -> None:
    drill = InterceptDrill(launch="coach")
    arena = arena_for("soccer_server", drill)
    drill.place(arena, drill.plan(arena), 25.0, 0.0)
    arena.place_player(DEFENDER, 0.0, -20.0, 0.0)
    arena.place_ball(52.45, 1.0, 10.0, 0.0)  # over the line and scored within one cycle
    drill.start_judging(arena)
    verdict = play(arena, drill, minds={})
    assert (verdict.label, verdict.reason) == ("GOAL", "ball into the goal between the posts")
    assert arena.score() == (1, 0)  # the referee's count, though the ball is back at the centre


def test_robot_ball_bouncing_off_the_end_wall_is_a_miss_not_a_save() -> None:
    drill = InterceptDrill(launch="coach")
    arena = arena_for("robot_physics", drill)
    drill.place(arena, drill.plan(arena), 0.6, 0.0)
    hl = arena.facts.pitch.half_length_m
    arena.place_player(DEFENDER, hl - 0.05, -0.4, math.pi)  # û points toward +x and down
    arena.place_ball(hl - 0.15, 0.5, 1.0, 0.0)  # wide of the posts, at the end wall
    drill.start_judging(arena)
    verdict = play(arena, drill, minds={})
    assert (verdict.label, verdict.reason) == (
        "MISS",
        "ball reached the end line wide of the posts",
    )


# ----------------------------------------------------------------------------- trials


def test_registered_and_options_checked() -> None:
    assert DRILLS["intercept"] is InterceptDrill
    drill = make_drill("intercept", {"behaviour": "random", "ta_mode": "every_see"})
    assert drill.labels == ("SAVE", "GOAL", "MISS")
    for bad in (
        {"behaviour": "dance"},
        {"behaviour": "net"},
        {"ta_mode": "never"},
        {"launch": "cannon"},
        {"sector_deg": 100.0},
        {"max_time_s": 0.0},
        {"speed": 3.0},
        {"defender_kick": "maybe"},
    ):
        with pytest.raises(ValueError):
            make_drill("intercept", bad)


@pytest.mark.parametrize(
    ("field_model", "option", "reach"),
    [
        ("soccer_server", True, 1.885),
        ("soccer_server", False, None),
        ("soccer_server", "false", None),
        ("robot_physics", True, None),  # no kicker: the robot blocks
    ],
)
def test_defender_clears_only_where_it_can_kick(
    field_model: str, option: bool | str, reach: float | None
) -> None:
    drill = InterceptDrill(defender_kick=option)
    arena = arena_for(field_model, drill)
    rngs = TrialRngs.for_trial(0, 0)
    drill.setup(arena, rngs)
    minds = drill.minds(arena, rngs)
    assert drill.defender_mind is minds[DEFENDER]
    assert drill.defender_mind.kickable_distance_m == (
        None if reach is None else pytest.approx(reach)
    )
    assert (SHOOTER in minds) == (field_model == "soccer_server")  # robots: the coach launches


def test_placement_follows_figure_6() -> None:
    for index in range(20):
        drill = InterceptDrill()
        rngs = TrialRngs.for_trial(7, index)
        arena = make_arena("soccer_server", "soccer_server_1996", drill.players(), rngs)
        drill.setup(arena, rngs)
        ball, defender = arena.ball_state(), arena.player_state(DEFENDER)
        shooter = arena.player_state(SHOOTER)
        assert (defender.x, defender.y) == (48.5, 0.0)
        assert 20.0 <= math.hypot(ball.x - defender.x, ball.y - defender.y) <= 30.0
        bearing = math.atan2(defender.y - ball.y, defender.x - ball.x)
        assert abs(bearing) <= math.radians(45.0)
        gap = math.hypot(ball.x - shooter.x, ball.y - shooter.y)
        assert gap == pytest.approx(1.385)  # in the shooter's kickable area
        assert math.atan2(defender.y - shooter.y, defender.x - shooter.x) == pytest.approx(
            shooter.heading
        )
        assert ball.speed == 0.0


def test_noiseless_shots_from_the_shooter_hit_a_still_defender() -> None:
    spec = TrialSpec(drill="intercept", field_model="soccer_server", preset="soccer_server_1996")
    still = spec.with_options(behaviour="still")
    results = [run_trial(with_noise(still, 0.0), i) for i in range(8)]
    assert [r.label for r in results] == ["SAVE"] * 8
    assert all(r.data == () for r in results)  # still never decides: nothing recorded
    wide = with_noise(still.with_options(aim_offset_deg=4.0), 0.0)
    assert {run_trial(wide, i).label for i in range(8)} == {"GOAL"}  # 4° at 20-30 m misses it


def with_noise(spec: TrialSpec, noise: float) -> TrialSpec:
    return spec.with_field(ball_noise=noise)


def decided(percepts: list[Percept], drill: InterceptDrill, arena: Arena) -> list[Percept]:
    """The percepts a defender with the plan's decision period decides on (the others unseen)."""
    period = decision_ticks(drill.plan(arena), arena.facts)
    out: list[Percept] = []
    for p in percepts:
        if not out or p.tick >= out[-1].tick + period:
            out.append(p)
    return out


def test_the_robots_defender_decides_every_other_frame_under_the_task_rule() -> None:
    drill = InterceptDrill(behaviour="straight", scaling="task")
    rngs = TrialRngs.for_trial(2, 1)
    arena = make_arena("robot_physics", MODELS["robot_physics"], drill.players(), rngs)
    plan = drill.plan(arena)
    assert plan.scaling == "task"
    frame_ticks = round(arena.facts.sensor_period_s / arena.facts.dt_s)
    assert decision_ticks(plan, arena.facts) == 2 * frame_ticks


@pytest.mark.parametrize("field_model", sorted(MODELS))
def test_the_example_is_recorded_once_at_the_trigger(field_model: str) -> None:
    drill = InterceptDrill(behaviour="straight")
    rngs = TrialRngs.for_trial(2, 1)
    options = FieldOptions(ball_noise=0.05)
    arena = make_arena(field_model, MODELS[field_model], drill.players(), rngs, options)
    drill.setup(arena, rngs)
    minds = drill.minds(arena, rngs)
    seen: list[Percept] = []

    def log(p: Percept, actions: tuple[Action, ...]) -> None:
        if p.player == DEFENDER:
            seen.append(p)

    play(arena, drill, minds, decisions=log)
    trigger = drill.plan(arena).trigger_distance_m
    sightings = [p for p in decided(seen, drill, arena) if p.ball is not None]
    first = next(i for i, p in enumerate(sightings) if p.ball and p.ball.distance_m <= trigger)
    assert first > 0
    now, before = sightings[first].ball, sightings[first - 1].ball
    assert now is not None and before is not None
    assert drill.data() == (now.distance_m, now.angle_rad, before.distance_m, 0.0)


def test_random_ta_lies_within_45_degrees_and_straight_gives_zero() -> None:
    spec = TrialSpec(drill="intercept", field_model="soccer_server", preset="soccer_server_1996")
    random = [run_trial(spec.with_options(behaviour="random"), i).data for i in range(40)]
    tas = [d[3] for d in random if d]
    assert len(tas) >= 35
    assert all(abs(ta) <= math.radians(45.0) for ta in tas)
    assert max(tas) - min(tas) > math.radians(45.0)
    straight = [run_trial(spec.with_options(behaviour="straight"), i).data for i in range(10)]
    assert all(d and d[3] == 0.0 for d in straight)


@pytest.mark.parametrize("field_model", sorted(MODELS))
def test_trials_are_a_function_of_their_seed(field_model: str) -> None:
    spec = TrialSpec(
        drill="intercept", field_model=field_model, preset=MODELS[field_model], seed=4
    ).with_options(behaviour="random")
    spec = with_noise(spec, 0.05)
    first = [run_trial(spec, i) for i in range(3)]
    assert [run_trial(spec, i) for i in range(3)] == first
    assert len({r.data for r in first}) == 3  # different trials, different situations
    assert all(r.label in ("SAVE", "GOAL", "MISS") for r in first)


def test_robots_with_a_kicker_shoot_at_the_planned_speed() -> None:
    from field_models.robot_physics import model
    from field_models.robot_physics.arena import RobotArena
    from field_models.robot_physics.config import KickerConfig

    base = model.load("small_size_1997", FieldOptions(perfect_perception=True, ball_noise=0.0))
    kicker = KickerConfig(reach_m=0.01, max_speed_mps=3.0, half_angle_rad=0.3)
    preset = dataclasses.replace(base, robot=dataclasses.replace(base.robot, kicker=kicker))
    facts = model.facts(preset)
    plan = launch_plan(facts)
    assert plan.launch == "shooter"
    assert plan.kick_power == pytest.approx(100.0 * plan.launch_speed_mps / 3.0)
    drill = InterceptDrill(behaviour="still")
    rngs = TrialRngs.for_trial(0, 0)
    arena = RobotArena(preset, facts, drill.players(), rngs)
    drill.setup(arena, rngs)
    minds = drill.minds(arena, rngs)
    assert isinstance(minds[SHOOTER], AimedShooterMind)
    top = 0.0
    for _ in range(40):
        for p in arena.step():
            if p.player in minds:
                arena.submit(p.player, minds[p.player].act(p))
        top = max(top, arena.ball_state().speed)
    assert top == pytest.approx(plan.launch_speed_mps, rel=0.02)
    assert play(arena, drill, minds).label == "SAVE"  # straight at the still defender


# ----------------------------------------------------------------------------- the SAVE rule


class ScriptedBall:
    """An arena stand-in whose ball the test moves by hand; the judge reads only these."""

    def __init__(self, field_model: str) -> None:
        self.facts = field_facts(field_model)
        self.ball = BodyState(0.0, 0.0, 0.0)
        self.tick = 0
        self.defender = BodyState(0.0, 0.0, 0.0)

    def ball_state(self) -> BodyState:
        return self.ball

    def player_state(self, ref: PlayerRef) -> BodyState:
        return self.defender if ref == DEFENDER else BodyState(-1.0, 0.0, 0.0)

    def score(self) -> tuple[int, int]:
        return (0, 0)

    def move(self, x: float, y: float, vx: float, vy: float) -> None:
        self.ball = BodyState(x, y, 0.0, vx, vy)
        self.tick += 1


def judged(field_model: str, backward_share: float) -> tuple[str | None, ScriptedBall, Any]:
    """A ball rolling at the defender along +x, then leaving with the given backward share."""
    arena = ScriptedBall(field_model)
    unit = arena.facts.unit_m
    drill = InterceptDrill(launch="coach")
    x_def = drill.plan_for(arena.facts).defender_x_m
    arena.defender = BodyState(x_def, 0.0, math.pi)
    arena.ball = BodyState(x_def - 20 * unit, 0.0, 0.0)
    drill.start_judging(arena)  # type: ignore[arg-type]
    speed = 10 * unit
    arena.move(x_def - 10 * unit, 0.0, speed, 0.0)
    assert drill.judge(arena) is None  # type: ignore[arg-type]
    along = -backward_share * speed
    side = math.sqrt(speed**2 - along**2)
    arena.move(x_def - 2 * unit, 0.5 * unit, along, side)
    verdict = drill.judge(arena)  # type: ignore[arg-type]
    return (None if verdict is None else verdict.label), arena, drill


@pytest.mark.parametrize("field_model", sorted(MODELS))
def test_a_save_needs_a_clear_backward_component(field_model: str) -> None:
    assert judged(field_model, 0.51)[0] == "SAVE"
    assert judged(field_model, 0.49)[0] is None  # glanced: judged on from here


@pytest.mark.parametrize("field_model", sorted(MODELS))
def test_a_glancing_ball_that_rolls_on_into_the_goal_is_a_goal(field_model: str) -> None:
    label, arena, drill = judged(field_model, 0.2)
    assert label is None
    pitch = arena.facts.pitch
    arena.move(pitch.half_length_m - pitch.player_radius_m, 0.0, 1.0, 0.0)  # past, rolling in
    assert drill.judge(arena).label == "GOAL"


@pytest.mark.parametrize("field_model", sorted(MODELS))
def test_a_glancing_ball_that_stops_short_is_a_save(field_model: str) -> None:
    label, arena, drill = judged(field_model, 0.2)
    assert label is None
    verdict = drill.timeout(arena)
    assert verdict.label == "SAVE" and "deflected" in verdict.reason


def test_the_ablation_options_change_the_plan_and_nothing_else() -> None:
    facts = field_facts("robot_physics", "small_size_1997")
    plan = InterceptDrill(scaling="task").plan_for(facts)
    changed = InterceptDrill(
        scaling="task", trigger_scale=1.5, launch_speed_scale=0.5, turn_tolerance_deg=0.0
    ).plan_for(facts)
    assert changed.trigger_distance_m == pytest.approx(1.5 * plan.trigger_distance_m)
    assert changed.launch_speed_mps == pytest.approx(0.5 * plan.launch_speed_mps)
    assert changed.turn_tolerance_rad == 0.0
    assert changed.arrival_time_s > plan.arrival_time_s
    same = ("noise_period_s", "decision_period_s", "min_distance_m", "defender_x_m")
    assert all(getattr(changed, name) == getattr(plan, name) for name in same)
    with pytest.raises(ValueError, match="trigger_scale"):
        InterceptDrill(trigger_scale=0.0)
    with pytest.raises(ValueError, match="turn_tolerance_deg"):
        InterceptDrill(turn_tolerance_deg=-1.0)
    with pytest.raises(ValueError, match=r"launch_speed_scale=0\.01"):
        InterceptDrill(scaling="task", launch_speed_scale=0.01).plan_for(facts)  # stops short
