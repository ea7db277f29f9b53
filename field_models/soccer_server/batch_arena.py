"""The Soccer Server's batch arena: the batch dynamics with the see timer and see geometry.

:class:`SoccerServerBatchArena` is :class:`~field_models.soccer_server.batch.BatchSoccerServer`
with the see timer and :mod:`~field_models.soccer_server.batch_sensing`; it satisfies
:class:`field_models.batch_arena.BatchArena`. Every trial draws its movement noise from its own
counter-based "movement" stream (:class:`~field_models.seeding.StreamBatch`), so trial k gives
the numbers of a one-trial :class:`~field_models.soccer_server.arena.SoccerServerArena` built
with the same trial's streams.

It has no neck and one view for every player (the preset's): it takes turn, dash and kick
arrays, never actions, and the batched drills' vectorised minds (the interception drill's)
have no ``turn_neck`` or ``change_view`` to send. A drill whose minds look with the neck runs
on the one-trial arena.
"""

from __future__ import annotations

from field_models.batch_arena import Array, Mask
from field_models.protocol import PlayerRef
from field_models.seeding import StreamBatch
from field_models.soccer_server.arena import see_schedule
from field_models.soccer_server.batch import BatchSoccerServer
from field_models.soccer_server.batch_sensing import see_object
from field_models.soccer_server.params import ServerPreset
from field_models.soccer_server.see_timing import SeeTimer


def batch_reason(preset: ServerPreset) -> str | None:
    """Why this preset has no batch form (None: it has one)."""
    if preset.dynamics.swept_ball_collisions:
        return "the batch dynamics do not support swept ball collisions"
    return None


class SoccerServerBatchArena(BatchSoccerServer):
    """K Soccer Server trials with their see timer and see geometry (module docstring)."""

    def __init__(
        self, preset: ServerPreset, players: tuple[PlayerRef, ...], movement: StreamBatch
    ) -> None:
        super().__init__(preset, players, movement)
        self._schedule = see_schedule(preset.sensing)
        self._timer = SeeTimer(preset.sensing)

    def sees_now(self) -> bool:
        """Whether sees are sent in this cycle (every player's timer has phase 0)."""
        cycle = self.cycle
        return self._schedule[cycle] if cycle < len(self._schedule) else self._timer.due(cycle)

    def see(self, observer: int, target: int) -> tuple[Mask, Array, Array]:
        """What player `observer`'s percept holds of object `target` (0: the ball)."""
        return see_object(
            self.preset.sensing,
            (self.x[:, observer], self.y[:, observer], self.heading[:, observer]),
            (self.x[:, target], self.y[:, target]),
        )
