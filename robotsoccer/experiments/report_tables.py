"""Per-model tables of the layer-1 report: Figure 7, Figure 8, Table 1, 4° wide, latency (§5).

Each function turns a :class:`~robotsoccer.experiments.report_records.ModelSection` into the
rows of one of the paper's tables, each row's setting cell stated (:func:`setting_of`);
:func:`model_markdown` puts together one field model's section of the report.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

from field_models.registry import PAPER_FIELD
from robotsoccer.experiments.paper import (
    AIM_4_DEG_WIDE,
    AIM_OFFSET_DEG,
    CALIBRATED,
    FIGURE_7,
    FIGURE_8,
    PAPER_ALL_SAVES,
    TABLE_1,
    TRAINING_FACTS,
)
from robotsoccer.experiments.report_cells import paper_table, percent_cell, versus_paper
from robotsoccer.experiments.report_records import (
    BEHAVIOUR_NAMES,
    OWN_SETTING,
    PAPER_SETTING,
    SWEPT_SETTING,
    Counts,
    ModelSection,
    Row,
    StageTiming,
)


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


def check_count(behaviour: str, counts: Counts) -> int:
    """The count a training-drill check compares with the paper's text (§5).

    "If the defender remains still, the ball hits it only 35% of the time": a hit ball comes
    back, so the still defender's *saves*. The straight defender's "stop the ball 53%": saves.
    The random defender "misses most (76%) of the time": it fails to stop the ball, so every
    trial that is not a save (goals and misses).
    """
    return counts.n - counts.saves if behaviour == "random" else counts.saves
