"""Go to the ball and face a target point: ``robotsoccer/GoToBall-v0`` on either field model.

A task of the per-step control environments (:class:`~robotsoccer.envs.control.ControlEnv`:
steps, options, seeds and bad input are described there): one player alone with a still ball
must reach it and face a target point (:class:`GoToBallEnv`).
"""

from __future__ import annotations

import math
from typing import Any, ClassVar

from field_models.arena import Arena, FieldFacts
from field_models.protocol import LEFT, Mind, PlayerRef, wrap_angle
from field_models.seeding import TrialRngs
from robotsoccer.drills.layered import control_reach
from robotsoccer.envs.control import ControlEnv

GO_PLAYER = PlayerRef(LEFT, 1)
MARGIN_UNITS = 5.0
"""Ball, player and target are placed at least this far inside the lines [units]."""
DISTANCE_UNITS = (8.0, 30.0)
"""The player starts this far from the ball [units] (uniform)."""
TARGET_MIN_UNITS = 10.0
"""The target point lies at least this far from the ball [units]."""
REACH_UNITS = 1.5
"""At the ball: within the field's control reach, or touching plus this much [units]."""
FACE_TOLERANCE_RAD = math.radians(20.0)
"""Facing the target: its direction within this of the heading."""
GO_TIME_PERIODS = 200
"""The default time limit, in sensor periods (6.7 s on the robots, 50 s on the server)."""


class GoToBallEnv(ControlEnv):
    """Go to the ball and face a target point (``robotsoccer/GoToBall-v0``).

    **Placement** (the episode's "placement" stream): the ball uniformly inside the lines
    less :data:`MARGIN_UNITS`; the player :data:`DISTANCE_UNITS` from it in a uniform
    direction, facing a uniform heading; the target point uniformly inside, at least
    :data:`TARGET_MIN_UNITS` from the ball. The ball lies still.

    **Success** (the coach, on the truth, every tick): the ball within reach
    (:data:`REACH_UNITS`) and the target within :data:`FACE_TOLERANCE_RAD` of the heading.
    The episode then terminates with ``info["is_success"]`` True.

    **Rewards** (weights: ``reward_weights``): ``success`` 1 at the success; ``approach``
    the fall of the player-ball distance over L (weight 1); ``facing`` the gain of
    cos(heading error to the target) × exp(-distance / (2·reach)), i.e. of facing the target
    near the ball (weight 0.2); ``time`` a cost per step (weight 0.001). The shaped terms are
    differences of potentials, so they do not change which policy is best.
    """

    default_weights: ClassVar[dict[str, float]] = {
        "success": 1.0,
        "approach": 1.0,
        "facing": 0.2,
        "time": 0.001,
    }
    sparse_term: ClassVar[str] = "success"
    learner = GO_PLAYER

    def _default_max_time_s(self, facts: FieldFacts) -> float:
        return GO_TIME_PERIODS * facts.sensor_period_s

    def _task_players(self, facts: FieldFacts) -> tuple[PlayerRef, ...]:
        unit = facts.unit_m
        self.reach_m = max(control_reach(facts), facts.touch_distance_m + REACH_UNITS * unit)
        self.target_xy = (0.0, 0.0)
        return (GO_PLAYER,)

    def _task_setup(self, arena: Arena, rngs: TrialRngs) -> dict[PlayerRef, Mind]:
        facts = arena.facts
        unit, pitch = facts.unit_m, facts.pitch
        hx = pitch.half_length_m - MARGIN_UNITS * unit
        hy = pitch.half_width_m - MARGIN_UNITS * unit
        rng = rngs["placement"]
        bx, by = rng.uniform(-hx, hx), rng.uniform(-hy, hy)
        px, py = bx, by
        for _ in range(100):  # redraw until the player starts inside (a fixed number of draws)
            d = rng.uniform(*DISTANCE_UNITS) * unit
            a = rng.uniform(-math.pi, math.pi)
            px, py = bx + d * math.cos(a), by + d * math.sin(a)
            if abs(px) <= hx and abs(py) <= hy:
                break
        px, py = max(-hx, min(px, hx)), max(-hy, min(py, hy))
        tx, ty = bx, by
        for _ in range(100):
            tx, ty = rng.uniform(-hx, hx), rng.uniform(-hy, hy)
            if math.hypot(tx - bx, ty - by) >= TARGET_MIN_UNITS * unit:
                break
        self.target_xy = (tx, ty)
        arena.place_ball(bx, by)
        arena.place_player(GO_PLAYER, px, py, rng.uniform(-math.pi, math.pi))
        return {}

    def _errors(self, arena: Arena) -> tuple[float, float]:
        """(player-ball distance [m], heading error to the target [rad]) on the truth."""
        p = arena.player_state(GO_PLAYER)
        b = arena.ball_state()
        tx, ty = self.target_xy
        error = wrap_angle(math.atan2(ty - p.y, tx - p.x) - p.heading)
        return math.hypot(b.x - p.x, b.y - p.y), error

    def _task_judge(self, arena: Arena) -> tuple[str, float] | None:
        distance, error = self._errors(arena)
        if distance <= self.reach_m and abs(error) <= FACE_TOLERANCE_RAD:
            return "SUCCESS", 1.0
        return None

    def _task_potentials(self, arena: Arena) -> dict[str, float]:
        distance, error = self._errors(arena)
        near = math.exp(-distance / (2.0 * self.reach_m))
        return {"approach": -distance / self.facts.pitch.length_m, "facing": math.cos(error) * near}

    def _task_target(self) -> tuple[float, float]:
        return self.target_xy

    def _task_info(self, label: str | None) -> dict[str, Any]:
        return {"is_success": label == "SUCCESS"}
