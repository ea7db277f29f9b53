"""When a player receives a see message: rcssserver's visual timer (spec §3.1).

:class:`SeeTimer` counts in milliseconds as the server does (its asynchronous visual timer;
synch-see mode is not modelled).
"""

from __future__ import annotations

from dataclasses import dataclass, field

from field_models.soccer_server.sensing_params import QUALITY_FACTOR, WIDTH_FACTOR, SensingParams


def visual_send_interval(params: SensingParams) -> int:
    """Visual-timer ticks between two sees: 4 at normal width and high quality (§3.1)."""
    factor = WIDTH_FACTOR[params.view_width] * QUALITY_FACTOR[params.view_quality]
    return max(1, round(4 * factor))


@dataclass(frozen=True, slots=True)
class SeeTimer:
    """On which 100 ms cycles a player receives a see message, counted in ms as the server does.

    The server's visual timer fires at the first multiple of ``recv_step`` (10 ms) at or after
    each multiple of ``send_step / 4`` ms; a player's see goes out every
    :func:`visual_send_interval` timer ticks (4 at normal width, high quality), so the interval
    is ``send_step`` ms at normal width. A see fired at time t ms belongs to cycle
    ``floor(t / simulator_step)`` and shows the state after that cycle's step (the step at
    t = 100·c runs before the sensors at the same instant). With ``send_step`` = 150 the cycles
    alternate gaps of 1 and 2 (1, 3, 4, 6, 7, ...); with 500 a see comes every 5 cycles.

    Attributes:
        params: Sensing parameters (send_step, recv_step, simulator_step, view width/quality).
        phase: Timer ticks by which this player's sees are offset (the server's send counter
            starts when the player connects): 0 .. interval - 1.
    """

    params: SensingParams
    phase: int = 0
    _interval: int = field(init=False, repr=False)

    def __post_init__(self) -> None:
        interval = visual_send_interval(self.params)
        if not 0 <= self.phase < interval:
            raise ValueError(f"phase: expected 0..{interval - 1}; got {self.phase}")
        object.__setattr__(self, "_interval", interval)

    def ticks_by(self, t_ms: int) -> int:
        """Visual-timer ticks that have fired at or before time `t_ms` (ticks k = 1, 2, ...)."""
        if t_ms < 0:
            return 0
        recv = self.params.recv_step_ms
        t_floor = (t_ms // recv) * recv
        # Tick k fires at ceil_recv(k * send_step / 4) <= T  <=>  4 k <= 4 floor_recv(T) / s.
        return (4 * t_floor) // self.params.send_step_ms

    def sees_by(self, t_ms: int) -> int:
        """This player's sees sent at or before `t_ms` (at ticks phase + j·interval, j >= 1)."""
        ticks = self.ticks_by(t_ms)
        return max(0, (ticks - self.phase) // self._interval)

    def sees_in_cycle(self, cycle: int) -> int:
        """How many sees this player gets during `cycle` (0, 1, or more for short intervals)."""
        step = self.params.simulator_step_ms
        return self.sees_by(step * (cycle + 1) - 1) - self.sees_by(step * cycle - 1)

    def due(self, cycle: int) -> bool:
        """True when at least one see is sent during `cycle`."""
        return self.sees_in_cycle(cycle) > 0

    def see_cycles(self, first: int, last: int) -> list[int]:
        """The cycles in ``[first, last]`` that carry a see (each once)."""
        return [c for c in range(first, last + 1) if self.due(c)]
