"""The command-line parser: the top parser, and each command's parser from its own module.

Each command module of :mod:`robotsoccer.cli.commands` adds its parser (its ``add_parser``);
the options several commands share are defined once in :mod:`robotsoccer.cli.shared`, their
types and bounds in :mod:`robotsoccer.cli.options`. :data:`COMMAND_MODULES` gives the order in
which the commands are listed in ``robotsoccer --help``.
"""

from __future__ import annotations

import argparse

from robotsoccer import __version__
from robotsoccer.cli.commands import (
    bench,
    demo,
    learn,
    match,
    replay,
    reproduce,
    serve,
    setplay,
    trace,
    transfer,
)
from robotsoccer.cli.shared import Commands, Parser

COMMAND_MODULES = (demo, trace, learn, reproduce, transfer, bench, match, setplay, serve, replay)
"""The command modules, in the order ``robotsoccer --help`` lists their commands."""


def build_parser() -> argparse.ArgumentParser:
    """The full command-line parser."""
    parser = Parser(
        prog="robotsoccer",
        description="Layered learning on soccer mini-robots: a pymunk robot testbed and a "
        "Soccer Server model behind one interface.",
        epilog="`robotsoccer COMMAND --help` describes a command and its options.",
    )
    parser.add_argument("--version", action="version", version=f"robotsoccer {__version__}")
    common = Parser(add_help=False)
    common.add_argument("--debug", action="store_true", help="show tracebacks of errors")
    table = parser.add_subparsers(dest="command", parser_class=Parser, metavar="COMMAND")
    commands = Commands(table, common)
    for module in COMMAND_MODULES:
        module.add_parser(commands)
    return parser
