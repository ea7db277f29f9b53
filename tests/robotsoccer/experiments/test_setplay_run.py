"""``robotsoccer setplay`` as a pipeline (robotsoccer.experiments.setplay_run), without argparse."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from robotsoccer.experiments.setplay_run import SetPlayRun, run_setplay

FIELDS = (("soccer_server", "soccer_server_1996"),)


def test_the_folder_is_named_after_client_plan_and_seed(tmp_path: Path) -> None:
    assert SetPlayRun(FIELDS, seed=3).folder == Path("runs/setplay-seed3")
    assert SetPlayRun(FIELDS, quick=True, client="cycle").folder == Path(
        "runs/setplay-cycle-quick-seed0"
    )
    assert SetPlayRun(FIELDS, out=tmp_path).folder == tmp_path


def test_missing_layers_are_refused_when_named_and_said_when_defaulted(tmp_path: Path) -> None:
    warnings: list[str] = []
    lacks = re.escape("lacks a field's net_750.npz or pass_tree.json")
    with pytest.raises(ValueError, match=lacks):
        SetPlayRun(FIELDS, models=tmp_path).layers(warnings.append)
    assert SetPlayRun(FIELDS, seed=987654).layers(warnings.append) is None
    assert warnings == [
        "no trained layers in runs/transfer-seed987654/models: the baseline minds only"
    ]
    for name in ("net_750.npz", "pass_tree.json"):
        (tmp_path / "models" / "soccer_server").mkdir(parents=True, exist_ok=True)
        (tmp_path / "models" / "soccer_server" / name).write_text("")
    assert SetPlayRun(FIELDS, models=tmp_path).layers(warnings.append) == tmp_path / "models"


def test_a_tiny_study_writes_its_report_and_refuses_a_second_run(tmp_path: Path) -> None:
    out = tmp_path / "run"
    request = SetPlayRun(FIELDS, seed=987654, plays=2, out=out, workers=1)
    outcome = run_setplay(request, lambda line: None, lambda line: None)
    assert outcome.report == out / "report.md" and outcome.report.is_file()
    assert outcome.lines == (f"report: {out / 'report.md'}",)
    with pytest.raises(ValueError):
        run_setplay(request, lambda line: None, lambda line: None)
