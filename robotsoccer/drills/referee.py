"""Referees of a match: the Soccer Server's play modes on an open field, the table's own rules.

A referee is part of the coach (DESIGN.md §2): it reads the truth and restarts play by moving
the ball and players, as the Soccer Server's referee and a trainer do. The rules follow the
field's facts, never its name: a field whose ball can leave it (:attr:`FieldFacts.walled`
False) gets the Soccer Server's rules, a walled table the robots' rules.

**Both fields.** The match has two halves of ``half_ticks`` each; the left team kicks off the
first, the right team the second (teams keep their ends, as in rcssserver). A goal (the
project's one goal-line rule, :class:`~robotsoccer.drills.base.GoalWatch`; on the Soccer
Server the model's own referee counts it) gives a kick-off to the team that conceded. For a
kick-off every player is put on its kick-off spot (the ``move`` a client makes before a
kick-off, made by the coach), the ball on the centre spot, and until the kick the other team
is kept out of the centre circle. A restart is taken when the ball moves; then ``play_on``.

**Soccer Server rules** (rcssserver's referee, `specs/soccer_server.md` §6), on an open field:

* ``kick_in_<side>``: the ball wholly over a side line; the team that did not touch it last
  restarts from where it crossed;
* ``goal_kick_<side>`` / ``corner_kick_<side>``: the ball wholly over an end line outside the
  goal; the defenders restart from the corner of their goal area if an attacker touched it
  last, the attackers from the corner arc otherwise;
* in these restarts the other team is kept :data:`RESTART_DISTANCE_UNITS` from the ball
  (rcssserver clears them from the ball area every cycle);
* ``drop_ball``: a restart not taken in :data:`DROP_BALL_CYCLES` server cycles (rcssserver's
  ``drop_ball_time``; the table's referee waits as long); then anyone may play it.

**Table rules** (the walled robot table: the ball never leaves it):

* ``kick_off_<side>`` after a goal, as above;
* ``drop_ball``: the ball moved less than :data:`STUCK_UNITS` in :data:`STUCK_S` seconds
  (stuck against a wall, in a corner or between robots): it is put on the nearest of the four
  free-ball spots (a quarter of the length and width in from the centre, as small-size robot
  soccer does), and robots within :data:`SPOT_CLEAR_UNITS` of the spot are moved back from it;
* the time limit ends the half (``half_time``) and the match (``time_over``).

Distances in units are Soccer Server metres, ``unit_m`` on another field.
"""

from __future__ import annotations

import math
from collections.abc import Mapping

from field_models.arena import Arena, ArenaEvent
from field_models.protocol import LEFT, RIGHT, Crossing, PlayerRef
from robotsoccer.drills.base import GoalWatch

CENTRE_CIRCLE_UNITS = 9.15
"""The centre circle's radius [units]."""
RESTART_DISTANCE_UNITS = 9.15
"""The other team keeps this far from a free kick, kick-in, corner or goal kick [units]."""
DROP_BALL_CYCLES = 200
"""rcssserver's ``drop_ball_time`` [cycles of 100 ms]; the table uses the same time."""
SERVER_CYCLE_S = 0.1
GOAL_AREA_LENGTH_UNITS = 5.5
GOAL_AREA_HALF_WIDTH_UNITS = 9.16
"""The goal area's depth and half width: a goal kick starts from its corner [units]."""
CORNER_INSET_UNITS = 1.0
"""A corner kick starts this far in from the corner flag along both lines [units]."""
STUCK_S = 5.0
STUCK_UNITS = 1.0
"""On the table a ball that moved less than this in this long is stuck."""
SPOT_CLEAR_UNITS = 6.0
"""Robots this close to a free-ball spot are moved back from it [units]."""
MOVED_SPEED_UNITS = 0.05
"""A restart is taken once the ball moves faster than this [units per second]."""

TOUCH_PERIOD_S = 0.02
"""How often the referee looks for who touches the ball [s] (every tick on a coarser field)."""

PLAY_ON = "play_on"
SIDE = {LEFT: "l", RIGHT: "r"}
OTHER = {LEFT: RIGHT, RIGHT: LEFT}


class Referee:
    """The match's referee (module docstring).

    Args:
        arena: The match's arena.
        kickoff_spots: Each team's kick-off spots, by kicking team: ``spots[kicker][player]``
            is (x, y, heading) [m, rad].
        half_ticks: Ticks in one half.
        control_m: A player this close to the ball touches it [m].

    Attributes:
        play_mode: The current play mode, as the Soccer Server spells it.
        score: Goals of the left and right team.
        last_touch: The player that touched the ball last, or None.
        events: Referee calls not yet taken (:meth:`drain`).
    """

    def __init__(
        self,
        arena: Arena,
        kickoff_spots: Mapping[str, Mapping[PlayerRef, tuple[float, float, float]]],
        half_ticks: int,
        control_m: float,
    ) -> None:
        facts = arena.facts
        self.pitch = facts.pitch
        self.unit = facts.unit_m
        self.walled = facts.walled
        self.kickoff_spots = kickoff_spots
        self.half_ticks = half_ticks
        self.control2 = control_m * control_m
        self.players = arena.players
        self.play_mode = "before_kick_off"
        self.score = [0, 0]
        self.last_touch: PlayerRef | None = None
        self.events: list[ArenaEvent] = []
        self._restart_team: str | None = None  # who takes the current restart
        self._restart_tick = 0
        self._restart_xy = (0.0, 0.0)
        self._goals = GoalWatch(arena, (0.0, 0.0))
        self._stuck_ticks = max(1, round(STUCK_S / facts.dt_s))
        self._stuck_anchor = (0.0, 0.0, 0)
        self._moved2 = (MOVED_SPEED_UNITS * self.unit) ** 2
        self._drop_ticks = max(1, round(DROP_BALL_CYCLES * SERVER_CYCLE_S / facts.dt_s))
        # Reading every player's state is the referee's main cost on a fine tick (the robots'
        # 1/240 s): touches are looked for every TOUCH_PERIOD_S, no touch is that short.
        self._touch_every = max(1, math.floor(TOUCH_PERIOD_S / facts.dt_s))

    # ------------------------------------------------------------------ calls

    def start(self, arena: Arena) -> None:
        """The first half's kick-off (the left team's)."""
        self._kick_off(arena, LEFT)

    def drain(self) -> list[ArenaEvent]:
        """Referee calls since the last call, oldest first."""
        events, self.events = self.events, []
        return events

    def _call(self, tick: int, mode: str, text: str | None = None) -> None:
        self.play_mode = mode
        self.events.append(ArenaEvent(tick, "referee", text or mode))

    def _kick_off(self, arena: Arena, team: str) -> None:
        for ref, (x, y, heading) in self.kickoff_spots[team].items():
            arena.place_player(ref, x, y, heading)
        arena.place_ball(0.0, 0.0)
        self._goals = GoalWatch(arena, (0.0, 0.0))
        self._restart(arena, team, f"kick_off_{SIDE[team]}", 0.0, 0.0)

    def _restart(self, arena: Arena, team: str, mode: str, x: float, y: float) -> None:
        self._restart_team = team
        self._restart_tick = arena.tick
        self._restart_xy = (x, y)
        self._stuck_anchor = (x, y, arena.tick)
        self._call(arena.tick, mode)

    # ------------------------------------------------------------------ each tick

    def step(self, arena: Arena) -> None:
        """Judge the tick just stepped: goals, halves, outs, stuck balls, restarts taken."""
        tick = arena.tick
        x, y, _, vx, vy = arena.ball_state()
        crossing = self._goals.step(arena, x, y)
        if tick % self._touch_every == 0:
            self._touch(arena, x, y)
        if crossing.is_goal:
            scorer = LEFT if crossing is Crossing.RIGHT_GOAL else RIGHT
            self.score[0 if scorer == LEFT else 1] += 1
            self._call(tick, f"goal_{SIDE[scorer]}", f"goal_{SIDE[scorer]}_{self.score_text()}")
            self._kick_off(arena, OTHER[scorer])
            return
        if tick == self.half_ticks:
            self._call(tick, "half_time")
            self._kick_off(arena, RIGHT)
            return
        if self._restart_team is not None:
            self._during_restart(arena, x, y, vx, vy)
            return
        if not self.walled:
            self._outs(arena, x, y, crossing)
        else:
            self._stuck(arena, x, y)

    def score_text(self) -> str:
        """The score as ``L-R``."""
        return f"{self.score[0]}-{self.score[1]}"

    def _touch(self, arena: Arena, x: float, y: float) -> None:
        best, best_d2 = None, self.control2
        for ref in self.players:
            p = arena.player_state(ref)
            d2 = (p.x - x) ** 2 + (p.y - y) ** 2
            if d2 <= best_d2:
                best, best_d2 = ref, d2
        if best is not None:
            self.last_touch = best

    def _during_restart(self, arena: Arena, x: float, y: float, vx: float, vy: float) -> None:
        team = self._restart_team
        assert team is not None
        tick = arena.tick
        if vx * vx + vy * vy > self._moved2:
            self._restart_team = None
            self._stuck_anchor = (x, y, tick)
            self._call(tick, PLAY_ON)
            return
        if tick - self._restart_tick >= self._drop_ticks:
            self._restart_team = None
            self._call(tick, "drop_ball")
            self._call(tick, PLAY_ON)
            return
        is_kick_off = self.play_mode.startswith("kick_off")
        radius = (CENTRE_CIRCLE_UNITS if is_kick_off else RESTART_DISTANCE_UNITS) * self.unit
        self._keep_out(arena, OTHER[team], radius + self.pitch.player_radius_m)

    def _keep_out(self, arena: Arena, team: str, radius: float) -> None:
        """Move `team`'s players in the circle of `radius` about the ball onto its edge."""
        bx, by = self._restart_xy
        for ref in self.players:
            if ref.team != team:
                continue
            p = arena.player_state(ref)
            dx, dy = p.x - bx, p.y - by
            d = math.hypot(dx, dy)
            if d >= radius:
                continue
            if d < 1e-9:
                dx, dy, d = (-1.0 if team == LEFT else 1.0), 0.0, 1.0
            nx, ny = self._inside(bx + dx / d * radius, by + dy / d * radius)
            arena.place_player(ref, nx, ny, p.heading)

    def _inside(self, x: float, y: float) -> tuple[float, float]:
        pitch = self.pitch
        lx = pitch.half_length_m - pitch.player_radius_m
        ly = pitch.half_width_m - pitch.player_radius_m
        return max(-lx, min(x, lx)), max(-ly, min(y, ly))

    # ------------------------------------------------------------------ open field

    def _outs(self, arena: Arena, x: float, y: float, crossing: Crossing) -> None:
        pitch, unit = self.pitch, self.unit
        half_l, half_w = pitch.half_length_m, pitch.half_width_m
        last = self.last_touch
        if abs(y) > half_w + pitch.ball_radius_m:
            team = OTHER[last.team] if last is not None else LEFT
            bx = max(-half_l, min(x, half_l))
            self._place_restart(arena, team, f"kick_in_{SIDE[team]}", bx, math.copysign(half_w, y))
            return
        if crossing is Crossing.NONE:
            return
        right_end = crossing is Crossing.RIGHT_WIDE
        defenders = RIGHT if right_end else LEFT
        sx = 1.0 if right_end else -1.0
        sy = 1.0 if y >= 0.0 else -1.0
        if last is not None and last.team == defenders:
            team = OTHER[defenders]
            bx = sx * (half_l - CORNER_INSET_UNITS * unit)
            by = sy * (half_w - CORNER_INSET_UNITS * unit)
            self._place_restart(arena, team, f"corner_kick_{SIDE[team]}", bx, by)
        else:
            bx = sx * (half_l - GOAL_AREA_LENGTH_UNITS * unit)
            by = sy * GOAL_AREA_HALF_WIDTH_UNITS * unit
            self._place_restart(arena, defenders, f"goal_kick_{SIDE[defenders]}", bx, by)

    def _place_restart(self, arena: Arena, team: str, mode: str, x: float, y: float) -> None:
        arena.place_ball(x, y)
        self._restart(arena, team, mode, x, y)

    # ------------------------------------------------------------------ walled table

    def _stuck(self, arena: Arena, x: float, y: float) -> None:
        ax, ay, since = self._stuck_anchor
        if (x - ax) ** 2 + (y - ay) ** 2 > (STUCK_UNITS * self.unit) ** 2:
            self._stuck_anchor = (x, y, arena.tick)
            return
        if arena.tick - since < self._stuck_ticks:
            return
        pitch = self.pitch
        sx = math.copysign(0.25 * pitch.length_m, x)
        sy = math.copysign(0.25 * pitch.width_m, y)
        clear = SPOT_CLEAR_UNITS * self.unit + pitch.player_radius_m
        self._restart_xy = (sx, sy)
        for team in (LEFT, RIGHT):
            self._keep_out(arena, team, clear)
        arena.place_ball(sx, sy)
        self._stuck_anchor = (sx, sy, arena.tick)
        self._call(arena.tick, "drop_ball")
        self._call(arena.tick, PLAY_ON)
