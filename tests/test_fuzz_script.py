"""The release fuzz (scripts/fuzz.py) runs: a few hundred cases, no finding."""

from __future__ import annotations

import importlib.util
from pathlib import Path

import pytest

SCRIPT = Path(__file__).parent.parent / "scripts" / "fuzz.py"


def test_a_short_fuzz_finds_nothing(capsys: pytest.CaptureFixture[str]) -> None:
    spec = importlib.util.spec_from_file_location("fuzz_script", SCRIPT)
    assert spec is not None and spec.loader is not None
    fuzz = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(fuzz)
    status = fuzz.main(["--cases", "240", "--quiet", "--trial-every", "3"])
    out = capsys.readouterr().out
    assert status == 0, out
    assert "all" in out and "findings" in out
