"""The command line's shared parts: the parser and the options every command shares.

Exit statuses, the option types with their bounds, the parser with the options defined once, and
the field models the commands run by name (the one place above the percept/action line that
names them: ``tests/test_boundaries.py``).
"""

from __future__ import annotations

import argparse
import math
from pathlib import Path
from typing import TYPE_CHECKING, Any, NoReturn

from field_models.arena import MAX_BALL_NOISE
from field_models.registry import FIELD_MODELS
from robotsoccer import __version__
from robotsoccer.drills import DRILLS
from robotsoccer.options import MAX_COUNT, MAX_SEED, MAX_SIMULATED_S, MAX_WORKERS

if TYPE_CHECKING:
    pass


DEFAULT_FIELD = "robot_physics"
"""The field model every command runs on unless told otherwise: the paper's mini-robots."""
PAPER_MODELS = ("soccer_server", "robot_physics")

TEAM_FIELD = "soccer_server"
"""Where ``reproduce`` runs layer 3: the 11-a-side match of the paper's §7 and of TPOT-RL."""
REFERENCE_FIELD, TARGET_FIELD = "soccer_server", "robot_physics"
"""The transfer study's source of randomised variants and the field it closes the gap on."""

LEAD_DRILLS: dict[str, tuple[str, tuple[tuple[str, str | float], ...], str]] = {
    "robot_physics": (
        "small_size_1997_arc",
        (
            ("shot", "goal_mouth"),
            ("scaling", "task"),
            ("launch", "coach"),
            ("launch_speed_mps", 0.6),
            ("launch_speed_max_mps", 1.2),
        ),
        "shots across the goal mouth at 0.6-1.2 m/s from 0.52-0.78 m, arcs, 30 Hz camera",
    ),
    "soccer_server": (
        "soccer_server_1996",
        (),
        "the paper's drill (§5), shots at the defender",
    ),
}
"""The lead study's drill on each field: (preset, drill options, summary)
(:mod:`robotsoccer.experiments.lead_study`, whose docstring gives the numbers' sources)."""
"""The field models ``reproduce`` runs, in report order."""
BENCH_TARGETS = {
    "robot_physics.realtime_factor.2_robots": (">=", 300.0),
    "robot_physics.realtime_factor.12_robots": (">=", 60.0),
    "robot_physics.share_of_chipmunk.2_robots": (">=", 0.5),
    "robot_physics.share_of_chipmunk.12_robots": (">=", 0.4),
    "soccer_server.cycles_per_s.2_players": (">=", 30_000.0),
    "soccer_server.object_cycles_per_s.batch": (">=", 2_000_000.0),
    "intercept.trials_per_s.soccer_server": (">=", 3_000.0),
    "intercept.trials_per_s.robot_physics": (">=", 100.0),
    "intercept.trials_per_s.soccer_server_batch": (">=", 90_000.0),
    "pass.trials_per_s.soccer_server": (">=", 300.0),
    "pass.trials_per_s.robot_physics": (">=", 40.0),
    "training.net_1000_saves_s": ("<=", 5.0),
    "match.wall_s.soccer_server": ("<=", 60.0),
    "match.realtime_factor.robot_physics": (">=", 50.0),
    "envs.score_env_to_bare_ratio.robot_physics": (">=", 0.8),
    "envs.score_env_to_bare_ratio.soccer_server": (">=", 0.8),
}
"""What ``robotsoccer bench`` checks each figure against."""

EXIT_USAGE, EXIT_FAILURE, EXIT_INTERRUPTED, EXIT_BROKEN_PIPE = 2, 1, 130, 141
"""Exit statuses: bad input; a failure while running; Ctrl-C; the output pipe closed."""


class UsageError(ValueError):
    """A user error reported as one line (exit status 2)."""


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


# ----------------------------------------------------------------------------- option types


def _positive_int(text: str, most: int = MAX_COUNT) -> int:
    value = _int(text)
    if not 0 < value <= most:
        raise argparse.ArgumentTypeError(f"expected a whole number > 0 and <= {most}, got {text!r}")
    return value


def _workers(text: str) -> int:
    return _positive_int(text, MAX_WORKERS)


def _positive_float(text: str) -> float:
    """A simulated duration [s] (``--half-time``): finite, > 0 and within the sane limit."""
    try:
        value = float(text)
    except ValueError:
        value = math.nan
    if not math.isfinite(value) or not 0.0 < value <= MAX_SIMULATED_S:
        raise argparse.ArgumentTypeError(
            f"expected a finite number > 0 and <= {MAX_SIMULATED_S:g}, got {text!r}"
        )
    return value


def _port(text: str) -> int:
    value = _int(text)
    if not 0 <= value <= 65535:
        raise argparse.ArgumentTypeError(f"a UDP port is 0..65535 (0: any free one), got {value}")
    return value


def _index(text: str) -> int:
    value = _int(text)
    if not 0 <= value <= MAX_SEED:
        raise argparse.ArgumentTypeError(f"expected a whole number >= 0 and < 2**64, got {text!r}")
    return value


def _int(text: str) -> int:
    try:
        return int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a whole number, got {text!r}") from None


def _noise(text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        value = math.nan
    if not math.isfinite(value) or not 0.0 <= value <= MAX_BALL_NOISE:
        raise argparse.ArgumentTypeError(
            f"expected a finite number >= 0 and <= {MAX_BALL_NOISE:g}, got {text!r}"
        )
    return value


def _drill_option(text: str) -> tuple[str, str | float | int | bool]:
    """``name=value`` → (name, value as bool, int, float or str)."""
    name, sep, raw = text.partition("=")
    if not sep or not name:
        raise argparse.ArgumentTypeError(f"expected NAME=VALUE, got {text!r}")
    if raw.lower() in ("true", "false"):
        return name, raw.lower() == "true"
    for kind in (int, float):
        try:
            value = kind(raw)
        except ValueError:
            continue
        if isinstance(value, float) and not math.isfinite(value):
            raise argparse.ArgumentTypeError(f"{name}: expected a finite number, got {raw!r}")
        return name, value
    return name, raw


# ----------------------------------------------------------------------------- the parser


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
    team.add_argument("--field", default="soccer_server", choices=FIELD_MODELS, help="field model")
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
        help="soccer_server preset name, .toml or server.conf",
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


# ----------------------------------------------------------------------------- main


TEAM_KINDS = ("layered", "baseline", "layer3")
"""The match drill's team kinds (:class:`robotsoccer.drills.match.TeamKind`)."""


SERVE_PRESET = "rcssserver_19"
"""The preset ``serve`` runs unless told: today's server, what existing agents expect."""
