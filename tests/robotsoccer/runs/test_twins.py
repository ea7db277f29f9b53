"""Twin tables: trials a run folder holds already under another name are copied, not run again."""

from __future__ import annotations

import dataclasses
import json
from pathlib import Path

import pytest

import robotsoccer.runs.pool as pool
from robotsoccer.experiments.layer1_evaluate import evaluate
from robotsoccer.experiments.layer1_plan import Condition
from robotsoccer.runs.folders import holding
from robotsoccer.runs.pool import manifest_path, read_results, run_trials
from robotsoccer.runs.runner import TrialSpec
from robotsoccer.runs.twins import fill_from_twins, twin_tables

SPEC = TrialSpec(drill="shootout", field_model="robot_physics", seed=11)


def _counting(monkeypatch: pytest.MonkeyPatch) -> list[int]:
    """Every trial index the pool runs from now on."""
    ran: list[int] = []
    real = pool.run_chunk

    def counting(spec, indices):
        ran.extend(indices)
        return real(spec, indices)

    monkeypatch.setattr(pool, "run_chunk", counting)
    return ran


def test_a_twin_cell_is_copied_whole_and_equals_a_fresh_run(tmp_path, monkeypatch) -> None:
    with holding(tmp_path):  # the run folder, as a command holds it: both folders lie in it
        first = evaluate(Condition("a", SPEC, 4), tmp_path / "one", workers=1)
        ran = _counting(monkeypatch)
        results, run_now, _ = evaluate(Condition("b", SPEC, 4), tmp_path / "two", workers=1)
    assert ran == [] and run_now == 0
    assert results == first[0]
    assert read_results(tmp_path / "two" / "b.csv") == {r.index: r for r in results}
    assert (
        json.loads(manifest_path(tmp_path / "two" / "b.csv").read_text())["spec"]
        == (json.loads(manifest_path(tmp_path / "one" / "a.csv").read_text())["spec"])
    )


def test_a_longer_cell_copies_the_twins_trials_and_runs_only_the_rest(
    tmp_path, monkeypatch
) -> None:
    evaluate(Condition("short", SPEC, 3), tmp_path, workers=1)
    ran = _counting(monkeypatch)
    results, run_now, _ = evaluate(Condition("long", SPEC, 5), tmp_path, workers=1)
    assert sorted(ran) == [3, 4] and run_now == 2
    assert results == run_trials(SPEC, 5, workers=1, progress=False)


def test_tables_of_another_spec_or_model_file_are_not_twins(tmp_path, monkeypatch) -> None:
    evaluate(Condition("a", SPEC, 2), tmp_path, workers=1)
    ran = _counting(monkeypatch)
    evaluate(Condition("b", dataclasses.replace(SPEC, seed=12), 2), tmp_path, workers=1)
    evaluate(Condition("c", SPEC.with_options(max_time_s=5.0), 2), tmp_path, workers=1)
    assert sorted(ran) == [0, 0, 1, 1]


def test_a_changed_code_version_is_not_a_twin(tmp_path, monkeypatch) -> None:
    evaluate(Condition("a", SPEC, 2), tmp_path, workers=1)
    monkeypatch.setattr(pool, "code_version", lambda: "another")
    ran = _counting(monkeypatch)
    evaluate(Condition("b", SPEC, 2), tmp_path, workers=1)
    assert sorted(ran) == [0, 1]


def test_only_the_held_run_folder_is_searched(tmp_path: Path) -> None:
    run_trials(SPEC, 2, workers=1, results_path=tmp_path / "x" / "a.csv", progress=False)
    assert fill_from_twins(tmp_path / "y" / "b.csv", SPEC, 2) == 0
    assert twin_tables(tmp_path / "y" / "b.csv", "key", tmp_path / "y") == []


def test_a_table_of_another_run_is_left_for_the_pool_to_refuse(tmp_path) -> None:
    evaluate(Condition("a", SPEC, 2), tmp_path, workers=1)
    other = tmp_path / "b.csv"
    run_trials(dataclasses.replace(SPEC, seed=12), 1, workers=1, results_path=other,
               progress=False)  # fmt: skip
    before = other.read_bytes()
    assert fill_from_twins(other, SPEC, 2) == 0
    assert other.read_bytes() == before
    with pytest.raises(pool.ResumeError, match="seed 12 then, 11 now"):
        evaluate(Condition("b", SPEC, 2), tmp_path, workers=1)


def test_a_twins_row_cut_short_is_not_copied(tmp_path, monkeypatch) -> None:
    evaluate(Condition("a", SPEC, 3), tmp_path, workers=1)
    twin = tmp_path / "a.csv"
    text = twin.read_text()
    twin.write_text(text[: len(text) - 5])  # the last row loses its end, as a kill leaves it
    ran = _counting(monkeypatch)
    results, _, _ = evaluate(Condition("b", SPEC, 3), tmp_path, workers=1)
    assert ran == [2]
    assert twin.read_text() == text[: len(text) - 5]  # the twin is read, never repaired
    assert results == run_trials(SPEC, 3, workers=1, progress=False)
