"""The interception drill's judge: the coach's labelling rule (paper §5), on plain floats.

**Labels** (the coach judges the truth after every tick; ``labels = ("SAVE", "GOAL", "MISS")``).
Let û be the unit vector from the ball's start to the defender's start, v the ball's velocity
and ε = 1e-3 · pitch length per second. Once the ball has been moving toward the defender
(v·û > ε):

* **SAVE** — the ball moves clearly back: v·û < -max(ε, ½|v|), i.e. more than 30° behind the
  sideways direction;
* a ball whose v·û drops below -ε without going clearly back was *deflected*: it may still roll
  on toward the goal line. After a deflection the trial is a GOAL if the ball then goes in and a
  SAVE in every other case (wide, to a side, or stopped: slower than ε);
* the ball gets past the defender (its progress along û exceeds the defender's start distance
  plus player radius plus ball radius): **GOAL** if its straight-line path crosses the goal
  mouth, else **MISS** ("heading wide"; SAVE after a deflection);
* the ball goes over an end line (:func:`field_models.protocol.end_line_crossing`, the one
  goal-line rule) or the field's referee counts a goal: **GOAL** into the defended goal, else
  **MISS**;
* the ball reaches a side line, or the end line wide of the posts (a wall on the robot table,
  whose bounce must not count as a save): **MISS**;
* time out (``max_time_s`` simulated, default 10 s): **MISS**, "ball stopped short".

:class:`InterceptJudge` applies it to one trial; the batched drill
(:mod:`robotsoccer.drills.intercept_batch`) applies the same rule, in the same order, to many.
"""

from __future__ import annotations

import math

from field_models.arena import Arena
from field_models.protocol import Crossing
from robotsoccer.drills.base import GoalWatch, Verdict
from robotsoccer.drills.intercept_plan import DEFENDER, LaunchPlan

SAVE_SPEED_PER_LENGTH = 1e-3
"""ε of the SAVE rule: this fraction of the pitch length per second."""
BACKWARD_SHARE = 0.5
"""A SAVE needs the ball to move back along û by at least this share of its speed (30° behind
sideways); a smaller backward component is a deflection (module docstring)."""

# The coach's reasons (module docstring), shared with the batched drill.
INTO_GOAL = "ball into the goal between the posts"
OVER_OWN_LINE = "ball over the shooter's goal line"
OVER_LINE_WIDE = "ball crossed the goal line wide of the posts"
AT_SIDE_LINE = "ball reached a side line"
AT_END_LINE_WIDE = "ball reached the end line wide of the posts"
DEFLECTED_STOPPED = "deflected by the defender, stopped short of the goal"
MOVING_BACK = "ball moving back toward the shooter"
PAST_INTO_GOAL = "ball past the defender, heading between the posts"
PAST_WIDE = "ball past the defender, heading wide"
STOPPED_SHORT = "ball stopped short"


def deflected_then(reason: str) -> str:
    """The reason of a SAVE whose deflected ball then did something that is not a goal."""
    return f"deflected by the defender; then {reason}"


class InterceptJudge:
    """The coach's labelling rule for one trial (module docstring), on plain floats."""

    def __init__(
        self,
        arena: Arena,
        plan: LaunchPlan,
        ball: tuple[float, float],
        defender: tuple[float, float],
        *,
        touches: bool = False,
    ) -> None:
        pitch = arena.facts.pitch
        # Shots across the goal mouth are all on target: one the defender touched and that did
        # not go in is a save even when it still rolls forward (pushed wide of the post).
        self.touch_m = arena.facts.touch_distance_m + 0.05 * arena.facts.unit_m if touches else 0.0
        self.dt_s = arena.facts.dt_s
        self.plan = plan
        self.half_length = pitch.half_length_m
        self.half_width = pitch.half_width_m
        self.post = 0.5 * pitch.goal_width_m
        self.radius = pitch.ball_radius_m
        self.margin = 0.01 * pitch.half_length_m  # a ball this close to a wall touches it
        self.eps = SAVE_SPEED_PER_LENGTH * pitch.length_m
        self.goals = GoalWatch(arena, ball)
        self.x0, self.y0 = ball
        dx, dy = defender[0] - ball[0], defender[1] - ball[1]
        distance = math.hypot(dx, dy)
        self.ux, self.uy = dx / distance, dy / distance
        self.past = distance + pitch.player_radius_m + pitch.ball_radius_m
        self.approaching = False
        self.deflected = False
        self.trigger: tuple[float, float, float] | None = None
        self.end: tuple[float, float, float] | None = None

    def note_trigger(self, arena: Arena) -> None:
        """The defender just chose its TA: note where and when (for the drill's measures)."""
        d = arena.player_state(DEFENDER)
        self.trigger = (arena.tick * self.dt_s, d.x, d.y)

    def finish(self, arena: Arena) -> None:
        """The trial ends now: note where the defender got to."""
        if self.end is None:
            d = arena.player_state(DEFENDER)
            self.end = (arena.tick * self.dt_s, d.x, d.y)

    def judge(self, arena: Arena) -> Verdict | None:
        """The verdict of this tick, or None; notes the defender's end on a verdict."""
        verdict = self._verdict(arena)
        if verdict is not None:
            self.finish(arena)
        return verdict

    def _verdict(self, arena: Arena) -> Verdict | None:  # every tick: keep it lean
        x, y, _, vx, vy = arena.ball_state()
        if self.touch_m and not self.deflected:
            d = arena.player_state(DEFENDER)
            if (d.x - x) ** 2 + (d.y - y) ** 2 <= self.touch_m * self.touch_m:
                self.deflected = True
        crossing = self.goals.step(arena, x, y)
        if crossing:
            if crossing is Crossing.RIGHT_GOAL:
                return Verdict("GOAL", INTO_GOAL)
            if crossing is Crossing.LEFT_GOAL:
                return self._not_in(OVER_OWN_LINE)
            return self._not_in(OVER_LINE_WIDE)
        edge = self.radius + self.margin
        if abs(y) >= self.half_width - edge:
            return self._not_in(AT_SIDE_LINE)
        if x >= self.half_length - edge and abs(y) >= self.post:
            return self._not_in(AT_END_LINE_WIDE)
        if self.deflected and vx * vx + vy * vy < self.eps * self.eps:
            return Verdict("SAVE", DEFLECTED_STOPPED)
        along = vx * self.ux + vy * self.uy
        if along > self.eps:
            self.approaching = True
        elif self.approaching and along < -self.eps:
            if along < -BACKWARD_SHARE * math.hypot(vx, vy):
                return Verdict("SAVE", MOVING_BACK)
            self.deflected = True
        if (x - self.x0) * self.ux + (y - self.y0) * self.uy > self.past:
            return self._past(x, y, vx, vy)
        return None

    def _not_in(self, reason: str) -> Verdict:
        """A ball that did not go in: a SAVE once the defender deflected it, else a MISS."""
        if self.deflected:
            return Verdict("SAVE", deflected_then(reason))
        return Verdict("MISS", reason)

    def _past(self, x: float, y: float, vx: float, vy: float) -> Verdict:
        """The ball got past the defender: GOAL if its path crosses the goal mouth."""
        if vx > 0.0:
            cross = y + (self.half_length - x) * vy / vx
            if abs(cross) < self.post:
                return Verdict("GOAL", PAST_INTO_GOAL)
        return self._not_in(PAST_WIDE)
