"""The CLI package's shape: one module per command, holding its parser and its function."""

from __future__ import annotations

import argparse

from robotsoccer.cli import COMMANDS, build_parser
from robotsoccer.cli.parser import COMMAND_MODULES
from robotsoccer.cli.shared import Commands, Parser


def _parsers(parser: argparse.ArgumentParser) -> dict[str, argparse.ArgumentParser]:
    (table,) = (a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    return dict(table.choices)


def test_every_command_has_a_parser_and_a_function() -> None:
    assert sorted(_parsers(build_parser())) == sorted(COMMANDS)


def test_each_command_module_adds_one_command_whose_function_it_holds() -> None:
    # A module that added two commands, or a command run by another module's function, would
    # bring back the grouped modules the CLI was split from.
    added = []
    for module in COMMAND_MODULES:
        parser = Parser()
        table = parser.add_subparsers(dest="command", parser_class=Parser)
        module.add_parser(Commands(table, Parser(add_help=False)))
        (name,) = _parsers(parser)
        assert COMMANDS[name].__module__ == module.__name__
        added.append(name)
    assert sorted(added) == sorted(COMMANDS)
