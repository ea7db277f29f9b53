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

As the single model, the batch keeps its parts with a job of their own in mixins: the players'
commands in :mod:`~field_models.soccer_server.batch_commands`, the play modes and the referee
in :mod:`~field_models.soccer_server.batch_referee`; this module keeps the state, the
read-outs, the trainer's moves and the cycle.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from field_models.protocol import BodyState, PlayerRef, wrap_angle
from field_models.seeding import Rng, StreamBatch
from field_models.soccer_server.batch_collisions import PairTable, collide
from field_models.soccer_server.batch_commands import BatchCommands, FloatArg
from field_models.soccer_server.batch_random import BatchRandom
from field_models.soccer_server.batch_referee import BatchReferee
from field_models.soccer_server.cycle_rules import (
    BEFORE_KICK_OFF,
    NO_COMMAND,
    PLAY_MODE_CODE,
    PLAY_MODES,
    PLAY_ON,
    side_of,
)
from field_models.soccer_server.params import ServerPreset

_BKO, _PLAY_ON = PLAY_MODE_CODE[BEFORE_KICK_OFF], PLAY_MODE_CODE[PLAY_ON]


class BatchSoccerServer(BatchCommands, BatchReferee):
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
