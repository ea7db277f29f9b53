"""Speed measurements behind ``robotsoccer bench``: simulated seconds per wall second, trials/s.

These are benchmarks, not tests: the machines are shared and noisy, so every figure is the
median of several repeats, and no test asserts a speed.

* ``robot_physics.realtime_factor.N_robots`` — one process, N robots (two teams) all chasing the
  ball with full camera, host, link and firmware running; simulated seconds per wall second.
* ``demo.trials_per_s.K_worker(s)`` — the shootout demo drill through the process pool.
* ``soccer_server.cycles_per_s.2_players`` — one trial at a time through the arena: 2 players
  and the ball, both receiving percepts on their see timer and acting on them (dynamics,
  sensing, hearing and the command queue all running).
* ``soccer_server.object_cycles_per_s.batch`` — many trials stepped together as arrays
  (`field_models.soccer_server.batch`), objects × cycles per second.
* ``intercept.trials_per_s.<field model>`` — the layer-1 interception drill (straight
  defender, ball noise 0.05) through the pool with 2 workers, pool start included; enough trials
  that start-up is a small share.
"""

from __future__ import annotations

import math
import platform
import statistics
import time
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

from field_models.protocol import LEFT, RIGHT, Action, Dash, Percept, PlayerRef, Turn
from field_models.registry import make_arena
from field_models.seeding import TrialRngs
from field_models.soccer_server.arena import SoccerServerArena
from field_models.soccer_server.batch import BatchSoccerServer
from field_models.soccer_server.dynamics import SoccerServerModel
from field_models.soccer_server.params import load_server_preset
from robotsoccer.runs.pool import default_workers, run_trials
from robotsoccer.runs.runner import TrialSpec


@dataclass
class ChaseMind:
    """Drive at the perceived ball (turn when off by more than 0.3 rad); a load generator."""

    def act(self, percept: Percept) -> tuple[Action, ...]:
        """One decision per percept."""
        if percept.ball is None:
            return (Turn(0.5),)
        if abs(percept.ball.angle_rad) > 0.3:
            return (Turn(percept.ball.angle_rad),)
        return (Dash(100.0),)


def robot_realtime_factor(n_robots: int, sim_seconds: float = 20.0, seed: int = 0) -> float:
    """Simulated seconds per wall second with `n_robots` chasing the ball (robot physics)."""
    players = tuple(PlayerRef(LEFT if i % 2 == 0 else RIGHT, i // 2 + 1) for i in range(n_robots))
    rngs = TrialRngs.for_trial(seed, 0)
    arena = make_arena("robot_physics", "small_size_1997", players, rngs)
    rng = rngs["placement"]
    hl, hw = arena.pitch.half_length_m, arena.pitch.half_width_m
    for ref in players:
        x, y = rng.uniform(-0.9 * hl, 0.9 * hl), rng.uniform(-0.9 * hw, 0.9 * hw)
        arena.place_player(ref, float(x), float(y), float(rng.uniform(-math.pi, math.pi)))
    arena.place_ball(0.0, 0.0, 1.0, 0.5)
    minds = {ref: ChaseMind() for ref in players}
    ticks = round(sim_seconds / arena.dt_s)
    start = time.perf_counter()
    for _ in range(ticks):
        for percept in arena.step():
            arena.submit(percept.player, minds[percept.player].act(percept))
    wall = time.perf_counter() - start
    return ticks * arena.dt_s / wall


def demo_trials_per_s(workers: int, trials: int, seed: int = 0) -> float:
    """Shootout demo trials per wall second through the pool (pool start-up included)."""
    spec = TrialSpec(seed=seed)
    start = time.perf_counter()
    run_trials(spec, trials, workers=workers, progress=False)
    return trials / (time.perf_counter() - start)


def intercept_trials_per_s(field_model: str, trials: int, workers: int = 2) -> float:
    """Interception-drill trials per wall second through the pool (straight defender)."""
    preset = {"soccer_server": "soccer_server_1996", "robot_physics": "small_size_1997"}
    spec = TrialSpec(
        drill="intercept", field_model=field_model, preset=preset[field_model], seed=1,
        ball_noise=0.05,
    ).with_options(behaviour="straight")  # fmt: skip
    start = time.perf_counter()
    run_trials(spec, trials, workers=workers, progress=False)
    return trials / (time.perf_counter() - start)


def median_of(repeats: int, measure: Callable[[], float]) -> float:
    """Median of `repeats` calls of `measure`."""
    return statistics.median(measure() for _ in range(repeats))


def run_benchmarks(quick: bool = False) -> dict[str, Any]:
    """All benchmark figures as a nested dict (medians of 3 repeats; 1 when `quick`)."""
    repeats = 1 if quick else 3
    sim = 5.0 if quick else 20.0
    trials = 100 if quick else 600
    rt2 = median_of(repeats, lambda: robot_realtime_factor(2, sim))
    rt12 = median_of(repeats, lambda: robot_realtime_factor(12, sim / 2))
    demo1 = median_of(repeats, lambda: demo_trials_per_s(1, trials // 2))
    demo2 = median_of(repeats, lambda: demo_trials_per_s(2, trials))
    results: dict[str, Any] = {
        "robot_physics": {
            "realtime_factor": {"2_robots": round(rt2, 1), "12_robots": round(rt12, 1)}
        },
        "demo": {"trials_per_s": {"1_worker": round(demo1, 1), "2_workers": round(demo2, 1)}},
    }
    server_trials, robot_trials = (4000, 2000) if quick else (20000, 6000)
    results["intercept"] = {
        "trials_per_s": {
            "soccer_server": round(
                median_of(repeats, lambda: intercept_trials_per_s("soccer_server", server_trials))
            ),
            "robot_physics": round(
                median_of(repeats, lambda: intercept_trials_per_s("robot_physics", robot_trials))
            ),
        }
    }
    results.update(soccer_server_benchmarks(quick))
    results["machine"] = {
        "python": platform.python_version(),
        "cpu_count": default_workers(),
        "repeats": repeats,
        "statistic": "median",
    }
    return results


# ----------------------------------------------------------------------------- Soccer Server

PLAYERS = (PlayerRef(LEFT, 1), PlayerRef(RIGHT, 1))


def arena_cycles_per_s(cycles: int, preset: str = "soccer_server_1996", seed: int = 0) -> float:
    """Cycles per wall second of a 2-player arena whose players chase the ball."""
    rngs = TrialRngs.for_trial(seed, 0)
    arena = SoccerServerArena.from_preset(preset, PLAYERS, rngs)
    minds = {ref: ChaseMind() for ref in PLAYERS}
    rng = rngs["placement"]
    start = time.perf_counter()
    done = 0
    while done < cycles:
        # A fresh rally every 200 cycles (5% of the time in placement): the ball is kicked off
        # from a random spot so the players keep running, turning and seeing a moving ball.
        arena.place_ball(float(rng.uniform(-30, 30)), float(rng.uniform(-20, 20)), 2.0, 1.0)
        arena.place_player(PLAYERS[0], -40.0, 0.0, 0.0)
        arena.place_player(PLAYERS[1], 40.0, 0.0, math.pi)
        for _ in range(200):
            for percept in arena.step():
                arena.submit(percept.player, minds[percept.player].act(percept))
        done += 200
    return done / (time.perf_counter() - start)


def _drill_like_trial(model: SoccerServerModel | BatchSoccerServer, cycles: int) -> None:
    """A shooter kicks, a defender dashes every cycle and turns every fifth (noise, referee on)."""
    model.move_ball(-20.0, 0.0)
    model.move_player(1, -20.5, 0.0, 0.0)
    model.move_player(2, 5.0, 1.0, math.pi)
    model.kick(1, 80.0, 0.0)
    for t in range(cycles):
        if t % 5 == 0:
            model.turn(2, 0.05)
        else:
            model.dash(2, 60.0)
        model.step()


def dynamics_cycles_per_s(cycles: int, preset: str = "soccer_server_1996") -> float:
    """Cycles per wall second of the bare dynamics (no sensing) for 2 players + ball."""
    model = SoccerServerModel(load_server_preset(preset), PLAYERS, np.random.default_rng(0))
    start = time.perf_counter()
    for _ in range(max(1, cycles // 100)):
        _drill_like_trial(model, 100)
    return max(1, cycles // 100) * 100 / (time.perf_counter() - start)


def batch_object_cycles_per_s(
    cycles: int, trials: int = 2000, preset: str = "soccer_server_1996"
) -> float:
    """Object-cycles per wall second of `trials` 2-player trials stepped as arrays."""
    rngs = [np.random.default_rng([1, k]) for k in range(trials)]
    batch = BatchSoccerServer(load_server_preset(preset), PLAYERS, rngs)
    start = time.perf_counter()
    _drill_like_trial(batch, cycles)
    return trials * (len(PLAYERS) + 1) * cycles / (time.perf_counter() - start)


def soccer_server_benchmarks(quick: bool = False) -> dict[str, Any]:
    """The Soccer Server figures (medians of 3 repeats; 1 when `quick`)."""
    repeats = 1 if quick else 3
    cycles = 4000 if quick else 20000
    single = median_of(repeats, lambda: arena_cycles_per_s(cycles))
    batch = median_of(repeats, lambda: batch_object_cycles_per_s(100 if quick else 300))
    return {
        "soccer_server": {
            "cycles_per_s": {"2_players": round(single)},
            "object_cycles_per_s": {"batch": round(batch)},
        }
    }
