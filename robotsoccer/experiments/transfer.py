"""The transfer study for layer 1: train on one field model, test on the other (the matrix).

Each field model's main net (layer 1's collection and training, :func:`~robotsoccer.experiments.
layer1.train_main_net`, the same files ``reproduce`` writes) is tested on every field model:

* on its own field, as ``reproduce`` tests it;
* on the other field with option ``transfer=true``: its distances are put in drill units
  through the stored distance scale (:func:`~robotsoccer.skills.intercept.
  transfer_distance_factor`), so k units on the test field enter the net as k units of the field
  it learned on;
* beside the straight and analytic defenders on the same field.

Every condition on a test field shares its evaluation seed, so the trials are paired (trial i
has the same placement and noise whatever the defender): the differences between nets are taken
trial by trial, with 95% intervals
(:func:`~robotsoccer.experiments.report_cells.paired_difference`).
The report gives the matrix as a table (saves with 95% Wilson intervals and n) and a heatmap.

Layer 2 (:func:`run_transfer_layer2`) does the same for the pass tree: each field's tree picks
the receiver on every field (``transfer=true`` on the other), beside the random and closest
choosers, while the receivers and defenders intercept with the test field's own net.

This is the first part of the transfer study. The scaling rule by the task's dimensionless
numbers, the ablations and the gap-closing methods come later.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

from field_models.registry import field_facts
from robotsoccer.drills import make_drill
from robotsoccer.drills.intercept import InterceptDrill
from robotsoccer.drills.intercept_plan import LaunchPlan
from robotsoccer.experiments.context import RunContext, Seeds
from robotsoccer.experiments.layer1_evaluate import evaluate
from robotsoccer.experiments.layer1_plan import Condition, Layer1Plan, base_spec, condition
from robotsoccer.experiments.layer2 import Layer2Plan, pass_spec
from robotsoccer.experiments.lead_study import LeadPlan, StudyDrill
from robotsoccer.experiments.report_cells import paired_cell
from robotsoccer.runs.runner import TrialResult, TrialSpec
from robotsoccer.stats import wilson_interval

BASELINES = ("straight", "analytic")
"""The defenders every test field also runs (no model file)."""


@dataclass(frozen=True)
class Cell:
    """One condition of the study: who defends, tested on which field, and its trials.

    Attributes:
        tested_on: The field model the trials ran on.
        defender: ``straight``, ``analytic`` or ``net`` (layer 1); the chooser ``tree``,
            ``random`` or ``closest`` (layer 2); `trained_on` says whose model.
        trained_on: The field model the model learned on ("" for a baseline).
        results: The trials, sorted by index.
        success: The label counted as a success.
    """

    tested_on: str
    defender: str
    trained_on: str
    results: tuple[TrialResult, ...]
    success: str = "SAVE"

    @property
    def saves(self) -> int:
        """Trials labelled with the success label (SAVE; SUCCESS for a pass)."""
        return sum(r.label == self.success for r in self.results)

    @property
    def name(self) -> str:
        """How the report names the defender (or the passer's chooser)."""
        if not self.trained_on:
            return self.defender
        return f"{self.defender} trained on {self.trained_on}"


def transfer_conditions(
    models: Sequence[tuple[str, str]],
    nets: dict[str, Path],
    plan: Layer1Plan,
    seeds: Seeds,
) -> list[tuple[str, str, str, Condition]]:
    """(tested on, defender, trained on, condition) for every cell, at the plan's noise."""
    out: list[tuple[str, str, str, Condition]] = []
    for tested, preset in models:
        base = base_spec(tested, preset, seeds.evaluation, plan.ta_mode)
        n = plan.eval_trials
        for behaviour in BASELINES:
            out.append((tested, behaviour, "", condition(base, n, behaviour, noise=plan.noise)))
        for trained, net in nets.items():
            cond = condition(base, n, "net", noise=plan.noise, model=net, tag=f"_{trained}")
            if trained != tested:
                cond = Condition(cond.name, cond.spec.with_options(transfer=True), n)
            out.append((tested, "net", trained, cond))
    return out


def run_transfer(
    models: Sequence[tuple[str, str]],
    nets: dict[str, Path],
    plan: Layer1Plan,
    ctx: RunContext,
) -> list[Cell]:
    """Layer 1's matrix: run every cell into ``out/results/transfer``.

    Args:
        models: (field model, preset) pairs, each trained on and tested on.
        nets: Each field's net (:func:`~robotsoccer.experiments.layer1.train_main_net`).
        plan: Layer 1's plan (trials per condition, noise).
        ctx: The run; its evaluation seed is shared by the cells of a test field.
    """
    cells = []
    for tested, defender, trained, cond in transfer_conditions(models, nets, plan, ctx.seeds):
        folder = ctx.results_dir("transfer") / tested
        results, _, seconds = evaluate(cond, folder, ctx.workers, ctx.progress)
        cell = Cell(tested, defender, trained, tuple(results))
        ctx.log(f"  [{tested}] {cell.name}: {cell.saves} saves of {len(results)} ({seconds:.1f} s)")
        cells.append(cell)
    return cells


def run_transfer_layer2(
    models: Sequence[tuple[str, str]],
    nets: dict[str, Path],
    trees: dict[str, Path],
    plan: Layer2Plan,
    ctx: RunContext,
) -> list[Cell]:
    """Layer 2's matrix: each field's pass tree chooses the receiver on every field.

    On a test field the receivers and defenders intercept with that field's own net (`nets`),
    so only the passer's tree moves between fields; beside it, the random and closest choosers.

    Args:
        models: (field model, preset) pairs.
        nets: Each field's layer-1 net.
        trees: Each field's pass tree (:func:`~robotsoccer.experiments.layer2.
            train_main_tree`).
        plan: Layer 2's plan (trials per condition).
        ctx: The run (its evaluation seed).
    """
    cells = []
    for tested, preset in models:
        base = pass_spec(tested, preset, ctx.seeds.evaluation, nets[tested])
        choosers: list[tuple[str, str, TrialSpec]] = [
            ("random", "", base.with_options(chooser="random")),
            ("closest", "", base.with_options(chooser="closest")),
        ]
        for trained, tree_path in trees.items():
            spec = base.with_options(chooser="tree", model=str(tree_path.resolve()))
            if trained != tested:
                spec = spec.with_options(transfer=True)
            choosers.append(("tree", trained, spec))
        for kind, trained, spec in choosers:
            name = f"layer2_{kind}" + (f"_{trained}" if trained else "")
            cond = Condition(name, spec, plan.eval_trials)
            folder = ctx.results_dir("transfer") / tested
            results, _, seconds = evaluate(cond, folder, ctx.workers, ctx.progress)
            cell = Cell(tested, kind, trained, tuple(results), success="SUCCESS")
            done = f"{cell.saves} passes of {len(results)}"
            ctx.log(f"  [{tested}] {cell.name}: {done} ({seconds:.1f} s)")
            cells.append(cell)
    return cells


def _percent(cell: Cell) -> str:
    n = len(cell.results)
    low, high = wilson_interval(cell.saves, n)
    return f"{100 * cell.saves / n:.1f} [{100 * low:.1f}, {100 * high:.1f}]"


def _paired(a: Cell, b: Cell) -> str:
    return paired_cell(a.results, b.results, a.success)


def transfer_markdown(cells: Sequence[Cell], noise: float, heatmaps: Sequence[Path] = ()) -> str:
    """The study's report section: each layer's matrix, its baselines and the paired gaps."""
    lines = [
        "## Transfer: train on one field model, test on the other",
        "",
        "Successes in % with 95% Wilson intervals: saves for layer 1 (ball noise "
        f"{noise:g}), completed passes for layer 2. A model tested on another field reads "
        "distances in drill units: a net's k units there enter it as k units of its own field, "
        "and the pass attributes are in units already. All cells of a column share their "
        "placements, so the gaps are paired, trial by trial.",
    ]
    for layer, title in ((1, "Layer 1: interception (saves)"), (2, "Layer 2: pass (success)")):
        mine = [c for c in cells if (c.success == "SAVE") == (layer == 1)]
        if mine:
            sizes = sorted({len(c.results) for c in mine})
            n = ", ".join(str(size) for size in sizes)
            lines += ["", f"### {title}", "", f"n = {n} trials per cell.", ""]
            lines += _matrix_lines(mine)
    lines += [""] + [f"![Transfer matrix](plots/{path.name})" for path in heatmaps]
    return "\n".join(lines) + "\n"


def _matrix_lines(cells: Sequence[Cell]) -> list[str]:
    tested = list(dict.fromkeys(c.tested_on for c in cells))
    learned = list(dict.fromkeys((c.defender, c.trained_on) for c in cells if c.trained_on))
    baselines = list(dict.fromkeys(c.defender for c in cells if not c.trained_on))
    at = {(c.tested_on, c.defender, c.trained_on): c for c in cells}
    lines = [
        "| | " + " | ".join(f"tested on {t}" for t in tested) + " |",
        "|---|" + "---|" * len(tested),
    ]
    for kind, source in learned:
        row = [_percent(at[(t, kind, source)]) for t in tested]
        lines.append(f"| {kind} trained on {source} | " + " | ".join(row) + " |")
    for kind in baselines:
        row = [_percent(at[(t, kind, "")]) for t in tested]
        lines.append(f"| {kind} | " + " | ".join(row) + " |")
    lines += ["", "Paired gaps in points (95% intervals):", ""]
    first = baselines[0] if baselines else None
    for t in tested:
        for kind, source in learned:
            native = at.get((t, kind, t))
            if source == t or native is None:
                continue
            moved = at[(t, kind, source)]
            gaps = [f"minus the native {kind}: {_paired(moved, native)}"]
            if first is not None:
                base = at[(t, first, "")]
                gaps += [
                    f"minus {first}: {_paired(moved, base)}",
                    f"the native {kind} minus {first}: {_paired(native, base)}",
                ]
            lines.append(f"- on {t}: the {kind} from {source} " + "; ".join(gaps) + ".")
    return lines


def plot_transfer(cells: Sequence[Cell], path: Path, title: str) -> Path | None:
    """A heatmap of successes: rows the defender (or chooser), columns the field tested on."""
    from robotsoccer.experiments.plots import _pyplot, _save

    tested = list(dict.fromkeys(c.tested_on for c in cells))
    rows = list(dict.fromkeys(c.name for c in cells))
    if not tested or not rows:
        return None
    value = {(c.name, c.tested_on): 100 * c.saves / max(1, len(c.results)) for c in cells}
    grid = [[value.get((r, t), math.nan) for t in tested] for r in rows]
    plt = _pyplot()
    fig, ax = plt.subplots(figsize=(1.8 + 2.2 * len(tested), 1.0 + 0.6 * len(rows)))
    image = ax.imshow(grid, cmap="viridis", vmin=0.0, vmax=100.0, aspect="auto")
    ax.set_xticks(range(len(tested)), [f"tested on\n{t}" for t in tested])
    ax.set_yticks(range(len(rows)), rows)
    for i, row in enumerate(grid):
        for j, v in enumerate(row):
            if not math.isnan(v):
                ax.text(j, i, f"{v:.1f}", ha="center", va="center", color="white")
    fig.colorbar(image, ax=ax, label="success (%)")
    ax.set_title(title)
    return _save(plt, fig, path)


# ----------------------------------------------------------------------------- the lead decision

LEAD_BASELINES = ("straight", "analytic")
"""The lead decision's baselines every test field runs beside the nets (no model file)."""


@dataclass(frozen=True)
class LeadNet:
    """A lead net and the drill it learned on.

    Attributes:
        path: The net's file (:func:`~robotsoccer.experiments.lead_study.train_net`).
        drill: The drill it was trained on (its field, preset and time scale).
        label: How the report names where it learned (the drill's label).
    """

    path: Path
    drill: StudyDrill
    label: str


def lead_plan(drill: StudyDrill) -> LaunchPlan:
    """The launch plan of a lead study's drill on its field (speeds, distances, flight time)."""
    made = make_drill("intercept", {**dict(drill.options), "decision": "lead"})
    assert isinstance(made, InterceptDrill)
    return made.plan_for(field_facts(drill.field_model, drill.preset))


def arrival_time_s(drill: StudyDrill) -> float:
    """The drill's mean ball flight from launch to the defender [s] (its time scale)."""
    return lead_plan(drill).arrival_time_s


def lead_time_scale(trained: StudyDrill, tested: StudyDrill) -> float:
    """The test drill's flight time over the training drill's: the check rows' factor on τ.

    A lead net reads distances and an angle and gives a time. ``transfer=true`` puts the
    distances in drill units (k units here enter the net as k units of its own field) and
    leaves the time alone: τ is applied in seconds, as the net gives it (the matrix's *lead
    net* cells). The other reading is that τ is a share of the drill's flight, since the
    training behaviour drew it uniformly over that flight
    (:func:`~robotsoccer.skills.lead.lead_policy`); multiplied by this factor (drill option
    ``lead_time_scale``) it stays the same share of the test drill's flight. The matrix runs it
    beside, as :data:`FLIGHT_SCALED`: in the seed-0 run it cost saves in both directions (the
    README's transfer section), so seconds are the main reading.
    """
    return arrival_time_s(tested) / arrival_time_s(trained)


def lead_transfer_conditions(
    drills: Sequence[tuple[str, StudyDrill]],
    nets: Sequence[LeadNet],
    plan: LeadPlan,
    seeds: Seeds,
) -> list[tuple[str, str, str, Condition]]:
    """(tested on, defender, trained on, condition) of every lead cell.

    Each test drill runs the lead baselines, every net (its own natively; another's with
    ``transfer=true``, τ in seconds) and every moved net with τ scaled by
    :func:`lead_time_scale`, all on the drill's evaluation seed: paired trials.
    """
    out: list[tuple[str, str, str, Condition]] = []
    for label, drill in drills:
        base = drill.spec(seeds.evaluation, "lead", plan.noise)
        n = plan.eval_trials
        for behaviour in LEAD_BASELINES:
            spec = base.with_options(behaviour=behaviour)
            out.append((label, f"lead {behaviour}", "", Condition(f"lead_{behaviour}", spec, n)))
        for net in nets:
            spec = base.with_options(behaviour="net", model=str(net.path.resolve()))
            tag = _slug(net.label)
            if net.drill == drill:
                out.append((label, "lead net", net.label, Condition(f"lead_net_{tag}", spec, n)))
                continue
            moved = spec.with_options(transfer=True)
            out.append((label, "lead net", net.label, Condition(f"lead_net_{tag}", moved, n)))
            scaled = moved.with_options(lead_time_scale=lead_time_scale(net.drill, drill))
            check = Condition(f"lead_net_{tag}_flight_scaled", scaled, n)
            out.append((label, FLIGHT_SCALED, net.label, check))
    return out


FLIGHT_SCALED = "lead net, τ × flight ratio"
"""The defender name of a moved lead net whose τ is scaled by :func:`lead_time_scale`."""


def _slug(label: str) -> str:
    return "".join(ch if ch.isalnum() else "_" for ch in label).strip("_")


def run_lead_transfer(
    drills: Sequence[tuple[str, StudyDrill]],
    nets: Sequence[LeadNet],
    plan: LeadPlan,
    ctx: RunContext,
) -> list[Cell]:
    """The lead matrix: run every cell into ``out/results/transfer_lead/<test drill>``."""
    cells = []
    conditions = lead_transfer_conditions(drills, nets, plan, ctx.seeds)
    for tested, defender, trained, cond in conditions:
        folder = ctx.results_dir("transfer_lead") / _slug(tested)
        results, _, seconds = evaluate(cond, folder, ctx.workers, ctx.progress)
        cell = Cell(tested, defender, trained, tuple(results))
        ctx.log(f"  [{tested}] {cell.name}: {cell.saves} saves of {len(results)} ({seconds:.1f} s)")
        cells.append(cell)
    return cells


def lead_markdown(
    cells: Sequence[Cell], drills: Sequence[tuple[str, StudyDrill]], plan: LeadPlan
) -> str:
    """The lead matrix's report section: the table, the drills and the paired gaps."""
    tested = [label for label, _ in drills]
    at = {(c.tested_on, c.defender, c.trained_on): c for c in cells}
    rows = list(dict.fromkeys((c.defender, c.trained_on) for c in cells if c.trained_on))
    rows.sort(key=lambda r: r[0] == FLIGHT_SCALED)
    baselines = list(dict.fromkeys(c.defender for c in cells if not c.trained_on))
    sizes = ", ".join(str(s) for s in sorted({len(c.results) for c in cells}))
    lines = [
        "## Transfer with the lead decision (layer 1 on the robots)",
        "",
        "Each field's lead net is trained by §5's recipe on its own drill "
        "(:mod:`robotsoccer.experiments.lead_study`: random leads, the saves' inputs, the 3-4-1 "
        "net) and tested on every drill beside the lead decision's straight pursuit and analytic "
        f"rule. Saves in % with 95% Wilson intervals, ball noise {plan.noise:g}, n = {sizes} "
        "trials per cell; all cells of a column share their placements (paired). A net tested "
        "on another drill reads distances in drill units (`transfer=true`) and gives its lead "
        f"τ in seconds; *{FLIGHT_SCALED}* multiplies τ by the test drill's flight time over its "
        "training drill's (`lead_time_scale`, "
        ":func:`~robotsoccer.experiments.transfer.lead_time_scale`), the other reading of a "
        "time learned on another field.",
        "",
        "Drills (columns):",
        "",
    ]
    for label, drill in drills:
        lines.append(
            f"- {label}: `{Path(drill.preset).stem}`, {drill.summary}; mean flight "
            f"{arrival_time_s(drill):.3f} s."
        )
    lines += [
        "",
        "| | " + " | ".join(f"tested on {t}" for t in tested) + " |",
        "|---|" + "---|" * len(tested),
    ]
    for kind, source in rows:
        row = [_percent(at[(t, kind, source)]) if (t, kind, source) in at else "—" for t in tested]
        lines.append(f"| {kind} trained on {source} | " + " | ".join(row) + " |")
    for kind in baselines:
        row = [_percent(at[(t, kind, "")]) if (t, kind, "") in at else "—" for t in tested]
        lines.append(f"| {kind} | " + " | ".join(row) + " |")
    lines += ["", "Paired gaps in points (95% intervals):", ""]
    for t in tested:
        native = at.get((t, "lead net", t))
        straight = at.get((t, "lead straight", ""))
        for kind, source in rows:
            moved = at.get((t, kind, source))
            if moved is None or source == t:
                continue
            gaps = []
            if native is not None:
                gaps.append(f"minus the native lead net: {_paired(moved, native)}")
            if straight is not None:
                gaps.append(f"minus lead straight: {_paired(moved, straight)}")
            lines.append(f"- on {t}: the {kind} from {source} " + "; ".join(gaps) + ".")
        if native is not None and straight is not None:
            lines.append(f"- on {t}: the native lead net minus lead straight: "
                         f"{_paired(native, straight)}.")  # fmt: skip
    return "\n".join(lines) + "\n"
