"""The coach's verdict on one set play: passes completed, shot, goal (paper §7, Figure 15).

:class:`SetPlayJudge` is the rule of :mod:`robotsoccer.drills.setplay`'s docstring ("The
coach"): at every tick the player nearest the ball, if within kick reach, holds it; the play's
passes are completed in order of its stages; the play ends in GOAL, SHOT, INTERCEPTED or OUT.
It carries out the coach's kicks first where the players have no aimable kick
(:class:`~robotsoccer.drills.setplay_kicks.CoachKicks`). Distances in metres.
"""

from __future__ import annotations

from field_models.arena import Arena
from field_models.protocol import RIGHT, Crossing, Mind, PlayerRef
from robotsoccer.drills.base import GoalWatch, Verdict
from robotsoccer.drills.passing import STOPPED_SPEED_PER_LENGTH
from robotsoccer.drills.setplay_kicks import CoachKicks, kick_reach
from robotsoccer.skills.setplay_receiver import SetPlayReceiverMind


class SetPlayJudge:
    """The coach's rule for one play (module docstring).

    Args:
        arena: The field, its players placed.
        ball: Where the ball starts (x, y) [m].
        kicks: The coach's kicks where the players have no aimable kick; else None.
        starter: Who holds the ball at the start.
        players: Everyone on the field, in the order ties for the ball are broken (the first
            nearest holds it).
        stages: Who completes each pass of the play, in order; the last stage's players are
            the shooters.
    """

    def __init__(
        self,
        arena: Arena,
        ball: tuple[float, float],
        kicks: CoachKicks | None,
        *,
        starter: PlayerRef,
        players: tuple[PlayerRef, ...],
        stages: tuple[tuple[PlayerRef, ...], ...],
    ) -> None:
        facts = arena.facts
        pitch = facts.pitch
        self.reach = kick_reach(facts)
        self.reach2 = self.reach * self.reach
        self.half_length = pitch.half_length_m
        self.half_width = pitch.half_width_m
        self.eps2 = (STOPPED_SPEED_PER_LENGTH * pitch.length_m) ** 2
        self.goals = GoalWatch(arena, ball)
        self.kicks = kicks
        self.minds: dict[PlayerRef, Mind] = {}
        self.players = players
        self.stages = stages
        self.holder: PlayerRef | None = starter
        self.passes = 0
        self.first_receiver = 0
        self.shot_tick: int | None = None
        self.goal = False

    def _shot(self) -> int | None:
        for ref in self.stages[-1]:
            mind = self.minds.get(ref)
            if isinstance(mind, SetPlayReceiverMind) and mind.kicked_tick is not None:
                return mind.kicked_tick
        return None

    def judge(self, arena: Arena) -> Verdict | None:
        """The verdict of this tick, or None."""
        if self.kicks is not None and self.kicks.pending:
            self.kicks.apply(arena, self.reach)
        x, y, _, vx, vy = arena.ball_state()
        crossing = self.goals.step(arena, x, y)
        if self.shot_tick is None:
            self.shot_tick = self._shot()
        if crossing is Crossing.RIGHT_GOAL:
            self.goal = True
            return Verdict("GOAL", f"goal after {self.passes} passes")
        taken = self._holder(arena, x, y)
        if taken is not None and taken != self.holder:
            if taken.team == RIGHT:
                label = "SHOT" if self.shot_tick is not None else "INTERCEPTED"
                return Verdict(label, f"{taken} took the ball after {self.passes} passes")
            if self.passes < len(self.stages) and taken in self.stages[self.passes]:
                self.passes += 1  # the play's next pass (module docstring)
                if self.passes == 1:
                    self.first_receiver = taken.number
            self.holder = taken
        if abs(x) > self.half_length or abs(y) > self.half_width or crossing is not Crossing.NONE:
            label = "SHOT" if self.shot_tick is not None else "OUT"
            return Verdict(label, f"the ball left the field after {self.passes} passes")
        if self.shot_tick is not None and vx * vx + vy * vy < self.eps2:
            return Verdict("SHOT", "the shot stopped short")
        return None

    def _holder(self, arena: Arena, x: float, y: float) -> PlayerRef | None:
        """The player nearest the ball among those within kick reach, or None."""
        best, best_d2 = None, self.reach2
        for ref in self.players:
            p = arena.player_state(ref)
            d2 = (p.x - x) ** 2 + (p.y - y) ** 2
            if d2 <= best_d2:
                best, best_d2 = ref, d2
        return best
