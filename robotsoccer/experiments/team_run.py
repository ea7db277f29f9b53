"""``robotsoccer learn team`` as a pipeline: layer 3's study into its own run folder.

The CLI (:mod:`robotsoccer.cli.commands.learn`) only reads its options into a :class:`TeamRun`
and prints what :func:`run_learn_team` returns; the plan (the quick or full one, with the
command's changes), the layers it plays on, the run folder, ``config.json`` and the study
(:func:`robotsoccer.experiments.team_study.run_team_study`) are decided here.
"""

from __future__ import annotations

import dataclasses
import json
import time
from dataclasses import dataclass, replace
from pathlib import Path

from field_models.registry import default_preset
from learning.tpot import WINDOW_CHOICE
from robotsoccer.experiments import team_study
from robotsoccer.experiments.context import Log, ReportOutcome, RunRequest, kept_on_interrupt
from robotsoccer.experiments.match_run import LayerFiles
from robotsoccer.experiments.team_plan import TeamPlan
from robotsoccer.runs.runner import check_spec


@dataclass(frozen=True)
class TeamRun(RunRequest):
    """What ``robotsoccer learn team`` runs, and where.

    Attributes:
        field: The field model.
        preset: Its preset; None: the model's default.
        layers: Where the layered team's net and tree come from.
        table: A learned layer-3 table: no training, the series only.
        quick: The quick plan (:func:`robotsoccer.experiments.team_plan.plan_for`).
        every: Layer 3 decides on every spell on the ball (TPOT-RL's own rule).
        window: When a reward closes (:data:`learning.tpot.REWARD_WINDOWS`).
        shot_guard: The shot-range guard (needs `every`).
        loss_penalty: The possession reward's loss penalty (0: the ball's advance alone).
        features_tree: Layer 3's own pass tree for its features; None: the team's tree.
        success: Layer 3's SUCCESS cut on that tree's confidence; None: the plan's.
        games_per_round: Training games that share one table; None: the plan's.
        training_games: Training games; None: the plan's.
        out: The run folder; None: ``runs/learn-team-<field>-<preset>[-...]-seed<S>``.

    The other run-folder settings are :class:`~robotsoccer.experiments.context.RunRequest`'s.
    """

    field: str
    preset: str | None = None
    layers: LayerFiles = dataclasses.field(default_factory=LayerFiles)
    table: Path | None = None
    every: bool = False
    window: str = WINDOW_CHOICE
    shot_guard: bool = False
    loss_penalty: float = 0.0
    features_tree: Path | None = None
    success: float | None = None
    games_per_round: int | None = None
    training_games: int | None = None

    def plan(self) -> TeamPlan:
        """The quick or full plan with the request's changes.

        Raises:
            ValueError: A plan the study cannot play (e.g. the guard without `every`).
        """
        plan = team_study.plan_for(self.quick, self.every, self.window)
        if self.training_games is not None:
            plan = replace(plan, training_games=self.training_games)
        if self.games_per_round is not None:
            plan = replace(plan, games_per_round=self.games_per_round)
        if self.shot_guard or self.loss_penalty:
            plan = replace(plan, guard=self.shot_guard, loss=self.loss_penalty)
        if self.features_tree is not None:
            plan = replace(plan, features_tree=str(self.features_tree.resolve()))
        if self.success is not None:
            plan = replace(plan, success=self.success)
        return plan

    @property
    def folder(self) -> Path:
        """The run folder: `out`, or one named after the field, preset, rule and seed."""
        preset = self.preset or default_preset(self.field)
        tag = f"learn-team-{self.field}-{Path(preset).stem}" + ("-every" if self.every else "")
        tag += "-horizon" if self.window == "horizon" else ""
        tag += "-guard" if self.shot_guard else ""
        tag += f"-loss{self.loss_penalty:g}" if self.loss_penalty else ""
        tag += f"-{self.features_tree.stem}" if self.features_tree is not None else ""
        tag += f"-cut{self.success:g}" if self.success is not None else ""
        tag += "-quick" if self.quick else ""
        return self.out or Path("runs") / f"{tag}-seed{self.seed}"


def run_learn_team(request: TeamRun, log: Log) -> ReportOutcome:
    """Check the request, prepare the run folder, write ``config.json``, run the study.

    The layers, the plan, the match spec and a given table are checked before the folder is
    touched. `log` gets the study's progress lines.

    Raises:
        ValueError: No layers found, a bad plan, preset or table, or a run folder in the way
            (one line each).
        RunInterrupted: Ctrl-C; the finished games are kept (``resume`` finishes the run).
    """
    preset = request.preset or default_preset(request.field)
    net, tree = request.layers.find(request.field, request.seed)
    plan = request.plan()
    base = team_study.match_base(request.field, request.preset, request.seed, net, tree)
    check_spec(base.with_options(left="layered", right="baseline"))
    if request.table is not None:
        from learning.tpot import load_table

        load_table(request.table)  # a corrupt or foreign table fails here, in one line
    out = request.folder
    workers = request.prepared(out)
    config = {
        "command": "robotsoccer learn team",
        "plan": plan.to_dict(),
        "seed": request.seed,
        "field": request.field,
        "preset": preset,
        "net": str(net),
        "tree": str(tree),
        "table": None if request.table is None else str(request.table),
        "workers": workers,
    }
    (out / "config.json").write_text(json.dumps(config, indent=2) + "\n")
    start = time.perf_counter()
    with kept_on_interrupt(out, "games"):
        report = team_study.run_team_study(
            base, plan, out, workers=workers, log=log, resume=request.resume,
            progress=request.progress, table=request.table,
        )  # fmt: skip
    return ReportOutcome(report, time.perf_counter() - start, workers)
