"""``robotsoccer setplay``: the set play of Figure 15 on both field models."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import TYPE_CHECKING

from field_models.registry import default_preset
from robotsoccer.cli.options import PAPER_MODELS, _index, _positive_int
from robotsoccer.cli.running import run_settings, show
from robotsoccer.cli.shared import Commands, run_options

if TYPE_CHECKING:
    from robotsoccer.experiments.setplay_run import SetPlayRun


def cmd_setplay(args: argparse.Namespace) -> int:
    """The set play on both field models, layered and baseline minds, with its report."""
    from robotsoccer.experiments.setplay_run import run_setplay

    def warn(line: str) -> None:
        print(line, file=sys.stderr)

    return show(lambda: run_setplay(setplay_request(args), print, warn))


def setplay_request(args: argparse.Namespace) -> SetPlayRun:
    """The study ``robotsoccer setplay``'s options ask for."""
    from robotsoccer.experiments.setplay_run import SetPlayRun

    return SetPlayRun(
        fields=tuple((m, default_preset(m)) for m in PAPER_MODELS),
        models=args.models,
        plays=args.plays,
        client=args.client,
        look=args.look,
        **run_settings(args, progress=True),
    )


def add_parser(commands: Commands) -> None:
    """``setplay``'s options."""
    setplay = commands.add(
        "setplay", "the set play of Figure 15 on both field models: layered and baseline minds"
    )
    setplay.add_argument(
        "--plays", type=_positive_int, default=1000, help="plays per field model and condition"
    )
    setplay.add_argument(
        "--models",
        type=Path,
        default=None,
        help="run folder of reproduce/transfer with models/<field>/net_750.npz and "
        "pass_tree.json (default: runs/transfer-seed<S>); without them only the baseline runs",
    )
    setplay.add_argument("--quick", action="store_true", help="40 plays per condition")
    setplay.add_argument(
        "--client",
        choices=("see", "cycle"),
        default="see",
        help="the Soccer Server players' client: see (the paper's: a decision at each see) or "
        "cycle (a command every cycle from a world model); the robots keep theirs",
    )
    setplay.add_argument(
        "--look",
        choices=("body", "neck"),
        default="body",
        help="how the Soccer Server attackers look: body (the paper's client: turning the body) "
        "or neck (the head keeps the ball in view, a wide view to search); the robots keep theirs",
    )
    setplay.add_argument("--seed", type=_index, default=0, help="experiment seed")
    run_options(setplay)
