"""The ``robotsoccer`` command line: demo, trace, learn, reproduce, transfer, bench, replay.

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
import contextlib
import json
import math
import os
import sys
import time
from collections import Counter
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any, NoReturn

from field_models.arena import MAX_BALL_NOISE, FieldOptions
from field_models.presets import PresetError
from field_models.protocol import PlayerRef
from field_models.registry import FIELD_MODELS, default_preset
from robotsoccer import __version__
from robotsoccer.drills import DRILLS, make_drill
from robotsoccer.options import MAX_COUNT, MAX_SEED, MAX_SIMULATED_S, MAX_WORKERS
from robotsoccer.runs.folders import prepare_run_folder, release_run_folders
from robotsoccer.runs.pool import default_workers, run_trials, using_backend
from robotsoccer.runs.ray_backend import require_ray
from robotsoccer.runs.runner import TrialResult, TrialSpec, build_trial
from robotsoccer.stats import wilson_interval

if TYPE_CHECKING:
    from robotsoccer.experiments.gap_closing import ParameterRange

DEFAULT_FIELD = "robot_physics"
"""The field model every command runs on unless told otherwise: the paper's mini-robots."""
PAPER_MODELS = ("soccer_server", "robot_physics")

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
        return _fail(EXIT_USAGE, str(exc))
    except BrokenPipeError:
        _silence_stdout()
        return EXIT_BROKEN_PIPE
    except OSError as exc:
        where = f" {exc.filename}" if exc.filename else ""
        return _fail(EXIT_FAILURE, f"{exc.strerror or exc}:{where}".rstrip(":"))
    except KeyboardInterrupt:
        return _fail(EXIT_INTERRUPTED, "interrupted")
    except Exception as exc:  # e.g. raised inside a worker: one line, the traceback on --debug
        return _fail(EXIT_FAILURE, f"{type(exc).__name__}: {exc} (--debug shows where)")


def _fail(status: int, message: str) -> int:
    first = message.strip().splitlines()[0] if message.strip() else "failed"
    with contextlib.suppress(BrokenPipeError):  # stderr closed too: nothing left to tell
        print(f"robotsoccer: error: {first}", file=sys.stderr)
    return status


def _silence_stdout() -> None:
    """After the reader closed the pipe, send what is left to /dev/null (no second error)."""
    devnull = os.open(os.devnull, os.O_WRONLY)
    os.dup2(devnull, sys.stdout.fileno())


# ----------------------------------------------------------------------------- demo


def spec_from(args: argparse.Namespace, **extra: Any) -> TrialSpec:
    """The TrialSpec a command's field and drill options describe."""
    field = FieldOptions(perfect_perception=args.perfect_perception, ball_noise=args.ball_noise)
    spec = TrialSpec(
        drill=args.drill,
        field_model=args.field,
        preset=args.field_preset,
        seed=args.seed,
        field=field,
        **extra,
    )
    return spec.with_options(**dict(args.option))


def cmd_demo(args: argparse.Namespace) -> int:
    """Run a drill's trials and print its summary table."""
    preset = args.field_preset or default_preset(args.field)
    run_name = f"{args.drill}-{args.field}-{Path(preset).stem}-seed{args.seed}"
    out = args.out or Path("runs") / run_name
    record_dir = out / "recordings" if args.record else None
    spec = spec_from(
        args,
        record_dir=str(record_dir) if record_dir else None,
        record_trials=args.record_trials if args.record else 0,
    )
    check_spec(spec)
    if args.backend == "ray":
        require_ray()  # without Ray: one line, before the run folder is touched
    prepare_run_folder(out, resume=args.resume, overwrite=args.overwrite)
    workers = args.workers or default_workers()
    results_path = out / "results.csv"
    tally = Tally()
    start = time.perf_counter()
    try:
        run_trials(
            spec,
            args.trials,
            workers=workers,
            results_path=results_path,
            resume=args.resume,
            progress=not args.quiet,
            keep=False,
            on_result=tally.add,
            backend=args.backend,
        )
    except KeyboardInterrupt:
        kept = f"; finished trials are kept in {results_path}" if results_path.exists() else ""
        return _fail(EXIT_INTERRUPTED, f"interrupted{kept} (--resume finishes the run)")
    wall = time.perf_counter() - start
    labels = make_drill(args.drill, dict(args.option)).labels
    print(tally.table(labels, title=f"{run_name}: {tally.n} trials"))
    print(
        f"\n{tally.simulated_s:.1f} simulated s in {wall:.1f} s wall with {workers} worker(s): "
        f"{tally.n / wall:.1f} trials/s"
    )
    print(f"results: {results_path}")
    if record_dir is not None:
        print(f"recordings: {record_dir}/ (open with: robotsoccer replay FILE)")
    return 0


def check_spec(spec: TrialSpec) -> None:
    """Set trial 0 up front so a bad preset, option or model fails here in one line."""
    rngs, drill, arena = build_trial(spec, 0)
    drill.setup(arena, rngs)
    drill.minds(arena, rngs)


class Tally:
    """Counts of a run's labels and its simulated time, built as results arrive."""

    def __init__(self) -> None:
        self.labels: Counter[str] = Counter()
        self.n = 0
        self.simulated_s = 0.0

    def add(self, result: TrialResult) -> None:
        """Count one result."""
        self.labels[result.label] += 1
        self.n += 1
        self.simulated_s += result.time_s

    def table(self, labels: Sequence[str], title: str) -> str:
        """A plain-text table: each label's count, share and 95% Wilson interval."""
        n = self.n
        lines = [title, f"{'label':<8}{'count':>7}{'share':>9}   95% interval"]
        for label in list(labels) + sorted(set(self.labels) - set(labels)):
            k = self.labels.get(label, 0)
            low, high = wilson_interval(k, n)
            share = 100.0 * k / n if n else 0.0
            lines.append(f"{label:<8}{k:>7}{share:>8.1f}%   [{100 * low:.1f}, {100 * high:.1f}]")
        return "\n".join(lines)


# ----------------------------------------------------------------------------- others


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


SERVE_PRESET = "rcssserver_19"
"""The preset ``serve`` runs unless told: today's server, what existing agents expect."""


def cmd_serve(args: argparse.Namespace) -> int:
    """Serve the Soccer Server model on UDP until a limit or Ctrl-C (:mod:`robotsoccer.serve`)."""
    from field_models.registry import entry
    from field_models.soccer_server.serving import ServedGame
    from field_models.soccer_server.udp import UdpServer
    from field_models.soccer_server.wire import server_params
    from robotsoccer.serve import GameRecorder, run_serve, stderr_log

    options = FieldOptions(perfect_perception=args.perfect_perception, ball_noise=args.ball_noise)
    preset = entry("soccer_server").load(args.field_preset, options)
    log = (lambda line: None) if args.quiet else stderr_log()
    if args.host != "127.0.0.1":
        log(f"binding {args.host}: reachable from other machines")
    overrides: dict[str, bool | int | float | str] = {
        "port": args.port,
        "coach_port": args.trainer_port,
        "olcoach_port": args.olcoach_port,
        "synch_mode": args.synch,
    }
    start = "play_on" if args.play_on else "before_kick_off"
    game = ServedGame(
        preset, seed=args.seed, synch=args.synch, log=log, overrides=overrides, start_mode=start
    )
    server = UdpServer(
        game,
        host=args.host,
        port=args.port,
        trainer_port=args.trainer_port,
        olcoach_port=args.olcoach_port,
        synch_timeout_s=args.synch_timeout,
        idle_timeout_s=args.idle_timeout,
        log=log,
    )
    recorder = None
    if args.record is not None:
        stem = f"serve_{time.strftime('%Y%m%d-%H%M%S')}_seed{args.seed}"
        params = server_params(preset, overrides)
        recorder = GameRecorder(args.record, stem, game.dt_s, params)
    return run_serve(
        server, game, cycles=args.cycles, seconds=args.seconds, recorder=recorder, log=log
    )


def cmd_replay(args: argparse.Namespace) -> int:
    """Open (or, headless, verify and explain how to open) a recording or a game log."""
    from robotsoccer.replay.recording import replay

    if args.file.suffix == ".rcg":
        from robotsoccer.replay.game_log import rrd_from_rcg

        return replay(rrd_from_rcg(args.file))
    return replay(args.file)


TEAM_KINDS = ("layered", "baseline")
"""The match drill's team kinds (:class:`robotsoccer.drills.match.TeamKind`)."""


def find_layers(args: argparse.Namespace) -> tuple[Path, Path]:
    """The layered team's net and tree: given, or the newest in a run folder's models.

    Raises:
        ValueError: None found (the message says how to make them).
    """
    if args.net is not None and args.tree is not None:
        return args.net, args.tree
    folders = (
        [args.models]
        if args.models is not None
        else [Path("runs") / f"{kind}-seed{args.seed}" for kind in ("reproduce", "transfer")]
    )
    for folder in folders:
        models = folder / "models" / args.field
        nets = sorted(models.glob("net_*.npz"), key=lambda p: _net_size(p.stem))
        tree = models / "pass_tree.json"
        if nets and tree.exists():
            return args.net or nets[-1], args.tree or tree
    where = ", ".join(str(f / "models" / args.field) for f in folders)
    raise ValueError(
        f"no trained layers for {args.field} in {where}: run `robotsoccer transfer "
        f"--no-ablations --no-gap-closing` first, or give --net and --tree"
    )


def _net_size(stem: str) -> int:
    tail = stem.rpartition("_")[2]
    return int(tail) if tail.isdigit() else -1


def cmd_match(args: argparse.Namespace) -> int:
    """One match, or a series of layered against baseline with its report."""
    from robotsoccer.experiments.match import run_series, write_report

    preset = args.field_preset or default_preset(args.field)
    layered = args.games > 1 or "layered" in (args.left, args.right)
    options: dict[str, Any] = {"players": args.players}
    if args.half_time is not None:
        options["half_time_s"] = args.half_time
    if layered:
        net, tree = find_layers(args)
        options |= {"net": str(net), "tree": str(tree)}
    kind = "series" if args.games > 1 else "match"
    out = args.out or Path("runs") / f"{kind}-{args.field}-{Path(preset).stem}-seed{args.seed}"
    record_dir = out / "recordings" if args.record else None
    base = TrialSpec(
        drill="match",
        field_model=args.field,
        preset=args.field_preset,
        seed=args.seed,
        field=FieldOptions(perfect_perception=args.perfect_perception, ball_noise=args.ball_noise),
        record_dir=str(record_dir) if record_dir else None,
        record_trials=1 if args.record else 0,
    ).with_options(**options)
    if args.games > 1:
        check_spec(base)
        prepare_run_folder(out, resume=args.resume, overwrite=args.overwrite)
        config = {"command": "robotsoccer match", "games": args.games, "field": args.field,
                  "preset": preset, "seed": args.seed, "options": options}  # fmt: skip
        (out / "config.json").write_text(json.dumps(config, indent=2) + "\n")
        start = time.perf_counter()
        try:
            games = run_series(
                base, args.games, out, workers=args.workers or default_workers(),
                resume=args.resume, progress=not args.quiet,
            )  # fmt: skip
        except KeyboardInterrupt:
            return _fail(EXIT_INTERRUPTED, f"interrupted; finished games are kept in {out}")
        title = f"Layered vs baseline on {args.field} ({Path(preset).stem}), seed {args.seed}"
        write_report(games, out, title, print)
        print(f"\n{len(games)} games in {time.perf_counter() - start:.1f} s; report: {out}")
    else:
        spec = base.with_options(left=args.left, right=args.right)
        check_spec(spec)
        prepare_run_folder(out, resume=args.resume, overwrite=args.overwrite)
        start = time.perf_counter()
        (result,) = run_trials(
            spec, 1, workers=1, results_path=out / "results.csv", resume=args.resume,
            progress=not args.quiet,
        )  # fmt: skip
        wall = time.perf_counter() - start
        print(f"{result.label}: {result.reason} ({result.time_s:.0f} simulated s in "
              f"{wall:.1f} s)")  # fmt: skip
        for name, value in result.measures:
            print(f"  {name} = {value:g}")
    if record_dir is not None:
        print(f"recordings: {record_dir}/ (open with: robotsoccer replay FILE)")
    return 0


def cmd_setplay(args: argparse.Namespace) -> int:
    """The set play on both field models, layered and baseline minds, with its report."""
    from robotsoccer.experiments.setplay import run_setplay_study

    folder = args.models or Path("runs") / f"transfer-seed{args.seed}"
    models: Path | None = folder / "models"
    if not all(
        (folder / "models" / m / f).exists()
        for m in PAPER_MODELS
        for f in ("net_750.npz", "pass_tree.json")
    ):
        if args.models is not None:
            raise UsageError(f"{folder}/models lacks a field's net_750.npz or pass_tree.json")
        print(f"no trained layers in {folder}/models: the baseline minds only", file=sys.stderr)
        models = None
    out = args.out or Path("runs") / f"setplay{'-quick' if args.quick else ''}-seed{args.seed}"
    prepare_run_folder(out, resume=args.resume, overwrite=args.overwrite)
    fields = [(m, default_preset(m)) for m in PAPER_MODELS]
    report = run_setplay_study(
        out, fields=fields, models=models, plays=args.plays, seed=args.seed,
        workers=args.workers or default_workers(), quick=args.quick, progress=True,
    )  # fmt: skip
    print(f"report: {report}")
    return 0


def cmd_learn(args: argparse.Namespace) -> int:
    """``learn intercept`` / ``learn pass``: one layer on one field model."""
    if args.target == "pass":
        return cmd_learn_pass(args)
    if args.target == "lead":
        return cmd_learn_lead(args)
    preset = args.field_preset or default_preset(args.field)
    tag = f"learn-intercept-{args.field}-{Path(preset).stem}" + ("-quick" if args.quick else "")
    out = args.out or Path("runs") / f"{tag}-seed{args.seed}"
    title = f"Layer 1 (interception) on {args.field}" + (" — quick plan" if args.quick else "")
    return _run_layer1(args, [(args.field, preset)], out, title, "robotsoccer learn intercept")


def cmd_learn_pass(args: argparse.Namespace) -> int:
    """``learn pass``: layer 2 on one field model (collect → train → evaluate → report)."""
    from robotsoccer.experiments.layer1 import plan_for, seeds_for, train_main_net
    from robotsoccer.experiments.layer2 import layer2_markdown, layer2_plan, run_layer2_model
    from robotsoccer.experiments.plots_layer2 import layer2_plots

    preset = args.field_preset or default_preset(args.field)
    tag = f"learn-pass-{args.field}-{Path(preset).stem}" + ("-quick" if args.quick else "")
    out = args.out or Path("runs") / f"{tag}-seed{args.seed}"
    check_spec(TrialSpec(drill="pass", field_model=args.field, preset=preset))
    if args.net is not None:
        check_spec(
            TrialSpec(drill="pass", field_model=args.field, preset=preset).with_options(
                interceptor="net", net=str(args.net)
            )
        )
    prepare_run_folder(out, resume=args.resume, overwrite=args.overwrite)
    plan = layer2_plan(args.quick)
    workers = args.workers or default_workers()
    seeds = seeds_for(args.seed)
    log = _clock_log()
    progress = sys.stderr.isatty()
    start = time.perf_counter()
    try:
        net = args.net
        if net is None:
            net = train_main_net(
                args.field, preset, plan_for(args.quick), out, seeds, workers, log, progress
            )
        section = run_layer2_model(
            args.field, preset, net, plan, out, seeds, workers, log, progress
        )
    except KeyboardInterrupt:
        return _fail(
            EXIT_INTERRUPTED,
            f"interrupted; finished trials are kept under {out} (--resume finishes the run)",
        )
    title = f"# Layer 2 (pass evaluation) on {args.field}" + (" — quick plan" if args.quick else "")
    report = out / "report.md"
    plots = layer2_plots([section], out)
    report.write_text(f"{title}\n\n{layer2_markdown([section], plan, plots)}")
    (out / "config.json").write_text(
        json.dumps({"plan": plan.to_dict(), "seed": args.seed, "net": str(net)}, indent=2) + "\n"
    )
    print()
    print(report.read_text())
    print(f"report: {report}  ({time.perf_counter() - start:.0f} s with {workers} worker(s))")
    return 0


def _lead_section(
    args: argparse.Namespace, out: Path, workers: int, log: Callable[[str], None]
) -> str:
    """The lead study (:mod:`robotsoccer.experiments.lead_study`) on the chosen fields."""
    from robotsoccer.experiments.layer1 import seeds_for
    from robotsoccer.experiments.lead_study import StudyDrill, plan_for, run_study

    field = getattr(args, "field", None)
    fields = [field] if field else list(LEAD_DRILLS)
    drills = [StudyDrill(f, *LEAD_DRILLS[f]) for f in fields]
    text, _ = run_study(drills, plan_for(args.quick), out, seeds_for(args.seed), workers, log)
    return text


def cmd_learn_lead(args: argparse.Namespace) -> int:
    """``learn lead``: layer 1's two decisions on one or both field models, with a report."""
    from robotsoccer.experiments.lead_study import plan_for

    fields = [args.field] if args.field else list(LEAD_DRILLS)
    tag = "learn-lead" + (f"-{args.field}" if args.field else "") + ("-quick" if args.quick else "")
    out = args.out or Path("runs") / f"{tag}-seed{args.seed}"
    prepare_run_folder(out, resume=args.resume, overwrite=args.overwrite)
    plan = plan_for(args.quick)
    workers = args.workers or default_workers()
    start = time.perf_counter()
    try:
        text = _lead_section(args, out, workers, _clock_log())
    except KeyboardInterrupt:
        return _fail(
            EXIT_INTERRUPTED,
            f"interrupted; finished trials are kept under {out} (--resume finishes the run)",
        )
    report = out / "report.md"
    report.write_text(
        f"# Layer 1: the lead decision{' — quick plan' if args.quick else ''}\n\n{text}"
    )
    (out / "config.json").write_text(
        json.dumps({"plan": plan.to_dict(), "seed": args.seed, "fields": fields}, indent=2) + "\n"
    )
    print()
    print(report.read_text())
    print(f"report: {report}  ({time.perf_counter() - start:.0f} s with {workers} worker(s))")
    return 0


def _clock_log() -> Callable[[str], None]:
    """A log that prefixes each line with the seconds since it was made."""
    start = time.perf_counter()

    def log(line: str) -> None:
        print(f"[{time.perf_counter() - start:6.1f} s] {line}", flush=True)

    return log


def cmd_reproduce(args: argparse.Namespace) -> int:
    """``reproduce``: all of layer 1 on both field models into one folder."""
    name = f"reproduce-quick-seed{args.seed}" if args.quick else f"reproduce-seed{args.seed}"
    out = args.out or Path("runs") / name
    models = [(model, default_preset(model)) for model in PAPER_MODELS]
    title = "Layers 1 and 2 reproduced (Stone & Veloso 1996, §5 and §6)" + (
        " — quick plan" if args.quick else ""
    )
    return _run_layer1(args, models, out, title, "robotsoccer reproduce", with_layer2=True)


def _run_layer1(
    args: argparse.Namespace,
    models: list[tuple[str, str]],
    out: Path,
    title: str,
    created_by: str,
    *,
    with_layer2: bool = False,
) -> int:
    from robotsoccer.experiments.layer1 import plan_for, run_layer1, seeds_for
    from robotsoccer.experiments.layer2 import layer2_markdown, layer2_plan, run_layer2_model
    from robotsoccer.experiments.plots_layer2 import layer2_plots

    for model, preset in models:  # a bad preset fails here with one line, not in a worker
        check_spec(TrialSpec(drill="intercept", field_model=model, preset=preset))
    prepare_run_folder(out, resume=args.resume, overwrite=args.overwrite)
    plan = plan_for(args.quick)
    workers = args.workers or default_workers()
    start = time.perf_counter()
    log = _clock_log()
    try:
        report, sections = run_layer1(
            models,
            plan,
            out,
            args.seed,
            workers,
            log,
            title=title,
            created_by=created_by,
            progress=sys.stderr.isatty(),
        )
        if with_layer2:
            plan2 = layer2_plan(args.quick)
            layer2 = [
                run_layer2_model(
                    s.field_model,
                    s.preset,
                    out / "models" / s.field_model / f"net_{s.net_examples}.npz",
                    plan2,
                    out,
                    seeds_for(args.seed),
                    workers,
                    log,
                    sys.stderr.isatty(),
                )
                for s in sections
            ]
            plots = layer2_plots(layer2, out)
            with report.open("a") as f:
                f.write("\n" + layer2_markdown(layer2, plan2, plots))
        if with_layer2 and not args.no_lead:
            section = _lead_section(args, out / "lead", workers, log)
            with report.open("a") as f:
                f.write("\n" + section)
        if with_layer2 and not args.no_transfer:
            section = _transfer_section(args, models, out, workers, created_by)
            with report.open("a") as f:
                f.write("\n" + section)
    except KeyboardInterrupt:
        return _fail(
            EXIT_INTERRUPTED,
            f"interrupted; finished trials are kept under {out} (--resume finishes the run)",
        )
    print()
    print(report.read_text())
    print(f"report: {report}  ({time.perf_counter() - start:.0f} s with {workers} worker(s))")
    return 0


def cmd_transfer(args: argparse.Namespace) -> int:
    """``transfer``: each field model's net and pass tree tested on every field model."""
    name = f"transfer-quick-seed{args.seed}" if args.quick else f"transfer-seed{args.seed}"
    out = args.out or Path("runs") / name
    models = [(model, default_preset(model)) for model in PAPER_MODELS]
    for model, preset in models:
        check_spec(TrialSpec(drill="intercept", field_model=model, preset=preset))
    prepare_run_folder(out, resume=args.resume, overwrite=args.overwrite)
    workers = args.workers or default_workers()
    start = time.perf_counter()
    try:
        section = _transfer_section(args, models, out, workers)
    except KeyboardInterrupt:
        return _fail(
            EXIT_INTERRUPTED,
            f"interrupted; finished trials are kept under {out} (--resume finishes the run)",
        )
    report = out / "report.md"
    title = "# The transfer study" + (" — quick plan" if args.quick else "")
    report.write_text(f"{title}\n\n{section}")
    print()
    print(report.read_text())
    print(f"report: {report}  ({time.perf_counter() - start:.0f} s with {workers} worker(s))")
    return 0


def server_ranges_covering_robots() -> tuple[ParameterRange, ...]:
    """Domain randomisation of the Soccer Server drill toward the robots (``transfer``).

    Not covered, because the Soccer Server model has no such parameter: the robots' camera
    latency, the time a robot takes to turn (the server turns within one cycle) and blocking
    without a kick.
    """
    from robotsoccer.experiments.gap_closing import ParameterRange

    return (
        ParameterRange(
            "dynamics.player_size_m", 0.8, 2.2,
            why="touch distance: 0.885 units on the server, 2.26 on the robots' table",
        ),
        ParameterRange(
            "dynamics.dash_power_rate_m_per_cycle2", 0.001, 0.01, log=True,
            why="reach after the trigger: about 25 units at the server's top speed, under 2 for "
            "the robots (0.18 s of flight at 115 units/s²)",
        ),
        ParameterRange(
            "dynamics.player_decay", 0.4, 0.8,
            why="inertia: a robot needs 0.4 s to top speed, longer than the ball's 0.18 s",
        ),
        ParameterRange(
            "sensing.send_step_ms", 150, 300, step=50,
            why="percepts from the trigger to the ball's arrival: 6.5 on the server, about 5.4 "
            "on the robots",
        ),
        ParameterRange(
            "dynamics.ball_decay", 0.95, 0.99,
            why="how fast the ball slows over its flight (below 0.94 the literal drill's "
            "power-100 kick stops short of 25 units)",
        ),
    )  # fmt: skip


def _transfer_section(
    args: argparse.Namespace,
    models: list[tuple[str, str]],
    out: Path,
    workers: int,
    created_by: str = "robotsoccer transfer",
) -> str:
    """Run the transfer study into `out` (the options say which parts) and return its text."""
    from robotsoccer.experiments.gap_closing import Randomisation
    from robotsoccer.experiments.layer1 import seeds_for
    from robotsoccer.experiments.transfer_study import StudyParts, run_transfer_study

    fields = dict(models)
    reference = ("soccer_server", fields["soccer_server"])
    target = ("robot_physics", fields["robot_physics"])
    randomisation = Randomisation(
        reference[1], server_ranges_covering_robots(), variants=4 if args.quick else 10
    )
    parts = StudyParts(
        ablations=not getattr(args, "no_ablations", False),
        gap_closing=not getattr(args, "no_gap_closing", False),
    )
    return run_transfer_study(
        reference,
        target,
        randomisation,
        args.quick,
        out,
        seeds_for(args.seed),
        workers,
        _clock_log(),
        parts,
        created_by,
        sys.stderr.isatty(),
    )


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


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
