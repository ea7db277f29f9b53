"""Client skills: minds that act on percepts only, wrapping the learned layers into behaviours.

:mod:`robotsoccer.skills.intercept` — layer 1 (paper §5): the interception defender with its
behaviours (still, straight, random, net, lookup, analytic) and the drill's shooter.
"""

from __future__ import annotations

from robotsoccer.skills.intercept import (
    BEHAVIOURS,
    TA_MODES,
    DefenderMind,
    ShooterMind,
    TurnPolicy,
    load_lookup_table,
    load_net_function,
    make_policy,
)

__all__ = [
    "BEHAVIOURS",
    "TA_MODES",
    "DefenderMind",
    "ShooterMind",
    "TurnPolicy",
    "load_lookup_table",
    "load_net_function",
    "make_policy",
]
