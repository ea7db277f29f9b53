"""The set play of Figure 15 (issue 11, first part): it runs on both field models, by seed."""

from __future__ import annotations

import pytest

from field_models.protocol import Heard, Percept, PlayerRef, SeenBall, SeenLandmark
from robotsoccer.drills import make_drill
from robotsoccer.runs.runner import TrialSpec, run_trial
from robotsoccer.skills.setplay import (
    WINGER_CUE,
    chase,
    dribble,
    opponent_in_path,
    shoot,
)

ME = PlayerRef("left", 1)


def percept(ball: tuple[float, float] | None, *, goal: float | None = None, heard=()) -> Percept:
    marks = () if goal is None else (SeenLandmark("g r", 30.0, goal),)
    seen = None if ball is None else SeenBall(ball[0], ball[1])
    return Percept(ME, 10, 10, seen, (), tuple(Heard(t) for t in heard), marks)


def test_the_skills_chase_dribble_and_shoot_by_the_ball_and_goal() -> None:
    assert type(chase(percept(None))[0]).__name__ == "Turn"
    assert type(chase(percept((5.0, 0.5)))[0]).__name__ == "Turn"
    assert type(chase(percept((5.0, 0.0)))[0]).__name__ == "Dash"
    kick = dribble(percept((1.0, 0.0)), 0.3, 1.5, 20.0)[0]
    assert type(kick).__name__ == "Kick" and kick.direction_rad == pytest.approx(0.3)
    assert type(dribble(percept((3.0, 0.0)), 0.3, 1.5, 20.0)[0]).__name__ == "Dash"
    assert type(shoot(percept((1.0, 0.0)), True, 1.5, 100.0)[0]).__name__ == "Turn"
    shot = shoot(percept((1.0, 0.0), goal=-0.2), True, 1.5, 100.0)[0]
    assert type(shot).__name__ == "Kick" and shot.direction_rad == pytest.approx(-0.2)
    assert not opponent_in_path(percept((1.0, 0.0)), 0.0, 10.0)
    assert WINGER_CUE == "wing"


def test_the_drill_refuses_bad_options() -> None:
    with pytest.raises(ValueError, match="model file"):
        make_drill("setplay", {"chooser": "tree"})
    with pytest.raises(ValueError, match="max_time_s"):
        make_drill("setplay", {"max_time_s": 0.0})


@pytest.mark.parametrize(
    ("model", "preset"),
    [("soccer_server", "soccer_server_1996"), ("robot_physics", "small_size_1997")],
)
def test_a_play_runs_and_repeats_by_seed(model: str, preset: str) -> None:
    spec = TrialSpec(drill="setplay", field_model=model, preset=preset, seed=3)
    first = [run_trial(spec, i) for i in range(3)]
    assert [run_trial(spec, i) for i in range(3)] == first
    for result in first:
        assert result.label in ("GOAL", "SHOT", "INTERCEPTED", "OUT", "TIMEOUT")
        measures = dict(result.measures)
        assert 0 <= measures["passes"] <= 3 and measures["goal"] in (0.0, 1.0)
        assert measures["goal"] <= measures["shot"] or result.label == "GOAL"
