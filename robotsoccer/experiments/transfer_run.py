"""``robotsoccer transfer`` as a pipeline: the transfer study into its own run folder.

The CLI (:mod:`robotsoccer.cli.commands.transfer`) only reads its options into a
:class:`TransferRun` and prints what :func:`run_transfer` returns; the run folder, the context
and the report around the study
(:func:`robotsoccer.experiments.transfer_study.run_transfer_study`) are decided here.
"""

from __future__ import annotations

import time
from dataclasses import dataclass
from pathlib import Path

from robotsoccer.experiments import transfer_study
from robotsoccer.experiments.context import (
    Log,
    ReportOutcome,
    RunRequest,
    kept_on_interrupt,
)
from robotsoccer.experiments.transfer_study import TransferSetup
from robotsoccer.runs.runner import TrialSpec, check_spec


@dataclass(frozen=True)
class TransferRun(RunRequest):
    """What ``robotsoccer transfer`` runs, and where.

    Attributes:
        setup: The study's fields, randomisation, parts and lead drills.
        quick: The quick plans.
        out: The run folder; None: ``runs/transfer[-quick]-seed<S>``.

    The other run-folder settings are :class:`~robotsoccer.experiments.context.RunRequest`'s.
    """

    setup: TransferSetup

    @property
    def folder(self) -> Path:
        """The run folder: `out`, or one named after the plan and seed."""
        name = f"transfer-quick-seed{self.seed}" if self.quick else f"transfer-seed{self.seed}"
        return self.out or Path("runs") / name


def run_transfer(request: TransferRun, log: Log) -> ReportOutcome:
    """Check the two fields' presets, prepare the folder, run the study, write the report.

    A bad preset fails before the folder is touched. `log` gets the study's progress lines.

    Raises:
        ValueError: A bad preset, or a run folder in the way (one line each).
        RunInterrupted: Ctrl-C; the finished trials are kept (``resume`` finishes the run).
    """
    setup = request.setup
    for model, preset in (setup.reference, setup.target):  # one line here, not in a worker
        check_spec(TrialSpec(drill="intercept", field_model=model, preset=preset))
    out = request.folder
    workers = request.prepared(out)
    ctx = request.context(out, workers, log, "robotsoccer transfer")
    start = time.perf_counter()
    with kept_on_interrupt(out):
        section = transfer_study.run_transfer_study(setup, request.quick, ctx)
    report = out / "report.md"
    title = "# The transfer study" + (" — quick plan" if request.quick else "")
    report.write_text(f"{title}\n\n{section}")
    return ReportOutcome(report, time.perf_counter() - start, workers)
