"""The benchmark scripts stay runnable: each imports what it measures (nothing is timed here)."""

from __future__ import annotations

import runpy
from pathlib import Path

import pytest

SCRIPTS = sorted((Path(__file__).resolve().parents[1] / "benchmarks").glob("*.py"))


@pytest.mark.parametrize("script", SCRIPTS, ids=lambda p: p.name)
def test_benchmark_script_imports_what_it_measures(script: Path) -> None:
    namespace = runpy.run_path(str(script), run_name="not_main")  # the main block does not run
    assert namespace
