"""Many independent Soccer Server trials stepped at once as numpy arrays.

:class:`BatchSoccerServer` holds K trials of the same preset and the same players, each with
its own random stream (a numpy generator per trial, or the trials' counter-based "movement"
streams as one :class:`~field_models.seeding.StreamBatch`, drawn as one array), as arrays of
shape (K, N+1) (row 0 the ball, rows 1..N the players). A step
does for all trials what :meth:`SoccerServerModel.step
<field_models.soccer_server.dynamics.SoccerServerModel.step>` does for one, with the same
operations in the same order on the same random numbers, so trial k equals a single model
built with generator k, seed for seed (``tests/field_models/soccer_server/test_batch.py``).

What batch mode supports: the ball and the players; dash (with direction), turn and kick with
the server's clamping and one body command per cycle; the trainer's moves and ``change_mode``;
movement noise, turn noise, kick noise; collisions; the referee's goals and kick-offs. What it
does not support: say/hear and sensing (no see messages; read the state arrays instead).

Numbers: positions [m] and stored velocities [m/cycle] in :attr:`BatchSoccerServer.x` etc.;
command arguments as in the single model (power in server units, angles in radians, counter-
clockwise). Each argument may be a scalar or an array of K values; `mask` (K booleans)
selects the trials a call applies to.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from field_models.protocol import BodyState, PlayerRef, end_line_crossing, wrap_angle
from field_models.seeding import Rng, StreamBatch
from field_models.soccer_server.batch_collisions import PairTable, collide
from field_models.soccer_server.batch_random import BatchRandom
from field_models.soccer_server.cycle_rules import (
    AFTER_GOAL_MODES,
    BEFORE_KICK_OFF,
    DASH,
    HALF_PI,
    KICK,
    NO_COMMAND,
    PLAY_MODES,
    PLAY_ON,
    RESTART_MODES,
    TURN,
    side_of,
    unit_noise,
)
from field_models.soccer_server.params import ServerPreset

_CODE = {mode: code for code, mode in enumerate(PLAY_MODES)}
_BKO, _PLAY_ON = _CODE[BEFORE_KICK_OFF], _CODE[PLAY_ON]
_GOAL_L, _GOAL_R = _CODE["goal_l"], _CODE["goal_r"]
_KICK_OFF_L, _KICK_OFF_R = _CODE["kick_off_l"], _CODE["kick_off_r"]
_RESTART_CODES = np.array([_CODE[m] for m in RESTART_MODES])

FloatArg = float | np.ndarray
"""A scalar for every trial, or one value per trial."""


class BatchSoccerServer:
    """K independent Soccer Server trials of one preset, stepped together.

    Attributes:
        preset: The server configuration. params: its dynamics.
        players: The players, rows 1..N of every trial.
        k: Number of trials.
        cycle: Cycles stepped so far (all trials step together).
        x, y: Positions (K, N+1) [m]. vx, vy: stored velocities (K, N+1) [m/cycle].
        heading: Body angles (K, N+1) [rad]; column 0 (the ball) stays 0.
        mode: Play-mode code per trial, an index into
            :data:`~field_models.soccer_server.cycle_rules.PLAY_MODES`.
        score_left, score_right: Goals per trial.
    """

    def __init__(
        self,
        preset: ServerPreset,
        players: tuple[PlayerRef, ...],
        rngs: Sequence[Rng] | StreamBatch,
    ) -> None:
        p = preset.dynamics
        if p.swept_ball_collisions:
            raise ValueError("batch mode does not support swept_ball_collisions")
        self.preset = preset
        self.params = p
        self.players = tuple(players)
        self._random = BatchRandom(rngs, len(self.players), p)
        self.k = self._random.k
        n = len(self.players) + 1
        self._n = n
        shape = (self.k, n)
        self.cycle = 0
        self.x = np.zeros(shape)
        self.y = np.zeros(shape)
        self.x[:, 1:] = [-3.0 * i for i in range(1, n)]  # off the pitch, as the single model
        self.y[:, 1:] = -(0.5 * p.pitch_width_m + 3.0)
        self.vx = np.zeros(shape)
        self.vy = np.zeros(shape)
        self.heading = np.zeros(shape)
        self._ax = np.zeros(shape)
        self._ay = np.zeros(shape)
        self.mode = np.full(self.k, _PLAY_ON)
        self.score_left = np.zeros(self.k, dtype=int)
        self.score_right = np.zeros(self.k, dtype=int)
        self._after_goal = np.zeros(self.k, dtype=int)
        self._kind = np.zeros(shape, dtype=np.int8)
        self._arg1 = np.zeros(shape)
        self._arg2 = np.zeros(shape)
        self._announce: dict[int, list[str]] = {}
        self._decay = np.array([p.ball_decay] + [p.player_decay] * (n - 1))
        self._rand = np.array([p.ball_rand] + [p.player_rand] * (n - 1))
        self._amax = np.array(
            [p.ball_accel_max_m_per_cycle2] + [p.player_accel_max_m_per_cycle2] * (n - 1)
        )
        self._smax = np.array(
            [p.ball_speed_max_m_per_cycle] + [p.player_speed_max_m_per_cycle] * (n - 1)
        )
        self._amax2 = self._amax * self._amax
        self._smax2 = self._smax * self._smax
        self._pairs = PairTable.of([p.ball_size_m] + [p.player_size_m] * (n - 1))
        self._side = np.array([0] + [side_of(ref) for ref in self.players])
        self._has_left = bool((self._side == 1).any())
        self._has_right = bool((self._side == -1).any())
        self._pitch = p.pitch()

    # ------------------------------------------------------------------ look-ups

    def keep(self, trials: np.ndarray) -> None:
        """Go on with the trials `trials` only (indices, in the order given), dropping the rest.

        A batch whose trials end at different times compacts itself with this, so finished
        trials cost nothing. Trial numbering restarts at 0 in the order of `trials`.
        """
        rows = np.asarray(trials, dtype=np.intp)
        for name in ("x", "y", "vx", "vy", "heading", "_ax", "_ay", "mode", "score_left",
                     "score_right", "_after_goal", "_kind", "_arg1", "_arg2"):  # fmt: skip
            setattr(self, name, getattr(self, name)[rows])
        self._random.keep(rows)
        new_index = {old: new for new, old in enumerate(rows.tolist())}
        self._announce = {
            new_index[t]: said for t, said in self._announce.items() if t in new_index
        }
        self.k = len(rows)

    def row(self, ref: PlayerRef) -> int:
        """Row (1..N) of player `ref`."""
        return self.players.index(ref) + 1

    def mode_name(self, trial: int) -> str:
        """Play mode of one trial."""
        return PLAY_MODES[int(self.mode[trial])]

    def ball_state(self, trial: int) -> BodyState:
        """The ball of one trial: position [m], velocity [m/s]."""
        return self._state(trial, 0)

    def player_state(self, trial: int, i: int) -> BodyState:
        """Player row `i` of one trial: position [m], heading [rad], velocity [m/s]."""
        self._check_player(i)
        return self._state(trial, i)

    def _state(self, trial: int, i: int) -> BodyState:
        k = 1.0 / self.params.dt_s
        return BodyState(
            float(self.x[trial, i]),
            float(self.y[trial, i]),
            float(self.heading[trial, i]),
            float(self.vx[trial, i]) * k,
            float(self.vy[trial, i]) * k,
        )

    def _mask(self, mask: np.ndarray | None) -> np.ndarray:
        if mask is None:
            return np.ones(self.k, dtype=bool)
        return np.asarray(mask, dtype=bool)

    def _check_player(self, i: int) -> None:
        if not 0 < i < self._n:
            raise IndexError(f"player row {i} outside 1..{self._n - 1}")

    # ------------------------------------------------------------------ coach / trainer

    def move_ball(
        self,
        x: FloatArg,
        y: FloatArg,
        vx_mps: FloatArg = 0.0,
        vy_mps: FloatArg = 0.0,
        mask: np.ndarray | None = None,
    ) -> None:
        """Put the ball at (x, y) [m] with velocity [m/s] in the trials of `mask`."""
        m = self._mask(mask)
        dt = self.params.dt_s
        self.x[:, 0] = np.where(m, x, self.x[:, 0])
        self.y[:, 0] = np.where(m, y, self.y[:, 0])
        self.vx[:, 0] = np.where(m, np.multiply(vx_mps, dt), self.vx[:, 0])
        self.vy[:, 0] = np.where(m, np.multiply(vy_mps, dt), self.vy[:, 0])
        self._ax[:, 0] = np.where(m, 0.0, self._ax[:, 0])
        self._ay[:, 0] = np.where(m, 0.0, self._ay[:, 0])

    def move_player(
        self,
        i: int,
        x: FloatArg,
        y: FloatArg,
        heading_rad: FloatArg,
        vx_mps: FloatArg = 0.0,
        vy_mps: FloatArg = 0.0,
        mask: np.ndarray | None = None,
    ) -> None:
        """Put player row `i` at (x, y) facing `heading_rad`, then resolve overlaps (§5)."""
        self._check_player(i)
        m = self._mask(mask)
        dt = self.params.dt_s
        heading = np.broadcast_to(np.asarray(heading_rad, dtype=float), (self.k,))
        wrapped = wrap_angle(np.array(heading))  # the array form: the same bits as per float
        self.x[:, i] = np.where(m, x, self.x[:, i])
        self.y[:, i] = np.where(m, y, self.y[:, i])
        self.heading[:, i] = np.where(m, wrapped, self.heading[:, i])
        self.vx[:, i] = np.where(m, np.multiply(vx_mps, dt), self.vx[:, i])
        self.vy[:, i] = np.where(m, np.multiply(vy_mps, dt), self.vy[:, i])
        self._collide(m)

    def change_mode(self, mode: str, mask: np.ndarray | None = None) -> None:
        """Set the play mode in the trials of `mask`; announced at the next step."""
        if mode not in PLAY_MODES:
            raise ValueError(f"unknown play mode {mode!r}; known: {', '.join(PLAY_MODES)}")
        m = self._mask(mask)
        self.mode[m] = _CODE[mode]
        self._after_goal[m] = 0
        if mode not in AFTER_GOAL_MODES:
            for trial in np.flatnonzero(m).tolist():
                self._announce.setdefault(trial, []).append(mode)

    # ------------------------------------------------------------------ player commands

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

    # ------------------------------------------------------------------ the cycle

    def step(self) -> list[tuple[int, str]]:
        """Advance every trial one cycle; return the referee messages as (trial, text)."""
        messages = self._announce
        self._announce = {}
        r = self._random.next_row()
        if (self._kind != NO_COMMAND).any():
            self._run_commands(r, messages)
        bx0, by0 = self.x[:, 0].copy(), self.y[:, 0].copy()
        held = self.mode == _BKO
        self._hold_players(held)
        moving = ~held
        self._move_objects(r, moving)
        self._collide(moving)
        if self.params.referee:
            self._judge(bx0, by0, moving, messages)
        self.cycle += 1
        return [(trial, text) for trial in sorted(messages) for text in messages[trial]]

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
            radius = self._kick_noise_radius(power, gap, dir_diff, np.sqrt(bvx * bvx + bvy * bvy))
            nx, ny = unit_noise(*self._random.kick_uniforms(r, i, idx), p.noise_model)
            ax = ax + radius * nx
            ay = ay + radius * ny
        self._ax[idx, 0] = self._ax[idx, 0] + ax
        self._ay[idx, 0] = self._ay[idx, 0] + ay
        return ok

    def _kick_noise_radius(
        self, power: np.ndarray, gap: np.ndarray, dir_diff: np.ndarray, ball_speed: np.ndarray
    ) -> np.ndarray:
        p = self.params
        scale = p.kick_rand * (power / p.maxpower)
        if p.noise_model == "box":
            return scale
        pos_rate = 0.5 + 0.25 * (dir_diff / math.pi + gap / p.kickable_margin_m)
        speed_rate = 0.5 + 0.5 * (ball_speed / (p.ball_speed_max_m_per_cycle * p.ball_decay))
        return scale * (pos_rate + speed_rate)

    def _hold_players(self, held: np.ndarray) -> None:
        if held.any():
            for arr in (self.vx, self.vy, self._ax, self._ay):
                arr[held, 1:] = 0.0

    def _move_objects(self, r: int, moving: np.ndarray) -> None:
        """The per-object update of all objects of the moving trials (§1.2)."""
        vx, vy, ax, ay = self.vx, self.vy, self._ax, self._ay
        pushed = (ax != 0.0) | (ay != 0.0)
        with np.errstate(divide="ignore", invalid="ignore"):
            # The clamps are rare: their square roots are taken only when one bites.
            a2 = ax * ax + ay * ay
            over = a2 > self._amax2
            if over.any():
                f = self._amax / np.sqrt(a2)
                ax, ay = np.where(over, ax * f, ax), np.where(over, ay * f, ay)
            ux, uy = vx + ax, vy + ay
            v2 = ux * ux + uy * uy
            over = v2 > self._smax2
            if over.any():
                f = self._smax / np.sqrt(v2)
                ux, uy = np.where(over, ux * f, ux), np.where(over, uy * f, uy)
        ux, uy = np.where(pushed, ux, vx), np.where(pushed, uy, vy)
        ax, ay = self._ax, self._ay
        radius = self._rand * np.sqrt(ux * ux + uy * uy)
        noise = self._random.noise
        ux = ux + radius * noise[0][:, r]
        uy = uy + radius * noise[1][:, r]
        if moving.all():  # the usual case: no trial holds its players
            self.x += ux
            self.y += uy
            self.vx, self.vy = self._decay * ux, self._decay * uy
            ax.fill(0.0)
            ay.fill(0.0)
            return
        keep = moving[:, None]
        self.x = np.where(keep, self.x + ux, self.x)
        self.y = np.where(keep, self.y + uy, self.y)
        self.vx = np.where(keep, self._decay * ux, vx)
        self.vy = np.where(keep, self._decay * uy, vy)
        self._ax = np.where(keep, 0.0, ax)
        self._ay = np.where(keep, 0.0, ay)

    def _collide(self, trials: np.ndarray) -> None:
        """Resolve overlaps in the given trials, as the single model does (§4)."""
        (self.x, self.y), (self.vx, self.vy) = collide(
            self._pairs, (self.x, self.y), (self.vx, self.vy), trials, self.mode == _PLAY_ON
        )

    # ------------------------------------------------------------------ referee (§6)

    def _judge(
        self, bx0: np.ndarray, by0: np.ndarray, moving: np.ndarray, messages: dict[int, list[str]]
    ) -> None:
        mode = self.mode.copy()
        after = moving & ((mode == _GOAL_L) | (mode == _GOAL_R))
        self._after_goal[after] += 1
        ready = after & (self._after_goal >= self.params.after_goal_wait_cycles)
        if ready.any():
            self._kick_off(np.flatnonzero(ready), messages)
        side = self._goal_side(bx0, by0, moving & ~after)
        if side.any():
            self._score(side, messages)
        kick_off = moving & ~after & (side == 0) & ((mode == _KICK_OFF_L) | (mode == _KICK_OFF_R))
        if kick_off.any():
            self._keep_halves(kick_off, np.where(mode == _KICK_OFF_L, 1, -1))

    def _goal_side(self, x0: np.ndarray, y0: np.ndarray, judged: np.ndarray) -> np.ndarray:
        """Per trial +1 (goal at +x, for the left team), -1 (at -x) or 0, among `judged`.

        A vector test picks the trials whose ball crossed an end line this cycle; only those
        go through the scalar rule, ``field_models.protocol.end_line_crossing``.
        """
        x1, y1 = self.x[:, 0], self.y[:, 0]
        line = 0.5 * self._pitch.length_m + self._pitch.ball_radius_m
        crossed = judged & (np.abs(x1) > line) & ~(np.abs(x0) > line)
        side = np.zeros(self.k, dtype=int)
        for trial in np.flatnonzero(crossed).tolist():
            crossing = end_line_crossing(
                self._pitch, float(x0[trial]), float(y0[trial]), float(x1[trial]), float(y1[trial])
            )
            if crossing.is_goal:
                side[trial] = int(crossing)
        return side

    def _score(self, side: np.ndarray, messages: dict[int, list[str]]) -> None:
        """The goals of this cycle: side[k] +1 (the left team scored), -1 (the right), 0."""
        scored = np.flatnonzero(side)
        left = side[scored] > 0
        self.score_left[scored[left]] += 1 if self._has_left else 0
        self.score_right[scored[~left]] += 1 if self._has_right else 0
        for trial, by_left in zip(scored.tolist(), left.tolist(), strict=True):
            count = self.score_left[trial] if by_left else self.score_right[trial]
            messages.setdefault(trial, []).append(f"goal_{'l' if by_left else 'r'}_{count}")
        self.mode[scored] = np.where(left, _GOAL_L, _GOAL_R)
        for arr in (self.vx, self.vy, self._ax, self._ay):
            arr[scored, 0] = 0.0
        self._after_goal[scored] = 0
        if self.params.after_goal_wait_cycles == 0:
            self._kick_off(scored, messages)

    def _kick_off(self, trials: np.ndarray, messages: dict[int, list[str]]) -> None:
        """Kick-offs after goals in `trials` (indices): ball to the centre, players placed."""
        kicker = np.where(self.mode[trials] == _GOAL_L, -1, 1)
        self.mode[trials] = np.where(kicker < 0, _KICK_OFF_R, _KICK_OFF_L)
        for trial in trials.tolist():
            messages.setdefault(trial, []).append(PLAY_MODES[int(self.mode[trial])])
        for arr in (self.x, self.y, self.vx, self.vy, self._ax, self._ay):
            arr[trials, 0] = 0.0
        chosen = np.zeros(self.k, dtype=bool)
        chosen[trials] = True
        kickers = np.zeros(self.k, dtype=int)
        kickers[trials] = kicker
        self._keep_halves(chosen, kickers)

    def _keep_halves(self, trials: np.ndarray, kicker: np.ndarray) -> None:
        """Players into their own half; the team not kicking off out of the centre circle."""
        p = self.params
        rows = np.flatnonzero(trials)  # a few trials: work on their rows only
        side = self._side[1:]
        x, y = self.x[rows, 1:], self.y[rows, 1:]
        x = np.where(side * x > 0.0, -side * p.player_size_m, x)
        radius = p.center_circle_radius_m + p.player_size_m
        r = np.sqrt(x * x + y * y)
        inside = (side != 0) & (side != kicker[rows, None]) & ~(r > radius)
        with np.errstate(divide="ignore", invalid="ignore"):
            nx = np.where(r == 0.0, radius, x * (radius / r))
            ny = np.where(r == 0.0, 0.0, y * (radius / r))
        self.x[rows, 1:] = np.where(inside, nx, x)
        self.y[rows, 1:] = np.where(inside, ny, y)
