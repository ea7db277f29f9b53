"""The runner's loop: minds act on percepts; a mind that is done gets no more of them."""

from __future__ import annotations

import math

import pytest

from field_models.protocol import Percept
from robotsoccer.drills.shootout import GOALIE, SHOOTER, ShootoutDrill
from robotsoccer.runs.runner import TrialResult, TrialSpec, build_trial, play


class Counting:
    def __init__(self, done_after: int | None = None) -> None:
        self.seen: list[int] = []
        self.done = False
        self.done_after = done_after

    def act(self, percept: Percept) -> tuple:
        self.seen.append(percept.tick)
        if self.done_after is not None and len(self.seen) >= self.done_after:
            self.done = True
        return ()


@pytest.mark.parametrize("field_model", ["robot_physics", "soccer_server"])
def test_a_mind_that_is_done_gets_no_more_percepts(field_model: str) -> None:
    spec = TrialSpec(drill="shootout", field_model=field_model)
    rngs, _, arena = build_trial(spec, 0)
    drill = ShootoutDrill(max_time_s=2.0)
    drill.setup(arena, rngs)
    quitter, stayer = Counting(done_after=2), Counting()
    play(arena, drill, {SHOOTER: quitter, GOALIE: stayer})
    assert len(quitter.seen) == 2
    assert len(stayer.seen) > 2


def test_trial_results_round_trip_through_the_csv_table() -> None:
    result = TrialResult(
        3, "SAVE", "why, with a comma", 17, 1.7000000000000002, (0.1, -2.5e-3), (("a", 1e-3),)
    )
    assert TrialResult.from_csv_row(result.csv_row()) == result
    assert result.measure("a") == 1e-3 and math.isnan(result.measure("b"))
    empty = TrialResult(4, "MISS", "", 1, 0.1)
    assert TrialResult.from_csv_row(empty.csv_row()) == empty
