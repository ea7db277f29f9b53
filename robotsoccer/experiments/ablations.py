"""Ablations of the robots' interception drill: what makes a learned turn angle pay (issue 10).

Each row changes one thing against the robots' drill under the ``task`` scaling
(:mod:`robotsoccer.drills.task_scaling`; not the drill's default), and learns under that
change: random TA until the plan's saves, a net on the first
:attr:`AblationPlan.net_examples` of them, then the still,
straight and net defenders on the same placements at the plan's noise. The Soccer Server's
literal drill is the first row, the reference the robots' rows are scaled to.

Rows: the scaling rule (``task`` against the former ``sensor_updates``); the turn primitive
(spin in place against an arc, preset ``small_size_1997_arc``); the turn tolerance; the trigger
distance; camera latency; the launch speed; faster robots (preset ``small_size_fast``); TA
chosen at every decision instead of once; a table 2.55 times as large (preset ``large_table``),
on which a robot's touch distance is the server player's in drill units; and that table with
robots 2.55 times as fast (preset ``large_table_fast``), whose reach in units is also kept.

Per row the report gives saves with 95% Wilson intervals, the net's gain over straight trial by
trial (paired, 95% interval), and the median distance the straight and net defenders move from
their trigger to the verdict, in drill units.
"""

from __future__ import annotations

import statistics
from collections.abc import Sequence
from dataclasses import dataclass

from robotsoccer.experiments.context import Field, RunContext
from robotsoccer.experiments.layer1_collect import collect
from robotsoccer.experiments.layer1_evaluate import evaluate
from robotsoccer.experiments.layer1_plan import Layer1Plan, base_spec, condition
from robotsoccer.experiments.layer1_train import train_series
from robotsoccer.experiments.report_cells import paired_cell, percent_cell
from robotsoccer.runs.runner import DrillOption, TrialResult, TrialSpec


@dataclass(frozen=True)
class Ablation:
    """One row: a field model and preset, drill options and a camera latency.

    Attributes:
        key: Folder name of the row's files.
        label: What the row changes, for the report.
        field_model: The field model.
        preset: Its preset.
        options: Drill options beside the behaviour.
        latency_s: Sensor latency override [s]; None keeps the preset's.
    """

    key: str
    label: str
    field_model: str
    preset: str
    options: tuple[tuple[str, DrillOption], ...] = ()
    latency_s: float | None = None


def ablations(reference: Field, robots: Field) -> list[Ablation]:
    """The rows of the study, the reference field's first (the caller names both fields).

    Every robot row but ``sensor_updates`` runs the ``task`` scaling (its own option first, so
    a row's options may override it). The arc, fast and large-table rows use presets of the
    robots' field model.
    """
    r = robots
    rows = [
        Ablation("server", "reference field, literal drill", *reference),
        Ablation("task", "robots, task scaling", *r),
        Ablation("sensor_updates", "robots, sensor_updates scaling", *r,
                 (("scaling", "sensor_updates"),)),
        Ablation("arc", "turn on an arc (preset small_size_1997_arc)", r[0],
                 "small_size_1997_arc"),
        Ablation("tolerance0", "turn tolerance 0° (plan: 3 heading sigmas)", *r,
                 (("turn_tolerance_deg", 0.0),)),
        Ablation("tolerance10", "turn tolerance 10°", *r, (("turn_tolerance_deg", 10.0),)),
        Ablation("trigger06", "trigger distance x0.6", *r, (("trigger_scale", 0.6),)),
        Ablation("trigger15", "trigger distance x1.5", *r, (("trigger_scale", 1.5),)),
        Ablation("latency0", "camera latency 0 ms", *r, latency_s=0.0),
        Ablation("latency100", "camera latency 100 ms", *r, latency_s=0.1),
        Ablation("launch05", "launch speed x0.5", *r, (("launch_speed_scale", 0.5),)),
        Ablation("launch15", "launch speed x1.5", *r, (("launch_speed_scale", 1.5),)),
        Ablation("fast", "robots 2x speed and acceleration (preset small_size_fast)", r[0],
                 "small_size_fast"),
        Ablation("every_see", "TA chosen at every decision", *r, (("ta_mode", "every_see"),)),
        Ablation("large_table", "table 2.55x as large: touch distance 0.88 units as on the "
                 "server (preset large_table)", r[0], "large_table"),
        Ablation("large_table_fast", "table 2.55x as large and robots 2.55x as fast: touch "
                 "and reach in units as on the server (preset large_table_fast)", r[0],
                 "large_table_fast"),
    ]  # fmt: skip
    return [rows[0], *(_task_first(row) for row in rows[1:])]


def _task_first(row: Ablation) -> Ablation:
    options = dict((("scaling", "task"), *row.options))
    return Ablation(
        row.key, row.label, row.field_model, row.preset, tuple(options.items()), row.latency_s
    )


@dataclass(frozen=True)
class AblationPlan:
    """Sizes of the study.

    Attributes:
        collect_saves: Random-TA saves collected per row.
        net_examples: Saves the row's net trains on.
        eval_trials: Trials per defender per row.
        noise: Ball noise of collection and evaluation.
        epochs: Training epochs.
    """

    collect_saves: int = 1500
    net_examples: int = 750
    eval_trials: int = 1000
    noise: float = 0.05
    epochs: int = 3000


def ablation_plan(quick: bool) -> AblationPlan:
    """The full plan, or a quick one (a few minutes less, wider intervals)."""
    if quick:
        return AblationPlan(collect_saves=400, net_examples=300, eval_trials=300)
    return AblationPlan()


@dataclass(frozen=True)
class AblationRow:
    """One row's trials, by defender (``still``, ``straight``, ``net``)."""

    ablation: Ablation
    trials: dict[str, list[TrialResult]]


def run_ablation(ablation: Ablation, plan: AblationPlan, ctx: RunContext) -> AblationRow:
    """Collect, train and evaluate one row into ``out/ablations/<key>/`` (resumable)."""
    folder = ctx.out / "ablations" / ablation.key
    layer1 = Layer1Plan(
        name="ablation",
        eval_trials=plan.eval_trials,
        collect_saves=plan.collect_saves,
        collect_batch=2000,
        noise=plan.noise,
        epochs=plan.epochs,
    )

    def spec_for(seed: int) -> TrialSpec:
        base = base_spec(ablation.field_model, ablation.preset, seed, "hold")
        return base.with_options(**dict(ablation.options))

    collect_base = spec_for(ctx.seeds.collection)
    dataset, _, _ = collect(
        collect_base,
        layer1,
        folder / "results",
        folder / "train.npz",
        ctx.workers,
        "robotsoccer transfer (ablations)",
        ctx.progress,
    )
    size = min(plan.net_examples, len(dataset))
    net = train_series(dataset, [size], plan.epochs, folder, ctx.log)[size]
    base = spec_for(ctx.seeds.evaluation)
    trials: dict[str, list[TrialResult]] = {}
    for behaviour in ("still", "straight", "net"):
        cond = condition(
            base,
            plan.eval_trials,
            behaviour,
            noise=plan.noise,
            model=net if behaviour == "net" else None,
            camera_latency_s=ablation.latency_s,
        )
        results, _, _ = evaluate(cond, folder / "results", ctx.workers, ctx.progress)
        trials[behaviour] = results
    row = AblationRow(ablation, trials)
    ctx.log(f"  [ablation] {ablation.label}: {row_summary(row)}")
    return row


def run_ablations(
    rows: Sequence[Ablation], plan: AblationPlan, ctx: RunContext
) -> list[AblationRow]:
    """Every row (:func:`ablations`), in order."""
    return [run_ablation(a, plan, ctx) for a in rows]


def _share(results: Sequence[TrialResult]) -> str:
    return percent_cell(sum(r.label == "SAVE" for r in results), len(results))


def _gain(row: AblationRow) -> str:
    return paired_cell(row.trials["net"], row.trials["straight"])


def median_travel(results: Sequence[TrialResult]) -> float | None:
    """The median distance the defender moved from its trigger to the verdict [units]."""
    travel = [r.measure("defender_travel_units") for r in results if r.measures]
    return statistics.median(travel) if travel else None


def _travel(results: Sequence[TrialResult]) -> str:
    value = median_travel(results)
    return "—" if value is None else f"{value:.2f}"


def row_summary(row: AblationRow) -> str:
    """One line: still, straight, net and the paired gain."""
    t = row.trials
    return (
        f"still {_share(t['still'])}, straight {_share(t['straight'])}, "
        f"net {_share(t['net'])}, net - straight {_gain(row)}"
    )


def ablation_markdown(rows: Sequence[AblationRow], plan: AblationPlan) -> str:
    """The report section: one table row per ablation."""
    lines = [
        "## Ablations: what makes the turn angle matter on the robots",
        "",
        f"Each row learns under its own change: random TA until {plan.collect_saves} saves, a "
        f"net on {plan.net_examples} of them, then {plan.eval_trials} trials per defender on "
        f"the same placements at ball noise {plan.noise:g}. Saves in % with 95% Wilson "
        "intervals; net - straight is paired, trial by trial, with its 95% interval; travel is "
        "the median distance the defender moves from its trigger to the verdict, in drill "
        "units.",
        "",
        "| change | still | straight | net | net - straight | travel: straight / net |",
        "|---|---|---|---|---|---|",
    ]
    for row in rows:
        t = row.trials
        lines.append(
            f"| {row.ablation.label} | {_share(t['still'])} | {_share(t['straight'])} | "
            f"{_share(t['net'])} | {_gain(row)} | {_travel(t['straight'])} / "
            f"{_travel(t['net'])} |"
        )
    return "\n".join(lines) + "\n"
