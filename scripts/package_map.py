"""Write the README's package map: every module of the three packages, one line each.

Each line is the module's file name and the first line of its docstring, so the map says what
the modules say of themselves and is remade, not hand-kept, when modules come and go (issue 23,
"docs follow the code"). A package's own line is its ``__init__.py``'s. The map sits in
``README.md`` between :data:`BEGIN` and :data:`END`; ``tests/test_package_map.py`` fails when a
module is missing from it or listed that no longer exists.

Usage::

    python scripts/package_map.py            # print the map
    python scripts/package_map.py --write    # replace the map in README.md
"""

from __future__ import annotations

import argparse
import ast
from pathlib import Path

PACKAGES = ("field_models", "learning", "robotsoccer")
BEGIN = "<!-- package map: scripts/package_map.py --write -->"
END = "<!-- end of package map -->"
ROOT = Path(__file__).resolve().parent.parent


def summary(path: Path) -> str:
    """The first line of a module's docstring, without its closing full stop."""
    doc = ast.get_docstring(ast.parse(path.read_text(encoding="utf-8"), filename=str(path)))
    if not doc:
        raise ValueError(f"{path}: no module docstring")
    return doc.splitlines()[0].strip().removesuffix(".")


def package_map(root: Path = ROOT) -> str:
    """The map as Markdown: a line per package directory, then a line per module in it."""
    lines: list[str] = []
    for package in PACKAGES:
        folders = sorted(
            {p.parent for p in (root / package).rglob("*.py")},
            key=lambda d: d.relative_to(root).parts,
        )
        for folder in folders:
            where = folder.relative_to(root).as_posix()
            init = folder / "__init__.py"
            head = f": {summary(init)}" if init.exists() else ""
            lines.append(f"- **`{where}/`**{head}")
            for path in sorted(folder.glob("*.py")):
                if path.name != "__init__.py":
                    lines.append(f"  - `{path.name}`: {summary(path)}")
    return "\n".join(lines) + "\n"


def write(readme: Path, text: str) -> None:
    """Replace the map between the markers in `readme`."""
    old = readme.read_text(encoding="utf-8")
    start, end = old.index(BEGIN) + len(BEGIN), old.index(END)
    readme.write_text(old[:start] + "\n\n" + text + "\n" + old[end:], encoding="utf-8")


def main(argv: list[str] | None = None) -> None:
    """Print the map, or with ``--write`` put it into README.md."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--write", action="store_true", help="replace the map in README.md")
    args = parser.parse_args(argv)
    text = package_map()
    if args.write:
        write(ROOT / "README.md", text)
    else:
        print(text, end="")


if __name__ == "__main__":
    main()
