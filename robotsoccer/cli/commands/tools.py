"""``robotsoccer bench``, ``trace``, ``serve`` and ``replay``."""

from __future__ import annotations

import argparse
import json
import sys
from typing import TYPE_CHECKING

from field_models.protocol import PlayerRef
from robotsoccer.cli.options import BENCH_TARGETS, DEFAULT_FIELD, UsageError
from robotsoccer.cli.running import spec_from

if TYPE_CHECKING:
    pass


def cmd_bench(args: argparse.Namespace) -> int:
    """Run the benchmarks, printing each figure beside its target as it is measured."""
    from robotsoccer.bench import iter_benchmarks, nest, target_cell

    def say(line: str) -> None:
        print(f"bench: {line}", file=sys.stderr, flush=True)

    rows = []
    for key, value in iter_benchmarks(quick=args.quick, demo_field=DEFAULT_FIELD, say=say):
        rows.append((key, value))
        if not args.json:
            cell = target_cell(key, value, BENCH_TARGETS)
            print(f"{key:<44} {value!s:>12}   {cell}".rstrip(), flush=True)
    if args.json:
        print(json.dumps(nest(rows)))
    return 0


def cmd_trace(args: argparse.Namespace) -> int:
    """Print the trace of one trial for one client."""
    from robotsoccer.replay.trace import trace_trial

    client = _player(args.player) if args.player else None
    for line in trace_trial(spec_from(args), args.trial, client):
        print(line)
    return 0


def _player(text: str) -> PlayerRef:
    """``left1`` → PlayerRef("left", 1)."""
    team = text.rstrip("0123456789")
    number = text[len(team) :]
    if not team or not number:
        raise UsageError(f"--player: expected a team and a number like left1, got {text!r}")
    return PlayerRef(team, int(number))


def cmd_replay(args: argparse.Namespace) -> int:
    """Open (or, headless, verify and explain how to open) a recording or a game log."""
    from robotsoccer.replay.rrd_files import replay

    if args.file.suffix == ".rcg":
        from robotsoccer.replay.game_log import rrd_from_rcg

        return replay(rrd_from_rcg(args.file))
    return replay(args.file)
