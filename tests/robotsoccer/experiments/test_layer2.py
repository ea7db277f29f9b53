"""Layer 2's pipeline on a small plan: collect, train, test, report, resume."""

from __future__ import annotations

import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from learning.datasets import Provenance
from learning.pass_dataset import PassDataset
from learning.pass_features import ATTRIBUTE_NAMES, PASS_SCHEMA
from learning.pass_tree_file import load_pass_tree
from robotsoccer.experiments.context import RunContext
from robotsoccer.experiments.layer1_plan import seeds_for
from robotsoccer.experiments.layer2 import (
    Layer2Plan,
    Layer2Section,
    comparison_lines,
    layer2_markdown,
    run_layer2_model,
    table2_lines,
)
from robotsoccer.experiments.report_records import OWN_SETTING, PAPER_SETTING
from robotsoccer.runs.runner import TrialResult

PLAN = Layer2Plan("test", collect_trials=60, eval_trials=16, tree_depth_shown=2)


@pytest.fixture(scope="module")
def net(tmp_path_factory: pytest.TempPathFactory) -> Path:
    from learning.interception import InterceptionModel

    rng = np.random.default_rng(0)
    x = rng.uniform([5, -0.2, 5], [14, 0.2, 16], (40, 3))
    origin = Provenance("soccer_server", "soccer_server_1996", 0, 0.05, "random", 100)
    path = tmp_path_factory.mktemp("net") / "net_40.npz"
    return InterceptionModel(epochs=5).fit(x, 0.3 * x[:, 1]).save(path, origin)


@pytest.fixture(scope="module")
def run(net: Path, tmp_path_factory: pytest.TempPathFactory):
    out = tmp_path_factory.mktemp("layer2")
    lines: list[str] = []
    ctx = RunContext(out, seeds_for(0), 2, lines.append)
    section = run_layer2_model(("soccer_server", "soccer_server_1996"), net, PLAN, ctx)
    return out, section, lines


def test_the_pipeline_leaves_a_dataset_a_tree_and_every_condition(run) -> None:
    out, section, _ = run
    dataset = PassDataset.load(out / "datasets" / "soccer_server" / "passes.npz")
    assert len(dataset) == section.dataset_rows > 0
    assert dataset.provenance["field_model"] == "soccer_server"
    assert dataset.provenance["interceptor_net"] == "net_40.npz"
    tree, provenance = load_pass_tree(
        out / "models" / "soccer_server" / "pass_tree.json", schema=PASS_SCHEMA
    )
    assert tree.n_nodes == section.tree_nodes and provenance["rows"] == len(dataset)
    assert tree.feature_names == ATTRIBUTE_NAMES
    assert 0.0 <= section.training_error <= 1.0
    assert set(section.results) == {
        "tree", "boost", "tree_passer_only", "random", "closest", "analytic", "tree_no_defenders"
    }  # fmt: skip
    # The passer-only tree never reads the receivers' half.
    own, _ = load_pass_tree(out / "models" / "soccer_server" / "pass_tree_passer_only.json")
    assert all(own.feature_names[f].startswith("passer") for f in own.feature if f >= 0)
    assert all(len(r) == PLAN.eval_trials for r in section.results.values())
    # The tree run records its confidence; a random run has none.
    assert all(0.0 < r.data[1] < 1.0 for r in section.results["tree"] if r.data)
    assert all(np.isnan(r.data[1]) for r in section.results["random"] if r.data)


def test_the_conditions_share_their_placements(run) -> None:
    out, _, _ = run
    csvs = out / "results" / "soccer_server" / "layer2"
    assert {p.stem for p in csvs.glob("*.csv")} >= {"tree", "random", "collect_random"}


def test_the_report_has_table_2_beside_the_paper(run) -> None:
    _, section, _ = run
    text = layer2_markdown([section], PLAN)
    assert "## Layer 2" in text and "**Table 2**" in text
    table = table2_lines(section)
    assert table[2].startswith("| overall |") and "| 65 |" in table[2]
    assert any(line.startswith("| .8-.9 |") for line in table)
    assert "87 nodes" in text and "26%" in text  # the paper's tree beside ours
    assert "```" in text  # the printed tree
    assert "What the receivers' reports add" in text


def test_the_plots_are_drawn(run) -> None:
    from robotsoccer.experiments.plots_layer2 import layer2_plots

    out, section, _ = run
    drawn = layer2_plots([section], out)
    assert [path for _, path in drawn] == ["plots/table2.png", "plots/reliability.png"]
    for _, path in drawn:
        assert (out / path).read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert layer2_plots([], out) == []


def test_a_second_run_resumes_without_running_trials(run, net: Path) -> None:
    out, first, _ = run
    ctx = RunContext(out, seeds_for(0), 1)
    again = run_layer2_model(("soccer_server", "soccer_server_1996"), net, PLAN, ctx)
    assert all(stage.trials == 0 for stage in again.stages)
    for name, results in first.results.items():
        assert [r.label for r in results] == [r.label for r in again.results[name]]


def test_learn_pass_refuses_a_net_from_another_field(net: Path, tmp_path: Path) -> None:
    done = subprocess.run(
        [sys.executable, "-m", "robotsoccer.cli", "learn", "pass", "--field", "robot_physics",
         "--net", str(net), "--quick", "--out", str(tmp_path / "x")],
        capture_output=True, text=True, timeout=120,
    )  # fmt: skip
    assert done.returncode == 2
    assert len(done.stderr.strip().splitlines()) == 1 and "transfer=true" in done.stderr
    assert not (tmp_path / "x").exists()


def _passes(success: int, failure: int, miss: int, confidence: float) -> list[TrialResult]:
    labels = ["SUCCESS"] * success + ["FAILURE"] * failure + ["MISS"] * miss
    return [TrialResult(i, label, "", 1, 0.1, (0.0, confidence)) for i, label in enumerate(labels)]


def _cells(line: str) -> list[str]:
    return [cell.strip() for cell in line.strip().strip("|").split("|")]


def test_the_layer2_tables_say_how_ours_stands_against_the_paper() -> None:
    section = Layer2Section("soccer_server", "soccer_server_1996", "net.npz")
    section.results = {
        # Forced tree: 65 / 26 / 9 of 1000 beside the paper's 65 / 26 / 8: all agree.
        "tree": _passes(650, 260, 90, 0.75),
        "random": _passes(400, 500, 100, math.nan),  # 40.0 [37.0, 43.1] vs 51: below
        "closest": _passes(700, 250, 50, math.nan),  # 70.0 [67.1, 72.7] vs 64: above
        "tree_no_defenders": _passes(860, 100, 40, 0.9),  # 86: agrees, setting says still
    }
    comparison = {_cells(line)[0]: _cells(line) for line in comparison_lines(section, PLAN)[2:]}
    header = _cells(comparison_lines(section, PLAN)[0])
    assert header[-2:] == ["setting", "vs paper"]
    assert comparison["DT, forced to pass (Table 2)"][-2:] == [PAPER_SETTING, "agrees"]
    assert comparison["random receiver"][-1] == "below (-11.0 pts)"
    assert comparison["closest teammate"][-1] == "above (+6.0 pts)"
    assert comparison["DT, defenders still"][-2:] == [
        f"{PAPER_SETTING}; defenders still (paper: no defenders)",
        "agrees",
    ]
    # No paper figure: dashes.
    assert comparison["gradient-boosted trees (ours)"][-2:] == ["—", "—"]
    table = {_cells(line)[0]: _cells(line) for line in table2_lines(section)[2:]}
    assert table["overall"][-2:] == [PAPER_SETTING, "agrees"]
    # Every pass sits in .7-.8 (paper 63 / 29 / 8): 65.0 [62.0, 67.9] agrees, 26.0 [23.4,
    # 28.8] lies below 29, 9.0 [7.4, 10.9] agrees.
    assert table[".7-.8"][-1] == "agrees / below (-3.0 pts) / agrees"
    assert table[".8-.9"][-1] == "—"  # no trials in the bin
    assert table["outside .6-.9"][-2:] == ["—", "—"]
    robots = Layer2Section("robot_physics", "small_size_1997", "net.npz")
    robots.results = section.results
    assert _cells(table2_lines(robots)[2])[-2] == OWN_SETTING
