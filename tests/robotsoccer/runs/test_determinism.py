"""One seed per trial: results and detections depend on the seed alone, not on worker count."""

from __future__ import annotations

import dataclasses

import pytest

from field_models.protocol import LEFT, RIGHT, PlayerRef
from field_models.registry import make_arena
from field_models.seeding import TrialRngs
from robotsoccer.runs.pool import run_trials
from robotsoccer.runs.runner import TrialSpec, run_trial

SPEC = TrialSpec(drill="shootout", field_model="robot_physics", seed=7)


def test_same_seed_gives_identical_trial_results() -> None:
    assert [run_trial(SPEC, i) for i in range(4)] == [run_trial(SPEC, i) for i in range(4)]


def test_different_seeds_give_different_trials() -> None:
    a = [run_trial(SPEC, i) for i in range(4)]
    b = [run_trial(dataclasses.replace(SPEC, seed=8), i) for i in range(4)]
    assert a != b


def percepts(seed: int) -> list:
    """Every percept of a 1 s run: they carry the camera's noise and misses."""
    players = (PlayerRef(LEFT, 1), PlayerRef(RIGHT, 1))
    arena = make_arena("robot_physics", "small_size_1997", players, TrialRngs.for_trial(seed, 0))
    arena.place_player(players[0], -0.5, 0.0, 0.0)
    arena.place_player(players[1], 0.5, 0.0, 3.14)
    arena.place_ball(0.0, 0.0, 0.5, 0.2)
    seen = []
    for _ in range(240):
        seen.extend(arena.step())
    return seen


def test_same_seed_gives_identical_detections_and_other_seeds_do_not() -> None:
    first = percepts(3)
    frames = len(range(8, 240 - 12 + 1, 8))  # 30 Hz captures delivered 50 ms (12 ticks) later
    assert len(first) == 2 * frames  # one percept per robot per frame
    assert first == percepts(3)
    assert first != percepts(4)


@pytest.mark.slow
@pytest.mark.parametrize("field_model", ["robot_physics", "soccer_server"])
@pytest.mark.parametrize("drill", ["shootout", "intercept"])
def test_one_and_two_workers_give_identical_tables(tmp_path, drill: str, field_model: str) -> None:
    spec = TrialSpec(drill=drill, field_model=field_model, seed=7).with_field(ball_noise=0.05)
    one = run_trials(spec, 12, workers=1, results_path=tmp_path / "one.csv", progress=False)
    two = run_trials(
        spec, 12, workers=2, results_path=tmp_path / "two.csv", progress=False, chunk_size=2
    )
    assert one == two
    rows = lambda p: sorted((tmp_path / p).read_text().splitlines())  # noqa: E731
    assert rows("one.csv") == rows("two.csv")
