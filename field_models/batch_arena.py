"""Many trials of one field stepped together as arrays: the batch arena interface.

A field model may offer a batch form of its arena (:func:`field_models.registry.
make_batch_arena`). Where the one-trial :class:`~field_models.arena.Arena` hands each client a
percept object, a batch arena holds K trials' truth as arrays and answers the see questions a
batched drill asks of them, with exactly the numbers the one-trial arena gives for the same
trial streams. Today the Soccer Server model has one
(:mod:`field_models.soccer_server.batch_arena`); the robot table's pymunk world does not.

Rows: 0 is the ball, 1..N the players in the order given. Positions in metres, velocities in
metres per tick, headings in radians (counter-clockwise), commands in the server's action
vocabulary (dash power, turn angle, kick power and direction); every command takes a mask of
the trials it applies to.
"""

from __future__ import annotations

from typing import Protocol

import numpy as np
import numpy.typing as npt

Array = npt.NDArray[np.float64]
Mask = npt.NDArray[np.bool_]


class BatchArena(Protocol):
    """K trials of one field and preset, stepped together (module docstring)."""

    k: int
    """Trials held."""
    cycle: int
    """Ticks stepped (every trial steps together)."""
    x: Array
    y: Array
    vx: Array
    vy: Array
    heading: Array
    score_left: npt.NDArray[np.int_]
    score_right: npt.NDArray[np.int_]

    def move_ball(
        self, x: Array | float, y: Array | float, vx_mps: Array | float = 0.0,
        vy_mps: Array | float = 0.0,
    ) -> None:  # fmt: skip
        """The coach puts the ball at (x, y) with a velocity [m/s], in every trial."""
        ...

    def move_player(
        self, row: int, x: Array | float, y: Array | float, heading: Array | float
    ) -> None:
        """The coach puts player `row` at rest at (x, y) facing `heading`, in every trial."""
        ...

    def dash(self, row: int, power: float, direction_rad: float, mask: Mask) -> Mask:
        """Queue a dash for player `row` in the trials of `mask`."""
        ...

    def turn(self, row: int, angle_rad: Array, mask: Mask) -> Mask:
        """Queue a turn for player `row` in the trials of `mask`."""
        ...

    def kick(self, row: int, power: float, direction_rad: Array, mask: Mask) -> Mask:
        """Queue a kick for player `row` in the trials of `mask`."""
        ...

    def step(self) -> list[tuple[int, str]]:
        """One tick of every trial; the referee's messages as (trial, text)."""
        ...

    def sees_now(self) -> bool:
        """Whether the players' percepts are due at this tick (the same in every trial)."""
        ...

    def see(self, observer: int, target: int) -> tuple[Mask, Array, Array]:
        """What player `observer`'s percept holds of object `target` in every trial.

        Returns (in the percept, distance [m], angle [rad, CCW from the heading]).
        """
        ...

    def keep(self, trials: npt.NDArray[np.intp]) -> None:
        """Go on with these trials only (compaction); numbering restarts at 0."""
        ...
