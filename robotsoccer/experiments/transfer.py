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
trial by trial, with 95% intervals (:func:`~robotsoccer.experiments.report.paired_difference`).
The report gives the matrix as a table (saves with 95% Wilson intervals and n) and a heatmap.

This is the first part of the transfer study. The scaling rule by the task's dimensionless
numbers, the ablations and the gap-closing methods come later.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path

from robotsoccer.experiments.layer1 import (
    Condition,
    Layer1Plan,
    Seeds,
    base_spec,
    condition,
    evaluate,
    train_main_net,
)
from robotsoccer.experiments.report import paired_difference
from robotsoccer.runs.runner import TrialResult
from robotsoccer.stats import wilson_interval

Log = Callable[[str], None]
BASELINES = ("straight", "analytic")
"""The defenders every test field also runs (no model file)."""


@dataclass(frozen=True)
class Cell:
    """One condition of the study: who defends, tested on which field, and its trials.

    Attributes:
        tested_on: The field model the trials ran on.
        defender: ``straight``, ``analytic``, or ``net`` (then `trained_on` says whose).
        trained_on: The field model the net learned on ("" for a baseline).
        results: The trials, sorted by index.
    """

    tested_on: str
    defender: str
    trained_on: str
    results: tuple[TrialResult, ...]

    @property
    def saves(self) -> int:
        """Trials labelled SAVE."""
        return sum(r.label == "SAVE" for r in self.results)

    @property
    def name(self) -> str:
        """How the report names the defender."""
        return f"net trained on {self.trained_on}" if self.defender == "net" else self.defender


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
    plan: Layer1Plan,
    out: Path,
    seeds: Seeds,
    workers: int | None,
    log: Log,
    progress: bool = False,
    nets: dict[str, Path] | None = None,
) -> list[Cell]:
    """Train (or take) each field's net and run every cell into ``out/results/transfer``.

    Args:
        models: (field model, preset) pairs, each trained on and tested on.
        plan: Layer 1's plan (trials per condition, noise, training).
        out: The run folder; nets go where ``reproduce`` puts them.
        seeds: Evaluation (shared by the cells of a test field) and collection seeds.
        workers: Processes.
        log: Progress lines.
        progress: Progress bars.
        nets: Net files by field model; None trains them (resumable).
    """
    if nets is None:
        nets = {
            model: train_main_net(model, preset, plan, out, seeds, workers, log, progress)
            for model, preset in models
        }
    cells = []
    for tested, defender, trained, cond in transfer_conditions(models, nets, plan, seeds):
        results, _, seconds = evaluate(
            cond, out / "results" / "transfer" / tested, workers, progress
        )
        cell = Cell(tested, defender, trained, tuple(results))
        log(f"  [{tested}] {cell.name}: {cell.saves} saves of {len(results)} ({seconds:.1f} s)")
        cells.append(cell)
    return cells


def _percent(cell: Cell) -> str:
    n = len(cell.results)
    low, high = wilson_interval(cell.saves, n)
    return f"{100 * cell.saves / n:.1f} [{100 * low:.1f}, {100 * high:.1f}]"


def _paired(a: Cell, b: Cell) -> str:
    found = paired_difference(list(a.results), list(b.results))
    if found is None:
        return "—"
    diff, low, high, _ = found
    return f"{diff:+.1f} [{low:+.1f}, {high:+.1f}]"


def transfer_markdown(cells: Sequence[Cell], plan: Layer1Plan, heatmap: Path | None) -> str:
    """The study's report section: the matrix, the baselines and the paired gaps."""
    tested = list(dict.fromkeys(c.tested_on for c in cells))
    trained = list(dict.fromkeys(c.trained_on for c in cells if c.defender == "net"))
    at = {(c.tested_on, c.defender, c.trained_on): c for c in cells}
    n = plan.eval_trials
    lines = [
        "## Transfer: train on one field model, test on the other (layer 1)",
        "",
        f"Saves in % of {n} trials per cell with 95% Wilson intervals, ball noise "
        f"{plan.noise:g}. A net tested on another field reads distances in drill units "
        "(k units there enter it as k units of its own field). All cells of a column share "
        "their placements, so the gaps below are paired, trial by trial.",
        "",
        "| defender | " + " | ".join(f"tested on {t}" for t in tested) + " |",
        "|---|" + "---|" * len(tested),
    ]
    for source in trained:
        row = [_percent(at[(t, "net", source)]) for t in tested]
        lines.append(f"| net trained on {source} | " + " | ".join(row) + " |")
    for behaviour in BASELINES:
        row = [_percent(at[(t, behaviour, "")]) for t in tested]
        lines.append(f"| {behaviour} | " + " | ".join(row) + " |")
    lines += ["", "Paired gaps in points (95% intervals):", ""]
    for t in tested:
        native = at.get((t, "net", t))
        for source in trained:
            if source == t or native is None:
                continue
            moved = at[(t, "net", source)]
            straight = at[(t, "straight", "")]
            lines.append(
                f"- on {t}: the net from {source} minus the native net: "
                f"{_paired(moved, native)}; minus straight: {_paired(moved, straight)}; the "
                f"native net minus straight: {_paired(native, straight)}."
            )
    if heatmap is not None:
        lines += ["", f"![Transfer matrix](plots/{heatmap.name})"]
    return "\n".join(lines) + "\n"


def plot_transfer(cells: Sequence[Cell], path: Path) -> Path | None:
    """A heatmap of saves: rows the defender, columns the field tested on."""
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
    fig.colorbar(image, ax=ax, label="saves (%)")
    ax.set_title("Layer 1 transfer: saves (%)")
    return _save(plt, fig, path)
