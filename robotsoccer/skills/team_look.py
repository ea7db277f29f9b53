"""Looking with the neck: where a team mind points its head, and its view width (issue 28).

On the Soccer Server a player sees along body + neck (shared `specs/soccer_server.md` §2.2,
§3.1), the neck within ±90° of the body, and ``turn_neck`` and ``change_view`` go beside the
cycle's body command (§1.1). With :attr:`~robotsoccer.skills.team_setup.TeamSetup.look`
``"neck"`` a team mind keeps its body for moving and looks with its head:

* **a ball seen, or seen within** :data:`LOOK_MEMORY_TICKS`: the neck points at it, allowing for
  the body turn the same cycle carries out (the neck is relative to the body), clipped to the
  neck's range; the view is normal;
* **no ball**: it scans: a wide view (180°) with the neck at one end of its range, then the
  other, so two sees cover all round the body whatever it does;
* a neck turn smaller than :data:`NECK_STEP_RAD` is not sent (the server prints directions in
  whole degrees); a view is sent only when it changes.

The body's own rules for this mode (a player off the ball walks home facing where it walks and
turns to the ball only when the head cannot reach it) are in
:mod:`robotsoccer.skills.team_chase`. On the robots the neck and view actions are accepted and
ignored (their camera sees all round), so the same minds run there.
"""

from __future__ import annotations

import dataclasses
import math

from field_models.protocol import Action, ChangeView, Percept, Turn, TurnNeck, wrap_angle
from robotsoccer.skills.localise import Pose

NECK_MAX_RAD = math.radians(90.0)
"""The neck's range either side of the body: rcssserver's ``maxneckang`` (§2.2)."""
VIEW_HALF_RAD = math.radians(45.0)
"""Half the normal view cone (``visible_angle`` / 2, §3.1): both Soccer Server presets'."""
LOOK_COVER_RAD = NECK_MAX_RAD + VIEW_HALF_RAD - math.radians(15.0)
"""A ball within this of the body's heading is kept in view by the neck alone (a margin of 15°
inside the cone's edge); farther round, a player at home turns its body toward it."""
NECK_STEP_RAD = math.radians(1.0)
"""Neck turns smaller than this are not sent."""
BACK_STEP_TOLERANCES = 4.0
"""Looking with the neck, a player whose home is behind it and within this many home
tolerances steps back to it (a negative dash) rather than turning round."""
LOOK_MEMORY_TICKS = 5
"""A ball not seen for longer than this [ticks] is looked for, no longer looked at."""


class NeckLook:
    """One player's head: its neck angle as last sensed, its view, its scan (module docstring).

    Attributes:
        neck_rad: The neck angle of the last percept (the server's truth at that see) [rad].
        view: The view width the player last asked for.
    """

    def __init__(self) -> None:
        self.neck_rad = 0.0
        self.view = "normal"
        self._scan_side = 1.0

    def sensed(self, percept: Percept) -> Percept:
        """Note the percept's neck angle; the percept with directions from the body."""
        self.neck_rad = percept.neck_rad
        return percept.body_relative()

    def look(self, actions: tuple[Action, ...], target_rad: float | None) -> tuple[Action, ...]:
        """`actions` with the neck turn and view change that look toward `target_rad`.

        Args:
            actions: The body's decision (its first turn runs in the same cycle as the neck's).
            target_rad: Where to look, from the body now [rad]; None: scan.
        """
        if target_rad is None:
            view = "wide"
            self._scan_side = -self._scan_side  # the other end of the neck's range each see
            goal = self._scan_side * NECK_MAX_RAD
        else:
            view = "normal"
            first = actions[0] if actions else None
            turn = first.angle_rad if isinstance(first, Turn) else 0.0  # the next step's turn
            goal = max(-NECK_MAX_RAD, min(wrap_angle(target_rad - turn), NECK_MAX_RAD))
        out = list(actions)
        if view != self.view:
            out.append(ChangeView(view, "high"))
            self.view = view
        moment = goal - self.neck_rad
        if abs(moment) >= NECK_STEP_RAD:
            out.append(TurnNeck(moment))
        return tuple(out)


def head_relative(percept: Percept, neck_rad: float) -> Percept:
    """A body-relative `percept` with its directions measured from the head again.

    The head points `neck_rad` from the body (:attr:`NeckLook.neck_rad`): a direction from the
    head is the one from the body less the neck. The result carries that neck angle, so its
    :meth:`~field_models.protocol.Percept.body_relative` gives `percept` back.
    """
    if neck_rad == 0.0:
        return percept
    # Measuring from the body adds the neck; adding its negative measures from the head.
    turned = dataclasses.replace(percept, neck_rad=-neck_rad).body_relative()
    return dataclasses.replace(turned, neck_rad=neck_rad)


def look_target(
    percept: Percept,
    pose: Pose | None,
    ball_xy: tuple[float, float] | None,
    seen_tick: int,
) -> float | None:
    """Where the ball is from the body [rad]: seen now, or remembered; None: look for it.

    `percept` is body-relative; `seen_tick` the last tick the ball was seen.
    """
    if percept.ball is not None:
        return percept.ball.angle_rad
    if pose is None or ball_xy is None or percept.tick - seen_tick > LOOK_MEMORY_TICKS:
        return None
    return wrap_angle(math.atan2(ball_xy[1] - pose.y, ball_xy[0] - pose.x) - pose.heading)
