"""``robotsoccer replay``: a recording (.rrd) or a game log (.rcg) in the rerun viewer."""

from __future__ import annotations

import argparse
from pathlib import Path

from robotsoccer.cli.shared import Commands


def cmd_replay(args: argparse.Namespace) -> int:
    """Open (or, headless, verify and explain how to open) a recording or a game log."""
    from robotsoccer.replay.rrd_files import replay

    if args.file.suffix == ".rcg":
        from robotsoccer.replay.game_log import rrd_from_rcg

        return replay(rrd_from_rcg(args.file))
    return replay(args.file)


def add_parser(commands: Commands) -> None:
    """``replay``'s argument."""
    replay = commands.add(
        "replay", "open a recording (.rrd, or a .rcg game log) in the rerun viewer"
    )
    replay.add_argument("file", type=Path, help="a .rrd recording or .rcg game log")
