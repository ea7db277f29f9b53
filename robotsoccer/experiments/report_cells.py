"""Cells of the layer-1 report: a percentage with its 95% interval, paired differences, vs paper.

A percentage is printed with its 95% Wilson interval (:func:`robotsoccer.stats.wilson_interval`);
two conditions run on the same seeds are compared trial by trial (:func:`paired_difference`);
a paper figure is judged against our interval (:func:`versus_paper`). :func:`paper_table` lays
rows out in the paper's columns, ours beside the paper's. Other studies use these cells too.
"""

from __future__ import annotations

import math
import statistics
from collections.abc import Sequence

from robotsoccer.experiments.report_records import AGREES, Row
from robotsoccer.runs.runner import TrialResult
from robotsoccer.stats import Z_95, wilson_interval


def percent_cell(successes: int, trials: int) -> str:
    """``"57.3 [54.2, 60.4]"``: a percentage with its 95% Wilson interval; "—" for no trials."""
    if trials <= 0:
        return "—"
    low, high = wilson_interval(successes, trials)
    return f"{100 * successes / trials:.1f} [{100 * low:.1f}, {100 * high:.1f}]"


def paired_cell(a: Sequence[TrialResult], b: Sequence[TrialResult], label: str = "SAVE") -> str:
    """``"+27.5 [+24.0, +31.0]"``: `a` minus `b`, paired (:func:`paired_difference`), 95%.

    "—" when the two share no trials.
    """
    found = paired_difference(a, b, label)
    if found is None:
        return "—"
    diff, low, high, _ = found
    return f"{diff:+.1f} [{low:+.1f}, {high:+.1f}]"


def paper_cell(value: float | None) -> str:
    """A paper number, or "—" when the paper does not give one."""
    return "—" if value is None else f"{value:g}"


def versus_paper(successes: int, trials: int, paper: float | None) -> str:
    """Our share against the paper's figure: ``agrees``, or ``above``/``below`` by how much.

    ``agrees`` when the paper's figure lies inside our 95% Wilson interval, judged at the
    printed precision (0.1 points, so a paper 0 beside our ``0.0 [0.0, 1.9]`` agrees);
    otherwise whether our share lies above or below the paper's, and ours minus the paper's
    in percentage points. "—" without a paper figure or without trials.

    >>> versus_paper(612, 1000, 86.0)
    'below (-24.8 pts)'
    >>> versus_paper(530, 1000, 53.0)
    'agrees'
    """
    if paper is None or trials <= 0:
        return "—"
    low, high = (round(100 * v, 1) for v in wilson_interval(successes, trials))
    if low <= paper <= high:
        return AGREES
    diff = 100 * successes / trials - paper
    return f"{'above' if paper < low else 'below'} ({diff:+.1f} pts)"


def versus_cell(verdicts: Sequence[str]) -> str:
    """One vs-paper cell from a row's verdicts, one per paper column (``—``: no figure).

    ``agrees`` when every figure the paper gives agrees; otherwise each column's verdict in
    the table's column order, joined by `` / `` (a single figure alone).
    """
    given = [v for v in verdicts if v != "—"]
    if not given:
        return "—"
    if all(v == AGREES for v in given):
        return AGREES
    return " / ".join(verdicts) if len(given) > 1 else given[0]


TABLE_COLUMNS = (
    "Saves (%)",
    "paper",
    "Goals (%)",
    "paper",
    "Saves/(Goals+Saves) (%)",
    "paper",
    "n",
    "setting",
    "vs paper",
)
"""The value columns of every results table, after the row's key columns."""


def paper_table(key_headers: Sequence[str], rows: Sequence[Row]) -> str:
    """A markdown table in the paper's layout: ours with 95% intervals, the paper's beside.

    Args:
        key_headers: Headers of the leading key columns (e.g. ``("Noise", "Behavior")``).
        rows: The rows; each has as many key cells as there are key headers.
    """
    headers = (*key_headers, *TABLE_COLUMNS)
    lines = ["| " + " | ".join(headers) + " |", "|" + "---|" * len(headers)]
    for row in rows:
        if len(row.keys) != len(key_headers):
            raise ValueError(f"row {row.keys} does not match headers {tuple(key_headers)}")
        lines.append("| " + " | ".join((*row.keys, *_value_cells(row))) + " |")
    return "\n".join(lines)


def _value_cells(row: Row) -> tuple[str, ...]:
    paper = row.paper
    ours: tuple[str, str, str, str]
    c = row.counts
    if c is None:
        ours = ("not run", "—", "—", "—")
    else:
        on_goal = percent_cell(c.saves, c.on_goal)
        ours = (
            percent_cell(c.saves, c.n),
            percent_cell(c.goals, c.n),
            f"{on_goal} of {c.on_goal}" if c.on_goal else on_goal,
            str(c.n),
        )
    setting, versus = "—", "—"
    if paper is not None:
        setting = row.setting
        if c is not None:
            versus = versus_cell(
                (
                    versus_paper(c.saves, c.n, paper.saves_pct),
                    versus_paper(c.goals, c.n, paper.goals_pct),
                    versus_paper(c.saves, c.on_goal, paper.on_goal_saved_pct),
                )
            )
    return (
        ours[0],
        paper_cell(paper.saves_pct if paper else None),
        ours[1],
        paper_cell(paper.goals_pct if paper else None),
        ours[2],
        paper_cell(paper.on_goal_saved_pct if paper else None),
        ours[3],
        setting,
        versus,
    )


def paired_difference(
    a: Sequence[TrialResult], b: Sequence[TrialResult], label: str = "SAVE"
) -> tuple[float, float, float, int] | None:
    """Mean difference in `label` share, in points, of two conditions on the same trials.

    The conditions share their seeds (trial i has the same placement), so the difference is
    taken trial by trial: its mean and a normal 95% interval of the mean.

    Returns:
        (difference, low, high, n) in percentage points, or None without common trials.
    """
    by_index = {r.index: r for r in b}
    pairs = [(r, by_index[r.index]) for r in a if r.index in by_index]
    n = len(pairs)
    if n < 2:
        return None
    diffs = [float(x.label == label) - float(y.label == label) for x, y in pairs]
    mean = statistics.fmean(diffs)
    half = Z_95 * statistics.stdev(diffs) / math.sqrt(n)
    return 100 * mean, 100 * (mean - half), 100 * (mean + half), n
