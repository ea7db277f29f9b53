"""Values at the edges of their stated ranges load and play (issue 30)."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from robotsoccer.runs.runner import TrialSpec, run_trial


@pytest.mark.parametrize(
    ("key", "value"),
    [("player_decay", "1.0"), ("player_decay", "0.0"), ("ball_decay", "1.0"), ("ball_rand", "1")],
)
def test_edge_values_inside_the_ranges_play(tmp_path: Path, key: str, value: str) -> None:
    path = tmp_path / f"{key}_{value}.toml"
    path.write_text(f'base = "soccer_server_1996"\n[dynamics]\n{key} = {value}\n')
    spec = TrialSpec(drill="intercept", field_model="soccer_server", preset=str(path))
    try:
        result = run_trial(spec, 0)
    except ValueError as err:  # a drill may refuse a field it cannot be set up on, in words
        assert "\n" not in str(err)
        return
    assert math.isfinite(result.time_s)
