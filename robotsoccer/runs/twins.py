"""Trials a run folder already holds under another name: copied into a new table, not run again.

A trial's result is a function of its spec, its index, the code and the files it reads
(DESIGN.md §4; :mod:`robotsoccer.runs.pool`), and a results table's manifest records exactly
those. So two tables of one run folder whose manifests agree on the spec, the code version and
the inputs' digests hold the same result for every index both hold. ``reproduce`` asks for
such cells more than once: the transfer study's matrices hold layer 1's and layer 2's own cells
(a field's tree, random and closest choosers on that field), the lead matrix holds the lead
study's, and ablation rows share collections. :func:`fill_from_twins` copies what such a *twin*
holds into a new table before the pool runs the rest (issue 21).

Only the run folder the table lies in is searched (the folder whose lock the run holds), and
only tables with a readable manifest of the current format; the machine a twin ran on is not
compared, as results do not depend on it (``tests/test_cpu_independence.py``).
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

from robotsoccer.runs.folders import holding
from robotsoccer.runs.pool import check_resumable, manifest, write_manifest
from robotsoccer.runs.runner import TrialResult, TrialSpec
from robotsoccer.runs.table import ResumeError, TableWriter, iter_results

_SAME = ("spec", "code_version", "inputs")
"""The manifest entries that fix a table's results (not the machine it ran on)."""

_KEYS: dict[Path, tuple[tuple[int, int], str | None]] = {}
"""Per process: a manifest file's (mtime, size) and its key, so a long run reads each once."""


def results_key(table_manifest: dict[str, Any]) -> str:
    """The part of a manifest that fixes its table's results, as one comparable string."""
    return json.dumps({name: table_manifest.get(name) for name in _SAME}, sort_keys=True)


def twin_tables(results_path: Path, key: str, root: Path) -> list[Path]:
    """Tables under `root`, other than `results_path`, whose manifest's key is `key`; by path."""
    own = results_path.resolve()
    found = []
    for where in sorted(root.rglob("*.json")):
        table = where.with_suffix(".csv")
        if table.resolve() == own or not table.is_file():
            continue
        if _key_of(where) == key:
            found.append(table)
    return found


def _key_of(where: Path) -> str | None:
    """The key of the manifest at `where`, or None if it is not one (cached by mtime, size)."""
    try:
        stat = where.stat()
    except OSError:
        return None
    stamp = (stat.st_mtime_ns, stat.st_size)
    cached = _KEYS.get(where)
    if cached is not None and cached[0] == stamp:
        return cached[1]
    try:
        data = json.loads(where.read_text())
        key = results_key(data) if isinstance(data, dict) and "spec" in data else None
    except (OSError, ValueError):
        key = None
    _KEYS[where] = (stamp, key)
    return key


def fill_from_twins(results_path: Path, spec: TrialSpec, n_trials: int) -> int:
    """Copy into `results_path` the trials 0..n_trials-1 it lacks that a twin table holds.

    The table is then what a resumed :func:`~robotsoccer.runs.pool.run_trials` of `spec`
    expects (its manifest written as that run would), so the pool runs only the rest.

    Returns:
        How many trials were copied (0 when no twin holds any, or when the table belongs to
        another run: the pool then refuses it with its own message).
    """
    results_path.parent.mkdir(parents=True, exist_ok=True)
    with holding(results_path.parent) as root:
        try:
            check_resumable(results_path, spec, root)
        except ResumeError:
            return 0
        have = {r.index for r in iter_results(results_path, repair=True)}
        if len(have) >= n_trials:
            return 0
        made = manifest(spec, root)
        copies: dict[int, TrialResult] = {}
        for twin in twin_tables(results_path, results_key(made), root):
            for result in iter_results(twin, warn=lambda _: None):
                index = result.index
                if index < n_trials and index not in have and index not in copies:
                    copies[index] = result
            if len(have) + len(copies) >= n_trials:
                break
        if not copies:
            return 0
        if not results_path.exists():
            write_manifest(results_path, made)
        writer = TableWriter(results_path, append=True)
        try:
            writer.write(copies[i] for i in sorted(copies))
        finally:
            writer.close()
        return len(copies)
