"""A paper-style trace of one trial (Figure 4): what one client sees and hears, and what it sends.

On the Soccer Server model the lines are the server's own text: ``(see ...)`` and ``(hear ...)``
messages as rendered for the client, and the client's commands preceded by ``**->``, as in the
paper. On the robot testbed the same client code is traced through the host: each percept is
written in the same ``(see T ((ball) D A) ...)`` form (metres, degrees, left positive), followed
by the primitives the host sent for the client's actions.
"""

from __future__ import annotations

import math

from field_models.arena import Arena
from field_models.protocol import Percept, PlayerRef
from robotsoccer.runs.runner import TrialSpec, build_trial, play


def trace_trial(spec: TrialSpec, index: int, client: PlayerRef | None = None) -> list[str]:
    """Run trial `index` of `spec` and return its trace lines for `client` (default: first).

    Raises:
        ValueError: when `client` is not a player of the drill.
    """
    rngs, drill, arena = build_trial(spec, index, trace=True)
    players = drill.players()
    client = client or players[0]
    if client not in players:
        known = ", ".join(map(str, players))
        raise ValueError(f"no player {client} in drill {spec.drill!r} (players: {known})")
    drill.setup(arena, rngs)
    lines: list[str] = []

    def observe(a: Arena, percepts: list[Percept]) -> None:
        if a.model_name != "soccer_server":
            lines.extend(robot_see(p) for p in percepts if p.player == client)
        for event in a.drain_events():
            if event.player not in (None, client):
                continue
            prefix = "**-> " if event.channel == "command" else ""
            if event.channel == "referee":
                continue  # the client hears the referee; the hear line shows it
            lines.append(prefix + event.text)

    verdict = play(arena, drill, drill.minds(arena, rngs), observe)
    lines.append(
        f"coach: {verdict.label} at t = {arena.tick * arena.dt_s:.2f} s ({verdict.reason})"
    )
    return lines


def robot_see(percept: Percept) -> str:
    """A robot percept in the Soccer Server's see form: metres and degrees, left positive."""
    parts = []
    for mark in percept.landmarks:
        name = {"g l": "goal l", "g r": "goal r"}.get(mark.name, mark.name)
        parts.append(f"(({name}) {mark.distance_m:.3f} {math.degrees(mark.angle_rad):.0f})")
    if percept.ball is not None:
        b = percept.ball
        parts.append(f"((ball) {b.distance_m:.3f} {math.degrees(b.angle_rad):.0f})")
    for p in percept.players:
        who = f"player {p.team} {p.number}" if p.team is not None else "player"
        parts.append(f"(({who}) {p.distance_m:.3f} {math.degrees(p.angle_rad):.0f})")
    return f"(see {percept.tick} {' '.join(parts)})"
