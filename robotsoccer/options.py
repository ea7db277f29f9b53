"""Drill and skill options given as text (command lines, run specs): choices and flags.

Options with a fixed set of values are :class:`enum.StrEnum` members; :func:`choice` turns a
string into one and, for anything else, raises a ValueError that names the option and lists
its values — the one line a user sees.
"""

from __future__ import annotations

from enum import StrEnum
from typing import TypeVar

E = TypeVar("E", bound=StrEnum)


def choice(kind: type[E], value: object, option: str) -> E:
    """`value` as a member of `kind`.

    >>> from enum import StrEnum
    >>> class Colour(StrEnum):
    ...     RED = "red"
    >>> choice(Colour, "red", "colour") is Colour.RED
    True

    Raises:
        ValueError: ``unknown <option> 'x' (known: a, b, c)``.
    """
    if isinstance(value, kind):
        return value
    if isinstance(value, str) and value in kind._value2member_map_:
        return kind(value)
    known = ", ".join(member.value for member in kind)
    raise ValueError(f"unknown {option} {value!r} (known: {known})")


def flag(option: str, value: bool | str) -> bool:
    """A boolean option; the strings "true"/"false" (any case) too, e.g. from a command line.

    Raises:
        ValueError: Anything else, naming the option.
    """
    if isinstance(value, bool):
        return value
    if isinstance(value, str) and value.lower() in ("true", "false"):
        return value.lower() == "true"
    raise ValueError(f"{option} must be true or false, got {value!r}")
