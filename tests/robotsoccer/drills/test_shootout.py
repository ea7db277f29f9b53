"""The demo drill's coach labels scripted shots correctly (minds idle, ball launched by hand)."""

from __future__ import annotations

import math

import pytest

from field_models.arena import FieldOptions
from field_models.registry import make_arena
from field_models.seeding import TrialRngs
from robotsoccer.drills.shootout import GOALIE, SHOOTER, ShootoutDrill
from robotsoccer.runs.runner import play


def scripted(ball_y: float, goalie_y: float, speed: float = 1.5, aim_y: float | None = None):
    drill = ShootoutDrill(max_time_s=6.0)
    arena = make_arena(
        "robot_physics",
        "small_size_1997",
        drill.players(),
        TrialRngs.for_trial(0, 0),
        FieldOptions(perfect_perception=True),
    )
    hl = arena.facts.pitch.half_length_m
    arena.place_player(SHOOTER, -hl + 0.2, 0.6, 0.0)
    arena.place_player(GOALIE, hl - 0.1, goalie_y, math.pi)
    start_x = hl - 1.0
    target_y = ball_y if aim_y is None else aim_y
    dx, dy = hl + 0.1 - start_x, target_y - ball_y
    n = math.hypot(dx, dy)
    arena.place_ball(start_x, ball_y, speed * dx / n, speed * dy / n)
    return play(arena, drill, minds={})


def test_shot_past_the_goalie_between_the_posts_is_a_goal() -> None:
    assert scripted(ball_y=0.1, goalie_y=-0.5).label == "GOAL"


def test_shot_into_the_goalie_is_a_save() -> None:
    assert scripted(ball_y=0.0, goalie_y=0.0).label == "SAVE"


@pytest.mark.parametrize("aim_y", [0.45, -0.45])
def test_shot_wide_of_the_posts_is_a_miss(aim_y: float) -> None:
    verdict = scripted(ball_y=0.0, goalie_y=-0.6 * math.copysign(1, aim_y), aim_y=aim_y)
    assert verdict.label == "MISS"
    assert "wide" in verdict.reason


def test_shot_that_never_arrives_is_a_miss_on_timeout() -> None:
    verdict = scripted(ball_y=0.0, goalie_y=-0.5, speed=0.1)
    assert verdict.label == "MISS"
    assert "within" in verdict.reason
