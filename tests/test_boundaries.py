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


RECORDERS = {
    "recording.py",
    "match_recording.py",
    "match_drawing.py",
    "field_recorder.py",
    "toolkit.py",
    "rows.py",
    "rrd_files.py",
}
"""The replay modules that write and read rerun recordings (trials, matches; the drawing toolkit
and its rows; reading files back): the only ones that import it."""


def test_rerun_is_imported_only_by_the_recording_modules() -> None:
    for path in sorted((ROOT / "robotsoccer").rglob("*.py")):
        if path.name not in RECORDERS or path.parent.name != "replay":
            assert "rerun" not in imported_roots(path), path.relative_to(ROOT)


def test_physics_imports_no_drawing_logging_or_cli() -> None:
    for path in sorted((ROOT / "field_models").rglob("*.py")):
        roots = imported_roots(path)
        assert not roots & {"matplotlib", "logging", "argparse", "rerun"}, path


# ----------------------------------------------------------------------------- one interface

MODEL_NAMES = {"robot_physics", "soccer_server"}
MODEL_PACKAGES = MODEL_NAMES | {"rcssserver"}
"""Imports of these field-model packages are checked too; the ``rcssserver`` model's name is
also the real server program's, which strings above the line may name, so it is not searched
for in strings."""
PRESET_CLASSES = {"RobotPhysicsPreset", "ServerPreset"}
MAY_NAME_MODELS = {Path("robotsoccer/cli/options.py"), Path("robotsoccer/cli/commands/serve.py")}
"""Above the line only the CLI names concrete field models (the registry lives below it)."""


def _docstrings(tree: ast.AST) -> set[int]:
    ids = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Module | ast.ClassDef | ast.FunctionDef | ast.AsyncFunctionDef):
            body = node.body
            if body and isinstance(body[0], ast.Expr) and isinstance(body[0].value, ast.Constant):
                ids.add(id(body[0].value))
    return ids


def concrete_model_uses(path: Path) -> list[str]:
    """Where a module names a concrete field model, imports one, or reads a preset class."""
    tree = ast.parse(path.read_text(), filename=str(path))
    docs = _docstrings(tree)
    found = []
    for node in ast.walk(tree):
        line = getattr(node, "lineno", 0)
        if isinstance(node, ast.Constant) and isinstance(node.value, str) and id(node) not in docs:
            if any(name in node.value for name in MODEL_NAMES):
                found.append(f"line {line}: names {node.value!r}")
        elif isinstance(node, ast.ImportFrom | ast.Import):
            modules = (
                [node.module or ""]
                if isinstance(node, ast.ImportFrom)
                else [alias.name for alias in node.names]
            )
            for module in modules:
                if any(f"field_models.{name}" in module for name in MODEL_PACKAGES):
                    found.append(f"line {line}: imports {module}")
            names = [alias.name for alias in node.names]
            found += [f"line {line}: imports {n}" for n in names if n in PRESET_CLASSES]
        elif isinstance(node, ast.Name | ast.Attribute):
            name = node.id if isinstance(node, ast.Name) else node.attr
            if name in PRESET_CLASSES:
                found.append(f"line {line}: uses {name}")
        elif (
            isinstance(node, ast.Call)
            and isinstance(node.func, ast.Name)
            and node.func.id == "getattr"
            and len(node.args) >= 2
            and isinstance(node.args[1], ast.Constant)
            and node.args[1].value == "preset"
        ):
            found.append(f"line {line}: reaches behind the interface for 'preset'")
    return found


def test_nothing_above_the_line_names_a_concrete_field_model() -> None:
    for path in sorted((ROOT / "robotsoccer").rglob("*.py")):
        relative = path.relative_to(ROOT)
        if relative in MAY_NAME_MODELS:
            continue
        uses = concrete_model_uses(path)
        assert not uses, f"{relative}: {uses}"


def test_the_check_catches_a_module_that_names_a_model(tmp_path) -> None:
    bad = tmp_path / "bad.py"
    bad.write_text(
        '"""Docstrings may say soccer_server."""\n'
        "from field_models.soccer_server.params import ServerPreset\n"
        "def f(arena):\n"
        '    if arena.facts.model == "robot_physics":\n'
        '        return getattr(arena, "preset")\n'
    )
    uses = concrete_model_uses(bad)
    assert len(uses) == 4 and not any("Docstrings" in use for use in uses)


def test_no_two_classes_share_a_name() -> None:
    where: dict[str, list[str]] = {}
    for package in sorted(OURS):
        for path in sorted((ROOT / package).rglob("*.py")):
            tree = ast.parse(path.read_text(), filename=str(path))
            for node in ast.walk(tree):
                if isinstance(node, ast.ClassDef):
                    where.setdefault(node.name, []).append(str(path.relative_to(ROOT)))
    shared = {name: paths for name, paths in where.items() if len(paths) > 1}
    assert not shared, shared


KNOWN_CYCLES: set[frozenset[str]] = set()
"""Import cycles not yet taken apart: none. A cycle found here must be taken apart, or listed
with its reason (and the test then fails once it is gone, so the list shrinks with the code)."""


def import_graph() -> dict[str, set[str]]:
    """Our modules and the modules of ours each imports, anywhere in it (lazy imports too)."""
    modules: dict[str, Path] = {}
    for package in sorted(OURS):
        for path in (ROOT / package).rglob("*.py"):
            name = ".".join(path.relative_to(ROOT).with_suffix("").parts)
            modules[name.removesuffix(".__init__")] = path
    graph: dict[str, set[str]] = {name: set() for name in modules}
    for name, path in modules.items():
        for node in ast.walk(ast.parse(path.read_text(), filename=str(path))):
            targets: list[str] = []
            if isinstance(node, ast.ImportFrom) and node.module and node.level == 0:
                targets = [f"{node.module}.{alias.name}" for alias in node.names]
                targets = [t if t in modules else node.module for t in targets]
            elif isinstance(node, ast.Import):
                targets = [alias.name for alias in node.names]
            graph[name].update(t for t in targets if t in modules and t != name)
    return graph


def strongly_connected(graph: dict[str, set[str]]) -> list[frozenset[str]]:
    """The graph's cycles: its strongly connected parts of more than one module (Tarjan)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    found: list[frozenset[str]] = []

    def visit(node: str) -> None:
        index[node] = low[node] = len(index)
        stack.append(node)
        for nxt in graph[node]:
            if nxt not in index:
                visit(nxt)
                low[node] = min(low[node], low[nxt])
            elif nxt in stack:
                low[node] = min(low[node], index[nxt])
        if low[node] == index[node]:
            part = []
            while True:
                top = stack.pop()
                part.append(top)
                if top == node:
                    break
            if len(part) > 1:
                found.append(frozenset(part))

    for node in sorted(graph):
        if node not in index:
            visit(node)
    return found


def test_no_module_imports_itself_round_a_cycle() -> None:
    assert set(strongly_connected(import_graph())) == KNOWN_CYCLES


def test_the_cycle_check_finds_a_cycle() -> None:
    graph = {"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}
    assert strongly_connected(graph) == [frozenset({"a", "b", "c"})]


def _imported_modules(path: Path) -> set[str]:
    tree = ast.parse(path.read_text(), filename=str(path))
    names: set[str] = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            names |= {alias.name for alias in node.names}
        elif isinstance(node, ast.ImportFrom) and node.module and node.level == 0:
            names.add(node.module)
    return names


SELF_CONTAINED = {
    "robot_physics": {"soccer_server", "rcssserver"},
    "soccer_server": {"robot_physics", "rcssserver"},
}
"""Each simulated field model is self-contained (DESIGN.md §3): what both need lives in
``field_models/`` itself (the arena interface, seeding, fpmath, records). The ``rcssserver``
model, a client of the real server, reuses the Soccer Server model's message code."""


@pytest.mark.parametrize("model", sorted(SELF_CONTAINED))
def test_a_field_model_imports_no_other_field_model(model: str) -> None:
    others = {f"field_models.{name}" for name in SELF_CONTAINED[model]}
    for path in sorted((ROOT / "field_models" / model).rglob("*.py")):
        bad = {m for m in _imported_modules(path) if ".".join(m.split(".")[:2]) in others}
        assert not bad, f"{path.relative_to(ROOT)} imports {sorted(bad)}"
