"""Layer 1 as a lead: the defender aims where the ball will be, re-planned at every percept.

The paper's decision (§5) is one turn angle TA, chosen when the ball comes within 14 units and
then held: TURN(BA + TA), DASH at each see. It was shaped by the 1996 server's sparse sensing
(a see every 250 ms). With a 30 Hz camera, straight pursuit re-aims thirty times a second and is
already close to the best a held turn offset can do, so a learned TA changes little on the
robots (README, "Layer 1 on the robots"). This module keeps §5's recipe and changes what is
learned: the **lead** τ, how far ahead in time along the ball's perceived track the defender
aims.

**The decision** (:class:`LeadDefenderMind`):

* until the trigger it faces the ball: TURN(BA). The trigger is the first percept within the
  trigger distance once the velocity fit holds its full window and shows the ball coming at
  the player (:data:`COMING_SHARE_PER_S`); the drill gives the farthest start distance: on a
  0.7 m shot the defender cannot wait;
* at the trigger it picks τ [s] with its behaviour, from (BD, track angle, previous BD), and
  records the example (BD, track angle, previous BD, τ). τ is held;
* at every percept from then on it re-plans the aim: the ball's newest position moved τ ahead
  along its newest velocity estimate, by the ball's own deceleration law
  (:meth:`field_models.arena.BallLaw.distance_in`). It turns toward the aim and dashes: TURN +
  DASH, which a robot whose host drives arcs (``robot.turn_style = "arc"``) runs as one arc,
  forward with a wheel-speed difference. The aim stays τ ahead of the ball as it comes: a
  rolling horizon, where the paper's held TA was a fixed offset from the line of sight.

**The track angle** is the angle at the ball from its velocity to the line from the ball to
the defender (counter-clockwise positive): 0 when the ball comes straight at the defender,
negative when its track lies to the left of that line as the ball sees it. It carries what BA
carried in the paper's drill, the ball's motion across the line of sight, which a defender that
keeps facing the ball at 30 Hz no longer sees in BA.

**Where positions come from.** The ball is put in the field frame through the defender's own
pose, localised from the landmarks its percept names (:class:`~robotsoccer.skills.localise.
Localiser`): on the robots the host gives both goals in every percept, so the pose is the
camera's detection and the ball comes out as the camera saw it; on the Soccer Server the drill
asks for every flag. Its velocity is the least-squares slope of its last
:func:`velocity_window` positions against the sensor's sample times. Without a pose or a
velocity the defender runs straight at the ball.

**Behaviours** (each a :class:`LeadPolicy`): ``straight`` τ = 0 (pursuit: aim at the ball as
seen); ``random`` τ uniform in [0, the ball's flight time] (training, §5's exploration; the
drill gives the flight time, a longer lead aims past the goal); ``net`` τ from the 3-4-1
interception net trained on the random saves; ``analytic`` re-computes τ at every percept as
the earliest time the defender can reach the ball's predicted position (:func:`earliest_meeting`:
a straight run from rest at the field's acceleration up to its top speed, after the sensor's
latency): the paper's analytic rule with a horizon in seconds instead of sensor steps.
"""

from __future__ import annotations

import math
from collections import deque
from collections.abc import Callable, Sequence
from dataclasses import dataclass

from field_models.arena import BallLaw, FieldFacts
from field_models.protocol import Action, Dash, Kick, Percept, wrap_angle
from field_models.seeding import Rng
from robotsoccer.skills.intercept import DASH_POWER, KICK_POWER, clearing_direction
from robotsoccer.skills.localise import Localiser, Pose
from robotsoccer.skills.motion import turn_then_go

RANDOM_LEAD_MAX_S = 1.0
"""The training behaviour's lead range: uniform in [0, 1] s, longer than any drill's flight."""

LEAD_CLIP_S = 2.0
"""A learned lead is clipped to [0, 2] s (a safety net, as the paper's TA clip)."""

VELOCITY_SPAN_S = 0.1
"""The ball's velocity is fitted over sightings spanning about this long [s]."""

COMING_SHARE_PER_S = 0.01
"""The ball comes at the player when its speed toward it exceeds this share of the pitch's
length per second (2.7 cm/s on the robots' table, 1.05 m/s on the server's pitch): the lead is
chosen for a ball in flight, not one at rest (a set play's ball before the first pass)."""

MEETING_STEP_S = 0.01
"""The analytic rule searches meeting times on this grid [s]."""

MEETING_HORIZON_S = 3.0
"""The analytic rule looks no further ahead than this [s]; beyond, it aims at the ball's stop."""

Point = tuple[float, float]

LeadPolicy = Callable[[float, float, float], float]
"""(BD [m], track angle [rad], previous BD [m]) -> lead τ [s]."""


def straight_lead(ball_distance_m: float, track_angle_rad: float, previous_m: float) -> float:
    """τ = 0: aim at the ball as seen (pursuit)."""
    return 0.0


@dataclass
class RandomLead:
    """τ uniform in [0, `max_s`] from the trial's ``"policy"`` stream (training).

    The drill gives the ball's flight time as `max_s`: a longer horizon aims past the goal.
    """

    rng: Rng
    max_s: float = RANDOM_LEAD_MAX_S

    def __call__(self, ball_distance_m: float, track_angle_rad: float, previous_m: float) -> float:
        """A fresh random lead [s]."""
        return float(self.rng.uniform(0.0, self.max_s))


def earliest_meeting(
    offset: Point,
    velocity: Point,
    ball: BallLaw,
    top_speed_mps: float,
    accel_mps2: float,
    delay_s: float,
) -> float:
    """The earliest time [s] the defender can be where the ball will be (analytic rule).

    Args:
        offset: The ball's position relative to the defender [m].
        velocity: The ball's velocity [m/s].
        ball: The ball's deceleration law.
        top_speed_mps: The defender's top speed.
        accel_mps2: Its acceleration from rest.
        delay_s: Time before it starts moving (the sensor's latency) [s].

    Returns:
        The first time on a :data:`MEETING_STEP_S` grid at which a straight run from rest
        covers the distance to the ball's predicted position; where none within
        :data:`MEETING_HORIZON_S` does, the time of the ball's closest approach.
    """
    speed = math.hypot(*velocity)
    ux, uy = (velocity[0] / speed, velocity[1] / speed) if speed > 0.0 else (0.0, 0.0)
    steps = round(MEETING_HORIZON_S / MEETING_STEP_S)
    closest, closest_at = math.inf, 0.0
    for k in range(steps + 1):
        t = k * MEETING_STEP_S
        along = ball.distance_in(speed, t)
        gap = math.hypot(offset[0] + ux * along, offset[1] + uy * along)
        if gap <= run_distance(t - delay_s, top_speed_mps, accel_mps2):
            return t
        if gap < closest:
            closest, closest_at = gap, t
    return closest_at


def run_distance(time_s: float, top_speed_mps: float, accel_mps2: float) -> float:
    """How far a run from rest gets in `time_s`: accelerate, then hold the top speed [m]."""
    if time_s <= 0.0:
        return 0.0
    ramp = top_speed_mps / accel_mps2
    if time_s <= ramp:
        return 0.5 * accel_mps2 * time_s * time_s
    return 0.5 * top_speed_mps * ramp + top_speed_mps * (time_s - ramp)


def ahead_of(ball: Point, velocity: Point, lead_s: float, law: BallLaw | None) -> Point:
    """Where a ball at `ball` moving at `velocity` is `lead_s` later [m].

    Along its velocity, slowing by the field's law (None: it keeps its speed); itself for a
    lead of 0 or less or a ball at rest.
    """
    speed = math.hypot(*velocity)
    if lead_s <= 0.0 or speed == 0.0:
        return ball
    along = speed * lead_s if law is None else law.distance_in(speed, lead_s)
    return ball[0] + velocity[0] / speed * along, ball[1] + velocity[1] / speed * along


def track_angle(ball: Point, velocity: Point, defender: Point) -> float:
    """Angle at the ball from its velocity to the line ball -> defender [rad, CCW positive].

    0 when the ball comes straight at the defender, negative when its track lies to the left
    of that line (seen from the ball), ±π when it moves straight away.
    """
    dx, dy = defender[0] - ball[0], defender[1] - ball[1]
    vx, vy = velocity
    return math.atan2(vx * dy - vy * dx, vx * dx + vy * dy)


def velocity_window(sensor_period_s: float) -> int:
    """Sightings in the velocity fit: those spanning :data:`VELOCITY_SPAN_S`, at least two.

    Four on the 30 Hz camera, two on the Soccer Server's 250 ms sees.
    """
    return max(2, 1 + round(VELOCITY_SPAN_S / sensor_period_s))


class BallTrack:
    """The ball's last positions in the field frame, and its velocity by a least-squares fit."""

    def __init__(self, window: int) -> None:
        self._seen: deque[tuple[float, float, float]] = deque(maxlen=window)

    def add(self, time_s: float, x: float, y: float) -> None:
        """A sighting at the sensor's sample time."""
        self._seen.append((time_s, x, y))

    def full(self) -> bool:
        """Whether the window holds its full number of sightings."""
        return len(self._seen) == self._seen.maxlen

    def velocity(self) -> Point | None:
        """The slope of x and y against time over the window [m/s]; None below two sightings."""
        seen = self._seen
        n = len(seen)
        if n < 2:
            return None
        mean_t = sum(s[0] for s in seen) / n
        spread = sum((s[0] - mean_t) ** 2 for s in seen)
        if spread <= 0.0:
            return None
        mean_x = sum(s[1] for s in seen) / n
        mean_y = sum(s[2] for s in seen) / n
        vx = sum((s[0] - mean_t) * (s[1] - mean_x) for s in seen) / spread
        vy = sum((s[0] - mean_t) * (s[2] - mean_y) for s in seen) / spread
        return vx, vy


class LeadDefenderMind:
    """The defender that meets the ball (module docstring).

    Args:
        policy: The behaviour's lead rule; None stands still (``still``).
        facts: The field's facts (tick, ball law, the defender's speed and latency, landmarks).
        trigger_distance_m: τ is chosen the first time BD is at most this [m].
        replan: Re-compute τ at every percept (the analytic rule); False holds the τ chosen at
            the trigger.
        kickable_distance_m: Kick (clear) when BD is at most this [m]; None never kicks.
        turn_tolerance_rad: Leave out turns smaller than this [rad].

    Attributes:
        example: (BD [m], track angle [rad], previous BD [m], τ [s]) at the trigger, or None.
        triggered: True once BD came within the trigger distance.
    """

    def __init__(
        self,
        policy: LeadPolicy | None,
        facts: FieldFacts,
        trigger_distance_m: float,
        *,
        replan: bool = False,
        kickable_distance_m: float | None = None,
        turn_tolerance_rad: float = 0.0,
    ) -> None:
        self.policy = policy
        self.facts = facts
        self.trigger_distance_m = trigger_distance_m
        self.replan = replan
        self._lead_s = 0.0
        self.kickable_distance_m = kickable_distance_m
        self.turn_tolerance_rad = turn_tolerance_rad
        self.example: tuple[float, float, float, float] | None = None
        self.triggered = False
        self._localiser = Localiser(facts.landmarks)
        self._track = BallTrack(velocity_window(facts.sensor_period_s))
        self._previous_bd: float | None = None
        self._delay_s = facts.sensor_latency_s or 0.0

    def act(self, percept: Percept) -> tuple[Action, ...]:
        """One decision per percept (module docstring)."""
        if self.policy is None:
            return ()
        ball = percept.ball
        pose = self._localiser.update(percept)
        if ball is None:
            return (Dash(DASH_POWER),) if self.triggered else ()
        bd, ba = ball.distance_m, ball.angle_rad
        previous_bd = bd if self._previous_bd is None else self._previous_bd
        self._previous_bd = bd
        now = percept.observed_tick * self.facts.dt_s
        if pose is None:
            return self._toward(ba, bd, percept)
        heading = pose.heading + ba
        bx, by = pose.x + bd * math.cos(heading), pose.y + bd * math.sin(heading)
        self._track.add(now, bx, by)
        velocity = self._track.velocity()
        if not self.triggered:
            coming = velocity is not None and self._closing_mps(velocity, (bx, by), pose) > (
                COMING_SHARE_PER_S * self.facts.pitch.length_m
            )
            if bd > self.trigger_distance_m or not self._track.full() or not coming:
                return self._turn(ba, ())
            self.triggered = True
            angle = 0.0 if velocity is None else track_angle((bx, by), velocity, (pose.x, pose.y))
            lead = self._clip(self.policy(bd, angle, previous_bd))
            self.example = (bd, angle, previous_bd, lead)
            self._lead_s = lead
        if velocity is None:
            return self._toward(ba, bd, percept)
        if self.replan:
            self._lead_s = self._analytic((bx - pose.x, by - pose.y), velocity)
        aim = self._aim((bx, by), velocity)
        angle = math.atan2(aim[1] - pose.y, aim[0] - pose.x) - pose.heading
        return self._toward(angle, bd, percept)

    @staticmethod
    def _closing_mps(velocity: Point, ball: Point, pose: Pose) -> float:
        """The ball's speed toward the player [m/s] (negative: moving away)."""
        dx, dy = pose.x - ball[0], pose.y - ball[1]
        distance = math.hypot(dx, dy)
        return (velocity[0] * dx + velocity[1] * dy) / distance if distance > 0.0 else 0.0

    def _analytic(self, offset: Point, velocity: Point) -> float:
        facts = self.facts
        return earliest_meeting(
            offset,
            velocity,
            facts.ball,
            facts.player_top_speed_mps,
            facts.player_accel_mps2,
            self._delay_s,
        )

    def _aim(self, ball: Point, velocity: Point) -> Point:
        """The ball's predicted position the lead ahead of its newest sighting."""
        return ahead_of(ball, velocity, self._lead_s, self.facts.ball)

    def _toward(self, angle: float, bd: float, percept: Percept) -> tuple[Action, ...]:
        """Clear the ball when in reach; else turn toward `angle` and dash (after the trigger)."""
        if not self.triggered:
            return self._turn(angle, ())
        if self.kickable_distance_m is not None and bd <= self.kickable_distance_m:
            return (Kick(KICK_POWER, clearing_direction(percept)),)
        return self._turn(angle, (Dash(DASH_POWER),))

    def _turn(self, angle: float, then: tuple[Action, ...]) -> tuple[Action, ...]:
        """Turn by `angle` (wrapped) then `then` (the motion skill; no turn below tolerance).

        Its pose comes from the camera's landmarks at every percept, so it keeps no record of
        its turns in flight (the team minds' hold, the set play's reckoning).
        """
        return turn_then_go(wrap_angle(angle), then, least_turn_rad=self.turn_tolerance_rad)

    @staticmethod
    def _clip(lead_s: float) -> float:
        return min(LEAD_CLIP_S, max(0.0, lead_s))


@dataclass(frozen=True)
class ScaledLead:
    """A lead rule whose τ is multiplied by `scale`: a net moved to a drill on another time scale.

    The transfer study (:mod:`robotsoccer.experiments.transfer`) checks a lead net moved between
    fields whose drills last differently long with ``scale`` the test drill's flight time over
    the training drill's, so a lead keeps its share of the flight (drill option
    ``lead_time_scale``).
    """

    rule: LeadPolicy
    scale: float

    def __call__(self, ball_distance_m: float, track_angle_rad: float, previous_m: float) -> float:
        """The rule's lead times the scale [s]."""
        return self.scale * self.rule(ball_distance_m, track_angle_rad, previous_m)


def lead_policy(
    name: str, rng: Rng, net: LeadPolicy | None = None, random_max_s: float = RANDOM_LEAD_MAX_S
) -> LeadPolicy | None:
    """The lead rule of a behaviour name: still (None), straight, random, net or analytic.

    ``analytic`` holds no rule of its own at the trigger (τ = 0 there); the mind re-plans.

    Raises:
        ValueError: An unknown name, or ``net`` without a net.
    """
    if name == "still":
        return None
    if name in ("straight", "analytic"):
        return straight_lead
    if name == "random":
        return RandomLead(rng, random_max_s)
    if name == "net":
        if net is None:
            raise ValueError("behaviour 'net' needs a model file (option model=...)")
        return net
    raise ValueError(
        f"behaviour {name!r} has no lead rule: choose still, straight, random, net, analytic"
    )


LEAD_BEHAVIOURS: Sequence[str] = ("still", "straight", "random", "net", "analytic")
"""The behaviours of the lead decision."""
