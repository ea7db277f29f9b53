"""The random numbers of a batch of Soccer Server trials: each trial's rows, drawn in blocks.

:class:`BatchRandom` gives :class:`~field_models.soccer_server.batch.BatchSoccerServer` the
uniforms of each cycle's row (:class:`~field_models.soccer_server.cycle_rules.RowLayout`) for
every trial, the same numbers the single-trial model draws for that trial: from a numpy
generator per trial (whole rows, in blocks of :data:`BATCH_BLOCK_CYCLES`), or from the trials'
counter-based streams (:class:`~field_models.seeding.StreamBatch`), where only the columns every
cycle uses are computed in advance and a turn's or a kick's draws when one happens.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from field_models.seeding import Rng, StreamBatch
from field_models.soccer_server.cycle_rules import row_layout, turn_factor, unit_noise
from field_models.soccer_server.params import DynamicsParams

BATCH_BLOCK_CYCLES = 8
"""Cycles of random numbers drawn at once per trial (any value gives the same numbers; a
short block draws little past a trial's end: a drill trial lasts 10-40 cycles)."""


class BatchRandom:
    """Each trial's random rows, with the movement noise of every object shaped per block.

    Args:
        rngs: A numpy generator per trial, or the trials' streams as one batch.
        n_players: Players per trial (rows 1..N; row 0 is the ball).
        params: The dynamics (noise model, ``player_rand``).

    Attributes:
        k: Number of trials.
        noise: Per block: movement noise x and y (K, block, N+1) in update-slot order per
            object; with generators also the turn factors and the two kick draws per player.
    """

    def __init__(
        self, rngs: Sequence[Rng] | StreamBatch, n_players: int, params: DynamicsParams
    ) -> None:
        self.params = params
        self.streams = rngs if isinstance(rngs, StreamBatch) else None
        self.rngs = [] if isinstance(rngs, StreamBatch) else list(rngs)
        self.k = len(rngs.keys) if isinstance(rngs, StreamBatch) else len(self.rngs)
        self._n = n_players + 1
        self._layout = row_layout(n_players)
        block = (BATCH_BLOCK_CYCLES, self._layout.width) if self.streams is None else (0, 0)
        self._rows = np.empty((self.k, *block))  # the generators' block (streams: unused)
        self._block_row = BATCH_BLOCK_CYCLES
        self.noise: tuple[np.ndarray, ...] = ()
        self._block_start = np.zeros(self.k, dtype=np.int64)
        self._needed = self._needed_offsets().ravel()  # the block's always-used draws

    def next_row(self) -> int:
        """The block row of the next cycle, drawing a new block when the last one is used up."""
        if self._block_row == BATCH_BLOCK_CYCLES:
            self._refill()
        r = self._block_row
        self._block_row += 1
        return r

    def keep(self, rows: np.ndarray) -> None:
        """Go on with the trials `rows` only (indices, in the order given)."""
        self.noise = tuple(block[rows] for block in self.noise)
        self._rows = self._rows[rows]
        if self.streams is not None:
            self.streams = self.streams.subset(rows)
            self._block_start = self._block_start[rows]
        else:
            self.rngs = [self.rngs[r] for r in rows.tolist()]
        self.k = len(rows)

    def _refill(self) -> None:
        """Draw every trial's next rows and give each object its update slot's noise.

        With counter-based streams only the columns every cycle uses (update order, movement
        noise) are computed here; a turn's or a kick's draws are computed when one happens
        (:meth:`_uniforms_at`), at their place in the row: the same numbers, a third less work.
        """
        lay = self._layout
        streams = self.streams
        if streams is not None:
            self._block_start = streams.positions.copy()
            u = streams.peek(self._needed).reshape(self.k, BATCH_BLOCK_CYCLES, -1)
            streams.advance(BATCH_BLOCK_CYCLES * lay.width)
            n = self._n
            order, a, b = u[..., 2 * n :], u[..., :n], u[..., n : 2 * n]
        else:
            u = self._rows
            for rng, rows in zip(self.rngs, u, strict=True):
                rng.random(out=rows)  # the same numbers as the single model's block draws
            order, a, b = u[..., lay.order], u[..., lay.move_a], u[..., lay.move_b]
        slot = _ranks(order)  # slot[..., i]: when object i is updated
        move_a = np.take_along_axis(a, slot, axis=-1)
        move_b = np.take_along_axis(b, slot, axis=-1)
        move_x, move_y = unit_noise(move_a, move_b, self.params.noise_model)
        if streams is not None:
            self.noise = (move_x, move_y)
        else:  # kick noise is shaped when a kick happens (kicks are few)
            self.noise = (
                move_x,
                move_y,
                turn_factor(u[..., lay.turn], self.params.player_rand),
                u[..., lay.kick_a].copy(),
                u[..., lay.kick_b].copy(),
            )
        self._block_row = 0

    def _needed_offsets(self) -> np.ndarray:
        """Offsets in a block of the columns every cycle uses: move_a, move_b, then order."""
        lay = self._layout
        cols = np.r_[
            np.arange(lay.move_a.start, lay.move_a.stop),
            np.arange(lay.move_b.start, lay.move_b.stop),
            np.arange(lay.order.start, lay.order.stop),
        ]
        rows = np.arange(BATCH_BLOCK_CYCLES)[:, None] * lay.width
        offsets: np.ndarray = rows + cols
        return offsets

    def _uniforms_at(self, r: int, column: int, trials: np.ndarray) -> np.ndarray:
        """The draw of cycle `r` of the block, column `column`, for `trials` (indices)."""
        assert self.streams is not None
        offset = self._block_start[trials] - self.streams.positions[trials]
        offset += r * self._layout.width + column
        drawn: np.ndarray = self.streams.peek(offset.reshape(-1, 1), trials)[:, 0]
        return drawn

    def turn_noise(self, r: int, i: int, m: np.ndarray) -> np.ndarray:
        """``1 + ξ`` of player row `i`'s turn at block cycle `r` (where `m`; 1 elsewhere)."""
        if self.streams is None:
            noise: np.ndarray = self.noise[2][:, r, i - 1]
            return noise
        factor = np.ones(self.k)
        trials = np.flatnonzero(m)
        u = self._uniforms_at(r, self._layout.turn.start + i - 1, trials)
        factor[trials] = turn_factor(u, self.params.player_rand)
        return factor

    def kick_uniforms(self, r: int, i: int, idx: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The two kick-noise draws of player row `i` at block cycle `r` in trials `idx`."""
        if self.streams is None:
            return self.noise[3][idx, r, i - 1], self.noise[4][idx, r, i - 1]
        lay = self._layout
        return (
            self._uniforms_at(r, lay.kick_a.start + i - 1, idx),
            self._uniforms_at(r, lay.kick_b.start + i - 1, idx),
        )


def _ranks(keys: np.ndarray) -> np.ndarray:
    """Position of each key in its row's stable ascending order (the inverse of argsort)."""
    n = keys.shape[-1]
    ranks = np.zeros(keys.shape, dtype=np.intp)
    for i in range(n):
        for j in range(n):
            if j < i:
                ranks[..., i] += keys[..., j] <= keys[..., i]
            elif j > i:
                ranks[..., i] += keys[..., j] < keys[..., i]
    return ranks
