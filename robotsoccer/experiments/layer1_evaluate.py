"""Layer 1's evaluation step (§5): run a condition, and every condition of one field model.

:func:`evaluate` runs one condition (behaviour, model file, noise, aim, latency) for the
plan's trials through :func:`robotsoccer.runs.pool.run_trials`: parallel, streamed to
``<out>/results/<model>/<condition>.csv`` and resumable. :func:`experiments` lists every
evaluation of a field model in report order; :func:`record_examples` reruns a few trials
with rerun recording on.
"""

from __future__ import annotations

import dataclasses
import math
import time
from collections.abc import Iterable, Sequence
from pathlib import Path
from typing import Any

from field_models.registry import has_preset
from robotsoccer.experiments.layer1_plan import Condition, Layer1Plan, Log, condition
from robotsoccer.experiments.layer1_train import Trained
from robotsoccer.experiments.report_records import Counts
from robotsoccer.runs.pool import run_trials
from robotsoccer.runs.runner import TrialResult, TrialSpec, run_trial
from robotsoccer.runs.table import iter_results
from robotsoccer.runs.twins import fill_from_twins


def evaluate(
    cond: Condition, results_dir: Path, workers: int | None, progress: bool = False
) -> tuple[list[TrialResult], int, float]:
    """Run one condition through the pool, streamed to ``results_dir/<name>.csv`` and resumed.

    Trials the run folder holds already in a table of the same spec, code and inputs are
    copied from it, not run again (:mod:`robotsoccer.runs.twins`).

    Returns:
        (results sorted by index, trials actually run now, wall seconds).
    """
    path = results_dir / f"{cond.name}.csv"
    before = _rows_in(path)
    start = time.perf_counter()
    before += fill_from_twins(path, cond.spec, cond.n_trials)
    results = run_trials(
        cond.spec,
        cond.n_trials,
        workers=workers,
        results_path=path,
        resume=True,
        progress=progress,
    )
    return results, max(0, cond.n_trials - before), time.perf_counter() - start


def _rows_in(path: Path) -> int:
    # rows, not lines: a quoted reason may hold line ends (run_trials warns of a cut-short row)
    return sum(1 for _ in iter_results(path, warn=lambda _: None))


def counts_of(results: Iterable[TrialResult]) -> Counts:
    """SAVE / GOAL / MISS counts of some results."""
    return Counts.from_labels(r.label for r in results)


Keyed = list[tuple[Any, Condition]]
"""An experiment's conditions, each under its key in the report (e.g. (noise, behaviour))."""


def experiments(
    plan: Layer1Plan, base: TrialSpec, trained: Trained, default_latency_s: float | None
) -> dict[str, Keyed]:
    """Every evaluation of one field model, in report order: experiment → keyed conditions.

    Conditions of the same name in two experiments (e.g. the net on 750 saves at noise .05 in
    Figure 7, Figure 8 and Table 1) are one run. `default_latency_s` is the robot preset's
    camera latency (None on the Soccer Server: no latency experiment); a latency equal to it
    runs as the preset's own, so it shares its condition with the other experiments.
    """
    n, noise, aim = plan.eval_trials, plan.noise, plan.aim_offset_deg
    nets = trained.nets

    def run(behaviour: str, examples: int | None = None, **kw: Any) -> Condition:
        if behaviour == "net":
            examples = examples or trained.main_examples
            return condition(base, n, "net", model=nets[examples], tag=str(examples), **kw)
        if behaviour == "lookup":
            tag = str(trained.main_examples)
            return condition(base, n, "lookup", model=trained.lookup, tag=tag, **kw)
        return condition(base, n, behaviour, **kw)

    plan_of: dict[str, Keyed] = {
        "Figure 7": [(size, run("net", size, noise=noise)) for size in sorted(nets)],
        "Figure 8": [
            ((level, b), run(b, noise=level)) for level in plan.noises for b in ("net", "straight")
        ],
        "Table 1": [(b, run(b, noise=noise)) for b in ("net", "lookup", "analytic", "straight")],
        f"{aim:g}° wide": [(b, run(b, noise=0.0, aim_offset_deg=aim)) for b in ("net", "straight")],
    }
    if default_latency_s is not None and plan.latencies_s:
        plan_of["camera latency"] = [
            (
                (lat, b),
                run(b, noise=noise, camera_latency_s=_latency(lat, default_latency_s)),
            )
            for lat in plan.latencies_s
            for b in ("net", "straight", "analytic")
        ]
    swept = swept_variant(base)
    if swept is not None:
        plan_of[SWEPT_EXPERIMENT] = [
            ((level, b), _on_preset(run(b, noise=level), swept, "_swept"))
            for level in (0.0, noise)
            for b in ("net", "straight")
        ]
    if plan.checks:
        plan_of["checks (still, straight)"] = [
            (b, run(b, noise=noise)) for b in ("still", "straight")
        ]
    return plan_of


SWEPT_EXPERIMENT = "swept collisions"
"""The pass-through diagnostic: Figure 8's noise 0 and the main noise with swept collisions."""


def swept_variant(base: TrialSpec) -> str | None:
    """The ``<preset>_swept`` variant of `base`'s preset, if its field model ships one.

    With swept ball–player collisions a ball cannot pass *through* a dashing defender between
    two cycles, which the real server allows (spec §4); running the same conditions on it
    measures how much of a gap to the paper that artefact explains.
    """
    name = f"{base.preset}_swept"
    return name if has_preset(base.field_model, name) else None


def _on_preset(cond: Condition, preset: str, suffix: str) -> Condition:
    """`cond` on a variant preset; a model trained on the base preset is used there on purpose."""
    spec = dataclasses.replace(cond.spec, preset=preset)
    if "model" in dict(spec.drill_options):
        spec = spec.with_options(transfer=True)
    return Condition(cond.name + suffix, spec, cond.n_trials)


def _latency(latency_s: float, default_s: float) -> float | None:
    return None if math.isclose(latency_s, default_s) else latency_s


def unique_conditions(plan_of: dict[str, Keyed]) -> dict[str, Condition]:
    """The distinct conditions of an experiment plan, by name, in first-use order."""
    unique: dict[str, Condition] = {}
    for keyed in plan_of.values():
        for _, cond in keyed:
            unique.setdefault(cond.name, cond)
    return unique


def record_examples(
    cond: Condition,
    results: Sequence[TrialResult],
    record_dir: Path,
    plan: Layer1Plan,
    log: Log,
) -> int:
    """Rerun the first saves and goals of `cond` with rerun recording on; return how many.

    A trial is a pure function of its seed and index, so the rerun is the same trial. The
    runner names each file with its outcome (``trial_<index>_<LABEL>.rrd``); here it becomes
    ``<condition>_trial<index>_<label>.rrd``.
    """
    # Needed only when recording (the module itself never loads the rerun SDK).
    from robotsoccer.replay.recording import recording_name

    chosen = [r for r in results if r.label == "SAVE"][: plan.record_saves]
    chosen += [r for r in results if r.label == "GOAL"][: plan.record_goals]
    record_dir.mkdir(parents=True, exist_ok=True)
    for first in chosen:
        spec = dataclasses.replace(
            cond.spec, record_dir=str(record_dir), record_trials=first.index + 1
        )
        again = run_trial(spec, first.index)
        raw = record_dir / recording_name(first.index, again.label)
        target = record_dir / f"{cond.name}_trial{first.index:04d}_{again.label}.rrd"
        raw.replace(target)
        if again.label != first.label:  # would mean a trial is not a function of its seed
            log(f"  warning: trial {first.index} gave {again.label} recorded, {first.label} before")
        log(f"  recorded {target}")
    return len(chosen)
