"""Issue 28's dithering measure: turn reversals of players, counted from true headings.

Used by the match studies and scripts (``scripts/server_series.py``, ``option_series.py``,
``robot_supersession.py``) and the tests that keep the team minds from dithering.
"""

from __future__ import annotations

import math

from field_models.protocol import wrap_angle

REVERSAL_MIN_TURN_RAD = math.radians(10.0)
"""A turn counted by :class:`TurnReversals` is one of more than 10° (issue 28's definition)."""


class TurnReversals:
    """Counts turn reversals: a turn of more than 10° the other way from the last such turn.

    Issue 28's dithering measure ("a reversal is a turn of more than 10° the other way from the
    player's last turn of more than 10°"). Feed it each player's true heading once per sample
    (a Soccer Server cycle; on the robots every 100 ms, the server's cycle, so the rates compare):
    the turn is the heading change since the player's previous sample.

    Attributes:
        count: Reversals seen so far, all players together.
    """

    def __init__(self, min_turn_rad: float = REVERSAL_MIN_TURN_RAD) -> None:
        if not (math.isfinite(min_turn_rad) and min_turn_rad >= 0.0):
            raise ValueError(f"min_turn_rad must be a finite angle >= 0, got {min_turn_rad!r}")
        self.min_turn_rad = min_turn_rad
        self.count = 0
        self._heading: dict[object, float] = {}
        self._sign: dict[object, int] = {}

    def sample(self, player: object, heading_rad: float) -> None:
        """Take `player`'s heading [rad] now; count a reversal if this turn is one."""
        last = self._heading.get(player)
        self._heading[player] = heading_rad
        if last is None:
            return
        turn = wrap_angle(heading_rad - last)
        if abs(turn) > self.min_turn_rad:
            sign = 1 if turn > 0.0 else -1
            if self._sign.get(player, 0) == -sign:
                self.count += 1
            self._sign[player] = sign
