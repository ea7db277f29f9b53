"""The whole transfer study in one call: the matrices, the ablations and the gap-closing methods.

``robotsoccer transfer`` runs it into its own folder; ``robotsoccer reproduce`` runs it into
its folder after layers 1 and 2, where it resumes their collections and nets (the same files,
the same seeds) instead of repeating them. The caller names the two field models: the
reference (the paper's, whose net is moved) and the target.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

from field_models.registry import field_facts
from robotsoccer.experiments import lead_study
from robotsoccer.experiments.ablations import (
    ablation_markdown,
    ablation_plan,
    ablations,
    run_ablations,
)
from robotsoccer.experiments.calibration import recovered_markdown
from robotsoccer.experiments.calibration_fit import calibrate as calibration_fit
from robotsoccer.experiments.calibration_preset import calibrated_drill, write_preset
from robotsoccer.experiments.calibration_traces import record_traces
from robotsoccer.experiments.context import Field, RunContext
from robotsoccer.experiments.gap_closing import domain_randomised_net, fine_tuning_curve, gap_plan
from robotsoccer.experiments.gap_report import References, gap_markdown, plot_curve
from robotsoccer.experiments.gap_variants import Randomisation
from robotsoccer.experiments.layer1 import train_main_net
from robotsoccer.experiments.layer1_collect import collect_into
from robotsoccer.experiments.layer1_evaluate import evaluate
from robotsoccer.experiments.layer1_plan import Condition, plan_for
from robotsoccer.experiments.layer2 import layer2_plan, train_main_tree
from robotsoccer.experiments.lead_study import LeadPlan, StudyDrill, train_net
from robotsoccer.experiments.transfer import (
    Cell,
    LeadNet,
    lead_markdown,
    lead_plan,
    plot_transfer,
    run_lead_transfer,
    run_transfer,
    run_transfer_layer2,
    transfer_markdown,
)
from robotsoccer.runs.runner import TrialResult


@dataclass(frozen=True)
class StudyParts:
    """Which parts of the study run beside the layer-1 matrix.

    Attributes:
        layer2: The pass tree's matrix.
        ablations: The robots' drill ablations (:mod:`robotsoccer.experiments.ablations`).
        gap_closing: Fine-tuning and domain randomisation
            (:mod:`robotsoccer.experiments.gap_closing`).
        lead: The lead decision's matrix (:func:`run_lead_study`), when lead drills are given.
        calibration: With `lead`, the calibrated Soccer Server preset and its lead net
            (:mod:`robotsoccer.experiments.calibration`).
    """

    layer2: bool = True
    ablations: bool = True
    gap_closing: bool = True
    lead: bool = True
    calibration: bool = True


@dataclass(frozen=True)
class TransferSetup:
    """What the transfer study compares.

    Attributes:
        reference: The field the nets are trained on first (the Soccer Server).
        target: The field they are moved to (the robots).
        randomisation: The reference's parameter ranges for domain randomisation.
        parts: Which parts run beside the layer-1 matrix.
        lead_drills: The lead study's drill on the reference and the target field
            (:func:`run_lead_study`); none: no lead matrix.
    """

    reference: Field
    target: Field
    randomisation: Randomisation
    parts: StudyParts = StudyParts()
    lead_drills: tuple[StudyDrill, ...] = ()


def run_transfer_study(setup: TransferSetup, quick: bool, ctx: RunContext) -> str:
    """Run the study into the run's folder (resumable) and return its report section (markdown).

    The context's `created_by` names the command in the files' provenance: ``reproduce`` passes
    its own, so the collections and nets it wrote before are the same files, not rewritten.
    """
    reference, target, randomisation = setup.reference, setup.target, setup.randomisation
    parts, lead_drills = setup.parts, setup.lead_drills
    models = [reference, target]
    plan = plan_for(quick)
    log = ctx.log
    nets = {model: train_main_net((model, preset), plan, ctx) for model, preset in models}
    log("[transfer] layer 1")
    cells = run_transfer(models, nets, plan, ctx)
    cells2: list[Cell] = []
    if parts.layer2:
        plan2 = layer2_plan(quick)
        trees = {
            model: train_main_tree((model, preset), nets[model], plan2, ctx).path
            for model, preset in models
        }
        log("[transfer] layer 2")
        cells2 = run_transfer_layer2(models, nets, trees, plan2, ctx)
    plots = ctx.out / "plots"
    heatmaps = [
        plot_transfer(cells, plots / "transfer_layer1.png", "Layer 1 transfer: saves (%)"),
        plot_transfer(cells2, plots / "transfer_layer2.png", "Layer 2 transfer: passes (%)"),
    ]
    found = [path for path in heatmaps if path is not None]
    text = transfer_markdown([*cells, *cells2], plan.noise, found)
    if parts.lead and lead_drills:
        log("[transfer] layer 1 with the lead decision")
        sizes = lead_study.plan_for(quick)
        text += "\n" + run_lead_study(
            lead_drills, reference[0], target[0], sizes, ctx, calibrate=parts.calibration
        )
    if parts.gap_closing:
        log("[transfer] closing the gap")
        gplan = gap_plan(plan, quick)
        dataset, _, _ = collect_into(target, plan, ctx)
        unit_m = field_facts(*target).unit_m
        curve = fine_tuning_curve(nets[reference[0]], target, dataset, unit_m, gplan, ctx)
        randomised = domain_randomised_net(reference, target, randomisation, gplan, ctx)
        refs = references(cells, reference[0], target[0])
        plot = plot_curve(refs, curve, plots / "fine_tuning.png")
        text += "\n" + gap_markdown(refs, curve, randomised, randomisation, gplan, plot)
    if parts.ablations:
        log("[transfer] ablations")
        plan3 = ablation_plan(quick)
        study = ablations(reference, target)
        rows = run_ablations(study, plan3, ctx)
        text += "\n" + ablation_markdown(rows, plan3)
    return text


def calibrated_label(reference: str) -> str:
    """The calibrated Soccer Server drill's name in the report."""
    return f"{reference} (calibrated)"


def run_lead_study(
    drills: Sequence[StudyDrill],
    reference: str,
    target: str,
    plan: LeadPlan,
    ctx: RunContext,
    *,
    calibrate: bool = True,
) -> str:
    """The lead matrix, and with `calibrate` the calibrated server beside it; its markdown.

    The nets are the lead study's own (:func:`~robotsoccer.experiments.lead_study.train_net`
    into ``out/lead``, the folder ``reproduce`` runs the lead study in, so it resumes them).
    Calibration records `target`'s traces on the collection seed, fits and writes the preset
    (``out/calibration``), trains a lead net on the calibrated server with the target drill in
    units, and tests it in the matrix as a third field; it trains the paper's TA net there as
    well and tests it on `target` beside the uncalibrated and native TA nets (:func:`turn_rows`).

    Raises:
        ValueError: `drills` holds no drill for `reference` or for `target`.
    """
    by_field = {d.field_model: d for d in drills}
    missing = [f for f in (reference, target) if f not in by_field]
    if missing:
        raise ValueError(f"the lead transfer needs a lead drill on {', '.join(missing)}")
    named = [(target, by_field[target]), (reference, by_field[reference])]
    out, seeds, log = ctx.out, ctx.seeds, ctx.log
    lead, calibration = ctx.at(out / "lead"), ctx.at(out / "calibration")
    nets = [LeadNet(train_net(d, "lead", plan, lead)[0], d, label) for label, d in named]
    cal = None
    if calibrate:
        robot = by_field[target]
        facts = field_facts(robot.field_model, robot.preset)
        traces = record_traces(
            robot.field_model, robot.preset, launch_speeds_units(robot), seeds.collection
        )
        cal = calibration_fit(traces, facts)
        server = by_field[reference]
        preset = write_preset(
            cal,
            calibration.out / f"{reference}_calibrated.toml",
            server.preset,
            ctx.created_by,
        )
        drill = calibrated_drill(robot, reference, preset, facts.unit_m)
        path, _ = train_net(drill, "lead", plan, calibration)
        named.append((calibrated_label(reference), drill))
        nets.append(LeadNet(path, drill, calibrated_label(reference)))
        log(f"  [calibration] preset {preset}")
    cells = run_lead_transfer(named, nets, plan, ctx)
    text = lead_markdown(cells, named, plan)
    if cal is not None:
        at = {(c.tested_on, c.defender, c.trained_on): c.results for c in cells}
        rows = {
            "straight": at[(target, "lead straight", "")],
            "uncalibrated": at[(target, "lead net", reference)],
            "calibrated": at[(target, "lead net", calibrated_label(reference))],
            "native": at[(target, "lead net", target)],
            "analytic": at[(target, "lead analytic", "")],
        }
        turn_nets = {
            "native": train_net(by_field[target], "turn", plan, lead),
            "uncalibrated": train_net(by_field[reference], "turn", plan, lead),
            "calibrated": train_net(named[-1][1], "turn", plan, calibration),
        }
        turn = turn_rows(
            by_field[target], {role: net[0] for role, net in turn_nets.items()}, plan, ctx
        )
        paper = field_facts(reference, by_field[reference].preset)
        where = f"calibration/{reference}_calibrated.toml"
        tables = {"lead": rows, "turn (the paper's TA)": turn}
        text += "\n" + recovered_markdown(cal, paper, target, tables, seeds.evaluation, where)
    return text


def turn_rows(
    drill: StudyDrill,
    nets: dict[str, Path],
    plan: LeadPlan,
    ctx: RunContext,
) -> dict[str, tuple[TrialResult, ...]]:
    """The paper's TA decision on `drill`: straight and each net (by role), paired placements.

    The ``native`` net runs as it is; every other with ``transfer=true`` (its distances in
    drill units; a TA is an angle, which needs no other scale).
    """
    base = drill.spec(ctx.seeds.evaluation, "turn", plan.noise)
    folder = ctx.results_dir("transfer_lead") / drill.field_model
    specs = {"straight": base.with_options(behaviour="straight")}
    for role, path in nets.items():
        spec = base.with_options(behaviour="net", model=str(path.resolve()))
        specs[role] = spec if role == "native" else spec.with_options(transfer=True)
    rows = {}
    for role, spec in specs.items():
        cond = Condition(f"turn_{role}", spec, plan.eval_trials)
        rows[role] = tuple(evaluate(cond, folder, ctx.workers, ctx.progress)[0])
    return rows


def launch_speeds_units(drill: StudyDrill) -> tuple[float, float, float]:
    """The drill's slowest, middle and fastest launch speed [units/s] (the calibration's).

    The drill's ``launch_speed_mps`` (and ``launch_speed_max_mps``) where it names them, else
    its plan's one launch speed.
    """
    facts = field_facts(drill.field_model, drill.preset)
    options = dict(drill.options)
    low = float(options.get("launch_speed_mps", 0.0))
    if low <= 0.0:
        low = lead_plan(drill).launch_speed_mps
    high = float(options.get("launch_speed_max_mps", 0.0)) or low
    u = facts.unit_m
    return low / u, 0.5 * (low + high) / u, high / u


def references(cells: list[Cell], reference: str, target: str) -> References:
    """The layer-1 matrix's cells on `target` that the gap-closing methods are measured against."""
    at = {(c.tested_on, c.defender, c.trained_on): c.results for c in cells}
    return References(
        target=target,
        reference=reference,
        transferred=at[(target, "net", reference)],
        native=at[(target, "net", target)],
        straight=at[(target, "straight", "")],
    )
