"""Layer 1 end to end: collect saves, train nets, evaluate every condition, write one folder (§5).

The pipeline for one field model, as steps, each in a module of its own:

1. set-up (:mod:`~robotsoccer.experiments.layer1_plan`): the plan, the seeds and the evaluation
   conditions;
2. collect (:mod:`~robotsoccer.experiments.layer1_collect`): the training drill (paper Figure 6)
   until the saves reach the plan's target, its saves a dataset;
3. train (:mod:`~robotsoccer.experiments.layer1_train`): the Figure 7 series of nets on nested
   prefixes of the saves, and the §5 lookup table;
4. evaluate (:mod:`~robotsoccer.experiments.layer1_evaluate`): every condition through
   :func:`robotsoccer.runs.pool.run_trials` (parallel, streamed, resumable), and a few rerun
   recordings of the net's saves and goals;
5. report (:mod:`~robotsoccer.experiments.layer1_report`): the report's text and sections.

This module chains them: :func:`run_model` for one field model, :func:`run_layer1` for a run
(``report.md``, the Figure 7/8 plots and ``config.json``), :func:`train_main_net` for the main
net alone (a layer-2 run), and :func:`claim_folder`, the run folder's guard.

Seeds (common random numbers): every evaluation condition of a field model uses the same
experiment seed, so trial i places shooter, ball and defender identically whatever the behaviour
(paired comparisons). Collection uses a different seed derived from it
(:func:`~robotsoccer.experiments.layer1_plan.seeds_for`), so the nets are never tested on the
placements they were trained on.

Noise: on every field the ball's velocity gets a uniform change in ±noise·|v| per axis once per
noise period (:attr:`field_models.arena.FieldFacts.ball_noise`; the Soccer Server's
``ball_rand``). Layer 1 passes the same noise value to every field model, and the drill sets the
period where it scales the drill (:mod:`robotsoccer.drills.intercept_plan`), so a noise level means
the same wander per shot on every field.

What the plans hold: :class:`~robotsoccer.experiments.layer1_plan.Layer1Plan`.
"""

from __future__ import annotations

import dataclasses
import json
import time
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from field_models.registry import default_preset, field_facts
from robotsoccer.drills.intercept_plan import launch_plan
from robotsoccer.experiments.context import Field, RunContext
from robotsoccer.experiments.layer1_collect import collect_into
from robotsoccer.experiments.layer1_evaluate import (
    counts_of,
    evaluate,
    experiments,
    record_examples,
    unique_conditions,
)
from robotsoccer.experiments.layer1_plan import (
    Condition,
    Layer1Plan,
    PipelineError,
    base_spec,
)
from robotsoccer.experiments.layer1_report import fill_section, intro_lines, scaling_notes
from robotsoccer.experiments.layer1_train import (
    net_for_figures,
    train,
    train_series,
    training_sizes,
)
from robotsoccer.experiments.report_records import ModelSection, StageTiming
from robotsoccer.runs.folders import lock_run_folder
from robotsoccer.runs.provenance import code_version
from robotsoccer.runs.runner import TrialResult


def run_model(
    field: Field, plan: Layer1Plan, ctx: RunContext
) -> tuple[ModelSection, dict[str, Condition]]:
    """Collect, train and evaluate layer 1 on one field model; record a few trials.

    Returns:
        The report section and the conditions that ran (for ``config.json``).
    """
    field_model, preset = field
    out, log = ctx.out, ctx.log
    results_dir = ctx.results_dir(field_model)
    facts = field_facts(field_model, preset)
    section = ModelSection(
        field_model,
        preset,
        noise=plan.noise,
        noise_period_s=launch_plan(facts).noise_period_s,
        facts=facts,
    )
    section.notes = scaling_notes(field_model, preset)

    dataset, collected, timing = collect_into(field, plan, ctx)
    section.checks["random"] = collected
    section.stages.append(timing)

    log(f"[{field_model}] train")
    start = time.perf_counter()
    trained = train(plan, dataset, ctx.models_dir(field_model), log)
    section.stages.append(StageTiming("train nets + lookup", 0, time.perf_counter() - start))
    section.net_examples = trained.main_examples
    section.train_seconds = trained.seconds

    base = base_spec(field_model, preset, ctx.seeds.evaluation, plan.ta_mode, plan.client)
    plan_of = experiments(plan, base, trained, facts.sensor_latency_s)
    done: dict[str, list[TrialResult]] = {}
    for experiment, keyed in plan_of.items():
        log(f"[{field_model}] {experiment}")
        ran, wall = 0, 0.0
        for _, cond in keyed:
            if cond.name in done:
                continue
            done[cond.name], n_run, seconds = evaluate(cond, results_dir, ctx.workers, ctx.progress)
            ran, wall = ran + n_run, wall + seconds
            c = counts_of(done[cond.name])
            log(f"  {cond.name}: {c.saves} SAVE, {c.goals} GOAL, {c.misses} MISS ({seconds:.1f} s)")
        counts = {key: counts_of(done[c.name]) for key, c in keyed}
        fill_section(section, experiment, counts, plan.include_all)
        section.stages.append(StageTiming(experiment, ran, wall))

    for experiment in ("Table 1", "checks (still, straight)"):
        for key, cond in plan_of.get(experiment, []):
            section.trials[key] = done[cond.name]
    main = plan_of["Table 1"][0][1]
    start = time.perf_counter()
    recorded = record_examples(main, done[main.name], out / "recordings" / field_model, plan, log)
    section.stages.append(StageTiming("record", recorded, time.perf_counter() - start))
    return section, unique_conditions(plan_of)


def run_layer1(
    models: Sequence[tuple[str, str | None]],
    plan: Layer1Plan,
    ctx: RunContext,
    title: str = "Layer 1 reproduction",
) -> tuple[Path, list[ModelSection]]:
    """Run layer 1 on each (field model, preset) and write one folder.

    The folder: ``config.json`` (plan, seeds, presets, every condition), ``datasets/``,
    ``models/``, ``results/``, ``recordings/``, ``plots/figure7.png``, ``plots/figure8.png`` and
    ``report.md``. Rerunning with the same plan and seed resumes (finished trials are kept).

    Returns:
        The report's path and the sections.

    Raises:
        PipelineError: `out` holds a run of another plan or seed.
    """
    from robotsoccer.experiments.plots import plot_figure7, plot_figure8
    from robotsoccer.experiments.report import report_markdown

    named = [(m, p or default_preset(m)) for m, p in models]
    out, seeds = ctx.out, ctx.seeds
    header = {
        "plan": plan.to_dict(),
        "seed": seeds.evaluation,
        "seeds": dataclasses.asdict(seeds),
        "models": [list(m) for m in named],
        "code_version": code_version(),
    }
    claim_folder(out, header)
    start = time.perf_counter()
    sections, conditions = [], {}
    for field_model, preset in named:
        section, conds = run_model((field_model, preset), plan, ctx)
        sections.append(section)
        conditions[field_model] = {
            name: {"n_trials": c.n_trials, "spec": dataclasses.asdict(c.spec)}
            for name, c in conds.items()
        }
    plots = []
    for caption, draw, name in (
        ("Figure 7: saves vs training examples", plot_figure7, "figure7.png"),
        ("Figure 8: saves vs ball noise", plot_figure8, "figure8.png"),
    ):
        if draw(sections, out / "plots" / name) is not None:
            plots.append((caption, f"plots/{name}"))
    wall = time.perf_counter() - start
    intro = intro_lines(plan, seeds, named, wall, ctx.workers, sections)
    report = out / "report.md"
    report.write_text(report_markdown(title, intro, sections, plots))
    config = {**header, "wall_s": round(wall, 1), "conditions": conditions}
    (out / "config.json").write_text(json.dumps(config, indent=2) + "\n")
    return report, sections


def claim_folder(out: Path, header: dict[str, Any]) -> None:
    """Refuse a folder holding another run's results; mark it as this run's and hold it.

    The folder's lock (:func:`~robotsoccer.runs.folders.lock_run_folder`) stays held until the
    command ends, so no other run writes there meanwhile, and the run's manifests store paths
    relative to it.

    Raises:
        PipelineError: ``config.json`` there differs in what defines the run.
        FolderInUseError: Another process holds the folder.
    """
    out.mkdir(parents=True, exist_ok=True)
    lock_run_folder(out)
    path = out / "config.json"
    if path.exists():
        try:
            old = json.loads(path.read_text())
        except ValueError:
            old = {}
        new = json.loads(json.dumps(header))
        differ = [k for k in new if old.get(k) != new[k]]
        if differ:
            raise PipelineError(
                f"{out} holds a run with another {', '.join(d.replace('_', ' ') for d in differ)};"
                " choose another --out or remove it"
            )
    path.write_text(json.dumps(header, indent=2) + "\n")


def train_main_net(field: Field, plan: Layer1Plan, ctx: RunContext) -> Path:
    """Layer 1's collection and its main net only (no evaluations), for a layer-2 run.

    The same collection and training as :func:`run_model` (same seeds, same files), so a later
    ``reproduce`` into the same folder resumes them. Returns the net's file.
    """
    dataset, _, _ = collect_into(field, plan, ctx)
    main = net_for_figures(plan, training_sizes(plan, len(dataset)))
    return train_series(dataset, [main], plan.epochs, ctx.models_dir(field[0]), ctx.log)[main]
