"""The wire arena's texts: the trainer's move and look, a client's sense_body time and neck.

Frames: the server's y points down and its angles turn clockwise, in degrees; velocities are
per cycle. Ours: y up, counter-clockwise radians, velocities per second. Every function here
converts one way, with `dt` the cycle length [s].
"""

from __future__ import annotations

import contextlib
import math

from field_models.protocol import LEFT, RIGHT, BodyState, PlayerRef
from field_models.rcssserver.client import WireError
from field_models.soccer_server.messages import MessageParseError, Quoted, parse_sexpr

_RAD2DEG = 180.0 / math.pi
TEAM_NAMES = {LEFT: "left", RIGHT: "right"}
"""Team names on the wire: the model's own, so a see names players as our refs do."""


def move_text(x: float, y: float, heading: float, vx: float, vy: float, dt: float) -> str:
    """The ``X Y Dir VX VY`` of a trainer's ``move``, from our frame (m, rad, m/s)."""
    deg = -heading * _RAD2DEG
    return f"{x!r} {-y!r} {deg!r} {vx * dt!r} {-vy * dt!r}"


def parse_look(text: str, dt: float) -> tuple[BodyState, dict[PlayerRef, BodyState]]:
    """The ball and the players of a trainer's ``(ok look ...)``, in our frame.

    Players of teams other than ``left`` and ``right`` are left out; a ball the look does not
    show is at rest on the centre mark.

    Raises:
        field_models.rcssserver.client.WireError: The text is not an s-expression.
    """
    try:
        tree = parse_sexpr(text)
    except MessageParseError as exc:
        raise WireError(f"unreadable look: {exc}") from None
    ball = BodyState(0.0, 0.0, 0.0)
    players: dict[PlayerRef, BodyState] = {}
    teams = {name: team for team, name in TEAM_NAMES.items()}
    for item in tree[3:]:
        if not isinstance(item, list) or not isinstance(item[0], list):
            continue
        name, values = item[0], [float(v) for v in item[1:] if isinstance(v, str)]
        if name == ["b"]:
            x, y, vx, vy = values[:4]
            ball = BodyState(x, -y + 0.0, 0.0, vx / dt, -vy / dt + 0.0)
        elif name and name[0] == "p" and len(name) >= 3 and isinstance(name[1], Quoted):
            team = teams.get(str(name[1]))
            if team is None:
                continue
            x, y, vx, vy, body = values[:5]
            ref = PlayerRef(team, int(str(name[2])))
            heading = math.remainder(-body / _RAD2DEG, math.tau)
            players[ref] = BodyState(x, -y + 0.0, heading, vx / dt, -vy / dt + 0.0)
    return ball, players


def head_angle(batch: list[str]) -> float:
    """The neck angle [rad, CCW] of the last ``sense_body``'s ``(head_angle H)`` (0: none).

    H is in the server's degrees, clockwise on our field, so its sign flips.
    """
    angle = 0.0
    for text in batch:
        if text.startswith("(sense_body "):
            start = text.find("(head_angle ")
            if start >= 0:
                token = text[start + len("(head_angle ") :].split(")", 1)[0]
                with contextlib.suppress(ValueError):
                    angle = -math.radians(float(token)) + 0.0
    return angle


def sense_time(batch: list[str]) -> int | None:
    """The time of the last ``sense_body`` in a client's messages (None: there was none)."""
    time_ = None
    for text in batch:
        if text.startswith("(sense_body "):
            with contextlib.suppress(IndexError, ValueError):
                time_ = int(text.split(maxsplit=2)[1])
    return time_
