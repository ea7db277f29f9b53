"""Speed measurements behind ``robotsoccer bench``: simulated seconds per wall second, trials/s.

These are benchmarks, not tests: the machines are shared and noisy, so every figure is the
median of several repeats, and no test asserts a speed. ``robotsoccer bench`` prints each
figure's target beside it (:func:`target_cell`).

* ``<field model>.*`` — each registered field model's own engine figures
  (``field_models.<model>.bench``): the robots' real-time factor, the Soccer Server's cycles per
  second through the arena and object-cycles per second in batch mode. Beside the robots'
  real-time factor, the same pymunk world stepped with ``space.step`` alone in the same run
  (``robot_physics.chipmunk_realtime_factor.N_robots``) and the engine's share of that speed
  (``robot_physics.share_of_chipmunk.N_robots``), a figure that means the same on any machine.
* ``demo.trials_per_s.K_worker(s)`` — the shootout demo drill through the process pool.
* ``intercept.trials_per_s.<field model>`` — the layer-1 interception drill (straight defender,
  ball noise 0.05) through the pool with 2 workers, pool start included; enough trials that
  start-up is a small share. On the Soccer Server the pool runs them through the batched engine,
  so this is what a user's run gets (results sent back to the parent, counted and sorted).
* ``intercept.*batch*``, ``envs.*`` — the batched interception engine on all cores, against
  batch size, its memory per trial, and the Gymnasium vector environment
  (:mod:`robotsoccer.bench_batch`).
* ``pass.trials_per_s.<field model>`` — the layer-2 pass drill (random receiver, straight
  interceptors, 12 players) through the pool with 2 workers, sized the same way.
* ``match.wall_s.<field model>``, ``match.realtime_factor.<field model>`` — one whole match
  (two halves of 300 s: 6000 cycles on the Soccer Server) between two baseline teams, the
  field's own size (11 v 11 on an open field, 5 v 5 on the robots' table, with camera, host,
  link and firmware running) in this process, on one core: wall seconds and simulated seconds
  per wall second. The baseline needs no model files; the layered team's net and tree are a
  small share of a decision's cost.
* ``envs.score_*.<field model>`` — the per-step ``robotsoccer/Score-v0`` (3 v 3) in this
  process: steps per second and real-time factor, the bare arena's real-time factor with the
  same players and baseline minds, and their ratio, the environment layer's share
  (:mod:`robotsoccer.bench_envs`; target: at least 0.8).
* ``envs.match_*.<field model>`` — a whole match (two halves of 300 s, the field's own team
  size) through the PettingZoo match environment, every player an agent: steps per second,
  agent decisions per second and real-time factor with random ``commands`` and with ``AUTO``
  macros, the bare match's real-time factor and the ``AUTO`` run's ratio to it (the same match:
  the environment layer's share); ``envs.hfo_*.<field model>`` — half-field offense, 2 v 1 and
  a goalie, the attackers ``AUTO``: steps and episodes per second, real-time factor
  (:mod:`robotsoccer.bench_envs`).
* ``training.net_1000_saves_s`` — wall seconds to train the paper's 3-4-1 net for 3000 epochs
  on 1000 synthetic saves (torch on the CPU, one thread).
"""

from __future__ import annotations

import functools
import math
import platform
import time
from collections.abc import Callable, Iterable, Iterator
from typing import Any

import numpy as np

from field_models.benchmarks import median_of
from field_models.registry import FIELD_MODELS, entry
from robotsoccer.runs.pool import default_workers, run_trials
from robotsoccer.runs.runner import TrialSpec

Progress = Callable[[str], None]
"""Where the benchmark says what it is measuring now (the CLI prints it on stderr)."""

Targets = dict[str, tuple[str, float]]
"""Dotted key → (">=" or "<=", bound): what a figure should reach; the CLI holds the numbers."""


def demo_trials_per_s(field_model: str, workers: int, trials: int, seed: int = 0) -> float:
    """Shootout demo trials per wall second through the pool (pool start-up included)."""
    spec = TrialSpec(drill="shootout", field_model=field_model, seed=seed)
    start = time.perf_counter()
    run_trials(spec, trials, workers=workers, progress=False)
    return trials / (time.perf_counter() - start)


def intercept_trials_per_s(field_model: str, trials: int, workers: int = 2) -> float:
    """Interception-drill trials per wall second through the pool (straight defender)."""
    spec = TrialSpec(drill="intercept", field_model=field_model, seed=1)
    spec = spec.with_options(behaviour="straight").with_field(ball_noise=0.05)
    start = time.perf_counter()
    run_trials(spec, trials, workers=workers, progress=False)
    return trials / (time.perf_counter() - start)


def pass_trials_per_s(field_model: str, trials: int, workers: int = 2) -> float:
    """Pass-drill trials per wall second through the pool (random receiver, straight interceptors).

    Straight interceptors measure the drill's own cost, without a net file to read.
    """
    spec = TrialSpec(drill="pass", field_model=field_model, seed=1)
    start = time.perf_counter()
    run_trials(spec, trials, workers=workers, progress=False)
    return trials / (time.perf_counter() - start)


def match_wall_s(field_model: str, half_time_s: float, seed: int = 0) -> float:
    """Wall seconds of one match of two baseline teams (two halves), in this process."""
    from robotsoccer.runs.runner import run_trial

    spec = TrialSpec(drill="match", field_model=field_model, seed=seed).with_options(
        left="baseline", right="baseline", half_time_s=half_time_s
    )
    start = time.perf_counter()
    run_trial(spec, 0)
    return time.perf_counter() - start


def training_seconds(saves: int = 1000) -> float:
    """Wall seconds to fit the interception net (default settings) on synthetic saves."""
    from learning.interception import InterceptionModel

    rng = np.random.default_rng(1)
    x = np.column_stack(
        [rng.uniform(5, 14, saves), rng.uniform(-0.2, 0.2, saves), rng.uniform(5, 16, saves)]
    )
    y = 0.5 * x[:, 1] + rng.normal(0.0, 0.05, saves)
    start = time.perf_counter()
    InterceptionModel().fit(x, y)
    return time.perf_counter() - start


def run_benchmarks(
    quick: bool = False, demo_field: str = FIELD_MODELS[0], say: Progress | None = None
) -> dict[str, Any]:
    """All benchmark figures as a nested dict (medians of 3 repeats; 1 when `quick`)."""
    return nest(iter_benchmarks(quick, demo_field, say))


def iter_benchmarks(
    quick: bool = False, demo_field: str = FIELD_MODELS[0], say: Progress | None = None
) -> Iterator[tuple[str, Any]]:
    """Every figure as (dotted key, value), each as soon as it is measured."""
    say = say or (lambda _: None)
    repeats = 1 if quick else 3
    for model in FIELD_MODELS:
        say(f"{model}: engine speed")
        yield from flatten(entry(model).benchmarks(quick), f"{model}.")
    trials = 100 if quick else 600
    say(f"demo ({demo_field}): 1 and 2 workers")
    demo1 = median_of(repeats, lambda: demo_trials_per_s(demo_field, 1, trials // 2))
    yield "demo.trials_per_s.1_worker", round(demo1, 1)
    demo2 = median_of(repeats, lambda: demo_trials_per_s(demo_field, 2, trials))
    yield "demo.trials_per_s.2_workers", round(demo2, 1)
    drilled = drill_models()
    for model in drilled:
        say(f"intercept drill: {model}")
        measure = functools.partial(intercept_trials_per_s, model, _intercept_trials(model, quick))
        yield f"intercept.trials_per_s.{model}", round(median_of(repeats, measure))
    yield from _batch_figures(quick, repeats, say)
    for model in drilled:
        say(f"pass drill: {model}")
        n = _sized(functools.partial(pass_trials_per_s, model), quick)
        measure = functools.partial(pass_trials_per_s, model, n)
        yield f"pass.trials_per_s.{model}", round(median_of(repeats, measure))
    for model in drilled:
        say(f"match: {model}")
        half = 60.0 if quick else 300.0
        wall = median_of(repeats, functools.partial(match_wall_s, model, half))
        yield f"match.wall_s.{model}", round(wall, 2)
        yield f"match.realtime_factor.{model}", round(2.0 * half / wall, 1)
    for model in FIELD_MODELS:
        say(f"score environment against the bare arena: {model}")
        yield from _score_env_figures(model, quick, repeats)
    for model in drilled:
        say(f"match and half-field offense environments: {model}")
        yield from _play_env_figures(model, quick, repeats)
    say("training: the interception net on 1000 saves")
    yield "training.net_1000_saves_s", round(median_of(repeats, training_seconds), 2)
    yield "machine.python", platform.python_version()
    yield "machine.cpu_count", default_workers()
    yield "machine.repeats", repeats
    yield "machine.statistic", "median"


def drill_models() -> tuple[str, ...]:
    """The field models whose drills and matches are timed: those that do not say otherwise.

    A model over the wire (``BENCH_DRILLS = False`` in its entry) times its own cycles against
    the in-process engine instead; its drills would time the sockets, not the drill.
    """
    return tuple(m for m in FIELD_MODELS if getattr(entry(m), "BENCH_DRILLS", True))


def _batch_figures(quick: bool, repeats: int, say: Progress) -> Iterator[tuple[str, Any]]:
    """The batched engine's figures (:mod:`robotsoccer.bench_batch`)."""
    from robotsoccer import bench_batch as bb

    trials = 16_384 if quick else 131_072
    workers = default_workers()
    say(f"intercept drill: batched engine, {workers} processes")
    measure = functools.partial(bb.batch_trials_per_s, trials, workers)
    key = f"intercept.trials_per_s.{bb.batch_spec().field_model}_batch"
    yield key, round(median_of(repeats, measure))
    for size in bb.BATCH_SIZES:
        say(f"intercept drill: batch of {size}, one core")
        one = functools.partial(bb.batch_trials_per_s_one_core, max(trials // 8, size), size)
        yield f"intercept.batch_trials_per_s.{size}", round(median_of(repeats, one))
    say("intercept drill: memory per batched trial")
    yield "intercept.batch_bytes_per_trial", round(bb.batch_bytes_per_trial())
    for envs in (64, 1024):
        say(f"vector environment: {envs} sub-environments")
        steps = max(2, (2_048 if quick else 16_384) // envs)
        step = functools.partial(bb.vector_env_steps_per_s, envs, steps)
        yield f"envs.intercept_vector_steps_per_s.{envs}_envs", round(median_of(repeats, step))


def _score_env_figures(model: str, quick: bool, repeats: int) -> Iterator[tuple[str, Any]]:
    """``robotsoccer/Score-v0`` against the bare arena (:mod:`robotsoccer.bench_envs`).

    The repeat with the median ratio gives every figure, so they belong together.
    """
    from robotsoccer.bench_envs import score_env_figures
    from robotsoccer.envs.score import ScoreEnv

    seconds = 60.0 if quick else 200.0
    ticks = round(seconds / ScoreEnv(model).facts.dt_s)
    runs = sorted(
        (score_env_figures(model, ticks) for _ in range(repeats)),
        key=lambda f: f["env_to_bare_ratio"],
    )
    for name, value in runs[len(runs) // 2].items():
        yield f"envs.score_{name}.{model}", value


def _play_env_figures(model: str, quick: bool, repeats: int) -> Iterator[tuple[str, Any]]:
    """The match and half-field offense environments (:mod:`robotsoccer.bench_envs`).

    The match's repeat with the median ratio gives its figures; HFO's, the median step rate.
    """
    from robotsoccer.bench_envs import hfo_env_figures, match_env_figures

    half = 60.0 if quick else 300.0
    matches = sorted(
        (match_env_figures(model, half) for _ in range(repeats)),
        key=lambda f: f["macro_to_bare_ratio"],
    )
    for name, value in matches[len(matches) // 2].items():
        yield f"envs.match_{name}.{model}", value
    episodes = 100 if quick else 500
    hfos = sorted(
        (hfo_env_figures(model, episodes) for _ in range(repeats)), key=lambda f: f["steps_per_s"]
    )
    for name, value in hfos[len(hfos) // 2].items():
        yield f"envs.hfo_{name}.{model}", value


def nest(rows: Iterable[tuple[str, Any]]) -> dict[str, Any]:
    """Dotted-key rows as a nested dict (the inverse of :func:`flatten`)."""
    tree: dict[str, Any] = {}
    for key, value in rows:
        *parents, leaf = key.split(".")
        node = tree
        for part in parents:
            node = node.setdefault(part, {})
        node[leaf] = value
    return tree


def _intercept_trials(field_model: str, quick: bool) -> int:
    """Interception trials enough for several seconds of work (:func:`_sized`)."""
    return _sized(functools.partial(intercept_trials_per_s, field_model), quick)


def _sized(run: Callable[[int], float], quick: bool) -> int:
    """Trials enough for several seconds of work, so pool start-up is a small share.

    Probes with doubling trial counts (from 100) until a run takes a quarter of the wanted
    time, then scales to the whole (rounded up to 100 trials).
    """
    wanted_s = 2.0 if quick else 8.0
    n = 100
    while True:
        start = time.perf_counter()
        run(n)
        seconds = time.perf_counter() - start
        if seconds >= 0.25 * wanted_s or n >= 100_000:
            return 100 * math.ceil(n * wanted_s / seconds / 100)
        n *= 2


def flatten(tree: dict[str, Any], prefix: str = "") -> list[tuple[str, Any]]:
    """A nested dict as (dotted key, value) rows, in insertion order."""
    rows: list[tuple[str, Any]] = []
    for key, value in tree.items():
        name = f"{prefix}{key}"
        if isinstance(value, dict):
            rows += flatten(value, name + ".")
        else:
            rows.append((name, value))
    return rows


def target_cell(key: str, value: Any, targets: Targets) -> str:
    """``">= 300: met"``, ``"<= 5: MISSED"``, or "" for a figure without a target."""
    if key not in targets:
        return ""
    sense, bound = targets[key]
    met = value >= bound if sense == ">=" else value <= bound
    return f"{sense} {bound:,.6g}: {'met' if met else 'MISSED'}"
