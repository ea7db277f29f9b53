"""The transfer matrix: every field's net on every field, paired with the baselines."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np

from learning.pass_features import ATTRIBUTE_NAMES, PASS_SCHEMA
from learning.pass_tree_file import save_pass_tree
from learning.pass_tree_grow import fit_pass_tree
from robotsoccer.experiments.context import RunContext
from robotsoccer.experiments.layer1_plan import plan_for, seeds_for
from robotsoccer.experiments.layer2 import Layer2Plan
from robotsoccer.experiments.transfer import (
    plot_transfer,
    run_transfer,
    run_transfer_layer2,
    transfer_conditions,
    transfer_markdown,
)
from tests.robotsoccer.skills.test_intercept import net_file

MODELS = [("soccer_server", "soccer_server_1996"), ("robot_physics", "small_size_1997")]


def nets(folder: Path) -> dict[str, Path]:
    return {
        "soccer_server": net_file(folder / "s.npz", seed=1, preset="soccer_server_1996"),
        "robot_physics": net_file(
            folder / "r.npz", seed=2, preset="small_size_1997", field="robot_physics"
        ),
    }


def test_only_the_cross_field_cells_are_transfer_runs(tmp_path: Path) -> None:
    plan = dataclasses.replace(plan_for(True), eval_trials=10)
    rows = transfer_conditions(MODELS, nets(tmp_path), plan, seeds_for(0))
    assert len(rows) == 2 * (2 + 2)
    for tested, defender, trained, cond in rows:
        options = dict(cond.spec.drill_options)
        assert cond.spec.field_model == tested and cond.spec.seed == 0
        assert options.get("transfer", False) == (defender == "net" and trained != tested)


def test_the_matrix_runs_and_reports_paired_cells(tmp_path: Path) -> None:
    plan = dataclasses.replace(plan_for(True), eval_trials=12)
    lines: list[str] = []
    cells = run_transfer(
        MODELS, nets(tmp_path), plan, RunContext(tmp_path, seeds_for(0), 1, lines.append)
    )
    assert len(cells) == 8 and all(len(c.results) == 12 for c in cells)
    for tested, _ in MODELS:  # every cell of a test field ran the same placements
        indices = {tuple(r.index for r in c.results) for c in cells if c.tested_on == tested}
        assert indices == {tuple(range(12))}
    heatmap = plot_transfer(cells, tmp_path / "plots" / "transfer.png", "saves")
    assert heatmap is not None and heatmap.stat().st_size > 1000
    text = transfer_markdown(cells, plan.noise, [heatmap])
    assert "| net trained on soccer_server |" in text and "| straight |" in text
    assert text.count("minus the native net") == 2 and "n = 12 trials per cell" in text
    assert (tmp_path / "results" / "transfer" / "robot_physics").is_dir()
    again = run_transfer(
        MODELS, nets(tmp_path), plan, RunContext(tmp_path, seeds_for(0), 1, lines.append)
    )
    assert [c.results for c in again] == [c.results for c in cells]  # resumed from the tables


def test_the_layer2_matrix_moves_only_the_passer_tree(tmp_path: Path) -> None:
    rng = np.random.default_rng(0)
    x = rng.uniform(0, 30, (60, len(ATTRIBUTE_NAMES)))
    y = np.where(x[:, 0] < 15, "SUCCESS", "FAILURE")
    tree = fit_pass_tree(x, y, ATTRIBUTE_NAMES, schema=PASS_SCHEMA)
    trees = {
        model: save_pass_tree(tree, tmp_path / f"{model}.json", {"field_model": model, "preset": p})
        for model, p in MODELS
    }
    plan = Layer2Plan("test", collect_trials=0, eval_trials=6)
    ctx = RunContext(tmp_path, seeds_for(0), 1)
    cells = run_transfer_layer2(MODELS, nets(tmp_path), trees, plan, ctx)
    assert len(cells) == 2 * 4 and all(c.success == "SUCCESS" for c in cells)
    for cell in cells:
        assert {r.label for r in cell.results} <= {"SUCCESS", "FAILURE", "MISS"}
    text = transfer_markdown(cells, 0.05)
    assert "### Layer 2: pass (success)" in text and "| tree trained on robot_physics |" in text
    assert text.count("minus the native tree") == 2
