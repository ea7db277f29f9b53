"""Flags, goals and lines of the Soccer Server pitch, named as the server prints them.

Positions are in OUR field frame: x toward the right goal ("r"), **y up**, metres. The server's
own y axis points down (its "t" = top touchline is at server y = -34), so every server position
(x, y_s) is stored here as (x, -y_s): ``(flag r t)`` sits at (52.5, +34). The conversion happens
only here, at the edge (shared `specs/soccer_server.md` §3.8, §0 "Conventions").

Names are kept in the short form without parentheses (``"f r t"``, ``"g l"``, ``"l b"``); the
long form of protocols < 6 (``"flag r t"``) is derived by :func:`long_name`.

Two landmark sets exist (``SensingParams.landmark_set``):

* ``"full"``: the 55 flags and goals of servers >= 4.00 ([CL 4.00]);
* ``"1996"``: the centre flag, the four corner flags, the six penalty-area flags and the two
  goals. The spec says the 1996–97 servers "had the centre, corner, penalty and goal flags";
  the exact 1997 set was not found, so this is our reading of that sentence (the paper's
  Figure 4 uses only names from it).
"""

from __future__ import annotations

from typing import NamedTuple

from field_models.soccer_server.sensing_params import LandmarkSet

PITCH_HALF_LENGTH_M = 52.5
"""Half the pitch length (goal line at x = ±52.5) [m]."""
PITCH_HALF_WIDTH_M = 34.0
"""Half the pitch width (touchlines at y = ±34) [m]."""
GOAL_HALF_WIDTH_M = 7.01
"""goal_width / 2 = 14.02 / 2 [m]; the goal-post flags stand there."""
PENALTY_FLAG_X_M = 36.0
"""|x| of the penalty-area flags: 52.5 - 16.5 [m]."""
PENALTY_FLAG_Y_M = 20.16
"""|y| of the penalty-area corner flags: 40.32 / 2 [m]."""
OUTER_FLAG_OFFSET_M = 5.0
"""Distance of the outer flags beyond the lines [m]."""

_LONG = {"f": "flag", "g": "goal", "l": "line", "b": "ball", "p": "player"}
_LONG_CLOSE = {"F": "Flag", "G": "Goal", "B": "Ball", "P": "Player"}
_SHORT_OF_LONG = {v: k for k, v in (_LONG | _LONG_CLOSE).items()}


class Landmark(NamedTuple):
    """A flag or goal: its short name (``"f r t"``) and position in our frame [m]."""

    name: str
    x: float
    y: float


class Line(NamedTuple):
    """A pitch line: its short name (``"l r"``) and where it lies in our frame.

    Attributes:
        name: ``"l l"``, ``"l r"``, ``"l t"`` or ``"l b"``.
        vertical: True for the goal lines (x = const), False for the touchlines (y = const).
        offset_m: the constant coordinate: x for a goal line, y (ours, up) for a touchline.
    """

    name: str
    vertical: bool
    offset_m: float


def _server(name: str, x: float, y_server: float) -> Landmark:
    """A landmark given in server coordinates (y down), stored in ours (y up)."""
    return Landmark(name, x, -y_server + 0.0)  # + 0.0 turns -0.0 into 0.0


def _full_flags() -> tuple[Landmark, ...]:
    """The 55 flags and goals of servers >= 4.00 (spec §3.8 table), server order of kinds."""
    hl, hw, gw = PITCH_HALF_LENGTH_M, PITCH_HALF_WIDTH_M, GOAL_HALF_WIDTH_M
    px, py, off = PENALTY_FLAG_X_M, PENALTY_FLAG_Y_M, OUTER_FLAG_OFFSET_M
    flags = [
        _server("f c", 0.0, 0.0),
        _server("f c t", 0.0, -hw),
        _server("f c b", 0.0, hw),
        _server("f l t", -hl, -hw),
        _server("f l b", -hl, hw),
        _server("f r t", hl, -hw),
        _server("f r b", hl, hw),
        _server("g l", -hl, 0.0),
        _server("g r", hl, 0.0),
        _server("f g l t", -hl, -gw),
        _server("f g l b", -hl, gw),
        _server("f g r t", hl, -gw),
        _server("f g r b", hl, gw),
        _server("f p l t", -px, -py),
        _server("f p l c", -px, 0.0),
        _server("f p l b", -px, py),
        _server("f p r t", px, -py),
        _server("f p r c", px, 0.0),
        _server("f p r b", px, py),
    ]
    for edge, ys in (("t", -(hw + off)), ("b", hw + off)):
        flags.append(_server(f"f {edge} 0", 0.0, ys))
        for n in (10, 20, 30, 40, 50):
            flags.append(_server(f"f {edge} l {n}", -float(n), ys))
            flags.append(_server(f"f {edge} r {n}", float(n), ys))
    for side, xs in (("l", -(hl + off)), ("r", hl + off)):
        flags.append(_server(f"f {side} 0", xs, 0.0))
        for n in (10, 20, 30):
            flags.append(_server(f"f {side} t {n}", xs, -float(n)))
            flags.append(_server(f"f {side} b {n}", xs, float(n)))
    return tuple(flags)


FLAGS_FULL: tuple[Landmark, ...] = _full_flags()
"""All 55 flags and goals (servers >= 4.00), positions in our frame."""

_EARLY = frozenset(
    {
        *("f c", "f l t", "f l b", "f r t", "f r b", "g l", "g r"),  # centre, corners, goals
        *("f p l t", "f p l c", "f p l b", "f p r t", "f p r c", "f p r b"),  # penalty areas
    }
)
FLAGS_1996: tuple[Landmark, ...] = tuple(f for f in FLAGS_FULL if f.name in _EARLY)
"""The reduced early set (centre, corners, penalty-area flags, goals); see module docstring."""

LINES: tuple[Line, ...] = (
    Line("l l", True, -PITCH_HALF_LENGTH_M),
    Line("l r", True, PITCH_HALF_LENGTH_M),
    Line("l t", False, PITCH_HALF_WIDTH_M),
    Line("l b", False, -PITCH_HALF_WIDTH_M),
)
"""The four lines in the order the server tests them (left, right, top, bottom)."""


def landmarks_for(landmark_set: LandmarkSet) -> tuple[Landmark, ...]:
    """The flags and goals of a landmark set (``"full"`` or ``"1996"``)."""
    if landmark_set == "full":
        return FLAGS_FULL
    if landmark_set == "1996":
        return FLAGS_1996
    raise ValueError(f"landmark_set: expected full or 1996; got {landmark_set!r}")


def long_name(short: str) -> str:
    """The protocol < 6 name of an object: ``"f r t"`` → ``"flag r t"``, ``"B"`` → ``"Ball"``."""
    head, _, rest = short.partition(" ")
    word = _LONG.get(head) or _LONG_CLOSE.get(head)
    if word is None:
        raise ValueError(f"unknown object kind {head!r} in {short!r}")
    return f"{word} {rest}" if rest else word


def short_name(name: str) -> str:
    """The short form of a long or short object name: ``"flag r t"`` → ``"f r t"``."""
    head, _, rest = name.partition(" ")
    head = _SHORT_OF_LONG.get(head, head)
    return f"{head} {rest}" if rest else head


def is_known_name(short: str) -> bool:
    """True for a flag, goal or line name of the full set, or a ball/player/close kind."""
    return short in _KNOWN


_KNOWN = frozenset(
    [f.name for f in FLAGS_FULL] + [ln.name for ln in LINES] + ["b", "p", "B", "P", "F", "G"]
)
