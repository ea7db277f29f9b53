"""Layer 1's collection step (§5, Figure 6): the training drill until the saves reach the plan.

The defender turns a random TA in [−45°, 45°] once the ball is within 14 units; trials run
in batches until the saves reach the plan's target (the paper's 4773), and the saves' (BD,
BA, previous BD, TA) become an :class:`~learning.datasets.InterceptionDataset` with its
provenance.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Iterable, Sequence
from pathlib import Path

import numpy as np

from field_models.registry import field_facts
from learning.datasets import InterceptionDataset, Provenance
from robotsoccer.drills import make_drill
from robotsoccer.drills.intercept import InterceptDrill
from robotsoccer.experiments.context import Field, RunContext
from robotsoccer.experiments.layer1_evaluate import counts_of, evaluate
from robotsoccer.experiments.layer1_plan import (
    COLLECT_BEHAVIOUR,
    DRILL,
    Layer1Plan,
    PipelineError,
    base_spec,
    condition,
)
from robotsoccer.experiments.report_records import Counts, StageTiming
from robotsoccer.runs.runner import TrialResult, TrialSpec


def dataset_from_results(
    results: Sequence[TrialResult], provenance: Provenance
) -> InterceptionDataset:
    """The saves' recorded (BD, BA, previous BD, TA) as a dataset, in trial order (§5).

    A save the defender made before it ever chose a TA (the ball came back before it was in
    range) taught it nothing and records no example: it is left out (see :func:`decided_saves`).

    Raises:
        PipelineError: A recorded example that is not four numbers.
    """
    rows = [r.data for r in decided_saves(results)]
    if any(len(row) != 4 for row in rows):
        raise PipelineError("a save recorded something other than (BD, BA, previous BD, TA)")
    data = np.array(rows, dtype=np.float64).reshape(len(rows), 4)
    return InterceptionDataset(data[:, :3], data[:, 3], provenance)


def decided_saves(results: Iterable[TrialResult]) -> list[TrialResult]:
    """The saves in which the defender chose a TA (they carry its example)."""
    return [r for r in results if r.label == "SAVE" and r.data]


def collect(
    base: TrialSpec,
    plan: Layer1Plan,
    results_dir: Path,
    dataset_path: Path,
    workers: int | None,
    created_by: str,
    progress: bool = False,
) -> tuple[InterceptionDataset, Counts, StageTiming]:
    """The training drill: random TA until the saves reach the plan's target; save the dataset.

    Trials run in batches on one resumable table: the first of ``plan.collect_batch``, each next
    one sized from the save rate so far (rounded up to 500 trials, 5% spare). The batch sizes
    depend only on the results, so the dataset is a function of the seed.
    """
    drill = make_drill(DRILL, {k: v for k, v in base.drill_options if k in PLAN_OPTIONS})
    assert isinstance(drill, InterceptDrill)
    launch = drill.plan_for(field_facts(base.field_model, base.preset))
    cond = condition(base, plan.collect_batch, COLLECT_BEHAVIOUR, noise=plan.noise)
    cond = dataclasses.replace(cond, name=f"collect_{cond.name}")
    limit = COLLECT_LIMIT_PER_SAVE * plan.collect_saves
    ran_total, wall_total = 0, 0.0
    while True:
        results, ran, wall = evaluate(cond, results_dir, workers, progress)
        ran_total, wall_total = ran_total + ran, wall_total + wall
        saves = len(decided_saves(results))
        if saves >= plan.collect_saves or cond.n_trials >= limit:
            break
        wanted = (plan.collect_saves - saves) * cond.n_trials / max(saves, 1) * 1.05
        more = 500 * math.ceil(wanted / 500)
        cond = dataclasses.replace(cond, n_trials=min(limit, cond.n_trials + more))
    counts = counts_of(results)
    provenance = Provenance(
        field_model=base.field_model,
        preset=base.preset_name,
        seed=base.seed,
        ball_noise=plan.noise,
        behaviour=COLLECT_BEHAVIOUR,
        n_trials=cond.n_trials,
        created_by=created_by,
        extra={
            "drill": DRILL,
            "ta_range_deg": 45.0,
            "trigger_distance_units": launch.trigger_distance_m / launch.unit_m,
            "trigger_distance_m": launch.trigger_distance_m,
            "ball_noise_period_s": launch.noise_period_s,
            "ta_mode": str(dict(base.drill_options).get("ta_mode", "hold")),
            **_client_of(base),
            "rows": "saves only, in trial order",
            "target_saves": plan.collect_saves,
            "saves": counts.saves,
            "saves_without_decision": counts.saves - len(decided_saves(results)),
            "goals": counts.goals,
            "misses": counts.misses,
        },
    )
    dataset = dataset_from_results(results, provenance)
    dataset_path.parent.mkdir(parents=True, exist_ok=True)
    dataset.save(dataset_path)
    return dataset, counts, StageTiming("collect (random TA)", ran_total, wall_total)


def _client_of(base: TrialSpec) -> dict[str, str]:
    """The dataset's ``client`` entry where the saves are not the see client's (else none)."""
    client = dict(base.drill_options).get("client", "see")
    return {} if client == "see" else {"client": str(client)}


PLAN_OPTIONS = frozenset({"scaling", "trigger_scale", "launch_speed_scale", "turn_tolerance_deg"})
"""The drill options that change the launch plan (named in a dataset's provenance)."""

COLLECT_LIMIT_PER_SAVE = 50
"""The training drill gives up growing after this many trials per wanted save (2% saves)."""


def collect_into(
    field: Field, plan: Layer1Plan, ctx: RunContext
) -> tuple[InterceptionDataset, Counts, StageTiming]:
    """:func:`collect` for one field model into the run folder's usual places, logged."""
    field_model, preset = field
    ctx.log(f"[{field_model}] collect: random TA until {plan.collect_saves} saves")
    dataset, collected, timing = collect(
        base_spec(field_model, preset, ctx.seeds.collection, plan.ta_mode, plan.client),
        plan,
        ctx.results_dir(field_model),
        ctx.out / "datasets" / field_model / "train.npz",
        ctx.workers,
        ctx.created_by,
        ctx.progress,
    )
    ctx.log(f"  {collected.saves} saves of {collected.n} trials ({timing.wall_s:.1f} s)")
    return dataset, collected, timing
