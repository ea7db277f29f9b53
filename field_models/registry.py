"""Build an arena for a field model by name: the one place that knows both models exist."""

from __future__ import annotations

import dataclasses
from functools import lru_cache

from field_models.arena import Arena
from field_models.protocol import PlayerRef
from field_models.robot_physics.config import RobotPhysicsPreset
from field_models.robot_physics.config import load_preset as _load_robot_preset
from field_models.seeding import TrialRngs
from field_models.soccer_server.params import ServerPreset
from field_models.soccer_server.params import load_server_preset as _load_server_preset

FIELD_MODELS = ("robot_physics", "soccer_server")
"""Field models an arena can be built for."""

DEFAULT_PRESETS = {"robot_physics": "small_size_1997", "soccer_server": "soccer_server_1996"}
"""Each field model's default preset."""


def make_arena(
    field_model: str,
    preset: str,
    players: tuple[PlayerRef, ...],
    rngs: TrialRngs,
    *,
    perfect: bool = False,
    keep_events: bool = False,
    trace: bool = False,
    ball_noise: float | None = None,
    camera_latency_s: float | None = None,
    ball_noise_period_s: float | None = None,
) -> Arena:
    """A fresh arena of `field_model` loaded with `preset` and the given players.

    Raises:
        ValueError: for an unknown field model.
        field_models.presets.PresetError: for a missing or wrong preset.

    `keep_events` keeps commands and messages for `Arena.drain_events` (recordings);
    `trace` also renders the Soccer Server's messages as text (robots: same as keep_events).
        field_models.presets.PresetError: for a missing or wrong preset.
    """
    if field_model == "robot_physics":
        from field_models.robot_physics.arena import RobotArena

        robot = robot_preset(preset, ball_noise, camera_latency_s, ball_noise_period_s)
        return RobotArena(robot, players, rngs, perfect=perfect, keep_events=keep_events or trace)
    if field_model == "soccer_server":
        from field_models.soccer_server.arena import SoccerServerArena

        if camera_latency_s is not None or ball_noise_period_s is not None:
            raise ValueError("camera latency and ball-noise period are robot_physics settings")
        server = server_preset(preset, ball_noise)
        return SoccerServerArena(server, players, rngs, keep_events=keep_events, trace=trace)
    raise ValueError(f"unknown field model {field_model!r} (known: {', '.join(FIELD_MODELS)})")


@lru_cache(maxsize=32)
def robot_preset(
    name: str,
    ball_noise: float | None = None,
    camera_latency_s: float | None = None,
    ball_noise_period_s: float | None = None,
) -> RobotPhysicsPreset:
    """A robot preset with optional overrides (loaded once per process: trials share it)."""
    preset = _load_robot_preset(name)
    if ball_noise is not None:
        preset = dataclasses.replace(
            preset, ball=dataclasses.replace(preset.ball, motion_noise=ball_noise)
        )
    if ball_noise_period_s is not None:
        ball = dataclasses.replace(preset.ball, noise_period_s=ball_noise_period_s)
        preset = dataclasses.replace(preset, ball=ball)
        preset.ticks(ball_noise_period_s, "ball.noise_period_s")  # refuse a fraction of a tick
    if camera_latency_s is not None:
        camera = dataclasses.replace(preset.camera, latency_s=camera_latency_s)
        preset = dataclasses.replace(preset, camera=camera)
        preset.ticks(camera_latency_s, "camera.latency_s")  # refuse a fraction of a tick
    return preset


@lru_cache(maxsize=32)
def server_preset(name: str, ball_noise: float | None = None) -> ServerPreset:
    """A Soccer Server preset with an optional ``ball_rand`` override (loaded once per process)."""
    preset = _load_server_preset(name)
    if ball_noise is not None:
        preset = preset.replace_dynamics(ball_rand=ball_noise)
    return preset
