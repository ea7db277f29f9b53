"""``robotsoccer setplay``: the set play of Figure 15 on both field models."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from field_models.registry import default_preset
from robotsoccer.cli.options import PAPER_MODELS, UsageError, _index, _positive_int
from robotsoccer.cli.shared import Commands, run_options
from robotsoccer.runs.folders import prepare_run_folder
from robotsoccer.runs.pool import default_workers


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


def add_parser(commands: Commands) -> None:
    """``setplay``'s options."""
    setplay = commands.add(
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
    run_options(setplay)
