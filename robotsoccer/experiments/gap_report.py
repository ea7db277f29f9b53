"""Closing the gap's report (issue 10): the section, its tables and the fine-tuning plot.

Measured against the transfer matrix's cells on the target (:class:`References`), each method's
saves and the points it recovers, paired trial by trial (:mod:`robotsoccer.experiments.gap_closing`
runs the methods).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

from robotsoccer.experiments.gap_closing import CurvePoint, GapPlan, RandomisedNet, save_share
from robotsoccer.experiments.gap_variants import Randomisation
from robotsoccer.experiments.report_cells import paired_cell
from robotsoccer.runs.runner import TrialResult


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
        f"- {r} net on {t}, as it is: {save_share(refs.transferred)}; {t}'s own net: "
        f"{save_share(refs.native)}; straight: {save_share(refs.straight)}.",
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
        f"| randomised | {save_share(on_target)} | {paired_cell(on_target, refs.transferred)} | "
        f"{paired_cell(on_target, refs.native)} | {save_share(on_reference)} |",
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
            f"| {p.examples} | {save_share(p.scratch)} | {save_share(p.tuned)} | "
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
