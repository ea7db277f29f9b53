"""scripts/robot_supersession.py (issue 28 item 5): its counters change nothing and count."""

from __future__ import annotations

import importlib.util
import sys
from pathlib import Path
from types import ModuleType

from robotsoccer.runs.runner import TrialSpec, run_trial

SCRIPT = Path(__file__).parent.parent / "scripts" / "robot_supersession.py"


def _script() -> ModuleType:
    spec = importlib.util.spec_from_file_location("robot_supersession", SCRIPT)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module  # its dataclass looks its module up by name
    spec.loader.exec_module(module)
    return module


def test_instrumented_match_plays_as_the_runner_and_counts() -> None:
    script = _script()
    spec = TrialSpec(
        "match",
        "robot_physics",
        "small_size_1997_arc",
        drill_options=(("left", "baseline"), ("right", "baseline"), ("half_time_s", 5.0)),
    )
    label, counts, measures = script.instrument(spec, 0)
    result = run_trial(spec, 0)
    assert label == result.label
    assert measures["goals_l"] >= 0.0 and 0.0 <= measures["possession_l"] <= 1.0
    assert counts.robot_minutes == 10 * 10.0 / 60.0  # 10 robots, two 5 s halves
    # A match of ten robots sends commands; the counters are within what was sent.
    assert counts.sent > 0
    assert 0 <= counts.cut_turns <= counts.cut_short <= counts.sent
    assert 0 <= counts.host_dropped_dashes <= counts.host_dropped
    again = script.instrument(spec, 0)[1]
    assert again == counts  # deterministic by seed


def test_the_dead_band_series_plays_it_on_each_side_and_adds_up() -> None:
    script = _script()
    line, data = script.series("small_size_1997_arc", 2, 3.0)
    assert line.startswith("| `small_size_1997_arc` | 2 | ")
    assert data["games"] == 2 and len(data["goal_difference"]) == 2
    for d, mine, theirs in zip(
        data["goal_difference"], data["goals_dead_band"], data["goals_default"], strict=True
    ):
        assert d == mine - theirs
    assert all(0.0 <= p <= 100.0 for p in data["possession_dead_band_pct"])
    assert data["robot_minutes"] == 2 * 10 * 6.0 / 60.0
