"""Client commands as text: the one way an action is written down, and read back.

The shared action vocabulary is the Soccer Server's (DESIGN.md §2), so its text form is the
server's client command syntax (shared `specs/soccer_server.md` §2, §3.1): ``(turn Moment)``,
``(dash Power [Direction])``, ``(kick Power Direction)``, ``(say Message)``,
``(turn_neck Moment)`` and ``(change_view Width Quality)``. Traces,
recordings and event logs of both field models write actions this way, and
:func:`parse_command` reads a client's command text back into an action.

This is the Soccer Server's message edge, so angles here are the server's: degrees, positive
clockwise on our y-up field (the server's y axis points down). ``Turn(+0.5 rad)``, a left turn,
is written ``(turn -28.6)``. :func:`render_command` rounds angles to 0.1° and powers to 0.1, as a
client would print them; :func:`parse_command` accepts any number the server would.
"""

from __future__ import annotations

import math

from field_models.protocol import (
    VIEW_QUALITIES,
    VIEW_WIDTHS,
    Action,
    ChangeView,
    Dash,
    Kick,
    Say,
    Turn,
    TurnNeck,
)

_RAD2DEG = 180.0 / math.pi


class CommandParseError(ValueError):
    """A client command's text is not an action (turn, dash, ...) the server would accept."""

    def __init__(self, reason: str, text: str) -> None:
        super().__init__(f"{reason}: {text!r}")
        self.reason = reason
        self.text = text


def server_degrees(angle_rad: float) -> float:
    """Our counter-clockwise radians as the server's clockwise degrees, to 0.1° (never -0)."""
    return round(-angle_rad * _RAD2DEG, 1) + 0.0


def _number(value: float) -> str:
    """A power or angle as a client prints it: at most one decimal, no trailing zeros.

    Fixed-point, not ``%g``: ``%g`` keeps six digits, so 100000.1 would print as 100000.

    >>> _number(100.0), _number(-0.04), _number(100000.14)
    ('100', '0', '100000.1')
    """
    text = f"{round(value, 1) + 0.0:.1f}"
    return text[:-2] if text.endswith(".0") else text


def render_command(action: Action) -> str:
    """The command a client sends for `action`, e.g. ``(dash 100)`` or ``(kick 80 -30)``.

    >>> render_command(Turn(math.radians(30)))
    '(turn -30)'
    >>> render_command(Dash(100.0, math.radians(-90)))
    '(dash 100 90)'
    """
    if isinstance(action, Turn):
        return f"(turn {_number(server_degrees(action.angle_rad))})"
    if isinstance(action, Dash):
        direction = _number(server_degrees(action.direction_rad))
        if direction == "0":  # a direction that prints as 0 is written as none, as 0 is
            return f"(dash {_number(action.power)})"
        return f"(dash {_number(action.power)} {direction})"
    if isinstance(action, Kick):
        return f"(kick {_number(action.power)} {_number(server_degrees(action.direction_rad))})"
    if isinstance(action, Say):
        return f"(say {_say_message(action.text)})"
    if isinstance(action, TurnNeck):
        return f"(turn_neck {_number(server_degrees(action.angle_rad))})"
    if isinstance(action, ChangeView):
        return f"(change_view {action.width} {action.quality})"
    raise TypeError(f"not an action: {action!r}")


def _say_message(text: str) -> str:
    """A say message as written: bare where it reads back unchanged, else in double quotes.

    Bare text loses its leading and trailing white space to :func:`parse_command`, and a text
    that is itself in quotes loses them; quoted, both survive (``Say(' x')`` is
    ``(say " x")``). Bare where that is safe keeps the form clients and traces print.

    >>> _say_message("hi there"), _say_message(" x"), _say_message('"q"')
    ('hi there', '" x"', '""q""')
    """
    if text and text == text.strip() and not (len(text) >= 2 and text[0] == text[-1] == '"'):
        return text
    return f'"{text}"'


def parse_command(text: str) -> Action:
    """The action of one client command: ``(turn 45)``, ``(dash 100 30)``, ``(say hi)``, ...

    Angles come back in our frame (radians, counter-clockwise). A say message may be quoted
    (``(say "hi")``, protocol >= 7) or bare; it keeps its inner spaces and parentheses, and a
    quoted one its outer spaces too, so ``parse_command(render_command(a)) == a`` for every
    say with a message.

    >>> parse_command("(kick 80 -30)")
    Kick(power=80.0, direction_rad=0.5235987755982988)

    Raises:
        CommandParseError: Not a single parenthesised command, an unknown command, the wrong
            number of arguments, or an argument that is not a finite number.
    """
    inner = _inner(text)
    name, _, rest = inner.partition(" ")
    if name == "say":
        return Say(_say_text(rest.strip(), text))
    if name == "change_view":
        return _change_view(rest.split(), text)
    args = [_float(token, text) for token in rest.split()]
    if name == "turn":
        _arity(args, 1, 1, text)
        return Turn(-math.radians(args[0]) + 0.0)
    if name == "dash":
        _arity(args, 1, 2, text)
        direction = -math.radians(args[1]) + 0.0 if len(args) == 2 else 0.0
        return Dash(args[0], direction)
    if name == "kick":
        _arity(args, 2, 2, text)
        return Kick(args[0], -math.radians(args[1]) + 0.0)
    if name == "turn_neck":
        _arity(args, 1, 1, text)
        return TurnNeck(-math.radians(args[0]) + 0.0)
    raise CommandParseError(
        f"unknown command {name!r} (known: turn, dash, kick, say, turn_neck, change_view)", text
    )


def _change_view(words: list[str], text: str) -> ChangeView:
    """``(change_view Width [Quality])``: the quality is high when left out, as the server's."""
    if not 1 <= len(words) <= 2:
        raise CommandParseError(f"expected 1 or 2 argument(s), got {len(words)}", text)
    width = words[0]
    quality = words[1] if len(words) == 2 else "high"
    if width not in VIEW_WIDTHS:
        raise CommandParseError(f"view width {width!r} (known: {', '.join(VIEW_WIDTHS)})", text)
    if quality not in VIEW_QUALITIES:
        raise CommandParseError(
            f"view quality {quality!r} (known: {', '.join(VIEW_QUALITIES)})", text
        )
    return ChangeView(width, quality)


def _inner(text: str) -> str:
    stripped = text.strip().rstrip("\0")
    if len(stripped) < 2 or stripped[0] != "(" or stripped[-1] != ")":
        raise CommandParseError("expected one command in parentheses", text)
    inner = stripped[1:-1].strip()
    if not inner:
        raise CommandParseError("empty command", text)
    return inner


def _say_text(message: str, text: str) -> str:
    if len(message) >= 2 and message[0] == '"' and message[-1] == '"':
        message = message[1:-1]
    if not message:
        raise CommandParseError("say without a message", text)
    return message


def _float(token: str, text: str) -> float:
    try:
        value = float(token)
    except ValueError:
        raise CommandParseError(f"{token!r} is not a number", text) from None
    if not math.isfinite(value):
        raise CommandParseError(f"{token!r} is not a finite number", text)
    return value


def _arity(args: list[float], low: int, high: int, text: str) -> None:
    if not low <= len(args) <= high:
        want = str(low) if low == high else f"{low} or {high}"
        raise CommandParseError(f"expected {want} argument(s), got {len(args)}", text)
