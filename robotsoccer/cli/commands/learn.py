"""``robotsoccer learn intercept|pass|lead|team``: one layer's experiment.

And the pipeline that ``learn intercept`` and ``reproduce`` share (:func:`run_pipeline`).
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path
from typing import TYPE_CHECKING

from field_models.registry import FIELD_MODELS, default_preset
from robotsoccer.cli.options import (
    DEFAULT_FIELD,
    EXIT_INTERRUPTED,
    LEAD_DRILLS,
    TEAM_FIELD,
    _positive_int,
)
from robotsoccer.cli.running import check_spec, clock_log, fail, run_context
from robotsoccer.cli.shared import Commands, Parser, experiment_options
from robotsoccer.runs.folders import prepare_run_folder
from robotsoccer.runs.pool import default_workers
from robotsoccer.runs.runner import TrialSpec

if TYPE_CHECKING:
    from robotsoccer.experiments.reproduce import ReproduceParts
    from robotsoccer.experiments.team_run import TeamRun


def cmd_learn(args: argparse.Namespace) -> int:
    """``learn intercept`` / ``learn pass``: one layer on one field model."""
    if args.target == "pass":
        return cmd_learn_pass(args)
    if args.target == "lead":
        return cmd_learn_lead(args)
    if args.target == "team":
        return cmd_learn_team(args)
    from robotsoccer.experiments.reproduce import ReproduceParts

    preset = args.field_preset or default_preset(args.field)
    client = "" if args.client == "see" else f"-{args.client}"
    tag = f"learn-intercept-{args.field}-{Path(preset).stem}{client}" + (
        "-quick" if args.quick else ""
    )
    out = args.out or Path("runs") / f"{tag}-seed{args.seed}"
    title = f"Layer 1 (interception) on {args.field}" + (" — quick plan" if args.quick else "")
    parts = ReproduceParts(client=args.client)
    return run_pipeline(
        args, [(args.field, preset)], out, title, "robotsoccer learn intercept", parts
    )


def cmd_learn_pass(args: argparse.Namespace) -> int:
    """``learn pass``: layer 2 on one field model (collect → train → evaluate → report)."""
    from robotsoccer.experiments.layer1 import train_main_net
    from robotsoccer.experiments.layer1_plan import plan_for
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
    ctx = run_context(args, out, "robotsoccer learn pass")
    workers = ctx.workers
    start = time.perf_counter()
    try:
        net = args.net
        if net is None:
            net = train_main_net((args.field, preset), plan_for(args.quick), ctx)
        section = run_layer2_model((args.field, preset), net, plan, ctx)
    except KeyboardInterrupt:
        return fail(
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


def cmd_learn_team(args: argparse.Namespace) -> int:
    """``learn team``: layer 3 (TPOT-RL) trained against the baseline, then the two series."""
    from robotsoccer.experiments.context import RunInterrupted
    from robotsoccer.experiments.team_run import run_learn_team

    try:
        outcome = run_learn_team(team_request(args), clock_log())
    except RunInterrupted as stop:
        return fail(EXIT_INTERRUPTED, str(stop))
    for line in outcome.lines:
        print(line)
    return 0


def team_request(args: argparse.Namespace) -> TeamRun:
    """The study ``robotsoccer learn team``'s options ask for."""
    from robotsoccer.cli.commands.match import layer_files
    from robotsoccer.experiments.team_run import TeamRun

    return TeamRun(
        field=args.field,
        preset=args.field_preset,
        seed=args.seed,
        layers=layer_files(args),
        table=args.table,
        quick=args.quick,
        every=args.every,
        window=args.window,
        shot_guard=args.shot_guard,
        loss_penalty=args.loss_penalty,
        games_per_round=args.games_per_round,
        training_games=args.training_games,
        out=args.out,
        resume=args.resume,
        overwrite=args.overwrite,
        workers=args.workers,
        progress=sys.stderr.isatty(),
    )


def cmd_learn_lead(args: argparse.Namespace) -> int:
    """``learn lead``: layer 1's two decisions on one or both field models, with a report."""
    from robotsoccer.experiments.lead_study import StudyDrill, plan_for
    from robotsoccer.experiments.reproduce import lead_step

    fields = [args.field] if args.field else list(LEAD_DRILLS)
    drills = [StudyDrill(f, *LEAD_DRILLS[f]) for f in fields]
    tag = "learn-lead" + (f"-{args.field}" if args.field else "") + ("-quick" if args.quick else "")
    out = args.out or Path("runs") / f"{tag}-seed{args.seed}"
    prepare_run_folder(out, resume=args.resume, overwrite=args.overwrite)
    plan = plan_for(args.quick)
    workers = args.workers or default_workers()
    start = time.perf_counter()
    try:
        text = lead_step(drills, args.quick, run_context(args, out, "robotsoccer learn lead"))
    except KeyboardInterrupt:
        return fail(
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


def run_pipeline(
    args: argparse.Namespace,
    models: list[tuple[str, str]],
    out: Path,
    title: str,
    created_by: str,
    parts: ReproduceParts,
) -> int:
    """Check the presets, prepare the folder and run the pipeline; one line on an interrupt.

    ``learn intercept`` and ``reproduce`` (:mod:`robotsoccer.cli.commands.reproduce`) run
    :func:`~robotsoccer.experiments.reproduce.run_reproduce` through it.
    """
    from robotsoccer.experiments.reproduce import run_reproduce

    for model, preset in models:  # a bad preset fails here with one line, not in a worker
        check_spec(TrialSpec(drill="intercept", field_model=model, preset=preset))
    prepare_run_folder(out, resume=args.resume, overwrite=args.overwrite)
    start = time.perf_counter()
    ctx = run_context(args, out, created_by)
    try:
        report = run_reproduce(models, args.quick, ctx, parts, title)
    except KeyboardInterrupt:
        return fail(
            EXIT_INTERRUPTED,
            f"interrupted; finished trials are kept under {out} (--resume finishes the run)",
        )
    print()
    print(report.read_text())
    print(f"report: {report}  ({time.perf_counter() - start:.0f} s with {ctx.workers} worker(s))")
    return 0


def add_parser(commands: Commands) -> None:
    """``learn``'s targets and their options."""
    learn = commands.add("learn", "learn a layer: collect, train, evaluate, report")
    targets = learn.add_subparsers(dest="target", required=True, parser_class=Parser)
    common = [commands.common]
    intercept = targets.add_parser(
        "intercept", help="layer 1: the interception net (paper §5)", parents=common
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
    experiment_options(intercept)
    passing = targets.add_parser(
        "pass", help="layer 2: the pass-evaluation tree (paper §6)", parents=common
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
    experiment_options(passing)
    lead = targets.add_parser(
        "lead",
        help="layer 1 with the lead decision beside the paper's turn angle, both field models",
        parents=common,
    )
    lead.add_argument(
        "--field",
        default=None,
        choices=FIELD_MODELS,
        help="one field model (default: both)",
    )
    experiment_options(lead)
    _team_parser(targets.add_parser(
        "team",
        help="layer 3: TPOT-RL's ball destinations learned in games against the baseline, "
        "then series against the layered team and the baseline",
        parents=common,
    ))  # fmt: skip


def _team_parser(team: argparse.ArgumentParser) -> None:
    """``learn team``'s options."""
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
    experiment_options(team)
