"""Table 2 (layer 2, the paper's §6) on the robots with a given layer-1 net, at a chosen plan size.

``robotsoccer learn pass`` runs either the quick plan (1000 training passes, 500 trials per row)
or the paper's (5000 / 5000). The README's robot Table 2 with lead-net interceptors used a plan
between them (5000 / 1000) because the full one did not fit the shared CPU; this script is how
that run is repeated. It runs the same steps as ``learn pass`` (:func:`~robotsoccer.experiments.
layer2.run_layer2_model`) into ``OUT``, which must not hold a run already.

Usage::

    python scripts/table2_robots.py OUT NET [--preset small_size_1997_arc] [--collect 5000]
        [--trials 1000] [--seed 0] [--workers 2]
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

from robotsoccer.cli.running import clock_log
from robotsoccer.experiments.context import RunContext
from robotsoccer.experiments.layer1_plan import seeds_for
from robotsoccer.experiments.layer2 import Layer2Plan, layer2_markdown, run_layer2_model
from robotsoccer.experiments.plots_layer2 import layer2_plots


def main(argv: list[str] | None = None) -> int:
    """Run the plan and write ``report.md`` and ``config.json``; 2 when OUT holds a report."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out", type=Path)
    parser.add_argument("net", type=Path, help="layer 1's net file (turn or lead)")
    parser.add_argument("--preset", default="small_size_1997_arc")
    parser.add_argument("--collect", type=int, default=5000, help="training passes")
    parser.add_argument("--trials", type=int, default=1000, help="trials per row")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--workers", type=int, default=2)
    args = parser.parse_args(argv)
    if (args.out / "report.md").exists():
        print(f"{args.out} holds a report already: give another folder", file=sys.stderr)
        return 2
    plan = Layer2Plan("mid", collect_trials=args.collect, eval_trials=args.trials)
    start = time.perf_counter()
    ctx = RunContext(args.out, seeds_for(args.seed), args.workers, clock_log())
    section = run_layer2_model(("robot_physics", args.preset), args.net, plan, ctx)
    plots = layer2_plots([section], args.out)
    title = f"# Layer 2 on robot_physics ({args.preset}), {args.collect} / {args.trials} plan\n\n"
    (args.out / "report.md").write_text(title + layer2_markdown([section], plan, plots))
    config = {"plan": plan.to_dict(), "seed": args.seed, "net": str(args.net)}
    (args.out / "config.json").write_text(json.dumps(config, indent=2) + "\n")
    print(f"done in {time.perf_counter() - start:.0f} s with {args.workers} worker(s)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
