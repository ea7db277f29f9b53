"""The examples still run (tiny settings): the API they show keeps carrying a learner."""

from __future__ import annotations

import importlib.util
from pathlib import Path

import pytest

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"


def test_the_cem_example_runs_and_prints_a_learning_curve(
    capsys: pytest.CaptureFixture[str],
) -> None:
    spec = importlib.util.spec_from_file_location("cem", EXAMPLES / "train_intercept_cem.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    module.main(["--iterations", "2", "--population", "4", "--episodes", "16",
                 "--test-episodes", "64"])  # fmt: skip
    lines = capsys.readouterr().out.splitlines()
    assert lines[0].startswith("straight (TA = 0):") and "n = 64" in lines[0]
    assert [line.split()[0] for line in lines[2:4]] == ["1", "2"]


def test_the_go_to_ball_example_learns_and_plots_its_curve(
    capsys: pytest.CaptureFixture[str], tmp_path: Path
) -> None:
    path = EXAMPLES / "train_go_to_ball_cem.py"
    spec = importlib.util.spec_from_file_location("go_to_ball", path)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    plot = tmp_path / "curve.png"
    tiny = ["--iterations", "2", "--population", "4", "--episodes", "2", "--test-episodes", "4"]
    curve = module.main([*tiny, "--workers", "1", "--plot", str(plot)])
    lines = capsys.readouterr().out.splitlines()
    assert lines[0].startswith("iteration")
    assert [line.split()[0] for line in lines[1:3]] == ["1", "2"]
    assert [point[0] for point in curve] == [8, 16] and plot.stat().st_size > 1000
