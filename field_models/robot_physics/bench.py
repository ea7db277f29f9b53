"""Speed of the robot testbed: simulated seconds per wall second (the ``robot_physics`` figures).

``realtime_factor.N_robots``: one process, N robots (two teams) placed at random, all chasing a
ball rolled from the centre, with camera, host, link and firmware running.

``chipmunk_realtime_factor.N_robots`` and ``share_of_chipmunk.N_robots`` (issue 21's figure):
the same pymunk world (the same walls, ball, robots, control bodies and joints, placed the same
way, the ball rolled the same) stepped with ``space.step`` alone, its robots driven as in shared
``specs/robot_physics.md`` §3.7: every 0.25 s each robot's control body takes a random wheel
command (forward speed up to the top wheel speed along the robot's heading then, turn rate up to
a third of the top rate), held until the next. The share is the engine's real-time factor over
this one, each repeat measuring both back to back; the median of the repeats' ratios. It means
the same on any machine (DESIGN.md §6).

``step_share.N_robots``: the share of the engine's own time spent in Chipmunk's step
(``cpSpaceStep``, the call under ``space.step``), from the same chase run again with each step
timed (same seed: the same world and motion, bit for bit). The bare world above moves otherwise
than the chase, so its contacts, and Chipmunk's work, differ; this figure has no such gap.
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


def bench_arena(n_robots: int, seed: int = 0, preset: str = "small_size_1997") -> RobotArena:
    """The benchmark's arena: `n_robots` (two teams) placed at random, the ball rolled.

    `preset`: the robot preset (the benchmark's figures use the default).
    """
    players = tuple(PlayerRef(LEFT if i % 2 == 0 else RIGHT, i // 2 + 1) for i in range(n_robots))
    rngs = TrialRngs.for_trial(seed, 0)
    arena = make_arena("robot_physics", preset, players, rngs)
    assert isinstance(arena, RobotArena)
    rng = rngs["placement"]
    pitch = arena.facts.pitch
    hl, hw = pitch.half_length_m, pitch.half_width_m
    for ref in players:
        x, y = rng.uniform(-0.9 * hl, 0.9 * hl), rng.uniform(-0.9 * hw, 0.9 * hw)
        arena.place_player(ref, float(x), float(y), float(rng.uniform(-math.pi, math.pi)))
    arena.place_ball(0.0, 0.0, 1.0, 0.5)
    return arena


def realtime_factor(
    n_robots: int, sim_seconds: float = 20.0, seed: int = 0, preset: str = "small_size_1997"
) -> float:
    """Simulated seconds per wall second with `n_robots` chasing the ball (on `preset`)."""
    arena = bench_arena(n_robots, seed, preset)
    minds = {ref: ChaseLoad() for ref in arena.players}
    ticks = round(sim_seconds / arena.facts.dt_s)
    start = time.perf_counter()
    drive(arena, minds, ticks)
    return ticks * arena.facts.dt_s / (time.perf_counter() - start)


def step_realtime_factor(n_robots: int, sim_seconds: float = 20.0, seed: int = 0) -> float:
    """Simulated seconds per wall second spent in ``cpSpaceStep`` during the same chase.

    The run of :func:`realtime_factor` with the same arguments, each tick's ``cpSpaceStep``
    timed on its own (the module docstring).
    """
    arena = bench_arena(n_robots, seed)
    world = arena.world
    raw = world.space_step
    clock = time.perf_counter
    spent = [0.0]

    def timed(space: Any, dt: float) -> None:
        start = clock()
        raw(space, dt)
        spent[0] += clock() - start

    world.space_step = timed
    minds = {ref: ChaseLoad() for ref in arena.players}
    ticks = round(sim_seconds / arena.facts.dt_s)
    drive(arena, minds, ticks)
    return ticks * arena.facts.dt_s / spent[0]


COMMAND_PERIOD_S = 0.25
"""How long the bare world's robots hold each random wheel command (robot_physics.md §3.7)."""


def chipmunk_realtime_factor(n_robots: int, sim_seconds: float = 20.0, seed: int = 0) -> float:
    """Simulated seconds per wall second of the benchmark's world under ``space.step`` alone.

    Robots driven by held random commands (the module docstring); the commands' few Python
    updates are timed too (one per robot per 60 steps).
    """
    arena = bench_arena(n_robots, seed)
    world = arena.world
    robot = world.preset.robot
    rng = TrialRngs.for_trial(seed, 0)["movement"]
    drives = world.drive_bodies()
    space, dt = world.space, world.dt_s
    period = max(1, round(COMMAND_PERIOD_S / dt))
    ticks = round(sim_seconds / dt)
    draws = rng.uniform(-1.0, 1.0, (ticks // period + 1, n_robots, 2)).tolist()
    vmax, rate = robot.max_wheel_speed_mps, robot.max_turn_rate_radps / 3.0
    start = time.perf_counter()
    for tick in range(ticks):
        if tick % period == 0:
            for (body, control), (v, w) in zip(drives, draws[tick // period], strict=True):
                heading = body.angle
                control.velocity = (vmax * v * math.cos(heading), vmax * v * math.sin(heading))
                control.angular_velocity = rate * w
        space.step(dt)
    return ticks * dt / (time.perf_counter() - start)


def share_figures(n_robots: int, sim_seconds: float, repeats: int) -> dict[str, float]:
    """The engine's real-time factor beside the bare world's and its own steps' (module doc).

    Each repeat measures the three back to back; the figures are medians over the repeats, the
    ratios the medians of the repeats' ratios.
    """
    engine, bare, steps = [], [], []
    for _ in range(repeats):
        engine.append(realtime_factor(n_robots, sim_seconds))
        bare.append(chipmunk_realtime_factor(n_robots, sim_seconds))
        steps.append(step_realtime_factor(n_robots, sim_seconds))
    return {
        "engine": statistics.median(engine),
        "chipmunk": statistics.median(bare),
        "share": statistics.median(e / b for e, b in zip(engine, bare, strict=True)),
        "step_share": statistics.median(e / s for e, s in zip(engine, steps, strict=True)),
    }


def benchmarks(quick: bool = False) -> dict[str, Any]:
    """The robot figures with 2 and 12 robots (medians of 3; 1 when quick; module docstring)."""
    repeats = 1 if quick else 3
    sim = 5.0 if quick else 20.0
    runs = {
        "2_robots": share_figures(2, sim, repeats),
        "12_robots": share_figures(12, sim / 2, repeats),
    }
    return {
        "realtime_factor": {k: round(v["engine"], 1) for k, v in runs.items()},
        "chipmunk_realtime_factor": {k: round(v["chipmunk"], 1) for k, v in runs.items()},
        "share_of_chipmunk": {k: round(v["share"], 3) for k, v in runs.items()},
        "step_share": {k: round(v["step_share"], 3) for k, v in runs.items()},
    }
