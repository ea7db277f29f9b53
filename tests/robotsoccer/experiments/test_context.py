"""The experiment context: one record of folder, seeds, workers, log and progress."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import pytest

from robotsoccer.experiments.context import RunContext, seeds_for


def test_a_context_from_one_seed_carries_both_experiment_seeds(tmp_path: Path) -> None:
    lines: list[str] = []
    ctx = RunContext.for_seed(tmp_path, 7, 2, lines.append, created_by="tests")
    assert ctx.seeds == seeds_for(7) and ctx.seeds.evaluation == 7
    assert ctx.seeds.collection != 7  # nets are never tested on their training placements
    assert (ctx.workers, ctx.progress, ctx.created_by) == (2, False, "tests")
    ctx.log("a line")
    assert lines == ["a line"]


def test_a_study_part_moves_the_folder_and_keeps_the_rest(tmp_path: Path) -> None:
    ctx = RunContext.for_seed(tmp_path, 3, 1)
    lead = ctx.at(tmp_path / "lead")
    assert lead.out == tmp_path / "lead"
    assert dataclasses.replace(lead, out=ctx.out) == ctx
    assert lead.results_dir("robot_physics") == tmp_path / "lead" / "results" / "robot_physics"
    assert ctx.models_dir("soccer_server") == tmp_path / "models" / "soccer_server"
    assert ctx.made_by("robotsoccer transfer").created_by == "robotsoccer transfer"


def test_a_context_is_immutable(tmp_path: Path) -> None:
    ctx = RunContext.for_seed(tmp_path, 0)
    with pytest.raises(dataclasses.FrozenInstanceError):
        ctx.workers = 4  # type: ignore[misc]
    ctx.log("dropped")  # the default log drops lines
