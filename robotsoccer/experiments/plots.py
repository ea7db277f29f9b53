"""PNG plots of the paper's Figure 7 and 8 curves: ours with 95% intervals, the paper's beside.

matplotlib is imported inside the functions, with the non-interactive Agg backend, so importing
this module costs nothing and plotting works on a machine without a display.

* :func:`plot_figure7` — saves (%) against training examples: one line per field model with its
  95% Wilson interval as error bars, and the paper's Figure 7 (the "all" row at 4773).
* :func:`plot_figure8` — saves (%) against ball noise, NN and straight: one panel per field model,
  ours with error bars, the paper's Figure 8 dashed.
* :func:`error_bars` — the asymmetric, never negative error bars every plot here draws.
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np

from robotsoccer.experiments.paper import (
    FIGURE_7,
    FIGURE_8,
    FIGURE_8_NOISES,
    PAPER_ALL_SAVES,
    PAPER_NOISE,
)
from robotsoccer.experiments.report_records import BEHAVIOUR_NAMES, Counts, ModelSection
from robotsoccer.stats import wilson_interval

_MODEL_COLOURS = ("tab:blue", "tab:orange", "tab:green", "tab:purple")
"""One colour per field model, in the order the sections come."""
_BEHAVIOUR_COLOURS = {"net": "tab:blue", "straight": "tab:red"}
NOISE_STEP = 0.01
"""The grid of Figure 8's noise levels: lines join only levels this far apart."""


def _pyplot() -> Any:
    import matplotlib

    matplotlib.use("Agg")  # no display needed; must precede the pyplot import
    import matplotlib.pyplot as plt

    return plt


def error_bars(
    values: Sequence[float], lows: Sequence[float], highs: Sequence[float]
) -> list[list[float]]:
    """Error bars ``[below, above]`` for matplotlib's ``yerr`` of values inside [low, high].

    A bar is clipped at 0: matplotlib refuses a negative one ("'yerr' must not contain negative
    values"), and a share and its interval scaled to percent separately can cross by a rounding
    error. NaN stays NaN (no bar).
    """
    value, low, high = (np.asarray(v, dtype=np.float64) for v in (values, lows, highs))
    below = np.maximum(value - low, 0.0)  # np.maximum keeps NaN, the builtin max would not
    above = np.maximum(high - value, 0.0)
    return [below.tolist(), above.tolist()]


def _saves_with_errors(counts: Sequence[Counts]) -> tuple[list[float], list[list[float]]]:
    """Saves % and the asymmetric error bars [below, above] of their 95% intervals."""
    values, lows, highs = [], [], []
    for c in counts:
        low, high = wilson_interval(c.saves, c.n)
        values.append(100.0 * c.saves / c.n if c.n else 0.0)
        lows.append(100.0 * low)
        highs.append(100.0 * high)
    return values, error_bars(values, lows, highs)


def plot_figure7(sections: Sequence[ModelSection], path: Path) -> Path | None:
    """Saves (%) vs training examples: ours ±95% per field model, the paper's, and straight.

    Each field model's straight defender at the same noise is a flat line of its colour (the
    baseline the nets should beat); the x axis is labelled with the training sizes used.

    Returns:
        The file written, or None when no section has Figure 7 data.
    """
    sections = [s for s in sections if s.figure7]
    if not sections:
        return None
    plt = _pyplot()
    fig, ax = plt.subplots(figsize=(8.0, 4.8))
    paper_x = sorted(FIGURE_7)
    ax.plot(
        paper_x,
        [FIGURE_7[n].saves_pct for n in paper_x],
        "k--o",
        label="paper NN (Soccer Server 1996)",
    )
    paper_straight = FIGURE_8.get((PAPER_NOISE, "straight"))
    if paper_straight is not None:
        ax.axhline(paper_straight.saves_pct, color="k", linestyle=":", linewidth=1,
                   label="paper straight (Soccer Server 1996)")  # fmt: skip
    ticks = {n: str(n) for n in paper_x if n != PAPER_ALL_SAVES}
    ticks[PAPER_ALL_SAVES] = f"all\n({PAPER_ALL_SAVES}, paper)"
    for index, s in enumerate(sections):
        colour = _MODEL_COLOURS[index % len(_MODEL_COLOURS)]
        xs = [examples for examples, _, _ in s.figure7]
        values, errors = _saves_with_errors([c for _, _, c in s.figure7])
        ax.errorbar(
            xs, values, yerr=errors, marker="s", capsize=3, color=colour,
            label=f"ours NN: {s.field_model} ({s.preset})",
        )  # fmt: skip
        for (examples, label, _), value in zip(s.figure7, values, strict=True):
            if examples not in ticks:  # e.g. all the saves collected: say how many
                ax.annotate(label, (examples, value), textcoords="offset points",
                            xytext=(0, -16 - 10 * index), ha="center", fontsize="small",
                            color=colour)  # fmt: skip
        straight = s.figure8.get((round(s.noise, 4), "straight")) or s.table1.get("straight")
        if straight is not None:
            ax.axhline(straight.saves_pct(), color=colour, linestyle=":", linewidth=1.5,
                       label=f"ours straight: {s.field_model}")  # fmt: skip
    ax.set_xscale("log")
    ax.set_xticks(sorted(ticks), [ticks[n].replace("all ", "all\n") for n in sorted(ticks)])
    ax.minorticks_off()
    ax.set_xlabel("training examples (saves); the last point: all collected")
    ax.set_ylabel("saves (%)")
    ax.set_ylim(0, 100)
    noises = ", ".join(sorted({f"{s.noise:g}" for s in sections}))
    ax.set_title(f"Figure 7: the net's saves vs training examples, ball noise {noises}")
    ax.grid(True, alpha=0.3)
    ax.legend(loc="lower right", fontsize="small")
    return _save(plt, fig, path)


def measured_runs(xs: Sequence[float], step: float = NOISE_STEP) -> list[list[int]]:
    """Indices of `xs` (ascending) split where a level between two points was not measured.

    Lines join only neighbouring levels of the grid (0.05 and 0.06, not 0 and 0.05).

    >>> measured_runs([0.0, 0.05, 0.06, 0.07, 0.1])
    [[0], [1, 2, 3], [4]]
    """
    runs: list[list[int]] = []
    for i, x in enumerate(xs):
        if runs and x - xs[runs[-1][-1]] <= step * 1.001:
            runs[-1].append(i)
        else:
            runs.append([i])
    return runs


def plot_figure8(sections: Sequence[ModelSection], path: Path) -> Path | None:
    """Saves (%) vs ball noise, NN and straight: one panel per field model, the paper's dashed.

    The paper's curves are the Soccer Server's, said so in every panel; each panel's x label
    gives its field's noise period; no line crosses a noise level that was not measured.

    Returns:
        The file written, or None when no section has Figure 8 data.
    """
    sections = [s for s in sections if s.figure8]
    if not sections:
        return None
    plt = _pyplot()
    fig, axes = plt.subplots(
        1, len(sections), figsize=(6.5 * len(sections), 4.8), squeeze=False, sharey=True
    )
    for ax, s in zip(axes[0], sections, strict=True):
        for behaviour in ("net", "straight"):
            colour = _BEHAVIOUR_COLOURS[behaviour]
            name = BEHAVIOUR_NAMES[behaviour]
            paper = [FIGURE_8[(noise, behaviour)].saves_pct for noise in FIGURE_8_NOISES]
            _plot_runs(ax, FIGURE_8_NOISES, paper, "--", colour, 0.5,
                       f"paper {name} (Soccer Server 1996)")  # fmt: skip
            points = sorted((noise, c) for (noise, b), c in s.figure8.items() if b == behaviour)
            if not points:
                continue
            xs = [noise for noise, _ in points]
            values, errors = _saves_with_errors([c for _, c in points])
            ax.errorbar(xs, values, yerr=errors, fmt="s", capsize=3, color=colour)
            _plot_runs(ax, xs, values, "-", colour, 1.0, f"ours {name}")
        ax.set_title(f"{s.field_model} ({s.preset}); NN on {s.net_examples} examples")
        period = f"{1000 * s.noise_period_s:.4g} ms" if s.noise_period_s else "noise period"
        ax.set_xlabel(f"ball noise (± share of speed per axis, once per {period})")
        ax.set_ylim(0, 102)
        ax.grid(True, alpha=0.3)
        ax.legend(loc="lower left", fontsize="small")
    axes[0][0].set_ylabel("saves (%)")
    fig.suptitle("Figure 8: saves vs ball noise (95% intervals)")
    return _save(plt, fig, path)


def _plot_runs(
    ax: Any, xs: Sequence[float], ys: Sequence[float], style: str, colour: str, alpha: float,
    label: str,
) -> None:  # fmt: skip
    """Markers at every point, lines only within runs of neighbouring noise levels."""
    ax.plot(xs, ys, "o", color=colour, alpha=alpha, label=label, markersize=4)
    for run in measured_runs(xs):
        if len(run) > 1:
            ax.plot([xs[i] for i in run], [ys[i] for i in run], style, color=colour, alpha=alpha)


def _save(plt: Any, fig: Any, path: Path) -> Path:
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path
