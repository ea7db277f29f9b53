"""``robotsoccer serve``: a served field model on the wire, with its game log and recording.

The server itself (the game, its text protocol and its sockets) lives below the percept/action
line, with the model it serves (``field_models.soccer_server.serving`` and ``.udp``); the CLI
builds it. This module runs it for the command: it logs what the server says, and with
``--record`` writes the game as an rcssserver game log (``.rcg``, every cycle stepped) and
converts that log into a rerun recording (``.rrd``) when the server stops.

It names no concrete field model: it sees the served game through :class:`ServedGameLike` and
the server through :class:`ServerLike`.
"""

from __future__ import annotations

import sys
import time
from collections.abc import Callable, Mapping
from pathlib import Path
from typing import Any, Protocol

from field_models.arena import CommandTally
from field_models.protocol import BodyState, PlayerRef, Truth
from robotsoccer.replay.frames import GameFrame
from robotsoccer.replay.rcg import SLOTS
from robotsoccer.replay.rcg_write import RcgWriter, log_team_name


class ServedGameLike(Protocol):
    """What the command reads of a served game after each cycle."""

    @property
    def time(self) -> int:
        """Cycles stepped."""
        ...

    @property
    def dt_s(self) -> float:
        """One cycle [s]."""
        ...

    @property
    def play_mode(self) -> str:
        """The play mode."""
        ...

    def truth(self) -> tuple[BodyState, dict[PlayerRef, BodyState]]:
        """Ball and connected players, exactly."""
        ...

    def score(self) -> tuple[int, int]:
        """Goals of each team."""
        ...

    def team_names(self) -> tuple[str | None, str | None]:
        """Team names so far."""
        ...

    def command_tally(self) -> dict[PlayerRef, CommandTally]:
        """Each player's command counts."""
        ...


class ServerLike(Protocol):
    """The socket server, as the command drives it."""

    @property
    def ports(self) -> tuple[int, int, int]:
        """Player, trainer, online-coach ports."""
        ...

    def serve(
        self,
        *,
        cycles: int | None = None,
        seconds: float | None = None,
        stop: Callable[[], bool] | None = None,
        on_step: Callable[[Any], None] | None = None,
    ) -> Any:
        """Serve until a limit."""
        ...

    def close(self) -> None:
        """Close every socket."""
        ...


def stderr_log() -> Callable[[str], None]:
    """A log that prints ``[seconds] line`` on stderr, seconds since the log was made."""
    start = time.monotonic()

    def log(line: str) -> None:
        print(f"[{time.monotonic() - start:9.3f}] {line}", file=sys.stderr, flush=True)

    return log


def frame_of(game: ServedGameLike) -> GameFrame:
    """The game's state after its last cycle as a game-log frame."""
    ball, players = game.truth()
    tick = game.time
    truth = Truth(tick, tick * game.dt_s, ball, players)
    return GameFrame(truth, game.play_mode, game.score(), game.command_tally())


class GameRecorder:
    """Writes a served game's cycles into an ``.rcg``; :meth:`finish` adds the ``.rrd``.

    Args:
        folder: Where ``serve_<seed>.rcg`` (and ``.rrd``) go.
        stem: The files' name without suffix.
        dt_s: One cycle [s].
        server_params: The ``server_param`` line's values (the served server's own).
    """

    def __init__(
        self, folder: Path, stem: str, dt_s: float, server_params: Mapping[str, Any]
    ) -> None:
        folder.mkdir(parents=True, exist_ok=True)
        self.rcg = folder / f"{stem}.rcg"
        self._writer = RcgWriter(
            self.rcg,
            players=SLOTS,
            teams=("null", "null"),
            dt_s=dt_s,
            server_params=dict(server_params),
            goal_scenes=False,  # the served referee plays out the after-goal pause itself
        )
        self._frames = 0

    def __call__(self, game: ServedGameLike) -> None:
        """Log the cycle the game just stepped."""
        left, right = game.team_names()
        self._writer.rename_teams(
            (log_team_name(left) if left else "null", log_team_name(right) if right else "null")
        )
        self._writer.write(frame_of(game))
        self._frames += 1

    def finish(self, score: tuple[int, int]) -> tuple[Path, Path | None]:
        """Close the log (``time_over`` last) and convert it; returns (.rcg, .rrd or None)."""
        if self._frames == 0:
            self._writer.close()
            self.rcg.unlink(missing_ok=True)
            return self.rcg, None
        self._writer.finish(score)
        from robotsoccer.replay.game_log import rrd_from_rcg  # rerun loads late

        return self.rcg, rrd_from_rcg(self.rcg)


def run_serve(
    server: ServerLike,
    game: ServedGameLike,
    *,
    cycles: int | None,
    seconds: float | None,
    recorder: GameRecorder | None,
    log: Callable[[str], None],
) -> int:
    """Serve until a limit; close the sockets and the recording (also on Ctrl-C); 0 when done."""
    player, trainer, olcoach = server.ports
    log(f"serving on player port {player}, trainer port {trainer}, online-coach port {olcoach}")
    try:
        stats = server.serve(cycles=cycles, seconds=seconds, on_step=recorder)
        log(
            f"stopped after {stats.cycles} cycles, {stats.datagrams} datagrams, "
            f"{stats.errors} error replies"
        )
    finally:  # Ctrl-C goes on to the CLI (exit 130) once the sockets and files are closed
        server.close()
        if recorder is not None:
            rcg, rrd = recorder.finish(game.score())
            log(f"game log {rcg}" + (f", recording {rrd}" if rrd else " (no cycle: none written)"))
    return 0
