"""PNG plots of layer 2 (§6): success by the tree's confidence bin, and its reliability.

* :func:`plot_table2` — one panel per field model: SUCCESS / FAILURE / MISS (%) of the tree's
  forced passes in Table 2's confidence bins, ours with 95% intervals, the paper's beside.
* :func:`plot_reliability` — observed success against the tree's mean confidence in tenths,
  one line per field model, with 95% intervals and the diagonal of perfect calibration.

matplotlib is imported inside the functions with the Agg backend (:mod:`.plots`).
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Sequence
from pathlib import Path

import numpy as np

from learning.pass_tree import LABELS
from robotsoccer.experiments.layer2 import RELIABILITY_BINS, Layer2Section, confidence_of, in_bin
from robotsoccer.experiments.paper import TABLE_2, TABLE_2_BINS
from robotsoccer.experiments.plots import _pyplot, _save, error_bars
from robotsoccer.stats import reliability, wilson_interval

_LABEL_COLOURS = {"SUCCESS": "tab:green", "FAILURE": "tab:red", "MISS": "tab:gray"}
_MODEL_COLOURS = ("tab:blue", "tab:orange", "tab:green", "tab:purple")


def plot_table2(sections: Sequence[Layer2Section], path: Path) -> Path | None:
    """Table 2 as grouped bars per confidence bin (None when no section has a tree run)."""
    shown = [s for s in sections if s.results.get("tree")]
    if not shown:
        return None
    plt = _pyplot()
    fig, axes = plt.subplots(1, len(shown), figsize=(6.5 * len(shown), 4.2), squeeze=False)
    keys = ["overall"] + [f".{round(10 * lo)}-.{round(10 * hi)}" for lo, hi in TABLE_2_BINS]
    width = 0.13
    for ax, section in zip(axes[0], shown, strict=True):
        tree = section.results["tree"]
        groups = [tree] + [in_bin(tree, lo, hi) for lo, hi in TABLE_2_BINS]
        x = np.arange(len(keys))
        for k, label in enumerate(LABELS):
            ours: list[float] = []
            lows: list[float] = []
            highs: list[float] = []
            for results in groups:
                n = len(results)
                hits = Counter(r.label for r in results)[label]
                low, high = wilson_interval(hits, n)
                ours.append(100.0 * hits / n if n else np.nan)
                lows.append(100.0 * low if n else np.nan)  # an empty bin draws no bar
                highs.append(100.0 * high if n else np.nan)
            err = error_bars(ours, lows, highs)
            offset = (k - 1) * 2 * width
            colour = _LABEL_COLOURS[label]
            ax.bar(x + offset - width / 2, ours, width, yerr=err, color=colour, capsize=2,
                   label=f"ours {label}")  # fmt: skip
            paper = [TABLE_2[key][label] for key in keys]
            ax.bar(x + offset + width / 2, paper, width, color=colour, alpha=0.35,
                   hatch="//", label=f"paper {label}")  # fmt: skip
        counts = [len(g) for g in groups]
        ax.set_xticks(x, [f"{key}\n(n={n})" for key, n in zip(keys, counts, strict=True)])
        ax.set_ylim(0, 100)
        ax.set_ylabel("share of passes (%)")
        ax.set_title(f"{section.field_model} ({section.preset})")
        ax.grid(axis="y", alpha=0.3)
    axes[0][0].legend(fontsize=7, ncol=2, loc="upper right")
    fig.suptitle("Table 2: the tree forced to pass, by its success confidence (95% intervals)")
    return _save(plt, fig, path)


def plot_reliability(sections: Sequence[Layer2Section], path: Path) -> Path | None:
    """Observed success against the tree's confidence (None when no section has a tree run)."""
    shown = [s for s in sections if s.results.get("tree")]
    if not shown:
        return None
    plt = _pyplot()
    fig, ax = plt.subplots(figsize=(5.5, 5.0))
    ax.plot([0, 1], [0, 1], color="black", linestyle=":", label="perfect calibration")
    lines = [(s, run) for s in shown for run in ("tree", "boost") if s.results.get(run)]
    for k, (section, run) in enumerate(lines):
        colour = _MODEL_COLOURS[k % len(_MODEL_COLOURS)]
        tree = [r for r in section.results[run] if r.data]
        conf = np.array([confidence_of(r) for r in tree])
        success = np.array([r.label == "SUCCESS" for r in tree])
        bins = [b for b in reliability(conf, success, RELIABILITY_BINS) if b.n]
        xs = [b.mean_confidence for b in bins]
        ys = [b.observed for b in bins]
        err = error_bars(ys, [b.observed_low for b in bins], [b.observed_high for b in bins])
        ax.errorbar(xs, ys, yerr=err, marker="o", color=colour, capsize=3,
                    label=f"{section.field_model}, {run} (n={len(tree)})")  # fmt: skip
    ax.set_xlim(0, 1)
    ax.set_ylim(0, 1)
    ax.set_xlabel("predicted success (mean in each tenth)")
    ax.set_ylabel("observed success")
    ax.set_title("Reliability: the tree and the boosted trees")
    ax.legend(fontsize=8, loc="upper left")
    ax.grid(alpha=0.3)
    return _save(plt, fig, path)


def layer2_plots(sections: Sequence[Layer2Section], out: Path) -> list[tuple[str, str]]:
    """Draw both plots under ``out/plots``; (caption, path relative to `out`) of each drawn."""
    drawn = []
    for caption, draw, name in (
        ("Table 2: the tree's passes by success confidence", plot_table2, "table2.png"),
        ("Reliability of the predicted success", plot_reliability, "reliability.png"),
    ):
        if draw(sections, out / "plots" / name) is not None:
            drawn.append((caption, f"plots/{name}"))
    return drawn
