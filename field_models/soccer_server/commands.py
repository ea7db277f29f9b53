"""The one-trial model's player commands: their queueing on arrival and their effect (§2).

:class:`PlayerCommands` is the part of
:class:`~field_models.soccer_server.dynamics.SoccerServerModel` that speaks for the players:
a command is clamped as the server clamps it and queued (one body command a cycle, a
``turn_neck`` and a say beside it; §1.1, §2), and at the step the queued dash, turn and kick
act against the state at the start of the cycle and the turn_necks commit. The formulas they
share with the batch are in :mod:`~field_models.soccer_server.cycle_rules`; the frame and sign
conventions, and the choices where the spec leaves one open, are the model's
(:mod:`~field_models.soccer_server.dynamics`).
"""

from __future__ import annotations

import math

from field_models.protocol import Action, Dash, Kick, Say, Turn, TurnNeck, wrap_angle
from field_models.soccer_server.cycle_rules import (
    AFTER_GOAL_MODES,
    BEFORE_KICK_OFF,
    DASH,
    KICK,
    NO_COMMAND,
    PLAY_ON,
    RESTART_MODES,
    TURN,
    clamp,
    dash_direction,
    dash_rate,
    kick_effectiveness,
    kick_noise_radius,
)
from field_models.soccer_server.params import DynamicsParams, ServerPreset


class PlayerCommands:
    """The players' commands of one trial: queued by the players, run by the step (§2).

    A mixin of :class:`~field_models.soccer_server.dynamics.SoccerServerModel`, which owns
    the state named below; see the model for what each attribute holds.
    """

    preset: ServerPreset
    params: DynamicsParams
    cycle: int
    play_mode: str
    x: list[float]
    y: list[float]
    vx: list[float]
    vy: list[float]
    heading: list[float]
    neck: list[float]
    kicked_at: list[int]
    _n: int
    _straight_dash: bool
    _kind: list[int]
    _arg1: list[float]
    _arg2: list[float]
    _pending: list[int]
    _neck_turn: dict[int, float]
    _say_queue: list[tuple[int, str]]
    _ax: list[float]
    _ay: list[float]
    _noise: tuple[list[list[float]], ...]

    # ------------------------------------------------------------------ on arrival

    def command(self, i: int, action: Action) -> bool:
        """Queue player row `i`'s action for the next step; False if the server would ignore it.

        A second body command (turn, dash, kick) in the same cycle is ignored (§1.1); a say
        or a turn_neck combines with one. A view change is the sensing's, not the model's.
        """
        if isinstance(action, Dash):
            return self.dash(i, action.power, action.direction_rad)
        if isinstance(action, Turn):
            return self.turn(i, action.angle_rad)
        if isinstance(action, Kick):
            return self.kick(i, action.power, action.direction_rad)
        if isinstance(action, Say):
            return self.say(i, action.text)
        if isinstance(action, TurnNeck):
            return self.turn_neck(i, action.angle_rad)
        raise TypeError(f"not a Soccer Server model action: {action!r}")

    def dash(self, i: int, power: float, direction_rad: float = 0.0) -> bool:
        """Queue ``(dash power direction)`` (§2.1; direction counter-clockwise from the heading).

        The power is clamped to [min_dash_power, max_dash_power]; the direction is clamped and
        rounded by :func:`dash_direction`. At the step the player is pushed toward heading +
        direction by power · :func:`dash_rate` · dash_power_rate.
        """
        p = self.params
        power = clamp(power, p.min_dash_power, p.max_dash_power)
        if direction_rad == 0.0 and self._straight_dash:
            return self._queue(i, DASH, power, 0.0)  # what dash_direction gives, for less
        return self._queue(i, DASH, power, dash_direction(direction_rad, p))

    def turn(self, i: int, angle_rad: float) -> bool:
        """Queue a turn by `angle_rad` (left positive), clamped in the server's sign (§2.2)."""
        p = self.params
        return self._queue(i, TURN, -clamp(-angle_rad, p.minmoment_rad, p.maxmoment_rad), 0.0)

    def kick(self, i: int, power: float, direction_rad: float) -> bool:
        """Queue a kick: power clamped to [minpower, maxpower], direction to the moment range."""
        p = self.params
        power = clamp(power, p.minpower, p.maxpower)
        direction = -clamp(-direction_rad, p.minmoment_rad, p.maxmoment_rad)
        return self._queue(i, KICK, power, direction)

    def turn_neck(self, i: int, angle_rad: float) -> bool:
        """Queue ``(turn_neck Moment)``: the neck turns by `angle_rad` (left positive) at the step.

        As rcssserver's ``Player::turn_neck``: the moment is clamped to [minneckmoment,
        maxneckmoment] and the new neck angle to [minneckang, maxneckang], both in the server's
        sign (§2.2); no noise, so no random number is drawn. Not a body command: it goes with
        one; a second turn_neck in the same cycle is ignored (False), as the server's
        per-cycle ``turn_neck`` flag does.
        """
        self._check_player(i)
        if i in self._neck_turn:
            return False
        p = self.params
        self._neck_turn[i] = -clamp(-angle_rad, p.minneckmoment_rad, p.maxneckmoment_rad)
        return True

    def say(self, i: int, text: str) -> bool:
        """Queue a say; a message longer than ``say_msg_size`` is dropped (§2.6)."""
        self._check_player(i)
        if len(text) > self.preset.sensing.say_msg_size:
            return False
        self._say_queue.append((i, text))
        return True

    def _queue(self, i: int, kind: int, arg1: float, arg2: float) -> bool:
        self._check_player(i)
        if self._kind[i] != NO_COMMAND:
            return False
        self._kind[i] = kind
        self._arg1[i] = float(arg1)  # plain floats keep the step free of numpy scalars
        self._arg2[i] = float(arg2)
        self._pending.append(i)
        return True

    def _check_player(self, i: int) -> None:
        if not 0 < i < self._n:
            raise IndexError(f"player row {i} outside 1..{self._n - 1}")

    # ------------------------------------------------------------------ at the step

    def _run_commands(self, r: int, messages: list[str]) -> None:
        """Dash, turn and kick, in row order, against the start-of-cycle state (§1.1, §2)."""
        kicked = False
        for i in sorted(self._pending):
            kind = self._kind[i]
            if kind == DASH:
                self._do_dash(i, self._arg1[i], self._arg2[i])
            elif kind == TURN:
                self._do_turn(i, self._arg1[i], self._noise[2][r][i - 1])
            elif kind == KICK and self._do_kick(i, self._arg1[i], self._arg2[i], r):
                kicked = True
                self.kicked_at[i] = self.cycle + 1
            self._kind[i] = NO_COMMAND
        self._pending.clear()
        if kicked and self.play_mode in RESTART_MODES and self.params.referee:
            self.play_mode = PLAY_ON
            messages.append(PLAY_ON)

    def _turn_necks(self) -> None:
        """Commit this cycle's turn_necks (the server commits the neck at the step, §1.1)."""
        p = self.params
        for i, moment in self._neck_turn.items():
            server = clamp(-(self.neck[i] + moment), p.minneckang_rad, p.maxneckang_rad)
            self.neck[i] = -server + 0.0
        self._neck_turn.clear()

    def _do_dash(self, i: int, power: float, direction: float) -> None:
        """Push the player toward heading + direction: power · dir rate · dash_power_rate.

        Effort is 1 (stamina is not modelled, §2.7). With both legs dashing alike and stamina
        to spare, rcssserver 19's ``Player::applyDashEffect`` (``src/player.cpp`` lines
        1205-1254: the mean of the legs' accelerations, no turn) reduces to one
        ``Leg::calcDashAccel`` (``src/leg.cpp`` lines 150-181): magnitude
        |power · dir_rate · dash_power_rate| toward body + direction, reversed for a negative
        power (possible only where ``min_dash_power`` < 0).
        """
        p = self.params
        h = self.heading[i]
        if direction == 0.0:
            a = power * p.dash_power_rate_m_per_cycle2
        else:
            rate = dash_rate(direction, p.side_dash_rate, p.back_dash_rate)
            a = power * rate * p.dash_power_rate_m_per_cycle2
            h = h + direction
        self._ax[i] += a * math.cos(h)
        self._ay[i] += a * math.sin(h)

    def _do_turn(self, i: int, angle: float, factor: float) -> None:
        """Turn by (1 + ξ)·angle / (1 + inertia_moment·|v|), |v| the stored speed (§2.2)."""
        vx, vy = self.vx[i], self.vy[i]
        speed = math.sqrt(vx * vx + vy * vy)
        h = self.heading[i] + factor * angle / (
            1.0 + self.params.inertia_moment_cycle_per_m * speed
        )
        self.heading[i] = wrap_angle(h)

    def _do_kick(self, i: int, power: float, direction: float, r: int) -> bool:
        """Push the ball if it is within the kickable area; True if the kick was taken (§2.3)."""
        p = self.params
        if self.play_mode == BEFORE_KICK_OFF or self.play_mode in AFTER_GOAL_MODES:
            return False
        rx = self.x[0] - self.x[i]
        ry = self.y[0] - self.y[i]
        dist2 = rx * rx + ry * ry
        reach = p.kickable_area_m
        if dist2 > reach * reach:
            return False
        h = self.heading[i]
        ch, sh = math.cos(h), math.sin(h)
        dir_diff = math.atan2(abs(ch * ry - sh * rx), ch * rx + sh * ry)
        gap = math.sqrt(dist2) - p.player_size_m - p.ball_size_m
        k = kick_effectiveness(gap, dir_diff, p.kickable_margin_m) if p.kick_reduction else 1.0
        a = power * p.kick_power_rate_m_per_cycle2 * k
        ang = h + direction
        ax = a * math.cos(ang)
        ay = a * math.sin(ang)
        if p.kick_rand:
            bvx, bvy = self.vx[0], self.vy[0]
            radius = kick_noise_radius(p, power, gap, dir_diff, math.sqrt(bvx * bvx + bvy * bvy))
            ax += radius * self._noise[3][r][i - 1]
            ay += radius * self._noise[4][r][i - 1]
        self._ax[0] += ax
        self._ay[0] += ay
        return True
