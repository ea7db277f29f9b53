"""The robot-physics field model's registry entry: presets with options, facts, arenas.

See :class:`field_models.registry.FieldModelEntry`. Loading a preset and reading its facts
imports no pymunk; building an arena does.
"""

from __future__ import annotations

import dataclasses
from functools import lru_cache
from typing import Any

from field_models.arena import Arena, BallLaw, FieldFacts, FieldOptions, KickFacts
from field_models.protocol import PlayerRef
from field_models.robot_physics.config import GRAVITY_MPS2, RobotPhysicsPreset, load_preset
from field_models.seeding import TrialRngs

NAME = "robot_physics"
"""The registered name."""
DEFAULT_PRESET = "small_size_1997"
"""The RoboCup-97 small-size table (``field_models/presets/robot_physics``)."""


@lru_cache(maxsize=32)
def load(preset: str, options: FieldOptions) -> RobotPhysicsPreset:
    """The preset with the run's options applied (loaded once per process: trials share it).

    ``sensor_latency_s`` is the camera's latency; times must be whole physics ticks.

    Raises:
        field_models.presets.PresetError: A missing or wrong preset, or a time that is not a
            whole number of ticks.
    """
    loaded = load_preset(preset)
    ball, camera = loaded.ball, loaded.camera
    if options.ball_noise is not None:
        ball = dataclasses.replace(ball, motion_noise=options.ball_noise)
    if options.ball_noise_period_s is not None:
        ball = dataclasses.replace(ball, noise_period_s=options.ball_noise_period_s)
        loaded.ticks(options.ball_noise_period_s, "ball.noise_period_s", least=1)
    if options.sensor_latency_s is not None:
        camera = dataclasses.replace(camera, latency_s=options.sensor_latency_s)
        loaded.ticks(options.sensor_latency_s, "camera.latency_s")
    if options.perfect_perception:
        camera = dataclasses.replace(camera, perfect=True)
    return dataclasses.replace(loaded, ball=ball, camera=camera)


@lru_cache(maxsize=32)
def facts(preset: RobotPhysicsPreset) -> FieldFacts:
    """What the code above the line may know about this table (:class:`FieldFacts`)."""
    robot, ball, camera = preset.robot, preset.ball, preset.camera
    kicker = robot.kicker
    kick = None
    if kicker is not None:
        kick = KickFacts(
            speed_per_power_mps=kicker.max_speed_mps / 100.0,
            max_speed_mps=kicker.max_speed_mps,
            reach_m=0.5 * robot.size_m + ball.radius_m + kicker.reach_m,
            aimable=False,
            half_angle_rad=kicker.half_angle_rad,
        )
    perfect = camera.perfect
    return FieldFacts(
        model=NAME,
        preset=preset.name,
        pitch=preset.pitch(),
        dt_s=preset.dt_s,
        sensor_period_s=1.0 / camera.frame_rate_hz,
        sensor_latency_s=0.0 if perfect else camera.latency_s,
        ball=BallLaw("constant", preset.dt_s, decel_mps2=ball.rolling_decel_mps2),
        ball_max_speed_mps=ball.max_speed_mps,
        ball_noise=ball.motion_noise,
        ball_noise_period_s=ball.noise_period_s,
        kick=kick,
        player_top_speed_mps=robot.max_wheel_speed_mps,
        player_accel_mps2=min(robot.wheel_accel_mps2, robot.tyre_mu * GRAVITY_MPS2),
        heading_sigma_rad=0.0 if perfect else camera.heading_sigma_rad,
        player_shape="square",
        perfect_perception=perfect,
        walled=True,
        landmarks=(
            ("g l", -0.5 * preset.field.length_m, 0.0),
            ("g r", 0.5 * preset.field.length_m, 0.0),
        ),
    )


def build(
    preset: RobotPhysicsPreset,
    facts: FieldFacts,
    players: tuple[PlayerRef, ...],
    rngs: TrialRngs,
    *,
    keep_events: bool,
    trace: bool,
) -> Arena:
    """A fresh robot arena (imports pymunk on first use)."""
    from field_models.robot_physics.arena import RobotArena

    return RobotArena(preset, facts, players, rngs, keep_events=keep_events, trace=trace)


def benchmarks(quick: bool = False) -> dict[str, Any]:
    """This model's own speed figures (:mod:`field_models.robot_physics.bench`)."""
    from field_models.robot_physics.bench import benchmarks as measure

    return measure(quick)
