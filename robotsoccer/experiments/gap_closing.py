"""Closing the transfer gap: a net trained on one field model made to work on another (issue 10).

The transfer matrix (:mod:`robotsoccer.experiments.transfer`) measures how much a net loses when
it moves from the field it learned on (the reference) to another (the target). Two methods to
win it back are measured here, each against the same matrix cells, on the same placements:

* **Fine-tuning** (:func:`fine_tuning_curve`): the reference's net, its distances read in the
  target's drill units, trains further on the target's first n random-TA saves
  (:meth:`learning.interception.InterceptionModel.fine_tuned`); beside it a net trained from
  scratch on the same n saves. Saves against n is the sample-efficiency curve.
* **Domain randomisation** (:func:`domain_randomised_net`): the reference drill is run on
  :attr:`Randomisation.variants` variant presets whose parameters are drawn from ranges chosen to
  cover the target (:class:`ParameterRange`, written as preset files that name the reference
  preset as their ``base``), an equal share of saves is collected on each, and one net trained on
  the pooled saves is tested on the target (its distances in drill units) and on the reference.

Which field is the reference and which parameters are randomised is the caller's choice (the
CLI names the models); nothing here depends on a particular field model.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from learning.datasets import InterceptionDataset, Provenance
from robotsoccer.experiments.layer1_collect import collect
from robotsoccer.experiments.layer1_evaluate import evaluate
from robotsoccer.experiments.layer1_plan import (
    Condition,
    Field,
    Layer1Plan,
    Log,
    Seeds,
    base_spec,
    condition,
)
from robotsoccer.experiments.layer1_train import prefix, train_series
from robotsoccer.experiments.report import paired_cell, percent_cell
from robotsoccer.runs.runner import TrialResult

PresetValue = float | int


# ----------------------------------------------------------------------------- randomisation


@dataclass(frozen=True)
class ParameterRange:
    """One preset parameter drawn per variant, uniformly (or log-uniformly) in [low, high].

    Attributes:
        key: Dotted preset key, ``"<table>.<name>"`` (e.g. ``"dynamics.player_decay"``).
        low: Smallest value, in the key's unit.
        high: Largest value.
        log: Draw uniformly in log space (for rates spanning a factor of several).
        step: Round to a multiple of this (an integer step gives an integer); None: no rounding.
        why: What on the target the range is meant to cover, for the report.
    """

    key: str
    low: float
    high: float
    log: bool = False
    step: float | None = None
    why: str = ""

    def __post_init__(self) -> None:
        table, _, name = self.key.partition(".")
        if not table or not name or "." in name:
            raise ValueError(f"range key {self.key!r} is not '<table>.<name>'")
        if not (math.isfinite(self.low) and math.isfinite(self.high) and self.low <= self.high):
            raise ValueError(
                f"range {self.key}: need finite low <= high, got {self.low}, {self.high}"
            )
        if self.log and self.low <= 0.0:
            raise ValueError(f"range {self.key}: a log range needs low > 0, got {self.low}")
        if self.step is not None and not self.step > 0.0:
            raise ValueError(f"range {self.key}: step must be > 0, got {self.step}")

    def draw(self, rng: np.random.Generator) -> PresetValue:
        """One value from `rng`."""
        if self.log:
            value = math.exp(rng.uniform(math.log(self.low), math.log(self.high)))
        else:
            value = rng.uniform(self.low, self.high)
        if self.step is None:
            return float(value)
        rounded = self.step * round(value / self.step)
        return int(rounded) if float(self.step).is_integer() else float(rounded)


@dataclass(frozen=True)
class Randomisation:
    """Domain randomisation of the reference field: its preset and the ranges drawn.

    Attributes:
        base_preset: The reference preset every variant starts from.
        ranges: The parameters drawn per variant.
        variants: Variant presets (each collects an equal share of the saves).
    """

    base_preset: str
    ranges: tuple[ParameterRange, ...]
    variants: int = 10

    def __post_init__(self) -> None:
        if self.variants < 1:
            raise ValueError(f"variants must be >= 1, got {self.variants}")
        keys = [r.key for r in self.ranges]
        if len(set(keys)) != len(keys):
            raise ValueError(f"a key is drawn twice: {keys}")


RANDOMISATION_STREAM = 0xD0A1
"""Names the generator of the variants' draws among those spawned from a run's seed."""


def draw_variants(randomisation: Randomisation, seed: int) -> list[dict[str, PresetValue]]:
    """Each variant's drawn values, by key; a function of `seed` only."""
    rng = np.random.default_rng(np.random.SeedSequence([seed, RANDOMISATION_STREAM]))
    return [
        {r.key: r.draw(rng) for r in randomisation.ranges} for _ in range(randomisation.variants)
    ]


def variant_text(base_preset: str, values: Mapping[str, PresetValue], note: str) -> str:
    """A preset file naming `base_preset` as its base and setting `values` (TOML)."""
    tables: dict[str, list[str]] = {}
    for key, value in values.items():
        table, name = key.split(".")
        tables.setdefault(table, []).append(f"{name} = {value!r}")
    lines = [f"# {note}", f'base = "{base_preset}"']
    for table, entries in tables.items():
        lines += ["", f"[{table}]", *entries]
    return "\n".join(lines) + "\n"


def write_variants(randomisation: Randomisation, folder: Path, seed: int) -> list[Path]:
    """Write the variant presets into `folder` (``variant_<k>.toml``); their paths."""
    folder.mkdir(parents=True, exist_ok=True)
    paths = []
    for k, values in enumerate(draw_variants(randomisation, seed)):
        note = f"domain randomisation variant {k} of {randomisation.base_preset} (seed {seed})"
        path = folder / f"variant_{k}.toml"
        path.write_text(variant_text(randomisation.base_preset, values, note))
        paths.append(path.resolve())
    return paths


# ----------------------------------------------------------------------------- plan


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


# ----------------------------------------------------------------------------- fine-tuning


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
    out: Path,
    seeds: Seeds,
    workers: int | None,
    log: Log,
    progress: bool = False,
) -> list[CurvePoint]:
    """Scratch and fine-tuned nets on the first n target saves, each tested on the target.

    Args:
        pretrained: The reference field's net.
        target: The field the nets are tested on; `dataset` is its random-TA saves.
        dataset: The target's training saves, in trial order.
        unit_m: One drill unit of the target [m] (the pre-trained net reads drill units).
        plan: The study's plan.
        out: The run folder (files under ``gap/`` and ``results/gap/``).
        seeds: The evaluation seed is shared with the transfer matrix (paired trials).
        workers: Processes.
        log: Progress lines.
        progress: Progress bars.
    """
    from learning.interception import InterceptionModel  # torch loads only when training

    folder = out / "gap" / "fine_tuning"
    sizes = [n for n in plan.sizes if n <= len(dataset)]
    scratch = train_series(dataset, sizes, plan.epochs, folder / "scratch", log)
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
            kind: _tested(target, net, f"_{kind}{n}", plan, out, seeds, workers, progress)
            for kind, net in nets.items()
        }
        point = CurvePoint(n, tuple(results["scratch"]), tuple(results["tuned"]))
        log(
            f"  [fine-tuning] {n} saves: scratch {_share(point.scratch)}, "
            f"fine-tuned {_share(point.tuned)}"
        )
        points.append(point)
    return points


def _tested(
    field: Field,
    net: Path,
    tag: str,
    plan: GapPlan,
    out: Path,
    seeds: Seeds,
    workers: int | None,
    progress: bool,
    *,
    transfer: bool = False,
) -> list[TrialResult]:
    base = base_spec(*field, seeds.evaluation, "hold")
    cond = condition(base, plan.eval_trials, "net", noise=plan.noise, model=net, tag=tag)
    if transfer:
        cond = Condition(cond.name, cond.spec.with_options(transfer=True), cond.n_trials)
    results, _, _ = evaluate(cond, out / "results" / "gap" / field[0], workers, progress)
    return results


# ----------------------------------------------------------------------------- randomisation


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
    out: Path,
    seeds: Seeds,
    workers: int | None,
    log: Log,
    progress: bool = False,
) -> RandomisedNet:
    """Collect on every variant, train one net on the pooled saves, test it on both fields.

    The net is tested on the target with its distances in drill units (``transfer=true``) and
    on the reference's own preset, both on the matrix's evaluation seed.
    """
    from learning.interception import InterceptionModel  # torch loads only when training

    folder = out / "gap" / "randomised"
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
            workers,
            "robotsoccer transfer (domain randomisation)",
            progress,
        )
        parts.append(prefix(dataset, min(share, len(dataset))))
    variants = tuple(draw_variants(randomisation, seeds.collection))
    pooled = _pooled(parts, reference, randomisation, variants, seeds.collection, plan.noise)
    model = InterceptionModel(epochs=plan.epochs).fit(pooled.x.copy(), pooled.y.copy())
    path = model.save(folder / f"net_{len(pooled)}.npz", pooled.provenance)
    log(f"  [randomised] net on {len(pooled)} saves of {len(presets)} variants")
    results = {
        target[0]: tuple(
            _tested(target, path, "_randomised", plan, out, seeds, workers, progress,
                    transfer=True)
        ),
        reference[0]: tuple(
            _tested(reference, path, "_randomised", plan, out, seeds, workers, progress)
        ),
    }  # fmt: skip
    for field, trials in results.items():
        log(f"  [randomised] on {field}: {_share(trials)}")
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


# ----------------------------------------------------------------------------- report


@dataclass(frozen=True)
class References:
    """The matrix's cells on the target field that the methods are measured against.

    Attributes:
        target: The target field model.
        reference: The reference field model.
        transferred: The reference's net on the target (the gap's lower end).
        native: The target's own net (its upper end).
        straight: The straight defender on the target.
    """

    target: str
    reference: str
    transferred: tuple[TrialResult, ...]
    native: tuple[TrialResult, ...]
    straight: tuple[TrialResult, ...]


def _share(results: Sequence[TrialResult]) -> str:
    return percent_cell(sum(r.label == "SAVE" for r in results), len(results))


def gap_markdown(
    refs: References,
    curve: Sequence[CurvePoint],
    randomised: RandomisedNet | None,
    randomisation: Randomisation | None,
    plan: GapPlan,
    plot: Path | None = None,
) -> str:
    """The report section: each method's saves on the target and the points it recovers."""
    t, r = refs.target, refs.reference
    lines = [
        f"## Closing the gap: the {r} net on {t}",
        "",
        f"Saves on {t} at ball noise {plan.noise:g}, in % with 95% Wilson intervals, "
        f"{len(refs.native)} trials per net on the transfer matrix's placements, so every gap is "
        f"paired trial by trial (95% interval). *Recovered* is a method's net minus the {r} "
        f"net moved as it is; *left* is it minus {t}'s own net.",
        "",
        f"- {r} net on {t}, as it is: {_share(refs.transferred)}; {t}'s own net: "
        f"{_share(refs.native)}; straight: {_share(refs.straight)}.",
        f"- the gap: {paired_cell(refs.transferred, refs.native)} points.",
    ]
    if randomised is not None and randomisation is not None:
        lines += ["", *_randomised_lines(refs, randomised, randomisation)]
    if curve:
        lines += ["", *_curve_lines(refs, curve, plan)]
    if plot is not None:
        lines += ["", f"![Fine-tuning: saves against {t} examples](plots/{plot.name})"]
    return "\n".join(lines) + "\n"


def _randomised_lines(
    refs: References, net: RandomisedNet, randomisation: Randomisation
) -> list[str]:
    on_target = net.results[refs.target]
    on_reference = net.results.get(refs.reference, ())
    lines = [
        "### Domain randomisation",
        "",
        f"{len(net.variants)} variants of `{randomisation.base_preset}`, each drawn from the "
        f"ranges below, {net.saves_per_variant} random-TA saves from each, one net on the "
        "pooled saves:",
        "",
        "| parameter | range | drawn | covers |",
        "|---|---|---|---|",
    ]
    for rng in randomisation.ranges:
        drawn = ", ".join(f"{v[rng.key]:g}" for v in net.variants)
        scale = " (log-uniform)" if rng.log else ""
        lines.append(f"| `{rng.key}` | {rng.low:g} – {rng.high:g}{scale} | {drawn} | {rng.why} |")
    lines += [
        "",
        f"| net | on {refs.target} | recovered | left | on {refs.reference} |",
        "|---|---|---|---|---|",
        f"| randomised | {_share(on_target)} | {paired_cell(on_target, refs.transferred)} | "
        f"{paired_cell(on_target, refs.native)} | {_share(on_reference)} |",
    ]
    return lines


def _curve_lines(refs: References, curve: Sequence[CurvePoint], plan: GapPlan) -> list[str]:
    lines = [
        "### Fine-tuning: a sample-efficiency curve",
        "",
        f"The {refs.reference} net, reading {refs.target}'s distances in drill units, trains "
        f"{plan.fine_tune_epochs} more epochs (Adam, step {plan.fine_tune_rate:g}, no weight "
        f"decay) on {refs.target}'s first n random-TA saves; *scratch* trains a new net "
        f"({plan.epochs} epochs, layer 1's recipe) on the same saves.",
        "",
        "| n saves | scratch | fine-tuned | fine-tuned - scratch | recovered | left |",
        "|---|---|---|---|---|---|",
    ]
    for p in curve:
        lines.append(
            f"| {p.examples} | {_share(p.scratch)} | {_share(p.tuned)} | "
            f"{paired_cell(p.tuned, p.scratch)} | {paired_cell(p.tuned, refs.transferred)} | "
            f"{paired_cell(p.tuned, refs.native)} |"
        )
    return lines


def plot_curve(refs: References, curve: Sequence[CurvePoint], path: Path) -> Path | None:
    """Saves against target examples, scratch and fine-tuned, beside the matrix's references."""
    from robotsoccer.experiments.plots import _pyplot, _save, error_bars
    from robotsoccer.stats import wilson_interval

    if not curve:
        return None

    def share(results: Sequence[TrialResult]) -> tuple[float, float, float]:
        k, n = sum(r.label == "SAVE" for r in results), len(results)
        low, high = wilson_interval(k, n)
        return 100 * k / n, 100 * low, 100 * high

    plt = _pyplot()
    fig, ax = plt.subplots(figsize=(6.4, 4.2))
    xs = [p.examples for p in curve]
    for kind, colour in (("scratch", "tab:blue"), ("tuned", "tab:orange")):
        values = [share(getattr(p, kind)) for p in curve]
        ax.errorbar(
            xs,
            [v[0] for v in values],
            yerr=error_bars(*zip(*values, strict=True)),
            marker="o",
            capsize=3,
            color=colour,
            label="fine-tuned" if kind == "tuned" else "from scratch",
        )
    for results, label, style in (
        (refs.native, f"{refs.target}'s own net", "-"),
        (refs.transferred, f"{refs.reference} net as it is", "--"),
        (refs.straight, "straight", ":"),
    ):
        ax.axhline(share(results)[0], color="grey", linestyle=style, label=label)
    ax.set_xscale("log")
    ax.set_xlabel(f"{refs.target} random-TA saves trained on")
    ax.set_ylabel(f"saves on {refs.target} (%)")
    ax.legend(fontsize=8)
    ax.set_title("Fine-tuning against training from scratch")
    return _save(plt, fig, path)
