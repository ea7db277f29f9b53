"""The whole transfer study in one call: the matrices, the ablations and the gap-closing methods.

``robotsoccer transfer`` runs it into its own folder; ``robotsoccer reproduce`` runs it into
its folder after layers 1 and 2, where it resumes their collections and nets (the same files,
the same seeds) instead of repeating them. The caller names the two field models: the
reference (the paper's, whose net is moved) and the target.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from field_models.registry import field_facts
from robotsoccer.experiments.ablations import (
    ablation_markdown,
    ablation_plan,
    ablations,
    run_ablations,
)
from robotsoccer.experiments.gap_closing import (
    Randomisation,
    References,
    domain_randomised_net,
    fine_tuning_curve,
    gap_markdown,
    gap_plan,
    plot_curve,
)
from robotsoccer.experiments.layer1 import (
    Field,
    Log,
    Seeds,
    collect_into,
    plan_for,
    train_main_net,
)
from robotsoccer.experiments.layer2 import layer2_plan, train_main_tree
from robotsoccer.experiments.transfer import (
    Cell,
    plot_transfer,
    run_transfer,
    run_transfer_layer2,
    transfer_markdown,
)


@dataclass(frozen=True)
class StudyParts:
    """Which parts of the study run beside the layer-1 matrix.

    Attributes:
        layer2: The pass tree's matrix.
        ablations: The robots' drill ablations (:mod:`robotsoccer.experiments.ablations`).
        gap_closing: Fine-tuning and domain randomisation
            (:mod:`robotsoccer.experiments.gap_closing`).
    """

    layer2: bool = True
    ablations: bool = True
    gap_closing: bool = True


def run_transfer_study(
    reference: Field,
    target: Field,
    randomisation: Randomisation,
    quick: bool,
    out: Path,
    seeds: Seeds,
    workers: int | None,
    log: Log,
    parts: StudyParts = StudyParts(),
    created_by: str = "robotsoccer transfer",
    progress: bool = False,
) -> str:
    """Run the study into `out` (resumable) and return its report section (markdown).

    `created_by` names the command in the files' provenance: ``reproduce`` passes its own, so
    the collections and nets it wrote before are the same files, not rewritten.
    """
    models = [reference, target]
    plan = plan_for(quick)
    nets = {
        model: train_main_net(model, preset, plan, out, seeds, workers, log, progress, created_by)
        for model, preset in models
    }
    log("[transfer] layer 1")
    cells = run_transfer(models, nets, plan, out, seeds, workers, log, progress)
    cells2: list[Cell] = []
    if parts.layer2:
        plan2 = layer2_plan(quick)
        trees = {
            model: train_main_tree(
                model, preset, nets[model], plan2, out, seeds, workers, log, progress
            ).path
            for model, preset in models
        }
        log("[transfer] layer 2")
        cells2 = run_transfer_layer2(models, nets, trees, plan2, out, seeds, workers, log, progress)
    plots = out / "plots"
    heatmaps = [
        plot_transfer(cells, plots / "transfer_layer1.png", "Layer 1 transfer: saves (%)"),
        plot_transfer(cells2, plots / "transfer_layer2.png", "Layer 2 transfer: passes (%)"),
    ]
    found = [path for path in heatmaps if path is not None]
    text = transfer_markdown([*cells, *cells2], plan.noise, found)
    if parts.gap_closing:
        log("[transfer] closing the gap")
        gplan = gap_plan(plan, quick)
        dataset, _, _ = collect_into(*target, plan, out, seeds, workers, log, created_by, progress)
        unit_m = field_facts(*target).unit_m
        curve = fine_tuning_curve(
            nets[reference[0]], target, dataset, unit_m, gplan, out, seeds, workers, log, progress
        )
        randomised = domain_randomised_net(
            reference, target, randomisation, gplan, out, seeds, workers, log, progress
        )
        refs = references(cells, reference[0], target[0])
        plot = plot_curve(refs, curve, plots / "fine_tuning.png")
        text += "\n" + gap_markdown(refs, curve, randomised, randomisation, gplan, plot)
    if parts.ablations:
        log("[transfer] ablations")
        plan3 = ablation_plan(quick)
        study = ablations(reference, target)
        rows = run_ablations(study, plan3, out, seeds, workers, log, progress)
        text += "\n" + ablation_markdown(rows, plan3)
    return text


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
