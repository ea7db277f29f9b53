"""Drill and skill options given as text (command lines, run specs): choices and flags.

Options with a fixed set of values are :class:`enum.StrEnum` members; :func:`choice` turns a
string into one and, for anything else, raises a ValueError that names the option and lists
its values — the one line a user sees. :func:`bounded` and :func:`duration` do the same for
numbers, within the sane limits below (counts, seeds, simulated time), so an absurd option is
refused in one line instead of running to nonsense or filling the memory.
"""

from __future__ import annotations

import math
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


MAX_COUNT = 10**8
"""The most trials, games or plays one command runs: a run keeps about a byte per trial, and
10^8 trials take days on a workstation."""
MAX_WORKERS = 1024
"""The most worker processes a run starts."""
MAX_SEED = 2**64 - 1
"""The largest seed or trial index (Gymnasium's rule: seeds are integers in [0, 2^64))."""
MAX_SIMULATED_S = 3600.0
"""The longest simulated time a trial, play or half may last [s]: a tick limit for every loop
that waits for the ball or the clock."""


def bounded(option: str, value: float, low: float, high: float, *, low_open: bool = False) -> float:
    """`value` when it is a finite number in [`low`, `high`] ((`low`, `high`] if `low_open`).

    >>> bounded("--ball-noise", 0.05, 0.0, 1.0)
    0.05

    Raises:
        ValueError: ``--ball-noise must be a number in [0, 1], got 1e+308``.
    """
    above = value > low if low_open else value >= low
    if not (math.isfinite(value) and above and value <= high):
        shown = f"{'(' if low_open else '['}{low:g}, {high:g}]"
        raise ValueError(f"{option} must be a number in {shown}, got {value!r}")
    return value


def duration(option: str, value: object, *, longest: float = MAX_SIMULATED_S) -> float:
    """A simulated duration [s] > 0 and at most `longest` (a drill's ``max_time_s``).

    Raises:
        ValueError: ``max_time_s must be a number in (0, 3600], got 0.0``, naming the option.
    """
    if isinstance(value, bool) or not isinstance(value, int | float | str):
        raise ValueError(f"{option} must be a number of seconds, got {value!r}")
    try:
        seconds = float(value)
    except (ValueError, OverflowError):
        raise ValueError(f"{option} must be a number of seconds, got {value!r}") from None
    return bounded(option, seconds, 0.0, longest, low_open=True)
