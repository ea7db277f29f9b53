"""Clients joining and leaving the served game: players, the trainer, monitors.

Players join with ``(init Team (version V) [(goalie)])`` (the first team named takes the left
side, uniform numbers count up from 1, 11 a side) or ``(reconnect Team Unum)`` outside
``play_on``; one trainer with ``(init (version V))``; monitors with ``(dispinit version 3)``
or 4 (rcssserver 19.0.0's ``src/stadium.cpp``). The model is rebuilt with the connected players
whenever one joins or leaves, state, clock, mode and score carried.
"""

from __future__ import annotations

from typing import Literal

from field_models.protocol import LEFT, RIGHT, BodyState, PlayerRef
from field_models.soccer_server.dynamics import SoccerServerModel
from field_models.soccer_server.messages import SExpr
from field_models.soccer_server.see_timing import SeeTimer
from field_models.soccer_server.serving_state import MAX_MONITORS, Client, GameState
from field_models.soccer_server.wire import (
    ILLEGAL_FORM,
    PLAYERS_PER_TEAM,
    SLOTS,
    UNKNOWN,
    CommandError,
    number,
    param_messages,
    parse_command,
    parse_player_init,
    split_commands,
    word,
)


class ClientRoster(GameState):
    """The served game's clients coming and going (see the module docstring)."""

    def join(self, kind: Literal["player", "trainer"], text: str) -> tuple[Client | None, str]:
        """A first datagram from a new address: a client joins, or the error reply comes back.

        On the player port it may be a player's ``init``/``reconnect`` or a monitor's
        ``dispinit``; on the trainer port the trainer's ``init``. On success the reply and the
        parameters are queued for the client (:meth:`drain`) and the returned text is empty.
        """
        try:
            commands = split_commands(text)
            tree = parse_command(commands[0])
            if kind == "trainer":
                return self._join_trainer(tree), ""
            name = tree[0]
            if name == "dispinit":
                return self._join_monitor(tree), ""
            if name == "init":
                return self._join_player(tree), ""
            if name == "reconnect":
                return self._reconnect(tree), ""
            raise CommandError(UNKNOWN, f"{name!r} before init")
        except CommandError as exc:
            self.log(f"refused a new {kind} client: {exc}")
            return None, exc.reply

    def _join_player(self, tree: list[SExpr]) -> Client:
        init = parse_player_init(tree)
        side = self._side_for(init.team)
        free = [n for n in range(1, PLAYERS_PER_TEAM + 1) if PlayerRef(side, n) not in self.players]
        if not free:
            raise CommandError("(error no_more_player_or_goalie_or_illegal_client_version)", "")
        ref = PlayerRef(side, free[0])
        client = self._new_player(ref, init.version)
        letter = "l" if side == LEFT else "r"
        self._send(client, f"(init {letter} {ref.number} {self.model.play_mode})")
        for message in param_messages(self.preset, init.version, self.overrides):
            self._send(client, message)
        self.log(f"player {init.team} {ref.number} (v{init.version:g}) joined on side {letter}")
        return client

    def _side_for(self, team: str) -> str:
        for i, name in enumerate(self.teams):
            if name == team:
                return LEFT if i == 0 else RIGHT
        for i, name in enumerate(self.teams):
            if name is None:
                self.teams[i] = team
                return LEFT if i == 0 else RIGHT
        raise CommandError("(error no_more_team)", team)

    def _reconnect(self, tree: list[SExpr]) -> Client:
        if self.model.play_mode == "play_on":
            raise CommandError("(error cannot_reconnect_while_playon)", "")
        if len(tree) != 3:
            raise CommandError(ILLEGAL_FORM, "reconnect Team Unum")
        team, unum = word(tree[1]), number(tree[2])
        if team not in self.teams or unum != int(unum) or not 1 <= unum <= PLAYERS_PER_TEAM:
            raise CommandError("(error no_such_team_or_player)", f"{team} {unum:g}")
        side = LEFT if self.teams[0] == team else RIGHT
        ref = PlayerRef(side, int(unum))
        old = self.players.get(ref)
        version = old.version if old is not None else 3.0
        if old is not None:
            self.leave(old, "replaced by a reconnect")
        client = self._new_player(ref, version)
        letter = "l" if side == LEFT else "r"
        self._send(client, f"(reconnect {letter} {self.model.play_mode})")
        self.log(f"player {team} {ref.number} reconnected")
        return client

    def _new_player(self, ref: PlayerRef, version: float) -> Client:
        protocol = max(1, min(19, int(version)))
        sensing = self.preset.sensing.replace(
            protocol_version=protocol, direction_mode="round" if protocol >= 7 else "truncate"
        )
        client = Client(next(self._ids), "player", version, ref, sensing, SeeTimer(sensing))
        self.players[ref] = client
        side = 1 if ref.team == LEFT else -1
        # rcssserver parks an idle player at (-3·unum·side, -37) (server frame, y down).
        self._rebuild({ref: BodyState(-3.0 * ref.number * side, 37.0, 0.0)})
        return client

    def _join_trainer(self, tree: list[SExpr]) -> Client:
        if self.trainer is not None:
            raise CommandError("(error already_have_offline_coach)", "")
        if tree[0] != "init":
            raise CommandError(ILLEGAL_FORM, "a trainer starts with (init (version V))")
        version = 3.0
        for option in tree[1:]:
            if isinstance(option, list) and len(option) == 2 and option[0] == "version":
                version = number(option[1])
            else:
                raise CommandError(ILLEGAL_FORM, "trainer init option")
        client = Client(next(self._ids), "trainer", version)
        self.trainer = client
        self._send(client, "(init ok)")
        for message in param_messages(self.preset, version, self.overrides):
            self._send(client, message)
        self.log(f"trainer (v{version:g}) joined")
        return client

    def _join_monitor(self, tree: list[SExpr]) -> Client:
        if len(tree) != 3 or tree[1] != "version":
            raise CommandError("(error illegal_client_version)", "binary monitor protocols")
        version = number(tree[2])
        if version not in (3.0, 4.0):
            raise CommandError("(error illegal_client_version)", f"monitor v{version:g}")
        if len(self.monitors) >= MAX_MONITORS:
            raise CommandError("(error no_more_monitor)", f"{MAX_MONITORS} monitors already")
        client = Client(next(self._ids), "monitor", version)
        self.monitors.append(client)
        for message in param_messages(self.preset, 999, self.overrides):
            self._send(client, message)
        self._send(client, self._show(client))
        self.log(f"monitor (v{version:g}) joined")
        return client

    def leave(self, client: Client, why: str) -> None:
        """A client is gone (``bye``, a timeout, a reconnect over it)."""
        if client.kind == "player" and client.ref is not None:
            if self.players.get(client.ref) is client:
                del self.players[client.ref]
                self._rebuild({})
        elif client.kind == "trainer" and self.trainer is client:
            self.trainer = None
        elif client in self.monitors:
            self.monitors.remove(client)
        self.log(f"{client.kind} {self._name(client)} left: {why}")

    def _rebuild(self, new: dict[PlayerRef, BodyState]) -> None:
        """A model with the connected players, carrying the old one's state (module docstring)."""
        old = self.model
        refs = tuple(ref for ref in SLOTS if ref in self.players)
        m = SoccerServerModel(self.preset, refs, self._movement)
        m.cycle, m.score_left, m.score_right = old.cycle, old.score_left, old.score_right
        m.play_mode = old.play_mode
        m._after_goal_cycles = old._after_goal_cycles  # the after-goal pause goes on
        rows = {ref: i + 1 for i, ref in enumerate(refs)}
        for ref, row in [(None, 0), *rows.items()]:
            if ref is None or ref in old.players:
                j = 0 if ref is None else old.row(ref)
                m.x[row], m.y[row], m.vx[row], m.vy[row] = old.x[j], old.y[j], old.vx[j], old.vy[j]
                m.heading[row] = old.heading[j]
                m.kicked_at[row] = old.kicked_at[j]
            elif ref in new:
                st = new[ref]
                m.x[row], m.y[row], m.heading[row] = st.x, st.y, st.heading
        self.model = m
