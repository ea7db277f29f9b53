"""The coach's drills, by name."""

from __future__ import annotations

from collections.abc import Callable, Mapping
from typing import Any

from robotsoccer.drills.base import Drill, Verdict
from robotsoccer.drills.intercept import InterceptDrill
from robotsoccer.drills.shootout import ShootoutDrill

DRILLS: dict[str, Callable[..., Drill]] = {"shootout": ShootoutDrill, "intercept": InterceptDrill}
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
    try:
        return factory(**dict(options or {}))
    except TypeError as exc:
        raise ValueError(f"drill {name!r}: {exc}") from None


__all__ = ["DRILLS", "Drill", "Verdict", "make_drill"]
