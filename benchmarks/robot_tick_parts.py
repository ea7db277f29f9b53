"""Where a robot tick's time goes: CPU µs per tick of each part of the engine (issue 21's profile).

The benchmark's chase (``field_models.robot_physics.bench``: N robots chasing a rolled ball, camera,
host, link and firmware running) with a timer around each part; the rest of the arena's step is
the drive loop. Times are the process's CPU time (a shared machine's load does not count), and
the timers' own cost, measured in the same process around a call that does nothing, is taken off
each part per call and off the total. A part timed inside another (the world's wheel targets,
set by the firmware) counts only in itself. Medians over repeats, one JSON object.

``--preset`` profiles another robot preset, e.g. ``small_size_1997_motor`` (the motor drive,
issue 21): there "steering" is the drive events (:class:`~field_models.robot_physics.motor.
MotorWorld`), and "wheel_targets" includes re-planning a robot whose targets changed.

    python benchmarks/robot_tick_parts.py [--robots 2 12] [--seconds 20] [--repeats 3]
        [--preset small_size_1997]
"""

from __future__ import annotations

import argparse
import json
import statistics
import time
from collections.abc import Callable
from typing import Any

from field_models.benchmarks import ChaseLoad
from field_models.robot_physics.bench import bench_arena
from field_models.robot_physics.config import DEFAULT_PRESET

PARTS = (
    "chipmunk_step",
    "steering",
    "percepts",
    "camera",
    "actions_to_link",
    "link_delivery",
    "firmware",
    "wheel_targets",
    "minds",
)
"""The timed parts, in the order the table prints them."""


def _timed(
    spent: dict[str, float],
    calls: dict[str, int],
    part: str,
    fn: Callable[..., Any],
    inner: list[int] | None = None,
) -> Callable[..., Any]:
    """`fn` timed into `spent[part]`, less the time of timed parts it calls (`inner`: shared)."""
    clock = time.process_time_ns
    nested = inner if inner is not None else []

    def wrapper(*args: Any, **kwargs: Any) -> Any:
        start = clock()
        nested.append(0)
        try:
            return fn(*args, **kwargs)
        finally:
            elapsed = clock() - start
            spent[part] += elapsed - nested.pop()
            calls[part] += 1
            if nested:
                nested[-1] += elapsed

    return wrapper


def _timer_cost(n: int = 20000) -> tuple[float, float]:
    """(ns a timed call that does nothing records, ns it costs in all beyond the plain call)."""
    spent, calls = {"x": 0.0}, {"x": 0}
    wrapped = _timed(spent, calls, "x", _nothing)
    clock = time.process_time_ns
    start = clock()
    for _ in range(n):
        _nothing()
    plain = clock() - start
    start = clock()
    for _ in range(n):
        wrapped()
    timed = clock() - start
    return spent["x"] / n, (timed - plain) / n


def _nothing() -> None:
    return None


def tick_parts(
    n_robots: int, sim_seconds: float, seed: int = 0, preset: str = DEFAULT_PRESET
) -> dict[str, float]:
    """CPU µs per tick of each part, and the total, in one chase run (module docstring)."""
    inside, whole = _timer_cost()
    arena = bench_arena(n_robots, seed, preset)
    spent = dict.fromkeys(PARTS, 0.0)
    calls = dict.fromkeys(PARTS, 0)
    world, host, camera = arena.world, arena.host, arena.camera
    world.space_step = _timed(spent, calls, "chipmunk_step", world.space_step)
    if hasattr(world, "_run_events"):  # the motor drive (field_models/robot_physics/motor.py)
        world._run_events = _timed(spent, calls, "steering", world._run_events)  # type: ignore[method-assign]
    else:
        world._steer = _timed(spent, calls, "steering", world._steer)  # type: ignore[method-assign]
        if hasattr(world, "_cruise"):  # steady-speed steering, split off by issue 21's speed-up
            world._cruise = _timed(spent, calls, "steering", world._cruise)  # type: ignore[method-assign]
    nested: list[int] = []  # the firmware sets the wheel targets: timed apart
    world.set_wheel_targets = _timed(spent, calls, "wheel_targets", world.set_wheel_targets, nested)  # type: ignore[method-assign]
    host.percepts = _timed(spent, calls, "percepts", host.percepts)  # type: ignore[method-assign]
    camera.capture = _timed(spent, calls, "camera", camera.capture)  # type: ignore[method-assign]
    camera.deliver = _timed(spent, calls, "camera", camera.deliver)  # type: ignore[method-assign]
    host.submit = _timed(spent, calls, "actions_to_link", host.submit)  # type: ignore[method-assign]
    arena.link.deliver = _timed(spent, calls, "link_delivery", arena.link.deliver)  # type: ignore[method-assign]
    arena._run_firmware = _timed(spent, calls, "firmware", arena._run_firmware, nested)  # type: ignore[method-assign]
    minds = {ref: ChaseLoad() for ref in arena.players}
    for mind in minds.values():
        mind.act = _timed(spent, calls, "minds", mind.act)  # type: ignore[method-assign]
    ticks = round(sim_seconds / arena.facts.dt_s)
    start = time.process_time_ns()
    for _ in range(ticks):
        for percept in arena.step():
            arena.submit(percept.player, minds[percept.player].act(percept))
    total = time.process_time_ns() - start - whole * sum(calls.values())
    out = {part: (spent[part] - inside * calls[part]) / ticks / 1e3 for part in PARTS}
    out["drive_loop"] = total / ticks / 1e3 - sum(out.values())
    out["total"] = total / ticks / 1e3
    return out


def main() -> None:
    """Print the medians as JSON: {"N_robots": {part: µs per tick}}."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--robots", type=int, nargs="+", default=[2, 12])
    parser.add_argument("--seconds", type=float, default=20.0)
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--preset", default=DEFAULT_PRESET)
    args = parser.parse_args()
    figures: dict[str, dict[str, float]] = {}
    for n in args.robots:
        runs = [tick_parts(n, args.seconds, preset=args.preset) for _ in range(args.repeats)]
        figures[f"{n}_robots"] = {
            k: round(statistics.median(r[k] for r in runs), 2) for k in runs[0]
        }
    print(json.dumps(figures, indent=1))


if __name__ == "__main__":
    main()
