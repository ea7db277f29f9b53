"""The lead study end to end on a tiny plan: collect, train, evaluate, report, resume."""

from __future__ import annotations

from pathlib import Path

from learning.datasets import InterceptionDataset
from learning.interception_file import read_net_file
from robotsoccer.experiments.context import RunContext
from robotsoccer.experiments.layer1_plan import seeds_for
from robotsoccer.experiments.lead_study import LeadPlan, StudyDrill, run_study

TINY = LeadPlan("tiny", eval_trials=20, collect_saves=15, collect_batch=60, epochs=20)
DRILLS = (
    StudyDrill(
        "robot_physics",
        "small_size_1997_arc",
        (("shot", "goal_mouth"), ("scaling", "task"), ("launch_speed_mps", 0.9)),
        "tiny robot drill",
    ),
    StudyDrill("soccer_server", "soccer_server_1996", (), "tiny server drill"),
)


def test_the_study_trains_both_decisions_and_reports_every_row(tmp_path: Path) -> None:
    lines: list[str] = []
    text, sections = run_study(DRILLS, TINY, RunContext(tmp_path, seeds_for(5), 1, lines.append))
    for section in sections:
        field = section.drill.field_model
        for decision in ("turn", "lead"):
            net = read_net_file(tmp_path / "models" / field / f"{decision}_net.npz")
            assert net.schema.decision == decision
            data = InterceptionDataset.load(tmp_path / "datasets" / field / f"{decision}.npz")
            assert data.decision == decision and len(data) == section.trained[decision] >= 15
        assert len(section.rows) == 9 and all(len(r.results) == 20 for r in section.rows)
    assert text.count("| lead | net |") == 2 and text.count("| — | still |") == 2
    assert "Learned lead" in text and "points" in text
    # Run again: everything is on disk, nothing runs, the same numbers come back.
    again, _ = run_study(DRILLS, TINY, RunContext(tmp_path, seeds_for(5), 1, lines.append))
    assert again == text
