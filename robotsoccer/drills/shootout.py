"""The demo drill: a shooter pushes (or kicks) the ball at a goal defended by a ball-chasing goalie.

Setup (coach, "placement" stream): the ball at a random spot in the middle third of the field;
the shooter (left 1) behind it on the line from the right goal's centre through the ball, facing
the ball; the goalie (right 1) on its goal line's centre, facing the field. Sizes scale with the
pitch, so the drill runs on either field model.

Minds (percepts only, :mod:`robotsoccer.skills.shootout`): the shooter goes round to the far side
of the ball from the goal, then drives through it (``Kick`` when touching and lined up: a kicker
fires, a kickerless robot pushes); the goalie drives straight at the ball it perceives.

Labels (coach, truth):

* **GOAL** — the ball goes wholly over the right goal line between the posts (the one goal-line
  rule, :func:`field_models.protocol.end_line_crossing`);
* **SAVE** — the goalie has touched the ball and it is then rolling back toward the field
  (vx < 0) or has stopped;
* **MISS** — the ball reaches the right end line (or wall) wide of the posts, goes into the left
  goal or over the left end line, or the trial runs out of time (the shot never arrived).
"""

from __future__ import annotations

import math

from field_models.arena import Arena, FieldFacts
from field_models.protocol import LEFT, RIGHT, Crossing, Mind, PlayerRef, end_line_crossing
from field_models.seeding import TrialRngs
from robotsoccer.drills.base import Verdict
from robotsoccer.options import duration
from robotsoccer.skills.shootout import ChaseGoalieMind, DribbleShooterMind

SHOOTER = PlayerRef(LEFT, 1)
GOALIE = PlayerRef(RIGHT, 1)


class ShootoutDrill:
    """Shooter against a ball-chasing goalie; labels GOAL, SAVE or MISS."""

    name: str = "shootout"
    labels: tuple[str, ...] = ("SAVE", "GOAL", "MISS")

    def __init__(self, max_time_s: float = 12.0) -> None:
        self.max_time_s = duration("max_time_s", max_time_s)
        self._touched = False
        self._last_ball = (0.0, 0.0)

    def players(self) -> tuple[PlayerRef, ...]:
        """Shooter and goalie."""
        return (SHOOTER, GOALIE)

    def field_settings(self, facts: FieldFacts) -> dict[str, float]:
        """The demo runs on the presets as they are."""
        return {}

    def inputs(self) -> tuple[str, ...]:
        """The demo reads no files."""
        return ()

    def setup(self, arena: Arena, rngs: TrialRngs) -> None:
        """Place ball, shooter and goalie."""
        rng = rngs["placement"]
        pitch = arena.facts.pitch
        hl, hw = pitch.half_length_m, pitch.half_width_m
        bx = float(rng.uniform(-0.3, 0.3)) * hl
        by = float(rng.uniform(-0.5, 0.5)) * hw
        ux, uy = _unit(bx - hl, by)  # away from the right goal's centre
        back = float(rng.uniform(0.1, 0.25)) * hl
        sx, sy = bx + ux * back, by + uy * back
        arena.place_ball(bx, by)
        arena.place_player(SHOOTER, sx, sy, math.atan2(by - sy, bx - sx))
        arena.place_player(GOALIE, hl - 2.0 * pitch.player_radius_m, 0.0, math.pi)
        self._touched = False
        self._last_ball = (bx, by)

    def minds(self, arena: Arena, rngs: TrialRngs) -> dict[PlayerRef, Mind]:
        """Shooter and goalie minds, sized to the pitch."""
        pitch = arena.facts.pitch
        touch = self._touch_distance(arena)
        return {
            SHOOTER: DribbleShooterMind(
                back_off_m=4.0 * pitch.player_radius_m, touch_m=touch * 1.2
            ),
            GOALIE: ChaseGoalieMind(),
        }

    def _touch_distance(self, arena: Arena) -> float:
        pitch = arena.facts.pitch
        return pitch.player_radius_m * math.sqrt(2.0) + pitch.ball_radius_m + 0.005

    def judge(self, arena: Arena) -> Verdict | None:
        """GOAL, SAVE, MISS or carry on."""
        pitch = arena.facts.pitch
        ball = arena.ball_state()
        lx, ly = self._last_ball
        self._last_ball = (ball.x, ball.y)
        crossing = end_line_crossing(pitch, lx, ly, ball.x, ball.y)
        if crossing is Crossing.RIGHT_GOAL:
            return Verdict("GOAL", "ball wholly over the line between the posts")
        if crossing is Crossing.LEFT_GOAL:
            return Verdict("MISS", "ball in the shooter's own goal")
        if crossing is not Crossing.NONE:
            return Verdict("MISS", "ball over an end line wide of the posts")
        hl, r, post = pitch.half_length_m, pitch.ball_radius_m, 0.5 * pitch.goal_width_m
        if ball.x > hl - r - 0.01 * hl and abs(ball.y) >= post:
            return Verdict("MISS", "ball reached the end wall wide of the posts")
        if not self._touched:
            g = arena.player_state(GOALIE)
            self._touched = math.hypot(ball.x - g.x, ball.y - g.y) < self._touch_distance(arena)
        elif ball.vx < 0.0 or ball.speed < 1e-3:
            return Verdict("SAVE", "goalie touched the ball and it rolls back or stopped")
        return None

    def timeout(self, arena: Arena) -> Verdict:
        """Out of time: the shot never arrived."""
        return Verdict("MISS", f"no result within {self.max_time_s:g} s")

    def data(self) -> tuple[float, ...]:
        """The demo records nothing for learning."""
        return ()

    def measures(self) -> dict[str, float]:
        """The demo measures nothing beyond its label."""
        return {}


def _unit(x: float, y: float) -> tuple[float, float]:
    n = math.hypot(x, y) or 1.0
    return x / n, y / n
