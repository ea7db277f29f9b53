"""The interception drill's geometry and launch on a field (paper §5, Figure 6), as a plan.

**Players**: the shooter is ``PlayerRef(LEFT, 1)``, the defender ``PlayerRef(RIGHT, 1)``,
defending the goal at +x.

**Geometry** in *units*: one unit is the field's :attr:`~field_models.arena.FieldFacts.unit_m`
(pitch length / 105: 1 m on the Soccer Server, about 2.6 cm on the 2.74 m robot table), so the
drill is the same picture on every field. The defender starts 4 units in front of the centre of
its goal, at (half_length - 4 u, 0), facing the ball; the ball starts 20-30 units from it
(uniform), at a bearing uniform in ±``sector_deg`` (default 45°: the paper draws the sector but
gives no number, so this is a calibrated setting) around the -x axis; the shooter stands behind
the ball on the line to the defender. The trigger distance of the defender (paper: "BD <= 14")
is 14 units (the ``task`` scaling moves it, below).

**Launch** (option ``launch``): ``"shooter"`` — the shooter sees the defender and at its first
percept kicks with the plan's power toward the seen direction plus ``aim_offset_deg``, the
paper's set-up (the ball starts at rest in the shooter's reach, between it and the defender);
``"coach"`` — the coach puts the ball in motion at the launch speed along the aim line (the line
to the defender turned by ``aim_offset_deg``) and the shooter stands behind it, idle. ``"auto"``
(default) is ``"shooter"`` where the players can kick and ``"coach"`` where they cannot (the
1997 robots had no kicker). A kick that fires along the heading (a solenoid kicker, not
aimable) is aimed by placing the shooter facing along the aim line.

**Scaling** (option ``scaling``, :func:`launch_plan`):

* ``"literal"`` — the paper's set-up as it stands: the shooter kicks with ``kick_power`` using
  the field's own kick, and the ball slows down by the field's own law. On the reference Soccer
  Server (``soccer_server_1996``) a power-100 kick gives the ball 1.6 m per cycle, decaying by
  0.96 per cycle, so it covers the mean 25 units in 24.0 cycles = 2.40 s = 9.6 sees of 250 ms.
* ``"sensor_updates"`` — the ball's speed is chosen so that the *same number of sensor updates*
  pass between the launch and the ball's arrival as in the literal drill on the paper's field
  (:func:`field_models.registry.paper_field_facts`); on the 30 Hz robot table that is 9.6
  frames (0.320 s) for 25 units (0.652 m), which a rolling ball with constant deceleration a
  covers when launched at ``v0 = D / t + a t / 2``. The trigger distance stays 14 units, about
  5 frames before arrival as 14 m is 5 sees on the server. Latencies are not part of the rule.
  The ball-motion noise then acts once per *scaled* server cycle
  (:meth:`robotsoccer.drills.intercept.InterceptDrill.field_settings`): the flight time over
  the reference's cycles in flight, to whole ticks, so a noise level means the same wander in
  units on both fields.
* ``"task"`` — keep what the task is about: the defender's reach between the trigger and the
  ball's arrival (in units), the ball's lateral wander (in touch distances) and the defender's
  decisions in that time, as on the paper's field
  (:mod:`robotsoccer.drills.task_scaling`). The launch speed, the trigger distance, the noise
  period and the defender's decision period (:attr:`LaunchPlan.decision_period_s`) follow.
  On the paper's field it is the literal drill.
* ``"auto"`` (default) — ``"literal"`` on a field at the paper's scale (a 105 m pitch, unit =
  1 m) whose kick takes a direction; ``"sensor_updates"`` anywhere else. (``"task"`` matches
  the still and straight baselines better, but the learned net loses to straight under it:
  README, "Ablations"; it is not the default until a rule makes learning pay.)

With a kicker that is not aimable, the power is the launch speed's share of its top speed.
"""

from __future__ import annotations

import dataclasses
import functools
import math
from dataclasses import dataclass

from field_models.arena import FieldFacts
from field_models.protocol import LEFT, RIGHT, PlayerRef
from field_models.registry import paper_field_facts
from robotsoccer.drills.intercept_options import Launch, Scaling
from robotsoccer.drills.task_scaling import ReferenceFlight, task_launch
from robotsoccer.options import choice

SHOOTER = PlayerRef(LEFT, 1)
DEFENDER = PlayerRef(RIGHT, 1)

DEFENDER_SETBACK_UNITS = 4.0
"""The defender starts this far in front of its goal line (paper Figure 6)."""
MIN_DISTANCE_UNITS = 20.0
MAX_DISTANCE_UNITS = 30.0
"""Ball (and shooter) start 20-30 units from the defender (paper Figure 6)."""
TRIGGER_UNITS = 14.0
"""The defender chooses TA when BD <= 14 units (paper §5)."""
TOLERANCE_HEADING_SIGMAS = 3.0
"""The defender leaves out turns below this many sigmas of the sensor's heading noise."""


@dataclass(frozen=True, slots=True)
class LaunchPlan:
    """The drill's geometry and launch on one field (see the module docstring).

    Attributes:
        model: The field model's name.
        preset: The preset's name.
        scaling: ``literal``, ``sensor_updates`` or ``task`` (``auto`` resolved).
        unit_m: One drill unit: pitch length / 105 [m].
        defender_x_m: The defender's start x (y = 0) [m].
        min_distance_m: Nearest ball start from the defender [m].
        max_distance_m: Farthest ball start from the defender [m].
        mean_distance_m: The distance the arrival numbers are computed for (25 units) [m].
        trigger_distance_m: The defender chooses TA at this BD (14 units; ``task``: the
            rule's) [m].
        launch: ``shooter`` or ``coach`` (``auto`` resolved).
        kick_power: The shooter's kick power (the reference's for a coach launch).
        aimable_kick: The shooter's kick takes a direction (else it fires along the heading).
        launch_speed_mps: The ball's speed as it leaves [m/s].
        sensor_period_s: Time between two percepts [s].
        arrival_time_s: Time for the ball to cover `mean_distance_m` [s].
        arrival_updates: Percepts in that time (the quantity ``sensor_updates`` matches).
        kickable_distance_m: The defender may clear when BD is within this [m]; None: no
            aimable kick, it blocks.
        shooter_gap_m: Centre distance from the shooter to the ball at the start [m].
        turn_tolerance_rad: The defender leaves out smaller turns [rad].
        noise_period_s: How often ball-motion noise acts [s].
        trigger_to_arrival_s: The ball's time from the trigger distance to the defender at the
            mean distance, without noise [s].
        decision_period_s: The defender decides at most this often [s]; 0: at every percept
            (the ``task`` rule sets it to match the reference's decisions after the trigger).
    """

    model: str
    preset: str
    scaling: Scaling
    unit_m: float
    defender_x_m: float
    min_distance_m: float
    max_distance_m: float
    mean_distance_m: float
    trigger_distance_m: float
    launch: Launch
    kick_power: float
    aimable_kick: bool
    launch_speed_mps: float
    sensor_period_s: float
    arrival_time_s: float
    arrival_updates: float
    kickable_distance_m: float | None
    shooter_gap_m: float
    turn_tolerance_rad: float
    noise_period_s: float
    trigger_to_arrival_s: float
    decision_period_s: float


def launch_plan(
    facts: FieldFacts,
    *,
    kick_power: float = 100.0,
    launch: Launch | str = Launch.AUTO,
    scaling: Scaling | str = Scaling.AUTO,
) -> LaunchPlan:
    """The scaled geometry and launch numbers of the drill on a field (module docstring).

    Args:
        facts: The field's facts (:func:`field_models.registry.field_facts`, ``arena.facts``).
        kick_power: The shooter's kick power in the literal drill (paper: fixed, 100).
        launch: ``auto``, ``shooter`` or ``coach``.
        scaling: ``auto``, ``literal``, ``sensor_updates`` or ``task``.

    Raises:
        ValueError: An unknown launch or scaling, a shooter launch where nobody can kick, a
            literal drill without an aimable kick, or a launch the field cannot make (the ball
            stops short or would be too fast, the kicker is too weak).
    """
    launch = choice(Launch, launch, "launch")
    scaling = choice(Scaling, scaling, "scaling")
    kick = facts.kick
    if launch is Launch.AUTO:
        launch = Launch.COACH if kick is None else Launch.SHOOTER
    if launch is Launch.SHOOTER and kick is None:
        raise ValueError(f"{facts.preset}: the players have no kick: use launch='coach'")
    aimable = kick is not None and kick.aimable
    if scaling is Scaling.AUTO:
        paper_scale = math.isclose(facts.unit_m, 1.0) and aimable
        scaling = Scaling.LITERAL if paper_scale else Scaling.SENSOR_UPDATES
    unit = facts.unit_m
    mean = 0.5 * (MIN_DISTANCE_UNITS + MAX_DISTANCE_UNITS) * unit
    trigger = TRIGGER_UNITS * unit
    decision_period = 0.0
    if scaling is Scaling.LITERAL:
        speed, time, power, noise_period = _literal_launch(facts, mean, kick_power)
    elif scaling is Scaling.SENSOR_UPDATES:
        speed, time, power, noise_period = _matched_launch(facts, mean, launch, kick_power)
    else:
        task = task_launch(facts, reference_flight(kick_power))
        speed, time, trigger = task.launch_speed_mps, task.flight_s, task.trigger_distance_m
        power = _launch_power(facts, launch, speed, kick_power)
        noise_period, decision_period = task.noise_period_s, task.decision_period_s
    touch = facts.touch_distance_m
    gap = touch + 0.5 * unit
    if launch is Launch.SHOOTER and kick is not None:
        gap = 0.5 * (touch + kick.reach_m)  # between touching and the edge of its reach
    return LaunchPlan(
        model=facts.model,
        preset=facts.preset,
        scaling=scaling,
        unit_m=unit,
        defender_x_m=facts.pitch.half_length_m - DEFENDER_SETBACK_UNITS * unit,
        min_distance_m=MIN_DISTANCE_UNITS * unit,
        max_distance_m=MAX_DISTANCE_UNITS * unit,
        mean_distance_m=mean,
        trigger_distance_m=trigger,
        launch=launch,
        kick_power=power,
        aimable_kick=aimable,
        launch_speed_mps=speed,
        sensor_period_s=facts.sensor_period_s,
        arrival_time_s=time,
        arrival_updates=time / facts.sensor_period_s,
        kickable_distance_m=kick.reach_m if kick is not None and kick.aimable else None,
        shooter_gap_m=gap,
        turn_tolerance_rad=TOLERANCE_HEADING_SIGMAS * facts.heading_sigma_rad,
        noise_period_s=noise_period,
        trigger_to_arrival_s=_after_trigger_s(facts, mean, trigger, speed, time),
        decision_period_s=decision_period,
    )


def _literal_launch(
    facts: FieldFacts, mean_m: float, kick_power: float
) -> tuple[float, float, float, float]:
    """(speed, arrival time, power, noise period) of the paper's kick on this field."""
    kick = facts.kick
    if kick is None or not kick.aimable:
        raise ValueError(f"{facts.preset}: the literal drill needs a kick that takes a direction")
    speed = kick.speed(kick_power)
    time = facts.ball.time_to_cover(mean_m, speed)
    if time is None:
        raise ValueError(f"{facts.preset}: a power-{kick_power:g} kick stops short of {mean_m:g} m")
    return speed, time, kick_power, facts.ball_noise_period_s


def _matched_launch(
    facts: FieldFacts, mean_m: float, launch: Launch, kick_power: float
) -> tuple[float, float, float, float]:
    """(speed, arrival time, power, noise period) matching the paper's sensor updates."""
    reference = launch_plan(paper_field_facts(), kick_power=kick_power, scaling=Scaling.LITERAL)
    time = reference.arrival_updates * facts.sensor_period_s
    speed = facts.ball.speed_to_cover(mean_m, time)
    if speed is None or speed > facts.ball_max_speed_mps:
        shown = "none" if speed is None else f"{speed:.3g} m/s"
        raise ValueError(f"{facts.preset}: the launch speed ({shown}) is not possible here")
    power = _launch_power(facts, launch, speed, reference.kick_power)
    # One server cycle in the drill's time: the flight over the reference's cycles in flight, so
    # the noise acts as many times per shot as on the paper's field.
    cycles = reference.arrival_time_s / reference.noise_period_s
    ticks = max(1, round(time / cycles / facts.dt_s))
    return speed, time, power, ticks * facts.dt_s


@functools.lru_cache(maxsize=64)
def ablated(
    plan: LaunchPlan,
    facts: FieldFacts,
    trigger_scale: float = 1.0,
    launch_speed_scale: float = 1.0,
    turn_tolerance_deg: float | None = None,
) -> LaunchPlan:
    """`plan` on `facts` with the drill's ablation options applied (itself when none is set).

    Raises:
        ValueError: The scaled launch stops short of the mean distance or is too fast.
    """
    if trigger_scale == 1.0 and launch_speed_scale == 1.0 and turn_tolerance_deg is None:
        return plan
    tolerance = plan.turn_tolerance_rad
    if turn_tolerance_deg is not None:
        tolerance = math.radians(turn_tolerance_deg)
    speed = plan.launch_speed_mps * launch_speed_scale
    arrival = facts.ball.time_to_cover(plan.mean_distance_m, speed)
    if arrival is None or speed > facts.ball_max_speed_mps:
        raise ValueError(
            f"{facts.preset}: launch_speed_scale={launch_speed_scale:g} gives "
            f"{speed:.3g} m/s, which is not possible here"
        )
    trigger = plan.trigger_distance_m * trigger_scale
    return dataclasses.replace(
        plan,
        trigger_distance_m=trigger,
        launch_speed_mps=speed,
        arrival_time_s=arrival,
        arrival_updates=arrival / plan.sensor_period_s,
        trigger_to_arrival_s=_after_trigger_s(facts, plan.mean_distance_m, trigger, speed, arrival),
        turn_tolerance_rad=tolerance,
    )


def _after_trigger_s(
    facts: FieldFacts, mean_m: float, trigger_m: float, speed_mps: float, arrival_s: float
) -> float:
    """The ball's time from `trigger_m` before the defender to its arrival there [s]."""
    before = facts.ball.time_to_cover(mean_m - trigger_m, speed_mps)
    return arrival_s - (0.0 if before is None else before)


def decision_ticks(plan: LaunchPlan, facts: FieldFacts) -> int:
    """The plan's decision period in whole ticks (0: every percept)."""
    return round(plan.decision_period_s / facts.dt_s)


def reference_flight(kick_power: float = 100.0) -> ReferenceFlight:
    """The literal drill's flight on the paper's field, which the ``task`` rule keeps."""
    facts = paper_field_facts()
    plan = launch_plan(facts, kick_power=kick_power, scaling=Scaling.LITERAL)
    mean_units = plan.mean_distance_m / plan.unit_m
    return ReferenceFlight(
        facts, plan.launch_speed_mps, plan.arrival_time_s, plan.trigger_to_arrival_s, mean_units
    )


def _launch_power(facts: FieldFacts, launch: Launch, speed_mps: float, reference: float) -> float:
    """The shooter's power for `speed_mps`; the reference's power for a coach launch."""
    kick = facts.kick
    if launch is not Launch.SHOOTER or kick is None:
        return reference
    needed = kick.power_for(speed_mps)
    if needed is None:
        raise ValueError(f"{facts.preset}: the kicker's top speed is below {speed_mps:.3g} m/s")
    return needed


@functools.lru_cache(maxsize=64)
def cached_launch_plan(
    facts: FieldFacts, kick_power: float, launch: Launch, scaling: Scaling
) -> LaunchPlan:
    """The plan of a field, once per process (facts are frozen, hence hashable)."""
    return launch_plan(facts, kick_power=kick_power, launch=launch, scaling=scaling)
