"""The Soccer Server's text messages: render and parse see and hear.

Formats follow shared `specs/soccer_server.md` §3.7 (see), §2.6 (hear) and rcssserver's
serializers; the paper's Figure 4 trace is the 1996 example. Rendering takes the
client protocol version (``SensingParams.protocol_version``: 3 for the paper's era, 19 today);
parsing detects the form by itself.

Version differences that matter here:

* see: protocol < 6 prints long names (``(flag r t)``, ``(ball)``, ``(player usa 2)``, close
  objects ``(Flag)``/``(Ball)``/...); >= 6 short names (``(f r t)``, ``(b)``,
  ``(p "usa" 2)``, ``(F)``/``(B)``/...). Numbers: ``Dist Dir [DistChg DirChg [BodyDir
  [HeadDir]]]``, or ``Dir`` alone in low quality. The paper's Figure 4 also shows
  ``((ball) 13.5 5 0)``: three numbers, read here as distance, direction and distance change.
  A seventh number (pointing direction) and a trailing ``t``/``k`` mark are accepted and dropped.
* hear: protocol <= 6 ``(hear T Dir Message)`` with the raw message, 7 quotes the message,
  >= 8 ``(hear T Dir our Unum "Msg")``, ``(hear T Dir opp "Msg")`` and the short forms
  ``(hear T our Unum)``, ``(hear T opp)``; ``(hear T self Msg)`` and ``(hear T referee Msg)``
  in every version.

Numbers are printed like C++ streams print doubles (``%g``, 6 significant digits), which is
exact for the server's quantised values, so a rendered message parses back to the same record.
A value ``%g`` would change (the exact floats of a perfect-perception see) is printed with
``repr`` instead, which parses back to the same double; directions may then be decimals. Any
malformed text raises
:class:`MessageParseError` (a ValueError) naming the position and showing the text; parsing
never raises anything else.
"""

from __future__ import annotations

import math
import re
from typing import TypeAlias

from field_models.soccer_server.hearing import HearInfo
from field_models.soccer_server.landmarks import is_known_name, long_name, short_name
from field_models.soccer_server.sensing import SeeInfo, SeenObject

MAX_DEPTH = 8
"""Deepest nesting the parser accepts (real messages nest at most 4 levels)."""
MAX_LENGTH = 65536
"""Longest message the parser accepts [characters] (the server's buffer is 8192)."""

_INT = re.compile(r"[-+]?[0-9]+", re.ASCII)
_FLOAT = re.compile(r"[-+]?(?:[0-9]+(?:\.[0-9]*)?|\.[0-9]+)(?:[eE][-+]?[0-9]{1,3})?", re.ASCII)
_ATOM = re.compile(r"[^\s()\"]+")
_PLAYER_KINDS = ("p", "player")
_CLOSE = ("B", "P", "F", "G")


class MessageParseError(ValueError):
    """A server message that does not follow the protocol: says what, where, and shows it."""

    def __init__(self, reason: str, text: str, position: int | None = None) -> None:
        self.reason = reason
        self.text = text
        self.position = position
        shown = text if len(text) <= 120 else text[:117] + "..."
        where = f" at position {position}" if position is not None else ""
        super().__init__(f"{reason}{where} in message {shown!r}")


# ----------------------------------------------------------------------------- s-expressions


class Quoted(str):
    """A double-quoted string token (team names, modern hear messages)."""

    __slots__ = ()


SExpr: TypeAlias = "str | list[SExpr]"


_TOKEN = re.compile(r'\s*(?:(\()|(\))|"([^"]*)("?)|([^\s()"]+))')


def parse_sexpr(text: str) -> list[SExpr]:
    """Parse one parenthesised S-expression into nested lists of atoms (str / :class:`Quoted`).

    Raises:
        MessageParseError: unbalanced parentheses, unterminated quote, trailing text, too deep.
    """
    if len(text) > MAX_LENGTH:
        raise MessageParseError(f"longer than {MAX_LENGTH} characters", text)
    start = _skip_space(text, 0)
    if start >= len(text) or text[start] != "(":
        raise MessageParseError("expected '('", text, start)
    stack: list[list[SExpr]] = []
    match = _TOKEN.match
    i = start
    while True:
        m = match(text, i)
        if m is None:
            break  # only trailing space (or nothing) is left
        i = m.end()
        opening, closing, quoted, end_quote, atom = m.groups()
        if opening:
            if len(stack) >= MAX_DEPTH:
                raise MessageParseError(f"nested deeper than {MAX_DEPTH}", text, m.start(1))
            node: list[SExpr] = []
            if stack:
                stack[-1].append(node)
            stack.append(node)
        elif closing:
            done = stack.pop()
            if not stack:
                _check_end(text, i)
                return done
        elif quoted is not None:
            if not end_quote:
                raise MessageParseError("unterminated quoted string", text, m.start(3) - 1)
            stack[-1].append(Quoted(quoted))
        else:
            stack[-1].append(atom)
    raise MessageParseError("missing ')' at the end", text, len(text))


def _check_end(text: str, i: int) -> None:
    """Only space or the server's terminating NUL may follow the closing parenthesis."""
    rest = _skip_space(text, i)
    if rest < len(text) and text[rest:].strip("\0 \t\r\n"):
        raise MessageParseError("text after the closing ')'", text, rest)


def _skip_space(text: str, i: int) -> int:
    """Index of the first non-space character at or after `i`."""
    n = len(text)
    while i < n and text[i].isspace():
        i += 1
    return i


def _int(token: SExpr, what: str, text: str, lo: int | None = None, hi: int | None = None) -> int:
    """An integer atom, in [lo, hi] when given."""
    if isinstance(token, list | Quoted) or not _INT.fullmatch(token):
        raise MessageParseError(f"{what}: expected an integer, got {_show(token)}", text)
    if len(token) > 12:
        raise MessageParseError(f"{what}: integer too long", text)
    value = int(token)
    if (lo is not None and value < lo) or (hi is not None and value > hi):
        raise MessageParseError(f"{what}: {value} outside [{lo}, {hi}]", text)
    return value


def _float(token: SExpr, what: str, text: str, non_negative: bool = False) -> float:
    """A finite number atom (``%g`` style), >= 0 when asked."""
    if isinstance(token, list | Quoted) or not _FLOAT.fullmatch(token):
        raise MessageParseError(f"{what}: expected a number, got {_show(token)}", text)
    if len(token) > 32:
        raise MessageParseError(f"{what}: number too long", text)
    value = float(token)
    if not math.isfinite(value):
        raise MessageParseError(f"{what}: not a finite number", text)
    if non_negative and value < 0:
        raise MessageParseError(f"{what}: expected >= 0, got {value}", text)
    return value + 0.0


def _show(token: SExpr) -> str:
    """A token for an error message."""
    if isinstance(token, list):
        return "a list"
    return repr(str(token))


def _num(value: float) -> str:
    """A number as the server prints it (``%g``; -0 as 0), or ``repr`` where ``%g`` would round.

    Integers (the server's directions) print as integers.
    """
    if type(value) is int:
        return str(value)
    value += 0.0
    text = f"{value:g}"
    return text if float(text) == value else repr(value)


# ----------------------------------------------------------------------------- see


def render_see(info: SeeInfo, protocol: int = 19) -> str:
    """The see message text for `info` in the given client protocol version.

    Raises:
        ValueError: an object whose optional fields cannot be written (e.g. a direction change
            without a distance change).
    """
    parts = [f"(see {info.time}"]
    for obj in info.objects:
        parts.append(f"({_render_name(obj, protocol)} {_render_numbers(obj)})")
    return " ".join(parts) + ")"


def _render_name(obj: SeenObject, protocol: int) -> str:
    """``(f r t)`` / ``(flag r t)``, ``(p "usa" 2)`` / ``(player usa 2)``."""
    short = protocol >= 6
    if obj.name == "p":
        words = ["p" if short else "player"]
        if obj.team is not None:
            words.append(f'"{obj.team}"' if short else obj.team)
            if obj.unum is not None:
                words.append(str(obj.unum))
        return "(" + " ".join(words) + ")"
    if short:
        return f"({obj.name})"
    long = _LONG_NAMES.get(obj.name)
    if long is None:
        long = _LONG_NAMES[obj.name] = f"({long_name(obj.name)})"
    return long


_LONG_NAMES: dict[str, str] = {}


def _render_numbers(obj: SeenObject) -> str:
    """``Dist Dir [DistChg DirChg [BodyDir [HeadDir]]]`` or ``Dir`` alone."""
    _, distance, direction, dist_chg, dir_chg, _, _, body, head = obj
    if distance is None:
        if dist_chg is not None or dir_chg is not None or body is not None or head is not None:
            raise ValueError(f"{obj}: changes without a distance cannot be written")
        return _num(direction)
    text = f"{_num(distance)} {_num(direction)}"
    if dist_chg is None:
        if dir_chg is not None or body is not None or head is not None:
            raise ValueError(f"{obj}: a missing value before a present one cannot be written")
        return text
    text += f" {_num(dist_chg)}"
    if dir_chg is None:
        if body is not None or head is not None:
            raise ValueError(f"{obj}: a missing value before a present one cannot be written")
        return text
    text += f" {_num(dir_chg)}"
    if body is None:
        if head is not None:
            raise ValueError(f"{obj}: a missing value before a present one cannot be written")
        return text
    text += f" {_num(body)}"
    return text if head is None else f"{text} {_num(head)}"


_SEE_CANONICAL = re.compile(r"\(see ([0-9]{1,12})((?: \(\([^()]*\)(?: [^\s()\"]+)+\))*)\)\0?")
_SEE_OBJECT = re.compile(r" \(\(([^()]*)\)((?: [^\s()\"]+)+)\)")


def parse_see(text: str) -> SeeInfo:
    """Parse a see message of any protocol version (long or short names detected per object).

    Messages in the server's own spacing take a regex fast path; anything else (and every
    error) goes through the general S-expression parser, which gives the same records.

    Raises:
        MessageParseError: anything that is not a well-formed see message.
    """
    m = _SEE_CANONICAL.fullmatch(text)
    if m is not None:
        try:
            objects = tuple(
                _object(_cached_ident(name, text), numbers.split(" ")[1:], text)
                for name, numbers in _SEE_OBJECT.findall(m.group(2))
            )
            return SeeInfo(int(m.group(1)), objects)
        except MessageParseError:
            pass  # let the general parser report it (or read an unusual spelling)
    return parse_see_general(text)


def parse_see_general(text: str) -> SeeInfo:
    """Parse a see message with the general S-expression parser (any spacing).

    Raises:
        MessageParseError: anything that is not a well-formed see message.
    """
    tree = parse_sexpr(text)
    if len(tree) < 2 or tree[0] != "see":
        raise MessageParseError("expected '(see Time ...)'", text, 0)
    time = _int(tree[1], "time", text, 0)
    objects = tuple(_parse_object(item, text) for item in tree[2:])
    return SeeInfo(time, objects)


_IDENT_CACHE: dict[str, _Ident] = {}


def _cached_ident(name: str, text: str) -> _Ident:
    """The parsed object name, memoised on its text (flag names and players recur)."""
    ident = _IDENT_CACHE.get(name)
    if ident is None:
        ident = _parse_name(_name_words(name), text)
        if len(_IDENT_CACHE) >= 4096:
            _IDENT_CACHE.clear()
        _IDENT_CACHE[name] = ident
    return ident


def _name_words(name: str) -> list[SExpr]:
    """The words of an object name in canonical spacing, quoted ones as :class:`Quoted`."""
    words: list[SExpr] = []
    for word in name.split(" "):
        if '"' in word:
            if len(word) < 2 or word[0] != '"' or word[-1] != '"' or '"' in word[1:-1]:
                raise MessageParseError("quoted word", name)  # caught: general parser decides
            words.append(Quoted(word[1:-1]))
        elif not word:
            raise MessageParseError("empty word", name)
        else:
            words.append(word)
    return words


def _parse_object(item: SExpr, text: str) -> SeenObject:
    """One ``(Name Numbers...)`` entry."""
    if not isinstance(item, list) or len(item) < 2 or not isinstance(item[0], list):
        raise MessageParseError(f"object: expected '((name) numbers...)', got {_show(item)}", text)
    return _object(_parse_name(item[0], text), item[1:], text)


_Ident: TypeAlias = tuple[str, str | None, int | None]


def _object(ident: _Ident, values: list[SExpr], text: str) -> SeenObject:
    """The numbers of one object: ``Dir`` or ``Dist Dir [DistChg DirChg [Body [Head [Point]]]]``."""
    name, team, unum = ident
    is_player = name == "p"
    if is_player and values and values[-1] in ("t", "k"):
        values = values[:-1]  # tackle / kick mark (protocol >= 13)
    n = len(values)
    if not 1 <= n <= (7 if is_player else 4):
        raise MessageParseError(
            f"object {name!r}: expected 1 to {7 if is_player else 4} numbers", text
        )
    if n == 1:
        return SeenObject(
            name, None, _angle(values[0], name, "direction", text), None, None, team, unum
        )
    distance = _value(values[0], name, "distance", text)
    if distance < 0:
        raise MessageParseError(f"{name} distance: expected >= 0, got {distance}", text)
    direction = _angle(values[1], name, "direction", text)
    dist_chg = _value(values[2], name, "distance change", text) if n > 2 else None
    dir_chg = _value(values[3], name, "direction change", text) if n > 3 else None
    body = _angle(values[4], name, "body direction", text) if n > 4 else None
    head = _angle(values[5], name, "head direction", text) if n > 5 else None
    if n > 6:
        _angle(values[6], name, "pointing direction", text)  # checked, dropped
    return SeenObject(name, distance, direction, dist_chg, dir_chg, team, unum, body, head)


def _angle(token: SExpr, name: str, field: str, text: str) -> float:
    """A direction in [-180, 180]; the error names the object and field.

    An integer as the server sends it, or a decimal (a perfect-perception see).
    """
    if type(token) is str and len(token) <= 12 and _INT.fullmatch(token):
        value = int(token)
        if -180 <= value <= 180:
            return value
    if type(token) is str and not _INT.fullmatch(token) and _FLOAT.fullmatch(token):
        exact = _value(token, name, field, text)
        if -180.0 <= exact <= 180.0:
            return exact
        raise MessageParseError(f"{name} {field}: {exact} outside [-180, 180]", text)
    return _int(token, f"{name} {field}", text, -180, 180)  # raises with the reason


def _value(token: SExpr, name: str, field: str, text: str) -> float:
    """A finite number; the error names the object and field."""
    if type(token) is str and len(token) <= 32 and _FLOAT.fullmatch(token):
        value = float(token)
        if math.isfinite(value):
            return value + 0.0
    return _float(token, f"{name} {field}", text)  # raises with the reason


def _parse_name(words: list[SExpr], text: str) -> tuple[str, str | None, int | None]:
    """Object name → (short name, team, unum); validates flags, goals and lines by name."""
    if not words or not all(isinstance(w, str) for w in words):
        raise MessageParseError("object name: expected words", text)
    head = words[0]
    assert isinstance(head, str)
    if head in _PLAYER_KINDS:
        return _parse_player_name(words[1:], text)
    if any(isinstance(w, Quoted) for w in words):
        raise MessageParseError(f"object name: unexpected quoted word in {head!r}", text)
    short = short_name(" ".join(str(w) for w in words))
    if not is_known_name(short):
        raise MessageParseError(f"unknown object name ({' '.join(map(str, words))})", text)
    return short, None, None


def _parse_player_name(rest: list[SExpr], text: str) -> tuple[str, str | None, int | None]:
    """``(p ["Team" [Unum [goalie]]])`` / ``(player [Team [Unum [goalie]]])``."""
    if rest and rest[-1] == "goalie" and len(rest) >= 2:
        rest = rest[:-1]
    if len(rest) > 2:
        raise MessageParseError("player name: too many words", text)
    team: str | None = None
    unum: int | None = None
    if rest:
        team = str(rest[0])
        if not team or any(ch.isspace() or ch in '()"' for ch in team):
            raise MessageParseError(f"player name: bad team name {team!r}", text)
    if len(rest) == 2:
        unum = _int(rest[1], "uniform number", text, 1, 99)
    return "p", team, unum


# ----------------------------------------------------------------------------- hear

_SENDERS = ("self", "referee", "coach", "online_coach_left", "online_coach_right")
_V8_FULL = re.compile(r'(our) ([0-9]{1,2}) "([^"]*)"|(opp) "([^"]*)"', re.ASCII)
_V8_SHORT = re.compile(r"(our) ([0-9]{1,2})|(opp)", re.ASCII)


def hear_style(protocol: int) -> str:
    """``"raw"`` (<= 6), ``"quoted"`` (7) or ``"team"`` (>= 8) player-message form."""
    return "raw" if protocol <= 6 else "quoted" if protocol == 7 else "team"


def render_hear(info: HearInfo, protocol: int = 19) -> str:
    """The hear message text for `info` in the given protocol version.

    Raises:
        ValueError: a record the protocol cannot express (e.g. a player message without a
            direction, or a short form before protocol 8).
    """
    style = hear_style(protocol)
    if info.sender != "player":
        if info.text is None:
            raise ValueError(f"{info}: a {info.sender} message needs a text")
        body = f'"{info.text}"' if info.sender == "self" and style != "raw" else info.text
        return f"(hear {info.time} {info.sender} {body})"
    if info.text is None:
        if style != "team":
            raise ValueError("short-form hear messages exist from protocol 8 only")
        who = f"our {info.unum}" if info.team == "our" else "opp"
        return f"(hear {info.time} {who})"
    if info.direction is None:
        raise ValueError(f"{info}: a player message needs a direction")
    if style == "raw":
        return f"(hear {info.time} {info.direction} {info.text})"
    if style == "quoted":
        return f'(hear {info.time} {info.direction} "{info.text}")'
    who = f"our {info.unum}" if info.team == "our" else "opp"
    return f'(hear {info.time} {info.direction} {who} "{info.text}")'


def parse_hear(text: str) -> HearInfo:
    """Parse a hear message of any protocol version (§2.6).

    Raises:
        MessageParseError: anything that is not a well-formed hear message.
    """
    if len(text) > MAX_LENGTH:
        raise MessageParseError(f"longer than {MAX_LENGTH} characters", text)
    body = text.rstrip("\0 \t\r\n")
    if not body.startswith("(hear ") or not body.endswith(")"):
        raise MessageParseError("expected '(hear Time Sender Message)'", text, 0)
    inner = body[len("(hear ") : -1]
    time_tok, _, rest = inner.partition(" ")
    time = _int(time_tok, "time", text, 0)
    if not rest:
        raise MessageParseError("hear: missing sender", text, len(text) - 1)
    short = _V8_SHORT.fullmatch(rest)
    if short is not None:
        unum = int(short.group(2)) if short.group(1) else None
        return HearInfo(time, "player", None, None, short.group(1) or "opp", unum)
    sender, _, message = rest.partition(" ")
    if sender in _SENDERS:
        return HearInfo(time, sender, _message(message, text))
    direction = _int(sender, "hear sender or direction", text, -180, 180)
    full = _V8_FULL.fullmatch(message)
    if full is not None:
        if full.group(1):
            unum = int(full.group(2))
            return HearInfo(time, "player", _nonempty(full.group(3), text), direction, "our", unum)
        return HearInfo(time, "player", _nonempty(full.group(5), text), direction, "opp", None)
    return HearInfo(time, "player", _message(message, text), direction)


def _message(message: str, text: str) -> str:
    """The message part: a quoted string (protocol >= 7) or the raw rest (older)."""
    if message.startswith('"'):
        if len(message) < 2 or not message.endswith('"') or '"' in message[1:-1]:
            raise MessageParseError("hear: badly quoted message", text)
        return _nonempty(message[1:-1], text)
    if '"' in message:
        raise MessageParseError("hear: stray quote in message", text)
    return _nonempty(message, text)


def _nonempty(message: str, text: str) -> str:
    """Refuse an empty message."""
    if not message:
        raise MessageParseError("hear: empty message", text)
    return message
