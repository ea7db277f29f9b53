"""Sensing parameters of the Soccer Server field model: see timing, view cone, quantisation.

One frozen record, :class:`SensingParams`, filled from the ``[sensing]`` table of a soccer-server
preset (``field_models/presets/soccer_server/*.toml``) by :func:`field_models.presets.load_record`.
Every field names the ``server.conf`` parameter it stands for (shared `specs/soccer_server.md`
§3, §2.6, §7). Units are in the names; the view half-angle is stored in radians, the see
interval in integer milliseconds (the server counts its sensor timers in ms, §3.1).

Choices made where the spec leaves one open (each is a field, so a preset can change it):

* ``direction_mode``: ``"truncate"`` (protocol < 7, the paper's era) or ``"round"`` (protocol
  >= 7, [CL 7.04]); §3.2.
* ``protocol_version``: the client protocol the text messages follow (names, quoting, hear
  form, BodyDir/HeadDir). 3 for the paper's era (pre-4: long names, no body/head directions),
  19 for today.
* ``report_changes``: whether distance/direction changes are ever sent. The paper's Figure 4
  shows a resting ball at 11 m without them, where a modern server prints ``0 0``; the 1996
  values therefore turn them off.
* ``landmark_set``: ``"full"`` (55 flags and goals since [CL 4.00]) or ``"1996"`` (centre,
  corner, penalty-area and goal flags, the set the spec says the 1996–97 servers had; the exact
  1997 set was not found, §3.8).
* ``send_step_ms`` for 1996: 250 ms (the paper's §5 "discrete intervals (250 msec)"); the
  Figure 4 trace's see every 5 cycles is ``send_step_ms = 500``.
* ``perfect``: perfect perception, our own switch (no server has it): sees carry exact
  distances, directions and changes, and always the team and number. The view cone and the see
  timing stay, because they are what the player can see, not noise.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field
from typing import Any, Literal

from field_models.presets import RecordError, check_ranges, non_negative, positive

DirectionMode = Literal["truncate", "round"]
"""How a direction becomes integer degrees: protocol < 7 truncates, >= 7 rounds (§3.2)."""
ViewWidth = Literal["narrow", "normal", "wide"]
"""The ``change_view`` width (§3.1)."""
ViewQuality = Literal["high", "low"]
"""The ``change_view`` quality (§3.1)."""
LandmarkSet = Literal["full", "1996"]
"""Which flags and goals the pitch has (§3.8)."""

MAX_STEP_MS = 10_000
"""The longest cycle, see interval or timer step [ms]."""
MAX_DISTANCE_M = 1000.0
"""The longest sensing distance [m]."""
MAX_COUNT = 1_000_000
"""The largest hearing capacity count."""

WIDTH_FACTOR: dict[ViewWidth, float] = {"narrow": 0.5, "normal": 1.0, "wide": 2.0}
"""View-cone width and see-interval factor per view width (§3.1)."""
QUALITY_FACTOR: dict[ViewQuality, float] = {"high": 1.0, "low": 0.5}
"""See-interval factor per view quality (§3.1: low quality halves the interval)."""


@dataclass(frozen=True, slots=True)
class SensingParams:
    """What a Soccer Server player sees and hears, and when (specs/soccer_server.md §3, §2.6).

    Attributes:
        send_step_ms: server.conf ``send_step``: see interval at normal width, high quality [ms].
        simulator_step_ms: server.conf ``simulator_step``: the cycle length [ms].
        recv_step_ms: server.conf ``recv_step``: the server's timer resolution; sensor timers
            fire on the first multiple of it at or after their due time [ms].
        view_width: the player's ``change_view`` width: narrow | normal | wide.
        view_quality: the player's ``change_view`` quality: high | low.
        view_half_angle_rad: server.conf ``visible_angle`` / 2 at normal width (90° / 2) [rad].
        visible_distance_m: server.conf ``visible_distance``: objects this close are "felt"
            behind the player (capitalised names, distance and direction only) [m].
        quantize_step: server.conf ``quantize_step``: log-distance step for ball and players.
        quantize_step_l: server.conf ``quantize_step_l``: log-distance step for flags, goals,
            lines.
        distance_resolution_m: the final rounding of every distance (0.1 m, compiled in) [m].
        dir_change_step_deg: rounding step of the reported direction change (0.1°) [deg].
        dist_change_rel_step: rounding step of the relative distance change (0.02).
        direction_mode: ``"truncate"`` (protocol < 7) or ``"round"`` (>= 7) the direction.
        protocol_version: client protocol of the text messages (3 for 1996, 19 for today).
        report_changes: send distance/direction changes at all.
        landmark_set: ``"full"`` (55 flags/goals) or ``"1996"`` (the reduced early set).
        unum_far_length_m: the player type's ``unum_far_length`` (not a server.conf
            parameter): uniform number always shown [m].
        unum_too_far_length_m: the player type's ``unum_too_far_length``: never shown beyond
            [m]; also the limit of ball/flag changes (protocol < 18, §3.4).
        team_far_length_m: the player type's ``team_far_length``: team always shown [m].
        team_too_far_length_m: the player type's ``team_too_far_length``: team never shown
            beyond [m].
        audio_cut_dist_m: server.conf ``audio_cut_dist``: hearing range of a say [m].
        say_msg_size: server.conf ``say_msg_size``: longest say message [characters].
        hear_max: server.conf ``hear_max``: hearing capacity ceiling.
        hear_inc: server.conf ``hear_inc``: capacity regained per cycle.
        hear_decay: server.conf ``hear_decay``: capacity one heard message costs.
        hear_per_team: separate capacities for teammates and opponents (since 8.0) or one.
        perfect: perfect perception: exact distances, directions and changes (no quantisation,
            rounding or random omission), team and number always shown; the cone and the see
            timing as above.
        percept_flags: a client's percept carries every flag it sees as well as the goals
            (the see message always holds them; the fast percept path leaves the flags out
            unless a client localises itself from them, as a match's players do).
    """

    send_step_ms: int = field(metadata=positive("server.conf send_step", high=MAX_STEP_MS, low=1))
    view_half_angle_rad: float = field(
        metadata=positive("server.conf visible_angle / 2", high=math.pi)
    )
    visible_distance_m: float = field(
        metadata=non_negative("server.conf visible_distance", high=MAX_DISTANCE_M)
    )
    quantize_step: float = field(metadata=positive("server.conf quantize_step", high=10))
    quantize_step_l: float = field(metadata=positive("server.conf quantize_step_l", high=10))
    direction_mode: DirectionMode
    # rcssserver 19 speaks protocols 1 to 19 (a client asking for more gets 19's messages).
    protocol_version: int = field(metadata=positive("client protocol version", high=19, low=1))
    report_changes: bool
    landmark_set: LandmarkSet
    unum_far_length_m: float = field(
        metadata=non_negative("player type unum_far_length", high=MAX_DISTANCE_M)
    )
    unum_too_far_length_m: float = field(
        metadata=non_negative("player type unum_too_far_length", high=MAX_DISTANCE_M)
    )
    team_far_length_m: float = field(
        metadata=non_negative("player type team_far_length", high=MAX_DISTANCE_M)
    )
    team_too_far_length_m: float = field(
        metadata=non_negative("player type team_too_far_length", high=MAX_DISTANCE_M)
    )
    audio_cut_dist_m: float = field(
        metadata=non_negative("server.conf audio_cut_dist", high=MAX_DISTANCE_M)
    )
    say_msg_size: int = field(metadata=positive("server.conf say_msg_size", high=100_000, low=1))
    hear_max: int = field(metadata=non_negative("server.conf hear_max", high=MAX_COUNT))
    hear_inc: int = field(metadata=non_negative("server.conf hear_inc", high=MAX_COUNT))
    hear_decay: int = field(metadata=non_negative("server.conf hear_decay", high=MAX_COUNT))
    hear_per_team: bool
    simulator_step_ms: int = field(
        default=100, metadata=positive("server.conf simulator_step", high=MAX_STEP_MS, low=1)
    )
    recv_step_ms: int = field(
        default=10, metadata=positive("server.conf recv_step", high=MAX_STEP_MS, low=1)
    )
    view_width: ViewWidth = "normal"
    view_quality: ViewQuality = "high"
    distance_resolution_m: float = field(
        default=0.1, metadata=positive("compiled in: 0.1 m", high=10)
    )
    dir_change_step_deg: float = field(
        default=0.1, metadata=positive("compiled in: 0.1°", high=360)
    )
    dist_change_rel_step: float = field(
        default=0.02, metadata=positive("compiled in: 0.02", high=10)
    )
    perfect: bool = False
    percept_flags: bool = False

    def __post_init__(self) -> None:
        check_ranges(self)
        if self.unum_too_far_length_m < self.unum_far_length_m:
            raise RecordError("unum_too_far_length_m", "expected >= unum_far_length_m")
        if self.team_too_far_length_m < self.team_far_length_m:
            raise RecordError("team_too_far_length_m", "expected >= team_far_length_m")

    @property
    def half_angle_rad(self) -> float:
        """Half-width of the view cone for the current view width [rad] (§3.1)."""
        return self.view_half_angle_rad * WIDTH_FACTOR[self.view_width]

    @property
    def see_interval_ms(self) -> float:
        """Time between two see messages for the current view width and quality [ms] (§3.1)."""
        return self.send_step_ms * WIDTH_FACTOR[self.view_width] * QUALITY_FACTOR[self.view_quality]

    @property
    def truncate(self) -> bool:
        """True when directions are truncated toward zero (protocol < 7), False when rounded."""
        return self.direction_mode == "truncate"

    def replace(self, **changes: Any) -> SensingParams:
        """A copy with some fields changed (validated again)."""
        return dataclasses.replace(self, **changes)


SENSING_19 = SensingParams(
    send_step_ms=150,
    view_half_angle_rad=math.radians(45.0),
    visible_distance_m=3.0,
    quantize_step=0.1,
    quantize_step_l=0.01,
    direction_mode="round",
    protocol_version=19,
    report_changes=True,
    landmark_set="full",
    unum_far_length_m=20.0,
    unum_too_far_length_m=40.0,
    team_far_length_m=125.1,
    team_too_far_length_m=125.1,
    audio_cut_dist_m=50.0,
    say_msg_size=10,
    hear_max=1,
    hear_inc=1,
    hear_decay=1,
    hear_per_team=True,
)
"""Today's defaults (rcssserver 19.0.0, §7)."""

SENSING_1996 = SensingParams(
    send_step_ms=250,
    view_half_angle_rad=math.radians(45.0),
    visible_distance_m=3.0,
    quantize_step=0.1,
    quantize_step_l=0.01,
    direction_mode="truncate",
    protocol_version=3,
    report_changes=False,
    landmark_set="1996",
    unum_far_length_m=20.0,
    unum_too_far_length_m=40.0,
    team_far_length_m=40.0,
    team_too_far_length_m=60.0,
    audio_cut_dist_m=50.0,
    say_msg_size=512,
    hear_max=2,
    hear_inc=1,
    hear_decay=2,
    hear_per_team=False,
)
"""The paper's era: 1998 (4.06) values where 1996 ones are unknown (§7), 250 ms sees (paper §5)."""


def sensing_params_for_era(era: str) -> SensingParams:
    """The built-in sensing values of an era: ``"1996"`` or ``"19"``.

    Presets are the source of truth; these are for tests and for building presets.
    """
    eras = {"1996": SENSING_1996, "19": SENSING_19}
    if era not in eras:
        raise ValueError(f"era: expected one of 1996, 19; got {era!r}")
    return eras[era]


def sensing_table(params: SensingParams) -> dict[str, Any]:
    """The ``[sensing]`` TOML table (as a dict) that loads back to `params`."""
    return {f.name: getattr(params, f.name) for f in dataclasses.fields(params)}
