"""Macro-actions for the match environments: one skill of the team minds per decision.

HFO (Hausknecht & Stone's half-field offense) gives its agents high-level actions besides the
server's commands: move, intercept, shoot, dribble, pass to teammate k. Here they are the
skills of the match's own :class:`~robotsoccer.skills.team.TeamMind`, so a macro does exactly
what the hand-written team does when its rule picks that skill (no second copy of the logic):

* ``AUTO`` (0) — the team mind's own decision (its whole rule, module docstring of
  :mod:`robotsoccer.skills.team`): the hand-written policy;
* ``INTERCEPT`` (1) — go for the ball: layer 1's interception for a layered team, straight at
  the ball for the baseline (the mind's chase);
* ``GO_HOME`` (2) — go to the formation home, shifted toward the ball, and face the ball;
* ``SHOOT`` (3) — kick at the opponents' goal with the shot power;
* ``DRIBBLE`` (4) — kick the ball a short way toward the opponents' goal;
* ``PASS_k`` (4 + k, k = 1 … team size) — kick to teammate k with the pass power.

**Masks** (:func:`macro_mask`, from the percept the agent decides on): ``AUTO`` and ``GO_HOME``
always; ``INTERCEPT`` when the ball is seen out of the mind's reach
(:attr:`~robotsoccer.skills.team_setup.TeamSetup.reach_m`); the kicks (``SHOOT``, ``DRIBBLE``,
``PASS_k``) when it is seen within that reach, the very test the mind makes before it kicks,
and ``PASS_k`` only for a teammate k the percept shows with its number (never the player
itself). So the ball holder chooses among ``{AUTO, GO_HOME, SHOOT, DRIBBLE, PASS_k …}``: the
choice the layer-3 learners learn (TPOT-RL: where to send the ball).

A macro lasts one decision (one percept), as HFO's do. Two rules of the mind stay in force
whatever the macro: with the ball unseen every macro searches for it (the mind turns toward
where it last saw it), and a decision that comes while the player's last turn is still under
way (the robots' camera latency) is skipped, as the mind skips it. ``SHOOT`` and ``DRIBBLE``
with the goal's direction unknown (not localised, goal unseen) turn to look for it, as the
mind does.
"""

from __future__ import annotations

from enum import IntEnum
from typing import Any

import numpy as np
import numpy.typing as npt

from field_models.protocol import Action, Kick, Percept, SeenPlayer, Turn
from robotsoccer.skills.localise import Pose
from robotsoccer.skills.team import TeamMind
from robotsoccer.skills.team_setup import SEARCH_TURN_RAD, TeamSetup


class Macro(IntEnum):
    """The macro-actions before the passes (module docstring)."""

    AUTO = 0
    INTERCEPT = 1
    GO_HOME = 2
    SHOOT = 3
    DRIBBLE = 4


PASS_BASE = len(Macro)
"""``PASS_BASE + k - 1`` passes to teammate number k."""
KICKS = (Macro.SHOOT, Macro.DRIBBLE)
"""The kicks other than passes."""


def macro_count(team_size: int) -> int:
    """How many macro-actions a player of a team of `team_size` has."""
    return PASS_BASE + team_size


def pass_macro(number: int) -> int:
    """The macro that passes to teammate `number`."""
    return PASS_BASE + number - 1


def macro_names(team_size: int) -> tuple[str, ...]:
    """The macros' names in index order (``PASS_1`` …)."""
    return (*(m.name for m in Macro), *(f"PASS_{k}" for k in range(1, team_size + 1)))


def holds_ball(percept: Percept, setup: TeamSetup) -> bool:
    """Whether the ball is seen within the reach the mind trusts for a kick."""
    ball = percept.ball
    return ball is not None and ball.distance_m <= setup.reach_m


def macro_mask(percept: Percept, setup: TeamSetup, team_size: int) -> npt.NDArray[np.int8]:
    """The macros open to the player on `percept` (module docstring), 1 where allowed."""
    mask = np.zeros(macro_count(team_size), dtype=np.int8)
    mask[Macro.AUTO] = mask[Macro.GO_HOME] = 1
    if percept.ball is None:
        return mask
    if not holds_ball(percept, setup):
        mask[Macro.INTERCEPT] = 1
        return mask
    mask[list(KICKS)] = 1
    me = percept.player
    for number in range(1, team_size + 1):
        if number != me.number and _teammate(percept, number) is not None:
            mask[pass_macro(number)] = 1
    return mask


def _teammate(percept: Percept, number: int) -> SeenPlayer | None:
    """Teammate `number` as the percept shows it (team and number known), or None."""
    own = percept.player.team
    for seen in percept.players:
        if seen.team == own and seen.number == number:
            return seen
    return None


def checked_macro(agent: str, value: Any, count: int) -> int:
    """`agent`'s macro action `value` as an index in 0..count-1.

    Raises:
        ValueError: Not one integer, or out of range.
    """
    array = np.asarray(value) if not isinstance(value, str | bytes) else None
    if array is None or array.shape not in ((), (1,)) or not np.issubdtype(array.dtype, np.integer):
        raise ValueError(
            f"{agent}'s action is a macro, an integer in 0..{count - 1}, got {value!r:.60}"
        )
    index = int(array.reshape(()))
    if not 0 <= index < count:
        raise ValueError(f"{agent}'s macro must be in 0..{count - 1}, got {index}")
    return index


class MacroMind(TeamMind):
    """A team mind that plays the macro its agent chose (module docstring).

    Same arguments as :class:`~robotsoccer.skills.team.TeamMind`. Set :attr:`macro` before
    each percept is handed to :meth:`act`; ``Macro.AUTO`` makes it the team mind itself.

    Attributes:
        macro: The macro of the next decision.
    """

    macro: int = Macro.AUTO

    def _is_chaser(self, percept: Percept) -> bool:
        """The team's chaser rule under AUTO; otherwise every macro but GO_HOME goes for it."""
        if self.macro == Macro.AUTO:
            return super()._is_chaser(percept)
        return self.macro != Macro.GO_HOME

    def _on_ball(self, percept: Percept, pose: Pose | None) -> tuple[Action, ...]:
        """The kick the macro names; AUTO (and a macro that is no kick): the team's rule."""
        macro, powers = self.macro, self.setup.powers
        if macro >= PASS_BASE:
            number = macro - PASS_BASE + 1
            seen = _teammate(percept, number)
            if seen is None:  # masked out; a direct caller gets the team's rule
                return super()._on_ball(percept, pose)
            return self._spell("pass", f"pass {number}", Kick(powers.passing, seen.angle_rad))
        if macro not in KICKS:
            return super()._on_ball(percept, pose)
        goal = self._goal_direction(percept, pose)
        if goal is None:
            self.intent = "search"
            return (Turn(SEARCH_TURN_RAD),)  # the mind's own move: hold the ball, find the goal
        if macro == Macro.SHOOT:
            return self._spell("shoot", "shoot", Kick(powers.shot, goal[1]))
        self.intent = "dribble"
        return (Kick(powers.dribble, goal[1]),)

    def _spell(self, kind: str, intent: str, kick: Kick) -> tuple[Action, ...]:
        """A shot or pass, counted once per spell on the ball as the team mind counts it."""
        self.intent = intent
        if self._spell_kicked != kind:
            if kind == "shoot":
                self.shots += 1
            else:
                self.passes += 1
            self._spell_kicked = kind
        return (kick,)
