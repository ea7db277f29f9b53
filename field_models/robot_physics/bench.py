"""Speed of the robot testbed: simulated seconds per wall second (the ``robot_physics`` figures).

``realtime_factor.N_robots``: one process, N robots (two teams) placed at random, all chasing a
ball rolled from the centre, with camera, host, link and firmware running.

``chipmunk_realtime_factor.N_robots``: the same pymunk world (the same walls, ball, robots,
control bodies and joints, placed the same way) stepped with ``space.step`` alone, measured in
the same run: each robot's control body drives at the top wheel speed toward the centre, where
the ball starts, so the robots converge and collide as the chasers do. Nothing else runs.

``share_of_chipmunk.N_robots``: the first over the second, the median over the repeats of each
repeat's ratio (the two are measured back to back, so the figure means the same on any
machine; DESIGN.md §6).
"""

from __future__ import annotations

import math
import statistics
import time
from typing import Any

from field_models.benchmarks import ChaseLoad, drive
from field_models.protocol import LEFT, RIGHT, PlayerRef
from field_models.registry import make_arena
from field_models.robot_physics.arena import RobotArena
from field_models.seeding import TrialRngs


def bench_arena(n_robots: int, seed: int = 0) -> RobotArena:
    """The benchmark's arena: `n_robots` (two teams) placed at random, the ball rolled."""
    players = tuple(PlayerRef(LEFT if i % 2 == 0 else RIGHT, i // 2 + 1) for i in range(n_robots))
    rngs = TrialRngs.for_trial(seed, 0)
    arena = make_arena("robot_physics", "small_size_1997", players, rngs)
    assert isinstance(arena, RobotArena)
    rng = rngs["placement"]
    pitch = arena.facts.pitch
    hl, hw = pitch.half_length_m, pitch.half_width_m
    for ref in players:
        x, y = rng.uniform(-0.9 * hl, 0.9 * hl), rng.uniform(-0.9 * hw, 0.9 * hw)
        arena.place_player(ref, float(x), float(y), float(rng.uniform(-math.pi, math.pi)))
    arena.place_ball(0.0, 0.0, 1.0, 0.5)
    return arena


def realtime_factor(n_robots: int, sim_seconds: float = 20.0, seed: int = 0) -> float:
    """Simulated seconds per wall second with `n_robots` chasing the ball."""
    arena = bench_arena(n_robots, seed)
    minds = {ref: ChaseLoad() for ref in arena.players}
    ticks = round(sim_seconds / arena.facts.dt_s)
    start = time.perf_counter()
    drive(arena, minds, ticks)
    return ticks * arena.facts.dt_s / (time.perf_counter() - start)


def chipmunk_realtime_factor(n_robots: int, sim_seconds: float = 20.0, seed: int = 0) -> float:
    """Simulated seconds per wall second of the benchmark's world under ``space.step`` alone."""
    arena = bench_arena(n_robots, seed)
    world = arena.world
    speed = world.preset.robot.max_wheel_speed_mps
    for i in range(n_robots):
        x, y, _ = world.robot_pose(i)
        norm = math.hypot(x, y) or 1.0
        world.drive_control(i, -speed * x / norm, -speed * y / norm, 0.0)
    space, dt = world.space, world.dt_s
    ticks = round(sim_seconds / dt)
    start = time.perf_counter()
    for _ in range(ticks):
        space.step(dt)
    return ticks * dt / (time.perf_counter() - start)


def share_figures(n_robots: int, sim_seconds: float, repeats: int) -> dict[str, float]:
    """Engine and ``space.step``-only real-time factors and their ratio, measured alternately.

    Each repeat measures the engine, then the bare world; the figures are medians over the
    repeats (the ratio is the median of the repeats' ratios).
    """
    engine, bare = [], []
    for _ in range(repeats):
        engine.append(realtime_factor(n_robots, sim_seconds))
        bare.append(chipmunk_realtime_factor(n_robots, sim_seconds))
    ratios = [e / b for e, b in zip(engine, bare, strict=True)]
    return {
        "engine": statistics.median(engine),
        "chipmunk": statistics.median(bare),
        "share": statistics.median(ratios),
    }


def benchmarks(quick: bool = False) -> dict[str, Any]:
    """The robot figures with 2 and 12 robots (medians of 3; 1 when quick).

    ``realtime_factor``, ``chipmunk_realtime_factor`` and ``share_of_chipmunk`` (the module
    docstring).
    """
    repeats = 1 if quick else 3
    sim = 5.0 if quick else 20.0
    two = share_figures(2, sim, repeats)
    twelve = share_figures(12, sim / 2, repeats)
    return {
        "realtime_factor": {
            "2_robots": round(two["engine"], 1),
            "12_robots": round(twelve["engine"], 1),
        },
        "chipmunk_realtime_factor": {
            "2_robots": round(two["chipmunk"], 1),
            "12_robots": round(twelve["chipmunk"], 1),
        },
        "share_of_chipmunk": {
            "2_robots": round(two["share"], 3),
            "12_robots": round(twelve["share"], 3),
        },
    }
