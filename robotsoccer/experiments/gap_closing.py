"""Closing the transfer gap: a net trained on one field model made to work on another (issue 10).

The transfer matrix (:mod:`robotsoccer.experiments.transfer`) measures how much a net loses when
it moves from the field it learned on (the reference) to another (the target). Two methods to
win it back are measured here, each against the same matrix cells, on the same placements:

* **Fine-tuning** (:func:`fine_tuning_curve`): the reference's net, its distances read in the
  target's drill units, trains further on the target's first n random-TA saves
  (:meth:`learning.interception.InterceptionModel.fine_tuned`); beside it a net trained from
  scratch on the same n saves. Saves against n is the sample-efficiency curve.
* **Domain randomisation** (:func:`domain_randomised_net`): the reference drill is run on
  ``Randomisation.variants`` variant presets whose parameters are drawn from ranges chosen to
  cover the target (:mod:`robotsoccer.experiments.gap_variants`: written as preset files that
  name the reference preset as their ``base``), an equal share of saves is collected on each,
  and one net trained on the pooled saves is tested on the target (its distances in drill
  units) and on the reference.

Which field is the reference and which parameters are randomised is the caller's choice (the
CLI names the models); nothing here depends on a particular field model. The report section and
the fine-tuning plot are :mod:`robotsoccer.experiments.gap_report`'s.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from learning.datasets import InterceptionDataset, Provenance
from robotsoccer.experiments.context import Field, RunContext
from robotsoccer.experiments.gap_variants import (
    PresetValue,
    Randomisation,
    draw_variants,
    write_variants,
)
from robotsoccer.experiments.layer1_collect import collect
from robotsoccer.experiments.layer1_evaluate import evaluate
from robotsoccer.experiments.layer1_plan import Condition, Layer1Plan, base_spec, condition
from robotsoccer.experiments.layer1_train import prefix, train_series
from robotsoccer.experiments.report_cells import percent_cell
from robotsoccer.runs.runner import TrialResult


def save_share(results: Sequence[TrialResult]) -> str:
    """The saves among `results`, in % with its 95% Wilson interval (a report cell)."""
    return percent_cell(sum(r.label == "SAVE" for r in results), len(results))


@dataclass(frozen=True)
class GapPlan:
    """Sizes of the gap-closing study.

    Attributes:
        sizes: Target-field saves of the sample-efficiency curve.
        fine_tune_epochs: Epochs of fine-tuning (fixed before any result was seen).
        fine_tune_rate: Adam's step in fine-tuning (a tenth of the default: the pre-trained
            weights are a starting point to keep near, not noise to leave).
        epochs: Epochs of a net trained from scratch (layer 1's).
        net_examples: Saves the randomised net trains on (the matrix nets').
        eval_trials: Trials per net per field.
        noise: Ball noise of collection and evaluation.
    """

    sizes: tuple[int, ...] = (10, 25, 50, 100, 200, 400, 750)
    fine_tune_epochs: int = 1000
    fine_tune_rate: float = 1e-3
    epochs: int = 3000
    net_examples: int = 750
    eval_trials: int = 1000
    noise: float = 0.05


def gap_plan(layer1: Layer1Plan, quick: bool) -> GapPlan:
    """The study's plan beside a layer-1 plan (its epochs, net size, trials and noise)."""
    sizes = (25, 100, 300) if quick else GapPlan.sizes
    return GapPlan(
        sizes=tuple(n for n in sizes if n <= layer1.net_examples) or (layer1.net_examples,),
        epochs=layer1.epochs,
        net_examples=layer1.net_examples,
        eval_trials=layer1.eval_trials,
        noise=layer1.noise,
    )


@dataclass(frozen=True)
class CurvePoint:
    """One size of the sample-efficiency curve: both nets' trials on the target field."""

    examples: int
    scratch: tuple[TrialResult, ...]
    tuned: tuple[TrialResult, ...]


def fine_tuning_curve(
    pretrained: Path,
    target: Field,
    dataset: InterceptionDataset,
    unit_m: float,
    plan: GapPlan,
    ctx: RunContext,
) -> list[CurvePoint]:
    """Scratch and fine-tuned nets on the first n target saves, each tested on the target.

    Args:
        pretrained: The reference field's net.
        target: The field the nets are tested on; `dataset` is its random-TA saves.
        dataset: The target's training saves, in trial order.
        unit_m: One drill unit of the target [m] (the pre-trained net reads drill units).
        plan: The study's plan.
        ctx: The run (files under ``gap/`` and ``results/gap/`` of its folder); its evaluation
            seed is shared with the transfer matrix (paired trials).
    """
    from learning.interception import InterceptionModel  # torch loads only when training

    folder = ctx.out / "gap" / "fine_tuning"
    sizes = [n for n in plan.sizes if n <= len(dataset)]
    scratch = train_series(dataset, sizes, plan.epochs, folder / "scratch", ctx.log)
    source = InterceptionModel.load(pretrained)
    (folder / "tuned").mkdir(parents=True, exist_ok=True)
    points = []
    for n in sizes:
        part = prefix(dataset, n)
        tuned = source.fine_tuned(
            part.x.copy(),
            part.y.copy(),
            distance_scale_m=unit_m,
            epochs=plan.fine_tune_epochs,
            learning_rate=plan.fine_tune_rate,
        )
        extra = {**part.provenance.extra, "fine_tuned_from": str(pretrained)}
        path = tuned.save(
            folder / "tuned" / f"net_{n}.npz",
            dataclasses.replace(part.provenance, extra=extra),
        )
        nets = {"scratch": scratch[n], "tuned": path}
        results = {
            kind: _tested(target, net, f"_{kind}{n}", plan, ctx) for kind, net in nets.items()
        }
        point = CurvePoint(n, tuple(results["scratch"]), tuple(results["tuned"]))
        ctx.log(
            f"  [fine-tuning] {n} saves: scratch {save_share(point.scratch)}, "
            f"fine-tuned {save_share(point.tuned)}"
        )
        points.append(point)
    return points


def _tested(
    field: Field,
    net: Path,
    tag: str,
    plan: GapPlan,
    ctx: RunContext,
    *,
    transfer: bool = False,
) -> list[TrialResult]:
    base = base_spec(*field, ctx.seeds.evaluation, "hold")
    cond = condition(base, plan.eval_trials, "net", noise=plan.noise, model=net, tag=tag)
    if transfer:
        cond = Condition(cond.name, cond.spec.with_options(transfer=True), cond.n_trials)
    results_dir = ctx.results_dir("gap") / field[0]
    results, _, _ = evaluate(cond, results_dir, ctx.workers, ctx.progress)
    return results


@dataclass(frozen=True)
class RandomisedNet:
    """The randomised net, its variants' values and its trials on each field tested.

    Attributes:
        path: The net's file.
        variants: Each variant's drawn values, by key.
        saves_per_variant: Saves each variant gave to the pooled training set.
        results: Trials by field model tested on.
    """

    path: Path
    variants: tuple[dict[str, PresetValue], ...]
    saves_per_variant: int
    results: dict[str, tuple[TrialResult, ...]]


def domain_randomised_net(
    reference: Field,
    target: Field,
    randomisation: Randomisation,
    plan: GapPlan,
    ctx: RunContext,
) -> RandomisedNet:
    """Collect on every variant, train one net on the pooled saves, test it on both fields.

    The net is tested on the target with its distances in drill units (``transfer=true``) and
    on the reference's own preset, both on the matrix's evaluation seed.
    """
    from learning.interception import InterceptionModel  # torch loads only when training

    folder = ctx.out / "gap" / "randomised"
    seeds = ctx.seeds
    presets = write_variants(randomisation, folder / "presets", seeds.collection)
    share = math.ceil(plan.net_examples / randomisation.variants)
    collect_plan = Layer1Plan(
        name="randomised",
        eval_trials=plan.eval_trials,
        collect_saves=share,
        collect_batch=500,
        noise=plan.noise,
        epochs=plan.epochs,
    )
    parts = []
    for k, preset in enumerate(presets):
        seed = int(np.random.SeedSequence([seeds.collection, 2, k]).generate_state(1)[0])
        dataset, _, _ = collect(
            base_spec(reference[0], str(preset), seed, "hold"),
            collect_plan,
            folder / f"variant_{k}" / "results",
            folder / f"variant_{k}" / "train.npz",
            ctx.workers,
            "robotsoccer transfer (domain randomisation)",
            ctx.progress,
        )
        parts.append(prefix(dataset, min(share, len(dataset))))
    variants = tuple(draw_variants(randomisation, seeds.collection))
    pooled = _pooled(parts, reference, randomisation, variants, seeds.collection, plan.noise)
    model = InterceptionModel(epochs=plan.epochs).fit(pooled.x.copy(), pooled.y.copy())
    path = model.save(folder / f"net_{len(pooled)}.npz", pooled.provenance)
    ctx.log(f"  [randomised] net on {len(pooled)} saves of {len(presets)} variants")
    results = {
        target[0]: tuple(_tested(target, path, "_randomised", plan, ctx, transfer=True)),
        reference[0]: tuple(_tested(reference, path, "_randomised", plan, ctx)),
    }
    for field, trials in results.items():
        ctx.log(f"  [randomised] on {field}: {save_share(trials)}")
    return RandomisedNet(path, variants, share, results)


def _pooled(
    parts: Sequence[InterceptionDataset],
    reference: Field,
    randomisation: Randomisation,
    variants: Sequence[Mapping[str, PresetValue]],
    seed: int,
    noise: float,
) -> InterceptionDataset:
    """The variants' saves as one training set, its provenance naming every drawn value."""
    extra: dict[str, str | float | int] = {
        "domain_randomisation": "pooled saves of the variants, variant by variant",
        "variants": len(parts),
        "variant_seed": seed,
        "randomised_keys": ", ".join(r.key for r in randomisation.ranges),
    }
    for k, values in enumerate(variants):
        extra |= {f"variant_{k}.{key}": value for key, value in values.items()}
    provenance = Provenance(
        field_model=reference[0],
        preset=randomisation.base_preset,
        seed=seed,
        ball_noise=noise,
        behaviour=parts[0].provenance.behaviour,
        n_trials=sum(p.provenance.n_trials for p in parts),
        created_by="robotsoccer transfer (domain randomisation)",
        extra=extra,
    )
    x = np.concatenate([p.x for p in parts])
    y = np.concatenate([p.y for p in parts])
    return InterceptionDataset(x, y, provenance)
