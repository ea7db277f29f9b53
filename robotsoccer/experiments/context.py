"""What every experiment step passes on: the run folder, seeds, workers, log and progress.

Layer 1, layer 2, the transfer study, gap closing, the lead study and the set play all run as
steps (collect, train, evaluate, report) inside one run folder, with one pair of experiment
seeds, one worker count, one log and one progress setting. :class:`RunContext` carries those
together, so a step's signature names only what is its own (the field, the plan, its inputs).

Where trials run (a process pool or Ray) is not in the context: the CLI chooses it once per
command with :func:`robotsoccer.runs.pool.using_backend`, and every run of that command uses
it. Results do not depend on it, nor on the worker count.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from robotsoccer.runs.folders import prepare_run_folder
from robotsoccer.runs.pool import default_workers

Log = Callable[[str], None]
"""Where progress lines go (the CLI prints them)."""

Field = tuple[str, str]
"""A field model and its preset."""


@dataclass(frozen=True)
class Seeds:
    """The experiment seeds of one run: evaluation (shared by all conditions) and collection."""

    evaluation: int
    collection: int


def seeds_for(seed: int) -> Seeds:
    """Evaluation uses `seed`; collection a 32-bit seed derived from it, never `seed` itself.

    The derived seed is the first word of ``SeedSequence([seed, 1])`` that differs from `seed`,
    so a run's nets are never tested on the placements they were trained on.
    """
    words = np.random.SeedSequence([seed, 1]).generate_state(2).tolist()
    derived = next(int(w) for w in words if w != seed)
    return Seeds(evaluation=seed, collection=derived)


@dataclass(frozen=True, kw_only=True)
class RunRequest:
    """The run-folder settings every command pipeline's request shares (given by keyword).

    Attributes:
        quick: The quick plan(s).
        seed: The experiment seed.
        out: The run folder; None: one the request names after itself (its ``folder``).
        resume: Continue the run in `out`.
        overwrite: Replace the run in `out`.
        workers: Processes (None: all cores).
        progress: Show a progress bar for each batch of trials.
    """

    quick: bool = False
    seed: int = 0
    out: Path | None = None
    resume: bool = False
    overwrite: bool = False
    workers: int | None = None
    progress: bool = False

    def prepared(self, out: Path) -> int:
        """Make `out` ready by the request's ``resume``/``overwrite``; the worker count to use.

        Raises:
            ValueError: A run folder in the way (:func:`~robotsoccer.runs.folders.
                prepare_run_folder`, one line).
        """
        prepare_run_folder(out, resume=self.resume, overwrite=self.overwrite)
        return self.workers or default_workers()

    def context(
        self, out: Path, workers: int, log: Log, created_by: str = "robotsoccer reproduce"
    ) -> RunContext:
        """The run's context: `out`, the request's seed and progress, `workers`, `log`."""
        return RunContext.for_seed(
            out, self.seed, workers, log, progress=self.progress, created_by=created_by
        )


class RunInterrupted(Exception):
    """Ctrl-C stopped a run; what it finished is kept, and the message (one line) says where.

    A pipeline raises it in place of the KeyboardInterrupt; the CLI prints the message and
    exits with its interrupt status.
    """


@contextmanager
def kept_on_interrupt(out: Path, kept: str = "trials") -> Iterator[None]:
    """Turn Ctrl-C inside the block into :class:`RunInterrupted` saying what `out` keeps.

    `kept` names what a rerun with ``--resume`` need not redo (trials, games).
    """
    try:
        yield
    except KeyboardInterrupt:
        raise RunInterrupted(
            f"interrupted; finished {kept} are kept under {out} (--resume finishes the run)"
        ) from None


@dataclass(frozen=True)
class ReportOutcome:
    """What a command's study left: its report, how long it took and with how many processes.

    Attributes:
        report: Its ``report.md``.
        wall_s: Wall time of the study [s].
        workers: The processes it ran with.
    """

    report: Path
    wall_s: float
    workers: int

    @property
    def lines(self) -> tuple[str, ...]:
        """What the command prints: a blank line, the report, where it is and how long it took."""
        return (
            "",
            self.report.read_text(),
            f"report: {self.report}  ({self.wall_s:.0f} s with {self.workers} worker(s))",
        )


def _quiet(line: str) -> None:
    """A log that drops every line."""


@dataclass(frozen=True)
class RunContext:
    """The run folder and settings shared by every step of one experiment.

    Attributes:
        out: The run folder (datasets, models, results, recordings, plots and the report go
            under it).
        seeds: The experiment seeds (:func:`seeds_for`).
        workers: Processes for the trials (None: all cores; 1: in this process).
        log: Where progress lines go.
        progress: Show a progress bar or lines for each batch of trials.
        created_by: The command named in the provenance of the files the run writes.
    """

    out: Path
    seeds: Seeds
    workers: int | None = None
    log: Log = _quiet
    progress: bool = False
    created_by: str = "robotsoccer reproduce"

    @classmethod
    def for_seed(
        cls,
        out: Path,
        seed: int,
        workers: int | None = None,
        log: Log = _quiet,
        *,
        progress: bool = False,
        created_by: str = "robotsoccer reproduce",
    ) -> RunContext:
        """The context of a run from one experiment seed (both seeds follow from it)."""
        return cls(out, seeds_for(seed), workers, log, progress, created_by)

    def made_by(self, created_by: str) -> RunContext:
        """The same context, naming another command in the files' provenance."""
        return dataclasses.replace(self, created_by=created_by)

    def at(self, out: Path) -> RunContext:
        """The same context writing into another folder (a study's own part of a run)."""
        return dataclasses.replace(self, out=out)

    def results_dir(self, field_model: str) -> Path:
        """Where a field model's result tables go."""
        return self.out / "results" / field_model

    def models_dir(self, field_model: str) -> Path:
        """Where a field model's trained models go."""
        return self.out / "models" / field_model
