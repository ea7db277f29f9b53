"""Calibration's traces (issue 20, step 1 of :mod:`robotsoccer.experiments.calibration`).

On any field model, through the arena interface only (coach placements, the truth, the percepts
a client gets), :func:`record_traces` records

* the ball rolling free after a launch at each of the drill's launch speeds (its speed at every
  tick, no ball noise);
* a player at rest commanded ``DASH 100`` at every tick (its speed at every tick);
* a player and a ball at rest 20, 25 and 30 units apart: the percepts' arrival ticks, their
  sample ticks (latency) and the seen distance's log error (sensing noise).

Speeds are in drill units per second (:attr:`~field_models.arena.FieldFacts.unit_m`), so a trace
of the robot table and one of the server's pitch are in the same units.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

from field_models.arena import FieldFacts, FieldOptions
from field_models.protocol import RIGHT, Dash, PlayerRef
from field_models.registry import make_arena
from field_models.seeding import TrialRngs

PLAYER = PlayerRef(RIGHT, 1)
"""The one player of the traces."""

TRACE_S = 1.0
"""Each motion trace lasts this long [s]: past a robot's time to top speed (0.4 s) and a 0.7 m
shot's flight."""

STILL_DISTANCES_UNITS = (20.0, 25.0, 30.0)
"""Ball-to-player distances of the sensing trace [units]: the drill's start distances."""

STILL_TRACE_S = 2.0
"""The sensing trace's length at each distance [s]."""

DASH_POWER = 100.0
"""The dash of the traces (the drills' defenders dash at full power)."""


@dataclass(frozen=True)
class Traces:
    """What one field model did, as a client and a coach see it, in units and seconds.

    Attributes:
        field_model: The field model recorded.
        preset: Its preset.
        seed: The recording's experiment seed.
        unit_m: One drill unit on that field [m].
        dt_s: Its tick [s].
        ball: For each launch, the ball's speed after every tick [units/s].
        launch_speeds: Each launch's speed [units/s].
        dash: The player's speed after every tick of ``DASH 100`` from rest [units/s].
        percept_ticks: The ticks at which the still player's percepts arrived.
        latency_ticks: Each such percept's arrival tick minus its sample tick.
        log_errors: log(seen distance / true distance) of the ball at rest, per percept.
    """

    field_model: str
    preset: str
    seed: int
    unit_m: float
    dt_s: float
    ball: tuple[tuple[float, ...], ...]
    launch_speeds: tuple[float, ...]
    dash: tuple[float, ...]
    percept_ticks: tuple[int, ...]
    latency_ticks: tuple[int, ...]
    log_errors: tuple[float, ...]


def record_traces(
    field_model: str, preset: str, launch_speeds_units: Sequence[float], seed: int
) -> Traces:
    """Record the ball, dash and sensing traces of one field model (module docstring, step 1).

    Args:
        field_model: The field model.
        preset: Its preset (a name or a ``.toml`` path).
        launch_speeds_units: The ball launches' speeds [units/s].
        seed: The experiment seed (trial i of the recording uses stream i).

    Raises:
        ValueError: No launch speed, or one that is not positive.
    """
    if not launch_speeds_units or min(launch_speeds_units) <= 0.0:
        raise ValueError(f"launch speeds must be positive units/s, got {launch_speeds_units!r}")
    options = FieldOptions(ball_noise=0.0)
    ball = []
    facts: FieldFacts | None = None
    for k, speed in enumerate(launch_speeds_units):
        arena = make_arena(field_model, preset, (PLAYER,), TrialRngs.for_trial(seed, k), options)
        facts = arena.facts
        u = facts.unit_m
        # The player stands aside, out of the ball's way; the ball rolls along the long axis.
        arena.place_player(PLAYER, 0.0, 0.8 * facts.pitch.half_width_m, 0.0)
        start = -0.5 * speed * TRACE_S * u
        arena.place_ball(start, 0.0, speed * u, 0.0)
        speeds = []
        for _ in range(_ticks(TRACE_S, facts.dt_s)):
            arena.step()
            speeds.append(arena.ball_state().speed / u)
        ball.append(tuple(speeds))
    n = len(launch_speeds_units)
    arena = make_arena(field_model, preset, (PLAYER,), TrialRngs.for_trial(seed, n), options)
    facts = arena.facts
    u = facts.unit_m
    arena.place_player(PLAYER, -0.5 * facts.pitch.half_length_m, 0.0, 0.0)
    arena.place_ball(0.0, 0.9 * facts.pitch.half_width_m)
    dash = []
    for _ in range(_ticks(TRACE_S, facts.dt_s)):
        arena.submit(PLAYER, (Dash(DASH_POWER),))
        arena.step()
        dash.append(arena.player_state(PLAYER).speed / u)
    ticks: list[int] = []
    latency: list[int] = []
    errors: list[float] = []
    for j, distance in enumerate(STILL_DISTANCES_UNITS):
        rngs = TrialRngs.for_trial(seed, n + 1 + j)
        arena = make_arena(field_model, preset, (PLAYER,), rngs, options)
        facts = arena.facts
        u = facts.unit_m
        arena.place_player(PLAYER, 0.0, 0.0, math.pi)
        arena.place_ball(-distance * u, 0.0)
        for _ in range(_ticks(STILL_TRACE_S, facts.dt_s)):
            for percept in arena.step():
                if percept.player != PLAYER:
                    continue
                if j == 0:
                    ticks.append(percept.tick)
                latency.append(percept.tick - percept.observed_tick)
                if percept.ball is not None and percept.ball.distance_m > 0.0:
                    truth = arena.truth()
                    me, it = truth.players[PLAYER], truth.ball
                    true = math.hypot(it.x - me.x, it.y - me.y)
                    errors.append(math.log(percept.ball.distance_m / true))
    assert facts is not None
    return Traces(
        field_model=field_model,
        preset=preset,
        seed=seed,
        unit_m=facts.unit_m,
        dt_s=facts.dt_s,
        ball=tuple(ball),
        launch_speeds=tuple(float(s) for s in launch_speeds_units),
        dash=tuple(dash),
        percept_ticks=tuple(ticks),
        latency_ticks=tuple(latency),
        log_errors=tuple(errors),
    )


def _ticks(seconds: float, dt_s: float) -> int:
    return max(2, round(seconds / dt_s))
