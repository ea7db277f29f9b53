"""Layer-1 results as markdown tables in the paper's layout, ours beside the paper's (§5).

Each table has the paper's columns — Saves(%), Goals(%), Saves/(Goals+Saves)(%) — and for each
our percentage with its 95% Wilson interval (:func:`robotsoccer.stats.wilson_interval`) beside
the paper's number. Saves and goals are shares of all trials (n, misses included, as the paper's
tables count them: "the misses are not included in the results" means they appear in neither
column, not that n excludes them); Saves/(Goals+Saves) is a share of the shots on goal, so its
interval uses n = saves + goals, printed with it.

This module only renders: :mod:`robotsoccer.experiments.layer1` runs the trials and fills a
:class:`ModelSection` per field model. Every number it prints comes from that section: this
run's counts and per-trial measures, and the field's facts (its configuration). The "Where we
differ from the paper" section states, for every row with a paper number, where the paper's
value lies outside our interval, checks the paper's claims on every field model, and gives the
measurements behind each difference (:func:`why_lines`).

Every row with a paper number ends in two columns that state facts (:func:`setting_of`,
:func:`versus_paper`):

* **setting**: the paper's own setting (:data:`PAPER_SETTING`), a setting of ours calibrated to
  a paper number (*calibrated* to what, :data:`~robotsoccer.experiments.paper.CALIBRATED`), or
  another field's own setting (:data:`OWN_SETTING`);
* **vs paper**: ``agrees`` when the paper's figure lies inside our 95% interval, otherwise
  ``above`` or ``below`` (our figure against the paper's) with the difference in points.

Rows without a paper number show a dash in both.
"""

from __future__ import annotations

import math
import statistics
from collections import Counter
from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field

from field_models.arena import FieldFacts
from field_models.registry import PAPER_FIELD
from robotsoccer.drills.intercept_options import DEFAULT_SECTOR_DEG
from robotsoccer.experiments.paper import (
    AIM_4_DEG_WIDE,
    AIM_OFFSET_DEG,
    CALIBRATED,
    FIGURE_7,
    FIGURE_8,
    PAPER_ALL_SAVES,
    TABLE_1,
    TRAINING_FACTS,
    PaperRow,
)
from robotsoccer.runs.runner import TrialResult
from robotsoccer.stats import Z_95, wilson_interval

BEHAVIOUR_NAMES = {
    "net": "NN",
    "straight": "Straight",
    "lookup": "Lookup Table",
    "analytic": "Analytic",
    "random": "Random TA",
    "still": "Still",
}
"""How each defender behaviour is named in the tables (the paper's words)."""

NEAR_100_PCT = 95.0
""""Both near 100%" with no noise is read as: both save at least this share."""

NET_LEAD_POINTS = 20.0
"""The issue's claim: at ball noise .05 the net saves at least this many points more."""

PAPER_SETTING = "the paper's setting"
"""Setting cell of a row run as the paper ran it, on the paper's own field."""
OWN_SETTING = "our field's own setting"
"""Setting cell of a row on another field: the drill carried there, nothing tuned to the paper."""
SWEPT_SETTING = "our variant: swept collisions"
"""Setting cell of the pass-through check's swept rows (a diagnostic preset of ours)."""
AGREES = "agrees"
"""The vs-paper word when the paper's figure lies inside our 95% interval."""


@dataclass(frozen=True, slots=True)
class Counts:
    """How many trials of one condition ended in each label."""

    saves: int
    goals: int
    misses: int

    @property
    def n(self) -> int:
        """All trials."""
        return self.saves + self.goals + self.misses

    @property
    def on_goal(self) -> int:
        """Shots on goal: saves + goals."""
        return self.saves + self.goals

    @classmethod
    def from_labels(cls, labels: Iterable[str]) -> Counts:
        """Count SAVE/GOAL/MISS labels (anything else is an error)."""
        counts = Counter(labels)
        unknown = set(counts) - {"SAVE", "GOAL", "MISS"}
        if unknown:
            raise ValueError(f"unexpected labels {sorted(unknown)}")
        return cls(counts["SAVE"], counts["GOAL"], counts["MISS"])

    def saves_pct(self) -> float:
        """Saves as a percentage of all trials (0 when there are none)."""
        return 100.0 * self.saves / self.n if self.n else 0.0


@dataclass(frozen=True, slots=True)
class Row:
    """One table row: its key cells, our counts (None: not run), the paper's row, the setting.

    `setting` is the row's setting cell (:func:`setting_of`); it shows only where the row has a
    paper number.
    """

    keys: tuple[str, ...]
    counts: Counts | None
    paper: PaperRow | None = None
    setting: str = PAPER_SETTING


@dataclass(frozen=True, slots=True)
class StageTiming:
    """Wall time of one stage of the pipeline and the trials it ran (resumed ones excluded)."""

    name: str
    trials: int
    wall_s: float

    def rate(self) -> str:
        """Trials per second, or "—" when the stage ran no trials."""
        if self.trials == 0 or self.wall_s <= 0.0:
            return "—"
        return f"{self.trials / self.wall_s:,.0f}"


@dataclass
class ModelSection:
    """Everything the report shows for one field model.

    Attributes:
        field_model: The field model's registered name.
        preset: The preset name.
        figure7: (training examples, row label, counts) per trained net, ascending.
        figure8: (noise, behaviour) → counts.
        table1: behaviour → counts (ball noise .05).
        wide: behaviour → counts (no noise, the shooter aiming 4° wide).
        latency: (camera latency [s], behaviour) → counts (robots only).
        swept: (noise, behaviour) → counts on the swept-collision variant preset (Soccer Server).
        checks: behaviour → counts of the training-drill checks (still, straight, random).
        noise: The ball noise of Figure 7, Table 1 and the checks.
        noise_period_s: How often the ball noise acts in the drill on this field [s].
        net_examples: Training examples of the net used in Figure 8, Table 1, 4° wide, latency.
        stages: Timing of each stage.
        notes: Free markdown lines (scaling, presets, ...), printed under the model's heading.
        facts: The field's facts (its geometry and speeds, for the "why" lines).
        trials: behaviour → the per-trial results at the main noise (Table 1 and the checks),
            whose measures the "why" lines summarise.
        train_seconds: training examples → wall seconds its net took in this run.
    """

    field_model: str
    preset: str
    figure7: list[tuple[int, str, Counts]] = field(default_factory=list)
    figure8: dict[tuple[float, str], Counts] = field(default_factory=dict)
    table1: dict[str, Counts] = field(default_factory=dict)
    wide: dict[str, Counts] = field(default_factory=dict)
    latency: dict[tuple[float, str], Counts] = field(default_factory=dict)
    swept: dict[tuple[float, str], Counts] = field(default_factory=dict)
    checks: dict[str, Counts] = field(default_factory=dict)
    noise: float = 0.05
    noise_period_s: float = 0.0
    net_examples: int = 750
    stages: list[StageTiming] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)
    facts: FieldFacts | None = None
    trials: dict[str, Sequence[TrialResult]] = field(default_factory=dict)
    train_seconds: dict[int, float] = field(default_factory=dict)


# ----------------------------------------------------------------------------- cells and tables


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


# ----------------------------------------------------------------------------- per-model tables


def is_calibrated(section: ModelSection, behaviour: str, noise: float) -> bool:
    """Whether a row's setting was chosen to match the paper: on the paper's own field only.

    The blocking defender was chosen on the paper's field; elsewhere the same rows are
    consequences of that choice, not fits (a kickerless robot blocks anyway).
    """
    on_paper_field = (section.field_model, section.preset) == PAPER_FIELD
    return on_paper_field and (behaviour, round(noise, 4)) in CALIBRATED


def setting_of(section: ModelSection, behaviour: str = "", noise: float = math.nan) -> str:
    """A row's setting cell: calibrated to a paper number (and to which), the paper's, or ours.

    Args:
        section: The field model the row ran on.
        behaviour: The row's defender behaviour ("" for rows no setting was tuned for).
        noise: The row's ball noise.
    """
    if is_calibrated(section, behaviour, noise):
        return f"*calibrated* to {CALIBRATED[(behaviour, round(noise, 4))]}"
    return field_setting(section.field_model, section.preset)


def field_setting(field_model: str, preset: str) -> str:
    """The setting cell of an untuned row: the paper's on the paper's own field, else ours."""
    return PAPER_SETTING if (field_model, preset) == PAPER_FIELD else OWN_SETTING


def figure7_rows(section: ModelSection) -> list[Row]:
    """Figure 7 rows; the last (all saves) is set beside the paper's 4773-example row."""
    rows = []
    for examples, label, counts in section.figure7:
        paper = FIGURE_7.get(PAPER_ALL_SAVES if label.startswith("all") else examples)
        rows.append(Row((label,), counts, paper, setting_of(section)))
    return rows


def figure8_rows(section: ModelSection) -> list[Row]:
    """Figure 8 rows: per noise level the NN then Straight, the paper's beside."""
    noises = sorted({noise for noise, _ in section.figure8})
    rows = []
    for noise in noises:
        for behaviour in ("net", "straight"):
            counts = section.figure8.get((noise, behaviour))
            if counts is None:
                continue
            label = f"{noise:g}"
            paper = FIGURE_8.get((round(noise, 4), behaviour))
            setting = setting_of(section, behaviour, noise)
            rows.append(Row((label, BEHAVIOUR_NAMES[behaviour]), counts, paper, setting))
    return rows


def swept_rows(section: ModelSection) -> list[Row]:
    """Pass-through check rows: our default-preset result, then the swept one, paper beside."""
    rows = []
    for noise in sorted({noise for noise, _ in section.swept}):
        for behaviour in ("net", "straight"):
            paper = FIGURE_8.get((round(noise, 4), behaviour))
            name = BEHAVIOUR_NAMES[behaviour]
            plain = section.figure8.get((noise, behaviour))
            if plain is not None:
                keys = (f"{noise:g}", name, "end of cycle (server)")
                rows.append(Row(keys, plain, paper, setting_of(section, behaviour, noise)))
            swept = section.swept.get((noise, behaviour))
            if swept is not None:
                # The variant preset is ours: a diagnostic, not the paper's server.
                rows.append(Row((f"{noise:g}", name, "swept"), swept, paper, SWEPT_SETTING))
    return rows


def table1_rows(section: ModelSection) -> list[Row]:
    """Table 1 rows (NN, lookup table, analytic, plus straight for reference)."""
    order = ("net", "lookup", "analytic", "straight")
    paper = {**TABLE_1, "straight": FIGURE_8[(0.05, "straight")]}
    return [
        Row(
            (BEHAVIOUR_NAMES[b],),
            section.table1[b],
            paper.get(b),
            setting_of(section, b, section.noise),
        )
        for b in order
        if b in section.table1
    ]


def wide_rows(section: ModelSection) -> list[Row]:
    """The 4°-wide rows (no noise): NN and Straight."""
    return [
        Row((BEHAVIOUR_NAMES[b],), section.wide[b], AIM_4_DEG_WIDE.get(b), setting_of(section))
        for b in ("net", "straight")
        if b in section.wide
    ]


def latency_rows(section: ModelSection) -> list[Row]:
    """Camera-latency rows (robots; the paper has no such experiment)."""
    rows = []
    for latency_s in sorted({lat for lat, _ in section.latency}):
        for behaviour in ("net", "straight", "analytic"):
            counts = section.latency.get((latency_s, behaviour))
            if counts is not None:
                rows.append(Row((f"{1000 * latency_s:.0f}", BEHAVIOUR_NAMES[behaviour]), counts))
    return rows


def checks_table(section: ModelSection) -> str:
    """The training drill's sanity numbers beside the paper's text (§5)."""
    lines = [
        "| Behavior | what | ours | paper | n | setting | vs paper |",
        "|---|---|---|---|---|---|---|",
    ]
    for behaviour, (what, paper) in TRAINING_FACTS.items():
        counts = section.checks.get(behaviour)
        if counts is None:
            continue
        k = check_count(behaviour, counts)
        setting = setting_of(section, behaviour, section.noise)
        lines.append(
            f"| {BEHAVIOUR_NAMES[behaviour]} | {what} | {percent_cell(k, counts.n)} "
            f"| {paper:g} | {counts.n} | {setting} | {versus_paper(k, counts.n, paper)} |"
        )
    return "\n".join(lines)


def stages_table(stages: Sequence[StageTiming]) -> str:
    """Wall time and trials per second of each stage."""
    lines = ["| stage | trials run | wall (s) | trials/s |", "|---|---|---|---|"]
    for s in stages:
        lines.append(f"| {s.name} | {s.trials} | {s.wall_s:.1f} | {s.rate()} |")
    return "\n".join(lines)


def model_markdown(section: ModelSection) -> str:
    """The section of the report for one field model: every table that was run."""
    out = [f"## {section.field_model} (`{section.preset}`)", ""]
    out += [*section.notes, ""] if section.notes else []
    if section.figure7:
        out += [
            f"### Figure 7 — nets trained on different numbers of saves (noise {section.noise:g})",
            "",
            paper_table(("Training examples",), figure7_rows(section)),
            "",
        ]
    if section.figure8:
        out += [
            f"### Figure 8 — ball noise, NN ({section.net_examples} examples) vs straight",
            "",
            paper_table(("Noise", "Behavior"), figure8_rows(section)),
            "",
        ]
    if section.table1:
        out += [
            f"### Table 1 — NN, lookup table, analytic (noise {section.noise:g})",
            "",
            paper_table(("Defender Behavior",), table1_rows(section)),
            "",
        ]
    if section.wide:
        out += [
            f"### The shooter aiming {AIM_OFFSET_DEG:g}° wide, no noise",
            "",
            paper_table(("Defender Behavior",), wide_rows(section)),
            "",
        ]
    if section.latency:
        out += [
            f"### Camera latency (noise {section.noise:g}; no paper numbers)",
            "",
            paper_table(("Latency (ms)", "Behavior"), latency_rows(section)),
            "",
        ]
    if section.swept:
        out += [
            "### Pass-through check: ball–player collisions checked at cycle ends or swept",
            "",
            "The real server checks overlaps only at the end of a cycle, so a ball may pass "
            "*through* a defender dashing at it (spec §4). The `_swept` variant preset also "
            "catches a ball that met the player mid-cycle. Same seeds and placements as Figure "
            '8; the sizes and speeds involved are under "Where we differ".',
            "",
            paper_table(("Noise", "Behavior", "collisions"), swept_rows(section)),
            "",
        ]
    if section.checks:
        out += ["### Training-drill checks (§5 text)", "", checks_table(section), ""]
    if section.stages:
        out += ["### Stages: wall time and speed", "", stages_table(section.stages), ""]
    return "\n".join(out)


# ----------------------------------------------------------------------------- differences


def differences(section: ModelSection) -> list[str]:
    """Facts, one markdown bullet per row: each paper number outside our 95% interval.

    "Outside" is judged at the printed precision (0.1 points), so a paper 0% beside our
    0.0 [0.0, 1.9] is inside.
    """
    facts: list[str] = []
    tables = (
        ("Figure 7", figure7_rows(section)),
        ("Figure 8", figure8_rows(section)),
        ("Table 1", table1_rows(section)),
        (f"{AIM_OFFSET_DEG:g}° wide", wide_rows(section)),
    )
    for title, rows in tables:
        for row in rows:
            if row.counts is None or row.paper is None:
                continue
            c, p = row.counts, row.paper
            parts = [
                _outside("saves", c.saves, c.n, p.saves_pct),
                _outside("goals", c.goals, c.n, p.goals_pct),
                _outside("saves/(goals+saves)", c.saves, c.on_goal, p.on_goal_saved_pct),
            ]
            found = [part for part in parts if part]
            if found:
                facts.append(f"- {title}, {' / '.join(row.keys)}: " + "; ".join(found) + ".")
    for behaviour, (what, paper) in TRAINING_FACTS.items():
        counts = section.checks.get(behaviour)
        if counts is not None:
            found_check = _outside(what, check_count(behaviour, counts), counts.n, paper)
            if found_check:
                facts.append(f"- Training drill, {BEHAVIOUR_NAMES[behaviour]}: {found_check}.")
    return facts


def check_count(behaviour: str, counts: Counts) -> int:
    """The count a training-drill check compares with the paper's text (§5).

    "If the defender remains still, the ball hits it only 35% of the time": a hit ball comes
    back, so the still defender's *saves*. The straight defender's "stop the ball 53%": saves.
    The random defender "misses most (76%) of the time": it fails to stop the ball, so every
    trial that is not a save (goals and misses).
    """
    return counts.n - counts.saves if behaviour == "random" else counts.saves


def _outside(what: str, k: int, n: int, paper: float | None) -> str:
    """``"goals 48.5 [41.7, 55.4] vs the paper's 35 (above)"``, or "" when inside or unknown."""
    verdict = versus_paper(k, n, paper)
    if verdict in (AGREES, "—"):
        return ""
    side = verdict.split(" ", 1)[0]
    return f"{what} {percent_cell(k, n)} (n={n}) {side} the paper's {paper:g}"


def claims(section: ModelSection) -> list[str]:
    """The issue's must-show claims, each stated with the numbers and PASS or FAIL."""
    lines = []
    net = section.figure8.get((0.05, "net"))
    straight = section.figure8.get((0.05, "straight"))
    if net and straight:
        lead = net.saves_pct() - straight.saves_pct()
        verdict = "PASS" if lead >= NET_LEAD_POINTS else "FAIL"
        lines.append(
            f"- {verdict}: noise .05, the net saves {lead:+.1f} points vs straight "
            f"({net.saves_pct():.1f}% vs {straight.saves_pct():.1f}%; claim ≥ "
            f"{NET_LEAD_POINTS:g}; paper 86% vs 53%)."
        )
    behind = [
        (noise, section.figure8[(noise, "net")], section.figure8[(noise, "straight")])
        for noise, b in sorted(section.figure8)
        if b == "net" and noise > 0 and (noise, "straight") in section.figure8
    ]
    if behind:
        worse = [f"{noise:g}" for noise, n, s in behind if n.saves < s.saves]
        verdict = "PASS" if not worse else "FAIL"
        detail = "every level" if not worse else "not at " + ", ".join(worse)
        lines.append(f"- {verdict}: net ≥ straight at every noise level above 0 ({detail}).")
    zero = [section.figure8.get((0.0, b)) for b in ("net", "straight")]
    if all(zero):
        shares = [c.saves_pct() for c in zero if c is not None]
        verdict = "PASS" if min(shares) >= NEAR_100_PCT else "FAIL"
        lines.append(
            f"- {verdict}: no noise, both near 100% (net {shares[0]:.1f}%, straight "
            f"{shares[1]:.1f}%; read as ≥ {NEAR_100_PCT:g}%)."
        )
    return lines


def why_lines(section: ModelSection) -> list[str]:
    """The measurements behind this field's differences from the paper, one bullet each.

    Every number is this run's: counts, per-trial measures of the drill (the defender's travel
    from the trigger to the verdict) and the field's facts (its configuration).
    """
    lines = [line for line in (_lead_line(section), _travel_line(section)) if line]
    lines += _target_lines(section)
    lines += _swept_lines(section)
    lines += _sector_lines(section)
    lines += _figure7_lines(section)
    return lines


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


def _lead_line(section: ModelSection) -> str:
    net, straight = section.trials.get("net"), section.trials.get("straight")
    if not net or not straight:
        return ""
    found = paired_difference(net, straight)
    if found is None:
        return ""
    diff, low, high, n = found
    verdict = (
        "the interval includes 0: no gain measured" if low <= 0.0 <= high else
        "a gain" if low > 0.0 else "a loss"
    )  # fmt: skip
    return (
        f"- **Net vs straight** at noise {section.noise:g}, trial by trial on the same "
        f"placements: {diff:+.1f} points [{low:+.1f}, {high:+.1f}] (n = {n}): {verdict}."
    )


def _travel_line(section: ModelSection) -> str:
    parts = []
    for behaviour in ("straight", "net"):
        results = [r for r in section.trials.get(behaviour, ()) if r.measures]
        travel = [r.measure("defender_travel_units") for r in results]
        updates = [r.measure("updates_after_trigger") for r in results]
        if len(travel) < 4:
            continue
        q1, med, q3 = statistics.quantiles(travel, n=4)
        parts.append(
            f"{BEHAVIOUR_NAMES[behaviour]} {med:.2f} units (quartiles {q1:.2f}–{q3:.2f}) in a "
            f"median of {statistics.median(updates):.1f} sensor updates (n = {len(travel)})"
        )
    if not parts:
        return ""
    return (
        "- **How far the defender gets.** From its trigger (the first BD within the plan's "
        "trigger distance) to the verdict, "
        "the defender moved a median of " + "; ".join(parts) + "."
    )


def _target_lines(section: ModelSection) -> list[str]:
    facts = section.facts
    if facts is None:
        return []
    size = facts.touch_distance_m / facts.unit_m
    still = section.checks.get("still")
    hit = ""
    if still is not None:
        hit = f"; a still defender is hit in {percent_cell(still.saves, still.n)} % of trials"
    top = facts.player_top_speed_mps / facts.unit_m
    return [
        f"- **Target and speed.** Body radius plus ball radius is {size:.2f} units on this "
        f"field{hit} (paper: 35%). A player's top speed is {top:.1f} units/s "
        f"({facts.player_top_speed_mps:.3g} m/s)."
    ]


def _swept_lines(section: ModelSection) -> list[str]:
    shown = [
        f"{BEHAVIOUR_NAMES[b]} {plain.saves_pct():.1f}% → {swept.saves_pct():.1f}%"
        for b in ("net", "straight")
        if (plain := section.figure8.get((0.0, b))) and (swept := section.swept.get((0.0, b)))
    ]
    if not shown:
        return []
    facts = section.facts
    geometry = ""
    if facts is not None:
        diameter = 2.0 * facts.touch_distance_m
        step = facts.player_top_speed_mps * facts.dt_s
        geometry = (
            f" The ball–player collision diameter is {diameter:.2f} m, and a player at top "
            f"speed alone moves {step:.2f} m per tick, so the two can close by more than the "
            "diameter between two end-of-tick checks."
        )
    return [
        "- **Pass-through at no noise.** Checking overlaps only at the end of each tick (the "
        "real server's rule) against swept collisions, same placements: "
        + ", ".join(shown)
        + "."
        + geometry
    ]


def _sector_lines(section: ModelSection) -> list[str]:
    straight = section.figure8.get((round(section.noise, 4), "straight"))
    paper = FIGURE_8.get((round(section.noise, 4), "straight"))
    if straight is None or paper is None or paper.goals_pct is None:
        return []
    return [
        f"- **Placement sector ±{DEFAULT_SECTOR_DEG:g}° (calibrated: the paper gives none).** "
        "It sets how many shots head wide: straight at noise "
        f"{section.noise:g} gives goals {percent_cell(straight.goals, straight.n)} % and misses "
        f"{percent_cell(straight.misses, straight.n)} % (paper: goals {paper.goals_pct:g} %)."
    ]


def _figure7_lines(section: ModelSection) -> list[str]:
    if not section.figure7:
        return []
    examples, label, counts = section.figure7[0]
    paper = FIGURE_7.get(examples)
    if paper is None:
        return []
    return [
        f"- **Figure 7's low end.** The net trained on {label} saves stops "
        f"{counts.saves_pct():.1f}% of the shots (paper: {paper.saves_pct:g}%); its training "
        "differs from the paper's (standardised inputs and the optimizer under Training)."
    ]


def net_lead_line(section: ModelSection) -> str:
    """The net's saves minus straight's, in points, at each noise level, the paper's beside."""
    leads = []
    for (noise, behaviour), net in sorted(section.figure8.items()):
        straight = section.figure8.get((noise, "straight"))
        if behaviour != "net" or straight is None:
            continue
        ours = net.saves_pct() - straight.saves_pct()
        paper_net, paper_straight = (FIGURE_8.get((noise, b)) for b in ("net", "straight"))
        theirs = ""
        if paper_net and paper_straight:
            theirs = f" (paper {paper_net.saves_pct - paper_straight.saves_pct:+g})"
        leads.append(f"{noise:g}: {ours:+.1f}{theirs}")
    if not leads:
        return ""
    return "Net minus straight, saves in points, by ball noise: " + ", ".join(leads) + "."


# ----------------------------------------------------------------------------- the document


def report_markdown(
    title: str,
    intro: Sequence[str],
    sections: Sequence[ModelSection],
    plots: Sequence[tuple[str, str]] = (),
) -> str:
    """The whole report: title, intro lines, plots, one section per model, the differences.

    Args:
        title: The report's title.
        intro: Markdown lines under the title.
        sections: One per field model.
        plots: (caption, path relative to the report) of each image.
    """
    out = [f"# {title}", "", *intro, ""]
    if plots:
        out += ["## Plots", ""]
        for caption, path in plots:
            out += [f"![{caption}]({path})", ""]
    for section in sections:
        out += [model_markdown(section), ""]
    out += ["## Where we differ from the paper", ""]
    out += [
        "Generated from this run's numbers: each line is a paper value outside our 95% "
        "interval; the measurements behind the differences follow each list.",
        "",
    ]
    for section in sections:
        facts = differences(section)
        checks = claims(section)
        out += [f"### {section.field_model}", ""]
        if checks:
            out += [f"The paper's claims, checked on `{section.preset}`:", "", *checks, ""]
        lead = net_lead_line(section)
        out += [lead, ""] if lead else []
        out += ["Paper numbers outside our 95% intervals:", ""]
        out += facts or ["- None: every paper number lies inside our 95% interval."]
        out += [""]
        why = why_lines(section)
        if why:
            out += ["Measurements behind the differences (this run):", "", *why, ""]
    return "\n".join(out).rstrip() + "\n"
