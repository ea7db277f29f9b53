"""Speed and memory of the batched interception drill and its vector environment.

The ``intercept.*batch*`` and ``envs.*`` figures of ``robotsoccer bench``
(:func:`robotsoccer.bench.iter_benchmarks`):

* ``intercept.trials_per_s.soccer_server_batch`` — trials per wall second of the batched engine
  (:func:`~robotsoccer.drills.intercept_batch.run_intercept_batch`, every result built as a
  :class:`~robotsoccer.runs.runner.TrialResult`) on all cores: one process per core, each
  running its share in batches of the default size; process start-up excluded, nothing written.
* ``intercept.batch_trials_per_s.<size>`` — the same on one core against the batch size.
* ``intercept.batch_bytes_per_trial`` — peak memory the engine allocates (numpy arrays and
  Python objects, ``tracemalloc``) per trial of one default-size batch, results included.
* ``envs.intercept_vector_steps_per_s.<n>_envs`` — steps per second of the Gymnasium vector
  environment (:class:`~robotsoccer.envs.intercept_vector.InterceptVectorEnv`) with n
  sub-environments on one core; a step is one whole episode per sub-environment.

The drill is the paper's §5 set-up with the straight defender and ball noise 0.05.
"""

from __future__ import annotations

import time
import tracemalloc
from concurrent.futures import ProcessPoolExecutor

import numpy as np

from field_models.registry import PAPER_FIELD
from robotsoccer.drills.intercept_batch import DEFAULT_BATCH, run_intercept_batch
from robotsoccer.runs.pool import worker_context
from robotsoccer.runs.runner import TrialSpec

BATCH_SIZES = (256, 1024, 4096, 16384)
"""The batch sizes of the trials/s-against-size figures."""


def batch_spec(seed: int = 1) -> TrialSpec:
    """The benchmarked drill: straight defender, ball noise 0.05, on the paper's server."""
    model, preset = PAPER_FIELD
    spec = TrialSpec(drill="intercept", field_model=model, preset=preset, seed=seed)
    return spec.with_options(behaviour="straight").with_field(ball_noise=0.05)


def count_batch(spec: TrialSpec, start: int, trials: int, batch_size: int) -> int:
    """Run trials ``start .. start + trials - 1`` batched; how many results came back."""
    return len(run_intercept_batch(spec, range(start, start + trials), batch_size))


def batch_trials_per_s_one_core(trials: int, batch_size: int = DEFAULT_BATCH) -> float:
    """Trials per wall second of the batched engine in this process."""
    spec = batch_spec()
    start = time.perf_counter()
    count_batch(spec, 0, trials, batch_size)
    return trials / (time.perf_counter() - start)


def batch_trials_per_s(trials: int, workers: int, batch_size: int = DEFAULT_BATCH) -> float:
    """Trials per wall second of the batched engine in `workers` processes (start-up excluded)."""
    spec = batch_spec()
    share = trials // workers
    with ProcessPoolExecutor(workers, mp_context=worker_context()) as pool:
        list(pool.map(count_batch, [spec] * workers, [0] * workers, [64] * workers, [64] * workers))
        start = time.perf_counter()
        jobs = [
            pool.submit(count_batch, spec, w * share, share, batch_size) for w in range(workers)
        ]
        done = sum(job.result() for job in jobs)
        seconds = time.perf_counter() - start
    return done / seconds


def batch_bytes_per_trial(batch_size: int = DEFAULT_BATCH) -> float:
    """Peak bytes allocated per trial while one batch of `batch_size` trials runs."""
    spec = batch_spec()
    count_batch(spec, 0, 64, 64)  # imports, presets and caches are not the batch's memory
    tracemalloc.start()
    try:
        count_batch(spec, 0, batch_size, batch_size)
        _, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    return peak / batch_size


def vector_env_steps_per_s(num_envs: int, steps: int) -> float:
    """Sub-environment steps (episodes) per wall second of the batched vector environment."""
    from robotsoccer.envs.intercept_vector import InterceptVectorEnv

    env = InterceptVectorEnv(num_envs, ball_noise=0.05)
    env.reset(seed=0)
    actions = np.zeros((num_envs, 1), dtype=np.float32)
    start = time.perf_counter()
    for _ in range(steps):
        env.step(actions)
    return num_envs * steps / (time.perf_counter() - start)
