"""``robotsoccer setplay`` as a pipeline: the set-play study into its own run folder.

The CLI (:mod:`robotsoccer.cli.commands.setplay`) only reads its options into a
:class:`SetPlayRun` and prints what :func:`run_setplay` returns; which layers the layered minds
get, the run folder, the context and the study
(:func:`robotsoccer.experiments.setplay.run_setplay_study`) are decided here.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

from robotsoccer.experiments.context import (
    Log,
    RunRequest,
    kept_on_interrupt,
)

LAYER_FILES = ("net_750.npz", "pass_tree.json")
"""What each field's ``models/<field>/`` must hold for the layered minds."""


@dataclass(frozen=True)
class SetPlayRun(RunRequest):
    """What ``robotsoccer setplay`` runs, and where.

    Attributes:
        fields: (field model, preset) of each field the study plays on.
        models: The run folder whose ``models/<field>/`` hold the layers; None: the default
            (``runs/transfer-seed<S>``), where missing layers mean the baseline minds only.
        plays: Plays per field model and condition.
        quick: The quick plan.
        client: The Soccer Server players' client (``see`` or ``cycle``).
        look: How the Soccer Server attackers look (``body`` or ``neck``).
        out: The run folder; None: ``runs/setplay[-<client>][-neck][-quick]-seed<S>``.

    The other run-folder settings are :class:`~robotsoccer.experiments.context.RunRequest`'s.
    """

    fields: tuple[tuple[str, str], ...]
    models: Path | None = None
    plays: int = 1000
    client: str = "see"
    look: str = "body"

    @property
    def folder(self) -> Path:
        """The run folder: `out`, or one named after the client, the look, the plan, the seed."""
        client = "" if self.client == "see" else f"-{self.client}"  # a see run's folder stays
        look = "" if self.look == "body" else f"-{self.look}"  # and so does a body run's
        quick = "-quick" if self.quick else ""
        return self.out or Path("runs") / f"setplay{client}{look}{quick}-seed{self.seed}"

    def layers(self, warn: Log) -> Path | None:
        """The ``models`` folder of the layers, or None (the baseline minds only, said in `warn`).

        Raises:
            ValueError: A `models` folder given that lacks a field's layers.
        """
        folder = self.models or Path("runs") / f"transfer-seed{self.seed}"
        models = folder / "models"
        if all((models / m / f).exists() for m, _ in self.fields for f in LAYER_FILES):
            return models
        if self.models is not None:
            raise ValueError(f"{folder}/models lacks a field's net_750.npz or pass_tree.json")
        warn(f"no trained layers in {folder}/models: the baseline minds only")
        return None


@dataclass(frozen=True)
class SetPlayOutcome:
    """Where the study's report is.

    Attributes:
        report: Its ``report.md``.
    """

    report: Path

    @property
    def lines(self) -> tuple[str, ...]:
        """What the command prints."""
        return (f"report: {self.report}",)


def run_setplay(request: SetPlayRun, log: Log, warn: Callable[[str], None]) -> SetPlayOutcome:
    """Find the layers, prepare the folder, run the study (its report is written as it goes).

    Raises:
        ValueError: A `models` folder without the layers, or a run folder in the way.
        RunInterrupted: Ctrl-C; the finished plays are kept (``resume`` finishes the run).
    """
    from robotsoccer.experiments.setplay import run_setplay_study

    models = request.layers(warn)
    out = request.folder
    workers = request.prepared(out)
    ctx = request.context(out, workers, log)
    with kept_on_interrupt(out, kept="plays"):
        report = run_setplay_study(
            ctx,
            fields=list(request.fields),
            models=models,
            plays=request.plays,
            quick=request.quick,
            client=request.client,
            look=request.look,
        )
    return SetPlayOutcome(report)
