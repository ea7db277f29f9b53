"""Print the shape of the code: long modules, long classes and long parameter lists.

Issue 23 ("One big tidy-up") sets three limits: no module over 500 lines, no class over
300 lines, no function with more than 8 parameters outside constructors of records. This
script measures all three over the project's packages (``robotsoccer``, ``field_models``,
``learning``) by reading the source with :mod:`ast`, so the numbers in a closing note come
from a run and not from a hand count.

Usage::

    python scripts/code_shape.py [--root DIR] [--max-module 500] [--max-class 300]
        [--max-params 8]

Parameters are counted as written, ``self``/``cls`` excluded, ``*args``/``**kwargs``
included; ``__init__`` methods are marked so that record constructors can be told apart.
"""

from __future__ import annotations

import argparse
import ast
from dataclasses import dataclass
from pathlib import Path

PACKAGES = ("robotsoccer", "field_models", "learning")


@dataclass(frozen=True)
class Shape:
    """What one module measures: its lines, its long classes and its long signatures."""

    path: str
    lines: int
    classes: tuple[tuple[str, int], ...]
    functions: tuple[tuple[str, int], ...]


def _param_count(node: ast.FunctionDef | ast.AsyncFunctionDef) -> int:
    """Count a function's parameters as written, leaving out a leading ``self`` or ``cls``."""
    args = node.args
    positional = [*args.posonlyargs, *args.args]
    if positional and positional[0].arg in ("self", "cls"):
        positional = positional[1:]
    extra = (args.vararg is not None) + (args.kwarg is not None)
    return len(positional) + len(args.kwonlyargs) + extra


def measure(path: Path, root: Path) -> Shape:
    """Measure one module: line count, every class's length, every function's parameters."""
    text = path.read_text(encoding="utf-8")
    tree = ast.parse(text, filename=str(path))
    classes: list[tuple[str, int]] = []
    functions: list[tuple[str, int]] = []

    def visit(node: ast.AST, prefix: str) -> None:
        for child in ast.iter_child_nodes(node):
            if isinstance(child, ast.ClassDef):
                end = child.end_lineno or child.lineno
                classes.append((prefix + child.name, end - child.lineno + 1))
                visit(child, prefix + child.name + ".")
            elif isinstance(child, ast.FunctionDef | ast.AsyncFunctionDef):
                functions.append((prefix + child.name, _param_count(child)))
                visit(child, prefix + child.name + ".")
            else:
                visit(child, prefix)

    visit(tree, "")
    return Shape(
        path=path.relative_to(root).as_posix(),
        lines=len(text.splitlines()),
        classes=tuple(classes),
        functions=tuple(functions),
    )


def shapes(root: Path) -> list[Shape]:
    """Measure every module of the project's packages under ``root``, in path order."""
    found: list[Shape] = []
    for package in PACKAGES:
        for path in sorted((root / package).rglob("*.py")):
            found.append(measure(path, root))
    return found


def main(argv: list[str] | None = None) -> None:
    """Print the three tables (modules, classes, functions over their limits)."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--root", type=Path, default=Path(__file__).resolve().parent.parent)
    parser.add_argument("--max-module", type=int, default=500)
    parser.add_argument("--max-class", type=int, default=300)
    parser.add_argument("--max-params", type=int, default=8)
    args = parser.parse_args(argv)
    if not all((args.root / p).is_dir() for p in PACKAGES):
        parser.error(f"--root {args.root} does not hold the packages {', '.join(PACKAGES)}")
    found = shapes(args.root)

    long_modules = sorted((s for s in found if s.lines > args.max_module), key=lambda s: -s.lines)
    print(f"## Modules over {args.max_module} lines ({len(long_modules)} of {len(found)})\n")
    print("| module | lines |\n|---|---:|")
    for s in long_modules:
        print(f"| {s.path} | {s.lines} |")

    long_classes = sorted(
        ((s.path, name, n) for s in found for name, n in s.classes if n > args.max_class),
        key=lambda row: -row[2],
    )
    print(f"\n## Classes over {args.max_class} lines ({len(long_classes)})\n")
    print("| module | class | lines |\n|---|---|---:|")
    for path, name, n in long_classes:
        print(f"| {path} | {name} | {n} |")

    long_sigs = sorted(
        ((s.path, name, n) for s in found for name, n in s.functions if n > args.max_params),
        key=lambda row: (-row[2], row[0], row[1]),
    )
    ctor = sum(1 for _, name, _ in long_sigs if name.endswith("__init__"))
    print(
        f"\n## Functions with more than {args.max_params} parameters "
        f"({len(long_sigs)}, of which {ctor} are __init__)\n"
    )
    print("| module | function | parameters |\n|---|---|---:|")
    for path, name, n in long_sigs:
        print(f"| {path} | {name} | {n} |")
    total = sum(s.lines for s in found)
    print(f"\n{len(found)} modules, {total} lines.")


if __name__ == "__main__":
    main()
