"""The ``task`` scaling of the interception drill: keep what the task is about, not the clock.

The paper's drill (§5) on the Soccer Server is a task with three dimensionless numbers:

* **reach** — how far the defender can get between the trigger and the ball's arrival, in drill
  units (one unit = pitch length / 105);
* **wander** — the ball's lateral wander from motion noise over its flight, in touch distances
  (player radius + ball radius: what the ball must miss the body by to get past a still
  defender), per unit of noise level;
* **decisions** — the defender's decisions between the trigger and the arrival.

The ``sensor_updates`` rule keeps the sensor updates of the whole flight instead; on the 30 Hz
robot table that makes the ball so fast (about 79 units/s against 16 on the server) that the
defender moves about a quarter of a unit after the trigger, and no turn angle can matter.

:func:`task_launch` carries the numbers to another field, in this order:

1. the time after the trigger is the field's sensor latency plus one sensor period (a decision
   waits for the next percept) plus the time to run :data:`REACH_UNITS` from rest at the field's
   acceleration and top speed;
2. the defender decides every whole number of sensor periods that gives the reference's
   decisions in that time (nearest, at least one period);
3. the flight over the mean 25 units lasts as many times the time after the trigger as on the
   reference, which gives the launch speed (the field's ball law) and the trigger distance
   (where the ball is that long before it arrives);
4. the ball-noise period is the whole number of ticks that gives the reference's wander in touch
   distances, as nearly as the tick allows (:func:`lateral_wander`).

The reference is the literal drill on the paper's field
(:func:`field_models.registry.paper_field_facts`), whose numbers the caller passes in
(:class:`ReferenceFlight`). On that field the rule gives back its own flight.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from field_models.arena import BallLaw, FieldFacts

REACH_UNITS = 8.0
"""Calibrated: the reach the rule keeps [drill units]. Its start was the straight defender's
median travel from the trigger to the verdict on the Soccer Server (5.6 units, issue 10); it
is then the one number tuned so that the robots' still and straight baselines match the
server's (README, "scaling the robot drill")."""

UNIFORM_SIGMA = 1.0 / math.sqrt(3.0)
"""Standard deviation of a uniform draw in ±1."""


@dataclass(frozen=True, slots=True)
class ReferenceFlight:
    """The reference drill's flight (the literal drill on the paper's field).

    Attributes:
        facts: The reference field.
        launch_speed_mps: Its ball's launch speed [m/s].
        flight_s: Its flight over the mean distance [s].
        after_trigger_s: The part of that flight after the trigger [s].
        mean_distance_units: The mean start distance [units].
    """

    facts: FieldFacts
    launch_speed_mps: float
    flight_s: float
    after_trigger_s: float
    mean_distance_units: float

    @property
    def decisions(self) -> float:
        """The reference defender's decisions after the trigger (one per percept)."""
        return self.after_trigger_s / self.facts.sensor_period_s

    @property
    def wander_touches(self) -> float:
        """Its lateral wander per unit noise level [touch distances]."""
        facts = self.facts
        wander_m = lateral_wander(
            facts.ball, self.launch_speed_mps, self.flight_s, facts.ball_noise_period_s
        )
        return wander_m / facts.touch_distance_m


@dataclass(frozen=True, slots=True)
class TaskLaunch:
    """What :func:`task_launch` chose on one field.

    Attributes:
        launch_speed_mps: The ball's launch speed [m/s].
        flight_s: Its flight over the mean distance [s].
        after_trigger_s: The part of the flight after the trigger [s].
        trigger_distance_m: The defender's trigger distance [m].
        noise_period_s: How often the ball-motion noise acts [s].
        decision_period_s: How often the defender decides [s].
        reach_units: The reach the rule kept [units].
        wander_touches: The wander per unit noise the noise period gives [touch distances].
        decisions: Decisions after the trigger.
    """

    launch_speed_mps: float
    flight_s: float
    after_trigger_s: float
    trigger_distance_m: float
    noise_period_s: float
    decision_period_s: float
    reach_units: float
    wander_touches: float
    decisions: float


def run_time_s(distance_m: float, accel_mps2: float, top_speed_mps: float) -> float:
    """Time [s] to run `distance_m` from rest: full acceleration, then top speed."""
    ramp_m = 0.5 * top_speed_mps * top_speed_mps / accel_mps2
    if distance_m <= ramp_m:
        return math.sqrt(2.0 * distance_m / accel_mps2)
    return top_speed_mps / accel_mps2 + (distance_m - ramp_m) / top_speed_mps


MAX_NOISE_PERIODS = 1_000_000
"""The most noise periods :func:`lateral_wander` sums over (a flight lasts a few hundred)."""


def lateral_wander(ball: BallLaw, speed_mps: float, flight_s: float, period_s: float) -> float:
    """Standard deviation [m] of the ball's sideways miss at arrival, per unit noise level.

    Each period the velocity gets a uniform change in ±noise·|v| per axis; the sideways part,
    a fraction δ of the speed, carries the ball δ times the distance it still covers (it slows
    by the same law), so the miss is the root of the sum of squares of those distances times
    noise / √3.

    Raises:
        ValueError: A flight of more than :data:`MAX_NOISE_PERIODS` noise periods (or none
            that ends): the sum would not end in reasonable time.
    """
    if not (period_s > 0.0 and flight_s / period_s <= MAX_NOISE_PERIODS):
        raise ValueError(
            f"a flight of {flight_s!r} s spans more than {MAX_NOISE_PERIODS} noise periods "
            f"of {period_s!r} s"
        )
    total = ball.distance_in(speed_mps, flight_s)
    squares = 0.0
    k = 1
    while k * period_s < flight_s:
        remaining = total - ball.distance_in(speed_mps, k * period_s)
        squares += remaining * remaining
        k += 1
    return UNIFORM_SIGMA * math.sqrt(squares)


def task_launch(facts: FieldFacts, reference: ReferenceFlight) -> TaskLaunch:
    """The launch, trigger, noise and decision periods that keep the task's numbers (module doc).

    Raises:
        ValueError: The field's ball cannot make the flight (it would stop short or be too fast).
    """
    unit = facts.unit_m
    on_reference = facts == reference.facts
    if on_reference:  # the reference's own flight; its defender decides at every percept
        after = reference.after_trigger_s
    else:
        latency = (facts.sensor_latency_s or 0.0) + facts.sensor_period_s
        reach_m = REACH_UNITS * unit
        after = latency + run_time_s(reach_m, facts.player_accel_mps2, facts.player_top_speed_mps)
    periods = max(1, round(after / reference.decisions / facts.sensor_period_s))
    decision_period = periods * facts.sensor_period_s
    flight = after * reference.flight_s / reference.after_trigger_s
    mean_m = reference.mean_distance_units * unit
    speed = facts.ball.speed_to_cover(mean_m, flight)
    if speed is None or speed > facts.ball_max_speed_mps:
        shown = "none" if speed is None else f"{speed:.3g} m/s"
        raise ValueError(f"{facts.preset}: the task's launch speed ({shown}) is not possible here")
    trigger = mean_m - facts.ball.distance_in(speed, flight - after)
    ticks = _noise_ticks(facts, speed, flight, reference.wander_touches)
    noise_period = ticks * facts.dt_s
    wander = lateral_wander(facts.ball, speed, flight, noise_period) / facts.touch_distance_m
    return TaskLaunch(
        launch_speed_mps=speed,
        flight_s=flight,
        after_trigger_s=after,
        trigger_distance_m=trigger,
        noise_period_s=noise_period,
        decision_period_s=0.0 if on_reference else decision_period,
        reach_units=REACH_UNITS,
        wander_touches=wander,
        decisions=after / decision_period,
    )


def _noise_ticks(facts: FieldFacts, speed_mps: float, flight_s: float, target: float) -> int:
    """The whole ticks of noise period whose wander is nearest `target` (touch distances)."""
    touch = facts.touch_distance_m

    def error(ticks: int) -> float:
        wander = lateral_wander(facts.ball, speed_mps, flight_s, ticks * facts.dt_s) / touch
        return abs(math.log(wander / target)) if wander > 0.0 else math.inf

    most = max(1, int(flight_s / facts.dt_s))
    best, best_error = 1, error(1)
    # Wander falls as the period grows: stop once it is past the target and getting worse.
    for ticks in range(2, most + 1):
        e = error(ticks)
        if e > best_error:
            break
        best, best_error = ticks, e
    return best
