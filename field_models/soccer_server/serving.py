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
"""

from __future__ import annotations

import contextlib
import itertools
import math
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Literal

from field_models.arena import COMMAND_COUNTERS, CommandTally
from field_models.commands import CommandParseError
from field_models.commands import parse_command as parse_action
from field_models.protocol import LEFT, RIGHT, Action, BodyState, PlayerRef, Say
from field_models.seeding import TrialRngs
from field_models.soccer_server.cycle_rules import PLAY_MODES
from field_models.soccer_server.dynamics import SoccerServerModel
from field_models.soccer_server.hearing import HearInfo, deliver_says, say_allowed
from field_models.soccer_server.messages import SExpr, render_hear, render_see
from field_models.soccer_server.params import ServerPreset
from field_models.soccer_server.see_timing import SeeTimer
from field_models.soccer_server.sensing import SeeInfo, observe
from field_models.soccer_server.sensing_params import SensingParams
from field_models.soccer_server.wire import (
    ILLEGAL_FORM,
    PLAYERS_PER_TEAM,
    SLOTS,
    TRAINER_MODES,
    UNKNOWN,
    BodySense,
    CommandError,
    ShowPlayer,
    global_objects,
    number,
    numbers,
    param_messages,
    parse_command,
    parse_player_init,
    render_sense_body,
    render_show,
    split_commands,
    word,
)

ClientKind = Literal["player", "trainer", "monitor"]
"""Who a client is."""
Log = Callable[[str], None]
"""Where the game writes a line about something worth knowing (a refused datagram, a join)."""

NOT_MODELLED = frozenset(
    (
        "turn_neck",
        "catch",
        "tackle",
        "pointto",
        "attentionto",
        "change_focus",
        "synch_see",
        "ear",
        "clang",
        "gaussian_see",
    )
)
"""Player commands rcssserver knows and the model does not: answered ``unknown_command``."""
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
_SHOW_ORDER = tuple(COUNTERS.index(name) if name in COUNTERS else -1 for name in COMMAND_COUNTERS)
_MOVE_MODES = ("before_kick_off", "goal_l", "goal_r")
_WIDTHS = ("narrow", "normal", "wide")
_QUALITIES = ("high", "low")
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


class ServedGame:
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
            counts = tuple(client.counts[i] if i >= 0 else 0 for i in _SHOW_ORDER)
            took = self.model.kicked_at[self.model.row(ref)] == tick
            out[ref] = CommandTally(counts, kicked=took, kick_missed=client.kicked_now and not took)
        return out

    # ------------------------------------------------------------------ joining

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

    def _name(self, client: Client) -> str:
        if client.ref is None:
            return f"#{client.id}"
        return f"{self.teams[0 if client.ref.team == LEFT else 1]} {client.ref.number}"

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

    # ------------------------------------------------------------------ messages

    def receive(self, client: Client, text: str) -> None:
        """A datagram from a connected client: every command in it, in order.

        Never raises: a refused command is answered (``(error ...)``) and logged, and the
        commands after it in the same datagram are not run (as the server stops parsing).
        """
        try:
            for command in split_commands(text):
                tree = parse_command(command)
                if client.kind == "player":
                    self._player_command(client, tree, command)
                elif client.kind == "trainer":
                    self._trainer_command(client, tree)
                else:
                    self._monitor_command(client, tree)
                if client.kind == "player" and client.ref not in self.players:
                    return  # it said bye
        except CommandError as exc:
            self._send(client, exc.reply)
            self.log(
                f"{client.kind} {self._name(client)}: {exc.detail or exc.reply}: {text!r:.200}"
            )

    def _player_command(self, client: Client, tree: list[SExpr], text: str) -> None:
        name = tree[0]
        if name in ("turn", "dash", "kick", "say"):
            try:
                action = parse_action(text)
            except CommandParseError as exc:
                raise CommandError(ILLEGAL_FORM, exc.reason) from None
            if isinstance(action, Say):
                self._say(client, action.text)
            elif client.pending is None:
                client.pending = action  # the first body command of a cycle wins (§1.1)
        elif name == "move":
            self._player_move(client, numbers(tree[1:], 2, 2))
        elif name == "change_view":
            self._change_view(client, tree[1:])
        elif name == "sense_body":
            self._send(client, self._sense_body(client))
        elif name == "score":
            ours, theirs = self.score()
            if client.ref is not None and client.ref.team == RIGHT:
                ours, theirs = theirs, ours
            self._send(client, f"(score {self.time} {ours} {theirs})")
        elif name == "done":
            client.done = True
        elif name == "bye":
            self.leave(client, "bye")
        elif name == "compression":
            self._send(client, "(warning compression_unsupported)")
        elif name in NOT_MODELLED:
            raise CommandError(UNKNOWN, f"{name} is not modelled")
        else:
            raise CommandError(UNKNOWN, f"unknown command {name!r}")

    def _say(self, client: Client, text: str) -> None:
        if len(text) > self.preset.sensing.say_msg_size:
            return  # the server drops a long message without a word (Player::say)
        if not say_allowed(text, self.preset.sensing):
            raise CommandError(ILLEGAL_FORM, "a character a say may not hold")
        assert client.ref is not None
        self.model.say(self.model.row(client.ref), text)
        client.counts[COUNTERS.index("say")] += 1

    def _player_move(self, client: Client, xy: list[float]) -> None:
        if self.model.play_mode not in _MOVE_MODES or client.ref is None:
            return  # rcssserver ignores a move in other modes
        side = 1.0 if client.ref.team == LEFT else -1.0
        if (
            self.model.play_mode == "before_kick_off"
            and xy[0] >= -self.preset.dynamics.player_size_m
        ):
            self._send(client, "(warning moving_to_opponent_field)")
        row = self.model.row(client.ref)
        self.model.move_player(row, xy[0] * side, -xy[1] * side, self.model.heading[row])
        client.counts[COUNTERS.index("move")] += 1

    def _change_view(self, client: Client, args: list[SExpr]) -> None:
        if not 1 <= len(args) <= 2:
            raise CommandError(ILLEGAL_FORM, "change_view Width [Quality]")
        width = word(args[0])
        quality = word(args[1]) if len(args) == 2 else "high"
        if width not in _WIDTHS or quality not in _QUALITIES:
            raise CommandError(ILLEGAL_FORM, f"view {width} {quality}")
        assert client.sensing is not None
        client.sensing = client.sensing.replace(view_width=width, view_quality=quality)
        client.timer = SeeTimer(client.sensing)
        client.counts[COUNTERS.index("change_view")] += 1

    def _trainer_command(self, client: Client, tree: list[SExpr]) -> None:
        name, args = tree[0], tree[1:]
        if name == "move":
            self._trainer_move(client, args)
        elif name == "change_mode":
            self._change_mode(client, args)
        elif name == "look":
            self._send(client, f"(ok look {self.time} {self._global(client)})")
        elif name in ("eye", "ear"):
            if len(args) != 1 or args[0] not in ("on", "off"):
                raise CommandError(ILLEGAL_FORM, f"{name} on|off")
            setattr(client, str(name), args[0] == "on")
            self._send(client, f"(ok {name} {args[0]})")
        elif name == "recover":
            self._send(client, "(ok recover)")  # stamina is not modelled: nothing to restore
        elif name == "start":
            if self.model.play_mode == "before_kick_off":
                self.model.change_mode("kick_off_l")
            self._send(client, "(ok start)")
        elif name == "check_ball":
            self._send(client, f"(ok check_ball {self.time} {self._ball_place()})")
        elif name == "team_names":
            teams = [f"(team {s} {n})" for s, n in zip("lr", self.teams, strict=True) if n]
            self._send(client, "(ok team_names" + "".join(" " + t for t in teams) + ")")
        elif name == "say":
            if not args:
                raise CommandError(ILLEGAL_FORM, "say Message")
            self._says_by_trainer.append(" ".join(str(a) for a in args if not isinstance(a, list)))
            self._send(client, "(ok say)")
        elif name == "done":
            client.done = True
        elif name == "compression":
            self._send(client, "(warning compression_unsupported)")
        elif name == "change_player_type":
            raise CommandError(UNKNOWN, "heterogeneous players are not modelled")
        else:
            raise CommandError(UNKNOWN, f"unknown trainer command {name!r}")

    def _trainer_move(self, client: Client, args: list[SExpr]) -> None:
        """``(move (ball) X Y [Dir [VX VY]])`` / ``(move (player Team Unum) X Y [Dir [VX VY]])``."""
        if not args or not isinstance(args[0], list):
            raise CommandError("(error illegal_object_form)", "move what")
        what, rest = args[0], args[1:]
        if len(rest) not in (2, 3, 5):
            raise CommandError(ILLEGAL_FORM, "move Object X Y [Dir [VX VY]]")
        values = numbers(rest, 2, 5)
        x, y = values[0], -values[1]
        dt = self.dt_s
        vx, vy = (values[3] / dt, -values[4] / dt) if len(values) == 5 else (0.0, 0.0)
        if what == ["ball"]:
            self.model.move_ball(x, y, vx, vy)
        elif len(what) == 3 and what[0] == "player":
            team, unum = word(what[1]), number(what[2])
            ref = self._ref_of(team, unum)
            if ref is not None:
                row = self.model.row(ref)
                p = self.preset.dynamics
                heading = self.model.heading[row]
                if len(values) >= 3:
                    deg = max(
                        math.degrees(p.minmoment_rad), min(values[2], math.degrees(p.maxmoment_rad))
                    )
                    heading = -math.radians(deg)
                self.model.move_player(row, x, y, heading, vx, vy)
            else:
                self.log(f"trainer moved {team} {unum:g}, who is not on the field")
        else:
            raise CommandError("(error illegal_object_form)", "move (ball) or (player Team Unum)")
        self._send(client, "(ok move)")

    def _ref_of(self, team: str, unum: float) -> PlayerRef | None:
        if team not in self.teams or unum != int(unum):
            return None
        ref = PlayerRef(LEFT if self.teams[0] == team else RIGHT, int(unum))
        return ref if ref in self.players else None

    def _change_mode(self, client: Client, args: list[SExpr]) -> None:
        if len(args) != 1 or isinstance(args[0], list):
            raise CommandError(ILLEGAL_FORM, "change_mode Mode")
        mode = str(args[0])
        if mode not in PLAY_MODES:
            why = "not modelled" if mode in TRAINER_MODES else "unknown"
            raise CommandError("(error illegal_mode)", f"play mode {mode!r} is {why}")
        self.model.change_mode(mode)
        self._send(client, "(ok change_mode)")

    def _monitor_command(self, client: Client, tree: list[SExpr]) -> None:
        name = tree[0]
        if name == "dispstart":
            if self.model.play_mode == "before_kick_off":
                self.model.change_mode("kick_off_l")
        elif name == "dispbye":
            self.leave(client, "dispbye")
        elif name == "dispinit":
            pass  # a monitor repeating its init: already joined
        else:
            raise CommandError(ILLEGAL_FORM, f"monitor command {name!r}")

    def _ball_place(self) -> str:
        p = self.preset.dynamics
        x, y = self.model.x[0], self.model.y[0]
        line = 0.5 * p.pitch_length_m + p.ball_size_m
        if abs(x) > line:
            if abs(y) <= 0.5 * p.goal_width_m + p.goal_post_radius_m:
                return "goal_r" if x > 0 else "goal_l"
            return "out_of_field"
        if abs(y) > 0.5 * p.pitch_width_m + p.ball_size_m:
            return "out_of_field"
        return "in_field"

    # ------------------------------------------------------------------ the cycle

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
        )
        return render_sense_body(self.time, client.version, sense)

    def _see(self, client: Client) -> str:
        m = self.model
        assert client.ref is not None and client.sensing is not None
        info = observe(
            m.row(client.ref), m.x, m.y, m.vx, m.vy, m.heading, m.players, m.cycle,
            client.sensing, self._see_rng, landmarks="all",
        )  # fmt: skip
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
            shown = tuple(counts[i] if i >= 0 else 0 for i in _SHOW_ORDER)
            kicked = client is not None and client.kicked_now
            slots.append(ShowPlayer(players.get(ref), shown, kicked))
        visible = math.degrees(2.0 * self.preset.sensing.view_half_angle_rad)
        return render_show(
            self.time, self.model.play_mode, (self.teams[0], self.teams[1]), self.score(),
            ball, slots, self.dt_s, visible_angle_deg=visible, version=int(monitor.version),
        )  # fmt: skip

    def _send(self, client: Client, text: str) -> None:
        self._out.append((client, text))
