"""``robotsoccer demo``: a drill's trials, headless, and their labels' shares."""

from __future__ import annotations

import argparse
import time
from pathlib import Path

from field_models.registry import default_preset
from robotsoccer.cli.options import EXIT_INTERRUPTED, _positive_int
from robotsoccer.cli.running import Tally, check_spec, fail, spec_from
from robotsoccer.cli.shared import Commands, drill_options, field_options, run_options
from robotsoccer.drills import make_drill
from robotsoccer.runs.folders import prepare_run_folder
from robotsoccer.runs.pool import default_workers, run_trials
from robotsoccer.runs.ray_backend import require_ray


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
            on_result=tally.add,
        )
    except KeyboardInterrupt:
        kept = f"; finished trials are kept in {results_path}" if results_path.exists() else ""
        return fail(EXIT_INTERRUPTED, f"interrupted{kept} (--resume finishes the run)")
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


def add_parser(commands: Commands) -> None:
    """``demo``'s options."""
    demo = commands.add("demo", "run a drill's trials headless and print its labels' shares")
    field_options(demo)
    drill_options(demo)
    demo.add_argument("--trials", type=_positive_int, default=200, help="how many trials")
    run_options(demo, backend=True)
    demo.add_argument("--record", action="store_true", help="write rerun recordings")
    demo.add_argument(
        "--record-trials", type=_positive_int, default=3, help="record this many first trials"
    )
    demo.add_argument("--quiet", action="store_true", help="no progress")
