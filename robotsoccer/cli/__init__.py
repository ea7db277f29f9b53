"""The ``robotsoccer`` command line: demo, trace, learn, reproduce, transfer, bench, replay, ...

A package: the top parser in :mod:`.parser`, the options several commands share (defined
once) in :mod:`.shared`, their types, bounds and the exit statuses in :mod:`.options`, what
every command does around its work in :mod:`.running`, and the commands in :mod:`.commands`,
one module per command, each with its own parser and its function; :func:`main` dispatches
through :data:`COMMANDS`.

Every error reaches the user as one line and a non-zero exit status, never a traceback (unless
``--debug`` is given): a wrong option, preset or model file exits with 2; a file-system error
or an error raised inside a worker with 1; Ctrl-C with 130, after keeping every finished trial;
a closed output pipe (``robotsoccer demo | head``) with 141.

Run folders are never mixed or silently replaced (:mod:`robotsoccer.runs.folders`): a folder
that holds a run is continued with ``--resume`` (only if the same run made it) or replaced with
``--overwrite``.

``learn intercept`` and ``reproduce`` run layer 1 of the paper (§5) through
:mod:`robotsoccer.experiments.layer1`, ``learn pass`` and ``reproduce`` layer 2 (§6) through
:mod:`robotsoccer.experiments.layer2`: collect, train, evaluate every condition and
write one folder with ``report.md``, plots, models and recordings.
"""

from __future__ import annotations

import argparse
import os
from collections.abc import Callable, Sequence

from field_models.presets import PresetError
from robotsoccer.cli.commands.bench import cmd_bench
from robotsoccer.cli.commands.demo import cmd_demo
from robotsoccer.cli.commands.learn import cmd_learn
from robotsoccer.cli.commands.match import cmd_match
from robotsoccer.cli.commands.replay import cmd_replay
from robotsoccer.cli.commands.reproduce import cmd_reproduce
from robotsoccer.cli.commands.serve import cmd_serve
from robotsoccer.cli.commands.setplay import cmd_setplay
from robotsoccer.cli.commands.trace import cmd_trace
from robotsoccer.cli.commands.transfer import cmd_transfer, server_ranges_covering_robots
from robotsoccer.cli.options import (
    EXIT_BROKEN_PIPE,
    EXIT_FAILURE,
    EXIT_INTERRUPTED,
    EXIT_USAGE,
    _index,
    _noise,
    _positive_float,
    _positive_int,
)
from robotsoccer.cli.parser import build_parser
from robotsoccer.cli.running import fail, silence_stdout
from robotsoccer.runs.folders import release_run_folders
from robotsoccer.runs.pool import using_backend
from robotsoccer.runs.ray_backend import require_ray

__all__ = [
    "COMMANDS",
    "_index",
    "_noise",
    "_positive_float",
    "_positive_int",
    "build_parser",
    "main",
    "server_ranges_covering_robots",
]


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of the ``robotsoccer`` console script (module docstring: exit statuses)."""
    parser = build_parser()
    args = parser.parse_args(argv)
    if not getattr(args, "debug", False):
        # Rerun's Rust logger prints coloured lines of its own (a full disk during a recording)
        # before our one-line error. It reads RUST_LOG when rerun is first imported, which is
        # later, in this process or a worker; a RUST_LOG the user set is kept.
        os.environ.setdefault("RUST_LOG", "off")
    if args.command is None:
        parser.print_help()
        return EXIT_USAGE
    command: Callable[[argparse.Namespace], int] = COMMANDS[args.command]

    def run(args: argparse.Namespace) -> int:
        backend = getattr(args, "backend", "process")
        if backend == "ray":
            require_ray()  # without Ray: one line, before any run folder is touched
        try:
            with using_backend(backend):
                return command(args)
        finally:
            release_run_folders()  # the command's run folder is free for the next one

    if args.debug:
        return run(args)
    try:
        return run(args)
    except (PresetError, ValueError) as exc:
        return fail(EXIT_USAGE, str(exc))
    except BrokenPipeError:
        silence_stdout()
        return EXIT_BROKEN_PIPE
    except OSError as exc:
        where = f" {exc.filename}" if exc.filename else ""
        return fail(EXIT_FAILURE, f"{exc.strerror or exc}:{where}".rstrip(":"))
    except KeyboardInterrupt:
        return fail(EXIT_INTERRUPTED, "interrupted")
    except Exception as exc:  # e.g. raised inside a worker: one line, the traceback on --debug
        return fail(EXIT_FAILURE, f"{type(exc).__name__}: {exc} (--debug shows where)")


COMMANDS: dict[str, Callable[[argparse.Namespace], int]] = {
    "demo": cmd_demo,
    "trace": cmd_trace,
    "learn": cmd_learn,
    "reproduce": cmd_reproduce,
    "transfer": cmd_transfer,
    "bench": cmd_bench,
    "replay": cmd_replay,
    "match": cmd_match,
    "setplay": cmd_setplay,
    "serve": cmd_serve,
}
"""Each command's function, by name."""
