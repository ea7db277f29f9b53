"""The demo drill: a shooter pushes (or kicks) the ball at a goal defended by a ball-chasing goalie.

Setup (coach, "placement" stream): the ball at a random spot in the middle third of the field;
the shooter (left 1) behind it on the line from the right goal's centre through the ball, facing
the ball; the goalie (right 1) on its goal line's centre, facing the field. Sizes scale with the
pitch, so the drill runs on either field model.

Minds (percepts only): the shooter goes round to the far side of the ball from the goal, then
drives through it (``Kick`` when touching and lined up: a kicker fires, a kickerless robot pushes);
the goalie drives straight at the ball it perceives (turn toward it when more than 0.2 rad off,
else dash at full power).

Labels (coach, truth):

* **GOAL** — the ball is wholly over the right goal line between the posts;
* **SAVE** — the goalie has touched the ball and it is then rolling back toward the field
  (vx < 0) or has stopped;
* **MISS** — the ball reaches the right end wall wide of the posts, goes into the left goal, or
  the trial runs out of time (the shot never arrived).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from field_models.arena import Arena
from field_models.protocol import (
    LEFT,
    RIGHT,
    Action,
    Dash,
    Kick,
    Mind,
    Percept,
    PlayerRef,
    Turn,
)
from field_models.seeding import TrialRngs
from robotsoccer.drills.base import Verdict

SHOOTER = PlayerRef(LEFT, 1)
GOALIE = PlayerRef(RIGHT, 1)


@dataclass
class ShooterMind:
    """Get behind the ball (as seen from the goal), then drive through it toward the goal."""

    back_off_m: float
    touch_m: float
    aim_tolerance_rad: float = 0.25
    search_turn_rad: float = math.radians(40.0)

    def act(self, percept: Percept) -> tuple[Action, ...]:
        """One decision per percept."""
        ball = percept.ball
        if ball is None:
            return (Turn(self.search_turn_rad),)
        bx, by = _xy(ball.distance_m, ball.angle_rad)
        goal = percept.landmark("g r")
        tx, ty = bx, by
        if goal is not None:
            gx, gy = _xy(goal.distance_m, goal.angle_rad)
            ux, uy = _unit(bx - gx, by - gy)  # from the goal through the ball
            lined_up = _cos_between(bx, by, -ux, -uy) > math.cos(math.radians(25.0))
            if lined_up and ball.distance_m < self.touch_m:
                return (Kick(100.0, math.atan2(gy - by, gx - bx)),)
            if not lined_up:
                tx, ty = bx + ux * self.back_off_m, by + uy * self.back_off_m
        angle = math.atan2(ty, tx)
        if abs(angle) > self.aim_tolerance_rad:
            return (Turn(angle),)
        return (Dash(100.0),)


@dataclass
class GoalieMind:
    """Drive straight at the perceived ball: turn toward it when off by more than a tolerance."""

    aim_tolerance_rad: float = 0.2

    def act(self, percept: Percept) -> tuple[Action, ...]:
        """One decision per percept."""
        if percept.ball is None:
            return ()
        if abs(percept.ball.angle_rad) > self.aim_tolerance_rad:
            return (Turn(percept.ball.angle_rad),)
        return (Dash(100.0),)


class ShootoutDrill:
    """Shooter against a ball-chasing goalie; labels GOAL, SAVE or MISS."""

    name: str = "shootout"
    labels: tuple[str, ...] = ("SAVE", "GOAL", "MISS")

    def __init__(self, max_time_s: float = 12.0) -> None:
        self.max_time_s = max_time_s
        self._touched = False

    def players(self) -> tuple[PlayerRef, ...]:
        """Shooter and goalie."""
        return (SHOOTER, GOALIE)

    def arena_settings(self, field_model: str, preset: str) -> dict[str, float]:
        """The demo runs on the presets as they are."""
        return {}

    def setup(self, arena: Arena, rngs: TrialRngs) -> None:
        """Place ball, shooter and goalie."""
        rng = rngs["placement"]
        pitch = arena.pitch
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

    def minds(self, arena: Arena, rngs: TrialRngs) -> dict[PlayerRef, Mind]:
        """Shooter and goalie minds, sized to the pitch."""
        pitch = arena.pitch
        touch = self._touch_distance(arena)
        return {
            SHOOTER: ShooterMind(back_off_m=4.0 * pitch.player_radius_m, touch_m=touch * 1.2),
            GOALIE: GoalieMind(),
        }

    def _touch_distance(self, arena: Arena) -> float:
        pitch = arena.pitch
        return pitch.player_radius_m * math.sqrt(2.0) + pitch.ball_radius_m + 0.005

    def judge(self, arena: Arena) -> Verdict | None:
        """GOAL, SAVE, MISS or carry on."""
        pitch = arena.pitch
        ball = arena.ball_state()
        hl, r, post = pitch.half_length_m, pitch.ball_radius_m, 0.5 * pitch.goal_width_m
        if ball.x > hl + r and abs(ball.y) < post:
            return Verdict("GOAL", "ball wholly over the line between the posts")
        if ball.x < -hl - r and abs(ball.y) < post:
            return Verdict("MISS", "ball in the shooter's own goal")
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
        """The demo records nothing."""
        return ()


def _xy(distance: float, angle: float) -> tuple[float, float]:
    return distance * math.cos(angle), distance * math.sin(angle)


def _unit(x: float, y: float) -> tuple[float, float]:
    n = math.hypot(x, y) or 1.0
    return x / n, y / n


def _cos_between(ax: float, ay: float, bx: float, by: float) -> float:
    na, nb = math.hypot(ax, ay), math.hypot(bx, by)
    if na == 0.0 or nb == 0.0:
        return 1.0
    return (ax * bx + ay * by) / (na * nb)
