"""``match`` and ``learn team`` as pipelines, called without the command line."""

from __future__ import annotations

import dataclasses
import json
import re
from pathlib import Path

import pytest

import robotsoccer.experiments.match_run as match_run
import robotsoccer.experiments.team_study as team_study
from learning.tpot import TpotTable, save_table
from robotsoccer.experiments.context import RunInterrupted
from robotsoccer.experiments.match_run import LayerFiles, MatchRun, run_match
from robotsoccer.experiments.team_run import TeamRun, run_learn_team
from robotsoccer.runs.runner import TrialResult
from tests.robotsoccer.drills.test_passing import _tree_file
from tests.robotsoccer.skills.test_intercept import net_file

FIELD = "soccer_server"
TINY_TEAM = team_study.TeamPlan("tiny", 2, 2, 5.0, 0.3, 0.05, 2, 5.0, 2)
"""One round of two short training games, two-game series."""


@pytest.fixture
def layers(tmp_path: Path) -> LayerFiles:
    net = net_file(tmp_path / "net.npz", preset="soccer_server_1996")
    return LayerFiles(net=net, tree=_tree_file(tmp_path, FIELD))


def test_one_match_plays_the_two_kinds_named_into_its_folder(tmp_path: Path) -> None:
    out = tmp_path / "m"
    request = MatchRun(FIELD, left="baseline", right="baseline", half_time_s=1.0, out=out)
    outcome = run_match(dataclasses.replace(request, progress=False))
    assert outcome.out == out and outcome.games == ()
    result = outcome.result
    assert isinstance(result, TrialResult) and result.time_s == pytest.approx(2.0)
    assert outcome.lines[0].startswith(f"{result.label}: {result.reason} (2 simulated s in ")
    assert outcome.lines[1:] == tuple(f"  {name} = {v:g}" for name, v in result.measures)
    assert (out / "results.csv").exists() and not (out / "config.json").exists()


def test_a_series_writes_its_config_and_report_and_shows_them(
    tmp_path: Path, layers: LayerFiles
) -> None:
    out = tmp_path / "s"
    request = MatchRun(FIELD, games=3, half_time_s=1.0, layers=layers, out=out, workers=1)
    outcome = run_match(dataclasses.replace(request, progress=False))
    assert len(outcome.games) == 3 and outcome.result is None
    config = json.loads((out / "config.json").read_text())
    assert config["games"] == 3 and config["preset"] == "soccer_server_1996"
    assert config["options"] == {
        "players": 0, "half_time_s": 1.0, "net": str(layers.net), "tree": str(layers.tree),
    }  # fmt: skip
    report = (out / "report.md").read_text().splitlines()
    assert report[0] == "# Layered vs baseline on soccer_server (soccer_server_1996), seed 0"
    assert list(outcome.lines[: len(report)]) == report  # the report, then the time
    assert outcome.lines[len(report)].startswith("\n3 games in ")
    assert outcome.lines[-1].endswith(f"report: {out}")


def test_every_option_is_checked_before_the_folder_is_touched(
    tmp_path: Path, layers: LayerFiles
) -> None:
    hfo = save_table(TpotTable.empty(1, actions=3), tmp_path / "hfo.npz")
    out = tmp_path / "never"
    for request, message in (
        (MatchRun(FIELD, left="layer3", layers=layers, out=out), "--tpot FILE"),
        (MatchRun(FIELD, left="layer3", layers=layers, tpot=hfo, out=out), "8 ball destin"),
        (MatchRun(FIELD, layers=layers, tpot=hfo, out=out), "name layer3"),
        (MatchRun(FIELD, options=(("players", 3),), layers=layers, out=out), "--option players"),
        (MatchRun(FIELD, options=(("net", "x"),), layers=layers, out=out), "--option net:"),
        (MatchRun(FIELD, options=(("bogus", 1),), layers=layers, out=out), "no option 'bogus'"),
        (MatchRun(FIELD, games=2, layers=LayerFiles(models=tmp_path), out=out), "no trained"),
    ):
        with pytest.raises(ValueError, match=message):
            run_match(request)
        assert not out.exists()


def test_the_layers_are_given_or_the_largest_net_of_a_models_folder(tmp_path: Path) -> None:
    models = tmp_path / "run" / "models" / FIELD
    models.mkdir(parents=True)
    for name in ("net_750.npz", "net_1000.npz", "net_200.npz", "pass_tree.json"):
        (models / name).touch()
    found = LayerFiles(models=tmp_path / "run").find(FIELD, 0)
    assert found == (models / "net_1000.npz", models / "pass_tree.json")
    given = LayerFiles(net=tmp_path / "n.npz", models=tmp_path / "run").find(FIELD, 0)
    assert given == (tmp_path / "n.npz", models / "pass_tree.json")
    with pytest.raises(ValueError, match=r"robot_physics in .*run/models/robot_physics: run"):
        LayerFiles(models=tmp_path / "run").find("robot_physics", 0)
    with pytest.raises(ValueError, match=r"runs/reproduce-seed7/.*runs/transfer-seed7/"):
        LayerFiles().find("no_such_field", 7)


def test_a_layer3_team_plays_as_its_table_learned(tmp_path: Path, layers: LayerFiles) -> None:
    plan = {"every": True, "success": 0.95, "window": "horizon", "guard": True, "loss": 0.5}
    table = save_table(TpotTable.empty(11, {"plan": plan}), tmp_path / "t.npz")
    request = MatchRun(FIELD, left="layer3", layers=layers, tpot=table, half_time_s=1.0)
    options = request.match_options()
    assert options == {
        "players": 0, "half_time_s": 1.0, "net": str(layers.net), "tree": str(layers.tree),
        "tpot": str(table), "tpot_every": True, "tpot_success": 0.95, "tpot_window": "horizon",
        "tpot_guard": True, "tpot_loss": 0.5,
    }  # fmt: skip
    assert request.teams == ("layer3", "baseline")
    assert MatchRun(FIELD, left="baseline").teams == ("layered", "baseline")
    plan = {**plan, "features_tree": "/models/pass_tree_passer_only.json"}
    table = save_table(TpotTable.empty(11, {"plan": plan}), tmp_path / "f.npz")
    options = MatchRun(FIELD, left="layer3", layers=layers, tpot=table).match_options()
    assert options["tpot_tree"] == "/models/pass_tree_passer_only.json"


def test_an_interrupted_series_says_its_games_are_kept(
    tmp_path: Path, layers: LayerFiles, monkeypatch: pytest.MonkeyPatch
) -> None:
    def interrupt(*args: object, **kwargs: object) -> None:
        raise KeyboardInterrupt

    monkeypatch.setattr(match_run, "run_series", interrupt)
    out = tmp_path / "s"
    message = f"interrupted; finished games are kept in {out}"
    with pytest.raises(RunInterrupted, match=f"^{re.escape(message)}$"):
        run_match(MatchRun(FIELD, games=2, half_time_s=1.0, layers=layers, out=out))
    assert (out / "config.json").exists()  # the folder was prepared before the games


def test_learn_team_plans_and_names_its_folder_from_the_request() -> None:
    request = TeamRun(FIELD, seed=3, quick=True, training_games=6, games_per_round=3)
    plan = request.plan()
    assert (plan.name, plan.training_games, plan.games_per_round) == ("quick", 6, 3)
    assert request.folder == Path("runs/learn-team-soccer_server-soccer_server_1996-quick-seed3")
    every = TeamRun(FIELD, every=True, window="horizon", shot_guard=True, loss_penalty=0.5)
    assert (every.plan().guard, every.plan().loss, every.plan().window) == (True, 0.5, "horizon")
    assert every.folder.name == (
        "learn-team-soccer_server-soccer_server_1996-every-horizon-guard-loss0.5-seed0"
    )
    assert TeamRun(FIELD, out=Path("x")).folder == Path("x")
    own = TeamRun(FIELD, every=True, features_tree=Path("m/passer.json"), success=0.5)
    assert own.plan().features_tree == str(Path("m/passer.json").resolve())
    assert own.plan().success == 0.5
    assert own.folder.name == (
        "learn-team-soccer_server-soccer_server_1996-every-passer-cut0.5-seed0"
    )
    with pytest.raises(ValueError, match="success must be in"):
        TeamRun(FIELD, success=1.5).plan()
    with pytest.raises(ValueError, match="guard needs every"):
        TeamRun(FIELD, shot_guard=True).plan()


def test_learn_team_runs_the_study_into_its_folder(
    tmp_path: Path, layers: LayerFiles, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setattr(team_study, "plan_for", lambda quick, every, window: TINY_TEAM)
    out = tmp_path / "t"
    lines: list[str] = []
    outcome = run_learn_team(TeamRun(FIELD, layers=layers, out=out, workers=1), lines.append)
    assert outcome.report == out / "report.md" and outcome.workers == 1
    assert any(line.startswith("training: 2 games") for line in lines)
    config = json.loads((out / "config.json").read_text())
    assert config["plan"]["name"] == "tiny" and config["table"] is None
    assert (config["net"], config["workers"]) == (str(layers.net), 1)
    blank, report, last = outcome.lines
    assert blank == "" and report == outcome.report.read_text()
    assert report.startswith("## Layer 3: TPOT-RL on soccer_server (tiny plan), seed 0")
    assert last.startswith(f"report: {outcome.report}  (") and last.endswith("1 worker(s))")


def test_learn_team_checks_before_the_folder_and_says_an_interrupt_keeps_games(
    tmp_path: Path, layers: LayerFiles, monkeypatch: pytest.MonkeyPatch
) -> None:
    corrupt = tmp_path / "corrupt.npz"
    corrupt.write_bytes(b"PK\x03\x04 not a table")
    out = tmp_path / "t"
    with pytest.raises(ValueError, match="not a TPOT-RL table"):
        run_learn_team(TeamRun(FIELD, layers=layers, table=corrupt, out=out), print)
    with pytest.raises(ValueError, match="no trained layers"):
        run_learn_team(TeamRun(FIELD, layers=LayerFiles(models=tmp_path), out=out), print)
    assert not out.exists()

    def interrupt(*args: object, **kwargs: object) -> None:
        raise KeyboardInterrupt

    monkeypatch.setattr(team_study, "run_team_study", interrupt)
    with pytest.raises(RunInterrupted, match=r"kept under .*/t \(--resume finishes the run\)$"):
        run_learn_team(TeamRun(FIELD, layers=layers, out=out, workers=1), print)
