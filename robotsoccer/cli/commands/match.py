"""``robotsoccer match``: one match or a series, with the layers it plays.

The pipeline is :func:`robotsoccer.experiments.match_run.run_match`; the command reads its
options into a :class:`~robotsoccer.experiments.match_run.MatchRun` and prints the outcome.
"""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import TYPE_CHECKING

from field_models.arena import FieldOptions
from robotsoccer.cli.options import (
    EXIT_INTERRUPTED,
    TEAM_KINDS,
    _drill_option,
    _index,
    _positive_float,
    _positive_int,
)
from robotsoccer.cli.running import fail
from robotsoccer.cli.shared import Commands, field_options, run_options

if TYPE_CHECKING:
    from robotsoccer.experiments.match_run import LayerFiles, MatchRun


def cmd_match(args: argparse.Namespace) -> int:
    """One match, or a series of layered against baseline with its report."""
    from robotsoccer.experiments.context import RunInterrupted
    from robotsoccer.experiments.match_run import run_match

    try:
        outcome = run_match(match_request(args))
    except RunInterrupted as stop:
        return fail(EXIT_INTERRUPTED, str(stop))
    for line in outcome.lines:
        print(line)
    return 0


def match_request(args: argparse.Namespace) -> MatchRun:
    """The match or series ``robotsoccer match``'s options ask for."""
    from robotsoccer.experiments.match_run import MatchRun

    return MatchRun(
        field=args.field,
        preset=args.field_preset,
        seed=args.seed,
        games=args.games,
        left=args.left,
        right=args.right,
        players=args.players,
        half_time_s=args.half_time,
        layers=layer_files(args),
        tpot=args.tpot,
        options=tuple(args.option),
        field_options=FieldOptions(
            perfect_perception=args.perfect_perception, ball_noise=args.ball_noise
        ),
        record=args.record,
        out=args.out,
        resume=args.resume,
        overwrite=args.overwrite,
        workers=args.workers,
        progress=not args.quiet,
    )


def layer_files(args: argparse.Namespace) -> LayerFiles:
    """Where ``--net``, ``--tree`` and ``--models`` say the layered team's files are."""
    from robotsoccer.experiments.match_run import LayerFiles

    return LayerFiles(net=args.net, tree=args.tree, models=args.models)


def add_parser(commands: Commands) -> None:
    """``match``'s options."""
    match = commands.add(
        "match",
        "play a match (or a series: --games N) between the layered team and the baseline",
    )
    field_options(match)
    match.add_argument(
        "--games", type=_positive_int, default=1, help="1: one match; more: a series (sides swap)"
    )
    match.add_argument("--left", default="layered", choices=TEAM_KINDS, help="one match: left")
    match.add_argument("--right", default="baseline", choices=TEAM_KINDS, help="one match: right")
    match.add_argument(
        "--models",
        type=Path,
        default=None,
        help="run folder of reproduce/transfer/learn pass with models/<field>/ (default: the "
        "first of runs/reproduce-seed<S>, runs/transfer-seed<S> that has them)",
    )
    match.add_argument("--net", type=Path, default=None, help="layer 1's net (.npz)")
    match.add_argument("--tree", type=Path, default=None, help="layer 2's tree (.json)")
    match.add_argument(
        "--tpot",
        type=Path,
        default=None,
        help="layer 3's table (.npz, from `learn team`) for a layer3 team; it plays with the "
        "rule it learned with (every spell on the ball or only where blocked)",
    )
    match.add_argument(
        "--players", type=_index, default=0, help="players a side (0: 11 open field, 5 table)"
    )
    match.add_argument("--half-time", type=_positive_float, default=None, help="one half [s] (300)")
    match.add_argument(
        "--record",
        action="store_true",
        help="rerun recording (and on the server's pitch an .rcg game log) of the first game "
        "of each side",
    )
    match.add_argument("--quiet", action="store_true", help="no progress")
    match.add_argument(
        "--option",
        action="append",
        default=[],
        type=_drill_option,
        metavar="NAME=VALUE",
        help="a match option for both teams' minds, e.g. look=neck, steady_turns=true, "
        "dead_band=true, turn_latency=reckon, client=cycle, receiver_half=estimated, "
        "net_domain=trained "
        "(repeatable; a team's own: "
        "left/right as the value where it takes one)",
    )
    run_options(match)
