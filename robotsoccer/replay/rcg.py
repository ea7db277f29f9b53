"""The Soccer Server's text game log (``.rcg``, format ``ULG5``): writing ours, reading any.

rcssserver writes one such log per match when started with ``game_log_version 5``; rcssmonitor,
rcsslogplayer and the usual analysis tools replay and read it. The syntax here is rcssserver
19.0.0's, read from its source:

* ``src/initsenderlogger.cpp`` (``InitSenderLoggerV5``): the header line ``ULG5``, then the
  ``(server_param ...)``, ``(player_param ...)`` and ``(player_type ...)`` lines
  (``src/initsender.cpp``, ``InitSenderCommonV8``; each parameter ``(name value)`` with no
  space between parameters, doubles as a C++ stream prints them, booleans ``0``/``1``,
  strings in double quotes). A log gets every parameter (its sender asks as protocol 999),
  sorted by name (the server's ``std::map``), and one line per player type: the writer writes
  all of them (:mod:`field_models.rcss_params`), rcssserver 19's defaults where it was given
  no value, and 18 types that are each the default type;
* ``src/logger.cpp`` (``Logger::writeGameLogImpl``): every cycle a ``(playmode T mode)`` line
  when the play mode changed, a ``(team T LEFT RIGHT SL SR)`` line when a name or the score
  changed (both first written at the first cycle), then the ``(show T ...)`` line;
* ``src/dispsender.cpp`` (``DispSenderLoggerV4::sendShow``) and ``src/serializermonitor.cpp``
  (``SerializerMonitorStdv3``/``v4``; log version 5 uses monitor serializer 4): the show line
  ``(show T ((b) x y vx vy) ((l 1) TYPE STATE x y vx vy body neck (v h 90)
  (s stamina effort recovery capacity) (c kick dash turn catch move turn_neck change_view say
  tackle pointto attentionto)) ...)``. Every show carries all 22 player slots in the
  server's order (left 1..11, right 1..11): the server creates its 22 players at the start
  (``Stadium``'s constructor, ``src/stadium.cpp``), and rcssmonitor's reader
  (``rcss/rcg/parser_v4.cpp``) refuses a show with fewer. STATE is hexadecimal with a ``0x``
  prefix (``std::showbase``, which prints zero as ``0``); bit 0x1 (``STAND``) marks an
  enabled player. A player not connected is written disabled (state 0) at x = -3·unum·side,
  y = -(68/2 + 3) (``Player::disable`` in ``src/player.cpp``; side +1 left, -1 right), which
  is how this writer writes a slot without a player in the frame.

**What the writer writes as the server does** (``src/types.h`` ``PlayerState``,
``src/referee.cpp``, ``src/stadium.cpp``):

* **cycles**: the frame's tick, which on a 100 ms field is the server's cycle count. The server
  logs a cycle after stepping it, so its first show is cycle 1: a frame at tick 0 (the placement
  before the first step) is refused;
* **play modes**: each frame's mode, where it changed. A goal is written as the referee calls
  it: the cycle the score rose in (the frame before the first frame with the new score) reads
  ``goal_l`` or ``goal_r`` with the new score and the ball still, and is shown
  :data:`AFTER_GOAL_WAIT` times in all with the clock held (``AFTER_GOAL_WAIT``: the server's
  pause before the kick-off), the players frozen where they stood, as our models do not play
  out that pause. (The 1996 preset puts the ball back on the centre spot in the goal's own
  cycle, as that server did, so its goal scene shows the ball there.) :meth:`RcgWriter.finish`
  ends the log with ``time_over`` at the last cycle;
* **state**: ``STAND`` (0x1) for every player on the field, ``GOALIE`` (0x8) for the goalies
  given, ``KICK`` (0x2) in a cycle whose kick reached the ball and ``KICK_FAULT`` (0x4) in one
  whose kick did not (from the frame's :class:`~field_models.arena.CommandTally`); our players
  cannot catch or tackle, so those flags never appear;
* **counters** ``(c kick dash turn catch move turn_neck change_view say tackle pointto
  attentionto)``: the frame's counts of the commands the server carried out; zeros where the
  field model does not count them. Our clients send only kick, dash, turn and say (the
  coach's kick-off placement is a trainer's move, not the player's), so the others stay 0;
* **stamina, effort, recovery, capacity** ``(s ...)``: our models do not simulate stamina (the
  dash uses effort 1), so every show carries the real server's initial values: the given
  ``stamina_max``, ``effort_init``, ``recover_init`` and ``stamina_capacity``, otherwise
  rcssserver 19's defaults 8000, 1, 1 and 130600. The neck angle is 0 (our players have no
  neck) and the view ``(v h visible_angle)``, the server's default view.

Coordinates are the server's: metres, x toward the right goal, **y down**, angles in degrees
clockwise positive, velocities per cycle. Our field frame has y up, counter-clockwise radians
and m/s, so the writer writes y, vy and the body angle negated and velocities times the cycle
(``dt_s``), and the reader undoes it. Positions and velocities are written with four decimals
and angles with three (the server's ``PREC`` 0.0001 and ``DPREC`` 0.001); with ``%.4f``
instead of the server's ``%g`` of the quantised value the file is a little larger and every
log reader parses it the same. Velocities are therefore kept to 0.0001 m per cycle (0.001 m/s
at the server's 100 ms cycle).

The cycle written is the frame's tick. ``simulator_step`` (ms) is always written, from
``dt_s``; the reader takes the cycle from it (0.1 s when a log has none). A step that is not a
whole number of milliseconds (a robot table's 1/240 s) is written as a decimal: the log players
then warn that the value is not an integer and keep their default, and our reader keeps the
exact step.
"""

from __future__ import annotations

import dataclasses
import math
import os
import re
from collections.abc import Collection, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from types import TracebackType

from field_models.arena import COMMAND_COUNTERS, CommandTally
from field_models.protocol import LEFT, RIGHT, BodyState, PlayerRef, Truth, wrap_angle
from field_models.rcss_params import (
    PLAYER_TYPE_FIELDS,
    ParamValue,
    cxx_text,
    default_player_params,
    default_player_type,
    default_server_params,
)
from robotsoccer.replay.frames import TEAM_NAME_CHARS, GameFrame

HEADER = "ULG5"
"""First line of the log: text format, version 5."""
FIRST_CYCLE = 1
"""The first cycle a server's log shows: it logs each cycle after stepping it."""
AFTER_GOAL_WAIT = 50
"""Shows of a goal's cycle, the clock held: rcssserver's pause before the kick-off
(``AFTER_GOAL_WAIT``, ``src/referee.h``)."""
TIME_OVER = "time_over"
"""The play mode of a log's last cycle (:meth:`RcgWriter.finish`)."""
READABLE_HEADERS = ("ULG4", "ULG5", "ULG6")
"""Headers :func:`read_rcg` accepts: the text versions, whose show lines read alike."""
MAX_PLAYERS_PER_TEAM = 11
"""Highest uniform number the log players accept (rcssmonitor's ``MAX_PLAYER``)."""
DEFAULT_CYCLE_S = 0.1
"""Cycle assumed when a log's ``server_param`` line has no ``simulator_step``."""
NO_PLAY_MODE = "before_kick_off"
"""Play mode of shows read before any ``playmode`` line (real logs always have one first)."""

SLOTS = tuple(
    PlayerRef(team, number)
    for team in (LEFT, RIGHT)
    for number in range(1, MAX_PLAYERS_PER_TEAM + 1)
)
"""Every show line's player slots, in rcssserver's order: left 1..11, then right 1..11."""

# rcssserver's PlayerState bits (src/types.h).
_STAND = 0x1
_KICK = 0x2
_KICK_FAULT = 0x4
_GOALIE = 0x8
_NO_COUNTS = (0,) * len(COMMAND_COUNTERS)
_NO_TALLY = CommandTally(_NO_COUNTS)
_PITCH_WIDTH_M = 68.0  # rcssserver's compiled ServerParam::PITCH_WIDTH
_RAD2DEG = 180.0 / math.pi
_DEG2RAD = math.pi / 180.0
_TEAM_NAME = re.compile(rf"[A-Za-z0-9_-]{{1,{TEAM_NAME_CHARS}}}", re.ASCII)
_PARAM_NAME = re.compile(r"[A-Za-z_][A-Za-z0-9_]*", re.ASCII)
_PLAY_MODE = re.compile(r"[A-Za-z0-9_]+", re.ASCII)
# The server's defaults for what a show line carries but our models do not simulate
# (src/serverparam.cpp): view cone, stamina, effort, recovery, stamina capacity.
_SHOW_DEFAULTS: dict[str, float] = {
    "visible_angle": 90.0,
    "stamina_max": 8000.0,
    "effort_init": 1.0,
    "recover_init": 1.0,
    "stamina_capacity": 130600.0,
}

_NUM = r"([-+]?(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eE][-+]?[0-9]+)?)"
_SHOW = re.compile(
    r"\(show (-?[0-9]+)\s*(?:\(pm [0-9]+\)\s*)?(?:\(tm [^()]*\)\s*)?"
    rf"\(\(b\) {_NUM} {_NUM} {_NUM} {_NUM}\)",
    re.ASCII,
)
_PLAYER = re.compile(
    r"\(\(([lr]) ([0-9]+)\) [0-9]+ (0[xX][0-9a-fA-F]+|[0-9a-fA-F]+)"
    rf" {_NUM} {_NUM} {_NUM} {_NUM} {_NUM} {_NUM}[ )]",
    re.ASCII,
)
_PLAYMODE_LINE = re.compile(r"\(playmode (-?[0-9]+) ([A-Za-z0-9_]+)\)", re.ASCII)
_TEAM_LINE = re.compile(
    r"\(team (-?[0-9]+) (\S+) (\S+) ([0-9]+) ([0-9]+)(?: [0-9]+ [0-9]+ [0-9]+ [0-9]+)?\)",
    re.ASCII,
)
_PARAM_VALUE = r"(?:[^()\s\"]+|\"[^\"]*\")"
_SERVER_PARAM_LINE = re.compile(
    rf"\(server_param\s*(?:\([A-Za-z0-9_]+ {_PARAM_VALUE}\)\s*)*\)", re.ASCII
)
_PARAM = re.compile(rf"\(([A-Za-z0-9_]+) ({_PARAM_VALUE})\)", re.ASCII)
_LINE_NAME = re.compile(r"\(([A-Za-z_][A-Za-z0-9_]*)[\s)]", re.ASCII)


# ----------------------------------------------------------------------------- writing


class RcgWriter:
    """Streams frames to an ``.rcg`` file, one cycle behind (no more kept in memory).

    A cycle is written when the next frame comes, since only the next frame's score tells
    whether a goal was scored in it (module docstring); :meth:`finish` writes the last cycle
    as ``time_over``, :meth:`close` as it is. The log is written under ``<name>.part`` next to
    `path` and renamed to `path` on closing, so a file under the final name is always a whole
    log. Also a context manager: leaving the ``with`` block closes the writer, also on an
    exception.

    Args:
        path: Where the finished log goes (``.rcg`` by convention).
        players: Every player of the match; a frame may hold no other. Teams must be
            :data:`~field_models.protocol.LEFT` or :data:`~field_models.protocol.RIGHT`,
            numbers 1..11. A slot of :data:`SLOTS` whose player a frame lacks is written
            disconnected.
        teams: The left and right team names: letters, digits, ``-`` and ``_``, at most
            :data:`~robotsoccer.replay.frames.TEAM_NAME_CHARS` characters (rcssserver's rule;
            :func:`log_team_name` turns a display name into one).
        dt_s: One cycle [s]; velocities are written per cycle and ``simulator_step`` from it.
        server_params: Parameters for the ``server_param`` line, in rcssserver's names and
            units (``goal_width``, ``ball_size``, ``player_size``, ``kickable_margin``,
            ``ball_decay``, ``player_decay``, ``visible_angle``, ...). ``simulator_step`` comes
            from `dt_s`; one given here must agree with it. ``visible_angle``, ``stamina_max``,
            ``effort_init``, ``recover_init`` and ``stamina_capacity`` also fill each player's
            ``(v ...)`` and ``(s ...)`` (server defaults otherwise).
        player_params: Parameters for the ``player_param`` line, in rcssserver's names.
        goalies: The players whose state carries the ``GOALIE`` flag (0x8).
        goal_scenes: Write a goal's cycle as the server's after-goal pause (module docstring).
            False where the frames already show the pause (a served game's own referee
            plays it out): every frame is then written as it is.

    Raises:
        ValueError: On a bad team name, player, cycle or parameter.
    """

    def __init__(
        self,
        path: Path,
        *,
        players: tuple[PlayerRef, ...],
        teams: tuple[str, str],
        dt_s: float,
        server_params: Mapping[str, float | int | str] | None = None,
        player_params: Mapping[str, float | int | str] | None = None,
        goalies: Collection[PlayerRef] = (),
        goal_scenes: bool = True,
    ) -> None:
        self._goal_scenes = goal_scenes
        for name in teams:
            if not isinstance(name, str) or _TEAM_NAME.fullmatch(name) is None:
                raise ValueError(
                    f"team name {name!r}: rcssserver allows 1 to {TEAM_NAME_CHARS} letters, "
                    "digits, '-' and '_'"
                )
        if len(teams) != 2:
            raise ValueError(f"need the left and the right team's names, got {teams!r}")
        if not (math.isfinite(dt_s) and dt_s > 0.0):
            raise ValueError(f"dt_s must be a positive number of seconds, got {dt_s!r}")
        self._players = _checked_players(players)
        stray = set(goalies) - self._players
        if stray:
            raise ValueError(f"goalies {', '.join(map(str, sorted(stray)))} are not in this log")
        self._dt = float(dt_s)
        params = _server_params(server_params or {}, self._dt)

        self.path = Path(path)
        self._part = self.path.with_name(self.path.name + ".part")
        self._teams = (teams[0], teams[1])
        self._mode: str | None = None
        self._score: tuple[int, int] | None = None
        self._pending: GameFrame | None = None
        self._show = _show_format(params)
        # rcssserver's show lines carry all 22 player slots (its players exist from the start,
        # and rcssmonitor refuses a show with fewer); a slot without a player is written as the
        # server writes a disconnected one.
        self._slots = tuple(
            (
                ref,
                _STAND | (_GOALIE if ref in goalies else 0),
                (
                    "0",
                    -3.0 * ref.number * _side(ref),
                    -(0.5 * _PITCH_WIDTH_M + 3.0),
                    0.0,
                    0.0,
                    0.0,
                    *_NO_COUNTS,
                ),
            )
            for ref in SLOTS
        )
        self._file = self._part.open("w", encoding="ascii", newline="\n", buffering=1 << 20)
        try:
            self._file.write(_header(params, dict(player_params or {})))
        except BaseException:
            self._file.close()
            self._part.unlink(missing_ok=True)
            raise

    @property
    def closed(self) -> bool:
        """Whether :meth:`close` has run."""
        return self._file.closed

    def rename_teams(self, teams: tuple[str, str]) -> None:
        """New team names from the next written cycle on (a team line then says so).

        Raises:
            ValueError: A name rcssserver would not allow (see the constructor).
        """
        for name in teams:
            if not isinstance(name, str) or _TEAM_NAME.fullmatch(name) is None:
                raise ValueError(f"team name {name!r} cannot be written in a game log")
        if (teams[0], teams[1]) != self._teams:
            self._teams = (teams[0], teams[1])
            self._score = None  # forces a team line, which carries the names

    def write(self, frame: GameFrame) -> None:
        """Take one cycle's frame; the previous one is written now (a goal's as a goal scene).

        Raises:
            ValueError: If the writer is closed, the frame's cycle is before
                :data:`FIRST_CYCLE` or before the previous frame's, its play mode is not one
                word, or it holds a player the writer was not given.
        """
        if self._file.closed:
            raise ValueError(f"{self._part}: the writer is closed")
        tick = frame.truth.tick
        if not self._players.issuperset(frame.truth.players):
            extra = sorted(set(frame.truth.players) - self._players)
            raise ValueError(
                f"tick {tick}: players {', '.join(map(str, extra))} are not in this log"
            )
        if _PLAY_MODE.fullmatch(frame.play_mode) is None:
            raise ValueError(f"play mode {frame.play_mode!r} is not one word")
        if tick < FIRST_CYCLE:
            raise ValueError(
                f"tick {tick}: a server's log starts at cycle {FIRST_CYCLE} (it logs a cycle "
                "after stepping it)"
            )
        pending = self._pending
        if pending is not None:
            if tick < pending.tick:
                raise ValueError(f"tick {tick} comes after tick {pending.tick}")
            self._write_pending(frame.score)
        self._pending = frame

    def finish(self, score: tuple[int, int] | None = None) -> None:
        """End the match: the last cycle as ``time_over``, then close the log.

        Args:
            score: The final score, where a goal in the last cycle raised it after its frame
                (None: the last frame's); that cycle is then written as the goal's scene first.
        """
        pending = self._pending
        if pending is not None and not self._file.closed:
            self._pending = None
            side = _scorer(pending.score, score or pending.score)
            if side is None:
                self._write_cycle(pending, TIME_OVER, pending.score)
            else:
                assert score is not None
                self._goal_scene(pending, side, score)
                self._write_cycle(_held(pending), TIME_OVER, score)
        self.close()

    def close(self) -> None:
        """Write the last cycle as it is, close and move the log to its final name; again: no-op."""
        if self._file.closed:
            return
        if self._pending is not None:
            self._write_pending(self._pending.score)
        self._file.close()
        os.replace(self._part, self.path)

    def __enter__(self) -> RcgWriter:
        return self

    def __exit__(
        self,
        exc_type: type[BaseException] | None,
        exc: BaseException | None,
        tb: TracebackType | None,
    ) -> None:
        self.close()

    # ------------------------------------------------------------------ cycles

    def _write_pending(self, next_score: tuple[int, int]) -> None:
        """Write the held-back frame: as a goal's scene when `next_score` shows a goal in it."""
        frame = self._pending
        assert frame is not None
        self._pending = None
        side = _scorer(frame.score, next_score) if self._goal_scenes else None
        if side is None:
            self._write_cycle(frame, frame.play_mode, frame.score)
        else:
            self._goal_scene(frame, side, next_score)

    def _goal_scene(self, frame: GameFrame, side: str, score: tuple[int, int]) -> None:
        """The goal's cycle as the server logs it: the goal mode and new score, held.

        rcssserver stops the ball when it scores the goal and holds the clock for
        :data:`AFTER_GOAL_WAIT` shows before the kick-off; our models play no such pause, so
        the players stay where they stood.
        """
        held = _held(frame)
        self._write_cycle(_ball_still(frame), f"goal_{side}", score)
        for _ in range(AFTER_GOAL_WAIT - 1):
            self._write_cycle(held, f"goal_{side}", score)

    def _write_cycle(self, frame: GameFrame, mode: str, score: tuple[int, int]) -> None:
        """One cycle: playmode and team lines where they changed, then the show line."""
        write = self._file.write
        tick = frame.truth.tick
        if mode != self._mode:
            self._mode = mode
            write(f"(playmode {tick} {mode})\n")
        if score != self._score:
            left, right = score
            self._score = (left, right)
            write(f"(team {tick} {self._teams[0]} {self._teams[1]} {left:d} {right:d})\n")
        write(self._show % self._show_values(frame))

    def _show_values(self, frame: GameFrame) -> tuple[object, ...]:
        """The show line's values: the cycle, the ball, then each slot's (:func:`_show_format`)."""
        dt = self._dt
        truth = frame.truth
        ball = truth.ball
        values: list[object] = [truth.tick, ball.x, 0.0 - ball.y, ball.vx * dt, 0.0 - ball.vy * dt]
        get = truth.players.get
        tallies = frame.commands or {}
        for ref, state_bits, absent in self._slots:
            state = get(ref)
            if state is None:
                values.extend(absent)
                continue
            x, y, heading, vx, vy = state
            # 0.0 - v rather than -v: no "-0.0000" for a zero.
            body = 0.0 - heading * _RAD2DEG
            if not -180.0 < body <= 180.0:
                body = 180.0 - (180.0 - body) % 360.0
            tally = tallies.get(ref, _NO_TALLY)
            bits = state_bits
            if tally.kicked:
                bits |= _KICK
            if tally.kick_missed:
                bits |= _KICK_FAULT
            values.extend((f"{bits:#x}", x, 0.0 - y, vx * dt, 0.0 - vy * dt, body))
            values.extend(tally.counts)
        return tuple(values)


def log_team_name(name: str) -> str:
    """A display name as a game log may carry it: runs of other characters become ``_``.

    >>> log_team_name("baseline (left)")
    'baseline_left'

    Raises:
        ValueError: Nothing of the name is left, or more than
            :data:`~robotsoccer.replay.frames.TEAM_NAME_CHARS` characters are.
    """
    text = re.sub(r"[^A-Za-z0-9_-]+", "_", name).strip("_")
    if _TEAM_NAME.fullmatch(text) is None:
        raise ValueError(f"team name {name!r} cannot be written in a game log")
    return text


def _scorer(before: tuple[int, int], after: tuple[int, int]) -> str | None:
    """``"l"`` or ``"r"``: the side whose score rose from `before` to `after`; None: neither."""
    if after[0] > before[0]:
        return "l"
    if after[1] > before[1]:
        return "r"
    return None


def _ball_still(frame: GameFrame) -> GameFrame:
    """`frame` with the ball at rest where it is (the server stops the ball at a goal)."""
    truth = frame.truth
    ball = truth.ball
    still = BodyState(ball.x, ball.y, ball.heading, 0.0, 0.0)
    return dataclasses.replace(frame, truth=dataclasses.replace(truth, ball=still))


def _held(frame: GameFrame) -> GameFrame:
    """`frame` frozen: everything at rest, no kick flags (a held cycle steps nothing)."""
    truth = frame.truth

    def still(s: BodyState) -> BodyState:
        return BodyState(s.x, s.y, s.heading, 0.0, 0.0)

    players = {ref: still(state) for ref, state in truth.players.items()}
    commands = None
    if frame.commands is not None:
        commands = {ref: CommandTally(t.counts) for ref, t in frame.commands.items()}
    held = dataclasses.replace(truth, ball=still(truth.ball), players=players)
    return dataclasses.replace(frame, truth=held, commands=commands)


def _side(ref: PlayerRef) -> int:
    """The server's side sign: +1 left, -1 right."""
    return 1 if ref.team == LEFT else -1


def _checked_players(players: tuple[PlayerRef, ...]) -> frozenset[PlayerRef]:
    """`players` as a set, checked: left or right, numbers 1..11, none twice."""
    for ref in players:
        if ref.team not in (LEFT, RIGHT):
            raise ValueError(f"player {ref}: the log has only the teams {LEFT!r} and {RIGHT!r}")
        if not 1 <= ref.number <= MAX_PLAYERS_PER_TEAM:
            raise ValueError(
                f"player {ref}: the log players take numbers 1 to {MAX_PLAYERS_PER_TEAM}"
            )
    if len(set(players)) != len(players):
        raise ValueError(f"players listed twice in {players!r}")
    return frozenset(players)


def _cxx_number(value: float | int) -> str:
    """A number as rcssserver prints it (``%g``), or exactly where ``%g`` would round it."""
    if isinstance(value, bool):
        return "1" if value else "0"  # C++ streams print bools as 0/1 without boolalpha
    if isinstance(value, int):
        return str(value)
    if not math.isfinite(value):
        raise ValueError(f"parameter value {value!r} is not finite")
    short = f"{value:g}"
    return short if float(short) == value else repr(float(value))


def _server_params(given: Mapping[str, float | int | str], dt_s: float) -> dict[str, str]:
    """The ``server_param`` entries as text, ``simulator_step`` set from `dt_s`."""
    step_ms = dt_s * 1000.0
    whole_ms = round(step_ms)
    step: float | int = whole_ms if abs(step_ms - whole_ms) < 1e-9 * max(1.0, step_ms) else step_ms
    out: dict[str, str] = {}
    for name, value in given.items():
        if _PARAM_NAME.fullmatch(name) is None:
            raise ValueError(f"server parameter name {name!r} is not a server name")
        if name == "simulator_step":
            if not isinstance(value, int | float) or not math.isclose(
                float(value), step_ms, rel_tol=1e-9
            ):
                raise ValueError(
                    f"server parameter simulator_step {value!r} ms disagrees with dt_s {dt_s!r}"
                )
            continue
        out[name] = _param_text(name, value)
    out["simulator_step"] = _cxx_number(step)
    return out


def _param_text(name: str, value: float | int | str) -> str:
    """One parameter's value as the server writes it; strings quoted."""
    if isinstance(value, str):
        if '"' in value or "\n" in value or "\r" in value:
            raise ValueError(f"parameter {name}: value {value!r} holds a quote or a line break")
        return f'"{value}"'
    if not isinstance(value, int | float):
        raise ValueError(f"parameter {name}: value {value!r} is not a number or a string")
    return _cxx_number(value)


def _param_line(kind: str, params: Mapping[str, str]) -> str:
    return f"({kind} " + "".join(f"({name} {text})" for name, text in params.items()) + ")\n"


def _header(server: dict[str, str], player: dict[str, float | int | str]) -> str:
    """The lines before the first cycle: header, server, player and player-type parameters.

    Every parameter rcssserver 19 logs, in its order (by name: :mod:`field_models.rcss_params`),
    with the server's defaults where the writer was given no value; then one ``player_type``
    line per type (``player_types``, 18), each the default type built from these server values:
    our players are all of the default type.
    """
    player_text = {}
    for name, value in player.items():
        if _PARAM_NAME.fullmatch(name) is None:
            raise ValueError(f"player parameter name {name!r} is not a server name")
        player_text[name] = _param_text(name, value)
    full_server = {name: cxx_text(value) for name, value in default_server_params().items()}
    full_server.update(server)
    full_player = {name: cxx_text(value) for name, value in default_player_params().items()}
    full_player.update(player_text)
    values: dict[str, ParamValue] = {**default_server_params(), **full_server}
    type0 = {
        name: value if isinstance(value, str) else cxx_text(value)
        for name, value in default_player_type(values).items()
    }
    fields = "".join(f"({name} {type0[name]})" for name, _ in PLAYER_TYPE_FIELDS)
    try:
        types = max(1, int(full_player.get("player_types", "18")))
    except ValueError:
        types = 18
    lines = [
        HEADER + "\n",
        _param_line("server_param", full_server),
        _param_line("player_param", full_player),
        *(f"(player_type (id {i}){fields})\n" for i in range(types)),
    ]
    return "".join(lines)


def _show_format(params: Mapping[str, str]) -> str:
    """The show line as one ``%`` format: the cycle, the ball, then every slot's fields.

    A slot takes its state, x, y, vx, vy, body and the
    :data:`~field_models.arena.COMMAND_COUNTERS` counts, in rcssserver's order
    (``SerializerMonitorStdv4::serializeShowPlayer``): ``((side unum) type state x y vx vy
    body neck (v quality width) (s stamina effort recovery capacity) (c counts...))``. An
    arm's point and a focus, which our players never have, are left out as the server leaves
    them out.
    """

    def number(name: str) -> str:
        text = params.get(name, "")
        try:
            float(text)
        except ValueError:
            return _cxx_number(_SHOW_DEFAULTS[name])
        return text

    view = f"(v h {number('visible_angle')})"
    stamina = (
        f"(s {number('stamina_max')} {number('effort_init')} {number('recover_init')}"
        f" {number('stamina_capacity')})"
    )
    counts = " ".join(["%d"] * len(COMMAND_COUNTERS))
    tail = f" 0 {view} {stamina}".replace("%", "%%") + f" (c {counts}))"
    parts = ["(show %d ((b) %.4f %.4f %.4f %.4f)"]
    for ref in SLOTS:
        side = "l" if ref.team == LEFT else "r"
        parts.append(f" (({side} {ref.number}) 0 %s %.4f %.4f %.4f %.4f %.3f{tail}")
    parts.append(")\n")
    return "".join(parts)


# ----------------------------------------------------------------------------- reading


@dataclass(frozen=True)
class RcgGame:
    """What :func:`read_rcg` reads from a game log.

    Attributes:
        teams: The left and right team names of the first ``team`` line (``("", "")`` where
            the log has none).
        server_params: The ``server_param`` line's entries as text, strings unquoted.
        frames: One frame per ``show`` line, in file order, in our field frame; players a
            show has disabled (disconnected) are left out of the truth.
    """

    teams: tuple[str, str]
    server_params: dict[str, str]
    frames: list[GameFrame]


def is_rcg(path: Path) -> bool:
    """Whether `path` is a game log: its first line starts with ``ULG`` (gzipped logs: no)."""
    try:
        with Path(path).open("rb") as file:
            return file.read(3) == b"ULG"
    except (FileNotFoundError, IsADirectoryError, NotADirectoryError):
        return False


def read_rcg(path: Path) -> RcgGame:
    """Read a text game log (ours or rcssserver's) back into frames in our field frame.

    ``show``, ``playmode``, ``team`` and ``server_param`` lines are read; ``player_param``,
    ``player_type``, ``msg``, ``team_graphic_*`` and other well-formed lines are passed over.
    y, vy and the body angle are negated, degrees become radians and per-cycle velocities m/s,
    with the cycle from ``simulator_step`` (ms), or :data:`DEFAULT_CYCLE_S`. Each frame carries
    the play mode and score of the last ``playmode`` and ``team`` lines before it.

    Raises:
        ValueError: Naming the file and line: the first line is not a text header
            (:data:`READABLE_HEADERS`), or a line is malformed.
    """
    path = Path(path)
    teams: tuple[str, str] | None = None
    params: dict[str, str] = {}
    frames: list[GameFrame] = []
    mode = NO_PLAY_MODE
    score = (0, 0)
    dt = DEFAULT_CYCLE_S
    with path.open(encoding="utf-8", errors="replace", newline=None) as file:
        header = file.readline().strip()
        if header not in READABLE_HEADERS:
            raise ValueError(
                f"{path}:1: not a text game log: the first line is {header[:40]!r}, "
                f"expected one of {', '.join(READABLE_HEADERS)}"
            )
        for number, raw in enumerate(file, start=2):
            line = raw.strip()
            if not line:
                continue
            head = _LINE_NAME.match(line)
            if head is None or line.count("(") != line.count(")"):
                raise _malformed(path, number, "not one parenthesised record", line)
            kind = head.group(1)
            if kind == "show":
                frames.append(_read_show(path, number, line, mode, score, dt))
            elif kind == "playmode":
                found = _PLAYMODE_LINE.fullmatch(line)
                if found is None:
                    raise _malformed(path, number, "bad playmode line", line)
                mode = found.group(2)
            elif kind == "team":
                team = _TEAM_LINE.fullmatch(line)
                if team is None:
                    raise _malformed(path, number, "bad team line", line)
                if teams is None:
                    teams = (team.group(2), team.group(3))
                score = (_whole(path, number, team.group(4), line),
                         _whole(path, number, team.group(5), line))  # fmt: skip
            elif kind == "server_param":
                if _SERVER_PARAM_LINE.fullmatch(line) is None:
                    raise _malformed(path, number, "bad server_param line", line)
                entries = [(m.group(1), m.group(2)) for m in _PARAM.finditer(line)]
                for name, value in entries:
                    if not value.startswith('"') and _overflows(value):
                        raise _malformed(path, number, f"{name}: not a finite number", line)
                params.update((name, value.strip('"')) for name, value in entries)
                dt = _cycle_s(path, number, params.get("simulator_step"), line)
    return RcgGame(teams=teams or ("", ""), server_params=params, frames=frames)


def _cycle_s(path: Path, number: int, step_ms: str | None, line: str) -> float:
    if step_ms is None:
        return DEFAULT_CYCLE_S
    try:
        dt = float(step_ms) / 1000.0
    except ValueError:
        dt = math.nan
    if not (math.isfinite(dt) and dt > 0.0):
        raise _malformed(path, number, f"simulator_step {step_ms!r} is not a positive number", line)
    return dt


def _read_show(
    path: Path, number: int, line: str, mode: str, score: tuple[int, int], dt: float
) -> GameFrame:
    """One show line as a frame."""
    show = _SHOW.match(line)
    if show is None:
        raise _malformed(path, number, "bad show line (cycle or ball)", line)
    rest = line[show.end() :]
    entries = _PLAYER.findall(rest)
    if len(entries) != rest.count("(("):
        raise _malformed(path, number, "bad player in show line", line)
    tick = _whole(path, number, show.group(1), line)
    bx, by, bvx, bvy = _finite(path, number, show.group(2, 3, 4, 5), line)
    players: dict[PlayerRef, BodyState] = {}
    for side, unum, state, *numbers in entries:
        if len(state) > _MAX_DIGITS:
            raise _malformed(path, number, "a player state too long to be one", line)
        if not int(state, 16) & _STAND:
            continue  # disabled: a disconnected player's placeholder
        x, y, vx, vy, body, _neck = _finite(path, number, numbers, line)
        ref = PlayerRef(LEFT if side == "l" else RIGHT, _whole(path, number, unum, line))
        players[ref] = BodyState(
            x,
            0.0 - y,
            wrap_angle(0.0 - body * _DEG2RAD),
            vx / dt,
            0.0 - vy / dt,
        )
    ball = BodyState(bx, 0.0 - by, 0.0, bvx / dt, 0.0 - bvy / dt)
    states = (ball, *players.values())
    if not all(math.isfinite(v) for s in states for v in (s.vx, s.vy)):  # 1e308 / 0.1 s
        raise _malformed(path, number, "a velocity beyond a double's range", line)
    truth = Truth(tick=tick, time_s=tick * dt, ball=ball, players=players)
    return GameFrame(truth=truth, play_mode=mode, score=score)


_MAX_DIGITS = 18
"""The most digits a whole number of a game log may have (cycles, scores: within 64 bits)."""


def _whole(path: Path, number: int, text: str, line: str) -> int:
    """A whole number of a line (matched as digits), refused when it has too many digits."""
    if len(text.lstrip("-")) > _MAX_DIGITS:
        raise _malformed(path, number, f"a number of more than {_MAX_DIGITS} digits", line)
    return int(text)


def _finite(path: Path, number: int, texts: Sequence[str], line: str) -> list[float]:
    """The numbers of a line; one that overflows a double (``1e999``) is refused like ``inf``."""
    values = [float(text) for text in texts]
    if not all(math.isfinite(v) for v in values):
        raise _malformed(path, number, "a number beyond a double's range", line)
    return values


def _overflows(text: str) -> bool:
    """Whether `text` reads as a number that is not finite (``1e999``, ``inf``, ``nan``)."""
    try:
        return not math.isfinite(float(text))
    except ValueError:
        return False  # not a number at all: a bare string value


def _malformed(path: Path, number: int, reason: str, line: str) -> ValueError:
    shown = line if len(line) <= 120 else line[:117] + "..."
    return ValueError(f"{path}:{number}: {reason}: {shown!r}")
