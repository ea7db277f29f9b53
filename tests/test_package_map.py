"""The README's package map names every module of the three packages, once, and no other."""

from __future__ import annotations

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
PACKAGES = ("field_models", "learning", "robotsoccer")
BEGIN = "<!-- package map: scripts/package_map.py --write -->"
END = "<!-- end of package map -->"


def mapped(readme: str) -> list[str]:
    """The module paths the map between the markers names, in its order."""
    block = readme[readme.index(BEGIN) : readme.index(END)]
    found: list[str] = []
    folder = ""
    for line in block.splitlines():
        if head := re.match(r"- \*\*`([\w/]+)/`\*\*", line):
            folder = head.group(1)
            found.append(f"{folder}/__init__.py")
        elif item := re.match(r"  - `(\w+\.py)`: \S", line):
            found.append(f"{folder}/{item.group(1)}")
    return found


def test_the_map_names_each_module_once() -> None:
    names = mapped((ROOT / "README.md").read_text(encoding="utf-8"))
    modules = sorted(
        p.relative_to(ROOT).as_posix()
        for package in PACKAGES
        for p in (ROOT / package).rglob("*.py")
    )
    assert len(names) == len(set(names))
    missing = sorted(set(modules) - set(names))
    gone = sorted(set(names) - set(modules))
    assert not missing and not gone, (
        f"run `python scripts/package_map.py --write`; missing {missing}, gone {gone}"
    )


def test_the_reader_finds_a_missing_module() -> None:
    readme = f"{BEGIN}\n- **`learning/`**: x\n  - `a.py`: y\n{END}\n"
    assert mapped(readme) == ["learning/__init__.py", "learning/a.py"]
