"""scripts/pass_breakdown.py (issue 28): the coach's passes split by kind add up to its count."""

from __future__ import annotations

import importlib.util
import sys
from pathlib import Path
from types import ModuleType

import pytest

from field_models.arena import FieldOptions
from robotsoccer.runs.runner import TrialSpec

SCRIPT = Path(__file__).parent.parent / "scripts" / "pass_breakdown.py"


def _script() -> ModuleType:
    spec = importlib.util.spec_from_file_location("pass_breakdown", SCRIPT)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module
    spec.loader.exec_module(module)
    return module


def _spec(**options: object) -> TrialSpec:
    return TrialSpec(
        drill="match",
        field_model="soccer_server",
        preset="soccer_server_1996",
        seed=0,
        field=FieldOptions(),
    ).with_options(left="baseline", right="baseline", players=0, half_time_s=30.0, **options)


@pytest.mark.parametrize("look", ["body", "neck"])
def test_passes_by_kind_add_up_to_the_coach_count(look: str) -> None:
    counts = _script().breakdown(_spec(look=look), 0)["baseline"]  # both teams together
    kinds = sum(n for name, n in counts.items() if name.startswith("after "))
    assert counts["coach passes"] > 0
    assert kinds == counts["passes"] == counts["coach passes"]
    assert counts["pass kicks arrived"] <= counts["pass kicks"]
    assert counts["pass kicks arrived"] > 0


def test_a_drill_without_a_referee_is_refused() -> None:
    spec = TrialSpec(drill="pass", field_model="soccer_server", preset="soccer_server_1996", seed=0)
    with pytest.raises(ValueError, match="not a match drill"):
        _script().breakdown(spec, 0)
