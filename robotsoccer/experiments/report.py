"""Layer-1 results as markdown tables in the paper's layout, ours beside the paper's (§5).

Each table has the paper's columns — Saves(%), Goals(%), Saves/(Goals+Saves)(%) — and for each
our percentage with its 95% Wilson interval (:func:`robotsoccer.stats.wilson_interval`) beside
the paper's number. Saves and goals are shares of all trials (n, misses included, as the paper's
tables count them: "the misses are not included in the results" means they appear in neither
column, not that n excludes them); Saves/(Goals+Saves) is a share of the shots on goal, so its
interval uses n = saves + goals, printed with it.

This module only renders: :mod:`robotsoccer.experiments.layer1` runs the trials and fills a
:class:`~robotsoccer.experiments.report_records.ModelSection` per field model. Every number it
prints comes from that section: this run's counts and per-trial measures, and the field's facts
(its configuration). The "Where we differ from the paper" section states, for every row with a
paper number, where the paper's value lies outside our interval, checks the paper's claims on
every field model, and gives the measurements behind each difference
(:func:`~robotsoccer.experiments.report_differences.why_lines`).

Every row with a paper number ends in two columns that state facts
(:func:`~robotsoccer.experiments.report_tables.setting_of`,
:func:`~robotsoccer.experiments.report_cells.versus_paper`):

* **setting**: the paper's own setting
  (:data:`~robotsoccer.experiments.report_records.PAPER_SETTING`), a setting of ours calibrated
  to a paper number (*calibrated* to what, :data:`~robotsoccer.experiments.paper.CALIBRATED`),
  or another field's own setting (:data:`~robotsoccer.experiments.report_records.OWN_SETTING`);
* **vs paper**: ``agrees`` when the paper's figure lies inside our 95% interval, otherwise
  ``above`` or ``below`` (our figure against the paper's) with the difference in points.

Rows without a paper number show a dash in both.

The report is built in layers, each importing only those below it:
:mod:`~robotsoccer.experiments.report_records` (the records),
:mod:`~robotsoccer.experiments.report_cells` (cells and paired statistics),
:mod:`~robotsoccer.experiments.report_tables` (the per-model tables),
:mod:`~robotsoccer.experiments.report_differences` ("Where we differ"), and this module, the
document (:func:`report_markdown`).
"""

from __future__ import annotations

from collections.abc import Sequence

from robotsoccer.experiments.report_differences import (
    claims,
    differences,
    net_lead_line,
    why_lines,
)
from robotsoccer.experiments.report_records import ModelSection
from robotsoccer.experiments.report_tables import model_markdown


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
