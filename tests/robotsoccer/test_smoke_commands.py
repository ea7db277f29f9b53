"""Every command's quick plan runs to its report on both fields, on a tiny budget.

The plans are shrunk in process (the plan factories are patched), so the pipelines, reports and
plots run on a handful of trials, where shares of 0 and n and empty rows come up: the cases that
once crashed ``reproduce --quick`` (an error bar below 0).
"""

from __future__ import annotations

import csv
from pathlib import Path

import pytest

import robotsoccer.experiments.layer1_plan as layer1_plan
import robotsoccer.experiments.layer2 as layer2
import robotsoccer.experiments.lead_study as lead_study
import robotsoccer.experiments.team_study as team_study
import robotsoccer.experiments.transfer_study as transfer_study
from robotsoccer.cli import main

TINY_LAYER1 = layer1_plan.Layer1Plan(
    name="tiny",
    eval_trials=12,
    collect_saves=20,
    collect_batch=100,
    training_sizes=(10,),
    net_examples=10,
    noises=(0.05,),
    latencies_s=(0.05,),
    epochs=10,
    record_saves=0,
    record_goals=0,
)
TINY_LAYER2 = layer2.Layer2Plan("tiny", collect_trials=60, eval_trials=12)
TINY_LEAD = lead_study.LeadPlan(
    "tiny", eval_trials=10, collect_saves=8, collect_batch=40, epochs=10
)
TINY_TEAM = team_study.TeamPlan("tiny", 2, 2, 5.0, 0.3, 0.05, 2, 5.0, 2, True, 0.95)


@pytest.fixture
def tiny_plans(monkeypatch: pytest.MonkeyPatch) -> None:
    for module in (layer1_plan, transfer_study):
        monkeypatch.setattr(module, "plan_for", lambda quick: TINY_LAYER1)
    for module in (layer2, transfer_study):
        monkeypatch.setattr(module, "layer2_plan", lambda quick: TINY_LAYER2)
    monkeypatch.setattr(lead_study, "plan_for", lambda quick: TINY_LEAD)
    monkeypatch.setattr(team_study, "plan_for", lambda quick, every=False: TINY_TEAM)


def test_reproduce_quick_reaches_its_report_with_the_transfer_study(
    tmp_path: Path, tiny_plans: None
) -> None:
    out = tmp_path / "reproduce"
    args = ["reproduce", "--quick", "--out", str(out), "--workers", "1"]
    assert main([*args, "--no-ablations", "--no-gap-closing"]) == 0
    report = (out / "report.md").read_text()
    parts = ("soccer_server", "robot_physics", "Table 2", "lead decision", "Transfer", "Layer 3")
    for part in parts:
        assert part in report, part
    assert (out / "plots" / "figure7.png").stat().st_size > 1000


def test_the_set_play_and_a_match_reach_their_reports(tmp_path: Path) -> None:
    setplay = tmp_path / "setplay"
    assert (
        main(["setplay", "--quick", "--plays", "4", "--out", str(setplay), "--workers", "1"]) == 0
    )
    assert (setplay / "report.md").exists()
    for field in ("robot_physics", "soccer_server"):
        out = tmp_path / f"match-{field}"
        args = ["match", "--field", field, "--left", "baseline", "--right", "baseline"]
        assert (
            main([*args, "--half-time", "5", "--out", str(out), "--quiet", "--workers", "1"]) == 0
        )
        with (out / "results.csv").open(newline="") as table:
            assert len(list(csv.DictReader(table))) == 1
