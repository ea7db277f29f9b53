"""``robotsoccer learn intercept|pass|lead`` and ``reproduce``: the layers' experiments."""

from __future__ import annotations

import argparse
import json
import sys
import time
from collections.abc import Callable, Sequence
from dataclasses import replace
from pathlib import Path
from typing import TYPE_CHECKING

from field_models.registry import default_preset
from robotsoccer.cli.commands.transfer import transfer_section
from robotsoccer.cli.options import EXIT_INTERRUPTED, LEAD_DRILLS, PAPER_MODELS, TEAM_FIELD
from robotsoccer.cli.running import check_spec, clock_log, fail
from robotsoccer.runs.folders import prepare_run_folder
from robotsoccer.runs.pool import default_workers
from robotsoccer.runs.runner import TrialSpec

if TYPE_CHECKING:
    from robotsoccer.experiments.report_records import ModelSection


def cmd_learn(args: argparse.Namespace) -> int:
    """``learn intercept`` / ``learn pass``: one layer on one field model."""
    if args.target == "pass":
        return cmd_learn_pass(args)
    if args.target == "lead":
        return cmd_learn_lead(args)
    if args.target == "team":
        return cmd_learn_team(args)
    preset = args.field_preset or default_preset(args.field)
    tag = f"learn-intercept-{args.field}-{Path(preset).stem}" + ("-quick" if args.quick else "")
    out = args.out or Path("runs") / f"{tag}-seed{args.seed}"
    title = f"Layer 1 (interception) on {args.field}" + (" — quick plan" if args.quick else "")
    return _run_layer1(args, [(args.field, preset)], out, title, "robotsoccer learn intercept")


def cmd_learn_pass(args: argparse.Namespace) -> int:
    """``learn pass``: layer 2 on one field model (collect → train → evaluate → report)."""
    from robotsoccer.experiments.layer1 import train_main_net
    from robotsoccer.experiments.layer1_plan import plan_for, seeds_for
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
    log = clock_log()
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
    from robotsoccer.cli.commands.play import find_layers
    from robotsoccer.experiments.team_study import match_base, plan_for, run_team_study

    preset = args.field_preset or default_preset(args.field)
    net, tree = find_layers(args)
    plan = plan_for(args.quick, args.every, args.window)
    if args.training_games is not None:
        plan = replace(plan, training_games=args.training_games)
    if args.games_per_round is not None:
        plan = replace(plan, games_per_round=args.games_per_round)
    if args.shot_guard or args.loss_penalty:
        plan = replace(plan, guard=args.shot_guard, loss=args.loss_penalty)
    base = match_base(args.field, args.field_preset, args.seed, net, tree)
    check_spec(base.with_options(left="layered", right="baseline"))
    if args.table is not None:
        from learning.tpot import load_table

        load_table(args.table)  # a corrupt or foreign table fails here, in one line
    tag = f"learn-team-{args.field}-{Path(preset).stem}" + ("-every" if args.every else "")
    tag += "-horizon" if args.window == "horizon" else ""
    tag += "-guard" if args.shot_guard else ""
    tag += f"-loss{args.loss_penalty:g}" if args.loss_penalty else ""
    tag += "-quick" if args.quick else ""
    out = args.out or Path("runs") / f"{tag}-seed{args.seed}"
    prepare_run_folder(out, resume=args.resume, overwrite=args.overwrite)
    workers = args.workers or default_workers()
    (out / "config.json").write_text(
        json.dumps(
            {
                "command": "robotsoccer learn team",
                "plan": plan.to_dict(),
                "seed": args.seed,
                "field": args.field,
                "preset": preset,
                "net": str(net),
                "tree": str(tree),
                "table": None if args.table is None else str(args.table),
                "workers": workers,
            },
            indent=2,
        )
        + "\n"
    )
    start = time.perf_counter()
    try:
        report = run_team_study(
            base, plan, out, workers=workers, log=clock_log(), resume=args.resume,
            progress=sys.stderr.isatty(), table=args.table,
        )  # fmt: skip
    except KeyboardInterrupt:
        return fail(
            EXIT_INTERRUPTED,
            f"interrupted; finished games are kept under {out} (--resume finishes the run)",
        )
    print()
    print(report.read_text())
    print(f"report: {report}  ({time.perf_counter() - start:.0f} s with {workers} worker(s))")
    return 0


def _lead_section(
    args: argparse.Namespace, out: Path, workers: int, log: Callable[[str], None]
) -> str:
    """The lead study (:mod:`robotsoccer.experiments.lead_study`) on the chosen fields."""
    from robotsoccer.experiments.layer1_plan import seeds_for
    from robotsoccer.experiments.lead_study import StudyDrill, plan_for, run_study

    field = getattr(args, "field", None)
    fields = [field] if field else list(LEAD_DRILLS)
    drills = [StudyDrill(f, *LEAD_DRILLS[f]) for f in fields]
    text, _ = run_study(drills, plan_for(args.quick), out, seeds_for(args.seed), workers, log)
    return text


def _team_section(
    args: argparse.Namespace,
    out: Path,
    sections: Sequence[ModelSection],
    workers: int,
    log: Callable[[str], None],
) -> str:
    """Layer 3 on the Soccer Server's new layers: a quick ``learn team --every`` (its report).

    The quick plan (8 training games, 4-game series) shows every step runs on this run's net
    and tree; the measured study is ``robotsoccer learn team --every``.
    """
    from robotsoccer.experiments import team_study

    field = TEAM_FIELD
    found = [s for s in sections if s.field_model == field]
    if not found:
        return ""
    models = out / "models" / field
    net, tree = models / f"net_{found[0].net_examples}.npz", models / "pass_tree.json"
    base = team_study.match_base(field, found[0].preset, args.seed, net, tree)
    plan = team_study.plan_for(True, True)
    report = team_study.run_team_study(base, plan, out / "team", workers=workers, log=log)
    text = report.read_text().replace("## Layer 3", "## Layer 3 (quick: a smoke-size run)", 1)
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
        text = _lead_section(args, out, workers, clock_log())
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
    from robotsoccer.experiments.layer1 import run_layer1
    from robotsoccer.experiments.layer1_plan import plan_for, seeds_for
    from robotsoccer.experiments.layer2 import layer2_markdown, layer2_plan, run_layer2_model
    from robotsoccer.experiments.plots_layer2 import layer2_plots

    for model, preset in models:  # a bad preset fails here with one line, not in a worker
        check_spec(TrialSpec(drill="intercept", field_model=model, preset=preset))
    prepare_run_folder(out, resume=args.resume, overwrite=args.overwrite)
    plan = plan_for(args.quick)
    workers = args.workers or default_workers()
    start = time.perf_counter()
    log = clock_log()
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
        if with_layer2 and not args.no_team:
            section = _team_section(args, out, sections, workers, log)
            with report.open("a") as f:
                f.write("\n" + section)
        if with_layer2 and not args.no_transfer:
            section = transfer_section(args, models, out, workers, created_by)
            with report.open("a") as f:
                f.write("\n" + section)
    except KeyboardInterrupt:
        return fail(
            EXIT_INTERRUPTED,
            f"interrupted; finished trials are kept under {out} (--resume finishes the run)",
        )
    print()
    print(report.read_text())
    print(f"report: {report}  ({time.perf_counter() - start:.0f} s with {workers} worker(s))")
    return 0
