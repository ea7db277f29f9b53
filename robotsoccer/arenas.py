"""Build an arena for a field model by name: the one place that knows both models exist."""

from __future__ import annotations

from field_models.protocol import PlayerRef
from robotsoccer.arena import Arena
from robotsoccer.seeding import TrialRngs

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
        from field_models.robot_physics.config import load_preset
        from robotsoccer.robot_arena import RobotArena

        return RobotArena(
            load_preset(preset), players, rngs, perfect=perfect, keep_events=keep_events or trace
        )
    if field_model == "soccer_server":
        from robotsoccer.server_arena import SoccerServerArena

        return SoccerServerArena.from_preset(
            preset, players, rngs, keep_events=keep_events, trace=trace
        )
    raise ValueError(f"unknown field model {field_model!r} (known: {', '.join(FIELD_MODELS)})")
