r"""The set play on the see-triggered client beside the per-cycle one (issue 28 item 3).

Runs the set-play drill (:mod:`robotsoccer.drills.setplay`) on the Soccer Server presets with
option ``client=see`` and ``client=cycle``, the same plays (seed and index: the same
placements), for the baseline minds (``chooser=closest interceptor=straight``) and, with
``--tree``/``--net``, the layered ones (the tree's passes, layer 1's net for receivers, winger
and defenders). ``--cycle-net PRESET=FILE`` gives the per-cycle client its own net on a preset
(one trained on that client); a net or tree from another preset runs with ``transfer=true``.
Prints per preset a table of shares with 95% Wilson intervals (≥ 1, ≥ 2 and 3 passes, a shot,
a goal) and the cycle − see difference paired play by play:

    python scripts/setplay_client_table.py --plays 100 \
        --tree runs/lp_ss0/models/soccer_server/pass_tree.json \
        --net runs/lp_ss0/models/soccer_server/net_750.npz \
        --cycle-net soccer_server_1996=runs/li_cycle_1996/models/soccer_server/net_750.npz \
        soccer_server_1996 rcssserver_19
"""

from __future__ import annotations

import argparse
import time
from collections.abc import Callable
from pathlib import Path

from robotsoccer.experiments.report_cells import percent_cell
from robotsoccer.experiments.setplay import paired_cell
from robotsoccer.runs.pool import run_trials
from robotsoccer.runs.runner import TrialResult, TrialSpec
from robotsoccer.runs.spec import DrillOption
from robotsoccer.skills.intercept import model_origin

MEASURES: list[tuple[str, Callable[[TrialResult], bool]]] = [
    ("≥ 1 pass", lambda r: r.measure("passes") >= 1.0),
    ("≥ 2 passes", lambda r: r.measure("passes") >= 2.0),
    ("3 passes", lambda r: r.measure("passes") >= 3.0),
    ("shot on goal", lambda r: r.measure("shot") == 1.0),
    ("goal", lambda r: r.label == "GOAL"),
]


def options(
    preset: str, client: str, tree: Path | None, net: Path | None
) -> tuple[tuple[str, DrillOption], ...]:
    """The drill options of one cell: baseline without files, else the layered minds."""
    if tree is None or net is None:
        return (("chooser", "closest"), ("interceptor", "straight"), ("client", client))
    origin = model_origin(str(net))
    transfer = origin is None or Path(origin[1]).stem != preset
    return (
        ("chooser", "tree"),
        ("model", str(tree.resolve())),
        ("interceptor", "net"),
        ("net", str(net.resolve())),
        ("transfer", "true" if transfer else "false"),
        ("client", client),
    )


def main() -> None:
    """Run the cells and print the tables."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("presets", nargs="+", help="Soccer Server presets")
    parser.add_argument("--plays", type=int, default=100)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--tree", type=Path, default=None)
    parser.add_argument("--net", type=Path, default=None)
    parser.add_argument("--cycle-net", action="append", default=[], metavar="PRESET=FILE")
    parser.add_argument("--workers", type=int, default=1)
    args = parser.parse_args()
    cycle_nets = dict(item.split("=", 1) for item in args.cycle_net)
    layered = args.tree is not None and args.net is not None
    for preset in args.presets:
        results: dict[str, list[TrialResult]] = {}
        files: dict[str, str] = {}
        for client in ("see", "cycle"):
            net = args.net
            if client == "cycle" and preset in cycle_nets:
                net = Path(cycle_nets[preset])
            opts = options(preset, client, args.tree, net)
            spec = TrialSpec(
                drill="setplay",
                field_model="soccer_server",
                preset=preset,
                seed=args.seed,
                drill_options=opts,
            )
            began = time.perf_counter()
            results[client] = run_trials(spec, args.plays, workers=args.workers, progress=False)
            wall = time.perf_counter() - began
            files[client] = f"{dict(opts)} ({wall:.0f} s)"
        minds = "layered" if layered else "baseline"
        print(f"\n### `{preset}`, {minds} minds, {args.plays} plays per client, seed {args.seed}")
        for client, text in files.items():
            print(f"- {client}: {text}")
        print("\n| measure | see | cycle | cycle − see, paired [points] |\n|---|---|---|---|")
        for title, holds in MEASURES:
            cells = []
            for client in ("see", "cycle"):
                rows = results[client]
                k = sum(1 for r in rows if holds(r))
                cells.append(f"{k} — {percent_cell(k, len(rows))}")
            diff = paired_cell(results["cycle"], results["see"], holds)
            print(f"| {title} | {cells[0]} | {cells[1]} | {diff} |")
        labels = sorted({r.label for rows in results.values() for r in rows})
        for client in ("see", "cycle"):
            counts = {lab: sum(1 for r in results[client] if r.label == lab) for lab in labels}
            print(f"- labels, {client}: {counts}")


if __name__ == "__main__":
    main()
