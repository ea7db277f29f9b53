"""The command line: the demo runs, bad input gives one line and a non-zero exit, no traceback."""

from __future__ import annotations

import json
import subprocess
import sys

import pytest

from robotsoccer.cli import main


def run_cli(*args: str, cwd=None) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, "-m", "robotsoccer.cli", *args],
        capture_output=True,
        text=True,
        cwd=cwd,
        timeout=300,
    )


@pytest.mark.parametrize(
    "args",
    [
        ("demo", "--bogus"),
        ("demo", "--trials", "0"),
        ("demo", "--workers", "two"),
        ("demo", "--field", "mars"),
        ("demo", "--field-preset", "nope"),
        ("frobnicate",),
    ],
)
def test_bad_option_gives_one_line_and_non_zero_exit(args) -> None:
    done = run_cli(*args)
    assert done.returncode == 2
    assert "Traceback" not in done.stderr
    lines = done.stderr.strip().splitlines()
    assert len(lines) == 1, done.stderr
    assert "error" in lines[0]


def test_wrong_preset_file_names_file_and_key(tmp_path) -> None:
    bad = tmp_path / "bad.toml"
    bad.write_text("[field]\nlength_m = -1\n")
    done = run_cli("demo", "--field-preset", str(bad))
    assert done.returncode == 2
    assert "Traceback" not in done.stderr
    assert str(bad) in done.stderr


def test_demo_prints_a_summary_table_and_writes_results(tmp_path, capsys) -> None:
    out = tmp_path / "run"
    code = main(["demo", "--trials", "6", "--workers", "1", "--out", str(out), "--quiet"])
    assert code == 0
    text = capsys.readouterr().out
    for label in ("SAVE", "GOAL", "MISS"):
        assert label in text
    assert "95% interval" in text
    assert len((out / "results.csv").read_text().splitlines()) == 7
    manifest = json.loads((out / "results.json").read_text())
    assert manifest["spec"]["drill"] == "shootout" and manifest["code_version"]


def test_demo_with_record_writes_a_recording_that_replays(tmp_path, monkeypatch, capsys) -> None:
    monkeypatch.chdir(tmp_path)
    monkeypatch.delenv("DISPLAY", raising=False)
    monkeypatch.delenv("WAYLAND_DISPLAY", raising=False)
    code = main(
        ["demo", "--trials", "2", "--workers", "1", "--record", "--record-trials", "1", "--quiet"]
    )
    assert code == 0
    files = sorted((tmp_path / "runs").rglob("recordings/*.rrd"))  # inside the run folder
    assert len(files) == 1
    assert main(["replay", str(files[0])]) == 0
    assert main(["replay", str(tmp_path / "absent.rrd")]) == 2


def test_match_plays_one_game_and_prints_the_score(tmp_path, capsys) -> None:
    out = tmp_path / "m"
    args = ["match", "--field", "soccer_server", "--left", "baseline", "--right", "baseline"]
    code = main([*args, "--half-time", "1", "--out", str(out), "--quiet"])
    assert code == 0
    text = capsys.readouterr().out
    assert "baseline" in text and "goals_l" in text
    assert (out / "results.csv").exists()


def test_a_series_without_trained_layers_says_how_to_make_them(tmp_path, capsys) -> None:
    args = ["match", "--games", "2", "--models", str(tmp_path), "--out", str(tmp_path / "s")]
    assert main(args) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "no trained layers" in err[0] and "--net" in err[0]


def test_a_series_reports_wins_draws_and_losses(tmp_path, capsys) -> None:
    from tests.robotsoccer.drills.test_passing import _tree_file
    from tests.robotsoccer.skills.test_intercept import net_file

    net = net_file(tmp_path / "net.npz", preset="soccer_server_1996")
    tree = _tree_file(tmp_path, "soccer_server")
    out = tmp_path / "s"
    args = ["match", "--field", "soccer_server", "--games", "3", "--half-time", "1"]
    args += ["--net", str(net), "--tree", str(tree), "--workers", "1", "--out", str(out)]
    assert main([*args, "--quiet"]) == 0
    report = (out / "report.md").read_text()
    rows = [
        line for line in report.splitlines() if line.startswith(("| wins", "| draws", "| loss"))
    ]
    assert sum(int(row.split("|")[2]) for row in rows) == 3
    assert main([*args, "--quiet", "--overwrite"]) == 0  # a series folder is a run folder


def test_setplay_with_a_models_folder_that_lacks_them_fails_in_one_line(tmp_path, capsys) -> None:
    assert main(["setplay", "--models", str(tmp_path), "--out", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "pass_tree.json" in err[0]


def test_learn_lead_writes_its_report_and_config(tmp_path, monkeypatch, capsys) -> None:
    import robotsoccer.experiments.lead_study as study

    tiny = study.LeadPlan("tiny", eval_trials=10, collect_saves=8, collect_batch=40, epochs=10)
    monkeypatch.setattr(study, "plan_for", lambda quick: tiny)
    out = tmp_path / "lead"
    code = main(["learn", "lead", "--field", "soccer_server", "--out", str(out), "--workers", "1"])
    assert code == 0
    report = (out / "report.md").read_text()
    assert report.startswith("# Layer 1: the lead decision") and "| lead | net |" in report
    assert "robot_physics" not in report
    assert json.loads((out / "config.json").read_text())["fields"] == ["soccer_server"]
    assert "report:" in capsys.readouterr().out


def test_match_plays_layer3_with_its_table_and_refuses_a_missing_or_corrupt_one(
    tmp_path, capsys
) -> None:
    from learning.tpot import TpotTable, save_table
    from tests.robotsoccer.drills.test_passing import _tree_file
    from tests.robotsoccer.skills.test_intercept import net_file

    net = net_file(tmp_path / "net.npz", preset="soccer_server_1996")
    tree = _tree_file(tmp_path, "soccer_server")
    args = ["match", "--field", "soccer_server", "--left", "layer3", "--half-time", "2"]
    args += ["--net", str(net), "--tree", str(tree), "--quiet"]
    assert main([*args, "--out", str(tmp_path / "none")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "--tpot FILE" in err[0]
    corrupt = tmp_path / "corrupt.npz"
    corrupt.write_bytes(b"PK\x03\x04 not a table")
    assert main([*args, "--tpot", str(corrupt), "--out", str(tmp_path / "bad")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "not a TPOT-RL table" in err[0]
    hfo = save_table(TpotTable.empty(1, actions=3), tmp_path / "hfo.npz")
    assert main([*args, "--tpot", str(hfo), "--out", str(tmp_path / "hfo")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "8 ball destinations" in err[0]
    plain = ["match", "--left", "layered", "--tpot", str(hfo), "--net", str(net)]
    assert main([*plain, "--tree", str(tree), "--out", str(tmp_path / "p")]) == 2
    assert "name layer3" in capsys.readouterr().err
    table = save_table(
        TpotTable.empty(11, {"plan": {"every": True, "success": 0.95}}), tmp_path / "t.npz"
    )
    out = tmp_path / "m"
    assert main([*args, "--tpot", str(table), "--out", str(out)]) == 0
    text = capsys.readouterr().out
    assert "layer3" in text and "goals_l" in text
    options = dict(json.loads((out / "results.json").read_text())["spec"]["drill_options"])
    assert options["tpot_every"] is True and options["tpot_success"] == 0.95  # the table's plan
    assert options["tpot_window"] == "choice"  # a table from before the window option
    table = save_table(
        TpotTable.empty(11, {"plan": {"every": True, "success": 0.95, "window": "horizon"}}),
        tmp_path / "h.npz",
    )
    out = tmp_path / "mh"
    assert main([*args, "--tpot", str(table), "--out", str(out)]) == 0
    capsys.readouterr()
    options = dict(json.loads((out / "results.json").read_text())["spec"]["drill_options"])
    assert options["tpot_window"] == "horizon"  # it plays with the window it learned with
    assert "tpot_guard" not in options and "tpot_loss" not in options  # older tables as before
    plan = {"every": True, "success": 0.95, "window": "horizon", "guard": True, "loss": 0.5}
    table = save_table(TpotTable.empty(11, {"plan": plan}), tmp_path / "g.npz")
    out = tmp_path / "mg"
    assert main([*args, "--tpot", str(table), "--out", str(out)]) == 0
    capsys.readouterr()
    options = dict(json.loads((out / "results.json").read_text())["spec"]["drill_options"])
    assert options["tpot_guard"] is True and options["tpot_loss"] == 0.5  # its guard and reward


def test_learn_team_refuses_a_guard_without_every_or_a_loss_penalty_out_of_range(
    tmp_path, capsys
) -> None:
    from tests.robotsoccer.drills.test_passing import _tree_file
    from tests.robotsoccer.skills.test_intercept import net_file

    net = net_file(tmp_path / "net.npz", preset="soccer_server_1996")
    tree = _tree_file(tmp_path, "soccer_server")
    args = ["learn", "team", "--net", str(net), "--tree", str(tree), "--out", str(tmp_path / "t")]
    assert main([*args, "--shot-guard"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "guard needs every" in err[0]
    assert main([*args, "--every", "--loss-penalty", "1.5"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "loss must be in [0, 1]" in err[0]


def test_match_takes_the_minds_options_and_refuses_bad_ones(tmp_path, capsys) -> None:
    base = ["match", "--left", "baseline", "--right", "baseline", "--half-time", "5", "--quiet"]
    base += ["--workers", "1"]
    neck = tmp_path / "neck"
    args = [*base, "--field", "soccer_server", "--option", "look=neck", "--out", str(neck)]
    assert main(args) == 0
    manifest = json.loads((neck / "results.json").read_text())
    assert ["look", "neck"] in manifest["spec"]["drill_options"]
    band = [*base, "--field", "robot_physics", "--option", "dead_band=left"]
    assert main([*band, "--out", str(tmp_path / "band")]) == 0
    capsys.readouterr()
    for option, message in (
        ("look=sideways", "look: expected one of body, neck; got 'sideways'"),
        ("players=3", "--option players: it has its own flag"),
        ("bogus=1", "drill 'match' has no option 'bogus'"),
    ):
        out = tmp_path / option.split("=")[0]
        args = [*base, "--field", "robot_physics", "--option", option, "--out", str(out)]
        assert main(args) == 2
        err = capsys.readouterr().err.strip()
        assert message in err and "\n" not in err
