"""Reading a Soccer Server text game log (``.rcg``: ``ULG4`` to ``ULG6``), ours or rcssserver's.

:func:`read_rcg` reads the show, play-mode, team and server-parameter lines back into frames in
our field frame; the format is described in :mod:`robotsoccer.replay.rcg`. Every malformed line
is refused with the file and line named.
"""

from __future__ import annotations

import math
import re
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

from field_models.protocol import LEFT, RIGHT, BodyState, PlayerRef, Truth, wrap_angle
from robotsoccer.replay.frames import GameFrame
from robotsoccer.replay.rcg import DEFAULT_CYCLE_S, NO_PLAY_MODE, READABLE_HEADERS, STAND

_DEG2RAD = math.pi / 180.0
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
        if not int(state, 16) & STAND:
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
