"""Dead reckoning of a Soccer Server player's own body from the commands it sent.

A client that acts every cycle (issue 28; :mod:`robotsoccer.skills.cycle`,
:mod:`robotsoccer.skills.team_cycle`) keeps its own heading and velocity between sees by
running the server's equations on the body commands the server carried out (shared
`specs/soccer_server.md` §1-2): a dash adds ``player_accel · dt²`` (× power / 100, × the
directed-dash factor) along heading + direction, the speed is capped at the top speed, the
body moves by the new velocity, then the velocity decays by ``1 - accel / top`` per cycle; a
turn of ``m`` turns it by ``m / (1 + inertia · |v|)``. The constants come from the field's
facts, so the minds do not import the server.

A state is ``(heading [rad], x, y [m], vx, vy [m/cycle])`` in the player's own reckoned frame:
only differences within it mean anything (collisions and kicks are not reckoned).
"""

from __future__ import annotations

import math

from field_models.arena import FieldFacts
from field_models.protocol import Action, Dash, Turn, wrap_angle

BodyState = tuple[float, float, float, float, float]
"""(heading [rad], x [m], y [m], vx [m/cycle], vy [m/cycle]) in a reckoned frame."""

FULL_POWER = 100.0
"""The dash power whose push is ``player_accel · dt²``."""


class BodyReckoner:
    """One server cycle of a player's body under a command (module docstring).

    Args:
        facts: The field's facts (cycle, dash push, top speed, turn inertia, dash rates).

    Attributes:
        push_m: A full-power dash's push [m/cycle].
        top_m: The top speed [m/cycle].
        decay: The speed kept from one cycle to the next (``1 - push / top``).
        inertia: The turn's inertia per (m/cycle) of speed.
    """

    def __init__(self, facts: FieldFacts) -> None:
        dt = facts.dt_s
        self.facts = facts
        self.push_m = facts.player_accel_mps2 * dt * dt
        self.top_m = facts.player_top_speed_mps * dt
        self.decay = 1.0 - self.push_m / self.top_m if self.top_m > 0.0 else 0.0
        self.inertia = facts.turn_inertia_s_per_m / dt

    def cycle(self, state: BodyState, action: Action | None) -> BodyState:
        """`state` after one server cycle carrying out `action` (None: no body command).

        The server's order (spec §1-2): the command, then the move by the new velocity (capped
        at the top speed), then the decay; a turn is shortened by the stored speed.
        """
        h, x, y, vx, vy = state
        if isinstance(action, Turn):
            h = wrap_angle(h + action.angle_rad / (1.0 + self.inertia * math.hypot(vx, vy)))
        elif isinstance(action, Dash):
            push = self.push_m * action.power / FULL_POWER
            direction = action.direction_rad
            if direction != 0.0:  # a directed dash pushes less (spec §2.1)
                push *= self.facts.dash_factor(direction)
            angle = h + direction
            vx, vy = vx + push * math.cos(angle), vy + push * math.sin(angle)
            speed = math.hypot(vx, vy)
            if speed > self.top_m > 0.0:
                vx, vy = vx * self.top_m / speed, vy * self.top_m / speed
        return h, x + vx, y + vy, vx * self.decay, vy * self.decay

    def run_on(
        self,
        start: BodyState,
        body: tuple[Action, ...],
        dash: Dash,
        distance_m: float,
        cycles: int,
        *,
        coast: bool,
    ) -> tuple[Action, ...]:
        """`body`, then `dash` every cycle while the run from `start` stays within `distance_m`.

        At most `cycles` commands in all; with `coast` the run counts what the body would still
        roll after the last dash (a point to stop at), without it only the distance run.
        """
        state = start
        for action in body:
            state = self.cycle(state, action)
        plan = list(body)
        while len(plan) < cycles:
            after = self.cycle(state, dash)
            run = math.hypot(after[1] - start[1], after[2] - start[2])
            if run + (self.coast_m(after) if coast else 0.0) > distance_m:
                break
            plan.append(dash)
            state = after
        return tuple(plan)

    def coast_m(self, state: BodyState) -> float:
        """How far the body still rolls with no more commands (the geometric series) [m]."""
        speed = math.hypot(state[3], state[4])
        return speed / (1.0 - self.decay) if self.decay < 1.0 else math.inf
