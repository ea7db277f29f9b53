"""Robot commands and percepts as text, for traces and event logs (the paper's Figure 4 form).

The host logs every command it sends over the link with :func:`describe`; the arena logs every
percept it hands a client with :func:`percept_text`, so a robot trace reads like a Soccer Server
one.
"""

from __future__ import annotations

from field_models.commands import server_degrees
from field_models.protocol import Percept
from field_models.robot_physics.link import Command, Primitive


def describe(command: Command) -> str:
    """A command as text, e.g. ``FORWARD 0.84 m/s for 16 ticks`` (without the addressee)."""
    primitive = command.primitive
    if primitive is Primitive.FORWARD or primitive is Primitive.BACKWARD:
        text = f"{primitive.name} {command.value:.2f} m/s"
    elif primitive is Primitive.TURN:
        text = f"TURN {command.value:+.2f} rad/s"
    elif primitive is Primitive.ARC:
        text = f"ARC {command.value:.2f} m/s {command.rate:+.2f} rad/s"
    elif primitive is Primitive.KICK:
        return f"KICK {command.value:.0f}"
    elif primitive is Primitive.WHEELS:
        text = f"WHEELS {command.value:+.2f} {command.rate:+.2f} m/s"
    else:
        return "STOP"
    if command.duration_ticks is not None:
        text += f" for {command.duration_ticks} ticks"
    return text


def percept_text(percept: Percept) -> str:
    """A robot's percept in the Soccer Server's see form, for traces.

    ``(see T ((goal r) D A) ((ball) D A) ((player left 2) D A))``: distances in metres to the
    millimetre, directions in the server's degrees (clockwise positive), so a robot trace reads
    like the paper's Figure 4.
    """
    parts = []
    for mark in percept.landmarks:
        name = {"g l": "goal l", "g r": "goal r"}.get(mark.name, mark.name)
        parts.append(f"(({name}) {mark.distance_m:.3f} {server_degrees(mark.angle_rad):g})")
    if percept.ball is not None:
        ball = percept.ball
        parts.append(f"((ball) {ball.distance_m:.3f} {server_degrees(ball.angle_rad):g})")
    for seen in percept.players:
        who = "player" if seen.team is None else f"player {seen.team} {seen.number}"
        parts.append(f"(({who}) {seen.distance_m:.3f} {server_degrees(seen.angle_rad):g})")
    return f"(see {percept.tick} {' '.join(parts)})"
