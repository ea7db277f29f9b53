"""``robotsoccer trace``: a paper-style trace (Figure 4) of one trial for one client."""

from __future__ import annotations

import argparse

from field_models.protocol import PlayerRef
from robotsoccer.cli.options import UsageError, _index
from robotsoccer.cli.running import spec_from
from robotsoccer.cli.shared import Commands, drill_options, field_options


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


def add_parser(commands: Commands) -> None:
    """``trace``'s options."""
    trace = commands.add("trace", "print a paper-style trace (Figure 4) of one trial")
    field_options(trace)
    drill_options(trace)
    trace.add_argument("--trial", type=_index, default=0, help="trial index")
    trace.add_argument("--player", default=None, help="client to trace, e.g. left1 (first)")
