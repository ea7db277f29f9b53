"""The clients' commands to the served game: players', the trainer's and monitors'.

Every command a client sends after joining (rcssserver 19.0.0's ``src/player.cpp``,
``src/coach.cpp``, ``src/monitor.cpp``): a player's body commands (the first of a cycle wins),
``say``, ``turn_neck`` (the first of a cycle wins), ``move``, ``change_view``, ``sense_body``,
``score``, ``done``, ``bye``; the trainer's ``move``, ``change_mode``, ``look``, ``eye``,
``ear``, ``recover``, ``start``, ``check_ball``,
``team_names``, ``say``, ``done``; a monitor's ``dispstart`` and ``dispbye``. What the model does
not have is answered ``(error unknown_command)``, a malformed command
``(error illegal_command_form)`` or the server's more specific error; nothing raises out of
:meth:`CommandHandling.receive`.
"""

from __future__ import annotations

import math

from field_models.commands import CommandParseError
from field_models.commands import parse_command as parse_action
from field_models.protocol import LEFT, RIGHT, PlayerRef, Say, TurnNeck
from field_models.soccer_server.cycle_rules import PLAY_MODES
from field_models.soccer_server.hearing import say_allowed
from field_models.soccer_server.messages import SExpr
from field_models.soccer_server.see_timing import SeeTimer
from field_models.soccer_server.serving_clients import ClientRoster
from field_models.soccer_server.serving_state import COUNTERS, Client
from field_models.soccer_server.wire import (
    ILLEGAL_FORM,
    TRAINER_MODES,
    UNKNOWN,
    CommandError,
    number,
    numbers,
    parse_command,
    split_commands,
    word,
)

_MOVE_MODES = ("before_kick_off", "goal_l", "goal_r")
_WIDTHS = ("narrow", "normal", "wide")
_QUALITIES = ("high", "low")
NOT_MODELLED = frozenset(
    (
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


class CommandHandling(ClientRoster):
    """The served game answering its clients' commands (see the module docstring)."""

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
        if name in ("turn", "dash", "kick", "say", "turn_neck"):
            try:
                action = parse_action(text)
            except CommandParseError as exc:
                raise CommandError(ILLEGAL_FORM, exc.reason) from None
            if isinstance(action, Say):
                self._say(client, action.text)
            elif isinstance(action, TurnNeck):
                assert client.ref is not None
                if self.model.turn_neck(self.model.row(client.ref), action.angle_rad):
                    client.counts[COUNTERS.index("turn_neck")] += 1
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
