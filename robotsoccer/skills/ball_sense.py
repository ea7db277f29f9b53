"""What a set-play player knows of its field's ball and of its own heading (paper §7).

Every mind of the set play (:mod:`robotsoccer.skills.setplay`) reads percepts only, so the
same code runs on the Soccer Server model and on the robots. This module holds what such a
player knows without looking at the truth:

* :class:`BallSense` — the field's facts about its ball and kick (the ball law, the kick's
  speed per unit of power and top power, touching and kicking distances, the sensor period,
  the settle and recall times of a field whose percepts lag);
* :class:`Heading` — **percepts that lag** (the robots' camera, §2: 50 ms): the turns the
  player commanded that the percept cannot show yet, and bearings remembered in the frame it
  now reckons it faces; a ball the camera missed for a frame or two is recalled where it was;
* :class:`CameraBall` — **a camera** (the robots: a pose from the goals in every percept,
  :attr:`BallSense.track_window` > 0): the ball's velocity fitted to the camera's sightings,
  and the player's heading now from the camera's last two poses rather than from the turns it
  commanded (a robot carries a turn out only in part before its next command).

The ball's velocity a player reckons from these is
:class:`~robotsoccer.skills.ball_tracker.BallTracker`'s. Headings are reckoned from the player's
own turns by the motion skill (:class:`~robotsoccer.skills.motion.TurnsInFlight`, as the
interception defender's, :mod:`robotsoccer.skills.intercept`); angles are radians, left
positive; distances metres.
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from dataclasses import dataclass, replace

from field_models.arena import BallLaw
from field_models.protocol import Action, Percept, SeenBall, wrap_angle
from robotsoccer.skills.lead import BallTrack
from robotsoccer.skills.localise import Localiser
from robotsoccer.skills.motion import TurnsInFlight, rotated


@dataclass(frozen=True, slots=True)
class BallSense:
    """What a player knows of its field's ball and kick (the field's facts; no truth).

    Attributes:
        law: How a free ball slows down.
        speed_per_power_mps: Ball speed a kick of one unit of power adds [m/s].
        max_power: The strongest kick [server units].
        touch_m: Centre distance at which the ball touches the player's body [m].
        reach_m: The distance within which the mind kicks [m] (inside the kick's reach).
        sensor_period_s: Time between two percepts [s].
        turn_settle_ticks: A turn (or a kick) shows in percepts observed this many ticks after
            it was commanded (:class:`Heading`, :meth:`BallTracker.fresh`).
        top_speed_mps: The player's own top speed [m/s] (to keep pace with a rolling ball).
        approach_power: The dash power a player comes up to the ball with at the last, slow
            enough to stop within its kick reach.
        recall_ticks: A ball the sensor missed is recalled this long after its last sighting.
        landmarks: (name, x [m], y [m]) of the field's landmarks, for a pose from a percept.
        track_window: Camera sightings in a velocity fit of the ball (:class:`CameraBall`);
            0: the ball's velocity is dead-reckoned only (the Soccer Server, whose 1996 see
            gives no positions to fit).
    """

    law: BallLaw
    speed_per_power_mps: float
    max_power: float
    touch_m: float
    reach_m: float
    sensor_period_s: float
    top_speed_mps: float = math.inf
    approach_power: float = 40.0
    turn_settle_ticks: int = 1
    recall_ticks: int = 0
    landmarks: tuple[tuple[str, float, float], ...] = ()
    track_window: int = 0

    def heading(self) -> Heading:
        """A fresh heading reckoner with this field's settle and recall times."""
        return Heading(self.turn_settle_ticks, self.recall_ticks)

    def speed(self, power: float) -> float:
        """Ball speed [m/s] a kick of `power` adds."""
        return power * self.speed_per_power_mps


Vector = tuple[float, float]


class CameraBall:
    """The ball's velocity fitted to a camera's sightings, in the player's body frame (robots).

    The robots' host gives both goals in every percept, so the player's pose is the camera's
    own detection (:class:`~robotsoccer.skills.localise.Localiser`) and the ball comes out in
    the field frame as the camera saw it; its velocity is the least-squares slope over the
    last :attr:`BallSense.track_window` sightings (:class:`~robotsoccer.skills.lead.BallTrack`,
    the fit layer 1's lead defender uses), at the sensor's sample times.
    """

    def __init__(self, sense: BallSense) -> None:
        self.sense = sense
        self._localiser = Localiser(sense.landmarks)
        self._track = BallTrack(sense.track_window)
        self._from_tick = 0
        self._pose: tuple[float, float, float, float] | None = None  # (t [s], heading, x, y)
        self.heading_now = 0.0
        """The player's heading now in the field frame [rad] (:meth:`update`)."""
        self.own_velocity: Vector = (0.0, 0.0)
        """The player's own velocity over the last two poses, in the body frame now [m/s]."""

    def restart(self, from_tick: int) -> None:
        """Forget the sightings; take none sampled before `from_tick` (a kick changed the ball)."""
        self._track = BallTrack(self.sense.track_window)
        self._from_tick = from_tick

    def update(self, raw: Percept) -> tuple[float | None, Vector | None]:
        """Add the percept's sighting; (the turn since the sample, the fit), None where unknown.

        The turn [rad] is the player's since the camera's sample; the fit [m/s] is the ball's
        velocity in the body frame of the heading now, once the window is full.

        The heading now (:attr:`heading_now`) is the camera's heading at the sample carried
        on over the sensor latency at the turn rate of the last two poses: the camera's own
        prediction, which needs no model of how the robot carries out its commands.
        """
        pose = self._localiser.update(raw)
        if pose is None:
            return None, None
        sampled = raw.observed_tick * self.sense.law.dt_s
        rate, own = 0.0, (0.0, 0.0)
        last = self._pose
        if last is not None and sampled > last[0]:
            span = sampled - last[0]
            rate = wrap_angle(pose.heading - last[1]) / span
            own = ((pose.x - last[2]) / span, (pose.y - last[3]) / span)
        self._pose = (sampled, pose.heading, pose.x, pose.y)
        turn = rate * (raw.tick - raw.observed_tick) * self.sense.law.dt_s
        frame = pose.heading + turn
        self.heading_now = frame
        cos, sin = math.cos(-frame), math.sin(-frame)
        self.own_velocity = (cos * own[0] - sin * own[1], sin * own[0] + cos * own[1])
        ball = raw.ball
        if ball is None or raw.observed_tick < self._from_tick:
            return turn, None
        bearing = pose.heading + ball.angle_rad
        x = pose.x + ball.distance_m * math.cos(bearing)
        y = pose.y + ball.distance_m * math.sin(bearing)
        self._track.add(sampled, x, y)
        fit = self._track.velocity()
        if fit is None or not self._track.full():
            return turn, None
        cos, sin = math.cos(-frame), math.sin(-frame)
        return turn, (cos * fit[0] - sin * fit[1], sin * fit[0] + cos * fit[1])


class Heading:
    """A player's heading reckoned from its own turns, and bearings remembered in that frame.

    A percept may have been sampled before the player's latest turns took effect (the robots'
    camera latency, §2): :meth:`view` turns such a percept into the frame the player now
    reckons it faces: the motion skill's reckoning (:class:`~robotsoccer.skills.motion.
    TurnsInFlight`, as the interception defender's, :mod:`robotsoccer.skills.intercept`): a turn
    shows in percepts observed :attr:`settle_ticks` after it was commanded.
    """

    def __init__(self, settle_ticks: int = 1, recall_ticks: int = 0) -> None:
        self.settle_ticks = settle_ticks
        self.recall_ticks = recall_ticks
        self.turns = TurnsInFlight(settle_ticks)
        """The turns commanded, and which of them the percepts show."""
        self.unseen_rad = 0.0
        """The turns commanded that the last percept viewed does not show yet [rad]."""
        self.bearings: dict[str, float] = {}
        self._ball: tuple[int, float, float] | None = None  # (tick, distance, bearing)

    @property
    def rad(self) -> float:
        """The heading now, reckoned from the turns commanded (or the camera's) [rad]."""
        return self.turns.heading_rad

    def note(self, actions: Iterable[Action], tick: int) -> None:
        """Add the turns the player sends at `tick`."""
        self.turns.note(actions, tick)

    def view(self, percept: Percept, camera: tuple[float, float] | None = None) -> Percept:
        """`percept` in the frame of the turns commanded so far, its ball recalled if missed.

        A turn shows in percepts observed :attr:`settle_ticks` after it was commanded. A ball
        the sensor missed but that was seen within :attr:`recall_ticks` is put back where it
        was last seen (a missed camera detection is not a ball gone out of sight).

        `camera`: (the heading now in the field frame, the turn since the sample) [rad], from
        the camera's poses (:meth:`CameraBall.update`): they replace the reckoning from the
        turns commanded, which a robot carries out only in part before its next command.
        """
        unseen = self.turns.in_flight(percept.observed_tick)
        if camera is not None:
            self.turns.heading_rad, unseen = wrap_angle(camera[0]), camera[1]
        self.unseen_rad = unseen
        view = percept if unseen == 0.0 else rotated(percept, -unseen)
        ball = view.ball
        if ball is not None:
            self._ball = (percept.tick, ball.distance_m, wrap_angle(self.rad + ball.angle_rad))
            return view
        last = self._ball
        if last is None or percept.tick - last[0] > self.recall_ticks:
            return view
        return replace(view, ball=SeenBall(last[1], wrap_angle(last[2] - self.rad)))

    def remember(self, name: str, angle_rad: float) -> None:
        """Something called `name` is seen at `angle_rad` from the heading now."""
        self.bearings[name] = wrap_angle(self.rad + angle_rad)

    def relative(self, name: str) -> float | None:
        """Where `name` was last seen, relative to the heading now; None if never seen."""
        bearing = self.bearings.get(name)
        return None if bearing is None else wrap_angle(bearing - self.rad)
