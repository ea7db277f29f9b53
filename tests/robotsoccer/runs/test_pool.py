"""The process pool: streamed results, interruption keeps finished trials, resume runs the rest."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np
import pytest

import robotsoccer.runs.pool as pool
from learning.lookup import LookupTable
from robotsoccer.runs.pool import (
    ResumeError,
    manifest,
    manifest_path,
    read_results,
    run_trials,
)
from robotsoccer.runs.runner import TrialResult, TrialSpec
from robotsoccer.runs.table import iter_results

SPEC = TrialSpec(drill="shootout", field_model="robot_physics", seed=11)


def test_results_stream_to_a_table_sorted_by_index(tmp_path) -> None:
    path = tmp_path / "results.csv"
    results = run_trials(SPEC, 5, workers=1, results_path=path, progress=False, chunk_size=2)
    assert [r.index for r in results] == list(range(5))
    assert path.read_text().splitlines()[0] == TrialResult.CSV_HEADER
    assert read_results(path) == {r.index: r for r in results}


def test_interrupted_run_keeps_finished_trials_and_resume_runs_only_the_rest(
    tmp_path, monkeypatch
) -> None:
    path = tmp_path / "results.csv"
    real_chunk = pool.run_chunk
    calls: list[list[int]] = []

    def interrupted_after_two_chunks(spec, indices):
        if len(calls) == 2:
            raise KeyboardInterrupt
        calls.append(list(indices))
        return real_chunk(spec, indices)

    monkeypatch.setattr(pool, "run_chunk", interrupted_after_two_chunks)
    with pytest.raises(KeyboardInterrupt):
        run_trials(SPEC, 6, workers=1, results_path=path, progress=False, chunk_size=2)
    kept = read_results(path)
    assert sorted(kept) == [0, 1, 2, 3]

    ran: list[list[int]] = []

    def counting(spec, indices):
        ran.append(list(indices))
        return real_chunk(spec, indices)

    monkeypatch.setattr(pool, "run_chunk", counting)
    results = run_trials(
        SPEC, 6, workers=1, results_path=path, resume=True, progress=False, chunk_size=2
    )
    assert ran == [[4, 5]]
    assert [r.index for r in results] == list(range(6))
    fresh = run_trials(SPEC, 6, workers=1, progress=False)
    assert results == fresh


def test_a_resume_onto_another_runs_table_is_refused_in_one_line(tmp_path) -> None:
    path = tmp_path / "results.csv"
    run_trials(SPEC, 3, workers=1, results_path=path, progress=False)
    other = dataclasses.replace(SPEC, seed=12)
    with pytest.raises(ResumeError, match="seed 11 then, 12 now") as caught:
        run_trials(other, 3, workers=1, results_path=path, resume=True, progress=False)
    assert "\n" not in str(caught.value)
    options = SPEC.with_options(max_time_s=5.0)
    with pytest.raises(ResumeError, match="drill_options"):
        run_trials(options, 3, workers=1, results_path=path, resume=True, progress=False)
    manifest_path(path).unlink()
    with pytest.raises(ResumeError, match="no readable record"):
        run_trials(SPEC, 3, workers=1, results_path=path, resume=True, progress=False)


def test_a_resume_refuses_results_of_another_code_version(tmp_path, monkeypatch) -> None:
    path = tmp_path / "results.csv"
    run_trials(SPEC, 2, workers=1, results_path=path, progress=False)
    monkeypatch.setattr(pool, "code_version", lambda: "0123456789abcdef")
    with pytest.raises(ResumeError, match="code version"):
        run_trials(SPEC, 2, workers=1, results_path=path, resume=True, progress=False)


def test_a_resume_refuses_results_made_with_another_model_file(tmp_path) -> None:
    model = tmp_path / "table.json"
    LookupTable([-0.1, 0.1], [0.0, 0.0]).save(model)
    spec = TrialSpec(drill="intercept", field_model="soccer_server", seed=1).with_options(
        behaviour="lookup",
        model=str(model),
        transfer=True,  # a hand-made table: no origin
    )
    path = tmp_path / "results.csv"
    run_trials(spec, 2, workers=1, results_path=path, progress=False)
    run_trials(spec, 3, workers=1, results_path=path, resume=True, progress=False)  # same file
    LookupTable([-0.1, 0.1], [0.1, 0.1]).save(model)
    with pytest.raises(ResumeError, match="model files changed"):
        run_trials(spec, 4, workers=1, results_path=path, resume=True, progress=False)


def test_a_last_row_cut_short_is_dropped_with_a_warning_and_run_again(tmp_path) -> None:
    path = tmp_path / "results.csv"
    full = run_trials(SPEC, 4, workers=1, results_path=path, progress=False)
    text = path.read_text()
    path.write_text(text[: text.rindex("\n", 0, len(text) - 1) + 12])  # kill mid-row
    warnings: list[str] = []
    kept = read_results(path, warnings.append)
    assert sorted(kept) == [0, 1, 2] and len(warnings) == 1 and "cut short" in warnings[0]
    assert not path.read_text().endswith("\n")  # a reader leaves the file as it is
    list(iter_results(path, warnings.append, repair=True))  # what a resume does first
    assert path.read_text().endswith("\n") and "dropped" in warnings[1]
    again = run_trials(SPEC, 4, workers=1, results_path=path, resume=True, progress=False)
    assert again == full
    assert read_results(path) == {r.index: r for r in full}


def test_a_damaged_row_in_the_middle_is_refused(tmp_path) -> None:
    path = tmp_path / "results.csv"
    run_trials(SPEC, 3, workers=1, results_path=path, progress=False)
    lines = path.read_text().splitlines()
    lines[2] = "garbage"
    path.write_text("\n".join(lines) + "\n")
    with pytest.raises(ResumeError, match="line 3 is not a result row"):
        read_results(path)


def test_a_manifest_records_the_cpu_and_numpys_simd_dispatch(tmp_path: Path) -> None:
    import numpy._core._multiarray_umath as umath

    spec = TrialSpec(drill="intercept", field_model="soccer_server", seed=1)
    recorded = manifest(spec)["machine"]
    assert recorded["cpu"] and recorded["numpy_simd_baseline"] == list(umath.__cpu_baseline__)
    assert set(recorded["numpy_simd_dispatched"]) <= set(umath.__cpu_dispatch__)
    assert recorded["packages"]["numpy"] == np.__version__


@pytest.mark.parametrize(
    ("n", "size", "workers"), [(1000, 50, 2), (37, 9, 2), (5, 50, 4), (400, 50, 1)]
)
def test_tapered_chunks_cover_every_trial_in_order_and_shrink_to_an_eighth(
    n: int, size: int, workers: int
) -> None:
    chunks = list(pool.tapered(iter(range(n)), size, n, workers))
    assert [i for c in chunks for i in c] == list(range(n))
    sizes = [len(c) for c in chunks]
    assert max(sizes) <= size
    assert all(s >= max(1, size // 8) for s in sizes[:-1])
    assert sizes[:-1] == sorted(sizes[:-1], reverse=True)  # never grows again


def test_a_long_run_ends_in_small_chunks() -> None:
    sizes = [len(c) for c in pool.tapered(iter(range(5000)), 50, 5000, 2)]
    assert sizes[0] == 50 and sizes[-2] == 6  # the tail: an eighth of the largest
    assert sum(s == 50 for s in sizes) >= 90
