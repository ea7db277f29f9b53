"""Reading a real rcssserver's configuration: a ``server.conf`` file or a ``server_param`` message.

Both formats as rcssserver 19.0.0 writes them:


* a ``server.conf`` file (``rcss/conf/builder.hpp``, ``createConfFileEntry``; parsed as
  ``rcss/conf/parser.cpp`` does): lines ``server::ball_decay = 0.94``; comments ``# ...``,
  ``// ...`` and ``/* ... */`` (several lines); blank lines; values ``true``/``false``/``on``/
  ``off`` (any case), integers, reals (``0.94``, ``1e-05``) and strings, quoted ``'...'`` or
  ``"..."`` or bare, on the line of their ``=``; an optional ``-``/``--`` before a name and
  the module ``server::`` are accepted (a name without a module counts as a server
  parameter); ``server::version`` is accepted and not used; a later setting of a parameter
  replaces an earlier one; ``include`` and ``help`` are refused;
* the text of a ``(server_param (goal_width 14.02) (ball_decay 0.94) ...)`` message as a
  server sends it to clients (``src/initsender.cpp``, ``InitSenderCommonV8``): doubles as a

Values are checked against the parameter's type in the server (``src/serverparam.h``,
:mod:`field_models.soccer_server.server_param_table`): a double takes any number, an integer an
integral number, a boolean a truth value or 0/1, a string a string. A name that is not a server
parameter or a value of the wrong type raises :class:`~field_models.presets.PresetError`
naming the file (and line) and the key. What the settings do to a preset is
:mod:`field_models.soccer_server.server_conf`'s.
"""

from __future__ import annotations

import math
import re
from typing import NamedTuple

from field_models.presets import PresetError
from field_models.soccer_server.messages import MessageParseError, Quoted, parse_sexpr
from field_models.soccer_server.server_param_table import (
    BOOL_PARAMS,
    INT_PARAMS,
    SERVER_PARAMS,
    STR_PARAMS,
    ServerValue,
)

_KNOWN = frozenset(SERVER_PARAMS)
MESSAGE_SOURCE = "<server_param message>"
"""How errors and :attr:`ServerPreset.source` name a configuration given as message text."""


class Setting(NamedTuple):
    """One parameter as the configuration sets it.

    Attributes:
        name: The server's parameter name (``ball_decay``).
        key: The key as written (``server::ball_decay`` in a server.conf), named in errors.
        value: The value as read: bool, int, float or str.
        where: The file, with the line in a server.conf (``server.conf:12``), named in errors.
    """

    name: str
    key: str
    value: ServerValue
    where: str


# ----------------------------------------------------------------------------- server.conf

_INT_TEXT = re.compile(r"[-+]?[0-9]+")
_REAL_TEXT = re.compile(r"[-+]?(?:[0-9]+\.[0-9]*|\.[0-9]+|[0-9]+(?=[eE]))(?:[eE][-+]?[0-9]+)?")
_NAME_END = frozenset(" \t\r\n\0=\"'")
_MAX_INT_DIGITS = 4000


def parse_server_conf(text: str, *, file: str) -> list[Setting]:
    """The settings of a ``server.conf`` text, in order (format: see the module docstring).

    Raises:
        PresetError: naming the file, the line and the key: a syntax error, a parameter that is
            not a server parameter, or a value of the wrong type.
    """
    settings: list[Setting] = []
    scan = _Scanner(text, file)
    while True:
        scan.skip_junk()
        if scan.done():
            return settings
        line = scan.line
        key = scan.name()
        where = f"{file}:{line}"
        module, _, name = key.rpartition("::")
        if name.lower() in ("include", "help") and not module:
            raise PresetError(f"{where}: key '{key}': '{name}' is not supported here")
        scan.skip_junk()
        if not scan.take("="):
            raise PresetError(f"{where}: key '{key}': expected '=' after the name")
        raw, quoted = scan.value(key, where)
        if module not in ("", "server"):
            raise PresetError(f"{where}: key '{key}': not a server parameter (module '{module}')")
        if name == "version":
            continue  # the server version that wrote the file
        value = _conf_value(raw, quoted)
        settings.append(Setting(name, key, _typed(name, value, key, where), where))


class _Scanner:
    """A cursor over a server.conf text that knows its comments, names and values."""

    def __init__(self, text: str, file: str) -> None:
        self.text = text
        self.file = file
        self.pos = 0
        self.line = 1

    def done(self) -> bool:
        return self.pos >= len(self.text)

    def take(self, char: str) -> bool:
        if self.text.startswith(char, self.pos):
            self.pos += len(char)
            return True
        return False

    def _advance(self, end: int) -> None:
        self.line += self.text.count("\n", self.pos, end)
        self.pos = end

    def skip_junk(self) -> None:
        """Skip space, newlines and comments (``#``, ``//``, ``/* */``)."""
        text = self.text
        while self.pos < len(text):
            char = text[self.pos]
            if char in " \t\r\n\0":
                self._advance(self.pos + 1)
            elif char == "#" or text.startswith("//", self.pos):
                end = text.find("\n", self.pos)
                self._advance(len(text) if end < 0 else end)
            elif text.startswith("/*", self.pos):
                end = text.find("*/", self.pos + 2)
                if end < 0:
                    raise PresetError(f"{self.file}:{self.line}: a '/*' comment is not closed")
                self._advance(end + 2)
            else:
                return

    def name(self) -> str:
        """A parameter name (``server::ball_decay``), after an optional ``-`` or ``--``."""
        self.take("-")
        self.take("-")
        start = self.pos
        while self.pos < len(self.text) and self.text[self.pos] not in _NAME_END:
            self.pos += 1
        key = self.text[start : self.pos]
        if not key or key.startswith(":") or key.endswith(":") or ":::" in key:
            shown = self.text[start : start + 20].split("\n")[0]
            raise PresetError(f"{self.file}:{self.line}: expected a parameter name, got {shown!r}")
        return key

    def value(self, key: str, where: str) -> tuple[str, bool]:
        """The value after ``=`` on the same line: its text and whether it was quoted."""
        text = self.text
        while self.pos < len(text) and text[self.pos] in " \t":
            self.pos += 1
        if self.pos < len(text) and text[self.pos] in "'\"":
            quote = text[self.pos]
            i = self.pos + 1
            while i < len(text) and text[i] != quote:
                i += 2 if text[i] == "\\" else 1
            if i >= len(text):
                raise PresetError(f"{where}: key '{key}': unterminated string")
            raw = text[self.pos + 1 : i].replace("\\" + quote, quote)
            self._advance(i + 1)
            return raw, True
        start = self.pos
        while self.pos < len(text) and text[self.pos] not in " \t\r\n\0":
            self.pos += 1
        raw = text[start : self.pos]
        if not raw:
            raise PresetError(f"{where}: key '{key}': expected a value after '='")
        return raw, False


def _conf_value(raw: str, quoted: bool) -> ServerValue:
    """A server.conf value as the server's parser reads it: truth value, number or string."""
    if quoted:
        return raw
    lower = raw.lower()
    if lower in ("on", "true"):
        return True
    if lower in ("off", "false"):
        return False
    if _INT_TEXT.fullmatch(raw):
        # Python refuses to read integers of more than 4300 digits; as a double such a
        # number is out of range, and _typed says so.
        return int(raw) if len(raw) <= _MAX_INT_DIGITS else math.inf
    if _REAL_TEXT.fullmatch(raw):
        return float(raw)  # 1e999 overflows to inf, refused by _typed as inf is
    return raw


# ----------------------------------------------------------------------------- server_param


def parse_server_param(text: str, *, file: str = MESSAGE_SOURCE) -> list[Setting]:
    """The settings of a ``(server_param (name value) ...)`` message, in order.

    Raises:
        PresetError: naming `file` and the key: a malformed message, a parameter that is not a
            server parameter, or a value of the wrong type.
    """
    try:
        tree = parse_sexpr(text)
    except MessageParseError as exc:
        raise PresetError(f"{file}: not a server_param message ({exc.reason})") from None
    if not tree or tree[0] != "server_param":
        raise PresetError(f"{file}: expected '(server_param (name value) ...)'")
    settings: list[Setting] = []
    for item in tree[1:]:
        if (
            not isinstance(item, list)
            or len(item) != 2
            or not isinstance(item[0], str)
            or isinstance(item[0], Quoted)
            or isinstance(item[1], list)
        ):
            shown = "a list" if isinstance(item, list) else repr(str(item))
            raise PresetError(f"{file}: expected '(name value)' entries, got {shown}")
        name, token = str(item[0]), item[1]
        value: ServerValue = str(token) if isinstance(token, Quoted) else _conf_value(token, False)
        settings.append(Setting(name, name, _typed(name, value, name, file), file))
    return settings


def _typed(name: str, value: ServerValue, key: str, where: str) -> ServerValue:
    """`value` as parameter `name`'s type in the server (int, bool, double or string).

    Raises:
        PresetError: `name` is not a parameter of rcssserver 19, or `value` cannot be its type.
    """
    if name not in _KNOWN:
        raise PresetError(f"{where}: key '{key}': not a parameter of rcssserver 19")
    shown = f"{type(value).__name__} {_short(value)}"
    if name in STR_PARAMS:
        if not isinstance(value, str):
            raise PresetError(f"{where}: key '{key}': expected a string, got {shown}")
        return value
    if name in BOOL_PARAMS:
        if isinstance(value, bool):
            return value
        if isinstance(value, int) and value in (0, 1):
            return bool(value)  # server_param messages print booleans as 0 and 1
        raise PresetError(f"{where}: key '{key}': expected true or false, got {shown}")
    if isinstance(value, bool) or not isinstance(value, int | float):
        raise PresetError(f"{where}: key '{key}': expected a number, got {shown}")
    # The server would read 1e999 as the largest double or inf; either is no parameter value,
    # so an overflowing number is refused like a written inf (which is not a number here).
    if (isinstance(value, float) and not math.isfinite(value)) or abs(value) > _MAX_NUMBER:
        raise PresetError(f"{where}: key '{key}': expected a finite number, got {_short(value)}")
    if name in INT_PARAMS:
        if isinstance(value, float) and not value.is_integer():
            raise PresetError(f"{where}: key '{key}': expected an integer, got {shown}")
        if not _INT_MIN <= value <= _INT_MAX:  # the server holds it in a C int
            raise PresetError(
                f"{where}: key '{key}': expected an integer in [{_INT_MIN}, {_INT_MAX}], "
                f"got {_short(value)}"
            )
        return int(value)
    return float(value)


_MAX_NUMBER = 1e300
"""The largest magnitude a number parameter may have: within a double, with room to compute."""
_INT_MIN, _INT_MAX = -(2**31), 2**31 - 1
"""The range of the server's ``int`` parameters (a 32-bit C int)."""


def _short(value: ServerValue) -> str:
    """A number for a one-line message: 1e999 read as inf, a 4000-digit integer not shown whole."""
    if isinstance(value, float) and math.isinf(value):
        return "a number beyond a double's range"
    text = repr(value)
    return text if len(text) <= 32 else f"an integer of {len(text.lstrip('-'))} digits"
