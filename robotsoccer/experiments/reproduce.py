"""``reproduce`` as a pipeline of steps, each appending its section to one report.

Layer 1, then layer 2, the lead study, layer 3 and the transfer study, in one run folder.
The CLI (:mod:`robotsoccer.cli.commands.reproduce`) only reads its options into a
:class:`ReproduceRun` and prints what :func:`run_reproduce` returns; the run folder, the
context and what runs, in which order and into which folders are decided here (the steps:
:func:`run_steps`). ``learn intercept`` is the same pipeline with layer 1 alone
(:class:`robotsoccer.experiments.learn_run.InterceptRun`).
"""

from __future__ import annotations

import dataclasses
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Protocol

from robotsoccer.experiments import layer1_plan
from robotsoccer.experiments.context import (
    Field,
    Log,
    ReportOutcome,
    RunContext,
    RunRequest,
    kept_on_interrupt,
)
from robotsoccer.experiments.lead_study import StudyDrill
from robotsoccer.experiments.report_records import ModelSection
from robotsoccer.experiments.transfer_study import TransferSetup
from robotsoccer.runs.pool import default_workers
from robotsoccer.runs.runner import TrialSpec, check_spec


@dataclass(frozen=True)
class ReproduceParts:
    """Which steps follow layer 1 (none by default: ``learn intercept``).

    Attributes:
        client: Layer 1's client on the Soccer Server (``see``: the paper's see-triggered
            client; ``cycle``: one that acts every cycle, :mod:`robotsoccer.skills.cycle`).
        layer2: Layer 2 on every field model, with the layer-1 net each trained.
        lead_drills: The lead study's drills (§5's recipe for the robots' lead decision), in
            ``lead/``; empty: no lead study.
        team_field: The field model of the quick layer-3 step (``team/``); None: none.
        transfer: The transfer study's setting; None: no transfer study.
    """

    client: str = "see"
    layer2: bool = False
    lead_drills: tuple[StudyDrill, ...] = ()
    team_field: str | None = None
    transfer: TransferSetup | None = None


class LayersRequest(Protocol):
    """What :func:`run_reproduce` runs: a :class:`ReproduceRun`, or ``learn intercept``'s."""

    @property
    def models(self) -> tuple[Field, ...]:
        """The field models and presets layer 1 runs on, in report order."""

    @property
    def parts(self) -> ReproduceParts:
        """The steps after layer 1."""

    @property
    def quick(self) -> bool:
        """The quick plans."""

    @property
    def seed(self) -> int:
        """The experiment seed."""

    @property
    def folder(self) -> Path:
        """The run folder."""

    @property
    def title(self) -> str:
        """The report's title."""

    @property
    def created_by(self) -> str:
        """The command named in the files' provenance."""

    def prepared(self, out: Path) -> int:
        """Make the run folder ready; the worker count (:class:`RunRequest`'s)."""

    def context(self, out: Path, workers: int, log: Log, created_by: str) -> RunContext:
        """The run's context (:class:`RunRequest`'s)."""


@dataclass(frozen=True)
class ReproduceRun(RunRequest):
    """What ``robotsoccer reproduce`` runs, and where.

    Attributes:
        models: The field models and presets, in report order.
        parts: The steps after layer 1 (by default none).
        quick: The quick plans.
        out: The run folder; None: ``runs/reproduce[-quick]-seed<S>``.

    The other run-folder settings are :class:`~robotsoccer.experiments.context.RunRequest`'s.
    """

    models: tuple[Field, ...]
    parts: ReproduceParts = ReproduceParts()

    @property
    def folder(self) -> Path:
        """The run folder: `out`, or one named after the plan and seed."""
        name = f"reproduce-quick-seed{self.seed}" if self.quick else f"reproduce-seed{self.seed}"
        return self.out or Path("runs") / name

    @property
    def title(self) -> str:
        """The report's title."""
        title = "Layers 1 and 2 reproduced (Stone & Veloso 1996, §5 and §6)"
        return title + (" — quick plan" if self.quick else "")

    @property
    def created_by(self) -> str:
        """The command named in the files' provenance."""
        return "robotsoccer reproduce"


def run_reproduce(request: LayersRequest, log: Log) -> ReportOutcome:
    """Check the presets, prepare the run folder and run the steps (:func:`run_steps`).

    A bad preset fails before the folder is touched. `log` gets the steps' progress lines.

    Raises:
        ValueError: A bad preset, or a run folder in the way (one line each).
        RunInterrupted: Ctrl-C; the finished trials are kept (``resume`` finishes the run).
    """
    for model, preset in request.models:  # a bad preset fails here with one line, not in a worker
        check_spec(TrialSpec(drill="intercept", field_model=model, preset=preset))
    out = request.folder
    workers = request.prepared(out)
    start = time.perf_counter()
    ctx = request.context(out, workers, log, request.created_by)
    with kept_on_interrupt(out):
        report = run_steps(request.models, request.quick, ctx, request.parts, request.title)
    return ReportOutcome(report, time.perf_counter() - start, workers)


def run_steps(
    models: Sequence[Field], quick: bool, ctx: RunContext, parts: ReproduceParts, title: str
) -> Path:
    """Run layer 1 on `models` and the steps `parts` names into the run; return the report.

    Rerunning into the same folder resumes every step (finished trials are kept).
    """
    from robotsoccer.experiments.layer1 import run_layer1
    from robotsoccer.experiments.transfer_study import run_transfer_study

    plan = dataclasses.replace(layer1_plan.plan_for(quick), client=parts.client)
    report, sections = run_layer1(models, plan, ctx, title=title)
    steps: list[Callable[[], str]] = []
    if parts.layer2:
        steps.append(lambda: layer2_step(sections, quick, ctx))
    if parts.layer2 and parts.lead_drills:
        steps.append(lambda: lead_step(parts.lead_drills, quick, ctx.at(ctx.out / "lead")))
    if parts.layer2 and parts.team_field is not None:
        field = parts.team_field
        steps.append(lambda: team_step(field, sections, ctx))
    if parts.layer2 and parts.transfer is not None:
        setup = parts.transfer
        steps.append(lambda: run_transfer_study(setup, quick, ctx))
    for step in steps:  # each section is in the report as soon as its step ends
        text = step()
        with report.open("a") as f:
            f.write("\n" + text)
    return report


def layer2_step(sections: Sequence[ModelSection], quick: bool, ctx: RunContext) -> str:
    """Layer 2 on each field of `sections`, with the net its layer 1 trained; the report part."""
    from robotsoccer.experiments.layer2 import layer2_markdown, layer2_plan, run_layer2_model
    from robotsoccer.experiments.plots_layer2 import layer2_plots

    plan = layer2_plan(quick)
    layer2 = [
        run_layer2_model(
            (s.field_model, s.preset),
            ctx.models_dir(s.field_model) / f"net_{s.net_examples}.npz",
            plan,
            ctx,
        )
        for s in sections
    ]
    return layer2_markdown(layer2, plan, layer2_plots(layer2, ctx.out))


def lead_step(drills: Sequence[StudyDrill], quick: bool, ctx: RunContext) -> str:
    """The lead study (:mod:`robotsoccer.experiments.lead_study`) on `drills`; its report part."""
    from robotsoccer.experiments.lead_study import plan_for as lead_plan_for
    from robotsoccer.experiments.lead_study import run_study

    text, _ = run_study(drills, lead_plan_for(quick), ctx)
    return text


def team_step(field: str, sections: Sequence[ModelSection], ctx: RunContext) -> str:
    """Layer 3 on `field`'s new layers: a quick ``learn team --every`` (its report part).

    The quick plan (8 training games, 4-game series) shows every step runs on this run's net
    and tree; the measured study is ``robotsoccer learn team --every``.
    """
    from robotsoccer.experiments import team_study

    found = [s for s in sections if s.field_model == field]
    if not found:
        return ""
    models = ctx.models_dir(field)
    net, tree = models / f"net_{found[0].net_examples}.npz", models / "pass_tree.json"
    base = team_study.match_base(field, found[0].preset, ctx.seeds.evaluation, net, tree)
    plan = team_study.plan_for(True, True)
    report = team_study.run_team_study(
        base, plan, ctx.out / "team", workers=ctx.workers or default_workers(), log=ctx.log
    )
    return report.read_text().replace("## Layer 3", "## Layer 3 (quick: a smoke-size run)", 1)
