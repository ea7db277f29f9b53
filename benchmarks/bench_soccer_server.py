"""Soccer Server speed per preset: bare dynamics (one trial), the full arena, and batch mode.

Targets: >= 30,000 cycles/s for 2 players + ball in one process *including sensing* (`arena`),
and >= 2,000,000 object-cycles/s in batch mode. Prints JSON; medians of 3 repeats. The
measuring code is `field_models/soccer_server/bench.py`, shared with `robotsoccer bench`.
"""

from __future__ import annotations

import json
import statistics

from field_models.soccer_server.bench import (
    arena_cycles_per_s,
    batch_object_cycles_per_s,
    dynamics_cycles_per_s,
)


def median3(measure) -> float:
    return round(statistics.median(measure() for _ in range(3)))


def figures_for(preset: str) -> dict[str, float]:
    return {
        "dynamics_cycles_per_s": median3(lambda: dynamics_cycles_per_s(20000, preset)),
        "arena_cycles_per_s": median3(lambda: arena_cycles_per_s(20000, preset)),
        "batch_object_cycles_per_s": median3(lambda: batch_object_cycles_per_s(200, 2000, preset)),
    }


if __name__ == "__main__":
    presets = ("soccer_server_1996", "rcssserver_19_async")
    print(json.dumps({"soccer_server": {p: figures_for(p) for p in presets}}, indent=2))
