"""Layer 1 with the lead decision, beside the paper's turn angle, on both field models.

The paper's layer 1 (§5) learns one turn angle TA at the trigger. On the mini-robots that does
not pay: a 30 Hz camera makes straight pursuit near-optimal for a held offset (README, "Layer
1 on the robots"). :mod:`robotsoccer.skills.lead` learns instead the **lead**, how far ahead
in time along the ball's perceived track the defender aims, re-applied at every percept and
driven on arcs. This study runs §5's recipe for both decisions on each field's drill and
reports them side by side:

1. **collect**: the random behaviour (TA uniform in ±45°; lead uniform over the ball's flight
   time) until the saves reach the plan's number, at the plan's ball noise; the saves' recorded
   inputs and decisions are the dataset (:class:`~learning.datasets.InterceptionDataset`, its
   decision ``"turn"`` or ``"lead"``);
2. **train**: the paper's 3-4-1 net on it (:class:`~learning.interception.InterceptionModel`);
3. **evaluate**: still, and for each decision straight, analytic, random and the net, each
   on the same placements (one evaluation seed: paired trials), the plan's trial count;
4. **report**: saves, goals and misses with 95% intervals, each row's paired difference from
   the lead decision's straight pursuit, and how far the defender travelled after its trigger.

**The drills** (the command line names them: ``robotsoccer learn lead``), in SI units:

* robots (``small_size_1997_arc``: the RoboCup-97 small-size table, 7.5 cm robots whose host
  drives a turn and a dash as one arc, 30 Hz camera with 50 ms latency, 2 mm / 0.02 rad noise,
  5% missed ball detections; sources in the preset): shots across the goal mouth, aimed at a
  point drawn uniformly between the posts (0.50 m goal), from 0.52-0.78 m (20-30 drill units)
  in front of the defender within ±45°, launched by the coach at a speed drawn uniformly in
  0.6-1.2 m/s: a 1997 robot pushed the ball with its body (no kicker), and its wheels top out
  at 1.2 m/s (rSim's VSS motor limit, ``specs/robot_physics.md`` §2.5). The defender stands
  4 units (10 cm) in front of its goal; a touched ball that does not go in is a save;
* Soccer Server (``soccer_server_1996``): the paper's drill as it stands (§5: the shooter
  kicks at the defender with power 100 from 20-30 m, ball noise ``ball_rand``).

Decisions: ``turn`` triggers at BD <= 14 units (the paper); ``lead`` at the first percept that
has a full velocity fit (the defender cannot afford to wait on a 0.7 m shot).
"""

from __future__ import annotations

import dataclasses
import math
import statistics
import time
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from learning.datasets import InterceptionDataset, Provenance
from robotsoccer.experiments.context import RunContext
from robotsoccer.experiments.layer1_collect import decided_saves
from robotsoccer.experiments.layer1_evaluate import counts_of, evaluate
from robotsoccer.experiments.layer1_plan import Condition as EvalCondition
from robotsoccer.experiments.report_cells import paired_cell, percent_cell
from robotsoccer.runs.runner import TrialResult, TrialSpec
from robotsoccer.stats import wilson_interval

DECISIONS = ("turn", "lead")
"""The paper's TA and the robot-native lead (:mod:`robotsoccer.skills.lead`)."""

BEHAVIOURS = ("straight", "analytic", "random", "net")
"""Evaluated for each decision (``still`` once: it never decides)."""

COLLECT_LIMIT_PER_SAVE = 20
"""Collection stops after this many trials per wanted save, saves or not."""


@dataclass(frozen=True)
class StudyDrill:
    """One field's drill of the study: the field, its preset and the drill's options."""

    field_model: str
    preset: str
    options: tuple[tuple[str, str | float], ...]
    summary: str

    def spec(self, seed: int, decision: str, noise: float) -> TrialSpec:
        """The drill with a decision at a ball noise, before the behaviour."""
        spec = TrialSpec(
            drill="intercept", field_model=self.field_model, preset=self.preset, seed=seed
        )
        return spec.with_options(**dict(self.options), decision=decision).with_field(
            ball_noise=noise
        )


@dataclass(frozen=True)
class LeadPlan:
    """How much the study runs.

    Attributes:
        name: ``"quick"``, ``"full"`` or a free name (tests).
        eval_trials: Trials per evaluated behaviour (paper: 1000).
        collect_saves: Saves to collect for each decision's net.
        collect_batch: Trials of each collection batch.
        noise: Ball noise of every trial (paper: .05).
        epochs: Training epochs (paper: 3000).
    """

    name: str
    eval_trials: int = 1000
    collect_saves: int = 1500
    collect_batch: int = 3000
    noise: float = 0.05
    epochs: int = 3000

    def to_dict(self) -> dict[str, Any]:
        """The plan as plain JSON types."""
        return dataclasses.asdict(self)


def plan_for(quick: bool) -> LeadPlan:
    """The full plan (1000 trials per row, 1500 saves per net) or the quick one."""
    if quick:
        return LeadPlan(
            "quick", eval_trials=200, collect_saves=400, collect_batch=1000, epochs=1000
        )
    return LeadPlan("full")


@dataclass(frozen=True)
class StudyRow:
    """One evaluated behaviour: its results (by trial index) and its label."""

    decision: str
    behaviour: str
    results: tuple[TrialResult, ...]


@dataclass(frozen=True)
class FieldSection:
    """One field's study: its drill, the nets' training sizes, the rows."""

    drill: StudyDrill
    trained: dict[str, int]
    rows: tuple[StudyRow, ...]

    def row(self, decision: str, behaviour: str) -> StudyRow:
        """The row of a decision and behaviour (``still`` under either decision)."""
        for row in self.rows:
            if row.behaviour == behaviour and (behaviour == "still" or row.decision == decision):
                return row
        raise KeyError((decision, behaviour))


def run_field(drill: StudyDrill, plan: LeadPlan, ctx: RunContext) -> FieldSection:
    """Collect, train and evaluate both decisions on one field (module docstring)."""
    trained: dict[str, int] = {}
    rows = [_evaluated(drill, plan, ("turn", "still"), None, ctx)]
    for decision in DECISIONS:
        net = train_net(drill, decision, plan, ctx)
        trained[decision] = net[1]
        for behaviour in BEHAVIOURS:
            model = net[0] if behaviour == "net" else None
            rows.append(_evaluated(drill, plan, (decision, behaviour), model, ctx))
    return FieldSection(drill, trained, tuple(rows))


def _evaluated(
    drill: StudyDrill,
    plan: LeadPlan,
    row: tuple[str, str],
    model: Path | None,
    ctx: RunContext,
) -> StudyRow:
    """One row: `row` is its (decision, behaviour); `model` the net of a ``net`` row."""
    decision, behaviour = row
    options: dict[str, str] = {"behaviour": behaviour}
    if model is not None:
        options["model"] = str(model.resolve())
    spec = drill.spec(ctx.seeds.evaluation, decision, plan.noise).with_options(**options)
    name = "still" if behaviour == "still" else f"{decision}_{behaviour}"
    cond = EvalCondition(name, spec, plan.eval_trials)
    results, ran, wall = evaluate(cond, ctx.results_dir(drill.field_model), ctx.workers)
    ctx.log(
        f"{drill.field_model}: {name}: {percent_cell(counts_of(results).saves, len(results))} "
        f"saves ({ran} trials run, {wall:.0f} s)"
    )
    return StudyRow(decision, behaviour, tuple(results))


def train_net(
    drill: StudyDrill, decision: str, plan: LeadPlan, ctx: RunContext
) -> tuple[Path, int]:
    """§5's recipe for one decision: random saves, then the 3-4-1 net. Returns (file, rows)."""
    from learning.interception import InterceptionModel  # torch: only when training

    out, seeds = ctx.out, ctx.seeds
    results_dir = ctx.results_dir(drill.field_model)
    spec = drill.spec(seeds.collection, decision, plan.noise).with_options(behaviour="random")
    n = plan.collect_batch
    limit = COLLECT_LIMIT_PER_SAVE * plan.collect_saves
    while True:
        cond = EvalCondition(f"collect_{decision}", spec, n)
        results, _, _ = evaluate(cond, results_dir, ctx.workers)
        saves = decided_saves(results)
        if len(saves) >= plan.collect_saves or n >= limit:
            break
        n = min(limit, n + plan.collect_batch)
    rows = np.array([r.data for r in saves], dtype=np.float64).reshape(len(saves), 4)
    provenance = Provenance(
        field_model=drill.field_model,
        preset=drill.preset,
        seed=seeds.collection,
        ball_noise=plan.noise,
        behaviour=f"random_{decision}",
        n_trials=n,
        created_by="robotsoccer.experiments.lead_study",
        extra={"drill": drill.summary, "rows": "saves only, in trial order"},
    )
    dataset = InterceptionDataset(rows[:, :3], rows[:, 3], provenance, decision)
    folder = out / "models" / drill.field_model
    folder.mkdir(parents=True, exist_ok=True)
    (out / "datasets" / drill.field_model).mkdir(parents=True, exist_ok=True)
    dataset.save(out / "datasets" / drill.field_model / f"{decision}.npz")
    path = folder / f"{decision}_net.npz"
    if not path.exists():
        start = time.perf_counter()
        model = InterceptionModel(epochs=plan.epochs, random_state=seeds.evaluation)
        model.fit(dataset.x, dataset.y, decision=decision).save(path, provenance)
        ctx.log(
            f"{drill.field_model}: {decision} net on {len(dataset)} saves "
            f"({time.perf_counter() - start:.0f} s)"
        )
    return path, len(dataset)


# ----------------------------------------------------------------------------- report


def travel_units(results: Sequence[TrialResult]) -> float:
    """The defender's mean travel after its trigger [units] (trials that triggered)."""
    values = [dict(r.measures).get("defender_travel_units") for r in results]
    found = [v for v in values if v is not None]
    return statistics.fmean(found) if found else math.nan


def _travel_cell(results: Sequence[TrialResult]) -> str:
    travel = travel_units(results)
    return "—" if math.isnan(travel) else f"{travel:.1f}"


def section_markdown(section: FieldSection, plan: LeadPlan) -> str:
    """One field's table and the checks against the issue's goals."""
    drill = section.drill
    straight = section.row("lead", "straight").results
    lines = [
        f"### {drill.field_model} (`{drill.preset}`): {drill.summary}",
        "",
        f"{plan.eval_trials} trials per row on the same placements (paired), ball noise "
        f"{plan.noise:g}. Nets: turn on {section.trained['turn']} saves, lead on "
        f"{section.trained['lead']}.",
        "",
        "| decision | behaviour | saves % | goals % | misses % | n | saves vs lead straight "
        "(paired, points) | travel after trigger (units) |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for row in section.rows:
        counts = counts_of(row.results)
        n = len(row.results)
        decision = "—" if row.behaviour == "still" else row.decision
        versus = "—" if row.results is straight else paired_cell(row.results, straight)
        lines.append(
            f"| {decision} | {row.behaviour} | {percent_cell(counts.saves, n)} | "
            f"{percent_cell(counts.goals, n)} | {percent_cell(counts.misses, n)} | {n} | "
            f"{versus} | {_travel_cell(row.results)} |"
        )
    lines += ["", *goal_lines(section)]
    return "\n".join(lines)


def share(results: Sequence[TrialResult]) -> tuple[float, float, float]:
    """Saves as a percentage with its 95% Wilson interval."""
    k, n = counts_of(results).saves, len(results)
    low, high = wilson_interval(k, n)
    return 100.0 * k / max(n, 1), 100.0 * low, 100.0 * high


def goal_lines(section: FieldSection) -> list[str]:
    """What the run says about the goals: the net against straight and analytic (lead)."""
    net = share(section.row("lead", "net").results)
    straight = share(section.row("lead", "straight").results)
    analytic = share(section.row("lead", "analytic").results)
    turn_net = share(section.row("turn", "net").results)
    apart = net[1] > straight[2]
    return [
        f"- Learned lead {net[0]:.1f}% against straight pursuit {straight[0]:.1f}%: "
        f"{net[0] - straight[0]:+.1f} points; the intervals "
        f"{'do not overlap' if apart else 'overlap'}.",
        f"- Learned lead against the analytic lead ({analytic[0]:.1f}%): "
        f"{net[0] - analytic[0]:+.1f} points.",
        f"- Learned lead against the paper's learned turn angle ({turn_net[0]:.1f}%): "
        f"{net[0] - turn_net[0]:+.1f} points.",
    ]


def study_markdown(sections: Sequence[FieldSection], plan: LeadPlan) -> str:
    """The study's report section (both fields)."""
    parts = [
        "## Layer 1 with the lead decision (robot-native), beside the paper's turn angle",
        "",
        "Each field's net is trained by §5's recipe (random decisions, the saves' inputs, the "
        "3-4-1 net) for each decision. *turn*: the paper's TA, chosen once at BD ≤ 14 units "
        "and held. *lead*: how far ahead in time along the ball's perceived track to aim, "
        "chosen at the first full velocity fit and re-applied at every percept; its analytic "
        "rule re-plans the earliest meeting time at every percept. Straight pursuit is the "
        "lead decision with a lead of 0.",
        "",
    ]
    for section in sections:
        parts += [section_markdown(section, plan), ""]
    return "\n".join(parts)


def run_study(
    drills: Sequence[StudyDrill], plan: LeadPlan, ctx: RunContext
) -> tuple[str, list[FieldSection]]:
    """The study on each field's drill; returns its markdown and sections."""
    sections = [run_field(drill, plan, ctx) for drill in drills]
    return study_markdown(sections, plan), sections
