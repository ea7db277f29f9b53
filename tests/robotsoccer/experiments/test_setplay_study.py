"""The set-play study on a few plays: the folder, the report's rows and counts, resuming."""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest

from robotsoccer.drills.setplay import SetPlayDrill
from robotsoccer.experiments.context import RunContext
from robotsoccer.experiments.layer1_plan import PipelineError
from robotsoccer.experiments.setplay import (
    RECORDED_PLAYS,
    model_files,
    play_conditions,
    run_setplay_study,
)
from robotsoccer.runs.pool import read_results

FIELDS = [("soccer_server", "soccer_server_1996")]
Study = tuple[Path, Path, list[str]]
PLAYS = 4


@pytest.fixture(scope="module")
def study(tmp_path_factory: pytest.TempPathFactory) -> Study:
    out = tmp_path_factory.mktemp("setplay")
    lines: list[str] = []
    ctx = RunContext.for_seed(out, 0, 1, lines.append)
    report = run_setplay_study(ctx, fields=FIELDS, models=None, plays=PLAYS)
    return out, report, lines


def _row(text: str, title: str) -> list[str]:
    line = next(line for line in text.splitlines() if line.startswith(f"| {title} |"))
    return [cell.strip() for cell in line.strip("|").split("|")]


def _count(cell: str) -> int:
    match = re.match(r"(\d+) — ", cell)
    assert match is not None, cell
    return int(match.group(1))


def test_the_folder_holds_results_recordings_config_and_report(study: Study) -> None:
    out, report, lines = study
    results = read_results(out / "results" / "soccer_server" / "baseline.csv")
    assert sorted(results) == list(range(PLAYS))
    recordings = sorted((out / "recordings" / "soccer_server").glob("baseline_play*.rrd"))
    assert len(recordings) == RECORDED_PLAYS
    for path in recordings:  # a recording is the same play: its label is the table's
        index = int(path.name[len("baseline_play") :][:4])
        assert path.stem.endswith(results[index].label)
    config = json.loads((out / "config.json").read_text())
    assert config["plays"] == PLAYS and config["fields"] == [list(f) for f in FIELDS]
    assert report == out / "report.md" and any("baseline" in line for line in lines)


def test_the_report_has_every_row_and_its_counts_add_up(study: Study) -> None:
    out, report, _ = study
    text = report.read_text()
    assert "## soccer_server (`soccer_server_1996`)" in text
    assert f"baseline (n={PLAYS})" in text
    results = read_results(out / "results" / "soccer_server" / "baseline.csv")
    exactly = [_count(_row(text, f"exactly {k}")[1]) for k in (1, 2, 3)]
    at_least = [_count(_row(text, f"≥ {k} pass{'es' if k > 1 else ''}")[1]) for k in (1, 2, 3)]
    assert at_least == [sum(exactly[k:]) for k in range(3)]
    none = sum(1 for r in results.values() if r.measure("passes") == 0)
    assert none + at_least[0] == PLAYS
    labels = [_count(_row(text, f"label {label}")[1]) for label in SetPlayDrill.labels]
    assert sum(labels) == PLAYS
    goals = _count(_row(text, "goal")[1])
    assert goals == labels[0] <= _count(_row(text, "shot on goal")[1]) + goals


def test_a_rerun_resumes_and_another_study_is_refused(study: Study) -> None:
    out, report, _ = study
    before = report.read_text()
    ctx = RunContext.for_seed(out, 0, 1, print)
    again = run_setplay_study(ctx, fields=FIELDS, models=None, plays=PLAYS)
    after = again.read_text()
    strip = re.compile(r"\d+ s( of wall time)?")  # timings differ; the numbers may not
    assert strip.sub("", after) == strip.sub("", before)
    with pytest.raises(PipelineError, match="another plays"):
        run_setplay_study(ctx, fields=FIELDS, models=None, plays=PLAYS + 1)


def test_the_layered_minds_need_each_fields_tree_and_net(tmp_path: Path) -> None:
    with pytest.raises(PipelineError, match="missing model file"):
        model_files(tmp_path, "soccer_server")
    folder = tmp_path / "soccer_server"
    folder.mkdir()
    (folder / "pass_tree.json").write_text("{}")
    (folder / "net_750.npz").write_bytes(b"")
    names = [c.name for c in play_conditions(FIELDS[0], tmp_path, 0)]
    assert names == ["layered", "layered_fixed", "baseline"]
    specs = {c.name: dict(c.spec.drill_options) for c in play_conditions(FIELDS[0], tmp_path, 7)}
    assert specs["layered"]["chooser"] == "tree" and specs["layered"]["interceptor"] == "net"
    assert "defenders" not in specs["layered"]  # the paper's: as the attackers intercept
    # The same layered attackers against the baseline's straight defenders.
    assert specs["layered_fixed"] == {**specs["layered"], "defenders": "straight"}
    assert specs["baseline"] == {"chooser": "closest", "interceptor": "straight"}
    with pytest.raises(ValueError, match="plays"):
        run_setplay_study(
            RunContext.for_seed(tmp_path / "x", 0), fields=FIELDS, models=None, plays=0
        )


def test_the_client_option_reaches_the_server_fields_conditions_only() -> None:
    server, robots = ("soccer_server", "soccer_server_1996"), ("robot_physics", "small_size_1997")
    for cond in play_conditions(server, None, 0, "cycle"):
        assert dict(cond.spec.drill_options)["client"] == "cycle"
    for cond in play_conditions(robots, None, 0, "cycle"):
        assert "client" not in dict(cond.spec.drill_options)  # their host acts every tick
    # The default leaves the conditions as they were (a resumed run's header is unchanged).
    plain = play_conditions(server, None, 0)
    assert all("client" not in dict(c.spec.drill_options) for c in plain)
