"""The interception drill (paper §5, Figure 6): a shooter kicks at a defender who must stop it.

**Players**: the shooter is ``PlayerRef(LEFT, 1)``, the defender ``PlayerRef(RIGHT, 1)``,
defending the goal at +x.

**Geometry** in *units*: one unit is the field's :attr:`~field_models.arena.FieldFacts.unit_m`
(pitch length / 105: 1 m on the Soccer Server, about 2.6 cm on the 2.74 m robot table), so the
drill is the same picture on every field. The defender starts 4 units in front of the centre of
its goal, at (half_length - 4 u, 0), facing the ball; the ball starts 20-30 units from it
(uniform), at a bearing uniform in ±``sector_deg`` (default 45°: the paper draws the sector but
gives no number, so this is a calibrated setting) around the -x axis; the shooter stands behind
the ball on the line to the defender. The trigger distance of the defender (paper: "BD <= 14")
is 14 units (the ``task`` scaling moves it, below). Placement draws, in this order, the
distance and the bearing from ``rngs["placement"]``.

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
  (:meth:`InterceptDrill.field_settings`): the flight time over the reference's cycles in
  flight, to whole ticks, so a noise level means the same wander in units on both fields.
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

**Defender** (:mod:`robotsoccer.skills.intercept`): the behaviour (option ``behaviour``: still,
straight, random, net, lookup, analytic; ``model`` the file of net/lookup), ``ta_mode`` ("hold":
TA chosen once at the trigger; "every_see"). By default it stops the ball with its body
(``defender_kick=False``), a calibrated choice: the paper's §5 baselines (still hit 35%, straight
53%) are matched that way, and the 1998 kickable area (1.885 m) is a far bigger target than the
body (0.885 m). With ``defender_kick=True`` it clears a ball within reach of an aimable kick with
power 100 away from its goal. It leaves out turns smaller than three sigmas of the sensor's
heading noise (a robot stops to spin for a whole camera period on each turn; 0 on the server).
Option ``client``: ``see`` (default, the paper's client: one decision per see, "turn, then
dash") or ``cycle`` (a command every cycle from a world model, :mod:`robotsoccer.skills.cycle`;
TA held, no decision period; it runs on the one-trial path, not the batch).

**Labels** (the coach judges the truth after every tick; ``labels = ("SAVE", "GOAL", "MISS")``).
Let û be the unit vector from the ball's start to the defender's start, v the ball's velocity
and ε = 1e-3 · pitch length per second. Once the ball has been moving toward the defender
(v·û > ε):

* **SAVE** — the ball moves clearly back: v·û < -max(ε, ½|v|), i.e. more than 30° behind the
  sideways direction;
* a ball whose v·û drops below -ε without going clearly back was *deflected*: it may still roll
  on toward the goal line. After a deflection the trial is a GOAL if the ball then goes in and a
  SAVE in every other case (wide, to a side, or stopped: slower than ε);
* the ball gets past the defender (its progress along û exceeds the defender's start distance
  plus player radius plus ball radius): **GOAL** if its straight-line path crosses the goal
  mouth, else **MISS** ("heading wide"; SAVE after a deflection);
* the ball goes over an end line (:func:`field_models.protocol.end_line_crossing`, the one
  goal-line rule) or the field's referee counts a goal: **GOAL** into the defended goal, else
  **MISS**;
* the ball reaches a side line, or the end line wide of the posts (a wall on the robot table,
  whose bounce must not count as a save): **MISS**;
* time out (``max_time_s`` simulated, default 10 s): **MISS**, "ball stopped short".

:meth:`InterceptDrill.data` returns the defender's example (BD [m], BA [rad], previous BD [m],
TA [rad]) recorded at the trigger, or ``()`` when no decision happened.
:meth:`InterceptDrill.measures` returns, for a trial whose defender triggered, how far it got
from the trigger to the verdict (in units), that time, and the sensor updates in it.
"""

from __future__ import annotations

import dataclasses
import functools
import math
from dataclasses import dataclass
from enum import StrEnum
from pathlib import Path

from field_models.arena import Arena, FieldFacts
from field_models.protocol import LEFT, RIGHT, Crossing, Mind, PlayerRef, wrap_angle
from field_models.registry import paper_field_facts
from field_models.seeding import TrialRngs
from robotsoccer.drills.base import GoalWatch, Verdict
from robotsoccer.drills.task_scaling import ReferenceFlight, task_launch
from robotsoccer.options import choice, duration, flag
from robotsoccer.skills.cycle import CycleDefenderMind
from robotsoccer.skills.intercept import (
    AimedShooterMind,
    Behaviour,
    DefenderMind,
    TaMode,
    check_behaviour,
    load_net_function,
    make_policy,
    model_decision,
    model_origin,
    transfer_distance_factor,
)
from robotsoccer.skills.lead import LeadDefenderMind, ScaledLead, lead_policy

SHOOTER = PlayerRef(LEFT, 1)
DEFENDER = PlayerRef(RIGHT, 1)

DEFENDER_SETBACK_UNITS = 4.0
"""The defender starts this far in front of its goal line (paper Figure 6)."""
MIN_DISTANCE_UNITS = 20.0
MAX_DISTANCE_UNITS = 30.0
"""Ball (and shooter) start 20-30 units from the defender (paper Figure 6)."""
TRIGGER_UNITS = 14.0
"""The defender chooses TA when BD <= 14 units (paper §5)."""
DEFAULT_SECTOR_DEG = 45.0
"""Half-width of the ball's start bearing (calibrated: the paper draws the sector, no number)."""
TOLERANCE_HEADING_SIGMAS = 3.0
"""The defender leaves out turns below this many sigmas of the sensor's heading noise."""
SAVE_SPEED_PER_LENGTH = 1e-3
"""ε of the SAVE rule: this fraction of the pitch length per second."""
BACKWARD_SHARE = 0.5
"""A SAVE needs the ball to move back along û by at least this share of its speed (30° behind
sideways); a smaller backward component is a deflection (module docstring)."""

# The coach's reasons (module docstring), shared with the batched drill.
INTO_GOAL = "ball into the goal between the posts"
OVER_OWN_LINE = "ball over the shooter's goal line"
OVER_LINE_WIDE = "ball crossed the goal line wide of the posts"
AT_SIDE_LINE = "ball reached a side line"
AT_END_LINE_WIDE = "ball reached the end line wide of the posts"
DEFLECTED_STOPPED = "deflected by the defender, stopped short of the goal"
MOVING_BACK = "ball moving back toward the shooter"
PAST_INTO_GOAL = "ball past the defender, heading between the posts"
PAST_WIDE = "ball past the defender, heading wide"
STOPPED_SHORT = "ball stopped short"


def deflected_then(reason: str) -> str:
    """The reason of a SAVE whose deflected ball then did something that is not a goal."""
    return f"deflected by the defender; then {reason}"


class Launch(StrEnum):
    """Who sets the ball moving (module docstring)."""

    AUTO = "auto"
    SHOOTER = "shooter"
    COACH = "coach"


class Decision(StrEnum):
    """What the defender decides at the trigger (module docstring, "Decision")."""

    TURN = "turn"
    LEAD = "lead"


class ClientKind(StrEnum):
    """How the defender's client acts (module docstring, "Defender")."""

    SEE = "see"
    CYCLE = "cycle"


class Shot(StrEnum):
    """Where the ball is aimed (module docstring, "Shot")."""

    DEFENDER = "defender"
    GOAL_MOUTH = "goal_mouth"


class Scaling(StrEnum):
    """How the paper's drill is carried to a field (module docstring)."""

    AUTO = "auto"
    LITERAL = "literal"
    SENSOR_UPDATES = "sensor_updates"
    TASK = "task"


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


class InterceptDrill:
    """The paper's Figure 6 trial on any field model; labels SAVE, GOAL or MISS.

    Args:
        behaviour: The defender's behaviour (:class:`~robotsoccer.skills.intercept.Behaviour`).
        model: Model file for ``net`` (``.npz``) or ``lookup`` (JSON).
        ta_mode: ``hold`` (TA chosen once, at the trigger) or ``every_see``.
        aim_offset_deg: The shooter aims this far left of the defender [deg] (paper: 4° wide).
        kick_power: The shooter's kick power in the literal drill (scales the matched launch).
        launch: ``auto``, ``shooter`` or ``coach`` (module docstring).
        scaling: ``auto``, ``literal``, ``sensor_updates`` or ``task`` (module docstring).
        sector_deg: Half-width of the ball's start bearing around -x from the defender [deg].
        max_time_s: Simulated time after which the trial is a MISS [s].
        defender_kick: Let the defender clear a ball within reach of an aimable kick; False
            (default): it stops the ball with its body (a calibrated choice, module docstring).
        transfer: Accept a model file trained on another field model or preset (the
            transfer study); False (default) refuses one whose provenance is not this field.
        trigger_scale: Multiply the plan's trigger distance by this (an ablation; 1: as
            planned).
        launch_speed_scale: Multiply the plan's launch speed by this (an ablation; the noise
            period and the trigger stay as planned).
        turn_tolerance_deg: The defender's turn tolerance [deg] instead of the plan's (an
            ablation); None: the plan's (three sigmas of the sensor's heading noise).
        decision: ``turn`` (the paper's TA) or ``lead`` (a meeting time,
            :mod:`robotsoccer.skills.lead`).
        shot: ``defender`` (the paper's: at the defender, plus the aim offset) or
            ``goal_mouth`` (at a point drawn uniformly across the goal mouth).
        launch_speed_mps: The ball's launch speed [m/s] in place of the plan's; 0: the plan's.
        launch_speed_max_mps: With `launch_speed_mps`, draw each trial's speed uniformly
            between the two [m/s] (a coach launch); 0: one speed. The plan's numbers
            (arrival time, ...) are those of the middle speed.
        client: ``see`` (the paper's client: decides at each see, "turn, then dash") or
            ``cycle`` (a command every cycle from a world model,
            :mod:`robotsoccer.skills.cycle`; the turn decision only, no decision period).
        lead_time_scale: Multiply a lead net's τ by this; 1 (default): τ in seconds as the
            net gives it. With ``transfer=true`` a net's distances are in drill units and its τ
            stays a time in seconds; the transfer study's check rows give the test drill's
            flight time over the training drill's here, so that τ keeps its share of the flight
            (:func:`robotsoccer.experiments.transfer.lead_time_scale`).

    Raises:
        ValueError: An unknown behaviour, TA mode, launch or scaling, a missing model file
            name, or a sector outside [0, 90] or a time limit that is not positive, or a scale
            that is not positive or a negative tolerance.
    """

    name: str = "intercept"
    labels: tuple[str, ...] = ("SAVE", "GOAL", "MISS")

    def __init__(
        self,
        behaviour: Behaviour | str = Behaviour.STRAIGHT,
        model: str = "",
        ta_mode: TaMode | str = TaMode.HOLD,
        aim_offset_deg: float = 0.0,
        kick_power: float = 100.0,
        launch: Launch | str = Launch.AUTO,
        scaling: Scaling | str = Scaling.AUTO,
        sector_deg: float = DEFAULT_SECTOR_DEG,
        max_time_s: float = 10.0,
        defender_kick: bool | str = False,
        transfer: bool | str = False,
        trigger_scale: float = 1.0,
        launch_speed_scale: float = 1.0,
        turn_tolerance_deg: float | None = None,
        decision: Decision | str = Decision.TURN,
        shot: Shot | str = Shot.DEFENDER,
        launch_speed_mps: float = 0.0,
        launch_speed_max_mps: float = 0.0,
        client: ClientKind | str = ClientKind.SEE,
        lead_time_scale: float = 1.0,
    ) -> None:
        self.behaviour = check_behaviour(behaviour, model)
        self.client = choice(ClientKind, client, "client")
        self.decision = choice(Decision, decision, "decision")
        self.shot = choice(Shot, shot, "shot")
        if self.decision is Decision.LEAD and self.behaviour is Behaviour.LOOKUP:
            raise ValueError("decision 'lead' has no lookup table: choose another behaviour")
        if self.decision is Decision.LEAD and self.client is ClientKind.CYCLE:
            raise ValueError("client 'cycle' plays the turn decision: use client=see for 'lead'")
        if not (math.isfinite(float(launch_speed_mps)) and float(launch_speed_mps) >= 0.0):
            raise ValueError(f"launch_speed_mps must be >= 0, got {launch_speed_mps!r}")
        self.launch_speed_mps = float(launch_speed_mps)
        self.launch_speed_max_mps = float(launch_speed_max_mps)
        if self.launch_speed_max_mps and not (
            math.isfinite(self.launch_speed_max_mps)
            and self.launch_speed_max_mps >= self.launch_speed_mps > 0.0
        ):
            raise ValueError(
                "launch_speed_max_mps needs 0 < launch_speed_mps <= launch_speed_max_mps, got "
                f"{launch_speed_mps!r} and {launch_speed_max_mps!r}"
            )
        if not (math.isfinite(float(lead_time_scale)) and float(lead_time_scale) > 0.0):
            raise ValueError(
                f"lead_time_scale must be a finite number > 0, got {lead_time_scale!r}"
            )
        if float(lead_time_scale) != 1.0 and not (
            self.decision is Decision.LEAD and self.behaviour is Behaviour.NET
        ):
            raise ValueError("lead_time_scale scales a lead net: give decision=lead behaviour=net")
        self.lead_time_scale = float(lead_time_scale)
        self.model = model
        self.ta_mode = choice(TaMode, ta_mode, "ta_mode")
        self.launch = choice(Launch, launch, "launch")
        self.scaling = choice(Scaling, scaling, "scaling")
        if not 0.0 <= sector_deg <= 90.0:
            raise ValueError(f"sector_deg must be in [0, 90], got {sector_deg!r}")
        max_time_s = duration("max_time_s", max_time_s)
        if not kick_power > 0.0:
            raise ValueError(f"kick_power must be > 0, got {kick_power!r}")
        for name, scale in (
            ("trigger_scale", trigger_scale),
            ("launch_speed_scale", launch_speed_scale),
        ):
            if not float(scale) > 0.0:
                raise ValueError(f"{name} must be > 0, got {scale!r}")
        if turn_tolerance_deg is not None and not float(turn_tolerance_deg) >= 0.0:
            raise ValueError(f"turn_tolerance_deg must be >= 0, got {turn_tolerance_deg!r}")
        self.trigger_scale = float(trigger_scale)
        self.launch_speed_scale = float(launch_speed_scale)
        self.turn_tolerance_deg = None if turn_tolerance_deg is None else float(turn_tolerance_deg)
        self.aim_offset_rad = math.radians(aim_offset_deg)
        self.kick_power = float(kick_power)
        self.sector_rad = math.radians(sector_deg)
        self.max_time_s = float(max_time_s)
        self.defender_kick = flag("defender_kick", defender_kick)
        self.transfer = flag("transfer", transfer)
        self.defender_mind: DefenderMind | CycleDefenderMind | LeadDefenderMind | None = None
        self._aim_offset_trial_rad = self.aim_offset_rad
        self._judge_state: _Judge | None = None
        self._plan: LaunchPlan | None = None
        self._plan_facts: FieldFacts | None = None

    def players(self) -> tuple[PlayerRef, ...]:
        """Shooter and defender."""
        return (SHOOTER, DEFENDER)

    def plan(self, arena: Arena) -> LaunchPlan:
        """This drill's launch plan on `arena`'s field (cached per field)."""
        facts = arena.facts
        if facts is not self._plan_facts:  # one look-up per trial, not one per call
            self._plan, self._plan_facts = self.checked_plan(facts), facts
        assert self._plan is not None
        return self._plan

    def plan_for(self, facts: FieldFacts) -> LaunchPlan:
        """This drill's launch plan on a field (cached per field), with the ablations applied."""
        plan = cached_launch_plan(facts, self.kick_power, self.launch, self.scaling)
        speed_scale = self.launch_speed_scale
        if self.launch_speed_mps:
            speed = self.launch_speed_mps
            if self.launch_speed_max_mps:
                speed = 0.5 * (speed + self.launch_speed_max_mps)
            speed_scale *= speed / plan.launch_speed_mps
        return ablated(plan, facts, self.trigger_scale, speed_scale, self.turn_tolerance_deg)

    def distance_factor(self, facts: FieldFacts) -> float:
        """The net's distance factor on this field (1 on the field it was trained on).

        A transfer run applying a net trained on another field converts distances through
        :func:`~robotsoccer.skills.intercept.transfer_distance_factor`.
        """
        if not (self.transfer and self.model and self.behaviour is Behaviour.NET):
            return 1.0
        return transfer_distance_factor(self.model, facts)

    def checked_plan(self, facts: FieldFacts) -> LaunchPlan:
        """The plan on a field, after refusing a model file trained elsewhere (not a transfer).

        Raises:
            ValueError: The model file was trained on another field and ``transfer`` is off.
        """
        self._check_origin(facts)
        self._check_decision()
        return self.plan_for(facts)

    def _check_decision(self) -> None:
        """Refuse a model file that decides the other thing (a TA net for the lead, ...)."""
        if not self.model:
            return
        decides = model_decision(self.model)
        if decides != self.decision.value:
            raise ValueError(
                f"model {self.model} decides the {decides}, this run's decision is "
                f"{self.decision.value!r}: train a {self.decision.value} model for it"
            )

    def _check_origin(self, facts: FieldFacts) -> None:
        """Refuse a model file trained on another field (unless this is a transfer run)."""
        if not self.model or self.transfer:
            return
        origin = model_origin(self.model)
        here = (facts.model, facts.preset)
        if origin is None or (origin[0], Path(origin[1]).stem) != (here[0], Path(here[1]).stem):
            trained = "an unrecorded field" if origin is None else f"{origin[0]} `{origin[1]}`"
            raise ValueError(
                f"model {self.model} was trained on {trained}, this run is {here[0]} "
                f"`{here[1]}`: give option transfer=true to test it across fields"
            )

    def field_settings(self, facts: FieldFacts) -> dict[str, float | bool]:
        """The field settings the drill needs where they differ from the field's own.

        The plan's ball-noise period; every landmark in the percepts for the lead decision.
        """
        plan = self.plan_for(facts)
        settings: dict[str, float | bool] = {}
        if not math.isclose(plan.noise_period_s, facts.ball_noise_period_s):
            settings["ball_noise_period_s"] = plan.noise_period_s
        if self.decision is Decision.LEAD:
            settings["all_landmarks"] = True  # the lead defender localises itself
        return settings

    def inputs(self) -> tuple[str, ...]:
        """The model file of ``net`` or ``lookup``."""
        return (self.model,) if self.model else ()

    def setup(self, arena: Arena, rngs: TrialRngs) -> None:
        """Place defender, ball and shooter (and launch the ball for a coach launch)."""
        plan = self.plan(arena)
        rng = rngs["placement"]
        distance = float(rng.uniform(plan.min_distance_m, plan.max_distance_m))
        bearing = float(rng.uniform(-self.sector_rad, self.sector_rad))
        target = None
        if self.shot is Shot.GOAL_MOUTH:
            pitch = arena.facts.pitch
            half = 0.5 * pitch.goal_width_m - pitch.ball_radius_m
            target = float(rng.uniform(-half, half))
        speed = None
        if self.launch_speed_max_mps:
            if plan.launch is not Launch.COACH:
                raise ValueError("launch_speed_max_mps needs a coach launch (launch=coach)")
            speed = float(rng.uniform(self.launch_speed_mps, self.launch_speed_max_mps))
        self.place(arena, plan, distance, bearing, target, speed)

    def place(
        self,
        arena: Arena,
        plan: LaunchPlan,
        distance_m: float,
        bearing_rad: float,
        target_y_m: float | None = None,
        speed_mps: float | None = None,
    ) -> None:
        """Place everything for a ball `distance_m` from the defender at `bearing_rad` off -x.

        The coach's deterministic half of :meth:`setup` (tests place by hand through it).
        `target_y_m`: aim at this point of the defended goal line instead of the defender;
        `speed_mps`: a coach launch at this speed instead of the plan's.
        """
        dx, dy = plan.defender_x_m, 0.0
        ux, uy = math.cos(bearing_rad), math.sin(bearing_rad)  # ball -> defender
        bx, by = dx - distance_m * ux, dy - distance_m * uy
        offset = self.aim_offset_rad
        if target_y_m is not None:
            line_x = arena.facts.pitch.half_length_m
            offset += wrap_angle(math.atan2(target_y_m - by, line_x - bx) - bearing_rad)
        self._aim_offset_trial_rad = offset
        aim = bearing_rad + offset
        ax, ay = math.cos(aim), math.sin(aim)
        gap = plan.shooter_gap_m
        if plan.launch is Launch.COACH:
            speed = plan.launch_speed_mps if speed_mps is None else speed_mps
            arena.place_ball(bx, by, speed * ax, speed * ay)
            arena.place_player(SHOOTER, bx - gap * ux, by - gap * uy, bearing_rad)
        elif not plan.aimable_kick:  # a kicker fires along the heading: aim the shooter
            arena.place_ball(bx, by)
            arena.place_player(SHOOTER, bx - gap * ax, by - gap * ay, aim)
        else:  # the kick takes a direction: face the defender, kick wide
            arena.place_ball(bx, by)
            arena.place_player(SHOOTER, bx - gap * ux, by - gap * uy, bearing_rad)
        arena.place_player(DEFENDER, dx, dy, bearing_rad + math.pi)
        self.start_judging(arena)
        self.defender_mind = None

    def start_judging(self, arena: Arena) -> None:
        """Take the ball's and the defender's present positions as the trial's start.

        :meth:`place` calls it; a test that moves objects by hand afterwards calls it again.
        """
        ball = arena.ball_state()
        defender = arena.player_state(DEFENDER)
        plan = self.plan(arena)
        self._judge_state = _Judge(
            arena,
            plan,
            (ball.x, ball.y),
            (defender.x, defender.y),
            touches=self.shot is Shot.GOAL_MOUTH,
        )

    def minds(self, arena: Arena, rngs: TrialRngs) -> dict[PlayerRef, Mind]:
        """The defender's behaviour, and the shooter when it launches the ball."""
        plan = self.plan(arena)
        defender: DefenderMind | CycleDefenderMind | LeadDefenderMind
        if self.decision is Decision.LEAD:
            defender = self._lead_mind(arena, plan, rngs)
        elif self.client is ClientKind.CYCLE:
            defender = self._cycle_mind(arena, plan, rngs)
        else:
            defender = self._turn_mind(arena, plan, rngs)
        self.defender_mind = defender
        minds: dict[PlayerRef, Mind] = {DEFENDER: defender}
        if plan.launch is Launch.SHOOTER:
            aim = self._aim_offset_trial_rad if plan.aimable_kick else 0.0
            minds[SHOOTER] = AimedShooterMind(DEFENDER, plan.kick_power, aim)
        return minds

    def _lead_mind(self, arena: Arena, plan: LaunchPlan, rngs: TrialRngs) -> LeadDefenderMind:
        """The lead defender (:mod:`robotsoccer.skills.lead`)."""
        net = None
        if self.behaviour is Behaviour.NET:
            net = load_net_function(self.model, self.distance_factor(arena.facts))
            if self.lead_time_scale != 1.0:
                net = ScaledLead(net, self.lead_time_scale)
        policy = lead_policy(self.behaviour.value, rngs["policy"], net, plan.arrival_time_s)
        return LeadDefenderMind(
            policy,
            arena.facts,
            plan.max_distance_m,  # decide at the first full velocity fit: no time to wait
            replan=self.behaviour is Behaviour.ANALYTIC,
            kickable_distance_m=plan.kickable_distance_m if self.defender_kick else None,
            turn_tolerance_rad=plan.turn_tolerance_rad,
        )

    def _turn_mind(self, arena: Arena, plan: LaunchPlan, rngs: TrialRngs) -> DefenderMind:
        """The paper's TA defender (:mod:`robotsoccer.skills.intercept`)."""
        policy = make_policy(
            self.behaviour, rngs["policy"], self.model, self.distance_factor(arena.facts)
        )
        return DefenderMind(
            policy,
            plan.trigger_distance_m,
            ta_mode=self.ta_mode,
            kickable_distance_m=plan.kickable_distance_m if self.defender_kick else None,
            turn_tolerance_rad=plan.turn_tolerance_rad,
            decision_period_ticks=decision_ticks(plan, arena.facts),
        )

    def _cycle_mind(self, arena: Arena, plan: LaunchPlan, rngs: TrialRngs) -> CycleDefenderMind:
        """The TA defender on a per-cycle client (:mod:`robotsoccer.skills.cycle`).

        Raises:
            ValueError: The plan sets a decision period (the ``task`` scaling), or TA is
                chosen at every see (the cycle client holds it).
        """
        if decision_ticks(plan, arena.facts):
            raise ValueError("client 'cycle' acts every cycle: this plan sets a decision period")
        if self.ta_mode is not TaMode.HOLD:
            raise ValueError("client 'cycle' holds TA: use ta_mode=hold")
        policy = make_policy(
            self.behaviour, rngs["policy"], self.model, self.distance_factor(arena.facts)
        )
        return CycleDefenderMind(
            policy,
            arena.facts,
            plan.trigger_distance_m,
            kickable_distance_m=plan.kickable_distance_m if self.defender_kick else None,
        )

    def judge(self, arena: Arena) -> Verdict | None:
        """SAVE, GOAL, MISS or carry on (module docstring)."""
        state = self._judge_state
        if state is None:
            raise RuntimeError("judge() before setup()")
        mind = self.defender_mind
        if mind is not None and mind.triggered and state.trigger is None:
            state.note_trigger(arena)
        return state.judge(arena)

    def timeout(self, arena: Arena) -> Verdict:
        """Out of time: a deflected ball that stopped is a SAVE; else the ball stopped short."""
        state = self._judge_state
        if state is not None:
            state.finish(arena)
            if state.deflected:
                return Verdict("SAVE", DEFLECTED_STOPPED)
        return Verdict("MISS", STOPPED_SHORT)

    def data(self) -> tuple[float, ...]:
        """The defender's example (BD, BA, previous BD, TA), or () without a decision."""
        mind = self.defender_mind
        if mind is None or mind.example is None:
            return ()
        return mind.example

    def measures(self) -> dict[str, float]:
        """From the trigger to the verdict: the defender's travel [units], time, sensor updates.

        Empty when the defender never triggered.
        """
        state = self._judge_state
        if state is None or state.trigger is None or state.end is None:
            return {}
        (t0, x0, y0), (t1, x1, y1) = state.trigger, state.end
        plan = state.plan
        seconds = t1 - t0
        return {
            "defender_travel_units": math.hypot(x1 - x0, y1 - y0) / plan.unit_m,
            "trigger_to_end_s": seconds,
            "updates_after_trigger": seconds / plan.sensor_period_s,
        }


class _Judge:
    """The coach's labelling rule for one trial (module docstring), on plain floats."""

    def __init__(
        self,
        arena: Arena,
        plan: LaunchPlan,
        ball: tuple[float, float],
        defender: tuple[float, float],
        *,
        touches: bool = False,
    ) -> None:
        pitch = arena.facts.pitch
        # Shots across the goal mouth are all on target: one the defender touched and that did
        # not go in is a save even when it still rolls forward (pushed wide of the post).
        self.touch_m = arena.facts.touch_distance_m + 0.05 * arena.facts.unit_m if touches else 0.0
        self.dt_s = arena.facts.dt_s
        self.plan = plan
        self.half_length = pitch.half_length_m
        self.half_width = pitch.half_width_m
        self.post = 0.5 * pitch.goal_width_m
        self.radius = pitch.ball_radius_m
        self.margin = 0.01 * pitch.half_length_m  # a ball this close to a wall touches it
        self.eps = SAVE_SPEED_PER_LENGTH * pitch.length_m
        self.goals = GoalWatch(arena, ball)
        self.x0, self.y0 = ball
        dx, dy = defender[0] - ball[0], defender[1] - ball[1]
        distance = math.hypot(dx, dy)
        self.ux, self.uy = dx / distance, dy / distance
        self.past = distance + pitch.player_radius_m + pitch.ball_radius_m
        self.approaching = False
        self.deflected = False
        self.trigger: tuple[float, float, float] | None = None
        self.end: tuple[float, float, float] | None = None

    def note_trigger(self, arena: Arena) -> None:
        """The defender just chose its TA: note where and when (for the drill's measures)."""
        d = arena.player_state(DEFENDER)
        self.trigger = (arena.tick * self.dt_s, d.x, d.y)

    def finish(self, arena: Arena) -> None:
        """The trial ends now: note where the defender got to."""
        if self.end is None:
            d = arena.player_state(DEFENDER)
            self.end = (arena.tick * self.dt_s, d.x, d.y)

    def judge(self, arena: Arena) -> Verdict | None:
        """The verdict of this tick, or None; notes the defender's end on a verdict."""
        verdict = self._verdict(arena)
        if verdict is not None:
            self.finish(arena)
        return verdict

    def _verdict(self, arena: Arena) -> Verdict | None:  # every tick: keep it lean
        x, y, _, vx, vy = arena.ball_state()
        if self.touch_m and not self.deflected:
            d = arena.player_state(DEFENDER)
            if (d.x - x) ** 2 + (d.y - y) ** 2 <= self.touch_m * self.touch_m:
                self.deflected = True
        crossing = self.goals.step(arena, x, y)
        if crossing:
            if crossing is Crossing.RIGHT_GOAL:
                return Verdict("GOAL", INTO_GOAL)
            if crossing is Crossing.LEFT_GOAL:
                return self._not_in(OVER_OWN_LINE)
            return self._not_in(OVER_LINE_WIDE)
        edge = self.radius + self.margin
        if abs(y) >= self.half_width - edge:
            return self._not_in(AT_SIDE_LINE)
        if x >= self.half_length - edge and abs(y) >= self.post:
            return self._not_in(AT_END_LINE_WIDE)
        if self.deflected and vx * vx + vy * vy < self.eps * self.eps:
            return Verdict("SAVE", DEFLECTED_STOPPED)
        along = vx * self.ux + vy * self.uy
        if along > self.eps:
            self.approaching = True
        elif self.approaching and along < -self.eps:
            if along < -BACKWARD_SHARE * math.hypot(vx, vy):
                return Verdict("SAVE", MOVING_BACK)
            self.deflected = True
        if (x - self.x0) * self.ux + (y - self.y0) * self.uy > self.past:
            return self._past(x, y, vx, vy)
        return None

    def _not_in(self, reason: str) -> Verdict:
        """A ball that did not go in: a SAVE once the defender deflected it, else a MISS."""
        if self.deflected:
            return Verdict("SAVE", deflected_then(reason))
        return Verdict("MISS", reason)

    def _past(self, x: float, y: float, vx: float, vy: float) -> Verdict:
        """The ball got past the defender: GOAL if its path crosses the goal mouth."""
        if vx > 0.0:
            cross = y + (self.half_length - x) * vy / vx
            if abs(cross) < self.post:
                return Verdict("GOAL", PAST_INTO_GOAL)
        return self._not_in(PAST_WIDE)
