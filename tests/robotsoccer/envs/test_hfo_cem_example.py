"""The half-field offense learner example runs (tiny settings) and chooses only open kicks."""

from __future__ import annotations

import importlib.util
from pathlib import Path
from types import ModuleType

import numpy as np
import pytest

from robotsoccer.envs.macros import PASS_BASE, Macro

EXAMPLE = Path(__file__).resolve().parents[3] / "examples" / "train_hfo_holder_cem.py"


def load() -> ModuleType:
    spec = importlib.util.spec_from_file_location("hfo_cem", EXAMPLE)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_the_linear_holder_takes_the_open_kick_it_scores_highest() -> None:
    module = load()
    size = 4
    weights = np.zeros((size + 1, module.CHOICES))
    weights[-1] = (0.0, 1.0, 2.0)  # bias: pass > dribble > shoot
    holder = module.LinearHolder(weights.ravel())
    mask = np.zeros(PASS_BASE + 2, np.int8)
    mask[[Macro.AUTO, Macro.SHOOT, Macro.DRIBBLE]] = 1
    assert holder(np.zeros(size, np.float32), mask) == Macro.DRIBBLE  # no pass open
    mask[PASS_BASE + 1] = 1
    assert holder(np.zeros(size, np.float32), mask) == PASS_BASE + 1


def test_the_example_learns_and_prints_the_table(capsys: pytest.CaptureFixture[str]) -> None:
    module = load()
    tiny = ["--iterations", "2", "--population", "3", "--episodes", "4", "--test-episodes", "6"]
    rows = module.main(tiny)
    lines = capsys.readouterr().out.splitlines()
    assert [line.split()[:2] for line in lines[:2]] == [["iteration", "1:"], ["iteration", "2:"]]
    assert list(rows) == ["hand-written (AUTO)", "uniform random kick", "CEM linear (mean)"]
    assert all(r.episodes == 6 for r in rows.values())
    assert module.main(tiny) == rows  # seeded: the same arguments, the same table
