"""``robotsoccer bench``: the speed figures, each beside its target."""

from __future__ import annotations

import argparse
import json
import sys

from robotsoccer.cli.options import BENCH_TARGETS, DEFAULT_FIELD
from robotsoccer.cli.shared import Commands


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


def add_parser(commands: Commands) -> None:
    """``bench``'s options."""
    bench = commands.add("bench", "measure speed, each figure beside its target")
    bench.add_argument("--json", action="store_true", help="print one JSON object at the end")
    bench.add_argument("--quick", action="store_true", help="one short repeat of each figure")
