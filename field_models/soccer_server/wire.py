"""rcssserver's UDP text protocol beyond see and hear: commands in, replies and sensors out.

What a client of a real rcssserver 19 sends and gets, as pure functions of text and state; the
served game (:mod:`~field_models.soccer_server.serving`) and the over-the-wire field model
(:mod:`field_models.rcssserver`) both use them. Formats read from rcssserver 19.0.0's source
(commit ce87001):

* client commands: one or more S-expressions in one datagram, ``(dash 80)(say "hi")``
  (``src/player.cpp`` ``Player::parseCommand``); :func:`split_commands` and :func:`parse_command`;
* ``(init Side Unum PlayMode)``, ``(reconnect Side PlayMode)`` (``src/serializerplayerstdv1.cpp``);
* ``server_param``, ``player_param``, ``player_type`` (:mod:`field_models.rcss_params`);
* ``sense_body`` by protocol version (``src/bodysender.cpp``, ``src/serializerplayerstdv*.cpp``):
  view mode, stamina (with capacity from 13), speed with direction (from 6), head angle,
  counters (``turn_neck catch move change_view`` from 6), ``arm``/``focus``/``tackle`` from 8,
  ``collision`` from 12, ``foul`` from 14, ``focus_point`` from 18;
* the trainer's ``(ok look T ...)`` / ``(see_global T ...)`` (``src/serializercoachstdv7.cpp``,
  ``src/visualsendercoach.cpp``): absolute positions and velocities in the server's frame, body
  and neck in integer degrees (rounded from protocol 8);
* a monitor's ``show`` (``src/serializermonitor.cpp``, ``SerializerMonitorStdv3``/``v4``):
  ``(show T (pm ID) (tm L R SL SR) ((b) x y vx vy) ((l 1) type state x y vx vy body neck
  (v h width) (s stamina effort recovery [capacity]) (c counts...)) ...)`` with all 22 slots,
  in :mod:`~field_models.soccer_server.wire_show` beside this module.

Coordinates on the wire are the server's: y down, angles clockwise in degrees, velocities per
cycle. Our frame (y up, counter-clockwise radians, m/s) is converted here (and in the show's
module) and nowhere else.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass

from field_models.protocol import LEFT, RIGHT, BodyState, PlayerRef
from field_models.rcss_params import (
    PLAYER_PARAMS,
    SERVER_PARAMS,
    ParamValue,
    default_player_params,
    default_player_type,
    default_server_params,
    param_message,
    player_type_message,
)
from field_models.soccer_server.messages import MessageParseError, Quoted, SExpr, parse_sexpr
from field_models.soccer_server.params import ServerPreset

MAX_DATAGRAM = 8192
"""Largest datagram the server reads (rcssserver's ``MaxMesg``); longer ones are cut there."""
MAX_COMMANDS = 32
"""Most commands one datagram may carry; the rest is refused (a flood guard of ours)."""
PLAYERS_PER_TEAM = 11
"""Player slots per team (``MAX_PLAYER``)."""
PLAY_MODE_IDS: dict[str, int] = {
    name: i
    for i, name in enumerate(
        (
            "",
            "before_kick_off",
            "time_over",
            "play_on",
            "kick_off_l",
            "kick_off_r",
            "kick_in_l",
            "kick_in_r",
            "free_kick_l",
            "free_kick_r",
            "corner_kick_l",
            "corner_kick_r",
            "goal_kick_l",
            "goal_kick_r",
            "goal_l",
            "goal_r",
            "drop_ball",
            "offside_l",
            "offside_r",
        )
    )
}
"""The first play modes of rcssserver's ``PLAYMODE_STRINGS`` (``src/types.h``): a show's ``pm``."""
TRAINER_MODES = tuple(name for name in PLAY_MODE_IDS if name)
"""Play-mode names a trainer's ``change_mode`` may give (the served model knows fewer)."""

_RAD2DEG = 180.0 / math.pi
_DEG2RAD = math.pi / 180.0


class CommandError(ValueError):
    """A command the server refuses: `reply` is the server's answer, ``(error ...)``."""

    def __init__(self, reply: str, detail: str) -> None:
        super().__init__(f"{reply}: {detail}")
        self.reply = reply
        self.detail = detail


ILLEGAL_FORM = "(error illegal_command_form)"
UNKNOWN = "(error unknown_command)"


# ----------------------------------------------------------------------------- commands in


def decode(data: bytes) -> str:
    """A datagram as text: cut at the first NUL and at :data:`MAX_DATAGRAM`; non-ASCII replaced."""
    data = data[:MAX_DATAGRAM]
    end = data.find(b"\0")
    if end >= 0:
        data = data[:end]
    return data.decode("ascii", errors="replace").rstrip("\r\n")


def split_commands(text: str) -> list[str]:
    """The top-level ``(...)`` expressions of one datagram, in order.

    Raises:
        CommandError: ``illegal_command_form`` for text outside parentheses, an unbalanced or
            unterminated expression, or more than :data:`MAX_COMMANDS` commands.
    """
    out: list[str] = []
    depth, start, quoted = 0, -1, False
    for i, ch in enumerate(text):
        if quoted:
            quoted = ch != '"'
        elif ch == '"':
            if depth == 0:
                raise CommandError(ILLEGAL_FORM, "quote outside a command")
            quoted = True
        elif ch == "(":
            if depth == 0:
                start = i
            depth += 1
        elif ch == ")":
            depth -= 1
            if depth < 0:
                raise CommandError(ILLEGAL_FORM, "unbalanced ')'")
            if depth == 0:
                out.append(text[start : i + 1])
                if len(out) > MAX_COMMANDS:
                    raise CommandError(ILLEGAL_FORM, f"more than {MAX_COMMANDS} commands")
        elif depth == 0 and not ch.isspace():
            raise CommandError(ILLEGAL_FORM, f"text outside a command at {i}")
    if depth or quoted:
        raise CommandError(ILLEGAL_FORM, "unterminated command")
    if not out:
        raise CommandError(ILLEGAL_FORM, "no command")
    return out


def parse_command(text: str) -> list[SExpr]:
    """One command as a list: name first (an atom), then its arguments.

    Raises:
        CommandError: ``illegal_command_form`` for anything that is not ``(name args...)``.
    """
    try:
        tree = parse_sexpr(text)
    except MessageParseError as exc:
        raise CommandError(ILLEGAL_FORM, exc.reason) from None
    if not tree or not isinstance(tree[0], str) or isinstance(tree[0], Quoted):
        raise CommandError(ILLEGAL_FORM, "a command starts with its name")
    return tree


def number(token: SExpr) -> float:
    """A finite number argument (``%lf`` accepts ints and reals).

    Raises:
        CommandError: ``illegal_command_form`` for anything else.
    """
    if isinstance(token, list | Quoted) or len(token) > 32:
        raise CommandError(ILLEGAL_FORM, "expected a number")
    try:
        value = float(token)
    except ValueError:
        raise CommandError(ILLEGAL_FORM, f"{token!r} is not a number") from None
    if not math.isfinite(value):
        raise CommandError(ILLEGAL_FORM, f"{token!r} is not a finite number")
    return value + 0.0


def numbers(args: Sequence[SExpr], low: int, high: int) -> list[float]:
    """`low`..`high` number arguments.

    Raises:
        CommandError: ``illegal_command_form`` for another count or a non-number.
    """
    if not low <= len(args) <= high:
        raise CommandError(ILLEGAL_FORM, f"expected {low} to {high} arguments")
    return [number(a) for a in args]


def word(token: SExpr) -> str:
    """A bare word argument (``on``, ``narrow``, a team name).

    Raises:
        CommandError: ``illegal_command_form`` for a list.
    """
    if isinstance(token, list):
        raise CommandError(ILLEGAL_FORM, "expected a word")
    return str(token)


def say_text(args: Sequence[SExpr]) -> str:
    """A say's message: one quoted string, or bare words joined by single spaces.

    Raises:
        CommandError: ``illegal_command_form`` for an empty message or a nested list.
    """
    if not args or any(isinstance(a, list) for a in args):
        raise CommandError(ILLEGAL_FORM, "say needs a message")
    return " ".join(str(a) for a in args)


@dataclass(frozen=True, slots=True)
class PlayerInit:
    """A parsed ``(init Team [(version V)] [(goalie)])`` (``Stadium::parsePlayerInit``)."""

    team: str
    version: float
    goalie: bool


def parse_player_init(tree: list[SExpr]) -> PlayerInit:
    """A player's init, checked as the server checks it (team name 1..15 of ``[-+_a-zA-Z0-9]``).

    Raises:
        CommandError: ``(error illegal_teamname)`` or ``illegal_command_form``.
    """
    if len(tree) < 2 or isinstance(tree[1], list | Quoted):
        raise CommandError("(error illegal_teamname)", "no team name")
    team = str(tree[1])
    if not 1 <= len(team) <= 15 or not all(ch.isalnum() or ch in "+-_" for ch in team):
        raise CommandError("(error illegal_teamname_or_too_long_teamname)", team)
    if not team.isascii():
        raise CommandError("(error illegal_teamname)", team)
    version, goalie = 3.0, False
    for option in tree[2:]:
        if option == ["goalie"]:
            goalie = True
        elif isinstance(option, list) and len(option) == 2 and option[0] == "version":
            version = number(option[1])
        else:
            raise CommandError(ILLEGAL_FORM, "init option")
    return PlayerInit(team, version, goalie)


# ----------------------------------------------------------------------------- parameters


_TO_SERVER: dict[str, tuple[str, str, float]] = {
    # server name: (record, field, factor from the preset's unit to the server's)
    "simulator_step": ("dynamics", "simulator_step_ms", 1.0),
    "goal_width": ("dynamics", "goal_width_m", 1.0),
    "ball_size": ("dynamics", "ball_size_m", 1.0),
    "ball_decay": ("dynamics", "ball_decay", 1.0),
    "ball_rand": ("dynamics", "ball_rand", 1.0),
    "ball_speed_max": ("dynamics", "ball_speed_max_m_per_cycle", 1.0),
    "ball_accel_max": ("dynamics", "ball_accel_max_m_per_cycle2", 1.0),
    "player_size": ("dynamics", "player_size_m", 1.0),
    "player_decay": ("dynamics", "player_decay", 1.0),
    "player_rand": ("dynamics", "player_rand", 1.0),
    "player_speed_max": ("dynamics", "player_speed_max_m_per_cycle", 1.0),
    "player_accel_max": ("dynamics", "player_accel_max_m_per_cycle2", 1.0),
    "inertia_moment": ("dynamics", "inertia_moment_cycle_per_m", 1.0),
    "dash_power_rate": ("dynamics", "dash_power_rate_m_per_cycle2", 1.0),
    "kick_power_rate": ("dynamics", "kick_power_rate_m_per_cycle2", 1.0),
    "kickable_margin": ("dynamics", "kickable_margin_m", 1.0),
    "kick_rand": ("dynamics", "kick_rand", 1.0),
    "minpower": ("dynamics", "minpower", 1.0),
    "maxpower": ("dynamics", "maxpower", 1.0),
    "min_dash_power": ("dynamics", "min_dash_power", 1.0),
    "max_dash_power": ("dynamics", "max_dash_power", 1.0),
    "minmoment": ("dynamics", "minmoment_rad", _RAD2DEG),
    "maxmoment": ("dynamics", "maxmoment_rad", _RAD2DEG),
    "side_dash_rate": ("dynamics", "side_dash_rate", 1.0),
    "back_dash_rate": ("dynamics", "back_dash_rate", 1.0),
    "dash_angle_step": ("dynamics", "dash_angle_step_rad", _RAD2DEG),
    "min_dash_angle": ("dynamics", "min_dash_angle_rad", _RAD2DEG),
    "max_dash_angle": ("dynamics", "max_dash_angle_rad", _RAD2DEG),
    "send_step": ("sensing", "send_step_ms", 1.0),
    "recv_step": ("sensing", "recv_step_ms", 1.0),
    "visible_angle": ("sensing", "view_half_angle_rad", 2.0 * _RAD2DEG),
    "visible_distance": ("sensing", "visible_distance_m", 1.0),
    "quantize_step": ("sensing", "quantize_step", 1.0),
    "quantize_step_l": ("sensing", "quantize_step_l", 1.0),
    "audio_cut_dist": ("sensing", "audio_cut_dist_m", 1.0),
    "say_msg_size": ("sensing", "say_msg_size", 1.0),
    "hear_max": ("sensing", "hear_max", 1.0),
    "hear_inc": ("sensing", "hear_inc", 1.0),
    "hear_decay": ("sensing", "hear_decay", 1.0),
}


def server_params(
    preset: ServerPreset, overrides: Mapping[str, ParamValue] | None = None
) -> dict[str, ParamValue]:
    """Every server parameter as a real server would send it for this preset.

    rcssserver 19's defaults, then every value the preset holds (in the server's units; an
    unbounded cap is sent as the server's largest double would not be, so a preset's ``inf``
    becomes 1e9), ``coach`` from the referee switch, then `overrides` (ports, synch mode).
    """
    values = default_server_params()
    records = {"dynamics": preset.dynamics, "sensing": preset.sensing}
    for name, (record, field_name, factor) in _TO_SERVER.items():
        raw = float(getattr(records[record], field_name)) * factor
        raw = 1e9 if math.isinf(raw) else raw
        default = values[name]
        values[name] = round(raw) if isinstance(default, int) else raw
    values["coach"] = not preset.dynamics.referee
    values.update(overrides or {})
    return values


def param_messages(
    preset: ServerPreset, version: float, overrides: Mapping[str, ParamValue] | None = None
) -> list[str]:
    """The ``server_param``, ``player_param`` and ``player_type`` messages of a new client.

    Protocol >= 7 gets them (``InitSenderCommonV7``); every player type is the default type,
    as the served model has no heterogeneous players.
    """
    if version < 7:
        return []
    v = int(version)
    server = server_params(preset, overrides)
    player = default_player_params()
    out = [
        param_message("server_param", server, SERVER_PARAMS, v),
        param_message("player_param", player, PLAYER_PARAMS, v),
    ]
    type0 = default_player_type(server)
    count = int(player["player_types"])
    out.extend(player_type_message(i, type0, v) for i in range(count))
    return out


# ----------------------------------------------------------------------------- sensors out


@dataclass(slots=True)
class BodySense:
    """What a sense_body reports of one player (our frame; :func:`render_sense_body` converts).

    Attributes:
        vx, vy: The player's stored velocity [m/cycle], our frame.
        heading: Body angle [rad], our frame.
        quality, width: The view mode (``high``/``low``, ``narrow``/``normal``/``wide``).
        stamina, effort, capacity: Reported as the server's initial values (not modelled).
        counts: Commands carried out: kick, dash, turn, say, turn_neck, catch, move,
            change_view, change_focus (in that order).
        neck: Neck angle relative to the body [rad], our frame (``head_angle``).
    """

    vx: float
    vy: float
    heading: float
    quality: str
    width: str
    stamina: float
    effort: float
    capacity: float
    counts: tuple[int, ...]
    neck: float = 0.0


def render_sense_body(time: int, version: float, s: BodySense) -> str:
    """``(sense_body T ...)`` for a client of `version` (module docstring)."""
    v = int(version)
    speed = math.hypot(s.vx, s.vy)
    parts = [f"(sense_body {time} (view_mode {s.quality} {s.width})"]
    if v >= 13:
        parts.append(f"(stamina {_g(s.stamina)} {_g(s.effort)} {_g(s.capacity)})")
    else:
        parts.append(f"(stamina {_g(s.stamina)} {_g(s.effort)})")
    shown = round(speed * 100.0) / 100.0  # the server quantises the speed to 0.01
    if v >= 6:
        # Direction of motion relative to the head, server sign (y down): our angle negated.
        rel = 0.0 if speed == 0.0 else math.atan2(s.vy, s.vx) - (s.heading + s.neck)
        rel = (rel + math.pi) % (2.0 * math.pi) - math.pi
        parts.append(f"(speed {_g(shown)} {round(-rel * _RAD2DEG) + 0})")
    else:
        parts.append(f"(speed {_g(shown)})")
    parts.append(f"(head_angle {round(-s.neck * _RAD2DEG) + 0})")
    kick, dash, turn, say, neck, catch, move, view, focus = s.counts
    parts.append(f"(kick {kick}) (dash {dash}) (turn {turn}) (say {say})")
    if v >= 6:
        parts.append(f"(turn_neck {neck}) (catch {catch}) (move {move}) (change_view {view})")
    if v >= 8:
        parts.append(
            "(arm (movable 0) (expires 0) (target 0 0) (count 0)) "
            "(focus (target none) (count 0)) (tackle (expires 0) (count 0))"
        )
    if v >= 12:
        parts.append("(collision none)")
    if v >= 14:
        parts.append("(foul (charged 0) (card none))")
    if v >= 18:
        parts.append(f"(focus_point 0 0) (change_focus {focus})")
    return " ".join(parts) + ")"


def _g(value: float) -> str:
    """A double as a C++ stream prints it (``%g``), -0 as 0."""
    return f"{value + 0.0:g}"


def global_objects(
    ball: BodyState,
    players: Mapping[PlayerRef, BodyState],
    names: Mapping[str, str],
    dt_s: float,
    version: float,
) -> str:
    """The objects of a trainer's ``see_global`` or ``ok look``, server frame.

    Goals, ball, then each player ``((p "Team" Unum) x y vx vy body neck)``; velocities per
    cycle, body in integer degrees (rounded from protocol 8, truncated before).
    """
    parts = ["((g l) -52.5 0)", "((g r) 52.5 0)"]
    parts.append(f"((b) {_g(ball.x)} {_g(-ball.y)} {_g(ball.vx * dt_s)} {_g(-ball.vy * dt_s)})")
    for ref, st in players.items():
        team = names.get(ref.team, ref.team)
        deg = -st.heading * _RAD2DEG
        body = round(deg) if version >= 8 else int(deg)
        parts.append(
            f'((p "{team}" {ref.number}) {_g(st.x)} {_g(-st.y)} {_g(st.vx * dt_s)} '
            f"{_g(-st.vy * dt_s)} {body + 0} 0)"
        )
    return " ".join(parts)


def team_side(ref: PlayerRef) -> str:
    """``"l"`` for the left team's slot, ``"r"`` for the right's."""
    return "l" if ref.team == LEFT else "r"


SLOTS: tuple[PlayerRef, ...] = tuple(
    PlayerRef(team, n) for team in (LEFT, RIGHT) for n in range(1, PLAYERS_PER_TEAM + 1)
)
"""The server's 22 player slots in its order: left 1..11, right 1..11."""


def server_to_ours(x: float, y: float, deg: float) -> tuple[float, float, float]:
    """A point and a direction of the server's frame in ours (y up, counter-clockwise rad)."""
    return x, -y + 0.0, -deg * _DEG2RAD + 0.0
