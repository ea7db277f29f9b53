"""The ``robotsoccer`` command line: demo, trace, learn, reproduce, bench, replay.

Bad input never ends in a traceback: a wrong option, an unknown preset or a wrong preset file
prints one line naming what is wrong and exits with status 2. Ctrl-C during a run keeps every
finished trial in the results table and exits with status 130.

``learn intercept`` and ``reproduce`` run layer 1 of the paper (§5) through
:mod:`robotsoccer.experiments.layer1`: collect saves, train nets, evaluate every condition and
write one folder with ``report.md``, plots, models and recordings; rerunning resumes.
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from collections import Counter
from collections.abc import Sequence
from dataclasses import asdict
from pathlib import Path
from typing import NoReturn

from field_models.arena import FieldOptions
from field_models.presets import PresetError
from field_models.protocol import PlayerRef
from field_models.registry import FIELD_MODELS, default_preset
from robotsoccer.drills import DRILLS, make_drill
from robotsoccer.runs.pool import default_workers, run_trials
from robotsoccer.runs.runner import TrialResult, TrialSpec, build_trial
from robotsoccer.stats import wilson_interval

DEMO_FIELD = "robot_physics"
"""The field model the demo (and the demo benchmark) runs on by default: the paper's robots."""
PAPER_MODELS = ("soccer_server", "robot_physics")
"""The field models ``reproduce`` runs, in report order."""
BENCH_TARGETS = {
    "robot_physics.realtime_factor.2_robots": (">=", 300.0),
    "robot_physics.realtime_factor.12_robots": (">=", 60.0),
    "soccer_server.cycles_per_s.2_players": (">=", 30_000.0),
    "soccer_server.object_cycles_per_s.batch": (">=", 2_000_000.0),
    "intercept.trials_per_s.soccer_server": (">=", 3_000.0),
    "intercept.trials_per_s.robot_physics": (">=", 100.0),
    "training.net_1000_saves_s": ("<=", 5.0),
}
"""What ``robotsoccer bench`` checks each figure against."""


class UsageError(Exception):
    """A user error reported as one line (exit status 2)."""


class _Parser(argparse.ArgumentParser):
    """An argument parser whose errors are one line and exit 2, without the usage dump."""

    def error(self, message: str) -> NoReturn:
        self.exit(2, f"{self.prog}: error: {message}\n")


def build_parser() -> argparse.ArgumentParser:
    """The full command-line parser."""
    parser = _Parser(prog="robotsoccer", description=__doc__.splitlines()[0])
    commands = parser.add_subparsers(dest="command", required=True, parser_class=_Parser)

    demo = commands.add_parser("demo", help="run the shootout demo drill headless")
    _add_run_options(demo, default_trials=200)
    demo.add_argument("--drill", default="shootout", choices=sorted(DRILLS))

    bench = commands.add_parser("bench", help="measure speed (simulated s per wall s, trials/s)")
    bench.add_argument("--json", action="store_true", help="print one JSON object")
    bench.add_argument("--quick", action="store_true", help="one short repeat of each figure")

    trace = commands.add_parser("trace", help="print a paper-style trace (Figure 4) of a trial")
    trace.add_argument("--field", default="soccer_server", choices=FIELD_MODELS)
    trace.add_argument("--field-preset", default=None, help="preset name or .toml path")
    trace.add_argument("--drill", default="shootout", choices=sorted(DRILLS))
    trace.add_argument("--seed", type=int, default=0)
    trace.add_argument("--trial", type=int, default=0, help="trial index")
    trace.add_argument("--player", default=None, help="client to trace, e.g. left1")
    trace.add_argument("--ball-noise", type=float, default=None, help="override ball noise")
    trace.add_argument(
        "--option",
        action="append",
        default=[],
        type=_drill_option,
        metavar="NAME=VALUE",
        help="drill option, e.g. behaviour=net (repeatable)",
    )

    replay = commands.add_parser("replay", help="open a recording in the rerun viewer")
    replay.add_argument("file", type=Path)

    learn = commands.add_parser("learn", help="learn a layer: collect, train, evaluate, report")
    targets = learn.add_subparsers(dest="target", required=True, parser_class=_Parser)
    intercept = targets.add_parser("intercept", help="layer 1: the interception net (paper §5)")
    intercept.add_argument("--field", required=True, choices=FIELD_MODELS, help="field model")
    intercept.add_argument("--field-preset", default=None, help="preset name or .toml path")
    _add_experiment_options(intercept)

    reproduce = commands.add_parser(
        "reproduce", help="run all of layer 1 on both field models; report, plots, models"
    )
    _add_experiment_options(reproduce)
    return parser


def _add_experiment_options(p: argparse.ArgumentParser) -> None:
    p.add_argument("--quick", action="store_true", help="~200 trials per condition (< 5 min)")
    p.add_argument("--seed", type=int, default=0, help="experiment seed")
    p.add_argument("--workers", type=_positive_int, default=None, help="default: all cores")
    p.add_argument("--out", type=Path, default=None, help="output folder (default under runs/)")


def _add_run_options(p: argparse.ArgumentParser, default_trials: int) -> None:
    p.add_argument("--trials", type=_positive_int, default=default_trials)
    p.add_argument("--field", default=DEMO_FIELD, choices=FIELD_MODELS, help="field model")
    p.add_argument("--field-preset", default=None, help="preset name or .toml path")
    p.add_argument("--seed", type=int, default=0, help="experiment seed")
    p.add_argument("--workers", type=_positive_int, default=None, help="default: all cores")
    p.add_argument("--record", action="store_true", help="write rerun recordings")
    p.add_argument("--record-trials", type=_positive_int, default=3, help="how many to record")
    p.add_argument("--out", type=Path, default=None, help="run folder (default under runs/)")
    p.add_argument("--resume", action="store_true", help="keep finished trials in --out")
    p.add_argument("--perfect-perception", action="store_true", help="camera without noise")
    p.add_argument("--quiet", action="store_true", help="no progress bar")


def _drill_option(text: str) -> tuple[str, str | float | int | bool]:
    """``name=value`` → (name, value as bool, int, float or str)."""
    name, sep, raw = text.partition("=")
    if not sep or not name:
        raise argparse.ArgumentTypeError(f"expected NAME=VALUE, got {text!r}")
    if raw.lower() in ("true", "false"):
        return name, raw.lower() == "true"
    for kind in (int, float):
        try:
            return name, kind(raw)
        except ValueError:
            pass
    return name, raw


def _positive_int(text: str) -> int:
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a positive integer, got {text!r}") from None
    if value <= 0:
        raise argparse.ArgumentTypeError(f"expected a positive integer, got {text!r}")
    return value


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of the ``robotsoccer`` console script."""
    args = build_parser().parse_args(argv)
    try:
        if args.command == "demo":
            return cmd_demo(args)
        if args.command == "bench":
            return cmd_bench(args)
        if args.command == "replay":
            return cmd_replay(args)
        if args.command == "trace":
            return cmd_trace(args)
        if args.command == "learn":
            return cmd_learn(args)
        if args.command == "reproduce":
            return cmd_reproduce(args)
    except (PresetError, UsageError, ValueError) as exc:
        print(f"robotsoccer: error: {exc}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("\nrobotsoccer: interrupted", file=sys.stderr)
        return 130
    raise AssertionError(args.command)  # argparse allows only the commands above


def cmd_demo(args: argparse.Namespace) -> int:
    """Run the demo drill and print its summary table."""
    preset = args.field_preset or default_preset(args.field)
    make_drill(args.drill)  # fail fast on a bad name, before any worker starts
    run_name = f"{args.drill}-{args.field}-{Path(preset).stem}-seed{args.seed}"
    out = args.out or Path("runs") / run_name
    record_dir = Path("recordings") / run_name if args.record else None
    spec = TrialSpec(
        drill=args.drill,
        field_model=args.field,
        preset=preset,
        seed=args.seed,
        field=FieldOptions(perfect_perception=args.perfect_perception),
        record_dir=str(record_dir) if record_dir else None,
        record_trials=args.record_trials if args.record else 0,
    )
    _check_spec(spec)
    out.mkdir(parents=True, exist_ok=True)
    (out / "config.json").write_text(json.dumps(asdict(spec) | {"trials": args.trials}, indent=2))
    workers = args.workers or default_workers()
    results_path = out / "results.csv"
    start = time.perf_counter()
    try:
        results = run_trials(
            spec,
            args.trials,
            workers=workers,
            results_path=results_path,
            resume=args.resume,
            progress=not args.quiet,
        )
    except KeyboardInterrupt:
        print(
            f"\nrobotsoccer: interrupted; finished trials are kept in {results_path} "
            "(rerun with --resume to finish)",
            file=sys.stderr,
        )
        return 130
    wall = time.perf_counter() - start
    labels = make_drill(args.drill).labels
    print(summary_table(results, labels, title=f"{run_name}: {len(results)} trials"))
    sim = sum(r.time_s for r in results)
    print(
        f"\n{sim:.1f} simulated s in {wall:.1f} s wall with {workers} worker(s): "
        f"{len(results) / wall:.1f} trials/s"
    )
    print(f"results: {results_path}")
    if record_dir is not None:
        print(f"recordings: {record_dir}/ (open with: robotsoccer replay FILE)")
    return 0


def _check_spec(spec: TrialSpec) -> None:
    """Build trial 0 up front so a bad preset or option fails here in one line, not in a worker."""
    build_trial(spec, 0)


def summary_table(results: Sequence[TrialResult], labels: Sequence[str], title: str) -> str:
    """A plain-text table: each label's count, share and 95% Wilson interval."""
    counts = Counter(r.label for r in results)
    n = len(results)
    lines = [title, f"{'label':<8}{'count':>7}{'share':>9}   95% interval"]
    for label in list(labels) + sorted(set(counts) - set(labels)):
        k = counts.get(label, 0)
        low, high = wilson_interval(k, n)
        share = 100.0 * k / n if n else 0.0
        lines.append(f"{label:<8}{k:>7}{share:>8.1f}%   [{100 * low:.1f}, {100 * high:.1f}]")
    return "\n".join(lines)


def cmd_bench(args: argparse.Namespace) -> int:
    """Run the benchmarks; print JSON or a readable list."""
    from robotsoccer.bench import flatten, run_benchmarks, target_cell

    def say(line: str) -> None:
        print(f"bench: {line}", file=sys.stderr, flush=True)

    results = run_benchmarks(quick=args.quick, demo_field=DEMO_FIELD, say=say)
    if args.json:
        print(json.dumps(results))
    else:
        for key, value in flatten(results):
            print(f"{key:<44} {value!s:>12}   {target_cell(key, value, BENCH_TARGETS)}".rstrip())
    return 0


def cmd_trace(args: argparse.Namespace) -> int:
    """Print the trace of one trial for one client."""
    from robotsoccer.replay.trace import trace_trial

    spec = TrialSpec(
        drill=args.drill,
        field_model=args.field,
        preset=args.field_preset,
        seed=args.seed,
        field=FieldOptions(ball_noise=args.ball_noise),
    ).with_options(**dict(args.option))
    client = _player(args.player) if args.player else None
    for line in trace_trial(spec, args.trial, client):
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
    """Open (or, headless, verify and explain how to open) a recording."""
    from robotsoccer.replay.recording import replay

    return replay(args.file)


def cmd_learn(args: argparse.Namespace) -> int:
    """``learn intercept``: layer 1 on one field model (collect → train → evaluate → report)."""
    preset = args.field_preset or default_preset(args.field)
    tag = f"learn-intercept-{args.field}-{Path(preset).stem}" + ("-quick" if args.quick else "")
    out = args.out or Path("runs") / f"{tag}-seed{args.seed}"
    title = f"Layer 1 (interception) on {args.field}" + (" — quick plan" if args.quick else "")
    return _run_layer1(args, [(args.field, preset)], out, title, "robotsoccer learn intercept")


def cmd_reproduce(args: argparse.Namespace) -> int:
    """``reproduce``: all of layer 1 on both field models into one folder."""
    name = f"reproduce-quick-seed{args.seed}" if args.quick else f"reproduce-seed{args.seed}"
    out = args.out or Path("runs") / name
    models = [(model, default_preset(model)) for model in PAPER_MODELS]
    title = "Layer 1 reproduction (Stone & Veloso 1996, §5)" + (
        " — quick plan" if args.quick else ""
    )
    return _run_layer1(args, models, out, title, "robotsoccer reproduce")


def _run_layer1(
    args: argparse.Namespace,
    models: list[tuple[str, str]],
    out: Path,
    title: str,
    created_by: str,
) -> int:
    from robotsoccer.experiments.layer1 import plan_for, run_layer1

    for model, preset in models:  # a bad preset fails here with one line, not in a worker
        _check_spec(TrialSpec(drill="intercept", field_model=model, preset=preset))
    plan = plan_for(args.quick)
    workers = args.workers or default_workers()
    start = time.perf_counter()

    def log(line: str) -> None:
        print(f"[{time.perf_counter() - start:6.1f} s] {line}", flush=True)

    try:
        report, _ = run_layer1(
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
    except KeyboardInterrupt:
        print(
            f"\nrobotsoccer: interrupted; finished trials are kept under {out}/results "
            "(rerun the same command to resume)",
            file=sys.stderr,
        )
        return 130
    print()
    print(report.read_text())
    print(f"report: {report}  ({time.perf_counter() - start:.0f} s with {workers} worker(s))")
    return 0


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
