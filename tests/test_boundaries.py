"""The import arrows of DESIGN.md §3, checked by parsing every module's imports."""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
OURS = {"robotsoccer", "field_models", "learning"}
FORBIDDEN = {
    # field_models: the worlds import nothing of ours and no rerun/torch/sklearn.
    "field_models": {"robotsoccer", "learning", "rerun", "torch", "sklearn"},
    # learning: arrays in, arrays out; no pymunk, no rerun, nothing from robotsoccer.
    "learning": {"robotsoccer", "field_models", "pymunk", "rerun"},
    # robotsoccer may import both, but rerun only in its recording module.
    "robotsoccer": set(),
}


def imported_roots(path: Path) -> set[str]:
    tree = ast.parse(path.read_text(), filename=str(path))
    roots: set[str] = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            roots |= {alias.name.split(".")[0] for alias in node.names}
        elif isinstance(node, ast.ImportFrom) and node.module and node.level == 0:
            roots.add(node.module.split(".")[0])
    return roots


@pytest.mark.parametrize("package", sorted(FORBIDDEN))
def test_package_imports_follow_the_design(package: str) -> None:
    files = sorted((ROOT / package).rglob("*.py"))
    assert files
    for path in files:
        bad = imported_roots(path) & FORBIDDEN[package]
        assert not bad, f"{path.relative_to(ROOT)} imports {sorted(bad)}"


def test_rerun_is_imported_only_by_the_recording_module() -> None:
    for path in sorted((ROOT / "robotsoccer").rglob("*.py")):
        if path.name != "recording.py":
            assert "rerun" not in imported_roots(path), path.relative_to(ROOT)


def test_physics_imports_no_drawing_logging_or_cli() -> None:
    for path in sorted((ROOT / "field_models").rglob("*.py")):
        roots = imported_roots(path)
        assert not roots & {"matplotlib", "logging", "argparse", "rerun"}, path
