"""``learn intercept|pass|lead``, ``reproduce`` and ``transfer`` as pipelines, without argparse."""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest

import robotsoccer.experiments.layer1_plan as layer1_plan
import robotsoccer.experiments.layer2 as layer2
import robotsoccer.experiments.lead_study as lead_study
import robotsoccer.experiments.reproduce as reproduce
import robotsoccer.experiments.transfer_study as transfer_study
from learning.datasets import InterceptionDataset
from robotsoccer.cli.options import EXIT_INTERRUPTED
from robotsoccer.cli.running import show
from robotsoccer.experiments.context import ReportOutcome, RunContext, RunInterrupted
from robotsoccer.experiments.gap_variants import Randomisation
from robotsoccer.experiments.learn_run import (
    InterceptRun,
    LeadRun,
    PassRun,
    run_learn_lead,
    run_learn_pass,
)
from robotsoccer.experiments.reproduce import ReproduceParts, ReproduceRun, run_reproduce
from robotsoccer.experiments.transfer_run import TransferRun, run_transfer
from robotsoccer.experiments.transfer_study import TransferSetup
from tests.robotsoccer.skills.test_intercept import net_file
from tests.robotsoccer.test_smoke_commands import TINY_LAYER1, TINY_LAYER2, TINY_LEAD

FIELD = "soccer_server"
SERVER = (FIELD, "soccer_server_1996")
ROBOTS = ("robot_physics", "small_size_1997")
LEAD = lead_study.StudyDrill(FIELD, "soccer_server_1996", (), "the paper's drill")


def interrupt(*args: object, **kwargs: object) -> None:
    """A step that the user stops with Ctrl-C."""
    raise KeyboardInterrupt


def kept(out: Path) -> str:
    """The one line of an interrupted run that keeps its trials in `out`."""
    message = f"interrupted; finished trials are kept under {out} (--resume finishes the run)"
    return f"^{re.escape(message)}$"


def test_each_request_names_its_default_folder_and_title() -> None:
    intercept = InterceptRun(FIELD, quick=True)
    assert intercept.folder == Path(
        "runs/learn-intercept-soccer_server-soccer_server_1996-quick-seed0"
    )
    assert intercept.models == (SERVER,) and intercept.parts == ReproduceParts()
    assert intercept.title == "Layer 1 (interception) on soccer_server — quick plan"
    assert intercept.created_by == "robotsoccer learn intercept"
    cycle = InterceptRun(FIELD, preset="soccer_server_2003", client="cycle", seed=3)
    assert cycle.folder.name == "learn-intercept-soccer_server-soccer_server_2003-cycle-seed3"
    assert (
        cycle.parts.client == "cycle" and cycle.title == "Layer 1 (interception) on soccer_server"
    )
    assert PassRun(FIELD, quick=True, seed=2).folder.name == (
        "learn-pass-soccer_server-soccer_server_1996-quick-seed2"
    )
    assert PassRun("robot_physics").model == ROBOTS
    assert LeadRun((LEAD,), seed=1).folder.name == "learn-lead-soccer_server-seed1"
    assert LeadRun((LEAD, LEAD), quick=True).folder.name == "learn-lead-quick-seed0"
    both = ReproduceRun((SERVER, ROBOTS), quick=True)
    assert both.folder.name == "reproduce-quick-seed0" and both.title.endswith(" — quick plan")
    assert ReproduceRun((SERVER,), seed=5).folder.name == "reproduce-seed5"
    setup = TransferSetup(SERVER, ROBOTS, Randomisation(SERVER[1], (), 2))
    assert TransferRun(setup, quick=True).folder.name == "transfer-quick-seed0"
    assert TransferRun(setup, seed=4).folder.name == "transfer-seed4"
    for request in (
        InterceptRun(FIELD, out=Path("x")),
        PassRun(FIELD, out=Path("x")),
        LeadRun((LEAD,), out=Path("x")),
        ReproduceRun((SERVER,), out=Path("x")),
        TransferRun(setup, out=Path("x")),
    ):
        assert request.folder == Path("x")


def test_learn_intercept_runs_layer_1_alone_into_its_folder(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setattr(layer1_plan, "plan_for", lambda quick: TINY_LAYER1)
    out = tmp_path / "i"
    lines: list[str] = []
    outcome = run_reproduce(InterceptRun(FIELD, quick=True, out=out, workers=1), lines.append)
    assert outcome.report == out / "report.md" and outcome.workers == 1
    assert lines and lines[0].startswith("[soccer_server] collect")
    blank, report, last = outcome.lines
    assert blank == "" and report == outcome.report.read_text()
    assert report.startswith("# Layer 1 (interception) on soccer_server — quick plan")
    assert "Table 2" not in report  # layer 1 alone
    assert last.startswith(f"report: {outcome.report}  (") and last.endswith("1 worker(s))")
    dataset = InterceptionDataset.load(out / "datasets" / FIELD / "train.npz")
    assert dataset.provenance.created_by == "robotsoccer learn intercept"


def test_the_layer_pipeline_checks_presets_before_the_folder_and_keeps_trials_on_ctrl_c(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    out = tmp_path / "r"
    with pytest.raises(ValueError, match="nope"):
        run_reproduce(ReproduceRun((SERVER, ("robot_physics", "nope")), out=out), print)
    assert not out.exists()
    monkeypatch.setattr(reproduce, "run_steps", interrupt)
    with pytest.raises(RunInterrupted, match=kept(out)):
        run_reproduce(ReproduceRun((SERVER,), out=out, workers=1), print)
    assert out.is_dir()  # the folder was prepared before the steps


def test_learn_pass_runs_layer_2_on_a_given_net(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setattr(layer2, "layer2_plan", lambda quick: TINY_LAYER2)
    net = net_file(tmp_path / "net.npz", preset="soccer_server_1996")
    out = tmp_path / "p"
    lines: list[str] = []
    request = PassRun(FIELD, net=net, quick=True, seed=1, out=out, workers=1)
    outcome = run_learn_pass(request, lines.append)
    assert any("layer 2: collect" in line for line in lines)
    report = outcome.report.read_text()
    assert report.startswith("# Layer 2 (pass evaluation) on soccer_server — quick plan\n\n")
    assert outcome.lines[1] == report and outcome.workers == 1
    config = json.loads((out / "config.json").read_text())
    assert config == {"plan": TINY_LAYER2.to_dict(), "seed": 1, "net": str(net)}
    assert not (out / "models" / FIELD / "net_10.npz").exists()  # the given net, none trained


def test_learn_pass_on_the_per_cycle_client_carries_it_into_every_trial_and_the_report(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    from robotsoccer.cli.commands.learn import pass_request
    from robotsoccer.cli.parser import build_parser

    args = build_parser().parse_args(["learn", "pass", "--client", "cycle"])
    assert pass_request(args).client == "cycle"
    assert pass_request(build_parser().parse_args(["learn", "pass"])).client == "see"
    monkeypatch.setattr(layer2, "layer2_plan", lambda quick: TINY_LAYER2)
    net = net_file(tmp_path / "net.npz", preset="soccer_server_1996")
    out = tmp_path / "p"
    request = PassRun(FIELD, net=net, seed=1, out=out, workers=1, client="cycle")
    report = run_learn_pass(request, print).report.read_text()
    assert "client, in every trial (collection and tests): the per-cycle client" in report
    results = sorted((out / "results" / FIELD / "layer2").glob("*.json"))
    assert len(results) == 8  # the collection and the 7 tests
    for path in results:
        options = dict(json.loads(path.read_text())["spec"]["drill_options"])
        assert options["client"] == "cycle", path.name
    assert json.loads((out / "config.json").read_text())["plan"]["client"] == "cycle"
    robots = tmp_path / "r"
    with pytest.raises(ValueError, match="robots' host"):
        run_learn_pass(PassRun("robot_physics", out=robots, client="cycle"), print)
    assert not robots.exists()


def test_learn_pass_trains_its_net_when_none_is_given(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setattr(layer1_plan, "plan_for", lambda quick: TINY_LAYER1)
    monkeypatch.setattr(layer2, "layer2_plan", lambda quick: TINY_LAYER2)
    out = tmp_path / "p"
    run_learn_pass(PassRun(FIELD, out=out, workers=1), print)
    net = json.loads((out / "config.json").read_text())["net"]
    assert Path(net) == out / "models" / FIELD / "net_10.npz" and Path(net).exists()


def test_learn_pass_refuses_a_bad_preset_or_net_before_the_folder_and_keeps_trials_on_ctrl_c(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    out = tmp_path / "p"
    with pytest.raises(ValueError, match="nope"):
        run_learn_pass(PassRun(FIELD, preset="nope", out=out), print)
    server_net = net_file(tmp_path / "net.npz", preset="soccer_server_1996")
    with pytest.raises(ValueError, match="transfer=true"):
        run_learn_pass(PassRun("robot_physics", net=server_net, out=out), print)
    assert not out.exists()
    monkeypatch.setattr(layer2, "run_layer2_model", interrupt)
    with pytest.raises(RunInterrupted, match=kept(out)):
        run_learn_pass(PassRun(FIELD, net=server_net, out=out, workers=1), print)
    assert out.is_dir() and not (out / "config.json").exists()


def test_learn_lead_runs_the_study_on_its_drills(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setattr(lead_study, "plan_for", lambda quick: TINY_LEAD)
    out = tmp_path / "l"
    outcome = run_learn_lead(LeadRun((LEAD,), quick=True, out=out, workers=1), print)
    report = outcome.report.read_text()
    assert report.startswith("# Layer 1: the lead decision — quick plan\n\n")
    assert "| lead | net |" in report and "robot_physics" not in report
    config = json.loads((out / "config.json").read_text())
    assert config == {"plan": TINY_LEAD.to_dict(), "seed": 0, "fields": [FIELD]}
    assert outcome.lines[2].startswith(f"report: {out / 'report.md'}  (")


def test_learn_lead_keeps_trials_on_ctrl_c(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(lead_study, "run_study", interrupt)
    out = tmp_path / "l"
    with pytest.raises(RunInterrupted, match=kept(out)):
        run_learn_lead(LeadRun((LEAD,), out=out, workers=1), print)
    assert out.is_dir() and not (out / "report.md").exists()


def test_transfer_writes_the_study_under_its_title(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    asked: list[tuple[TransferSetup, bool, Path, str]] = []

    def study(setup: TransferSetup, quick: bool, ctx: RunContext) -> str:
        asked.append((setup, quick, ctx.out, ctx.created_by))
        return "## The matrix\n"

    monkeypatch.setattr(transfer_study, "run_transfer_study", study)
    setup = TransferSetup(SERVER, ROBOTS, Randomisation(SERVER[1], (), 2))
    out = tmp_path / "x"
    outcome = run_transfer(TransferRun(setup, quick=True, out=out, workers=1), print)
    assert asked == [(setup, True, out, "robotsoccer transfer")]
    assert outcome.report.read_text() == "# The transfer study — quick plan\n\n## The matrix\n"
    bad = TransferSetup(SERVER, ("robot_physics", "nope"), setup.randomisation)
    with pytest.raises(ValueError, match="nope"):
        run_transfer(TransferRun(bad, out=tmp_path / "bad"), print)
    assert not (tmp_path / "bad").exists()
    monkeypatch.setattr(transfer_study, "run_transfer_study", interrupt)
    with pytest.raises(RunInterrupted, match=kept(out)):
        run_transfer(TransferRun(setup, out=out, resume=True, workers=1), print)


def test_the_command_prints_an_outcome_or_an_interrupt_in_one_line(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    report = tmp_path / "report.md"
    report.write_text("# A report\n")
    assert show(lambda: ReportOutcome(report, 12.4, 3)) == 0
    assert capsys.readouterr().out == f"\n# A report\n\nreport: {report}  (12 s with 3 worker(s))\n"

    def stopped() -> ReportOutcome:
        raise RunInterrupted("interrupted; finished trials are kept under x")

    assert show(stopped) == EXIT_INTERRUPTED
    captured = capsys.readouterr()
    assert captured.out == ""
    assert captured.err == "robotsoccer: error: interrupted; finished trials are kept under x\n"
