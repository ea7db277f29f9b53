"""The Soccer Server model as a server: clients, their commands, and what each cycle sends them.

:class:`ServedGame` is everything ``robotsoccer serve`` does except the sockets: the transport
(:mod:`~field_models.soccer_server.udp`) hands it each datagram's text with the client it came
from, calls :meth:`ServedGame.step` when a cycle is due, and sends what
:meth:`ServedGame.drain` returns. Keeping the sockets out makes every reply testable and the
fuzz test fast.

Clients (shared `specs/soccer_server.md` §5 and rcssserver 19.0.0's ``src/stadium.cpp``):

* **players** join with ``(init Team (version V) [(goalie)])`` on the player port; the first team
  named takes the left side, the second the right, uniform numbers count up from 1 (11 a side);
  ``(reconnect Team Unum)`` takes a slot of a known team outside ``play_on``; ``(bye)`` leaves.
  Each player's see and hear follow its protocol version (names, quoting, rounding).
* **one trainer** (offline coach) on the trainer port: ``(init (version V))``, then ``move``,
  ``change_mode``, ``look``, ``eye``, ``ear``, ``recover``, ``start``, ``check_ball``,
  ``team_names``, ``say``, ``done``.
* **monitors** join on the player port with ``(dispinit version 3)`` (or 4), as rcssmonitor
  does, and get the parameters and a ``show`` every cycle.

What the model does not have is answered the way rcssserver answers a command it does not know,
``(error unknown_command)``, with a log line naming it: ``turn_neck``, ``catch``, ``tackle``,
``pointto``, ``attentionto``, ``change_focus``, ``synch_see``, ``ear`` (players),
``change_player_type``. Every malformed command gets ``(error illegal_command_form)`` (or the
server's more specific error) and a log line; no text raises out of :meth:`ServedGame.receive`.

The clock is the model's cycle, which counts every step (rcssserver holds its clock in
``before_kick_off``; the model does not). Players that join are placed off the pitch where
rcssserver parks an idle player, (-3·unum·side, -37) in the server's frame. The model is rebuilt
with the connected players whenever one joins or leaves (state, clock, mode and score carried),
so sees list only connected players.

The served game is built in layers, one job each: its state, read-outs and rendered messages
(:mod:`~field_models.soccer_server.serving_state`), clients joining and leaving
(:mod:`~field_models.soccer_server.serving_clients`), the clients' commands
(:mod:`~field_models.soccer_server.serving_commands`) and, here, the cycle: commands to the
model, its step, then every client's messages of the cycle.
"""

from __future__ import annotations

import contextlib

from field_models.protocol import LEFT, RIGHT
from field_models.soccer_server.hearing import HearInfo, deliver_says
from field_models.soccer_server.messages import render_hear, render_see
from field_models.soccer_server.sensing import Bodies, SeeInfo, observe
from field_models.soccer_server.serving_commands import CommandHandling
from field_models.soccer_server.serving_state import COUNTERS, Client


class ServedGame(CommandHandling):
    """The served Soccer Server: clients in, messages out, one :meth:`step` per cycle.

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

    def step(self) -> None:
        """One cycle: commands, the model's step, then every client's messages of the cycle."""
        m = self.model
        for client in self.players.values():
            client.kicked_now = False
            action, client.pending = client.pending, None
            if action is None or client.ref is None:
                continue
            if m.command(m.row(client.ref), action):
                kind = type(action).__name__.lower()
                client.counts[COUNTERS.index(kind)] += 1
                client.kicked_now = kind == "kick"
        referee = m.step()
        for client in self.players.values():
            client.done = False
            self._send(client, self._sense_body(client))
        self._hear(m.said(), referee)
        for client in self.players.values():
            assert client.timer is not None
            if client.timer.due(m.cycle):
                self._send(client, self._see(client))
        if self.trainer is not None:
            self.trainer.done = False
            if self.trainer.eye:
                self._send(self.trainer, f"(see_global {self.time} {self._global(self.trainer)})")
        for monitor in self.monitors:
            self._send(monitor, self._show(monitor))
        if self.synch:
            for client in self._synched():
                self._send(client, "(think)")

    def _see(self, client: Client) -> str:
        m = self.model
        assert client.ref is not None and client.sensing is not None
        info = observe(
            m.row(client.ref),
            Bodies(m.x, m.y, m.vx, m.vy, m.heading, neck=m.neck),
            m.players,
            m.cycle,
            client.sensing,
            self._see_rng,
            landmarks="all",
        )
        return render_see(self._named(info), client.sensing.protocol_version)

    def _named(self, info: SeeInfo) -> SeeInfo:
        """The see with the teams' own names in place of the model's left/right."""
        names = {LEFT: self.teams[0], RIGHT: self.teams[1]}
        objects = tuple(
            obj._replace(team=names.get(obj.team) or obj.team) if obj.team is not None else obj
            for obj in info.objects
        )
        return SeeInfo(info.time, objects)

    def _hear(self, says: list[tuple[int, str]], referee: list[str]) -> None:
        m = self.model
        time = m.cycle
        full = self.preset.sensing.replace(protocol_version=19)
        heard = deliver_says(says, m.x, m.y, m.heading, m.players, time, full)
        rows = {ref: m.row(ref) for ref in m.players}
        for ref, client in self.players.items():
            infos = list(heard.get(rows[ref], []))
            infos += [HearInfo(time, "referee", msg) for msg in referee]
            infos += [HearInfo(time, "coach", msg) for msg in self._says_by_trainer]
            for info in infos:
                # A short form an old protocol cannot carry: that client hears nothing.
                with contextlib.suppress(ValueError):
                    self._send(client, render_hear(info, int(min(client.version, 19))))
        self._says_by_trainer = []
        trainer = self.trainer
        if trainer is not None and trainer.ear:
            for msg in referee:
                self._send(trainer, f"(hear referee {time} {msg})")
            for row, text in says:
                ref = m.players[row - 1]
                team = self.teams[0 if ref.team == LEFT else 1]
                self._send(trainer, f'(hear {time} (p "{team}" {ref.number}) "{text}")')
