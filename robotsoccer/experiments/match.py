"""A series of matches, layered team against the baseline, with the figures a reader wants.

Half the games have the layered team on the left, half on the right (the same trial seeds on
both sides, so each pair of games differs in who plays where, not in the draws). Each game is a
trial of the ``match`` drill (:mod:`robotsoccer.drills.match`) through the usual pool, streamed
to ``<out>/<side>/results.csv``, so an interrupted series keeps the games it finished and
``resume`` plays only the rest.

The summary is from the layered team's side: wins, draws and losses with 95% Wilson intervals;
the mean goal difference with a 95% interval (normal approximation: mean ± 1.96·sd/√n); and per
team the mean goals, possession share, passes completed and shots, each with its interval.
"""

from __future__ import annotations

import math
import statistics
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path

from robotsoccer.runs.pool import run_trials
from robotsoccer.runs.runner import TrialResult, TrialSpec
from robotsoccer.stats import wilson_interval

Z_95 = 1.959963984540054
SIDES = ("layered_left", "layered_right")
"""Sub-folders of a series: the layered team on the left, then on the right."""
TEAM_FIGURES = ("goals", "possession", "passes", "shots")
"""Per-team figures of the summary, as the match drill measures them."""


@dataclass(frozen=True, slots=True)
class Game:
    """One game from the layered team's side.

    Attributes:
        layered_left: The layered team played on the left.
        result: ``W``, ``D`` or ``L`` for the layered team.
        layered: The layered team's figures (:data:`TEAM_FIGURES`).
        baseline: The baseline team's.
    """

    layered_left: bool
    result: str
    layered: dict[str, float]
    baseline: dict[str, float]

    @property
    def goal_difference(self) -> float:
        """Layered goals minus baseline goals."""
        return self.layered["goals"] - self.baseline["goals"]


def game_from(result: TrialResult, layered_left: bool) -> Game:
    """A match trial's result, from the layered team's side."""
    mine, theirs = ("l", "r") if layered_left else ("r", "l")
    layered = {k: result.measure(f"{k}_{mine}") for k in TEAM_FIGURES}
    baseline = {k: result.measure(f"{k}_{theirs}") for k in TEAM_FIGURES}
    won = "LEFT_WIN" if layered_left else "RIGHT_WIN"
    outcome = "W" if result.label == won else "D" if result.label == "DRAW" else "L"
    return Game(layered_left, outcome, layered, baseline)


def series_specs(
    base: TrialSpec, teams: tuple[str, str] = ("layered", "baseline")
) -> tuple[TrialSpec, TrialSpec]:
    """The two specs of a series: layered on the left, then on the right (same seed).

    `teams` names the two kinds (the first plays the "layered" part of a :class:`Game`).
    """
    first, second = teams
    return (
        base.with_options(left=first, right=second),
        base.with_options(left=second, right=first),
    )


def run_series(
    base: TrialSpec,
    games: int,
    out: Path,
    *,
    workers: int | None,
    resume: bool = False,
    progress: bool = True,
    teams: tuple[str, str] = ("layered", "baseline"),
) -> list[Game]:
    """Play `games` matches (half with the layered team on each side) into `out`.

    `base` is a ``match`` spec with the layered team's files (options ``net``, ``tree``); the
    sides are set here. The first side gets the odd game when `games` is odd. `teams`: the two
    kinds that meet (:func:`series_specs`).
    """
    if games < 1:
        raise ValueError(f"games must be >= 1, got {games}")
    counts = ((games + 1) // 2, games // 2)
    played: list[Game] = []
    for side, spec, n in zip(SIDES, series_specs(base, teams), counts, strict=True):
        if n == 0:
            continue
        folder = out / side
        folder.mkdir(parents=True, exist_ok=True)
        results = run_trials(
            spec,
            n,
            workers=workers,
            results_path=folder / "results.csv",
            resume=resume,
            progress=progress,
        )
        played += [game_from(r, side == SIDES[0]) for r in results]
    return played


@dataclass(frozen=True, slots=True)
class Interval:
    """A mean (or share) with its 95% interval."""

    value: float
    low: float
    high: float

    def text(self, digits: int = 2, percent: bool = False) -> str:
        """``v [lo, hi]``, in percent when asked."""
        scale = 100.0 if percent else 1.0
        v, lo, hi = (scale * x for x in (self.value, self.low, self.high))
        return f"{v:.{digits}f} [{lo:.{digits}f}, {hi:.{digits}f}]"


def mean_interval(values: Sequence[float]) -> Interval:
    """The mean with a 95% normal interval (one value: no spread, a zero-width interval)."""
    n = len(values)
    if n == 0:
        return Interval(math.nan, math.nan, math.nan)
    mean = statistics.fmean(values)
    half = Z_95 * statistics.stdev(values) / math.sqrt(n) if n > 1 else 0.0
    return Interval(mean, mean - half, mean + half)


def share_interval(successes: int, n: int) -> Interval:
    """A share with its 95% Wilson interval."""
    low, high = wilson_interval(successes, n)
    return Interval(successes / n if n else math.nan, low, high)


def summary_lines(
    games: Sequence[Game], title: str, names: tuple[str, str] = ("layered", "baseline")
) -> list[str]:
    """The series' report in markdown: results, goal difference, per-team figures.

    `names`: what the report calls the two teams (the games' "layered" and "baseline" parts).
    """
    n = len(games)
    first, second = names
    lines = [f"# {title}", "", f"{n} games; the {first} team's results, 95% intervals.", ""]
    lines += ["| result | games | share |", "|---|---|---|"]
    for key, name in (("W", "wins"), ("D", "draws"), ("L", "losses")):
        k = sum(g.result == key for g in games)
        lines.append(f"| {name} | {k} | {share_interval(k, n).text(1, percent=True)} % |")
    diff = mean_interval([g.goal_difference for g in games])
    lines += ["", f"Mean goal difference ({first} − {second}): {diff.text()} per game.", ""]
    lines += [f"| per game | {first} | {second} |", "|---|---|---|"]
    for figure in TEAM_FIGURES:
        percent = figure == "possession"
        cells = [
            mean_interval([getattr(g, team)[figure] for g in games]).text(
                1 if percent else 2, percent=percent
            )
            for team in ("layered", "baseline")
        ]
        unit = " (%)" if percent else ""
        lines.append(f"| {figure}{unit} | {cells[0]} | {cells[1]} |")
    by_side = {side: [g for g in games if g.layered_left == (side == SIDES[0])] for side in SIDES}
    lines += ["", f"| {first} team on | games | W-D-L | goal difference |", "|---|---|---|---|"]
    for side, subset in by_side.items():
        if not subset:
            continue
        wdl = "-".join(str(sum(g.result == k for g in subset)) for k in "WDL")
        diff_side = mean_interval([g.goal_difference for g in subset]).text()
        lines.append(f"| {side.split('_')[1]} | {len(subset)} | {wdl} | {diff_side} |")
    return lines


def write_report(
    games: Sequence[Game],
    out: Path,
    title: str,
    log: Callable[[str], None],
    names: tuple[str, str] = ("layered", "baseline"),
) -> Path:
    """Write ``<out>/report.md`` and echo it through `log`."""
    lines = summary_lines(games, title, names)
    path = out / "report.md"
    path.write_text("\n".join(lines) + "\n")
    for line in lines:
        log(line)
    return path
