"""The process pool: streamed results, interruption keeps finished trials, resume runs the rest."""

from __future__ import annotations

import pytest

import robotsoccer.runs.pool as pool
from robotsoccer.runs.pool import read_results, run_trials
from robotsoccer.runs.runner import TrialResult, TrialSpec

SPEC = TrialSpec(seed=11)


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
