"""Writing the Soccer Server's text game log (``.rcg``, ``ULG5``) from our frames.

:class:`RcgWriter` writes what rcssserver 19.0.0 would write for the same match: the format
and what each field holds are described in :mod:`robotsoccer.replay.rcg`, with the sources
they were read from.
"""

from __future__ import annotations

import dataclasses
import math
import os
import re
from collections.abc import Collection, Mapping
from pathlib import Path
from types import TracebackType

from field_models.arena import COMMAND_COUNTERS, CommandTally
from field_models.protocol import LEFT, RIGHT, BodyState, PlayerRef
from field_models.rcss_params import (
    PLAYER_TYPE_FIELDS,
    ParamValue,
    cxx_text,
    default_player_params,
    default_player_type,
    default_server_params,
)
from robotsoccer.replay.frames import TEAM_NAME_CHARS, GameFrame
from robotsoccer.replay.rcg import (
    AFTER_GOAL_WAIT,
    FIRST_CYCLE,
    HEADER,
    MAX_PLAYERS_PER_TEAM,
    SLOTS,
    STAND,
    TIME_OVER,
)

# rcssserver's PlayerState bits (src/types.h).
_KICK = 0x2
_KICK_FAULT = 0x4
_GOALIE = 0x8
_NO_COUNTS = (0,) * len(COMMAND_COUNTERS)
_NO_TALLY = CommandTally(_NO_COUNTS)
_PITCH_WIDTH_M = 68.0  # rcssserver's compiled ServerParam::PITCH_WIDTH
_RAD2DEG = 180.0 / math.pi
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
            numbers 1..11. A slot of :data:`~robotsoccer.replay.rcg.SLOTS` whose player a frame
            lacks is written disconnected.
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
                STAND | (_GOALIE if ref in goalies else 0),
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
