"""The Soccer Server field model's registry entry: presets with options, facts, arenas.

See :class:`field_models.registry.FieldModelEntry`.
"""

from __future__ import annotations

import math
from functools import lru_cache
from typing import Any

from field_models.arena import Arena, BallLaw, FieldFacts, FieldOptions, KickFacts
from field_models.batch_arena import BatchArena
from field_models.protocol import PlayerRef
from field_models.seeding import StreamBatch, TrialRngs
from field_models.soccer_server.landmarks import landmarks_for
from field_models.soccer_server.params import ServerPreset
from field_models.soccer_server.server_conf import load_preset

NAME = "soccer_server"
"""The registered name."""
DEFAULT_PRESET = "soccer_server_1996"
"""The paper's server (``field_models/presets/soccer_server``)."""


@lru_cache(maxsize=32)
def load(preset: str, options: FieldOptions) -> ServerPreset:
    """The preset with the run's options applied (loaded once per process: trials share it).

    ``ball_noise`` is ``ball_rand``; perfect perception gives noise-free sees.

    Raises:
        field_models.presets.PresetError: A missing or wrong preset.
        ValueError: A sensor latency (a see shows the cycle it is sent in: there is none to
            set), or a ball-noise period other than the 100 ms cycle (``ball_rand`` acts once
            per cycle, spec §1.3).
    """
    loaded = load_preset(preset)
    if options.sensor_latency_s is not None:
        raise ValueError(f"{NAME} has no sensor latency to set (a see shows its own cycle)")
    period = options.ball_noise_period_s
    if period is not None and not math.isclose(period, loaded.dynamics.dt_s):
        raise ValueError(
            f"{NAME}: ball noise acts once per {loaded.dynamics.dt_s:g} s cycle; "
            f"a ball-noise period of {period:g} s is not supported"
        )
    if options.ball_noise is not None:
        loaded = loaded.replace_dynamics(ball_rand=options.ball_noise)
    if options.perfect_perception:
        loaded = loaded.replace_sensing(perfect=True)
    if options.all_landmarks:
        loaded = loaded.replace_sensing(percept_flags=True)
    return loaded


@lru_cache(maxsize=32)
def facts(preset: ServerPreset) -> FieldFacts:
    """What the code above the line may know about this server (:class:`FieldFacts`)."""
    d, s = preset.dynamics, preset.sensing
    dt = d.dt_s
    push = min(d.max_dash_power * d.dash_power_rate_m_per_cycle2, d.player_accel_max_m_per_cycle2)
    # Steady speed under full dash: push / (1 - decay); a decay of 1 (no friction) never
    # settles, so the cap alone bounds it.
    settled = push / (1.0 - d.player_decay) if d.player_decay < 1.0 else math.inf
    top = min(settled, d.player_speed_max_m_per_cycle)
    return FieldFacts(
        model=NAME,
        preset=preset.name,
        pitch=d.pitch(),
        dt_s=dt,
        sensor_period_s=s.see_interval_ms / 1000.0,
        sensor_latency_s=None,
        ball=BallLaw("geometric", dt, decay_per_tick=d.ball_decay),
        ball_max_speed_mps=d.ball_speed_max_m_per_cycle / dt,
        ball_noise=d.ball_rand,
        ball_noise_period_s=dt,
        kick=KickFacts(
            speed_per_power_mps=d.kick_power_rate_m_per_cycle2 / dt,
            max_speed_mps=min(
                d.ball_speed_max_m_per_cycle,
                d.ball_accel_max_m_per_cycle2,
                d.maxpower * d.kick_power_rate_m_per_cycle2,  # the strongest kick (spec §2.3)
            )
            / dt,
            reach_m=d.kickable_area_m,
            aimable=True,
            half_angle_rad=math.pi,
        ),
        player_top_speed_mps=top / dt,
        player_accel_mps2=push / (dt * dt),
        heading_sigma_rad=0.0,
        player_shape="circle",
        perfect_perception=s.perfect,
        say_max_chars=s.say_msg_size,
        turn_inertia_s_per_m=d.inertia_moment_cycle_per_m * dt,
        dash_rates=(
            (d.side_dash_rate, d.back_dash_rate)
            if d.min_dash_angle_rad < 0.0 < d.max_dash_angle_rad
            else None
        ),
        dash_angle_step_rad=d.dash_angle_step_rad,
        landmarks=tuple((m.name, m.x, m.y) for m in landmarks_for(s.landmark_set)),
    )


def build(
    preset: ServerPreset,
    facts: FieldFacts,
    players: tuple[PlayerRef, ...],
    rngs: TrialRngs,
    *,
    keep_events: bool,
    trace: bool,
) -> Arena:
    """A fresh Soccer Server arena."""
    from field_models.soccer_server.arena import SoccerServerArena

    return SoccerServerArena(preset, facts, players, rngs, keep_events=keep_events, trace=trace)


def benchmarks(quick: bool = False) -> dict[str, Any]:
    """This model's own speed figures (:mod:`field_models.soccer_server.bench`)."""
    from field_models.soccer_server.bench import benchmarks as measure

    return measure(quick)


def batch_reason(preset: ServerPreset) -> str | None:
    """Why this preset has no batch arena (None: it has one)."""
    from field_models.soccer_server.batch_arena import batch_reason as reason

    return reason(preset)


def build_batch(
    preset: ServerPreset, players: tuple[PlayerRef, ...], movement: StreamBatch
) -> BatchArena:
    """K trials stepped together (:mod:`field_models.soccer_server.batch_arena`)."""
    from field_models.soccer_server.batch_arena import SoccerServerBatchArena

    return SoccerServerBatchArena(preset, players, movement)
