"""The coach's drills, by name."""

from __future__ import annotations

import dataclasses
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
"""Registered drills: name → factory taking the drill's options as keywords
(:func:`drill_options` names them)."""


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
    """The options drill `name` takes, in order.

    A drill whose options are a typed record names it as ``OPTIONS`` (a dataclass): its fields;
    any other drill takes its options as keywords: its signature's parameters.
    """
    factory = DRILLS[name]
    record = getattr(factory, "OPTIONS", None)
    if isinstance(record, type) and dataclasses.is_dataclass(record):
        return tuple(field.name for field in dataclasses.fields(record))
    return tuple(inspect.signature(factory).parameters)


__all__ = ["DRILLS", "Drill", "GoalWatch", "Verdict", "drill_options", "make_drill"]
