r"""The set play with the attackers looking with the body beside the neck (issue 28 item 3).

Runs the set-play drill (:mod:`robotsoccer.drills.setplay`) on the Soccer Server presets with
option ``look=body`` and ``look=neck``, the same plays (seed and index: the same placements),
on one client (``--client``, default ``cycle``), for the baseline minds and, with ``--tree`` and
``--net PRESET=FILE``, the layered ones. The cells' drill options are
``scripts/setplay_client_table.py``'s (:func:`setplay_client_table.options`), as are the measures
and the paired differences. Prints per preset and minds a table of shares with 95% Wilson
intervals and the neck − body difference paired play by play, and the attackers' body-turn
reversals per player-minute (:class:`~robotsoccer.skills.reversals.TurnReversals` on the six
attackers' true headings, every cycle, over each play's length):

    python scripts/setplay_look_table.py --plays 500 --workers 2 \
        --tree soccer_server_1996=runs/lp_ss0/models/soccer_server/pass_tree.json \
        --net soccer_server_1996=runs/li_cycle_1996/models/soccer_server/net_750.npz \
        --tree rcssserver_19=runs/lp_v19/models/soccer_server/pass_tree.json \
        --net rcssserver_19=runs/li_cycle_v19/models/soccer_server/net_750.npz \
        soccer_server_1996 rcssserver_19
"""

from __future__ import annotations

import argparse
import time
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

from setplay_client_table import MEASURES, options

from field_models.protocol import LEFT, Percept
from robotsoccer.experiments.match import mean_interval
from robotsoccer.experiments.report_cells import percent_cell
from robotsoccer.experiments.setplay import paired_cell
from robotsoccer.runs.runner import TrialResult, TrialSpec, build_trial, play
from robotsoccer.skills.reversals import TurnReversals

LOOKS = ("body", "neck")
SHOWN = ("≥ 2 passes", "3 passes", "goal")
"""The measures of the table (``setplay_client_table.MEASURES``' titles)."""


def one_play(spec: TrialSpec, index: int) -> tuple[TrialResult, int, float]:
    """Play `index` of `spec`: its result, its attackers' turn reversals and player-minutes.

    The result is the one ``run_trial`` gives (the same play, observed).
    """
    rngs, drill, arena = build_trial(spec, index)
    drill.setup(arena, rngs)
    minds = drill.minds(arena, rngs)
    attackers = [ref for ref in arena.players if ref.team == LEFT]
    counter = TurnReversals()

    def observe(a: object, percepts: list[Percept]) -> None:
        for ref in attackers:
            counter.sample(ref, arena.player_state(ref).heading)

    observe(arena, [])
    verdict = play(arena, drill, minds, observe)
    seconds = arena.tick * arena.facts.dt_s
    result = TrialResult(
        index, verdict.label, verdict.reason, arena.tick, seconds, drill.data(),
        tuple(drill.measures().items()),
    )  # fmt: skip
    return result, counter.count, len(attackers) * seconds / 60.0


def run_cell(
    spec: TrialSpec, plays: int, workers: int
) -> tuple[list[TrialResult], list[tuple[int, float]]]:
    """Plays 0..plays-1 of `spec`: results and (reversals, player-minutes), by index."""
    with ProcessPoolExecutor(workers) as pool:
        done = list(pool.map(one_play, [spec] * plays, range(plays), chunksize=8))
    return [r for r, _, _ in done], [(n, m) for _, n, m in done]


def main() -> None:
    """Run the cells and print the tables (module docstring)."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("presets", nargs="+", help="Soccer Server presets")
    parser.add_argument("--plays", type=int, default=100)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--client", choices=("see", "cycle"), default="cycle")
    parser.add_argument("--tree", action="append", default=[], metavar="PRESET=FILE")
    parser.add_argument("--net", action="append", default=[], metavar="PRESET=FILE")
    parser.add_argument("--workers", type=int, default=1)
    args = parser.parse_args()
    trees = {k: Path(v) for k, v in (item.split("=", 1) for item in args.tree)}
    nets = {k: Path(v) for k, v in (item.split("=", 1) for item in args.net)}
    for preset in args.presets:
        layers = [("baseline", None, None)]
        if preset in trees and preset in nets:
            layers.insert(0, ("layered", trees[preset], nets[preset]))
        for minds, tree, net in layers:
            results: dict[str, list[TrialResult]] = {}
            rates: dict[str, list[tuple[int, float]]] = {}
            walls: dict[str, float] = {}
            opts = options(preset, args.client, tree, net)
            for look in LOOKS:
                spec = TrialSpec(
                    drill="setplay",
                    field_model="soccer_server",
                    preset=preset,
                    seed=args.seed,
                    drill_options=(*opts, ("look", look)),
                )
                began = time.perf_counter()
                results[look], rates[look] = run_cell(spec, args.plays, args.workers)
                walls[look] = time.perf_counter() - began
            print(
                f"\n### `{preset}`, {minds} minds, client={args.client}, "
                f"{args.plays} plays per look, seed {args.seed}"
            )
            print(
                f"- options: {dict(opts)}; wall "
                + ", ".join(f"{k} {v:.0f} s" for k, v in walls.items())
            )
            print("\n| measure | body | neck | neck − body, paired [points] |\n|---|---|---|---|")
            for title, holds in MEASURES:
                if title not in SHOWN:
                    continue
                cells = []
                for look in LOOKS:
                    k = sum(1 for r in results[look] if holds(r))
                    cells.append(f"{k} — {percent_cell(k, len(results[look]))}")
                diff = paired_cell(results["neck"], results["body"], holds)
                print(f"| {title} | {cells[0]} | {cells[1]} | {diff} |")
            turns = []
            for look in LOOKS:
                # All plays together; the interval is that of the mean of the plays' own rates.
                count = sum(n for n, _ in rates[look])
                minutes = sum(m for _, m in rates[look])
                m = mean_interval([n / t for n, t in rates[look]])
                turns.append(
                    f"{count / minutes:.1f} (per play {m.value:.1f} [{m.low:.1f}, {m.high:.1f}])"
                )
            print(f"| attackers' turn reversals / player-minute | {turns[0]} | {turns[1]} | |")
            labels = sorted({r.label for rows in results.values() for r in rows})
            for look in LOOKS:
                counts = {lab: sum(1 for r in results[look] if r.label == lab) for lab in labels}
                print(f"- labels, {look}: {counts}")


if __name__ == "__main__":
    main()
