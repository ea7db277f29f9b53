r"""A diagnostic: the set play with the attackers on one client and the defenders on the other.

The drill's option ``client`` moves both sides (:mod:`robotsoccer.drills.setplay`). This builds
each play twice, ``client=see`` and ``client=cycle`` (layered minds: ``lp_ss0``'s tree and net,
``li_cycle_1996``'s net for the cycle client on ``soccer_server_1996``), and plays it with one
build's attackers and the other's defenders and goalie (the coach of the attackers' build
judges). Prints the labels and the shares of plays with ≥ 1, 2, 3 passes and a shot:

    ROBOTSOCCER_RUNS=runs python scripts/setplay_mixed_clients.py soccer_server_1996 500
"""

from __future__ import annotations

import collections
import os
import sys

from robotsoccer.drills.setplay import DEFENDERS
from robotsoccer.experiments.report_cells import percent_cell
from robotsoccer.runs.runner import TrialLoop, TrialSpec, build_trial

RUNS = os.environ.get("ROBOTSOCCER_RUNS", "runs")
"""The run folders of the models (``learn pass``/``learn intercept`` runs named as above)."""
SEE = f"{RUNS}/lp_ss0/models/soccer_server/"
CYCLE_NET = f"{RUNS}/li_cycle_1996/models/soccer_server/net_750.npz"


def spec(preset: str, client: str) -> TrialSpec:
    """The layered minds on `client`."""
    net = CYCLE_NET if client == "cycle" and preset == "soccer_server_1996" else SEE + "net_750.npz"
    options = (
        ("chooser", "tree"),
        ("model", SEE + "pass_tree.json"),
        ("interceptor", "net"),
        ("net", net),
        ("transfer", "false" if preset == "soccer_server_1996" else "true"),
        ("client", client),
    )
    return TrialSpec("setplay", "soccer_server", preset=preset, seed=0, drill_options=options)


def play(attack: TrialSpec, defend: TrialSpec, index: int) -> tuple[str, dict[str, float]]:
    """Play `index` with `attack`'s attackers and `defend`'s defenders: label and measures."""
    rngs, drill, arena = build_trial(attack, index)
    drill.setup(arena, rngs)
    minds = drill.minds(arena, rngs)
    other_rngs, other, other_arena = build_trial(defend, index)
    other.setup(other_arena, other_rngs)
    theirs = other.minds(other_arena, other_rngs)
    for ref in DEFENDERS:
        minds[ref] = theirs[ref]
    verdict = TrialLoop(arena, drill, minds).run()
    assert verdict is not None
    return verdict.label, drill.measures()


def main() -> None:
    """Both mixes on the preset and number of plays given."""
    preset, n = sys.argv[1], int(sys.argv[2])
    see, cycle = spec(preset, "see"), spec(preset, "cycle")
    mixes = (("attack cycle, defend see", cycle, see), ("attack see, defend cycle", see, cycle))
    for name, attack, defend in mixes:
        counts: collections.Counter[str] = collections.Counter()
        for i in range(n):
            label, measures = play(attack, defend, i)
            counts[label] += 1
            for k in (1, 2, 3):
                counts[f"passes>={k}"] += measures["passes"] >= k
            counts["shot"] += measures["shot"] == 1.0
        cells = {key: f"{v} ({percent_cell(v, n)})" for key, v in sorted(counts.items())}
        print(preset, name, n, cells)


if __name__ == "__main__":
    main()
