"""The served game's state: its clients, its model, what can be read and what it sends.

:class:`GameState` is the base of :class:`~field_models.soccer_server.serving.ServedGame`: the
clients (:class:`Client`) and the model, the read-outs the transport and the CLI use, and the
messages that render the state for one client (``sense_body``, a trainer's global view, a
monitor's ``show``). Joining and leaving are :mod:`~field_models.soccer_server.serving_clients`',
the clients' commands :mod:`~field_models.soccer_server.serving_commands`' and the cycle
:mod:`~field_models.soccer_server.serving`'s.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Literal

from field_models.arena import COMMAND_COUNTERS, CommandTally
from field_models.protocol import LEFT, RIGHT, Action, BodyState, PlayerRef
from field_models.seeding import TrialRngs
from field_models.soccer_server.dynamics import SoccerServerModel
from field_models.soccer_server.params import ServerPreset
from field_models.soccer_server.see_timing import SeeTimer
from field_models.soccer_server.sensing_params import SensingParams
from field_models.soccer_server.wire import (
    SLOTS,
    BodySense,
    global_objects,
    render_sense_body,
)
from field_models.soccer_server.wire_show import Show, ShowPlayer, render_show

ClientKind = Literal["player", "trainer", "monitor"]
"""Who a client is."""
Log = Callable[[str], None]
"""Where the game writes a line about something worth knowing (a refused datagram, a join)."""

MAX_MONITORS = 8
"""Most monitors at once. rcssserver's ``max_monitors`` defaults to no limit; each monitor
costs a show every cycle, so a flood of ``dispinit`` could stall the server: ours stops at 8."""
COUNTERS = (
    "kick",
    "dash",
    "turn",
    "say",
    "turn_neck",
    "catch",
    "move",
    "change_view",
    "change_focus",
)
"""A player's command counters, in sense_body order."""
SHOW_ORDER = tuple(COUNTERS.index(name) if name in COUNTERS else -1 for name in COMMAND_COUNTERS)
"""Where each of :data:`~field_models.arena.COMMAND_COUNTERS` is in :data:`COUNTERS` (-1: not)."""
_INITIAL_STAMINA = (8000.0, 1.0, 130600.0)  # not modelled: the server's initial values


@dataclass(eq=False)
class Client:
    """One connected client and what the game keeps about it.

    Attributes:
        id: A number unique in this game (the transport maps it to an address and socket).
        kind: Player, trainer or monitor.
        version: The protocol version it asked for.
        ref: A player's slot (``LEFT``/``RIGHT`` and its uniform number).
        sensing: A player's sensing parameters (its protocol, view width and quality).
        counts: A player's command counters (:data:`COUNTERS`).
        pending: A player's body action for the next step (the first of a cycle wins).
        done: Sent ``(done)`` since the last step (synch mode).
        eye, ear: A trainer's ``eye`` and ``ear`` switches.
        last_seen: When it last sent something [s, the transport's clock].
    """

    id: int
    kind: ClientKind
    version: float
    ref: PlayerRef | None = None
    sensing: SensingParams | None = None
    timer: SeeTimer | None = None
    counts: list[int] = field(default_factory=lambda: [0] * len(COUNTERS))
    pending: Action | None = None
    kicked_now: bool = False
    done: bool = False
    eye: bool = False
    ear: bool = False
    last_seen: float = 0.0


class GameState:
    """The served Soccer Server's state: its clients and model, read-outs and rendered messages.

    Args:
        preset: The server preset (options applied).
        seed: Seeds the model's movement and sensing noise (trial 0 of this seed).
        rngs: The streams to draw that noise from instead (a trial's own, for an arena).
        synch: Synch mode: players (and a trainer with ``eye on``) get ``(think)`` after each
            cycle's sensors, and :meth:`ready` says when all of them answered ``(done)``.
        log: Where lines about joins, leaves and refused messages go.
        overrides: Server parameters reported beyond the preset's (ports, ``synch_mode``).
        start_mode: The play mode before any trainer changes it (rcssserver's
            ``before_kick_off``).
    """

    def __init__(
        self,
        preset: ServerPreset,
        *,
        seed: int = 0,
        rngs: TrialRngs | None = None,
        synch: bool = False,
        log: Log | None = None,
        overrides: dict[str, bool | int | float | str] | None = None,
        start_mode: str = "before_kick_off",
    ) -> None:
        self.preset = preset
        self.synch = synch
        self.log: Log = log or (lambda line: None)
        self.overrides = dict(overrides or {})
        self.overrides.setdefault("synch_mode", synch)
        rngs = rngs if rngs is not None else TrialRngs.for_trial(seed, 0)
        self._movement = rngs["movement"]
        self._see_rng = rngs["sensing"]
        self.model = SoccerServerModel(preset, (), self._movement)
        if start_mode != self.model.play_mode:
            self.model.change_mode(start_mode)
        self.teams: list[str | None] = [None, None]
        self.players: dict[PlayerRef, Client] = {}
        self.trainer: Client | None = None
        self.monitors: list[Client] = []
        self._ids = itertools.count(1)
        self._out: list[tuple[Client, str]] = []
        self._says_by_trainer: list[str] = []

    # ------------------------------------------------------------------ reading

    @property
    def time(self) -> int:
        """The server's clock: cycles stepped."""
        return self.model.cycle

    @property
    def dt_s(self) -> float:
        """One cycle [s]."""
        return self.model.dt_s

    def clients(self) -> list[Client]:
        """Every connected client."""
        out: list[Client] = list(self.players.values())
        if self.trainer is not None:
            out.append(self.trainer)
        return out + self.monitors

    def drain(self) -> list[tuple[Client, str]]:
        """Messages to send since the last call, in order."""
        out, self._out = self._out, []
        return out

    def ready(self) -> bool:
        """Synch mode: every player (and an eye-on trainer) sent ``(done)``; at least one."""
        waiting = self._synched()
        return bool(waiting) and all(c.done for c in waiting)

    def has_synched(self) -> bool:
        """Synch mode: whether a client takes part in lock-step (a player, an eye-on trainer)."""
        return bool(self._synched())

    def _synched(self) -> list[Client]:
        out = list(self.players.values())
        if self.trainer is not None and self.trainer.eye:
            out.append(self.trainer)
        return out

    def truth(self) -> tuple[BodyState, dict[PlayerRef, BodyState]]:
        """The ball's and every connected player's exact state (our frame, m/s)."""
        m = self.model
        return m.ball_state(), {ref: m.player_state(m.row(ref)) for ref in m.players}

    def score(self) -> tuple[int, int]:
        """Goals of the left and the right team."""
        return self.model.score_left, self.model.score_right

    @property
    def play_mode(self) -> str:
        """The current play mode, as the server spells it."""
        return self.model.play_mode

    def team_names(self) -> tuple[str | None, str | None]:
        """The left and the right team's names (None: no player of that side joined yet)."""
        return self.teams[0], self.teams[1]

    def command_tally(self) -> dict[PlayerRef, CommandTally]:
        """Every connected player's command counts, and whether its last kick reached the ball.

        Counts in :data:`~field_models.arena.COMMAND_COUNTERS` order (a monitor's and a log's).
        """
        tick = self.model.cycle
        out = {}
        for ref, client in self.players.items():
            counts = tuple(client.counts[i] if i >= 0 else 0 for i in SHOW_ORDER)
            took = self.model.kicked_at[self.model.row(ref)] == tick
            out[ref] = CommandTally(counts, kicked=took, kick_missed=client.kicked_now and not took)
        return out

    # ------------------------------------------------------------------ rendering

    def _sense_body(self, client: Client) -> str:
        m = self.model
        assert client.ref is not None and client.sensing is not None
        row = m.row(client.ref)
        sense = BodySense(
            m.vx[row],
            m.vy[row],
            m.heading[row],
            client.sensing.view_quality,
            client.sensing.view_width,
            *_INITIAL_STAMINA[:2],
            _INITIAL_STAMINA[2],
            tuple(client.counts),
            m.neck[row],
        )
        return render_sense_body(self.time, client.version, sense)

    def _global(self, client: Client) -> str:
        ball, players = self.truth()
        names = {LEFT: self.teams[0] or LEFT, RIGHT: self.teams[1] or RIGHT}
        return global_objects(ball, players, names, self.dt_s, client.version)

    def _show(self, monitor: Client) -> str:
        ball, players = self.truth()
        slots = []
        for ref in SLOTS:
            client = self.players.get(ref)
            counts = client.counts if client is not None else [0] * len(COUNTERS)
            shown = tuple(counts[i] if i >= 0 else 0 for i in SHOW_ORDER)
            kicked = client is not None and client.kicked_now
            slots.append(ShowPlayer(players.get(ref), shown, kicked))
        visible = math.degrees(2.0 * self.preset.sensing.view_half_angle_rad)
        teams = (self.teams[0], self.teams[1])
        show = Show(self.time, self.model.play_mode, teams, self.score(), ball, slots)
        return render_show(show, self.dt_s, visible_angle_deg=visible, version=int(monitor.version))

    def _name(self, client: Client) -> str:
        if client.ref is None:
            return f"#{client.id}"
        return f"{self.teams[0 if client.ref.team == LEFT else 1]} {client.ref.number}"

    def _send(self, client: Client, text: str) -> None:
        self._out.append((client, text))
