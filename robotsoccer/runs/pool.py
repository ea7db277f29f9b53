"""Many trials in parallel processes, streamed to a results table on disk as they finish.

* Trials run in chunks in a `ProcessPoolExecutor` (every worker builds its own pymunk space;
  nothing is shared); the chunks shrink toward a run's end (:func:`tapered`) so the workers
  finish together. Workers come from a ``forkserver`` that has imported the project once, so
  a pool starts in milliseconds rather than re-importing numpy and pymunk per worker (and, unlike
  a plain fork, never inherits the threads of a parent that trained a torch model). One worker
  runs the trials in this process, with no pool at all.
* Each finished chunk is appended to the CSV table (:mod:`robotsoccer.runs.table`) and flushed
  at once, so an interrupted run keeps every trial it finished; a rerun with ``resume=True``
  skips them. Beside the table a manifest (``<table>.json``) records what made it: the spec, the
  code version and the digests of the files the trials read (:mod:`robotsoccer.runs.provenance`),
  with paths inside the run folder stored relative to it, so a copied or moved folder resumes. A
  resume onto a table made by anything else is refused with one line saying what differs; a last
  row cut short by a killed write is dropped with a warning and run again.
* A run holds the lock of the table's folder while it writes (or of the run folder above it
  that the command holds already: :mod:`robotsoccer.runs.folders`), so two runs can never
  write one table at once.
* Results come back sorted by trial index, and each trial depends only on its own seed, so the
  table is identical whatever the worker count (a test checks this).
"""

from __future__ import annotations

import contextlib
import contextvars
import dataclasses
import functools
import json
import multiprocessing
import os
import signal
import sys
import time
from collections.abc import Callable, Iterable, Iterator, Sequence
from concurrent.futures import FIRST_COMPLETED, Future, ProcessPoolExecutor, wait
from pathlib import Path
from typing import Any, TextIO

from field_models.registry import preload_modules
from robotsoccer.drills.intercept_batch import DEFAULT_BATCH, batch_reason, run_intercept_batch
from robotsoccer.runs.folders import holding
from robotsoccer.runs.provenance import code_version, file_digest, machine
from robotsoccer.runs.runner import TrialResult, TrialSpec, resolve, run_trial
from robotsoccer.runs.table import ResumeError, TableWriter, iter_results
from robotsoccer.runs.table import read_results as read_results  # where callers found it


def default_workers() -> int:
    """All cores this process may use."""
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:  # pragma: no cover - not Linux
        return os.cpu_count() or 1


PRELOAD = ("robotsoccer.runs.pool", "robotsoccer.drills", *preload_modules())
"""Modules the fork server imports once, so that every worker starts with them loaded."""


def worker_context() -> multiprocessing.context.BaseContext:
    """A fork-server context preloaded with the project (spawn where forkserver is missing)."""
    if "forkserver" not in multiprocessing.get_all_start_methods():  # pragma: no cover
        return multiprocessing.get_context("spawn")
    context = multiprocessing.get_context("forkserver")
    context.set_forkserver_preload(list(PRELOAD))
    return context


def _ignore_interrupts() -> None:
    """Workers leave Ctrl-C to the parent, which stops the pool and keeps what finished.

    Without this every worker would print its own KeyboardInterrupt traceback.
    """
    signal.signal(signal.SIGINT, signal.SIG_IGN)


def run_chunk(spec: TrialSpec, indices: Sequence[int]) -> list[TrialResult]:
    """Run the trials `indices` of `spec` (the unit of work a worker receives).

    Trials the batched engine can run (:func:`batched`) run as arrays
    (:func:`~robotsoccer.drills.intercept_batch.run_intercept_batch`), with exactly the
    one-trial path's results; recorded trials and all others run one at a time.
    """
    if not batched(spec):
        return [run_trial(spec, i) for i in indices]
    plain = [i for i in indices if not spec.records(i)]
    results = {r.index: r for r in run_intercept_batch(spec, plain)}
    results.update((i, run_trial(spec, i)) for i in indices if spec.records(i))
    return [results[i] for i in indices]


@functools.lru_cache(maxsize=64)
def batched(spec: TrialSpec) -> bool:
    """Whether `spec`'s trials run through the batched engine.

    The Soccer Server intercept drill does (:func:`~robotsoccer.drills.intercept_batch.
    batch_reason` says what does not).
    """
    return batch_reason(spec) is None


CHUNKS_PER_WORKER = 4
"""Chunks of plain trials queued per worker: a chunk is at most that share of what is left."""


def default_chunk_size(spec: TrialSpec, remaining: int, workers: int) -> int:
    """Trials per unit of work: a few chunks per worker.

    At most one batch for batched specs (a large chunk is what makes a batch pay), else 50.
    """
    limit = DEFAULT_BATCH if batched(spec) else 50
    parts = (2 if batched(spec) else CHUNKS_PER_WORKER) * workers
    return max(1, min(limit, remaining // parts or 1))


def chunked(indices: Iterable[int], size: int) -> Iterator[list[int]]:
    """Split `indices` into lists of at most `size`, as they come (any iterable, lazily)."""
    chunk: list[int] = []
    for index in indices:
        chunk.append(index)
        if len(chunk) == size:
            yield chunk
            chunk = []
    if chunk:
        yield chunk


def tapered(indices: Iterable[int], size: int, remaining: int, workers: int) -> Iterator[list[int]]:
    """Chunks of at most `size` that shrink toward the end of the run, to no less than size/8.

    The last chunks decide when the run ends: with full-size chunks one worker may run a whole
    chunk alone while the others wait. Here a chunk is at most a quarter of each worker's share
    of what is left, so the workers finish close together (a result depends only on its trial,
    so chunking never changes one).

    Args:
        indices: The trials to run, in order.
        size: The largest chunk.
        remaining: How many `indices` yields.
        workers: Processes sharing the work.
    """
    floor, parts = max(1, size // 8), CHUNKS_PER_WORKER * workers
    chunk: list[int] = []
    want = max(floor, min(size, remaining // parts))
    for index in indices:
        chunk.append(index)
        if len(chunk) == want:
            yield chunk
            remaining -= want
            chunk = []
            want = max(floor, min(size, remaining // parts))
    if chunk:
        yield chunk


class Progress:
    """Progress of a run on stderr: a tqdm bar on a terminal, plain lines anywhere else.

    A bar's carriage returns garble a log file or a pipe, so when the stream is not a
    terminal the progress is a line at every tenth of the run instead.

    Args:
        total: Trials in the run.
        stream: Where to write.
        enabled: False draws nothing at all.
    """

    def __init__(self, total: int, stream: TextIO = sys.stderr, enabled: bool = True) -> None:
        self.total = total
        self.done = 0
        self.stream = stream
        self.enabled = enabled and total > 0
        self.start = time.perf_counter()
        self._bar: Any = None
        self._next_line = 0.1
        if self.enabled and stream.isatty():
            from tqdm import tqdm

            self._bar = tqdm(total=total, file=stream, unit="trial", dynamic_ncols=True)

    def advance(self, count: int) -> None:
        """Count `count` more finished trials."""
        self.done += count
        if not self.enabled:
            return
        if self._bar is not None:
            self._bar.update(count)
            return
        share = self.done / self.total
        if share + 1e-12 >= self._next_line or self.done >= self.total:
            elapsed = time.perf_counter() - self.start
            rate = self.done / elapsed if elapsed > 0 else 0.0
            self.stream.write(
                f"progress: {self.done}/{self.total} trials ({100 * share:.0f}%), "
                f"{rate:.1f} trials/s\n"
            )
            self.stream.flush()
            self._next_line = (int(share * 10) + 1) / 10

    def close(self) -> None:
        """End the bar (a no-op for plain lines)."""
        if self._bar is not None:
            self._bar.close()


def manifest(spec: TrialSpec, root: Path | None = None) -> dict[str, Any]:
    """What makes a run's results: its spec, the code version and its input files' digests.

    Args:
        spec: The run's spec.
        root: The run folder: absolute paths inside it (model files, presets) are stored
            relative to it, so a copy of the folder is the same run. None keeps every path.

    It also records the machine (CPU, numpy's SIMD dispatch, versions); a resume does not
    compare it, since results do not depend on it.
    """
    root = root.resolve() if root is not None else None
    inputs = resolve(spec).new_drill().inputs()
    recorded = dataclasses.replace(spec, record_dir=None, record_trials=0)
    return {
        "spec": _relative(json.loads(json.dumps(dataclasses.asdict(recorded), default=str)), root),
        "code_version": code_version(),
        "inputs": {_relative(path, root): file_digest(path) for path in inputs},
        "machine": machine(),
    }


def _relative(value: Any, root: Path | None) -> Any:
    """`value` (JSON data) with every absolute path inside `root` made relative to it."""
    if root is None:
        return value
    if isinstance(value, dict):
        return {_relative(k, root): _relative(v, root) for k, v in value.items()}
    if isinstance(value, list):
        return [_relative(v, root) for v in value]
    if isinstance(value, str) and os.path.isabs(value):
        path = Path(value).resolve()
        if path.is_relative_to(root):
            return path.relative_to(root).as_posix()
    return value


def manifest_path(results_path: Path) -> Path:
    """Where the manifest of a results table lives: beside it, ``.json``."""
    return results_path.with_suffix(".json")


def check_resumable(results_path: Path, spec: TrialSpec, root: Path | None = None) -> None:
    """Refuse to add `spec`'s trials to a table another run made (one line: what differs).

    Args:
        results_path: The table.
        spec: What the run now would run.
        root: The run folder (:func:`manifest`); None: the table's folder. A manifest written
            with absolute paths (before paths were stored relative) is read the same way.

    Raises:
        ResumeError: The table exists but its manifest is missing, unreadable or different.
    """
    if not results_path.exists():
        return
    root = (root or results_path.parent).resolve()
    where = manifest_path(results_path)
    try:
        old = json.loads(where.read_text())
        old = {**old, "spec": _relative(old.get("spec", {}), root),
               "inputs": _relative(old.get("inputs"), root)}  # fmt: skip
    except (OSError, ValueError, AttributeError, TypeError):  # absent, not JSON, not a dict
        raise ResumeError(
            f"{results_path}: no readable record of the run that made it ({where.name}); "
            "--overwrite replaces it, or choose another --out"
        ) from None
    new = manifest(spec, root)
    differences = _differences(old, new)
    if differences:
        raise ResumeError(
            f"{results_path} was made by another run ({'; '.join(differences)}); "
            "--overwrite replaces it, or choose another --out"
        )


def _differences(old: dict[str, Any], new: dict[str, Any]) -> list[str]:
    found = []
    old_spec, new_spec = old.get("spec", {}), new["spec"]
    for key in sorted(set(old_spec) | set(new_spec)):
        if old_spec.get(key) != new_spec.get(key):
            found.append(f"{key} {old_spec.get(key)!r} then, {new_spec.get(key)!r} now")
    if old.get("code_version") != new["code_version"]:
        found.append(f"code version {old.get('code_version')} then, {new['code_version']} now")
    if old.get("inputs") != new["inputs"]:
        found.append("its model files changed")
    return found


_BACKEND: contextvars.ContextVar[str] = contextvars.ContextVar("backend", default="process")


@contextlib.contextmanager
def using_backend(backend: str) -> Iterator[None]:
    """Run every :func:`run_trials` inside the block on `backend` unless it names its own.

    The CLI sets it once per command, so the experiments' many runs need no parameter for it.
    """
    token = _BACKEND.set(backend)
    try:
        yield
    finally:
        _BACKEND.reset(token)


def run_trials(
    spec: TrialSpec,
    n_trials: int,
    *,
    workers: int | None = None,
    results_path: Path | None = None,
    resume: bool = False,
    progress: bool = True,
    chunk_size: int | None = None,
    on_result: Callable[[TrialResult], None] | None = None,
) -> list[TrialResult]:
    """Run trials 0..n_trials-1 of `spec` and return their results sorted by index.

    Trial indices are generated as the work goes, and with `on_result` no result is held:
    memory does not grow with `n_trials` beyond one byte per trial.

    Trials run on the backend :func:`using_backend` set (default ``"process"``: a process pool
    on this machine; ``"ray"``: Ray tasks, on a local Ray instance or the cluster
    ``RAY_ADDRESS`` names, :mod:`robotsoccer.runs.ray_backend`). The results are the same
    either way; the CLI sets it once per command (``--backend``).

    Args:
        spec: What to run.
        n_trials: How many trials.
        workers: Processes to use (default: all cores); 1 runs in this process.
        results_path: CSV table to stream results into (appended as chunks finish).
        resume: Keep the trials already in `results_path` and run only the others; refused
            (ResumeError) when another spec, code version or model file made them.
        progress: Show progress on stderr (a bar on a terminal, lines otherwise).
        chunk_size: Trials per unit of work (default: small enough to balance the workers).
        on_result: Stream every result to it (the resumed ones first) instead of returning
            them: the run then returns [].

    Raises:
        KeyboardInterrupt: after flushing every finished trial to `results_path`.
        ResumeError: `resume` onto a table another run made, or a damaged table.
        ValueError: An unknown backend, or ``"ray"`` without Ray installed (before anything
            is written).
    """
    backend = _BACKEND.get()
    keep = on_result is None
    if backend not in ("process", "ray"):
        raise ValueError(f"unknown backend {backend!r}: choose 'process' or 'ray'")
    if backend == "ray":
        from robotsoccer.runs.ray_backend import require_ray

        require_ray()
    workers = workers or default_workers()
    finished = bytearray(n_trials)  # one byte a trial: which indices are done
    kept: dict[int, TrialResult] = {}

    def record(result: TrialResult) -> None:
        finished[result.index] = 1
        if keep:
            kept[result.index] = result
        if on_result is not None:
            on_result(result)

    with contextlib.ExitStack() as stack:
        writer = None
        resumed = 0
        if results_path is not None:
            results_path.parent.mkdir(parents=True, exist_ok=True)
            # held until the run ends: no other run may read or append this table meanwhile
            root = stack.enter_context(holding(results_path.parent))
            if resume:
                check_resumable(results_path, spec, root)
                for result in iter_results(results_path, repair=True):
                    if result.index < n_trials and not finished[result.index]:
                        record(result)
                        resumed += 1
            write_manifest(results_path, manifest(spec, root))
            writer = TableWriter(results_path, append=resume)
            stack.callback(writer.close)
        remaining = n_trials - resumed
        todo = (i for i in range(n_trials) if not finished[i])
        if chunk_size or batched(spec):  # a batch pays by its size: never tapered
            chunks = chunked(todo, chunk_size or default_chunk_size(spec, remaining, workers))
        else:
            chunks = tapered(todo, default_chunk_size(spec, remaining, workers), remaining, workers)
        bar = Progress(n_trials, enabled=progress)
        stack.callback(bar.close)
        bar.advance(resumed)
        for chunk in _execute(spec, chunks, workers, backend):
            for result in chunk:
                record(result)
            if writer is not None:
                writer.write(chunk)
            bar.advance(len(chunk))
    return [kept[i] for i in sorted(kept)]


def write_manifest(results_path: Path, made: dict[str, Any]) -> None:
    """Write a table's manifest whole or not at all (a kill must not leave half of one).

    Args:
        results_path: The table.
        made: Its manifest (:func:`manifest`).
    """
    where = manifest_path(results_path)
    partial = where.with_name(where.name + ".part")
    partial.write_text(json.dumps(made, indent=2) + "\n")
    partial.replace(where)


def _execute(
    spec: TrialSpec, chunks: Iterable[list[int]], workers: int, backend: str = "process"
) -> Iterator[list[TrialResult]]:
    """Yield finished chunks as they complete (any order)."""
    if backend == "ray":  # Ray is imported only here, when asked for
        from robotsoccer.runs.ray_backend import execute_ray

        yield from execute_ray(spec, chunks, workers, run_chunk)
        return
    if workers <= 1:
        for chunk in chunks:
            yield run_chunk(spec, chunk)
        return
    context = worker_context()
    pool = ProcessPoolExecutor(
        max_workers=workers, mp_context=context, initializer=_ignore_interrupts
    )
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
