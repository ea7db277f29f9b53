"""``robotsoccer transfer``: the transfer study, and the server ranges its randomisation covers."""

from __future__ import annotations

import argparse
from collections.abc import Sequence
from typing import TYPE_CHECKING

from field_models.registry import default_preset
from robotsoccer.cli.options import LEAD_DRILLS, PAPER_MODELS, REFERENCE_FIELD, TARGET_FIELD
from robotsoccer.cli.running import clock_log, run_settings, show
from robotsoccer.cli.shared import Commands, experiment_options, transfer_options

if TYPE_CHECKING:
    from robotsoccer.experiments.gap_variants import ParameterRange
    from robotsoccer.experiments.transfer_run import TransferRun
    from robotsoccer.experiments.transfer_study import TransferSetup


def cmd_transfer(args: argparse.Namespace) -> int:
    """``transfer``: each field model's net and pass tree tested on every field model."""
    from robotsoccer.experiments.transfer_run import run_transfer

    return show(lambda: run_transfer(transfer_request(args), clock_log()))


def transfer_request(args: argparse.Namespace) -> TransferRun:
    """The study ``robotsoccer transfer``'s options ask for, on the paper's field models."""
    from robotsoccer.experiments.transfer_run import TransferRun

    models = [(model, default_preset(model)) for model in PAPER_MODELS]
    return TransferRun(
        setup=transfer_setup(args, models),
        **run_settings(args),
    )


def server_ranges_covering_robots() -> tuple[ParameterRange, ...]:
    """Domain randomisation of the Soccer Server drill toward the robots (``transfer``).

    Not covered, because the Soccer Server model has no such parameter: the robots' camera
    latency, the time a robot takes to turn (the server turns within one cycle) and blocking
    without a kick.
    """
    from robotsoccer.experiments.gap_variants import ParameterRange

    return (
        ParameterRange(
            "dynamics.player_size_m", 0.8, 2.2,
            why="touch distance: 0.885 units on the server, 2.26 on the robots' table",
        ),
        ParameterRange(
            "dynamics.dash_power_rate_m_per_cycle2", 0.001, 0.01, log=True,
            why="reach after the trigger: about 25 units at the server's top speed, under 2 for "
            "the robots (0.18 s of flight at 115 units/s²)",
        ),
        ParameterRange(
            "dynamics.player_decay", 0.4, 0.8,
            why="inertia: a robot needs 0.4 s to top speed, longer than the ball's 0.18 s",
        ),
        ParameterRange(
            "sensing.send_step_ms", 150, 300, step=50,
            why="percepts from the trigger to the ball's arrival: 6.5 on the server, about 5.4 "
            "on the robots",
        ),
        ParameterRange(
            "dynamics.ball_decay", 0.95, 0.99,
            why="how fast the ball slows over its flight (below 0.94 the literal drill's "
            "power-100 kick stops short of 25 units)",
        ),
    )  # fmt: skip


def transfer_setup(args: argparse.Namespace, models: Sequence[tuple[str, str]]) -> TransferSetup:
    """The transfer study's setting from the command's options (which parts, quick or not)."""
    from robotsoccer.experiments.gap_variants import Randomisation
    from robotsoccer.experiments.lead_study import StudyDrill
    from robotsoccer.experiments.transfer_study import StudyParts, TransferSetup

    fields = dict(models)
    reference = (REFERENCE_FIELD, fields[REFERENCE_FIELD])
    randomisation = Randomisation(
        reference[1], server_ranges_covering_robots(), variants=4 if args.quick else 10
    )
    parts = StudyParts(
        ablations=not getattr(args, "no_ablations", False),
        gap_closing=not getattr(args, "no_gap_closing", False),
        lead=not getattr(args, "no_lead_transfer", False),
        calibration=not getattr(args, "no_calibration", False),
    )
    lead_drills = tuple(StudyDrill(f, *LEAD_DRILLS[f]) for f in LEAD_DRILLS)
    target = (TARGET_FIELD, fields[TARGET_FIELD])
    return TransferSetup(reference, target, randomisation, parts, lead_drills)


def add_parser(commands: Commands) -> None:
    """``transfer``'s options."""
    transfer = commands.add(
        "transfer",
        "the transfer matrix: each field model's net and pass tree on every model; then the "
        "ablations of the robots' interception drill",
    )
    experiment_options(transfer)
    transfer_options(transfer)
