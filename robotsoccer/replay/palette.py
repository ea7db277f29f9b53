"""How recordings look and are named: colours, draw orders, timelines, entity names, legend words.

The drawing toolkit's style, shared by the trial and match recordings and the raster frames
(:mod:`robotsoccer.replay.raster`). Colours are 8-bit RGB; draw orders are rerun's
``DrawOrder`` (larger on top). Imports no drawing library.
"""

from __future__ import annotations

import re
from collections.abc import Sequence

from field_models.protocol import LEFT, RIGHT, Action, Kick, Say

Colour = tuple[int, int, int]
"""An 8-bit RGB colour."""

SIM_TIME = "sim_time"
"""Name of the simulated-time (duration) timeline."""
TICK = "tick"
"""Name of the integer-tick (sequence) timeline."""
ROUTINE_DECISIONS = "events/routine"
"""Entity of routine decisions (turns, dashes, nothing): recorded, hidden by default."""

TEAM_COLOURS: dict[str, Colour] = {LEFT: (60, 130, 255), RIGHT: (255, 200, 40)}
"""The two sides' colours: blue for the left team, yellow for the right."""
OTHER_TEAM_COLOURS: tuple[Colour, ...] = ((200, 80, 220), (80, 220, 160), (240, 90, 90))
"""Colours of further teams (drills name teams of their own)."""
# Percept rings: hues far from the team colours, the ball's orange and the pitch's green.
PERCEPT_COLOURS: tuple[Colour, ...] = (
    (255, 70, 220),
    (70, 235, 235),
    (255, 255, 255),
    (190, 150, 255),
)
"""Colours of the observers' percept rings, by the observer's place among the players."""
PERCEPT_COLOUR_NAMES = ("magenta", "cyan", "white", "lilac")
"""The legend's names of :data:`PERCEPT_COLOURS`."""
BALL_COLOUR: Colour = (255, 120, 0)
"""The ball: orange."""
LINE_COLOUR: Colour = (230, 230, 230)
"""The pitch's lines and markings."""
ARROW_COLOUR: Colour = (255, 255, 255)
"""Heading arrows and label text (white reads best)."""
PITCH_COLOUR: Colour = (24, 64, 36)
"""The grass."""
_OUTCOME_COLOURS: dict[str, Colour] = {
    "GOAL": (255, 80, 80),
    "SAVE": (90, 235, 120),
    "SUCCESS": (90, 235, 120),
}
_OTHER_OUTCOME_COLOUR: Colour = (235, 235, 235)

# Draw order (rerun's DrawOrder, larger on top): markings under players under the ball under
# the percept rings, so a ring around the true ball stays visible.
ORDER_MARKINGS = 10.0
"""Draw order of the pitch's markings, goals and posts."""
ORDER_PLAYERS = 30.0
"""Draw order of the players' discs and names."""
ORDER_OUTLINE = 31.0
"""Draw order of the players' outlines."""
ORDER_HEADING = 32.0
"""Draw order of the heading arrows."""
ORDER_BALL = 40.0
"""Draw order of the ball."""
ORDER_PERCEPT = 50.0
"""Draw order of the percept rings."""
ORDER_OUTCOME = 60.0
"""Draw order of the outcome (and a match's scoreboard) above the field."""

_ENTITY_UNSAFE = re.compile(r"[^A-Za-z0-9_\-]")


def team_colour(team: str, teams: Sequence[str]) -> Colour:
    """Display colour of a team: fixed for LEFT/RIGHT, from a small palette otherwise."""
    if team in TEAM_COLOURS:
        return TEAM_COLOURS[team]
    others = [t for t in teams if t not in TEAM_COLOURS]
    index = others.index(team) if team in others else len(others)
    return OTHER_TEAM_COLOURS[index % len(OTHER_TEAM_COLOURS)]


def colour_name(colour: Colour) -> str:
    """The name the legend gives a team colour."""
    names = {
        TEAM_COLOURS[LEFT]: "blue",
        TEAM_COLOURS[RIGHT]: "yellow",
        OTHER_TEAM_COLOURS[0]: "purple",
        OTHER_TEAM_COLOURS[1]: "teal",
        OTHER_TEAM_COLOURS[2]: "red",
    }
    return names.get(colour, "coloured")


def outcome_colour(label: str) -> Colour:
    """Display colour of a trial label: red for a goal, green for a save, light grey otherwise."""
    return _OUTCOME_COLOURS.get(label, _OTHER_OUTCOME_COLOUR)


def outcome_text(label: str, detail: str = "") -> str:
    """The outcome as shown on the field and in the legend: ``"GOAL — why"``."""
    return f"{label} — {detail}" if detail else label


def lighter(colour: Colour, amount: float = 0.45) -> Colour:
    """`colour` mixed with white, for outlines drawn over a disc of that colour."""
    r, g, b = (round(c + amount * (255 - c)) for c in colour)
    return (r, g, b)


def length_text(metres: float) -> str:
    """A length for the legend: centimetres below a metre, metres above."""
    return f"{100.0 * metres:.3g} cm" if metres < 1.0 else f"{metres:.3g} m"


def seen_label(team: str | None, number: int | None) -> str:
    """Label of a perceived player: what the sensor identified, '?' for the unknown parts."""
    if team is None and number is None:
        return "?"
    return f"{team if team is not None else '?'}{number if number is not None else '?'}"


def entity_name(text: str) -> str:
    """Make `text` safe as one entity-path part."""
    return _ENTITY_UNSAFE.sub("_", text) or "_"


def is_routine(actions: Sequence[Action]) -> bool:
    """Whether a decision only steers or waits: turns and dashes, or nothing (no kick, no say).

    >>> from field_models.protocol import Dash, Turn
    >>> is_routine((Turn(0.5), Dash(100.0))), is_routine(()), is_routine((Kick(80.0, 0.0),))
    (True, True, False)
    """
    return not any(isinstance(action, Kick | Say) for action in actions)
