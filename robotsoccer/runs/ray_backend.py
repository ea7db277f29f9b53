"""Trials as Ray tasks: the pool's chunks on a local Ray instance or on a Ray cluster.

:func:`robotsoccer.runs.pool.run_trials` with ``backend="ray"`` hands its chunks to
:func:`execute_ray`, which runs each as a Ray task calling the same
:func:`robotsoccer.runs.pool.run_chunk` the process pool calls, so the results (and the table
they are streamed into) are the same whatever the backend.

* Where: ``RAY_ADDRESS`` in the environment names a cluster to join (``host:6379`` from
  ``ray start --head``, ``auto`` for the one running on this machine, ``ray://host:10001`` for
  Ray Client, which needs ``ray[client]``); without it a private local instance starts with one
  CPU per worker. A Ray already initialised in this process (``ray.init`` called by the caller)
  is used as it is. Every node must have the same version of this project installed: the tasks
  import it there.
* How much at once: a few chunks per CPU are in flight, never all of them, so that memory does
  not grow with the run and a Ctrl-C loses little.
* Ctrl-C (or the caller stopping early) cancels the tasks still out; the chunks that finished
  were already handed back, and :func:`~robotsoccer.runs.pool.run_trials` has flushed them.
  An error inside a trial is raised as itself, as the process pool raises it.

Ray is imported only here, and only when this backend is used; without it the error is one line
(:func:`require_ray`).
"""

from __future__ import annotations

import contextlib
import importlib
import logging
import os
from collections.abc import Callable, Iterable, Iterator, Sequence
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from robotsoccer.runs.runner import TrialResult, TrialSpec

MISSING_RAY = "backend 'ray' needs Ray: pip install '.[ray]'"
"""The one line a run with the Ray backend fails with where Ray is not installed."""

IN_FLIGHT_PER_CPU = 3
"""Chunks submitted ahead per CPU (the process pool keeps as many per worker)."""

SETTLE_S = 5.0
"""How long a failing run waits for its cancelled tasks to end, to collect their errors."""


def require_ray() -> Any:
    """The ``ray`` module, imported now.

    Returns:
        The module (typed Any: Ray is an optional dependency).

    Raises:
        ValueError: Ray is not installed (:data:`MISSING_RAY`, one line).
    """
    try:
        return importlib.import_module("ray")
    except ImportError:
        raise ValueError(MISSING_RAY) from None


def connect(workers: int) -> Any:
    """Join the Ray named by ``RAY_ADDRESS``, or start a local one; reuse one already joined.

    Args:
        workers: CPUs of a local instance started here (ignored when joining a cluster).

    Returns:
        The ``ray`` module, initialised.

    Raises:
        ValueError: Ray is not installed.
    """
    ray = require_ray()
    if ray.is_initialized():
        return ray
    address = os.environ.get("RAY_ADDRESS") or None
    quiet: dict[str, Any] = {
        "include_dashboard": False,
        "log_to_driver": False,
        "logging_level": logging.WARNING,
    }
    if address is None:  # "local": a private instance, not whatever `ray start` left running
        # A private instance needs no word on its access token (recent Ray warns of it).
        auth = logging.getLogger("ray._private.authentication")
        level = auth.level
        auth.setLevel(logging.ERROR)
        try:
            ray.init(address="local", num_cpus=max(1, workers), **quiet)
        finally:
            auth.setLevel(level)
    else:
        ray.init(address=address, **quiet)
    return ray


def _result(ray: Any, ref: Any) -> list[TrialResult]:
    """A finished task's chunk; its error raised as the error the trial raised.

    As the process pool does: Ray's own wrapper would put the task's name, pid and address
    where the CLI expects the error's message.
    """
    try:
        chunk: list[TrialResult] = ray.get(ref)
    except ray.exceptions.RayTaskError as exc:
        cause = getattr(exc, "cause", None)
        if isinstance(cause, Exception):
            raise cause from exc
        raise
    return chunk


ChunkRunner = Callable[["TrialSpec", Sequence[int]], "list[TrialResult]"]
"""Runs one chunk of trials: the pool's :func:`~robotsoccer.runs.pool.run_chunk`."""


def execute_ray(
    spec: TrialSpec, chunks: Iterable[list[int]], workers: int, run_chunk: ChunkRunner
) -> Iterator[list[TrialResult]]:
    """Run `chunks` of `spec` as Ray tasks and yield each chunk's results as it finishes.

    Ray is joined (or started) before the first chunk is submitted. At most
    :data:`IN_FLIGHT_PER_CPU` chunks per CPU (the larger of `workers` and the CPUs of the Ray
    cluster) are out at a time. When the caller stops early, by Ctrl-C or by closing this
    generator, the tasks still out are cancelled.

    Args:
        spec: What to run.
        chunks: Lists of trial indices, taken lazily.
        workers: CPUs of a local Ray instance started here; the least parallelism to plan for.
        run_chunk: The chunk's body, a module-level function the workers import by name (the
            pool passes its own, so this module needs nothing from the pool).

    Yields:
        The results of one chunk, in the order of its indices; chunks in any order.

    Raises:
        ValueError: Ray is not installed.
        Exception: What a trial raised, itself (not Ray's wrapper of it), as the process pool
            does; the other tasks are cancelled first.
    """
    ray = connect(workers)
    cpus = int(ray.cluster_resources().get("CPU", 0))
    limit = IN_FLIGHT_PER_CPU * max(workers, cpus, 1)
    task = ray.remote(num_cpus=1)(run_chunk)
    spec_ref = ray.put(spec)  # sent to the object store once, not with every chunk
    queue = iter(chunks)
    pending: list[Any] = []
    try:
        for chunk in queue:
            pending.append(task.remote(spec_ref, chunk))
            if len(pending) >= limit:
                break
        while pending:
            done, pending = ray.wait(pending, num_returns=1)
            for ref in done:
                try:
                    results = _result(ray, ref)
                except Exception:
                    _cancel(ray, pending, settle=True)
                    pending = []
                    raise
                yield results
                nxt = next(queue, None)
                if nxt is not None:
                    pending.append(task.remote(spec_ref, nxt))
    finally:
        _cancel(ray, pending)


def _cancel(ray: Any, refs: list[Any], settle: bool = False) -> None:
    """Cancel the tasks of `refs` that are not done; with `settle`, first let them finish.

    Ray 2.x can abort the driver when a cancel races with a task's completion ("Check failed:
    it != submissible_tasks_.end()", ray-project/ray#54846): seen here about once in eight
    suite runs. So a failing run first waits up to :data:`SETTLE_S` for its few in-flight
    tasks (their errors are collected, not logged by Ray with tracebacks), and only the tasks
    still not done are cancelled.
    """
    if not refs:
        return
    timeout = SETTLE_S if settle else 0.0
    ready, waiting = ray.wait(refs, num_returns=len(refs), timeout=timeout)
    for ref in waiting:
        ray.cancel(ref)
    for ref in ready:
        with contextlib.suppress(Exception):
            ray.get(ref)
