"""The Soccer Server's dynamics for one trial: commands, movement, collisions, referee.

Follows specs/soccer_server.md §1 (cycle and per-object update), §2 (dash, turn, kick, say),
§4 (collisions), §5 (trainer moves) and §6 (goals, referee messages). One :meth:`step` is one
100 ms cycle:

1. the body commands queued since the last step run against the state at the start of the
   cycle: dash pushes the player (along its heading plus the dash direction, see
   :func:`dash_rate`), turn sets its new heading, kick pushes the ball (§1.1, §2);
2. every object, in a freshly shuffled order, accelerates (with caps), gets movement noise,
   moves, decays and forgets its acceleration (§1.2, §1.3);
3. overlaps are pushed apart, velocities of colliding objects × −0.1 (§4);
4. the referee looks for a goal and runs the after-goal sequence (§6).

Frames and units. The model runs in our field frame (x toward the right goal, y up, angles
counter-clockwise). The server's frame has y down and clockwise angles; the dynamics are
mirror-symmetric, so only command arguments change sign: a ``Turn(+a)`` is the server's
``(turn -a)``, a ``Kick(p, +d)`` its ``(kick p -d)``, a ``Dash(p, +d)`` its ``(dash p -d)``, and
the ranges ``minmoment``/``maxmoment`` and ``min_dash_angle``/``max_dash_angle`` are applied in
the server's convention. Headings are wrapped by ``field_models.protocol.wrap_angle``. Object
rows: 0 is the ball, 1..N the players in the order given. The raw lists
:attr:`SoccerServerModel.x`, ``y``, ``vx``, ``vy``, ``heading`` hold metres, metres per
*cycle* (the server's stored, post-decay velocity) and radians; the coach
accessors :meth:`~SoccerServerModel.ball_state`, :meth:`~SoccerServerModel.player_state` and
the trainer's :meth:`~SoccerServerModel.move_ball` / :meth:`~SoccerServerModel.move_player`
speak m/s.

The rules it shares with the batch (play modes, the row layout, the command formulas) are in
:mod:`~field_models.soccer_server.cycle_rules`, the collisions in
:mod:`~field_models.soccer_server.collisions`. The model's parts with a job of their own are
mixins in modules of their own: the players' commands, queued and run (§2), in
:mod:`~field_models.soccer_server.commands`; the play mode and the referee (§5, §6) in
:mod:`~field_models.soccer_server.referee`. This module keeps the state, the coach's read-outs
and moves, and the cycle itself (§1, §4).

Randomness. Each cycle consumes one *row* of uniforms from the trial's generator, whatever
happens in it (:class:`RowLayout`: movement noise per update slot, turn and kick noise per
player, the update order; the slot order decides which numbers each object gets, as the
server's one generator serves the objects in update order). Rows are drawn in blocks of
:data:`BLOCK_CYCLES`; numpy's ``Generator.random`` yields the same numbers whatever the block
size, so :class:`~field_models.soccer_server.batch.BatchSoccerServer` reproduces a trial seed
for seed. Pass the model a generator of its own (e.g. the trial's ``"movement"`` stream).

Choices where the spec leaves one open (or where we simplify), each documented here:

* Movement noise has size ``rand·|u|``, u the velocity after this cycle's acceleration, as the
  server computes it (§1.3); the paper's §5 wording ("perturbed by a random amount between
  -.05 and .05") leaves out the speed factor. Box or polar per ``noise_model``; kick noise
  follows the same model (box: ±kick_rand·P/maxpower per axis as in 6.07–11.x; polar: §2.3).
* Commands run at the step, against the positions at its start (the server runs a kick on
  arrival, against the same positions; a coach move between commands and step is seen).
* In restart modes either team may kick (the server's kick-off faults are not modelled).
* Objects whose centres coincide in a collision are separated along +x, not at a random
  angle, so collisions draw no random numbers (§4).
* No stamina, effort or recovery: effort is 1 (§2.7 is not modelled). A dash is therefore
  rcssserver 19's two-leg dash with both legs alike and unlimited stamina (:func:`dash_rate`);
  ``slowness_on_top_for_*`` (1 by default) is not modelled.
* No goal posts as obstacles, no ball-out, offside, catch or ball-stuck rules. The referee
  (``DynamicsParams.referee``) only scores goals (the project's one goal-line rule,
  ``field_models.protocol.end_line_crossing``, on the pitch with the post radius) and
  restarts: after ``goal_l_N`` the ball stops, kicks are refused, and
  ``after_goal_wait_cycles`` later the ball goes to the centre and the mode becomes
  ``kick_off_r`` (mirror for the right team). In kick-off modes players are
  kept in their own half and the defending team out of the centre circle every cycle (the
  server's ``forbid_kick_off_offside``). In any restart mode (kick-off, free kick, ...) an
  accepted kick turns the mode into ``play_on`` and announces it. With the referee off, the
  play mode changes only through :meth:`~SoccerServerModel.change_mode`.
* A goal scores for a side only when a player of that team (``LEFT``/``RIGHT``) is on the field,
  as the server scores only for a connected team; the announced N is the new score.
* ``before_kick_off``: players keep their place (velocities and accelerations zeroed), the ball
  is not updated, no collisions (§1.1). The model starts in ``play_on``, as a trainer's drill.
* The time :attr:`~SoccerServerModel.cycle` counts every step, stopped modes included.
"""

from __future__ import annotations

import math

import numpy as np

from field_models.protocol import (
    BodyState,
    Pitch,
    PlayerRef,
    wrap_angle,
)
from field_models.seeding import Rng
from field_models.soccer_server.collisions import (
    any_overlap_swept,
    catch_passing_ball,
    resolve_collisions,
    sweep_of,
)
from field_models.soccer_server.commands import PlayerCommands
from field_models.soccer_server.cycle_rules import (
    BEFORE_KICK_OFF,
    NO_COMMAND,
    PLAY_ON,
    draw_rows,
    row_layout,
    side_of,
    turn_factor,
    unit_noise,
)
from field_models.soccer_server.params import ServerPreset
from field_models.soccer_server.referee import ModelReferee

BLOCK_CYCLES = 32
"""Cycles of random numbers drawn at once by the single-trial model."""

_state = tuple.__new__  # a BodyState from its 5 values, without the Python-level __new__


class SoccerServerModel(PlayerCommands, ModelReferee):
    """One trial of the Soccer Server: ball and players, stepped one 100 ms cycle at a time.

    Attributes:
        preset: The server configuration.
        params: Its dynamics (``preset.dynamics``).
        players: The players, rows 1..N.
        cycle: Cycles stepped so far.
        play_mode: Current play mode (one of :data:`PLAY_MODES`).
        score_left, score_right: Goals of each team.
        x, y: Positions per row [m]. vx, vy: stored velocities per row [m/cycle].
        heading: Body angle per row [rad], counter-clockwise; 0 for the ball.
        neck: Neck angle per row relative to the body [rad], counter-clockwise; 0 for the
            ball and for every player that never sent ``turn_neck``. The view points along
            heading + neck (§2.2, §3.1).
        kicked_at: Per row, the cycle count (``cycle`` after the step) of the last step whose
            kick took effect; -1 before any. rcssserver flags such a player's ``KICK`` state in
            that cycle's show (monitors and game logs read it).

    The ball starts at rest on the centre mark, the players at rest off the pitch (3 m apart
    below the bottom touchline) until the coach places them. The players' commands (queued,
    then run at the step) are :class:`~field_models.soccer_server.commands.PlayerCommands`',
    the play mode and the referee :class:`~field_models.soccer_server.referee.ModelReferee`'s.
    """

    def __init__(self, preset: ServerPreset, players: tuple[PlayerRef, ...], rng: Rng) -> None:
        p = preset.dynamics
        self.preset = preset
        self.params = p
        self._per_s = 1.0 / p.dt_s  # cycles per second: m/cycle -> m/s
        self.players = tuple(players)
        self.rng = rng
        n = len(self.players) + 1
        self._n = n
        self._rows = {ref: i + 1 for i, ref in enumerate(self.players)}
        if len(self._rows) != len(self.players):
            raise ValueError("players: a player appears twice")
        self.cycle = 0
        self.play_mode = PLAY_ON
        self.score_left = 0
        self.score_right = 0
        # Off the pitch below the bottom line, 3 m apart, so that no first move collides.
        self.x = [0.0] + [-3.0 * i for i in range(1, n)]
        self.y = [0.0] + [-(0.5 * p.pitch_width_m + 3.0)] * (n - 1)
        self.vx = [0.0] * n
        self.vy = [0.0] * n
        self.heading = [0.0] * n
        self.neck = [0.0] * n
        self._neck_turn: dict[int, float] = {}  # this cycle's turn_neck per row (one a cycle)
        self._ax = [0.0] * n
        self._ay = [0.0] * n
        self._size = [p.ball_size_m] + [p.player_size_m] * (n - 1)
        self._decay = [p.ball_decay] + [p.player_decay] * (n - 1)
        self._rand = [p.ball_rand] + [p.player_rand] * (n - 1)
        self._amax = [p.ball_accel_max_m_per_cycle2] + [p.player_accel_max_m_per_cycle2] * (n - 1)
        self._smax = [p.ball_speed_max_m_per_cycle] + [p.player_speed_max_m_per_cycle] * (n - 1)
        self._side = [0] + [side_of(ref) for ref in self.players]
        self._pitch = p.pitch()
        self._goal_line = 0.5 * p.pitch_length_m + p.ball_size_m
        self._straight_dash = p.min_dash_angle_rad <= 0.0 <= p.max_dash_angle_rad
        self._sweep = sweep_of(tuple(self._size))
        self._pairs = self._sweep.pairs
        self._kind = [NO_COMMAND] * n
        self.kicked_at = [-1] * n
        self._arg1 = [0.0] * n
        self._arg2 = [0.0] * n
        self._pending: list[int] = []
        self._say_queue: list[tuple[int, str]] = []
        self._said: list[tuple[int, str]] = []
        self._announce: list[str] = []
        self._after_goal_cycles = 0
        self._block_row = BLOCK_CYCLES
        self._noise: tuple[list[list[float]], ...] = ()
        self._order: list[list[int]] = []

    # ------------------------------------------------------------------ look-ups

    @property
    def dt_s(self) -> float:
        """Length of one cycle [s]."""
        return self.params.dt_s

    def pitch(self) -> Pitch:
        """Field geometry."""
        return self._pitch

    def row(self, ref: PlayerRef) -> int:
        """Row (1..N) of player `ref`."""
        return self._rows[ref]

    def ball_state(self) -> BodyState:
        """The ball's exact state: position [m], velocity [m/s]; heading 0."""
        k = self._per_s
        return _state(BodyState, (self.x[0], self.y[0], 0.0, self.vx[0] * k, self.vy[0] * k))

    def player_state(self, i: int) -> BodyState:
        """Player row `i`'s exact state: position [m], heading [rad], velocity [m/s]."""
        if not 0 < i < self._n:  # _check_player, in line: a coach reads states every cycle
            raise IndexError(f"player row {i} outside 1..{self._n - 1}")
        x, y, h, k = self.x[i], self.y[i], self.heading[i], self._per_s
        return _state(BodyState, (x, y, h, self.vx[i] * k, self.vy[i] * k))

    def said(self) -> list[tuple[int, str]]:
        """Messages said during the cycle the last :meth:`step` completed, as (row, text)."""
        return list(self._said)

    # ------------------------------------------------------------------ coach / trainer

    def move_ball(self, x: float, y: float, vx_mps: float = 0.0, vy_mps: float = 0.0) -> None:
        """Put the ball at (x, y) [m] with velocity (vx, vy) [m/s]; its pending push is dropped.

        The trainer's ``(move (ball) X Y 0 VX VY)`` (§5), in our frame.
        """
        dt = self.params.dt_s
        self.x[0], self.y[0] = float(x), float(y)
        self.vx[0], self.vy[0] = float(vx_mps) * dt, float(vy_mps) * dt
        self._ax[0] = self._ay[0] = 0.0

    def move_player(
        self,
        i: int,
        x: float,
        y: float,
        heading_rad: float,
        vx_mps: float = 0.0,
        vy_mps: float = 0.0,
    ) -> None:
        """Put player row `i` at (x, y) [m] facing `heading_rad`, then resolve overlaps (§5)."""
        self._check_player(i)
        dt = self.params.dt_s
        self.x[i], self.y[i] = float(x), float(y)
        self.heading[i] = wrap_angle(float(heading_rad))
        self.vx[i], self.vy[i] = float(vx_mps) * dt, float(vy_mps) * dt
        if any_overlap_swept(self._sweep, self.x, self.y):
            self._resolve_collisions()

    # ------------------------------------------------------------------ the cycle

    def step(self) -> list[str]:
        """Advance one cycle; return the referee messages of this cycle (``goal_l_1``, ...)."""
        messages = self._announce
        self._announce = []
        r = self._block_row
        if r == BLOCK_CYCLES:
            self._refill()
            r = 0
        self._block_row = r + 1
        if self._pending:
            self._run_commands(r, messages)
        if self._neck_turn:
            self._turn_necks()
        bx0, by0 = self.x[0], self.y[0]
        if self.play_mode == BEFORE_KICK_OFF:
            self._hold_players()
        else:
            if self.params.swept_ball_collisions:
                x0, y0 = list(self.x), list(self.y)
                self._move_objects(r)
                catch_passing_ball(self._pairs, (self.x, self.y), (x0, y0))
            else:
                self._move_objects(r)
            if any_overlap_swept(self._sweep, self.x, self.y):
                self._resolve_collisions()
            if self.params.referee:
                self._judge(bx0, by0, messages)
        self.cycle += 1
        self._said = self._say_queue
        self._say_queue = []
        return messages

    def _refill(self) -> None:
        """Draw the next block of rows and shape it into plain lists (no numpy per step)."""
        lay = row_layout(self._n - 1)
        u = draw_rows(self.rng, self._n - 1, BLOCK_CYCLES)
        model = self.params.noise_model
        move_x, move_y = unit_noise(u[:, lay.move_a], u[:, lay.move_b], model)
        kick_x, kick_y = unit_noise(u[:, lay.kick_a], u[:, lay.kick_b], model)
        self._noise = (
            move_x.tolist(),
            move_y.tolist(),
            turn_factor(u[:, lay.turn], self.params.player_rand).tolist(),
            kick_x.tolist(),
            kick_y.tolist(),
        )
        self._order = np.argsort(u[:, lay.order], axis=1, kind="stable").tolist()

    def _hold_players(self) -> None:
        """before_kick_off: players keep their place, the ball is not updated (§1.1)."""
        for i in range(1, self._n):
            self.vx[i] = self.vy[i] = self._ax[i] = self._ay[i] = 0.0

    def _move_objects(self, r: int) -> None:
        """Accelerate (capped), add noise, move, decay, reset — in shuffled order (§1.2)."""
        x, y, vxs, vys, axs, ays = self.x, self.y, self.vx, self.vy, self._ax, self._ay
        amax, smax, rand, decay = self._amax, self._smax, self._rand, self._decay
        nx, ny = self._noise[0][r], self._noise[1][r]
        for slot, i in enumerate(self._order[r]):
            vx, vy, ax, ay = vxs[i], vys[i], axs[i], ays[i]
            if ax or ay:
                cap = amax[i]
                a2 = ax * ax + ay * ay
                if a2 > cap * cap:
                    f = cap / math.sqrt(a2)
                    ax, ay = ax * f, ay * f
                vx, vy = vx + ax, vy + ay
                cap = smax[i]
                v2 = vx * vx + vy * vy
                if v2 > cap * cap:
                    f = cap / math.sqrt(v2)
                    vx, vy = vx * f, vy * f
                axs[i] = ays[i] = 0.0
            noise = rand[i]
            if noise:
                radius = noise * math.sqrt(vx * vx + vy * vy)
                vx, vy = vx + radius * nx[slot], vy + radius * ny[slot]
            x[i] += vx
            y[i] += vy
            d = decay[i]
            vxs[i], vys[i] = d * vx, d * vy

    def _resolve_collisions(self) -> None:
        """Push overlapping pairs apart, velocities × −0.1 (§4, :func:`resolve_collisions`)."""
        xy, vxy = (self.x, self.y), (self.vx, self.vy)
        resolve_collisions(self._pairs, xy, vxy, self.play_mode == PLAY_ON)
