"""A paper-style trace of one trial (Figure 4): what one client sees and hears, and what it sends.

The lines are the field model's own trace events, in the Soccer Server's text forms: each see
and hear the client received (on the Soccer Server the messages themselves; on the robot
testbed the host's percept written as a see), each command the client sent preceded by
``**->`` as in the paper, and, on the robots, each primitive the host sent for it preceded by
``  link:``. The coach's verdict closes the trace.
"""

from __future__ import annotations

from field_models.arena import Arena, ArenaEvent
from field_models.protocol import Percept, PlayerRef
from robotsoccer.runs.runner import TrialSpec, build_trial, play

_PREFIX = {"see": "", "hear": "", "command": "**-> ", "link": "  link: "}
"""How each event channel is shown; channels not listed (referee, decision) are left out: the
client hears the referee in its hear lines."""


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
        lines.extend(trace_line(e) for e in a.drain_events() if _shown(e, client))

    verdict = play(arena, drill, drill.minds(arena, rngs), observe)
    lines.extend(trace_line(e) for e in arena.drain_events() if _shown(e, client))
    seconds = arena.tick * arena.facts.dt_s
    lines.append(f"coach: {verdict.label} at t = {seconds:.2f} s ({verdict.reason})")
    return lines


def _shown(event: ArenaEvent, client: PlayerRef) -> bool:
    return event.channel in _PREFIX and event.player in (None, client)


def trace_line(event: ArenaEvent) -> str:
    """One event as a trace line: ``**-> (dash 100)``, ``(see 12 ((ball) 20.1 -3))``, ..."""
    return _PREFIX.get(event.channel, f"{event.channel}: ") + event.text
