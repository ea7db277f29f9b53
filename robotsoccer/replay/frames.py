"""What a match recording keeps of one instant: the truth plus the referee's state.

A :class:`GameFrame` is the one record both match outputs are written from: the rerun
recording (:mod:`robotsoccer.replay.match_recording`) and the Soccer Server's text game log
(:mod:`robotsoccer.replay.rcg`). Reading an ``.rcg`` file back gives the same records, so a
replay of either kind draws the same thing.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

from field_models.arena import CommandTally
from field_models.protocol import PlayerRef, Truth

TEAM_NAME_CHARS = 16
"""Longest team name the game log carries (rcssserver limits names to 16 characters)."""


@dataclass(frozen=True, slots=True)
class GameFrame:
    """One recorded tick of a match.

    Attributes:
        truth: Exact state of the ball and every player (field frame, SI units).
        play_mode: The referee's play mode, as the Soccer Server spells it (``play_on``,
            ``kick_off_l``, ``kick_in_r``, ``goal_l``, ...; the robot table's referee uses the
            same names for its restarts).
        score: Goals of the left and the right team so far.
        commands: Each player's commands as a Soccer Server counts them, and the tick's kicks
            (:class:`~field_models.arena.CommandTally`), where the field model counts them;
            None elsewhere (a game log then writes zeros).
    """

    truth: Truth
    play_mode: str
    score: tuple[int, int]
    commands: Mapping[PlayerRef, CommandTally] | None = None

    @property
    def tick(self) -> int:
        """The tick the frame shows."""
        return self.truth.tick
