"""Content digests of the robot engine's behaviour on fixed seeds: the identity check of a speed-up.

A change that only makes the robot engine faster (issue 21) must leave everything it computes
bit for bit the same. This script runs, on each robot preset named below:

* a **chase** (``field_models.robot_physics.bench``'s arena: 2 and 12 robots chasing a rolled
  ball), digesting every percept delivered (``repr``: floats exactly) and the world's exact
  truth every tick;
* **intercept**, **pass** and **match** trials through the trial runner, digesting each
  result's table row (floats exactly, :meth:`TrialResult.csv_fields`).

Run it on two trees (``PYTHONPATH=TREE``) and compare the JSON: equal digests, equal behaviour.

    python scripts/robot_digest.py [--quick]
"""

from __future__ import annotations

import argparse
import hashlib
import json
from typing import Any

from field_models.benchmarks import ChaseLoad
from field_models.robot_physics.bench import bench_arena
from robotsoccer.runs.runner import TrialSpec, run_trial

PRESETS = ("small_size_1997", "small_size_1997_arc", "small_size_fast", "vss")
"""The robot presets checked: the default, arcs, the fast robots and the VSS table."""


def chase_digest(preset: str, n_robots: int, ticks: int, seed: int = 0) -> str:
    """SHA-256 of every percept and every tick's truth in a chase of `ticks` ticks."""
    arena = bench_arena(n_robots, seed, preset)
    minds = {ref: ChaseLoad() for ref in arena.players}
    h = hashlib.sha256()
    for _ in range(ticks):
        for percept in arena.step():
            h.update(repr(percept).encode())
            arena.submit(percept.player, minds[percept.player].act(percept))
        h.update(repr(arena.world.truth()).encode())
    return h.hexdigest()


def trials_digest(spec: TrialSpec, trials: int) -> str:
    """SHA-256 of the table rows of trials 0 .. `trials` - 1 of `spec`."""
    h = hashlib.sha256()
    for index in range(trials):
        h.update("\x1f".join(run_trial(spec, index).csv_fields()).encode())
    return h.hexdigest()


def digests(quick: bool) -> dict[str, Any]:
    """Every digest, by preset and run."""
    scale = 1 if quick else 4
    out: dict[str, Any] = {}
    for preset in PRESETS:
        row: dict[str, str] = {}
        for n in (2, 12):
            row[f"chase_{n}"] = chase_digest(preset, n, 600 * scale)

        def spec(drill: str, preset: str = preset) -> TrialSpec:
            return TrialSpec(drill=drill, field_model="robot_physics", preset=preset, seed=1)

        intercept = spec("intercept").with_options(behaviour="straight")
        row["intercept"] = trials_digest(intercept.with_field(ball_noise=0.05), 10 * scale)
        row["pass"] = trials_digest(spec("pass"), 5 * scale)
        match = spec("match").with_options(
            left="baseline", right="baseline", half_time_s=5.0 * scale
        )
        row["match"] = trials_digest(match, 1)
        out[preset] = row
    return out


def main() -> None:
    """Print the digests as JSON."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="shorter runs (a quarter)")
    args = parser.parse_args()
    print(json.dumps(digests(args.quick), indent=1, sort_keys=True))


if __name__ == "__main__":
    main()
