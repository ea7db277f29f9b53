"""The ablation study of the robots' interception drill (issue 10)."""

from __future__ import annotations

from pathlib import Path

from robotsoccer.experiments.ablations import (
    Ablation,
    AblationPlan,
    ablation_markdown,
    ablations,
    median_travel,
    run_ablations,
)
from robotsoccer.experiments.context import RunContext
from robotsoccer.experiments.layer1_plan import seeds_for


def test_every_robot_row_but_the_former_rule_runs_the_task_scaling() -> None:
    rows = ablations(("soccer_server", "soccer_server_1996"), ("robot_physics", "small_size_1997"))
    assert len({row.key for row in rows}) == len(rows)
    assert rows[0].field_model == "soccer_server"
    for row in rows[1:]:
        scaling = dict(row.options)["scaling"]
        assert scaling == ("sensor_updates" if row.key == "sensor_updates" else "task")


def test_a_row_learns_and_reports_its_defenders(tmp_path: Path) -> None:
    plan = AblationPlan(collect_saves=12, net_examples=10, eval_trials=30, epochs=20)
    row = Ablation(
        "trigger", "trigger x1.5", "robot_physics", "small_size_1997",
        (("scaling", "task"), ("trigger_scale", 1.5)),
    )  # fmt: skip
    lines: list[str] = []
    (result,) = run_ablations([row], plan, RunContext(tmp_path, seeds_for(0), 1, lines.append))
    assert {k: len(v) for k, v in result.trials.items()} == {"still": 30, "straight": 30, "net": 30}
    # Same placements for every defender: the still defender never moves.
    assert median_travel(result.trials["still"]) in (None, 0.0)
    assert (median_travel(result.trials["straight"]) or 0.0) > 0.0
    assert (tmp_path / "ablations" / "trigger" / "net_10.npz").is_file()
    text = ablation_markdown([result], plan)
    assert "| trigger x1.5 |" in text and "net - straight" in text
    again = run_ablations([row], plan, RunContext(tmp_path, seeds_for(0), 1, lines.append))
    assert again[0].trials == result.trials  # resumed from the files, the same trials
