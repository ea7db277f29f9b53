"""Robot testbed real-time factor against robot count (camera, host, link, firmware running)."""

from __future__ import annotations

import json
import statistics

from field_models.robot_physics.bench import realtime_factor

if __name__ == "__main__":
    figures = {}
    for n in (2, 4, 6, 12, 22):
        runs = [realtime_factor(n, sim_seconds=10.0, seed=s) for s in range(3)]
        figures[f"{n}_robots"] = round(statistics.median(runs), 1)
    print(json.dumps({"robot_physics": {"realtime_factor": figures}}, indent=2))
