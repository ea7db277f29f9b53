"""``robotsoccer reproduce``: layers 1 and 2, the lead study, layer 3 and the transfer study."""

from __future__ import annotations

import argparse
from typing import TYPE_CHECKING

from field_models.registry import default_preset
from robotsoccer.cli.commands.transfer import transfer_setup
from robotsoccer.cli.options import LEAD_DRILLS, PAPER_MODELS, TEAM_FIELD
from robotsoccer.cli.running import clock_log, run_settings, show
from robotsoccer.cli.shared import Commands, experiment_options, transfer_options

if TYPE_CHECKING:
    from robotsoccer.experiments.reproduce import ReproduceRun


def cmd_reproduce(args: argparse.Namespace) -> int:
    """``reproduce``: the pipeline of :func:`~robotsoccer.experiments.reproduce.run_reproduce`.

    Layers 1 and 2 on both field models, the lead study, a quick layer 3 and the transfer
    study, into one folder; ``--no-lead``, ``--no-team``, ``--no-transfer`` leave steps out.
    """
    from robotsoccer.experiments.reproduce import run_reproduce

    return show(lambda: run_reproduce(reproduce_request(args), clock_log()))


def reproduce_request(args: argparse.Namespace) -> ReproduceRun:
    """The run ``robotsoccer reproduce``'s options ask for: both paper models, the steps kept."""
    from robotsoccer.experiments.lead_study import StudyDrill
    from robotsoccer.experiments.reproduce import ReproduceParts, ReproduceRun

    models = tuple((model, default_preset(model)) for model in PAPER_MODELS)
    parts = ReproduceParts(
        layer2=True,
        lead_drills=()
        if args.no_lead
        else tuple(StudyDrill(f, *LEAD_DRILLS[f]) for f in LEAD_DRILLS),
        team_field=None if args.no_team else TEAM_FIELD,
        transfer=None if args.no_transfer else transfer_setup(args, models),
    )
    return ReproduceRun(
        models=models,
        parts=parts,
        **run_settings(args),
    )


def add_parser(commands: Commands) -> None:
    """``reproduce``'s options."""
    reproduce = commands.add(
        "reproduce",
        "layers 1 and 2 on both field models, then the transfer study: report, plots",
    )
    experiment_options(reproduce)
    reproduce.add_argument(
        "--no-transfer", action="store_true", help="layers 1 and 2 only, without the transfer study"
    )
    reproduce.add_argument(
        "--no-lead",
        action="store_true",
        help="without layer 1's lead decision (robotsoccer learn lead) after layers 1 and 2",
    )
    reproduce.add_argument(
        "--no-team",
        action="store_true",
        help="without layer 3 (a quick `learn team --every` on the Soccer Server's layers)",
    )
    transfer_options(reproduce)
