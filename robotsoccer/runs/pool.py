"""Many trials in parallel processes, streamed to a results table on disk as they finish.

* Trials run in chunks in a `ProcessPoolExecutor` (every worker builds its own pymunk space;
  nothing is shared). Workers come from a ``forkserver`` that has imported the project once, so
  a pool starts in milliseconds rather than re-importing numpy and pymunk per worker (and, unlike
  a plain fork, never inherits the threads of a parent that trained a torch model). One worker
  runs the trials in this process, with no pool at all.
* Each finished chunk is appended to the CSV table and flushed at once, so an interrupted run
  keeps every trial it finished; a rerun with ``resume=True`` skips them.
* Results come back sorted by trial index, and each trial depends only on its own seed, so the
  table is identical whatever the worker count (a test checks this).
"""

from __future__ import annotations

import multiprocessing
import os
import sys
import time
from collections.abc import Iterable, Iterator, Sequence
from concurrent.futures import FIRST_COMPLETED, Future, ProcessPoolExecutor, wait
from pathlib import Path
from typing import TextIO

from robotsoccer.runs.runner import TrialResult, TrialSpec, run_trial


def default_workers() -> int:
    """All cores this process may use."""
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:  # pragma: no cover - not Linux
        return os.cpu_count() or 1


PRELOAD = (
    "robotsoccer.runs.pool",
    "robotsoccer.drills",
    "field_models.robot_physics.arena",
    "field_models.soccer_server.arena",
)
"""Modules the fork server imports once, so that every worker starts with them loaded."""


def _worker_context() -> multiprocessing.context.BaseContext:
    """A fork-server context preloaded with the project (spawn where forkserver is missing)."""
    if "forkserver" not in multiprocessing.get_all_start_methods():  # pragma: no cover
        return multiprocessing.get_context("spawn")
    context = multiprocessing.get_context("forkserver")
    context.set_forkserver_preload(list(PRELOAD))
    return context


def run_chunk(spec: TrialSpec, indices: Sequence[int]) -> list[TrialResult]:
    """Run the trials `indices` of `spec` (the unit of work a worker receives)."""
    return [run_trial(spec, i) for i in indices]


def chunked(indices: Sequence[int], size: int) -> Iterator[list[int]]:
    """Split `indices` into lists of at most `size`."""
    for start in range(0, len(indices), size):
        yield list(indices[start : start + size])


class Progress:
    """A one-line progress bar on a terminal stream (silent when `enabled` is False)."""

    def __init__(self, total: int, stream: TextIO = sys.stderr, enabled: bool = True) -> None:
        self.total = total
        self.done = 0
        self.stream = stream
        self.enabled = enabled
        self.start = time.perf_counter()

    def advance(self, count: int) -> None:
        """Count `count` more finished trials and redraw."""
        self.done += count
        if not self.enabled:
            return
        elapsed = time.perf_counter() - self.start
        rate = self.done / elapsed if elapsed > 0 else 0.0
        filled = int(30 * self.done / max(1, self.total))
        bar = "#" * filled + "-" * (30 - filled)
        end = "\n" if self.done >= self.total else ""
        self.stream.write(f"\r[{bar}] {self.done}/{self.total} trials  {rate:6.1f}/s{end}")
        self.stream.flush()


def read_results(path: Path) -> dict[int, TrialResult]:
    """Results already in a table (for resuming); an absent file holds none."""
    if not path.exists():
        return {}
    lines = path.read_text().splitlines()
    rows = [line for line in lines[1:] if line.strip()]
    results = (TrialResult.from_csv_row(line) for line in rows)
    return {r.index: r for r in results}


def run_trials(
    spec: TrialSpec,
    n_trials: int,
    *,
    workers: int | None = None,
    results_path: Path | None = None,
    resume: bool = False,
    progress: bool = True,
    chunk_size: int | None = None,
) -> list[TrialResult]:
    """Run trials 0..n_trials-1 of `spec` and return their results sorted by index.

    Args:
        spec: What to run.
        n_trials: How many trials.
        workers: Processes to use (default: all cores); 1 runs in this process.
        results_path: CSV table to stream results into (appended as chunks finish).
        resume: Keep the trials already in `results_path` and run only the others.
        progress: Draw a progress bar on stderr.
        chunk_size: Trials per unit of work (default: small enough to balance the workers).

    Raises:
        KeyboardInterrupt: after flushing every finished trial to `results_path`.
    """
    workers = workers or default_workers()
    done = read_results(results_path) if (results_path and resume) else {}
    todo = [i for i in range(n_trials) if i not in done]
    size = chunk_size or max(1, min(50, len(todo) // (4 * workers) or 1))
    bar = Progress(n_trials, enabled=progress)
    bar.advance(len(done))
    sink = _open_sink(results_path, keep=bool(done))
    try:
        for chunk in _execute(spec, chunked(todo, size), workers):
            for result in chunk:
                done[result.index] = result
                if sink is not None:
                    sink.write(result.csv_row() + "\n")
            if sink is not None:
                sink.flush()
            bar.advance(len(chunk))
    finally:
        if sink is not None:
            sink.close()
    return [done[i] for i in sorted(done) if i < n_trials]


def _open_sink(path: Path | None, keep: bool) -> TextIO | None:
    if path is None:
        return None
    path.parent.mkdir(parents=True, exist_ok=True)
    if keep:
        return path.open("a")
    sink = path.open("w")
    sink.write(TrialResult.CSV_HEADER + "\n")
    return sink


def _execute(
    spec: TrialSpec, chunks: Iterable[list[int]], workers: int
) -> Iterator[list[TrialResult]]:
    """Yield finished chunks as they complete (any order)."""
    if workers <= 1:
        for chunk in chunks:
            yield run_chunk(spec, chunk)
        return
    context = _worker_context()
    pool = ProcessPoolExecutor(max_workers=workers, mp_context=context)
    pending: set[Future[list[TrialResult]]] = set()
    queue = iter(chunks)
    try:
        for chunk in queue:  # keep a few chunks in flight per worker, not all of them
            pending.add(pool.submit(run_chunk, spec, chunk))
            if len(pending) >= 3 * workers:
                break
        while pending:
            finished, pending = wait(pending, return_when=FIRST_COMPLETED)
            for future in finished:
                yield future.result()
                nxt = next(queue, None)
                if nxt is not None:
                    pending.add(pool.submit(run_chunk, spec, nxt))
    finally:
        pool.shutdown(wait=not pending, cancel_futures=True)
