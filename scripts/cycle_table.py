r"""Issue 28's drill table: see-triggered against per-cycle client, each behaviour, and dash share.

For each preset, client (``see``, ``cycle``) and behaviour (``straight``, ``analytic``, ``net``)
it plays the interception drill trial by trial (the runner's own loop, so each trial's result
equals :func:`robotsoccer.runs.runner.run_trial`'s) and prints saves with 95% Wilson intervals.

**Dash share** (issue 28: "dashes on at least 80% of the cycles after the trigger when the ball
is not yet reachable"): the cycles after the see at which the defender chose TA in which the
ball came closer to the defender (true positions) and was beyond the kickable distance when the
cycle began; a cycle counts as a dash when the server carried out a dash in it (the arena's
command tally). Pooled over trials; its interval treats cycles as independent (they are not:
trials cluster them), so it is narrower than it should be.

    PYTHONPATH=$PWD python scripts/cycle_table.py --presets rcssserver_19 \\
        --net-see SEE.npz --net-cycle CYCLE.npz [--trials 2000] [--seed 0]
"""

from __future__ import annotations

import argparse
import math
import time
from dataclasses import dataclass

from field_models.protocol import Percept
from robotsoccer.drills.intercept_plan import DEFENDER
from robotsoccer.runs.runner import TrialLoop, TrialSpec, build_trial
from robotsoccer.stats import wilson_interval

DASH = 1  # COMMAND_COUNTERS index of dash (checked below)


@dataclass
class Cell:
    """One preset × client × behaviour: saves and the dash share's cycles."""

    trials: int = 0
    saves: int = 0
    eligible: int = 0
    dashes: int = 0


def play(spec: TrialSpec, index: int, cell: Cell) -> None:
    """One trial of `spec`, its outcome and dash-share cycles added to `cell`."""
    rngs, drill, arena = build_trial(spec, index)
    drill.setup(arena, rngs)
    minds = drill.minds(arena, rngs)
    mind = minds[DEFENDER]
    reach = drill.plan_for(arena.facts).kickable_distance_m  # type: ignore[attr-defined]
    state = {"trigger": -1, "distance": _distance(arena), "dashes": 0}

    def observe(a: object, percepts: list[Percept]) -> None:
        tally = arena.command_tally()[DEFENDER].counts  # type: ignore[attr-defined]
        distance = _distance(arena)
        if state["trigger"] < 0 and getattr(mind, "triggered", False):
            state["trigger"] = arena.tick
        elif state["trigger"] >= 0 and state["distance"] > reach and distance < state["distance"]:
            cell.eligible += 1
            cell.dashes += tally[DASH] > state["dashes"]
        state["distance"], state["dashes"] = distance, tally[DASH]

    verdict = TrialLoop(arena, drill, minds, observe).run()
    cell.trials += 1
    cell.saves += verdict is not None and verdict.label == "SAVE"


def _distance(arena: object) -> float:
    b, d = arena.ball_state(), arena.player_state(DEFENDER)  # type: ignore[attr-defined]
    return math.hypot(b.x - d.x, b.y - d.y)


def spec_for(
    preset: str, client: str, behaviour: str, model: str, seed: int, noise: float
) -> TrialSpec:
    """The drill's spec for one cell (a net from another preset needs ``transfer``)."""
    options: dict[str, object] = {"behaviour": behaviour}
    if client != "see":
        options["client"] = client
    if model:
        options["model"] = model
        options["transfer"] = True
    spec = TrialSpec("intercept", "soccer_server", preset, seed=seed)
    return spec.with_options(**options).with_field(ball_noise=noise)  # type: ignore[arg-type]


def percent(k: int, n: int) -> str:
    """The share k of n as a percentage with its 95% Wilson interval."""
    lo, hi = wilson_interval(k, n)
    return f"{100 * k / n:.1f} [{100 * lo:.1f}, {100 * hi:.1f}]"


def main() -> None:
    """Print the table (markdown) for the presets asked for."""
    from field_models.arena import COMMAND_COUNTERS

    assert COMMAND_COUNTERS[DASH] == "dash"
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--presets", default="rcssserver_19,rcssserver_19_async")
    parser.add_argument("--clients", default="see,cycle")
    parser.add_argument("--behaviours", default="straight,analytic,net")
    parser.add_argument("--net-see", default="")
    parser.add_argument("--net-cycle", default="")
    parser.add_argument("--trials", type=int, default=2000)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--noise", type=float, default=0.05)
    args = parser.parse_args()
    nets = {"see": args.net_see, "cycle": args.net_cycle}
    print("| preset | behaviour | client | n | saves % [95%] | dash share % [95%] (cycles) | s |")
    print("|---|---|---|---|---|---|---|")
    for preset in args.presets.split(","):
        for behaviour in args.behaviours.split(","):
            for client in args.clients.split(","):
                model = nets[client] if behaviour == "net" else ""
                if behaviour == "net" and not model:
                    continue
                spec = spec_for(preset, client, behaviour, model, args.seed, args.noise)
                cell, start = Cell(), time.perf_counter()
                for i in range(args.trials):
                    play(spec, i, cell)
                wall = time.perf_counter() - start
                share = percent(cell.dashes, cell.eligible) if cell.eligible else "-"
                saves = percent(cell.saves, cell.trials)
                print(
                    f"| `{preset}` | {behaviour} | {client} | {cell.trials} | {saves} | "
                    f"{share} ({cell.eligible}) | {wall:.0f} |",
                    flush=True,
                )


if __name__ == "__main__":
    main()
