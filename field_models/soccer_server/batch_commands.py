"""The batch's player commands: queued with the server's clamping, run at the step (§2).

:class:`BatchCommands` is the part of
:class:`~field_models.soccer_server.batch.BatchSoccerServer` that speaks for the players: the
one-trial model's :class:`~field_models.soccer_server.commands.PlayerCommands` elementwise,
with the same operations in the same order on the same random numbers, over the trials of a
mask.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np

from field_models.protocol import wrap_angle
from field_models.soccer_server.batch_random import BatchRandom
from field_models.soccer_server.cycle_rules import (
    BEFORE_KICK_OFF,
    DASH,
    HALF_PI,
    KICK,
    NO_COMMAND,
    PLAY_MODE_CODE,
    PLAY_ON,
    RESTART_MODES,
    TURN,
    kick_noise_radius,
    unit_noise,
)
from field_models.soccer_server.params import DynamicsParams

_BKO, _PLAY_ON = PLAY_MODE_CODE[BEFORE_KICK_OFF], PLAY_MODE_CODE[PLAY_ON]
_GOAL_L, _GOAL_R = PLAY_MODE_CODE["goal_l"], PLAY_MODE_CODE["goal_r"]
_RESTART_CODES = np.array([PLAY_MODE_CODE[m] for m in RESTART_MODES])

FloatArg = float | np.ndarray
"""A scalar for every trial, or one value per trial."""


class BatchCommands:
    """The players' commands of K trials: queued by the players, run by the step (§2).

    A mixin of :class:`~field_models.soccer_server.batch.BatchSoccerServer`, which owns the
    state named below; see the batch for what each attribute holds.
    """

    params: DynamicsParams
    k: int
    _n: int
    x: np.ndarray
    y: np.ndarray
    vx: np.ndarray
    vy: np.ndarray
    heading: np.ndarray
    mode: np.ndarray
    _ax: np.ndarray
    _ay: np.ndarray
    _kind: np.ndarray
    _arg1: np.ndarray
    _arg2: np.ndarray
    _random: BatchRandom
    _mask: Callable[[np.ndarray | None], np.ndarray]
    _check_player: Callable[[int], None]

    # ------------------------------------------------------------------ on arrival

    def dash(
        self,
        i: int,
        power: FloatArg,
        direction_rad: FloatArg = 0.0,
        mask: np.ndarray | None = None,
    ) -> np.ndarray:
        """Queue ``(dash power direction)`` for player row `i`; returns the trials that took it.

        Power and direction are clamped (and the direction rounded) as in the single model
        (:func:`~field_models.soccer_server.cycle_rules.dash_direction`).
        """
        p = self.params
        power = np.clip(power, p.min_dash_power, p.max_dash_power)
        d = -np.clip(np.negative(direction_rad), p.min_dash_angle_rad, p.max_dash_angle_rad)
        step = p.dash_angle_step_rad
        if step > 0.0:
            d = step * np.round(d / step)  # half to even, as the single model's round
        return self._queue(i, DASH, power, d + 0.0, mask)

    def turn(self, i: int, angle_rad: FloatArg, mask: np.ndarray | None = None) -> np.ndarray:
        """Queue a turn by `angle_rad` (left positive), clamped in the server's sign."""
        p = self.params
        angle = -np.clip(np.negative(angle_rad), p.minmoment_rad, p.maxmoment_rad)
        return self._queue(i, TURN, angle, 0.0, mask)

    def kick(
        self, i: int, power: FloatArg, direction_rad: FloatArg, mask: np.ndarray | None = None
    ) -> np.ndarray:
        """Queue a kick; power and direction clamped as in the single model."""
        p = self.params
        power = np.clip(power, p.minpower, p.maxpower)
        direction = -np.clip(np.negative(direction_rad), p.minmoment_rad, p.maxmoment_rad)
        return self._queue(i, KICK, power, direction, mask)

    def _queue(
        self, i: int, kind: int, arg1: FloatArg, arg2: FloatArg, mask: np.ndarray | None
    ) -> np.ndarray:
        self._check_player(i)
        ok = self._mask(mask) & (self._kind[:, i] == NO_COMMAND)
        self._kind[:, i] = np.where(ok, kind, self._kind[:, i])
        self._arg1[:, i] = np.where(ok, arg1, self._arg1[:, i])
        self._arg2[:, i] = np.where(ok, arg2, self._arg2[:, i])
        return ok

    # ------------------------------------------------------------------ at the step

    def _run_commands(self, r: int, messages: dict[int, list[str]]) -> None:
        kicked = np.zeros(self.k, dtype=bool)
        for i in range(1, self._n):
            kind = self._kind[:, i]
            if (kind == DASH).any():
                self._do_dash(i, kind == DASH)
            if (kind == TURN).any():
                self._do_turn(i, kind == TURN, self._random.turn_noise(r, i, kind == TURN))
            if (kind == KICK).any():
                kicked |= self._do_kick(i, kind == KICK, r)
        self._kind[:] = NO_COMMAND
        restart = kicked & np.isin(self.mode, _RESTART_CODES)
        if self.params.referee and restart.any():
            self.mode[restart] = _PLAY_ON
            for trial in np.flatnonzero(restart).tolist():
                messages.setdefault(trial, []).append(PLAY_ON)

    def _do_dash(self, i: int, m: np.ndarray) -> None:
        """The single model's ``_do_dash`` elementwise: rate 1 and no turn for direction 0."""
        p = self.params
        d = self._arg2[:, i]
        power, dpr = self._arg1[:, i], p.dash_power_rate_m_per_cycle2
        h = self.heading[:, i]
        a = power * dpr
        directed = d != 0.0
        if directed.any():
            a_abs = np.abs(d)
            side, back = p.side_dash_rate, p.back_dash_rate
            rate = np.where(
                a_abs > HALF_PI,
                back - (back - side) * (1.0 - (a_abs - HALF_PI) / HALF_PI),
                side + (1.0 - side) * (1.0 - a_abs / HALF_PI),
            )
            a = np.where(directed, power * np.clip(rate, 0.0, 1.0) * dpr, a)
            h = np.where(directed, h + d, h)
        self._ax[:, i] = np.where(m, self._ax[:, i] + a * np.cos(h), self._ax[:, i])
        self._ay[:, i] = np.where(m, self._ay[:, i] + a * np.sin(h), self._ay[:, i])

    def _do_turn(self, i: int, m: np.ndarray, factor: np.ndarray) -> None:
        vx, vy = self.vx[:, i], self.vy[:, i]
        speed = np.sqrt(vx * vx + vy * vy)
        inertia = self.params.inertia_moment_cycle_per_m
        h = wrap_angle(self.heading[:, i] + factor * self._arg1[:, i] / (1.0 + inertia * speed))
        self.heading[:, i] = np.where(m, h, self.heading[:, i])

    def _do_kick(self, i: int, m: np.ndarray, r: int) -> np.ndarray:
        """Kick in the trials of `m` where allowed and in reach; returns where it was taken."""
        p = self.params
        stopped = (self.mode == _BKO) | (self.mode == _GOAL_L) | (self.mode == _GOAL_R)
        rx = self.x[:, 0] - self.x[:, i]
        ry = self.y[:, 0] - self.y[:, i]
        dist2 = rx * rx + ry * ry
        reach = p.kickable_area_m
        ok = m & ~stopped & ~(dist2 > reach * reach)
        idx = np.flatnonzero(ok)
        if idx.size == 0:
            return ok
        h = self.heading[idx, i]
        ch, sh = np.cos(h), np.sin(h)
        rx, ry, dist2 = rx[idx], ry[idx], dist2[idx]
        cross = np.abs(ch * ry - sh * rx)
        dot = ch * rx + sh * ry
        # math.atan2, not np.arctan2: the two differ in the last bit (kicks are few).
        dir_diff = np.array(
            [math.atan2(c, d) for c, d in zip(cross.tolist(), dot.tolist(), strict=True)]
        )
        gap = np.sqrt(dist2) - p.player_size_m - p.ball_size_m
        if p.kick_reduction:
            k = 1.0 - 0.25 * dir_diff / math.pi - 0.25 * gap / p.kickable_margin_m
        else:
            k = np.ones(idx.size)
        power = self._arg1[idx, i]
        a = power * p.kick_power_rate_m_per_cycle2 * k
        ang = h + self._arg2[idx, i]
        ax = a * np.cos(ang)
        ay = a * np.sin(ang)
        if p.kick_rand:
            bvx, bvy = self.vx[idx, 0], self.vy[idx, 0]
            radius = kick_noise_radius(p, power, gap, dir_diff, np.sqrt(bvx * bvx + bvy * bvy))
            nx, ny = unit_noise(*self._random.kick_uniforms(r, i, idx), p.noise_model)
            ax = ax + radius * nx
            ay = ay + radius * ny
        self._ax[idx, 0] = self._ax[idx, 0] + ax
        self._ay[idx, 0] = self._ay[idx, 0] + ay
        return ok
