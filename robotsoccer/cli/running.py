"""What every command does around its work.

One-line failures, a pipeline's outcome shown, the spec a command's options describe, a demo's
tally, a clock for the log.
"""

from __future__ import annotations

import argparse
import contextlib
import os
import sys
import time
from collections import Counter
from collections.abc import Callable, Sequence
from typing import Any, Protocol

from field_models.arena import FieldOptions
from robotsoccer.cli.options import EXIT_INTERRUPTED
from robotsoccer.runs.runner import TrialResult, TrialSpec

# check_spec lives beside build_trial (the pipelines in robotsoccer.experiments use it too);
# re-exported here, where the commands have always found it.
from robotsoccer.runs.runner import check_spec as check_spec
from robotsoccer.stats import wilson_interval


def fail(status: int, message: str) -> int:
    """Print `message` as one line on stderr (its first line) and return the exit status."""
    first = message.strip().splitlines()[0] if message.strip() else "failed"
    with contextlib.suppress(BrokenPipeError):  # stderr closed too: nothing left to tell
        print(f"robotsoccer: error: {first}", file=sys.stderr)
    return status


class Shown(Protocol):
    """A pipeline's outcome as the command prints it."""

    @property
    def lines(self) -> tuple[str, ...]:
        """The lines to print, in order."""


def run_settings(args: argparse.Namespace, *, progress: bool | None = None) -> dict[str, Any]:
    """A command's run-folder options as its request's fields.

    They are :class:`~robotsoccer.experiments.context.RunRequest`'s; the progress bar shows
    where stderr is a terminal unless `progress` says otherwise.
    """
    return {
        "quick": args.quick,
        "seed": args.seed,
        "out": args.out,
        "resume": args.resume,
        "overwrite": args.overwrite,
        "workers": args.workers,
        "progress": sys.stderr.isatty() if progress is None else progress,
    }


def show(run: Callable[[], Shown]) -> int:
    """Run a pipeline and print its outcome's lines (exit 0), or its interrupt's one line.

    A pipeline raises :class:`~robotsoccer.experiments.context.RunInterrupted` on Ctrl-C with
    what it kept; that is the one line, with the interrupt's exit status.
    """
    from robotsoccer.experiments.context import RunInterrupted

    try:
        outcome = run()
    except RunInterrupted as stop:
        return fail(EXIT_INTERRUPTED, str(stop))
    for line in outcome.lines:
        print(line)
    return 0


def silence_stdout() -> None:
    """After the reader closed the pipe, send what is left to /dev/null (no second error)."""
    devnull = os.open(os.devnull, os.O_WRONLY)
    os.dup2(devnull, sys.stdout.fileno())


def spec_from(args: argparse.Namespace, **extra: Any) -> TrialSpec:
    """The TrialSpec a command's field and drill options describe."""
    field = FieldOptions(perfect_perception=args.perfect_perception, ball_noise=args.ball_noise)
    spec = TrialSpec(
        drill=args.drill,
        field_model=args.field,
        preset=args.field_preset,
        seed=args.seed,
        field=field,
        **extra,
    )
    return spec.with_options(**dict(args.option))


class Tally:
    """Counts of a run's labels and its simulated time, built as results arrive."""

    def __init__(self) -> None:
        self.labels: Counter[str] = Counter()
        self.n = 0
        self.simulated_s = 0.0

    def add(self, result: TrialResult) -> None:
        """Count one result."""
        self.labels[result.label] += 1
        self.n += 1
        self.simulated_s += result.time_s

    def table(self, labels: Sequence[str], title: str) -> str:
        """A plain-text table: each label's count, share and 95% Wilson interval."""
        n = self.n
        lines = [title, f"{'label':<8}{'count':>7}{'share':>9}   95% interval"]
        for label in list(labels) + sorted(set(self.labels) - set(labels)):
            k = self.labels.get(label, 0)
            low, high = wilson_interval(k, n)
            share = 100.0 * k / n if n else 0.0
            lines.append(f"{label:<8}{k:>7}{share:>8.1f}%   [{100 * low:.1f}, {100 * high:.1f}]")
        return "\n".join(lines)


def clock_log() -> Callable[[str], None]:
    """A log that prefixes each line with the seconds since it was made."""
    start = time.perf_counter()

    def log(line: str) -> None:
        print(f"[{time.perf_counter() - start:6.1f} s] {line}", flush=True)

    return log
