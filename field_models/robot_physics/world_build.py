"""The bodies of the robot world: walls and goals, the ball, a robot and its control body.

What :class:`~field_models.robot_physics.world.RobotWorld` is made of, added to its pymunk
space in the order the world calls these functions (walls, ball, robots: the order fixes the
solver's, so it is part of a trial's numbers). The modelling choices are the world's module
docstring's (:mod:`~field_models.robot_physics.world`, shared `specs/robot_physics.md` §3):
static box walls outside the field lines with 45° corner panels (§3.5), the per-pair
restitution on the wall or robot and 1.0 on the ball (§3.1), the ball's rolling resistance as
a pivot joint to the static body (§3.4), and a robot's grip-capped pivot and gear joints to its
kinematic control body (§3.2 option A).
"""

from __future__ import annotations

import math

import pymunk
from pymunk._chipmunk import ffi as _ffi
from pymunk._chipmunk import lib as _cp

from field_models.robot_physics.config import (
    GRAVITY_MPS2,
    BallConfig,
    FieldConfig,
    RobotConfig,
)

_IDENTITY = tuple(pymunk.Transform.identity())  # what pymunk's Poly passes by default


def add_walls(space: pymunk.Space, field: FieldConfig, wall_restitution: float) -> list[object]:
    """Add the field's walls, goal boxes and corner panels to `space`, as static shapes.

    The shapes are Chipmunk's own, made by the call pymunk's ``Poly`` makes
    (``cpPolyShapeNew`` with the identity transform and no radius) and added in the same order,
    but without pymunk's Python wrappers: nothing reads a wall back, and the wrappers cost more
    than the rest of a short trial's set-up (issue 21). The caller keeps the returned handles
    for as long as the space lives; each one frees its shape, first taking it out of a space
    that still holds it (pymunk's own rule for its shapes, so either may go first).
    """
    f = field
    hl, hw, t = 0.5 * f.length_m, 0.5 * f.width_m, f.wall_thickness_m
    gw, gd = 0.5 * f.goal_width_m, f.goal_depth_m
    boxes = [
        (-hl - gd - t, hw, hl + gd + t, hw + t),  # top side wall (spans the goal boxes too)
        (-hl - gd - t, -hw - t, hl + gd + t, -hw),  # bottom side wall
    ]
    for sign in (-1.0, 1.0):
        line_out = sign * hl, sign * (hl + t)
        back = sign * (hl + gd), sign * (hl + gd + t)
        boxes += [
            (min(line_out), gw + t, max(line_out), hw),  # end wall above the goal
            (min(line_out), -hw, max(line_out), -gw - t),  # end wall below the goal
            (min(sign * hl, back[1]), gw, max(sign * hl, back[1]), gw + t),  # goal side (post)
            (min(sign * hl, back[1]), -gw - t, max(sign * hl, back[1]), -gw),
            (min(back), -gw - t, max(back), gw + t),  # goal back wall
        ]
    outlines = [[(x0, y0), (x1, y0), (x1, y1), (x0, y1)] for x0, y0, x1, y1 in boxes]
    outlines += _corner_panels(hl, hw, f.corner_fillet_m)
    static, space_ptr = space.static_body._body, space._space
    shapes = []
    for outline in outlines:
        shape = _ffi.gc(
            _cp.cpPolyShapeNew(static, len(outline), outline, _IDENTITY, 0.0), _free_shape
        )
        _cp.cpShapeSetElasticity(shape, wall_restitution)
        _cp.cpShapeSetFriction(shape, 0.2)
        _cp.cpSpaceAddShape(space_ptr, shape)
        shapes.append(shape)
    return shapes


def _free_shape(shape: object) -> None:
    """Free a wall shape, out of its space first if the space still holds it."""
    space = _cp.cpShapeGetSpace(shape)
    if space != _ffi.NULL:
        _cp.cpSpaceRemoveShape(space, shape)
    _cp.cpShapeFree(shape)


def _corner_panels(hl: float, hw: float, leg: float) -> list[list[tuple[float, float]]]:
    if leg <= 0:
        return []
    panels = []
    for sx in (-1.0, 1.0):
        for sy in (-1.0, 1.0):
            cx, cy = sx * hl, sy * hw
            # A triangle filling the corner, extended into the walls so it has no thin edge.
            panels.append([(cx, cy), (cx - sx * leg, cy), (cx, cy - sy * leg)])
    return panels


def add_ball(space: pymunk.Space, ball: BallConfig) -> pymunk.Body:
    """Add the ball (infinite moment, rolling resistance) to `space`, at rest at the centre."""
    b = ball
    body = pymunk.Body(b.mass_kg, math.inf)
    shape = pymunk.Circle(body, b.radius_m)
    shape.elasticity = 1.0  # the per-pair value sits on the other shape (§3.1)
    shape.friction = 0.2
    roll = pymunk.PivotJoint(space.static_body, body, (0, 0), (0, 0))
    roll.max_bias = 0.0  # velocity-only: a friction, not a spring
    roll.max_force = b.mass_kg * b.rolling_decel_mps2
    space.add(body, shape, roll)
    body.position = (0.0, 0.0)
    return body


def add_robot(space: pymunk.Space, robot: RobotConfig) -> tuple[pymunk.Body, pymunk.Body]:
    """Add one robot to `space`: its (dynamic body, kinematic control body), joined by grip."""
    r = robot
    body = pymunk.Body(r.mass_kg, pymunk.moment_for_box(r.mass_kg, (r.size_m, r.size_m)))
    shape = pymunk.Poly.create_box(body, (r.size_m, r.size_m))
    shape.elasticity = r.elasticity
    shape.friction = 0.3
    control = pymunk.Body(body_type=pymunk.Body.KINEMATIC)
    grip = r.tyre_mu * r.mass_kg * GRAVITY_MPS2
    drive = pymunk.PivotJoint(control, body, (0, 0), (0, 0))
    drive.max_bias = 0.0
    drive.max_force = grip
    # Yaw torque the two tyres can give: each carries m·g/2 at ±track/2 (§3.2 option A).
    spin = pymunk.GearJoint(control, body, 0.0, 1.0)
    spin.max_bias = 0.0
    spin.max_force = grip * 0.5 * r.track_m
    space.add(body, shape, control, drive, spin)
    return body, control
