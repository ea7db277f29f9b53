"""The robot engine's speed under both drives beside bare Chipmunk (issue 21 item 1).

Each repeat runs, back to back in this process, ``robotsoccer bench``'s chase
(:func:`field_models.robot_physics.bench.realtime_factor`) with the kinematic drive
(``small_size_1997``) and with the motor drive (``small_size_1997_motor``), and the bench's bare
Chipmunk world (:func:`~field_models.robot_physics.bench.chipmunk_realtime_factor`, the same for
both: the share's denominator), then the two chases again timed in process CPU time (a shared
machine's other work does not count there). Prints medians over repeats of the real-time
factors, the shares of Chipmunk and the motor/kinematic ratios (wall and CPU), as JSON; 12
robots run half the simulated time, as in the bench.

    python benchmarks/motor_speed.py [--seconds 20] [--repeats 3]
"""

from __future__ import annotations

import argparse
import json
import statistics
import time

from field_models.benchmarks import ChaseLoad, drive
from field_models.robot_physics.bench import bench_arena, chipmunk_realtime_factor, realtime_factor

DRIVES = {"kinematic": "small_size_1997", "motor": "small_size_1997_motor"}


def cpu_realtime_factor(n_robots: int, sim_seconds: float, preset: str) -> float:
    """:func:`realtime_factor`'s chase, simulated seconds per CPU second of this process."""
    arena = bench_arena(n_robots, 0, preset)
    minds = {ref: ChaseLoad() for ref in arena.players}
    ticks = round(sim_seconds / arena.facts.dt_s)
    start = time.process_time()
    drive(arena, minds, ticks)
    return ticks * arena.facts.dt_s / (time.process_time() - start)


def figures(n_robots: int, sim_seconds: float, repeats: int) -> dict[str, float]:
    """Medians over `repeats` of each drive's real-time factor, share and their ratio."""
    rows = []
    for _ in range(repeats):
        row = {d: realtime_factor(n_robots, sim_seconds, preset=p) for d, p in DRIVES.items()}
        row["chipmunk"] = chipmunk_realtime_factor(n_robots, sim_seconds)
        cpu = {d: cpu_realtime_factor(n_robots, sim_seconds, p) for d, p in DRIVES.items()}
        row["cpu_ratio"] = cpu["motor"] / cpu["kinematic"]
        rows.append(row)
    out = {
        f"realtime_factor.{k}": statistics.median(r[k] for r in rows) for k in (*DRIVES, "chipmunk")
    }
    for name in DRIVES:
        out[f"share_of_chipmunk.{name}"] = statistics.median(r[name] / r["chipmunk"] for r in rows)
    out["motor_over_kinematic"] = statistics.median(r["motor"] / r["kinematic"] for r in rows)
    out["motor_over_kinematic.cpu"] = statistics.median(r["cpu_ratio"] for r in rows)
    return {k: round(v, 3) for k, v in out.items()}


def main() -> None:
    """Print the figures for 2 and 12 robots (module docstring)."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seconds", type=float, default=20.0)
    parser.add_argument("--repeats", type=int, default=3)
    args = parser.parse_args()
    result = {
        "2_robots": figures(2, args.seconds, args.repeats),
        "12_robots": figures(12, args.seconds / 2, args.repeats),
    }
    print(json.dumps(result, indent=1))


if __name__ == "__main__":
    main()
