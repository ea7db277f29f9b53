"""Soccer Server hearing (spec §2.6): who hears a say, with which capacity, in which words.

Pure functions of the state, as :mod:`field_models.soccer_server.sensing` is for sees: the
range (``audio_cut_dist``), the length and character rules of a say, each listener's hearing
capacity (:class:`HearingBudget`) and the hear messages' content (:class:`HearInfo`), as
rcssserver's ``audio.cpp`` makes them. Inputs are in our frame (y up, CCW radians); directions
come out in the server's integer degrees and sign.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import NamedTuple

from field_models import fpmath
from field_models.protocol import PlayerRef, wrap_angle
from field_models.soccer_server.see_numbers import RAD2DEG, degrees
from field_models.soccer_server.sensing_params import SensingParams

SAY_ALLOWED_CHARS = frozenset(
    "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789 ().+*/?<>_-"
)
"""Characters a say message may hold (§2.6, today's server; applied to every era)."""


class HearInfo(NamedTuple):
    """The content of one hear message (§2.6).

    Attributes:
        time: Server time (cycle) of the message.
        sender: ``"player"``, ``"self"``, ``"referee"``, ``"coach"``, ``"online_coach_left"`` or
            ``"online_coach_right"``.
        text: The message; None for the short form (hearing capacity exhausted, protocol >= 8).
        direction: Direction of the speaker relative to the listener's body [deg, server sign].
        team: ``"our"`` or ``"opp"`` for player messages in protocol >= 8, else None.
        unum: The speaker's uniform number for ``"our"`` messages in protocol >= 8, else None.
    """

    time: int
    sender: str
    text: str | None
    direction: int | None = None
    team: str | None = None
    unum: int | None = None


def say_allowed(text: str, params: SensingParams) -> bool:
    """True when the server would broadcast `text`: short enough and only allowed characters.

    A longer message is dropped whole (§2.6, ``say_msg_size``); so is one with a character
    outside :data:`SAY_ALLOWED_CHARS` (today's rule, also used for the 1996 era: it keeps the
    unquoted old hear format parseable). Empty messages are refused.
    """
    return 0 < len(text) <= params.say_msg_size and all(ch in SAY_ALLOWED_CHARS for ch in text)


def hearers(
    speaker: int, x: Sequence[float], y: Sequence[float], params: SensingParams
) -> list[int]:
    """Player rows within ``audio_cut_dist`` of row `speaker`, the speaker included (§2.6)."""
    sx, sy = x[speaker], y[speaker]
    limit2 = params.audio_cut_dist_m**2
    return [
        row
        for row in range(1, len(x))
        if row == speaker or (x[row] - sx) ** 2 + (y[row] - sy) ** 2 <= limit2
    ]


@dataclass(slots=True)
class HearingBudget:
    """One listener's hearing capacity (§2.6): ``hear_max``, ``hear_inc``, ``hear_decay``.

    With ``hear_per_team`` (servers >= 8) teammates and opponents have separate counters;
    otherwise (1990s) one counter serves both. Referee, coach and own messages cost nothing.
    """

    params: SensingParams
    teammates: int = -1
    opponents: int = -1

    def __post_init__(self) -> None:
        if self.teammates < 0:
            self.teammates = self.params.hear_max
        if self.opponents < 0:
            self.opponents = self.params.hear_max

    def new_cycle(self) -> None:
        """Regain ``hear_inc`` per counter, up to ``hear_max`` (called once per cycle)."""
        p = self.params
        self.teammates = min(p.hear_max, self.teammates + p.hear_inc)
        self.opponents = min(p.hear_max, self.opponents + p.hear_inc)

    def take(self, same_team: bool) -> bool:
        """Spend ``hear_decay`` for a message from a player; False when capacity is short."""
        cost = self.params.hear_decay
        use_team = same_team or not self.params.hear_per_team
        have = self.teammates if use_team else self.opponents
        if have < cost:
            return False
        if use_team:
            self.teammates -= cost
        else:
            self.opponents -= cost
        return True


def hear_direction_truncates(protocol: int) -> bool:
    """Hear directions: truncated before 7, rounded in 7, truncated again from 8 (audio.cpp)."""
    return protocol != 7


def deliver_says(
    says: Sequence[tuple[int, str]],
    x: Sequence[float],
    y: Sequence[float],
    heading: Sequence[float],
    players: tuple[PlayerRef, ...],
    time: int,
    params: SensingParams,
    budgets: dict[int, HearingBudget] | None = None,
) -> dict[int, list[HearInfo]]:
    """Who hears which say of this cycle, as hear-message contents per listener row (§2.6).

    Args:
        says: (speaker row, text) in the order the server received them.
        x: Per-object x [m], our frame (row 0 = ball).
        y: Per-object y [m], our frame.
        heading: Per-object heading [rad], CCW, our frame.
        players: Identities of rows 1..N.
        time: Server time stamped on the messages.
        params: Sensing parameters (range, length cap, capacity, protocol).
        budgets: Hearing capacity per listener row; None = unlimited.

    Returns:
        For each listener row that hears something, its hear messages in order. A message too
        long or with forbidden characters is heard by nobody. Over capacity, protocol >= 8
        listeners get the short form (text None); older ones get nothing.
    """
    out: dict[int, list[HearInfo]] = {}
    protocol = params.protocol_version
    trunc = hear_direction_truncates(protocol)
    for speaker, text in says:
        if not say_allowed(text, params):
            continue
        who = players[speaker - 1]
        say = _Say(time, text, speaker, who.number, protocol, trunc)
        for row in hearers(speaker, x, y, params):
            if row == speaker:
                out.setdefault(row, []).append(HearInfo(time, "self", text))
                continue
            same = players[row - 1].team == who.team
            full = budgets is None or budgets[row].take(same)
            heard = _player_hear(say, row, full, same, (x, y, heading))
            if heard is not None:
                out.setdefault(row, []).append(heard)
    return out


class _Say(NamedTuple):
    """One say being delivered: when, what, by whom, and the protocol's hear rules."""

    time: int
    text: str
    speaker: int  # the speaker's row
    unum: int
    protocol: int
    trunc: bool  # hear directions truncated (not rounded)


def _player_hear(
    say: _Say,
    row: int,
    full: bool,
    same: bool,
    state: tuple[Sequence[float], Sequence[float], Sequence[float]],
) -> HearInfo | None:
    """Listener `row`'s hear message of another player's say (``sendNonSelfPlayerAudio``).

    `state` is every object's (x, y, heading) in our frame; `full` whether the listener has the
    capacity for the text, `same` whether it is on the speaker's team.
    """
    x, y, heading = state
    time, protocol, speaker = say.time, say.protocol, say.speaker
    team = ("our" if same else "opp") if protocol >= 8 else None
    number = say.unum if protocol >= 8 and same else None
    if not full:
        return HearInfo(time, "player", None, None, team, number) if protocol >= 8 else None
    # Direction from the listener's body, server sign: negate our CCW angle.
    dy, dx = y[speaker] - y[row], x[speaker] - x[row]
    return HearInfo(
        time, "player", say.text, hear_degrees(dy, dx, heading[row], say.trunc), team, number
    )


_fast_atan2 = math.atan2
"""The C library's atan2 (a module name, so that a test can perturb it)."""

HEAR_MARGIN_RAD = 1e-9
"""How near a degree boundary or ±π a direction from the C library's ``atan2`` may come before
the CPU-independent :func:`field_models.fpmath.atan2` decides it; the two differ by a few units
in the last place (below 1e-14 rad here), so outside this margin both give the same degrees."""


def hear_degrees(dy: float, dx: float, heading: float, truncate: bool) -> int:
    """``degrees(wrap_angle(-(fpmath.atan2(dy, dx) - heading)), truncate)``, the same integer.

    A hear reports whole degrees (truncated: flips at whole degrees; rounded: at halves), so
    the C library's faster ``atan2`` gives the same report except next to such a boundary or
    where ±π wraps; there, and on an axis (signed zeros), the scalar :mod:`field_models.fpmath`
    rule decides.
    """
    rel = wrap_angle(-(_fast_atan2(dy, dx) - heading))
    deg = rel * RAD2DEG
    edge = deg if truncate else deg + 0.5
    if (
        abs(edge - round(edge)) < HEAR_MARGIN_RAD * RAD2DEG
        or abs(abs(rel) - math.pi) < HEAR_MARGIN_RAD
        or dx == 0.0
        or dy == 0.0
    ):
        rel = wrap_angle(-(fpmath.atan2(dy, dx) - heading))
    return degrees(rel, truncate)


def referee_hear(time: int, message: str) -> HearInfo:
    """A referee announcement (``goal_l_1``, ``kick_off_r``, ...) as heard by every player."""
    return HearInfo(time, "referee", message)
