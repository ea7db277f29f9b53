"""One latency-aware motion skill (turn then go) and one dribble rule, for every mind.

**Turns in flight.** A player's percept may have been sampled before a turn it sent shows in
it: the Soccer Server runs a command in the next cycle; the robots' camera sees a robot its
latency late, and a robot's timed turn takes a while (`field_models.robot_physics.host`). A
mind that decides on such a percept as if the turn were done turns twice and swings about.
:class:`TurnsInFlight` is the one record of this every mind keeps: each turn sent, with the
first observed tick from which a percept shows it (the tick sent plus the field's *settle*
ticks, fixed or a function of the angle). It answers two questions, one per setting:

* **reckon** — which turns does this percept not show yet? :meth:`TurnsInFlight.in_flight` is
  their sum, and :meth:`TurnsInFlight.view` turns the percept into the frame the player now
  reckons it faces, so the mind decides at every percept (the set play's
  :class:`~robotsoccer.skills.ball_sense.Heading`, settle one tick on the server and one camera
  period more on the robots; the interception defender, whose heading estimate,
  :attr:`TurnsInFlight.shown_rad`, is the turns its percepts show, settle one tick);
* **hold** — the conservative setting: is the last turn sent still unseen?
  :meth:`TurnsInFlight.holding`; the mind then decides nothing and the body goes on with its
  last command (the team minds, :mod:`robotsoccer.skills.team`, settle
  :meth:`~robotsoccer.skills.team_setup.TeamSetup.turn_ticks`: the latency plus the spin).

The two settings give different commands where a percept comes while a turn is under way (the
robots; on the Soccer Server model's 1996 preset, looking with the body, a see never comes
before the turn it follows shows, so there the hold never holds and reckoning rotates nothing),
so each caller keeps its measured setting; the README's "One motion skill (issue 23,
measured)" gives what the team minds' switch to reckoning costs (on the robots 0.4-0.6 goals a
game).

**Turn then go** (:func:`turn_then_go`): facing the target within a tolerance the player goes
(a dash; nothing for a player that only faces); else it turns toward it and goes, or only turns
(near a point, where running while turning circles it). The team minds, the set play and both
layer-1 defenders (:mod:`robotsoccer.skills.intercept`, :mod:`robotsoccer.skills.lead`) turn
so, each with its own tolerance: the team minds and the set play run within their facing angle
(inclusive), the defenders leave out a turn smaller than their turn tolerance (exclusive: a
tolerance of 0 keeps every turn, as the paper's client, even a turn by 0).

**The dribble rule** (:func:`dribble_speed`, :func:`dribble_power`): one for matches and the
set play. A dribble kick sends the ball :data:`DRIBBLE_UNITS` in :data:`DRIBBLE_PERIODS` sensor
periods (2 s on the Soccer Server's 1996 see), and no faster than half the speed from which the
player can stop within its kick margin (:func:`stop_speed`), so that it catches up with its
ball. Where the players push the ball instead of kicking it (a match on the robots, no coach to
kick for them) the dribble is a push at :data:`PUSH_DRIBBLE_POWER`.

Angles are radians, left positive; distances metres; ticks the field's.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable
from dataclasses import replace

from field_models.arena import FieldFacts
from field_models.protocol import Action, Percept, Turn, wrap_angle

DRIBBLE_UNITS = 4.0
DRIBBLE_PERIODS = 8.0
"""A dribble kick sends the ball this far [units] in this many sensor periods (2 s on the
Soccer Server's 1996 preset, a quarter second on the robots' 30 Hz camera)."""
PUSH_DRIBBLE_POWER = 40.0
"""A pushing player (no aimable kick and no coach to kick for it: a match on the robots)
dribbles by driving through the ball at this share of its top speed [%] (the match's setting
since issue 11; the kick rule's speed there, some 6% of the top speed, is not measured)."""

Settle = Callable[[float], int]
"""Ticks after a turn by an angle [rad] was sent until a percept observed then shows it."""


class TurnsInFlight:
    """The turns a player sent and which of them its percepts show (module docstring).

    Args:
        settle: Ticks from sending a turn to the first observed tick whose percept shows it: a
            number for every turn, or a function of the turn's angle.

    Attributes:
        heading_rad: The player's heading reckoned from every turn sent, wrapped [rad] (the
            set play's frame: 0 at its first percept).
        shown_rad: The sum of the turns the percepts show so far, in the order shown [rad]
            (the interception defender's heading estimate).
    """

    def __init__(self, settle: int | Settle = 1) -> None:
        self._settle = settle
        self.heading_rad = 0.0
        self.shown_rad = 0.0
        self._turns: list[tuple[int, float]] = []  # (first tick that shows it, angle), in order
        self._last_shown = -1  # the first observed tick that shows the last turn sent

    def settle_ticks(self, angle_rad: float) -> int:
        """Ticks until a percept shows a turn by `angle_rad`."""
        settle = self._settle
        return settle if isinstance(settle, int) else settle(angle_rad)

    def sent(self, tick: int, angle_rad: float) -> None:
        """The player sends a turn by `angle_rad` at `tick`."""
        shown = tick + self.settle_ticks(angle_rad)
        self.heading_rad = wrap_angle(self.heading_rad + angle_rad)
        self._turns.append((shown, angle_rad))
        self._last_shown = shown

    def note(self, actions: Iterable[Action], tick: int) -> None:
        """The player sends `actions` at `tick`: every turn among them is sent."""
        for action in actions:
            if isinstance(action, Turn):
                self.sent(tick, action.angle_rad)

    def in_flight(self, observed_tick: int) -> float:
        """The sum of the turns a percept observed at `observed_tick` does not show [rad].

        Turns it shows leave the record (into :attr:`shown_rad`, in the order sent; with a
        fixed settle they are the oldest ones).
        """
        kept = []
        for shown, angle in self._turns:
            if shown <= observed_tick:
                self.shown_rad += angle
            else:
                kept.append((shown, angle))
        self._turns = kept
        return sum(angle for _, angle in kept)

    def holding(self, observed_tick: int) -> bool:
        """Hold: the last turn sent is not shown by a percept observed at `observed_tick`."""
        self.in_flight(observed_tick)  # (forget what is shown: the record stays short)
        return observed_tick < self._last_shown

    def view(self, percept: Percept) -> Percept:
        """Reckon: `percept` turned into the frame of every turn sent (none in flight: itself)."""
        unseen = self.in_flight(percept.observed_tick)
        return percept if unseen == 0.0 else rotated(percept, -unseen)


def turn_then_go(
    angle_rad: float,
    go: tuple[Action, ...] = (),
    *,
    facing_rad: float | None = None,
    least_turn_rad: float = 0.0,
    turn_only: bool = False,
) -> tuple[Action, ...]:
    """Toward `angle_rad` (from the heading, wrapped by the caller): turn, then `go`.

    Facing it, `go` alone: within `facing_rad` inclusive (a mind's facing angle), or below
    `least_turn_rad` (a defender's turn tolerance: a smaller turn is left out; 0 keeps every
    turn). Otherwise ``Turn(angle_rad)`` then `go`, or the turn alone with `turn_only` (near a
    point: running while turning circles it).
    """
    magnitude = abs(angle_rad)
    if (facing_rad is not None and magnitude <= facing_rad) or magnitude < least_turn_rad:
        return go
    if turn_only:
        return (Turn(angle_rad),)
    return (Turn(angle_rad), *go)


def stop_speed(facts: FieldFacts, distance_m: float) -> float:
    """The speed [m/s] a player can stop from within half of `distance_m`.

    It sees the ball the sensor latency late and then brakes at its acceleration a: the
    speed v with v·latency + v²/(2a) = distance / 2.
    """
    a, lag = facts.player_accel_mps2, facts.sensor_latency_s or 0.0
    return a * (math.sqrt(lag * lag + distance_m / a) - lag)


def dribble_speed(facts: FieldFacts, margin_m: float) -> float | None:
    """The dribble kick's ball speed [m/s] (module docstring); None: no speed covers it.

    :data:`DRIBBLE_UNITS` in :data:`DRIBBLE_PERIODS` sensor periods, at most half the speed the
    player stops from within `margin_m` (its kick margin beyond touching the ball).
    """
    time_s = DRIBBLE_PERIODS * facts.sensor_period_s
    speed = facts.ball.speed_to_cover(DRIBBLE_UNITS * facts.unit_m, time_s)
    if speed is None:
        return None
    return min(speed, 0.5 * stop_speed(facts, margin_m))


def dribble_power(
    facts: FieldFacts,
    margin_m: float,
    speed_per_power_mps: float | None,
    max_power: float = 100.0,
) -> float:
    """The dribble's kick power (module docstring): the one rule of matches and the set play.

    Args:
        facts: The field's facts.
        margin_m: The player's kick margin beyond touching the ball [m].
        speed_per_power_mps: Ball speed per unit of power of the kick (the field's aimable
            kick, or the coach's for players without one); None: the players push the ball
            (:data:`PUSH_DRIBBLE_POWER`).
        max_power: The strongest kick.

    Raises:
        ValueError: No kick up to `max_power` sends the ball :data:`DRIBBLE_UNITS`.
    """
    if speed_per_power_mps is None:
        return PUSH_DRIBBLE_POWER
    time_s = DRIBBLE_PERIODS * facts.sensor_period_s
    top = max_power * speed_per_power_mps
    full = facts.ball.speed_to_cover(DRIBBLE_UNITS * facts.unit_m, time_s)
    speed = dribble_speed(facts, margin_m)
    if full is None or speed is None or full > top:
        raise ValueError(f"{facts.preset}: no kick sends the ball {DRIBBLE_UNITS:g} units")
    return speed / speed_per_power_mps


def rotated(percept: Percept, angle_rad: float) -> Percept:
    """`percept` with every direction turned by `angle_rad` (a turn of the viewer by -angle)."""
    ball = percept.ball
    if ball is not None:
        ball = replace(ball, angle_rad=wrap_angle(ball.angle_rad + angle_rad))
    players = tuple(
        replace(s, angle_rad=wrap_angle(s.angle_rad + angle_rad)) for s in percept.players
    )
    marks = tuple(
        replace(m, angle_rad=wrap_angle(m.angle_rad + angle_rad)) for m in percept.landmarks
    )
    return replace(percept, ball=ball, players=players, landmarks=marks)
