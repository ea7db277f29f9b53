"""``robotsoccer learn intercept|pass|lead`` as pipelines: one layer's study into its run folder.

The CLI (:mod:`robotsoccer.cli.commands.learn`) only reads its options into an
:class:`InterceptRun`, a :class:`PassRun` or a :class:`LeadRun` and prints what the pipeline
returns; the run folder, ``config.json``, the context and the study are decided here.
``learn intercept`` runs :func:`robotsoccer.experiments.reproduce.run_reproduce` with layer 1
alone; ``learn pass`` layer 2 (:mod:`robotsoccer.experiments.layer2`) on a net given or trained
first; ``learn lead`` the lead study (:mod:`robotsoccer.experiments.lead_study`).
"""

from __future__ import annotations

import dataclasses
import json
import time
from dataclasses import dataclass
from pathlib import Path

from field_models.registry import default_preset
from robotsoccer.experiments import layer1_plan, layer2, lead_study
from robotsoccer.experiments.context import (
    Field,
    Log,
    ReportOutcome,
    RunRequest,
    kept_on_interrupt,
)
from robotsoccer.experiments.lead_study import StudyDrill
from robotsoccer.experiments.reproduce import ReproduceParts, lead_step
from robotsoccer.runs.runner import TrialSpec, check_spec


def _quick(quick: bool) -> str:
    """The title's mark of the quick plan."""
    return " — quick plan" if quick else ""


@dataclass(frozen=True)
class InterceptRun(RunRequest):
    """What ``robotsoccer learn intercept`` runs, and where (a :class:`~.reproduce.LayersRequest`).

    Attributes:
        field: The field model.
        preset: Its preset; None: the model's default.
        client: Layer 1's client on the Soccer Server (``see`` or ``cycle``:
            :class:`~robotsoccer.experiments.reproduce.ReproduceParts`).
        quick: The quick plan.
        out: The run folder; None:
            ``runs/learn-intercept-<field>-<preset>[-<client>][-quick]-seed<S>``.

    The other run-folder settings are :class:`~robotsoccer.experiments.context.RunRequest`'s.
    """

    field: str
    preset: str | None = None
    client: str = "see"

    @property
    def models(self) -> tuple[Field, ...]:
        """The one field model with its preset (resolved: never None)."""
        return ((self.field, self.preset or default_preset(self.field)),)

    @property
    def parts(self) -> ReproduceParts:
        """Layer 1 alone, with the request's client."""
        return ReproduceParts(client=self.client)

    @property
    def folder(self) -> Path:
        """The run folder: `out`, or one named after the field, preset, client, plan and seed."""
        preset = self.models[0][1]
        client = "" if self.client == "see" else f"-{self.client}"
        tag = f"learn-intercept-{self.field}-{Path(preset).stem}{client}"
        tag += "-quick" if self.quick else ""
        return self.out or Path("runs") / f"{tag}-seed{self.seed}"

    @property
    def title(self) -> str:
        """The report's title."""
        return f"Layer 1 (interception) on {self.field}{_quick(self.quick)}"

    @property
    def created_by(self) -> str:
        """The command named in the files' provenance."""
        return "robotsoccer learn intercept"


@dataclass(frozen=True)
class PassRun(RunRequest):
    """What ``robotsoccer learn pass`` runs, and where.

    Attributes:
        field: The field model.
        preset: Its preset; None: the model's default.
        net: Layer 1's interception net for receivers and defenders; None: train it first
            (:func:`robotsoccer.experiments.layer1.train_main_net`).
        quick: The quick plans (layer 2's, and layer 1's for the net).
        out: The run folder; None: ``runs/learn-pass-<field>-<preset>[-quick]-seed<S>``.
        client: The receivers' and defenders' client (``see`` or ``cycle``; the layer-2
            plan's ``client``).

    The other run-folder settings are :class:`~robotsoccer.experiments.context.RunRequest`'s.
    """

    field: str
    preset: str | None = None
    net: Path | None = None
    client: str = "see"

    @property
    def model(self) -> Field:
        """The field model with its preset (resolved: never None)."""
        return self.field, self.preset or default_preset(self.field)

    @property
    def folder(self) -> Path:
        """The run folder: `out`, or one named after the field, preset, plan and seed."""
        tag = f"learn-pass-{self.field}-{Path(self.model[1]).stem}"
        tag += "-quick" if self.quick else ""
        return self.out or Path("runs") / f"{tag}-seed{self.seed}"


def run_learn_pass(request: PassRun, log: Log) -> ReportOutcome:
    """Check the drill, prepare the folder, get the net, run layer 2, write the report.

    The pass drill, and with a given net the drill with that net, are checked before the
    folder is touched. `log` gets the steps' progress lines.

    Raises:
        ValueError: A bad preset or net (e.g. one trained on another field), or a run folder
            in the way (one line each).
        RunInterrupted: Ctrl-C; the finished trials are kept (``resume`` finishes the run).
    """
    from robotsoccer.experiments.layer1 import train_main_net
    from robotsoccer.experiments.plots_layer2 import layer2_plots

    model = request.model
    spec = TrialSpec(drill="pass", field_model=model[0], preset=model[1])
    if request.client != "see":
        spec = spec.with_options(client=request.client)
    check_spec(spec)
    if request.net is not None:
        check_spec(spec.with_options(interceptor="net", net=str(request.net)))
    out = request.folder
    workers = request.prepared(out)
    plan = dataclasses.replace(layer2.layer2_plan(request.quick), client=request.client)
    ctx = request.context(out, workers, log, "robotsoccer learn pass")
    start = time.perf_counter()
    with kept_on_interrupt(out):
        net = request.net
        if net is None:
            net = train_main_net(model, layer1_plan.plan_for(request.quick), ctx)
        section = layer2.run_layer2_model(model, net, plan, ctx)
    title = f"# Layer 2 (pass evaluation) on {request.field}{_quick(request.quick)}"
    report = out / "report.md"
    plots = layer2_plots([section], out)
    report.write_text(f"{title}\n\n{layer2.layer2_markdown([section], plan, plots)}")
    config = {"plan": plan.to_dict(), "seed": request.seed, "net": str(net)}
    (out / "config.json").write_text(json.dumps(config, indent=2) + "\n")
    return ReportOutcome(report, time.perf_counter() - start, workers)


@dataclass(frozen=True)
class LeadRun(RunRequest):
    """What ``robotsoccer learn lead`` runs, and where.

    Attributes:
        drills: The study's drill on each field, in report order.
        quick: The quick plan (:func:`robotsoccer.experiments.lead_study.plan_for`).
        out: The run folder; None: ``runs/learn-lead[-<field>][-quick]-seed<S>``, the field
            named when the study runs on one.

    The other run-folder settings are :class:`~robotsoccer.experiments.context.RunRequest`'s.
    """

    drills: tuple[StudyDrill, ...]

    @property
    def folder(self) -> Path:
        """The run folder: `out`, or one named after the field (if one), plan and seed."""
        tag = "learn-lead" + (f"-{self.drills[0].field_model}" if len(self.drills) == 1 else "")
        tag += "-quick" if self.quick else ""
        return self.out or Path("runs") / f"{tag}-seed{self.seed}"


def run_learn_lead(request: LeadRun, log: Log) -> ReportOutcome:
    """Prepare the folder, run the lead study on the request's drills, write the report.

    `log` gets the study's progress lines.

    Raises:
        ValueError: A run folder in the way (one line).
        RunInterrupted: Ctrl-C; the finished trials are kept (``resume`` finishes the run).
    """
    out = request.folder
    workers = request.prepared(out)
    plan = lead_study.plan_for(request.quick)
    start = time.perf_counter()
    ctx = request.context(out, workers, log, "robotsoccer learn lead")
    with kept_on_interrupt(out):
        text = lead_step(request.drills, request.quick, ctx)
    report = out / "report.md"
    report.write_text(f"# Layer 1: the lead decision{_quick(request.quick)}\n\n{text}")
    fields = [drill.field_model for drill in request.drills]
    config = {"plan": plan.to_dict(), "seed": request.seed, "fields": fields}
    (out / "config.json").write_text(json.dumps(config, indent=2) + "\n")
    return ReportOutcome(report, time.perf_counter() - start, workers)
