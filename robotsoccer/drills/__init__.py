"""The coach's drills, by name."""

from __future__ import annotations

from collections.abc import Callable

from robotsoccer.drills.base import Drill, Verdict
from robotsoccer.drills.shootout import ShootoutDrill

DRILLS: dict[str, Callable[[], Drill]] = {"shootout": ShootoutDrill}
"""Registered drills: name → factory."""


def make_drill(name: str) -> Drill:
    """A fresh drill by registered name."""
    try:
        return DRILLS[name]()
    except KeyError:
        raise ValueError(f"unknown drill {name!r} (known: {', '.join(sorted(DRILLS))})") from None


__all__ = ["DRILLS", "Drill", "Verdict", "make_drill"]
