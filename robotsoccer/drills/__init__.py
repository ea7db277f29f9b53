"""The coach's drills, by name."""

from __future__ import annotations

import functools
import inspect
from collections.abc import Callable, Mapping
from typing import Any

from robotsoccer.drills.base import Drill, GoalWatch, Verdict
from robotsoccer.drills.intercept import InterceptDrill
from robotsoccer.drills.match import MatchDrill
from robotsoccer.drills.passing import PassDrill
from robotsoccer.drills.setplay import SetPlayDrill
from robotsoccer.drills.shootout import ShootoutDrill

DRILLS: dict[str, Callable[..., Drill]] = {
    "shootout": ShootoutDrill,
    "intercept": InterceptDrill,
    "pass": PassDrill,
    "setplay": SetPlayDrill,
    "match": MatchDrill,
}
"""Registered drills: name → factory taking the drill's options as keywords."""


def make_drill(name: str, options: Mapping[str, Any] | None = None) -> Drill:
    """A fresh drill by registered name, with its options.

    Raises:
        ValueError: for an unknown drill or an option it does not take.
    """
    try:
        factory = DRILLS[name]
    except KeyError:
        raise ValueError(f"unknown drill {name!r} (known: {', '.join(sorted(DRILLS))})") from None
    given = dict(options or {})
    known = drill_options(name)
    unknown = sorted(set(given) - set(known))
    if unknown:
        raise ValueError(
            f"drill {name!r} has no option {unknown[0]!r} (options: {', '.join(known)})"
        )
    try:
        return factory(**given)
    except TypeError as exc:  # an option of the wrong type, e.g. a word where a number goes
        raise ValueError(f"drill {name!r}: {exc}") from None


@functools.cache
def drill_options(name: str) -> tuple[str, ...]:
    """The options drill `name` takes, in its signature's order."""
    return tuple(inspect.signature(DRILLS[name]).parameters)


__all__ = ["DRILLS", "Drill", "GoalWatch", "Verdict", "drill_options", "make_drill"]
