"""The command-line parser: every command and its options, the shared ones defined once.

The option types, their bounds, the exit statuses and the field models the commands run by name
live in :mod:`robotsoccer.cli.options`; this module only builds the parser from them
(:func:`build_parser`).
"""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import Any, NoReturn

from field_models.registry import FIELD_MODELS
from robotsoccer import __version__
from robotsoccer.cli.options import (
    DEFAULT_FIELD,
    EXIT_USAGE,
    SERVE_FIELD,
    SERVE_PRESET,
    TEAM_FIELD,
    TEAM_KINDS,
    _drill_option,
    _index,
    _noise,
    _port,
    _positive_float,
    _positive_int,
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


class _Parser(argparse.ArgumentParser):
    """An argument parser whose errors are one line and exit 2, and whose help shows defaults."""

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        kwargs.setdefault("formatter_class", _Help)
        super().__init__(*args, **kwargs)

    def error(self, message: str) -> NoReturn:
        self.exit(EXIT_USAGE, f"{self.prog}: error: {message}\n")


def build_parser() -> argparse.ArgumentParser:
    """The full command-line parser."""
    parser = _Parser(
        prog="robotsoccer",
        description="Layered learning on soccer mini-robots: a pymunk robot testbed and a "
        "Soccer Server model behind one interface.",
        epilog="`robotsoccer COMMAND --help` describes a command and its options.",
    )
    parser.add_argument("--version", action="version", version=f"robotsoccer {__version__}")
    common = _Parser(add_help=False)
    common.add_argument("--debug", action="store_true", help="show tracebacks of errors")
    commands = parser.add_subparsers(dest="command", parser_class=_Parser, metavar="COMMAND")

    def command(name: str, summary: str) -> argparse.ArgumentParser:
        return commands.add_parser(name, help=summary, description=summary, parents=[common])

    demo = command("demo", "run a drill's trials headless and print its labels' shares")
    _field_options(demo)
    _drill_options(demo)
    demo.add_argument("--trials", type=_positive_int, default=200, help="how many trials")
    _run_options(demo, backend=True)
    demo.add_argument("--record", action="store_true", help="write rerun recordings")
    demo.add_argument(
        "--record-trials", type=_positive_int, default=3, help="record this many first trials"
    )
    demo.add_argument("--quiet", action="store_true", help="no progress")

    trace = command("trace", "print a paper-style trace (Figure 4) of one trial")
    _field_options(trace)
    _drill_options(trace)
    trace.add_argument("--trial", type=_index, default=0, help="trial index")
    trace.add_argument("--player", default=None, help="client to trace, e.g. left1 (first)")

    learn = command("learn", "learn a layer: collect, train, evaluate, report")
    targets = learn.add_subparsers(dest="target", required=True, parser_class=_Parser)
    intercept = targets.add_parser(
        "intercept", help="layer 1: the interception net (paper §5)", parents=[common]
    )
    intercept.add_argument(
        "--field", default=DEFAULT_FIELD, choices=FIELD_MODELS, help="field model"
    )
    intercept.add_argument(
        "--field-preset", default=None, help="preset name, .toml or server.conf (model's default)"
    )
    intercept.add_argument(
        "--client",
        default="see",
        choices=("see", "cycle"),
        help="the defender's client: see (the paper's: turn, then dash, at each see) or cycle "
        "(a command every cycle, issue 28)",
    )
    _experiment_options(intercept)
    passing = targets.add_parser(
        "pass", help="layer 2: the pass-evaluation tree (paper §6)", parents=[common]
    )
    passing.add_argument("--field", default=DEFAULT_FIELD, choices=FIELD_MODELS, help="field model")
    passing.add_argument(
        "--field-preset", default=None, help="preset name, .toml or server.conf (model's default)"
    )
    passing.add_argument(
        "--net",
        type=Path,
        default=None,
        help="layer 1's interception net (.npz) for receivers and defenders (default: train it)",
    )
    _experiment_options(passing)

    lead = targets.add_parser(
        "lead",
        help="layer 1 with the lead decision beside the paper's turn angle, both field models",
        parents=[common],
    )
    lead.add_argument(
        "--field",
        default=None,
        choices=FIELD_MODELS,
        help="one field model (default: both)",
    )
    _experiment_options(lead)

    team = targets.add_parser(
        "team",
        help="layer 3: TPOT-RL's ball destinations learned in games against the baseline, "
        "then series against the layered team and the baseline",
        parents=[common],
    )
    team.add_argument("--field", default=TEAM_FIELD, choices=FIELD_MODELS, help="field model")
    team.add_argument(
        "--field-preset", default=None, help="preset name, .toml or server.conf (model's default)"
    )
    team.add_argument("--net", type=Path, default=None, help="layer 1's net (.npz)")
    team.add_argument("--tree", type=Path, default=None, help="layer 2's pass tree (.json)")
    team.add_argument(
        "--models",
        type=Path,
        default=None,
        help="run folder with models/<field>/ holding the net and pass tree (as `match`)",
    )
    team.add_argument(
        "--table",
        type=Path,
        default=None,
        help="a learned layer-3 table (.npz): skip training, play the series only",
    )
    team.add_argument(
        "--every",
        action="store_true",
        help="TPOT-RL's own rule: the holder chooses a destination on every spell on the ball "
        "(shoot and keep included), not only where the layered team would ask the tree",
    )
    team.add_argument(
        "--window",
        choices=("choice", "horizon"),
        default="choice",
        help="when a reward closes: choice (also at the player's next choice, the first "
        "studies') or horizon (only at 30 s, a goal or play stopping: TPOT-RL's fixed window)",
    )
    team.add_argument(
        "--shot-guard",
        action="store_true",
        help="with --every: the goal is a shot only within the teams' shooting range, beyond "
        "it an advance toward the goal (a pass toward it, else a dribble)",
    )
    team.add_argument(
        "--loss-penalty",
        type=float,
        default=0.0,
        help="reward possession: an opponent's touch closes a choice's reward, which loses up "
        "to this much (0..1; default 0: the ball's advance alone)",
    )
    team.add_argument(
        "--games-per-round",
        type=_positive_int,
        default=None,
        help="training games that share one table before it learns from them (default 4); "
        "up to this many play at once, so a many-core machine needs it at least its workers",
    )
    team.add_argument(
        "--training-games",
        type=_positive_int,
        default=None,
        help="training games instead of the plan's (400 with --every, 240 without)",
    )
    _experiment_options(team)

    reproduce = command(
        "reproduce",
        "layers 1 and 2 on both field models, then the transfer study: report, plots",
    )
    _experiment_options(reproduce)
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
    _transfer_options(reproduce)
    transfer = command(
        "transfer",
        "the transfer matrix: each field model's net and pass tree on every model; then the "
        "ablations of the robots' interception drill",
    )
    _experiment_options(transfer)
    _transfer_options(transfer)

    bench = command("bench", "measure speed, each figure beside its target")
    bench.add_argument("--json", action="store_true", help="print one JSON object at the end")
    bench.add_argument("--quick", action="store_true", help="one short repeat of each figure")

    match = command(
        "match",
        "play a match (or a series: --games N) between the layered team and the baseline",
    )
    _field_options(match)
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
        "dead_band=true, turn_latency=reckon, client=cycle (repeatable; a team's own: "
        "left/right as the value where it takes one)",
    )
    _run_options(match)

    setplay = command(
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
    setplay.add_argument("--seed", type=_index, default=0, help="experiment seed")
    _run_options(setplay)

    serve = command(
        "serve",
        "serve the Soccer Server model over UDP in rcssserver's protocol: players, a trainer, "
        "monitors",
    )
    serve.add_argument(
        "--field-preset",
        default=SERVE_PRESET,
        help=f"{SERVE_FIELD} preset name, .toml or server.conf",
    )
    serve.add_argument("--seed", type=_index, default=0, help="seed of the server's noise")
    serve.add_argument(
        "--ball-noise", type=_noise, default=None, help="ball noise (preset's when not given)"
    )
    serve.add_argument(
        "--perfect-perception", action="store_true", help="sees without quantisation or fading"
    )
    serve.add_argument(
        "--host", default="127.0.0.1", help="address to bind (another than 127.0.0.1: on purpose)"
    )
    serve.add_argument("--port", type=_port, default=6000, help="player and monitor port")
    serve.add_argument("--trainer-port", type=_port, default=6001, help="trainer port")
    serve.add_argument("--olcoach-port", type=_port, default=6002, help="online-coach port")
    serve.add_argument(
        "--synch", action="store_true", help="synch mode: a cycle as soon as every client is done"
    )
    serve.add_argument(
        "--synch-timeout", type=_positive_float, default=1.25, help="synch: step anyway after [s]"
    )
    serve.add_argument(
        "--idle-timeout", type=_positive_float, default=30.0, help="drop a client silent for [s]"
    )
    serve.add_argument(
        "--play-on", action="store_true", help="start in play_on (default: before_kick_off)"
    )
    serve.add_argument("--cycles", type=_positive_int, default=None, help="stop after N cycles")
    serve.add_argument("--seconds", type=_positive_float, default=None, help="stop after [s]")
    serve.add_argument(
        "--record",
        type=Path,
        nargs="?",
        const=Path("recordings"),
        default=None,
        metavar="DIR",
        help="write the game as .rcg and .rrd into DIR (recordings/)",
    )
    serve.add_argument("--quiet", action="store_true", help="no log lines")

    replay = command("replay", "open a recording (.rrd, or a .rcg game log) in the rerun viewer")
    replay.add_argument("file", type=Path, help="a .rrd recording or .rcg game log")
    return parser


def _transfer_options(p: argparse.ArgumentParser) -> None:
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


def _field_options(p: argparse.ArgumentParser) -> None:
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


def _drill_options(p: argparse.ArgumentParser) -> None:
    p.add_argument("--drill", default="shootout", choices=sorted(DRILLS), help="the drill")
    p.add_argument(
        "--option",
        action="append",
        default=[],
        type=_drill_option,
        metavar="NAME=VALUE",
        help="drill option, e.g. behaviour=net (repeatable)",
    )


def _run_options(p: argparse.ArgumentParser, *, backend: bool = False) -> None:
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


def _experiment_options(p: argparse.ArgumentParser) -> None:
    p.add_argument(
        "--quick",
        action="store_true",
        help="quick plan: layer 1 200 trials per condition, 1500 saves; layer 2 1000 training "
        "and 500 test trials per condition",
    )
    p.add_argument("--seed", type=_index, default=0, help="experiment seed")
    _run_options(p, backend=True)
