"""Layer 1's report text (§5): the introduction, training set-up, scaling notes and counts.

The introduction, the training set-up, the drill's scaling notes on each field, and each
experiment's counts put into its place in a model's report section
(:mod:`robotsoccer.experiments.report` writes the markdown).
"""

from __future__ import annotations

import dataclasses
from collections.abc import Sequence
from typing import Any

from field_models.registry import field_facts
from robotsoccer.drills.intercept_plan import launch_plan
from robotsoccer.experiments.layer1_evaluate import SWEPT_EXPERIMENT
from robotsoccer.experiments.layer1_plan import Layer1Plan, Seeds
from robotsoccer.experiments.report_records import Counts, ModelSection


def fill_section(
    section: ModelSection, experiment: str, counts: dict[Any, Counts], include_all: bool
) -> None:
    """Put one experiment's counts into its place in the report section."""
    if experiment == "Figure 7":
        largest = max(counts)
        section.figure7 = [
            (size, f"all ({size})" if include_all and size == largest else str(size), c)
            for size, c in sorted(counts.items())
        ]
    elif experiment == "Figure 8":
        section.figure8 = counts
    elif experiment == "Table 1":
        section.table1 = counts
    elif experiment.endswith("wide"):
        section.wide = counts
    elif experiment == "camera latency":
        section.latency = counts
    elif experiment == SWEPT_EXPERIMENT:
        section.swept = counts
    else:
        section.checks.update(counts)


def scaling_notes(field_model: str, preset: str) -> list[str]:
    """Markdown lines on the drill's geometry, launch and noise period on this field.

    From the drill's ``launch_plan``; adds how many times the ball-motion noise acts during a
    shot of the mean distance (the drill scales the robots' noise period so that it matches the
    Soccer Server's cycles in flight).
    """
    plan = launch_plan(field_facts(field_model, preset))
    lines = [
        "Drill geometry and launch (`robotsoccer.drills.intercept_plan.launch_plan`; distances in "
        "metres, one unit = pitch length / 105; the scaling rule is in that module's "
        "docstring):",
        "",
        "| quantity | value |",
        "|---|---|",
    ]
    lines += [f"| {key} | {_fmt(value)} |" for key, value in dataclasses.asdict(plan).items()]
    lines += [
        f"| noise applications during a shot (arrival_time_s / noise_period_s) "
        f"| {plan.arrival_time_s / plan.noise_period_s:.1f} |",
        f"| trigger distance [units] | {plan.trigger_distance_m / plan.unit_m:.2f} |",
        f"| decisions after the trigger (trigger_to_arrival_s / decision period) "
        f"| {plan.trigger_to_arrival_s / (plan.decision_period_s or plan.sensor_period_s):.1f} |",
    ]
    return lines


def _fmt(value: object) -> str:
    if isinstance(value, float):
        return f"{value:.4g}"
    return str(value)


def intro_lines(
    plan: Layer1Plan,
    seeds: Seeds,
    models: Sequence[tuple[str, str]],
    wall_s: float,
    workers: int | None,
    sections: Sequence[ModelSection] = (),
) -> list[str]:
    """The report's introduction: what ran, seeds, presets, noise meaning, training set-up."""
    from robotsoccer.runs.pool import default_workers

    presets = ", ".join(f"{m} `{p}`" for m, p in models)
    client = (
        "the per-cycle client of issue 28 (`client=cycle`: a command every cycle from a "
        "world model kept between sees)"
        if plan.client == "cycle"
        else "the paper's see-triggered client (`client=see`: turn, then dash, at each see)"
    )
    return [
        f"Defender client, in every table below (collection and evaluation): {client}.",
        "",
        f"Plan **{plan.name}**: {plan.eval_trials} trials per evaluation condition; the "
        f"training drill runs until {plan.collect_saves} saves. Field models and presets: "
        f"{presets}. Wall time {wall_s / 60:.1f} min with {workers or default_workers()} "
        "worker(s).",
        "",
        f"Seeds: evaluation seed {seeds.evaluation}, shared by every condition (trial i has the "
        "same placement whatever the behaviour: paired comparisons); training collection seed "
        f"{seeds.collection} (derived; never an evaluation seed).",
        "",
        f"Ball noise: {plan.noise:g} unless varied. On every field model it is a uniform "
        "perturbation of the ball's velocity in ±noise·|v| per axis (the Soccer Server's "
        "`ball_rand`), applied once per `noise_period_s` of the drill's launch plan (each "
        "model's table below): one server cycle on the paper's field, one *scaled* cycle "
        "elsewhere, so the noise acts as many times per shot on every field.",
        "",
        "Calibrated settings (chosen to match the paper, not reproduced): the defender stops "
        "the ball with its body instead of kicking it clear, chosen so that the training "
        "drill's baselines match §5 (rows whose setting reads *calibrated*: the still and "
        "straight defenders at the main noise on the paper's field); the placement sector of "
        "±45° around the defender (the paper draws it without a number). Every other row was "
        "not tuned.",
        "",
        "Percentages are of all trials (misses count in n); each carries its 95% Wilson "
        "interval in brackets; Saves/(Goals+Saves) is a share of the shots on goal, with its "
        "own n. The paper's number sits in the column beside ours. **setting** says how the "
        "row was run: the paper's setting, *calibrated* to a paper number (and to which), or "
        "another field's own setting. **vs paper** says `agrees` where the paper's figure "
        "lies inside our 95% interval, otherwise whether ours is `above` or `below` it and by "
        "how many points (ours minus the paper's); a row with several paper figures gives "
        "each in column order (saves / goals / saves of the shots on goal), unless all agree.",
        "",
        *training_lines(plan, sections),
    ]


def training_lines(plan: Layer1Plan, sections: Sequence[ModelSection] = ()) -> list[str]:
    """The net's training set-up and why it differs from the paper's (learning.interception)."""
    from learning.interception import DEFAULT_LEARNING_RATES, InterceptionModel

    params = InterceptionModel(epochs=plan.epochs).get_params()
    rate = params["learning_rate"] or DEFAULT_LEARNING_RATES[params["optimizer"]]
    return [
        f"Training: the paper's net (3 inputs → {params['hidden']} sigmoid → 1 linear), "
        f"{params['optimizer']} at learning rate {rate:g}, full batch, {params['epochs']} "
        f"epochs, input-to-hidden weight decay {100 * params['weight_decay']:g}% per update "
        "falling linearly to 0, none on the output; float64, one thread, seed "
        f"{params['random_state']}. Nets train on the first n saves of the collection (nested "
        "subsets). The paper used plain back-propagation at a learning rate of 1e-6 on raw "
        "inputs (distances in units, angles in degrees), 3000 epochs, the same decay. We "
        "standardise the inputs (the scaler is stored in the model file) so that one rate "
        "suits fields of any size, and train with the optimizer above (`learning/"
        "interception.py` says why).",
        *_training_times(sections),
    ]


def _training_times(sections: Sequence[ModelSection]) -> list[str]:
    """This run's training time of each field model's largest net, as a line (or none)."""
    parts = []
    for s in sections:
        if s.train_seconds:
            n = max(s.train_seconds)
            parts.append(f"{s.field_model}: {n} saves in {s.train_seconds[n]:.1f} s")
    if not parts:
        return []
    return ["", "Training time of the largest net in this run: " + "; ".join(parts) + "."]
