"""``robotsoccer match`` and ``setplay``: whole matches and the set play, with their layers."""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path
from typing import TYPE_CHECKING, Any

from field_models.arena import FieldOptions
from field_models.registry import default_preset
from robotsoccer.cli.options import EXIT_INTERRUPTED, PAPER_MODELS, UsageError
from robotsoccer.cli.running import check_spec, fail
from robotsoccer.runs.folders import prepare_run_folder
from robotsoccer.runs.pool import default_workers, run_trials
from robotsoccer.runs.runner import TrialSpec

if TYPE_CHECKING:
    pass


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


def layer3_options(table: Path | None) -> dict[str, Any]:
    """The match drill's options for a layer3 team playing `table`.

    The table's provenance says how it learned (every spell on the ball or only where blocked,
    its SUCCESS cut, its reward window, shot-range guard and loss penalty); it plays the same
    way.

    Raises:
        UsageError: No table given.
        ValueError: Not a readable TPOT-RL table (:func:`learning.tpot.load_table`'s one line).
    """
    from learning.tpot import N_ACTIONS, load_table
    from robotsoccer.drills.match_options import PASS_THRESHOLD

    if table is None:
        raise UsageError(
            "a layer3 team needs its table: --tpot FILE (from `robotsoccer learn team`)"
        )
    learned = load_table(table)
    if learned.actions != N_ACTIONS:
        raise ValueError(
            f"{table}: a table of {learned.actions} actions, not the match's {N_ACTIONS} ball "
            "destinations (a half-field offense table?)"
        )
    plan = learned.provenance.get("plan", {})
    plan = plan if isinstance(plan, dict) else {}
    options: dict[str, Any] = {
        "tpot": str(table),
        "tpot_every": bool(plan.get("every", False)),
        "tpot_success": float(plan.get("success", PASS_THRESHOLD)),
        "tpot_window": str(plan.get("window", "choice")),
    }
    # Named only when set, as the study names them (team_study.TeamPlan.drill_options).
    if plan.get("guard", False):
        options["tpot_guard"] = True
    if plan.get("loss", 0.0):
        options["tpot_loss"] = float(plan["loss"])
    return options


MATCH_FLAGS = frozenset({"left", "right", "players", "half_time_s", "net", "tree", "tpot"})
"""Match options the command sets from its own flags, so ``--option`` may not name them."""


def cmd_match(args: argparse.Namespace) -> int:
    """One match, or a series of layered against baseline with its report."""
    from robotsoccer.experiments.match import run_series, write_report

    preset = args.field_preset or default_preset(args.field)
    kinds = (args.left, args.right)
    layer3 = "layer3" in kinds
    layered = args.games > 1 or "layered" in kinds or layer3
    options: dict[str, Any] = {"players": args.players}
    if args.half_time is not None:
        options["half_time_s"] = args.half_time
    if layered:
        net, tree = find_layers(args)
        options |= {"net": str(net), "tree": str(tree)}
    if layer3:
        options |= layer3_options(args.tpot)
    elif args.tpot is not None:
        raise UsageError("--tpot is layer 3's table: name layer3 in --left or --right")
    extra = dict(args.option)
    flagged = sorted(set(extra) & (set(options) | MATCH_FLAGS))
    if flagged:
        raise UsageError(f"--option {flagged[0]}: it has its own flag (see robotsoccer match -h)")
    options |= extra
    # A series is layered against baseline, or with layer 3 the two kinds named.
    teams = kinds if layer3 else ("layered", "baseline")
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
                resume=args.resume, progress=not args.quiet, teams=teams,
            )  # fmt: skip
        except KeyboardInterrupt:
            return fail(EXIT_INTERRUPTED, f"interrupted; finished games are kept in {out}")
        title = (f"{teams[0].capitalize()} vs {teams[1]} on {args.field} "
                 f"({Path(preset).stem}), seed {args.seed}")  # fmt: skip
        write_report(games, out, title, print, names=teams)
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
    from robotsoccer.experiments.context import RunContext, seeds_for
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
    client = "" if args.client == "see" else f"-{args.client}"  # a see run's folder stays
    quick = "-quick" if args.quick else ""
    out = args.out or Path("runs") / f"setplay{client}{quick}-seed{args.seed}"
    prepare_run_folder(out, resume=args.resume, overwrite=args.overwrite)
    fields = [(m, default_preset(m)) for m in PAPER_MODELS]
    ctx = RunContext(out, seeds_for(args.seed), args.workers or default_workers(), print, True)
    report = run_setplay_study(
        ctx, fields=fields, models=models, plays=args.plays, quick=args.quick, client=args.client
    )
    print(f"report: {report}")
    return 0
