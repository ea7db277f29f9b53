"""The pass drill's see cycles on the Soccer Server: all percepts at once against one see at a time.

Plays `--trials` pass trials (seed 1, the drill's defaults, as ``robotsoccer bench`` does) and
records every cycle in which sees are built: the observers, every object's state, the landmark
mode. It then builds those cycles' percepts both ways, alternating for `--rounds` rounds, each
way with a fresh sensing stream of the same seed: the arena's route
(:func:`field_models.soccer_server.percepts_many.percepts_of`) and
:func:`field_models.soccer_server.percepts.percept_from_state` for each observer in turn (issue
21, item 3). Times are the process's CPU time per cycle; the ratio is per round. It also checks
that both ways gave the same percepts. One JSON object.

    python benchmarks/server_see_cycles.py [--trials 100] [--rounds 5]
"""

from __future__ import annotations

import argparse
import json
import statistics
import time
from collections.abc import Callable
from typing import Any

from field_models.protocol import Percept
from field_models.seeding import TrialRngs
from field_models.soccer_server import arena as arena_module
from field_models.soccer_server.percepts import percept_from_state
from field_models.soccer_server.percepts_many import percepts_of
from field_models.soccer_server.sensing import Bodies
from robotsoccer.runs.runner import TrialSpec, run_trial

Cycle = tuple[Any, ...]
"""One recorded see cycle: the arguments of ``percepts_of`` but the stream and what was heard."""


def record_cycles(trials: int) -> list[Cycle]:
    """The see cycles of `trials` pass trials (the arena's own calls, state copied)."""
    cycles: list[Cycle] = []
    built = arena_module.percepts_of

    def recording(observers: Any, bodies: Bodies, players: Any, *rest: Any) -> list[Percept]:
        params, _, time_, _, landmarks = rest
        # Copies of the columns, which the model goes on changing after the call.
        b = bodies
        state = Bodies(list(b.x), list(b.y), list(b.vx), list(b.vy), list(b.heading), b.neck)
        cycles.append((tuple(observers), state, players, params, time_, landmarks))
        return built(observers, bodies, players, *rest)

    arena_module.percepts_of = recording  # type: ignore[assignment]
    try:
        spec = TrialSpec(drill="pass", field_model="soccer_server", seed=1)
        for index in range(trials):
            run_trial(spec, index)
    finally:
        arena_module.percepts_of = built
    return cycles


def at_once(cycle: Cycle, rng: Any) -> list[Percept]:
    """The arena's route: every observer's percept of the cycle in one call."""
    observers, bodies, players, params, time_, landmarks = cycle
    heard = [()] * len(observers)
    return percepts_of(observers, bodies, players, params, rng, time_, heard, landmarks)


def one_at_a_time(cycle: Cycle, rng: Any) -> list[Percept]:
    """The one-player route, observer after observer."""
    observers, b, players, params, time_, landmarks = cycle
    return [
        percept_from_state(row, b, players, time_, params, rng, landmarks=landmarks)
        for row in observers
    ]


def cpu_us_per_cycle(route: Callable[[Cycle, Any], list[Percept]], cycles: list[Cycle]) -> float:
    """CPU µs per cycle of `route` over all `cycles`, on a fresh sensing stream."""
    rng = TrialRngs.for_trial(0, 0)["sensing"]
    start = time.process_time_ns()
    for cycle in cycles:
        route(cycle, rng)
    return (time.process_time_ns() - start) / len(cycles) / 1e3


def main() -> None:
    """Print the figures as JSON (module docstring)."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--trials", type=int, default=100)
    parser.add_argument("--rounds", type=int, default=5)
    args = parser.parse_args()
    cycles = record_cycles(args.trials)
    old, new = [], []
    for _ in range(args.rounds):
        old.append(cpu_us_per_cycle(one_at_a_time, cycles))
        new.append(cpu_us_per_cycle(at_once, cycles))
    ratios = [n / o for n, o in zip(new, old, strict=True)]
    rng_a, rng_b = (TrialRngs.for_trial(0, 0)["sensing"] for _ in range(2))
    same = all(one_at_a_time(c, rng_a) == at_once(c, rng_b) for c in cycles)
    figures = {
        "cycles": len(cycles),
        "observers_per_cycle": round(sum(len(c[0]) for c in cycles) / len(cycles), 2),
        "one_at_a_time_us_per_cycle": round(statistics.median(old), 1),
        "at_once_us_per_cycle": round(statistics.median(new), 1),
        "ratio_median": round(statistics.median(ratios), 3),
        "ratio_range": [round(min(ratios), 3), round(max(ratios), 3)],
        "identical_percepts": same,
    }
    print(json.dumps(figures, indent=1))


if __name__ == "__main__":
    main()
