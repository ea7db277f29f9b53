"""The robot world's read-outs: exact states of the ball and the robots, and the truth.

:class:`WorldTruth` is the part of :class:`~field_models.robot_physics.world.RobotWorld` that
observers read (the coach, the camera, the arena's truth): positions, headings and velocities
straight from Chipmunk, in SI units, headings wrapped to [-π, π) except in the camera's fast
poses. Nothing here changes the world.
"""

from __future__ import annotations

import math

import pymunk
from pymunk._chipmunk import lib as _cp

from field_models.protocol import TWO_PI, BodyState, PlayerRef, Truth

# Chipmunk's getters through pymunk's cffi layer, as the world's step calls them (the reason
# is in field_models.robot_physics.world): a camera reads every robot every frame.
_get_angle = _cp.cpBodyGetAngle
_get_position = _cp.cpBodyGetPosition
_get_velocity = _cp.cpBodyGetVelocity
_new_tuple = tuple.__new__  # what a NamedTuple's __new__ calls, without its Python frame


class WorldTruth:
    """Read-outs of a robot world's state (a mixin of :class:`~.world.RobotWorld`).

    The world owns the state named below; see it for what each attribute holds.
    """

    refs: tuple[PlayerRef, ...]
    tick: int
    dt_s: float
    ball: pymunk.Body
    _ball_ptr: object
    _body_ptrs: list[object]  # each robot's Chipmunk body, in the robots' order

    def ball_xy(self) -> tuple[float, float]:
        """The ball's position [m] (fast path for coaches that check it every tick)."""
        p = _get_position(self._ball_ptr)
        return p.x, p.y

    def ball_state(self) -> BodyState:
        """The ball's exact state."""
        p, v = _get_position(self._ball_ptr), _get_velocity(self._ball_ptr)
        return _new_tuple(BodyState, (p.x, p.y, 0.0, v.x, v.y))

    def robot_state(self, index: int) -> BodyState:
        """Robot `index`'s exact state."""
        ptr = self._body_ptrs[index]
        p, v = _get_position(ptr), _get_velocity(ptr)
        heading = _get_angle(ptr)
        if not -math.pi <= heading < math.pi:  # wrap_angle, inlined (field_models.protocol)
            heading = (heading + math.pi) % TWO_PI - math.pi
        return _new_tuple(BodyState, (p.x, p.y, heading, v.x, v.y))

    def robot_pose(self, index: int) -> tuple[float, float, float]:
        """Robot `index`'s (x, y, heading) [m, m, rad] (fast path for the camera)."""
        ptr = self._body_ptrs[index]
        p = _get_position(ptr)
        return p.x, p.y, _get_angle(ptr)

    def robot_poses(self) -> list[tuple[float, float, float]]:
        """Every robot's (x, y, heading) [m, m, rad], in the robots' order (the camera's read)."""
        out = []
        for ptr in self._body_ptrs:
            p = _get_position(ptr)
            out.append((p.x, p.y, _get_angle(ptr)))
        return out

    def truth(self) -> Truth:
        """Exact state of the ball and every robot."""
        players = {ref: self.robot_state(i) for i, ref in enumerate(self.refs)}
        return Truth(self.tick, self.tick * self.dt_s, self.ball_state(), players)
