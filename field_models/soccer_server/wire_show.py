"""A monitor's ``show`` on rcssserver's wire (:mod:`~field_models.soccer_server.wire`'s formats).

``(show T (pm ID) (tm L R SL SR) ((b) x y vx vy) ((l 1) type state x y vx vy body neck
(v h width) (s stamina effort recovery [capacity]) (c counts...)) ...)`` with all 22 slots
(``src/serializermonitor.cpp``, ``SerializerMonitorStdv3``/``v4``). Our frame (y up,
counter-clockwise radians, m/s) becomes the server's here, as in the wire module.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

from field_models.protocol import BodyState
from field_models.soccer_server.wire import PLAY_MODE_IDS, PLAYERS_PER_TEAM

_RAD2DEG = 180.0 / math.pi


@dataclass(frozen=True, slots=True)
class ShowPlayer:
    """One slot of a monitor's show: the player's state (None: not connected) and counts."""

    state: BodyState | None
    counts: tuple[int, ...]
    kicked: bool = False


@dataclass(frozen=True, slots=True)
class Show:
    """What a monitor's show carries: the time, play mode, teams, score, ball and 22 slots.

    Attributes:
        time: Server time (cycle).
        mode: Play mode name (``PLAY_MODE_IDS``; an unknown one shows as 0).
        teams: Left and right team names (None: no team yet, shown as ``null``).
        score: Left and right goals.
        ball: The ball's state, our frame (velocities per second).
        slots: The 22 player slots, left 1..11 then right 1..11.
    """

    time: int
    mode: str
    teams: tuple[str | None, str | None]
    score: tuple[int, int]
    ball: BodyState
    slots: Sequence[ShowPlayer]


def render_show(show: Show, dt_s: float, *, visible_angle_deg: float, version: int = 3) -> str:
    """A monitor's ``(show ...)`` (protocol 3; 4 adds the stamina capacity). 22 slots, l then r.

    `dt_s` is the cycle length [s] (velocities are shown per cycle) and `visible_angle_deg` the
    players' view width.
    """
    time, mode, teams, score, ball = show.time, show.mode, show.teams, show.score, show.ball
    left, right = (name or "null" for name in teams)
    parts = [
        f"(show {time} (pm {PLAY_MODE_IDS.get(mode, 0)}) (tm {left} {right} {score[0]} {score[1]})"
        f" ((b) {_p(ball.x)} {_p(-ball.y)} {_p(ball.vx * dt_s)} {_p(-ball.vy * dt_s)})"
    ]
    stamina = "(s 8000 1 1 130600)" if version >= 4 else "(s 8000 1 1)"
    view = f"(v h {visible_angle_deg + 0.0:g})"  # as a C++ stream prints a double
    for i, slot in enumerate(show.slots):
        side = "l" if i < PLAYERS_PER_TEAM else "r"
        unum = i % PLAYERS_PER_TEAM + 1
        st = slot.state
        if st is None:
            sign = 1 if side == "l" else -1
            head = f"(({side} {unum}) 0 0 {_p(-3.0 * unum * sign)} -37 0 0 0 0"
        else:
            bits = 0x1 | (0x2 if slot.kicked else 0)
            body = (-st.heading * _RAD2DEG + 180.0) % 360.0 - 180.0
            head = (
                f"(({side} {unum}) 0 {bits:#x} {_p(st.x)} {_p(-st.y)} {_p(st.vx * dt_s)} "
                f"{_p(-st.vy * dt_s)} {round(body, 3) + 0.0:g} 0"
            )
        counts = " ".join(str(c) for c in slot.counts)
        parts.append(f" {head} {view} {stamina} (c {counts}))")
    return "".join(parts) + ")"


def _p(value: float) -> str:
    """A position or velocity quantised to 0.0001 (``PREC``) and printed ``%g``."""
    return f"{round(value, 4) + 0.0:g}"
