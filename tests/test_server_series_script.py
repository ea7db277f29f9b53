"""scripts/server_series.py (issue 28): the paired change of the layered team's goal difference."""

from __future__ import annotations

import importlib.util
import sys
from pathlib import Path
from types import ModuleType

import pytest

SCRIPT = Path(__file__).parent.parent / "scripts" / "server_series.py"


def _script() -> ModuleType:
    spec = importlib.util.spec_from_file_location("server_series", SCRIPT)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module
    spec.loader.exec_module(module)
    return module


def _series(folder: Path, left: list[tuple[int, int]], right: list[tuple[int, int]]) -> Path:
    """A series folder as run_series writes it: goals (left team, right team) per game."""
    for side, games in (("layered_left", left), ("layered_right", right)):
        (folder / side).mkdir(parents=True)
        lines = ["index,label,ticks,time_s,data,measures,reason"]
        for index, (gl, gr) in reversed(list(enumerate(games))):  # out of order, as workers
            lines.append(f"{index},DRAW,6000,600.0,,goals_l={gl}.0 goals_r={gr}.0,x")
        (folder / side / "results.csv").write_text("\n".join(lines) + "\n")
    return folder


def test_goal_differences_take_the_layered_side_and_pair_by_game(tmp_path: Path) -> None:
    script = _script()
    before = _series(tmp_path / "a", [(3, 1), (2, 2)], [(0, 4), (1, 0)])
    after = _series(tmp_path / "b", [(2, 1), (2, 2)], [(0, 4), (2, 0)])
    assert script.goal_differences(before) == {
        ("layered_left", 0): 2.0,
        ("layered_left", 1): 0.0,
        ("layered_right", 0): 4.0,  # layered on the right: right goals minus left goals
        ("layered_right", 1): -1.0,
    }
    # Changes per game: -1, 0, 0, -1 (layered on the right lost by 2, not 1): mean -0.5.
    assert script.paired_change(before, after).startswith("-0.50 [")
    other = _series(tmp_path / "c", [(1, 1)], [(1, 1)])
    with pytest.raises(ValueError, match="same games"):
        script.paired_change(before, other)


def test_dither_counts_both_baseline_teams_together() -> None:
    script = _script()
    games = script.dither("soccer_server_1996", [0], {"half_time_s": 3.0})
    assert len(games) == 1
    game = games[0]
    assert game["player_minutes"] == pytest.approx(22 * 6.0 / 60.0)  # both teams of 11
    assert game["reversals"] > 0
    assert game["per_player_minute"] == game["reversals"] / game["player_minutes"]
