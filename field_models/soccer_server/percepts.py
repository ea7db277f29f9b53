"""Client percepts on the Soccer Server model, built from see and hear message contents.

A percept (``field_models.protocol.Percept``) is what the paper's clients work from (DESIGN.md
§2). On this model it comes from the see message (shared `specs/soccer_server.md` §3):

* directions: the server's integer degrees, clockwise-positive in our frame, become radians
  counter-clockwise positive: ``angle_rad = -radians(direction)``;
* distances stay exactly as the message gives them (quantised, or exact in perfect perception);
* changes: ``dist_change`` [m/cycle] / cycle length → m/s, ``dir_change`` [deg/cycle] → rad/s
  with the sign flipped like directions;
* the ball is the ``(b)`` entry, or the felt ``(B)`` when it is behind the player within
  ``visible_distance`` (a real client knows what ``(B)`` is); likewise ``(P)`` gives a player
  with no team or number. Objects without a distance (low quality) are left out: a percept
  always has distances;
* flags and goals seen become ``SeenLandmark`` entries under their short server names
  (``"g r"``, ``"f p r c"``); felt ``(F)``/``(G)`` (name unknown) and lines (their direction is
  an angle to the line, not to a point) are left out.

Two routes give the same percept: text (``render_see`` → ``parse_see`` →
:func:`percept_from_see`) and the structured fast path :func:`percept_from_state`, which skips
the text and, by default, every landmark but the goals;
``tests/field_models/soccer_server/test_percepts.py`` proves they agree. In perfect perception
(``SensingParams.perfect``) the see carries exact values and so does the percept, by either
route.
"""

from __future__ import annotations

import math

from field_models.protocol import Heard, Percept, PlayerRef, SeenBall, SeenLandmark, SeenPlayer
from field_models.seeding import Rng
from field_models.soccer_server.hearing import HearInfo
from field_models.soccer_server.sensing import (
    Bodies,
    LandmarkMode,
    SeeInfo,
    SeenObject,
    observe,
)
from field_models.soccer_server.sensing_params import SensingParams

_DEG2RAD = math.pi / 180.0


def _angle(direction_deg: float) -> float:
    """Server degrees (clockwise in our frame) → our CCW radians."""
    return -(direction_deg * _DEG2RAD) + 0.0


def _ball(obj: SeenObject, cycle_s: float) -> SeenBall:
    """A ``(b)``/``(B)`` entry as a SeenBall."""
    assert obj.distance is not None
    return SeenBall(
        distance_m=obj.distance,
        angle_rad=_angle(obj.direction),
        distance_change_mps=None if obj.dist_change is None else obj.dist_change / cycle_s,
        angle_change_radps=None if obj.dir_change is None else _angle(obj.dir_change) / cycle_s,
    )


def percept_from_see(
    info: SeeInfo,
    player: PlayerRef,
    tick: int,
    observed_tick: int,
    heard: tuple[Heard, ...] = (),
    *,
    cycle_s: float = 0.1,
    neck_rad: float = 0.0,
) -> Percept:
    """The percept of `player` from the content of one see message.

    Args:
        info: The see message content (from :func:`~.sensing.observe` or ``parse_see``).
        player: Whose percept.
        tick: Cycle at which the percept reaches the client.
        observed_tick: Cycle whose state the see shows.
        heard: Messages heard since the previous percept.
        cycle_s: Cycle length [s], to turn per-cycle changes into per-second rates.
        neck_rad: The player's neck angle when the see was sampled [rad], CCW: the see's
            directions are relative to the head (body + neck), and the percept says so.
    """
    ball: SeenBall | None = None
    seen: list[SeenPlayer] = []
    marks: list[SeenLandmark] = []
    for obj in info.objects:
        name = obj.name
        if obj.distance is None:
            continue
        kind = name[0]
        if kind == "b" or kind == "B":
            if ball is None:
                ball = _ball(obj, cycle_s)
        elif kind == "p" or kind == "P":
            seen.append(SeenPlayer(obj.distance, _angle(obj.direction), obj.team, obj.unum))
        elif (kind == "f" or kind == "g") and len(name) > 1:
            marks.append(SeenLandmark(name, obj.distance, _angle(obj.direction)))
    return Percept(player, tick, observed_tick, ball, tuple(seen), heard, tuple(marks), neck_rad)


def heard_from_hear(info: HearInfo, listener: PlayerRef) -> Heard | None:
    """A hear message as a percept's Heard entry; None for a short form (no text).

    The sender is known for the listener's own messages (``self``) and for teammates in
    protocol >= 8 (``our Unum``); referee, coach, opponent and pre-8 player messages have none.
    """
    if info.text is None:
        return None
    sender: PlayerRef | None = None
    if info.sender == "self":
        sender = listener
    elif info.sender == "player" and info.team == "our" and info.unum is not None:
        sender = PlayerRef(listener.team, info.unum)
    direction = None if info.direction is None else _angle(info.direction)
    return Heard(info.text, sender, direction, info.time)


def percept_from_state(
    observer: int,
    bodies: Bodies,
    players: tuple[PlayerRef, ...],
    time: int,
    params: SensingParams,
    rng: Rng,
    *,
    heard: tuple[Heard, ...] = (),
    landmarks: LandmarkMode = "goals",
) -> Percept:
    """The structured fast path: the percept a see at `time` gives, without any text.

    Arguments are those of :func:`~.sensing.observe` (velocities in m/cycle); `time` is the
    percept's ``observed_tick`` and also its ``tick``: the arena's see reaches the client in the
    cycle it shows (:func:`percept_from_see` takes a later one). `heard`: the messages heard
    since the previous percept. `landmarks` picks what the percept's landmarks hold:
    ``"goals"`` (default, cheap), ``"all"`` flags and goals, or ``"none"``. It draws the same
    random numbers as the full see, so for the same generator state it equals the text route's
    percept (restricted to the same landmarks). The bodies' `neck` (per row, CCW; None: all 0)
    turns the view, and the percept carries the observer's neck angle.
    """
    info = observe(observer, bodies, players, time, params, rng, landmarks=landmarks)
    cycle_s = params.simulator_step_ms / 1000.0
    neck_rad = 0.0 if bodies.neck is None else bodies.neck[observer]
    return percept_from_see(
        info, players[observer - 1], time, time, heard, cycle_s=cycle_s, neck_rad=neck_rad
    )
