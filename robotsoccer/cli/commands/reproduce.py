"""``robotsoccer reproduce``: layers 1 and 2, the lead study, layer 3 and the transfer study."""

from __future__ import annotations

import argparse
from pathlib import Path

from field_models.registry import default_preset
from robotsoccer.cli.commands.learn import run_pipeline
from robotsoccer.cli.commands.transfer import transfer_setup
from robotsoccer.cli.options import LEAD_DRILLS, PAPER_MODELS, TEAM_FIELD
from robotsoccer.cli.shared import Commands, experiment_options, transfer_options


def cmd_reproduce(args: argparse.Namespace) -> int:
    """``reproduce``: the pipeline of :func:`~robotsoccer.experiments.reproduce.run_reproduce`.

    Layers 1 and 2 on both field models, the lead study, a quick layer 3 and the transfer
    study, into one folder; ``--no-lead``, ``--no-team``, ``--no-transfer`` leave steps out.
    """
    from robotsoccer.experiments.lead_study import StudyDrill
    from robotsoccer.experiments.reproduce import ReproduceParts

    name = f"reproduce-quick-seed{args.seed}" if args.quick else f"reproduce-seed{args.seed}"
    out = args.out or Path("runs") / name
    models = [(model, default_preset(model)) for model in PAPER_MODELS]
    title = "Layers 1 and 2 reproduced (Stone & Veloso 1996, §5 and §6)" + (
        " — quick plan" if args.quick else ""
    )
    parts = ReproduceParts(
        layer2=True,
        lead_drills=()
        if args.no_lead
        else tuple(StudyDrill(f, *LEAD_DRILLS[f]) for f in LEAD_DRILLS),
        team_field=None if args.no_team else TEAM_FIELD,
        transfer=None if args.no_transfer else transfer_setup(args, models),
    )
    return run_pipeline(args, models, out, title, "robotsoccer reproduce", parts)


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
