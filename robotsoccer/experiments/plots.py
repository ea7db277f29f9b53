"""PNG plots of the paper's Figure 7 and 8 curves: ours with 95% intervals, the paper's beside.

matplotlib is imported inside the functions, with the non-interactive Agg backend, so importing
this module costs nothing and plotting works on a machine without a display.

* :func:`plot_figure7` — saves (%) against training examples: one line per field model with its
  95% Wilson interval as error bars, and the paper's Figure 7 (the "all" row at 4773).
* :func:`plot_figure8` — saves (%) against ball noise, NN and straight: one panel per field model,
  ours with error bars, the paper's Figure 8 dashed.
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from typing import Any

from robotsoccer.experiments.paper import FIGURE_7, FIGURE_8, FIGURE_8_NOISES
from robotsoccer.experiments.report import BEHAVIOUR_NAMES, Counts, ModelSection
from robotsoccer.stats import wilson_interval

_MODEL_COLOURS = ("tab:blue", "tab:orange", "tab:green", "tab:purple")
"""One colour per field model, in the order the sections come."""
_BEHAVIOUR_COLOURS = {"net": "tab:blue", "straight": "tab:red"}


def _pyplot() -> Any:
    import matplotlib

    matplotlib.use("Agg")  # no display needed; must precede the pyplot import
    import matplotlib.pyplot as plt

    return plt


def _saves_with_errors(counts: Sequence[Counts]) -> tuple[list[float], list[list[float]]]:
    """Saves % and the asymmetric error bars [below, above] of their 95% intervals."""
    values, below, above = [], [], []
    for c in counts:
        low, high = wilson_interval(c.saves, c.n)
        share = 100.0 * c.saves / c.n if c.n else 0.0
        values.append(share)
        below.append(share - 100.0 * low)
        above.append(100.0 * high - share)
    return values, [below, above]


def plot_figure7(sections: Sequence[ModelSection], path: Path) -> Path | None:
    """Saves (%) vs training examples: ours ±95% per field model, and the paper's.

    Returns:
        The file written, or None when no section has Figure 7 data.
    """
    sections = [s for s in sections if s.figure7]
    if not sections:
        return None
    plt = _pyplot()
    fig, ax = plt.subplots(figsize=(7.0, 4.5))
    paper_x = sorted(FIGURE_7)
    ax.plot(
        paper_x,
        [FIGURE_7[n].saves_pct for n in paper_x],
        "k--o",
        label="paper (Soccer Server 1996)",
    )
    for index, s in enumerate(sections):
        xs = [examples for examples, _, _ in s.figure7]
        values, errors = _saves_with_errors([c for _, _, c in s.figure7])
        ax.errorbar(
            xs,
            values,
            yerr=errors,
            marker="s",
            capsize=3,
            color=_MODEL_COLOURS[index % len(_MODEL_COLOURS)],
            label=f"ours: {s.field_model} ({s.preset})",
        )
    ax.set_xscale("log")
    ax.set_xlabel("training examples (saves); last point: all collected")
    ax.set_ylabel("saves (%)")
    ax.set_ylim(0, 100)
    ax.set_title("Figure 7: the net's saves vs training examples (95% intervals)")
    ax.grid(True, alpha=0.3)
    ax.legend(loc="lower right")
    return _save(plt, fig, path)


def plot_figure8(sections: Sequence[ModelSection], path: Path) -> Path | None:
    """Saves (%) vs ball noise, NN and straight: one panel per field model, the paper's dashed.

    Returns:
        The file written, or None when no section has Figure 8 data.
    """
    sections = [s for s in sections if s.figure8]
    if not sections:
        return None
    plt = _pyplot()
    fig, axes = plt.subplots(
        1, len(sections), figsize=(6.0 * len(sections), 4.5), squeeze=False, sharey=True
    )
    for ax, s in zip(axes[0], sections, strict=True):
        for behaviour in ("net", "straight"):
            colour = _BEHAVIOUR_COLOURS[behaviour]
            name = BEHAVIOUR_NAMES[behaviour]
            paper = [FIGURE_8[(noise, behaviour)].saves_pct for noise in FIGURE_8_NOISES]
            ax.plot(FIGURE_8_NOISES, paper, "--o", color=colour, alpha=0.5, label=f"paper {name}")
            points = sorted((noise, c) for (noise, b), c in s.figure8.items() if b == behaviour)
            if not points:
                continue
            values, errors = _saves_with_errors([c for _, c in points])
            ax.errorbar(
                [noise for noise, _ in points],
                values,
                yerr=errors,
                marker="s",
                capsize=3,
                color=colour,
                label=f"ours {name}",
            )
        ax.set_title(f"{s.field_model} ({s.preset}); NN on {s.net_examples} examples")
        ax.set_xlabel("ball noise (fraction of speed per axis per 100 ms)")
        ax.set_ylim(0, 102)
        ax.grid(True, alpha=0.3)
        ax.legend(loc="lower left")
    axes[0][0].set_ylabel("saves (%)")
    fig.suptitle("Figure 8: saves vs ball noise (95% intervals)")
    return _save(plt, fig, path)


def _save(plt: Any, fig: Any, path: Path) -> Path:
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path
