"""What every command's parser shares: the parser class, the command table, the shared options.

Each command module (:mod:`robotsoccer.cli.commands`) adds its own parser through
:class:`Commands` and takes the option groups it shares with others from here, so each shared
option is defined once: the field (:func:`field_options`), the drill (:func:`drill_options`),
the run folder and workers (:func:`run_options`), an experiment's plan and seed
(:func:`experiment_options`) and the transfer study's parts (:func:`transfer_options`). The
option types and their bounds are in :mod:`robotsoccer.cli.options`.
"""

from __future__ import annotations

import argparse
from dataclasses import dataclass
from pathlib import Path
from typing import Any, NoReturn

from field_models.registry import FIELD_MODELS
from robotsoccer.cli.options import (
    DEFAULT_FIELD,
    EXIT_USAGE,
    _drill_option,
    _index,
    _noise,
    _workers,
)
from robotsoccer.drills import DRILLS


class _Help(argparse.HelpFormatter):
    """Help that shows each option's default, where it has one worth showing."""

    def _get_help_string(self, action: argparse.Action) -> str | None:
        text = action.help or ""
        default = action.default
        unshown = default is None or default is False or default == [] or "%(default)" in text
        if unshown or default is argparse.SUPPRESS:
            return text
        return f"{text} (default: %(default)s)"


class Parser(argparse.ArgumentParser):
    """An argument parser whose errors are one line and exit 2, and whose help shows defaults."""

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        kwargs.setdefault("formatter_class", _Help)
        super().__init__(*args, **kwargs)

    def error(self, message: str) -> NoReturn:
        """Print the usage error as one line and exit with the usage status."""
        self.exit(EXIT_USAGE, f"{self.prog}: error: {message}\n")


@dataclass(frozen=True)
class Commands:
    """Where a command module adds its parser: the command table and the options all share.

    Attributes:
        table: The top parser's sub-commands.
        common: The parent parser of every command (``--debug``).
    """

    table: argparse._SubParsersAction[Parser]
    common: Parser

    def add(self, name: str, summary: str) -> argparse.ArgumentParser:
        """A command's parser, with `summary` as its help line and description."""
        return self.table.add_parser(name, help=summary, description=summary, parents=[self.common])


def transfer_options(p: argparse.ArgumentParser) -> None:
    """The transfer study's parts, each of which can be left out."""
    p.add_argument(
        "--no-ablations", action="store_true", help="the transfer study without the ablations"
    )
    p.add_argument(
        "--no-gap-closing",
        action="store_true",
        help="the transfer study without fine-tuning and domain randomisation",
    )
    p.add_argument(
        "--no-lead-transfer",
        action="store_true",
        help="the transfer study without the lead decision's matrix (and its calibration)",
    )
    p.add_argument(
        "--no-calibration",
        action="store_true",
        help="the lead matrix without the Soccer Server calibrated to robot traces",
    )


def field_options(p: argparse.ArgumentParser) -> None:
    """The field model, its preset, the seed and the sensor's options."""
    p.add_argument("--field", default=DEFAULT_FIELD, choices=FIELD_MODELS, help="field model")
    p.add_argument(
        "--field-preset", default=None, help="preset name, .toml or server.conf (model's default)"
    )
    p.add_argument("--seed", type=_index, default=0, help="experiment seed")
    p.add_argument(
        "--ball-noise", type=_noise, default=None, help="ball noise (preset's when not given)"
    )
    p.add_argument(
        "--perfect-perception", action="store_true", help="sensor without noise or latency"
    )


def drill_options(p: argparse.ArgumentParser) -> None:
    """The drill and its ``--option NAME=VALUE`` list."""
    p.add_argument("--drill", default="shootout", choices=sorted(DRILLS), help="the drill")
    p.add_argument(
        "--option",
        action="append",
        default=[],
        type=_drill_option,
        metavar="NAME=VALUE",
        help="drill option, e.g. behaviour=net (repeatable)",
    )


def run_options(p: argparse.ArgumentParser, *, backend: bool = False) -> None:
    """Workers, (with `backend`) where trials run, and the run folder."""
    p.add_argument("--workers", type=_workers, default=None, help="processes (all cores)")
    if backend:
        p.add_argument(
            "--backend",
            default="process",
            choices=("process", "ray"),
            help="where trials run: a process pool here, or Ray (a cluster if RAY_ADDRESS is set)",
        )
    p.add_argument("--out", type=Path, default=None, help="run folder (under runs/)")
    p.add_argument("--resume", action="store_true", help="continue the run in --out")
    p.add_argument("--overwrite", action="store_true", help="replace the run in --out")


def experiment_options(p: argparse.ArgumentParser) -> None:
    """An experiment's plan (``--quick``), its seed and the run options with the backend."""
    p.add_argument(
        "--quick",
        action="store_true",
        help="quick plan: layer 1 200 trials per condition, 1500 saves; layer 2 1000 training "
        "and 500 test trials per condition",
    )
    p.add_argument("--seed", type=_index, default=0, help="experiment seed")
    run_options(p, backend=True)
