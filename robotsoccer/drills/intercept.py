"""The interception drill (paper §5, Figure 6): a shooter kicks at a defender who must stop it.

**Players** (lead's decision): the shooter is ``PlayerRef(LEFT, 1)``, the defender
``PlayerRef(RIGHT, 1)``, defending the goal at +x.

**Geometry** in *units*: one unit is ``pitch.length_m / 105`` (1 m on the Soccer Server, about
2.6 cm on the 2.74 m robot table), so the drill is the same picture on every field. The defender
starts 4 units in front of the centre of its goal, at (half_length - 4 u, 0), facing the ball;
the ball starts 20-30 units from it (uniform), at a bearing uniform in ±``sector_deg`` (default
45°) around the -x axis; the shooter stands behind the ball on the line to the defender. The
trigger distance of the defender (paper: "BD <= 14") is 14 units. Placement draws, in this
order, the distance and the bearing from ``rngs["placement"]``.

**Launch** (option ``launch``): ``"shooter"`` — the shooter sees the defender and at its first
percept kicks with ``kick_power`` toward the seen direction plus ``aim_offset_deg``, the paper's
set-up (the ball starts at rest in the shooter's kickable area, between it and the defender);
``"coach"`` — the coach puts the ball in motion at the launch speed along the aim line (the line
to the defender turned by ``aim_offset_deg``) and the shooter stands behind it, idle.
``"auto"`` (default) is ``"shooter"`` on the Soccer Server and on robots with a kicker, and
``"coach"`` on robots without one (the default ``small_size_1997`` preset: the 1997 robots had no
kicker).

**Scaling to the robots** (:func:`launch_plan`). Geometry scales with the unit. The ball's speed
is chosen so that the *same number of sensor updates* pass between the launch and the ball's
arrival at the defender (the issue's example): on the reference Soccer Server preset
(``soccer_server_1996``) a power-P kick gives the ball v0 = P · kick_power_rate per cycle, after
which it moves v0 · decay^k in cycle k, so it covers D = 25 units (the mean distance, centre to
centre) in n cycles with ``D = v0 (1 - decay^n) / (1 - decay)``: for P = 100, v0 = 1.6 m/cycle,
decay 0.96, n = 24.0 cycles = 2.40 s = 9.6 sees of 250 ms. On the robots the ball rolls with
constant deceleration a, and the camera sends a frame every 1/30 s; the ball must cover 25 units
(0.652 m) in 9.6 frames (0.320 s): ``v0 = D / t + a t / 2`` = 2.05 m/s. The robot trigger
distance is then 14 units = 0.365 m, about 5 frames before arrival, as 14 m is on the server.
Latencies (camera, link) are not part of the rule. With ``launch="shooter"`` on a robot with a
kicker, the power is the launch speed's share of the kicker's top speed.

The same time scale sets the ball-motion noise on the robots
(:meth:`InterceptDrill.arena_settings`): one server cycle corresponds to the robot flight time over
the server's 24 cycles in flight, 0.320 s / 24 = 13.3 ms, i.e. 3 physics ticks (12.5 ms). The
robots' noise (a fraction of the speed per axis, like ``ball_rand``) then acts about as many times
per flight as on the Soccer Server, so a noise level means the same wander in units on both fields.
(With the preset's 100 ms period it would act only 3 times per flight and the drill would be nearly
noiseless.)

**Defender** (:mod:`robotsoccer.skills.intercept`): the behaviour (option ``behaviour``: still,
straight, random, net, lookup, analytic; ``model`` the file of net/lookup), ``ta_mode`` ("hold":
TA chosen once at the trigger; "every_see"). By default it stops the ball with its body on both
fields (``defender_kick=False``: the paper's §5 baselines are matched that way, see "Measured");
with ``defender_kick=True`` it clears a ball within the Soccer Server's kickable area
(``dynamics.kickable_area_m``) with power 100 away from its goal. On robots it leaves out
turns smaller than three camera heading-noise sigmas (a robot stops to spin for a whole camera
period on each turn).

**Labels** (the coach judges the truth after every tick; ``labels = ("SAVE", "GOAL", "MISS")``).
Let û be the unit vector from the ball's start to the defender's start and ε = 1e-3 · pitch
length per second:

* **SAVE** — after the ball has been moving toward the defender (velocity along û > ε), its
  velocity along û drops below -ε: it moves back toward the shooter;
* **past the defender** — the ball's progress along û exceeds the defender's start distance plus
  player radius plus ball radius: **GOAL** if its straight-line path crosses the goal line
  (x = half_length) between the posts, else **MISS** ("heading wide");
* the ball crosses the goal line (x = half_length): **GOAL** between the posts, else **MISS**;
  a ball the Soccer Server's referee put back on the centre spot (it scored) is a **GOAL**;
* the ball reaches a side line or the end line wide of the posts (a wall on the robot table,
  whose bounce must not count as a save): **MISS**;
* time out (``max_time_s`` simulated, default 10 s): **MISS**, "ball stopped short".

:meth:`InterceptDrill.data` returns the defender's example (BD [m], BA [rad], previous BD [m],
TA [rad]) recorded at the trigger, or ``()`` when no decision happened.

**Measured** (1000 trials, seed 1, ``soccer_server_1996``, ball_rand 0.05; saves / goals /
misses in %): still 32.9 / 61.6 / 5.5 (paper: "hits it only 35%"); straight 82.3 / 15.1 / 2.6
clearing kickable balls, 51.6 / 43.6 / 4.8 with ``defender_kick=False`` (paper 53 / 35); random
43.7 / 52.9 / 3.4 clearing, 22.2 / 73.4 / 4.4 blocking (paper: misses 76 %); analytic 92.6 /
6.6 / 0.8 clearing, 73.0 / 23.8 / 3.2 blocking (paper 82 / 13). The paper's training-drill
numbers are matched by a defender that stops the ball with its body; the 1998 kickable area
(1.885 m) is a far bigger target than the body (0.885 m). On ``small_size_1997`` at ball noise
0.05 the robot drill is almost always a save (still 99.7 %, straight 99.8 %, random 98.0 %):
robot and ball radii add up to 2.3 units against the server's 0.9, the ball's noise acts every
100 ms (3 times in its 0.32 s flight, against 24 cycles on the server), and in the ~5 frames
after the trigger a robot moves about half a unit.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

from field_models.arena import Arena
from field_models.protocol import LEFT, RIGHT, Mind, PlayerRef
from field_models.registry import DEFAULT_PRESETS, robot_preset, server_preset
from field_models.robot_physics.config import RobotPhysicsPreset
from field_models.seeding import TrialRngs
from field_models.soccer_server.params import ServerPreset
from robotsoccer.drills.base import Verdict
from robotsoccer.skills.intercept import (
    TA_MODES,
    DefenderMind,
    ShooterMind,
    check_behaviour,
    make_policy,
)

SHOOTER = PlayerRef(LEFT, 1)
DEFENDER = PlayerRef(RIGHT, 1)

SERVER_FIELD_LENGTH_M = 105.0
"""The Soccer Server's field length: the drill's distances are in units of length / 105."""
DEFENDER_SETBACK_UNITS = 4.0
"""The defender starts this far in front of its goal line (paper Figure 6)."""
MIN_DISTANCE_UNITS = 20.0
MAX_DISTANCE_UNITS = 30.0
"""Ball (and shooter) start 20-30 units from the defender (paper Figure 6)."""
TRIGGER_UNITS = 14.0
"""The defender chooses TA when BD <= 14 units (paper §5)."""
REFERENCE_SERVER_PRESET = "soccer_server_1996"
"""The Soccer Server whose sees between kick and arrival the robot launch matches."""
LAUNCHES = ("auto", "shooter", "coach")
"""Values of the ``launch`` option."""
TOLERANCE_HEADING_SIGMAS = 3.0
"""Robots leave out turns below this many camera heading-noise sigmas."""
SAVE_SPEED_PER_LENGTH = 1e-3
"""ε of the SAVE rule: this fraction of the pitch length per second."""


@dataclass(frozen=True, slots=True)
class LaunchPlan:
    """The drill's geometry and launch on one field, scaled from the Soccer Server (see module).

    Attributes:
        field_model: ``"soccer_server"`` or ``"robot_physics"``.
        preset: The preset's name.
        unit_m: One drill unit: pitch length / 105 [m].
        defender_x_m: The defender's start x (y = 0) [m].
        min_distance_m: Nearest ball start from the defender [m].
        max_distance_m: Farthest ball start from the defender [m].
        mean_distance_m: The distance the arrival numbers are computed for (25 units) [m].
        trigger_distance_m: The defender chooses TA at this BD (14 units) [m].
        launch: ``"shooter"`` or ``"coach"`` (``"auto"`` resolved).
        kick_power: The shooter's kick power (server units, or the robot kicker's 0-100).
        launch_speed_mps: The ball's speed as it leaves [m/s].
        sensor_period_s: Time between two percepts (see interval, camera frame period) [s].
        arrival_time_s: Time for the ball to cover `mean_distance_m` [s].
        arrival_updates: Percepts in that time (the quantity matched across fields).
        kickable_distance_m: The defender kicks when BD is within this [m]; None: it blocks.
        shooter_gap_m: Centre distance from the shooter to the ball at the start [m].
        turn_tolerance_rad: The defender leaves out smaller turns [rad].
        reference_preset: The Soccer Server preset whose arrival_updates were matched.
        noise_period_s: How often ball-motion noise acts [s]: one server cycle on the Soccer
            Server; on the robots one *scaled* cycle, the flight time over the reference's
            cycles in flight, to whole physics ticks (module docstring).
    """

    field_model: str
    preset: str
    unit_m: float
    defender_x_m: float
    min_distance_m: float
    max_distance_m: float
    mean_distance_m: float
    trigger_distance_m: float
    launch: str
    kick_power: float
    launch_speed_mps: float
    sensor_period_s: float
    arrival_time_s: float
    arrival_updates: float
    kickable_distance_m: float | None
    shooter_gap_m: float
    turn_tolerance_rad: float
    reference_preset: str
    noise_period_s: float


def launch_plan(
    source: str | Arena | RobotPhysicsPreset | ServerPreset,
    preset: str | None = None,
    *,
    kick_power: float = 100.0,
    launch: str = "auto",
    reference_preset: str = REFERENCE_SERVER_PRESET,
) -> LaunchPlan:
    """The scaled geometry and launch numbers of the drill on a field (module docstring).

    Args:
        source: A field model name (then `preset` names the preset, default the model's
            default), a loaded preset, or an arena (its preset).
        preset: Preset name or path when `source` is a field model name.
        kick_power: The shooter's kick power on the reference Soccer Server (paper: fixed).
        launch: ``"auto"``, ``"shooter"`` or ``"coach"``.
        reference_preset: The Soccer Server preset the robot launch is matched to.

    Raises:
        ValueError: Unknown field model or launch, a shooter launch on a robot without a
            kicker, or a launch the field cannot make (ball stops short, too fast, kicker too
            weak).
    """
    if launch not in LAUNCHES:
        raise ValueError(f"unknown launch {launch!r} (known: {', '.join(LAUNCHES)})")
    loaded = _preset_of(source, preset)
    if isinstance(loaded, ServerPreset):
        return _server_plan(loaded, kick_power, launch)
    reference = _server_plan(server_preset(reference_preset), kick_power, "shooter")
    return _robot_plan(loaded, reference, launch, reference_preset)


def _preset_of(
    source: str | Arena | RobotPhysicsPreset | ServerPreset, preset: str | None
) -> RobotPhysicsPreset | ServerPreset:
    if isinstance(source, RobotPhysicsPreset | ServerPreset):
        return source
    if isinstance(source, str):
        if source == "soccer_server":
            return server_preset(preset or DEFAULT_PRESETS[source])
        if source == "robot_physics":
            return robot_preset(preset or DEFAULT_PRESETS[source])
        raise ValueError(f"unknown field model {source!r}")
    loaded = getattr(source, "preset", None)  # both arenas keep their preset
    if not isinstance(loaded, RobotPhysicsPreset | ServerPreset):
        raise TypeError(f"cannot find the preset of {source!r}")
    return loaded


def _server_plan(p: ServerPreset, kick_power: float, launch: str) -> LaunchPlan:
    d = p.dynamics
    unit = d.pitch_length_m / SERVER_FIELD_LENGTH_M
    mean = 0.5 * (MIN_DISTANCE_UNITS + MAX_DISTANCE_UNITS) * unit
    v0 = min(kick_power * d.kick_power_rate_m_per_cycle2, d.ball_speed_max_m_per_cycle)
    cycles = _cycles_to_cover(mean, v0, d.ball_decay)
    if cycles is None:
        raise ValueError(f"a power-{kick_power:g} kick stops short of {mean:g} m")
    period = p.sensing.see_interval_ms / 1000.0
    return LaunchPlan(
        field_model="soccer_server",
        preset=p.name,
        unit_m=unit,
        defender_x_m=0.5 * d.pitch_length_m - DEFENDER_SETBACK_UNITS * unit,
        min_distance_m=MIN_DISTANCE_UNITS * unit,
        max_distance_m=MAX_DISTANCE_UNITS * unit,
        mean_distance_m=mean,
        trigger_distance_m=TRIGGER_UNITS * unit,
        launch="shooter" if launch == "auto" else launch,
        kick_power=kick_power,
        launch_speed_mps=v0 / d.dt_s,
        sensor_period_s=period,
        arrival_time_s=cycles * d.dt_s,
        arrival_updates=cycles * d.dt_s / period,
        kickable_distance_m=d.kickable_area_m,
        shooter_gap_m=d.player_size_m + d.ball_size_m + 0.5 * d.kickable_margin_m,
        turn_tolerance_rad=0.0,
        reference_preset=p.name,
        noise_period_s=d.dt_s,
    )


def _cycles_to_cover(distance: float, v0: float, decay: float) -> float | None:
    """Cycles (fractional) a ball starting at v0 per cycle, decaying, takes to cover `distance`.

    Solves ``distance = v0 (1 - decay^n) / (1 - decay)``; None if it never gets there.
    """
    if v0 <= 0.0:
        return None
    if decay >= 1.0:
        return distance / v0
    left = 1.0 - distance * (1.0 - decay) / v0
    if left <= 0.0 or decay <= 0.0:
        return None
    return math.log(left) / math.log(decay)


def _robot_plan(
    p: RobotPhysicsPreset, reference: LaunchPlan, launch: str, reference_name: str
) -> LaunchPlan:
    unit = p.field.length_m / SERVER_FIELD_LENGTH_M
    mean = 0.5 * (MIN_DISTANCE_UNITS + MAX_DISTANCE_UNITS) * unit
    kicker = p.robot.kicker
    if launch == "auto":
        launch = "coach" if kicker is None else "shooter"
    period = 1.0 / p.camera.frame_rate_hz
    time = reference.arrival_updates * period
    decel = p.ball.rolling_decel_mps2
    speed = mean / time + 0.5 * decel * time
    if speed - decel * time <= 0.0 or speed > p.ball.max_speed_mps:
        raise ValueError(f"{p.name}: launch speed {speed:.3g} m/s is not possible on this table")
    half = 0.5 * p.robot.size_m
    if launch == "shooter":
        if kicker is None:
            raise ValueError(f"{p.name}: the robots have no kicker: use launch='coach'")
        power = 100.0 * speed / kicker.max_speed_mps
        if power > 100.0:
            raise ValueError(f"{p.name}: the kicker's top speed is below {speed:.3g} m/s")
        gap = half + p.ball.radius_m + 0.5 * kicker.reach_m
    else:
        power = reference.kick_power
        gap = half + p.ball.radius_m + 0.5 * unit
    return LaunchPlan(
        field_model="robot_physics",
        preset=p.name,
        unit_m=unit,
        defender_x_m=0.5 * p.field.length_m - DEFENDER_SETBACK_UNITS * unit,
        min_distance_m=MIN_DISTANCE_UNITS * unit,
        max_distance_m=MAX_DISTANCE_UNITS * unit,
        mean_distance_m=mean,
        trigger_distance_m=TRIGGER_UNITS * unit,
        launch=launch,
        kick_power=power,
        launch_speed_mps=speed,
        sensor_period_s=period,
        arrival_time_s=time,
        arrival_updates=reference.arrival_updates,
        kickable_distance_m=None,
        shooter_gap_m=gap,
        turn_tolerance_rad=TOLERANCE_HEADING_SIGMAS * p.camera.heading_sigma_rad,
        reference_preset=reference_name,
        noise_period_s=_scaled_cycle(p, time, reference),
    )


def _scaled_cycle(p: RobotPhysicsPreset, flight_s: float, reference: LaunchPlan) -> float:
    """One server cycle in the robot drill's time: the flight over the reference's cycles.

    The ball_rand-like noise then acts as many times per flight as on the Soccer Server (24 for
    a power-100 kick over 25 units), so the ball's path wanders by the same number of units.
    """
    cycles = reference.arrival_time_s / reference.noise_period_s
    ticks = max(1, round(flight_s / cycles * p.timing.physics_hz))
    return ticks / p.timing.physics_hz


@functools.lru_cache(maxsize=64)
def _cached_plan(
    preset: RobotPhysicsPreset | ServerPreset, kick_power: float, launch: str
) -> LaunchPlan:
    """The plan of a preset, once per process (presets are frozen, hence hashable)."""
    return launch_plan(preset, kick_power=kick_power, launch=launch)


class InterceptDrill:
    """The paper's Figure 6 trial on either field model; labels SAVE, GOAL or MISS.

    Args:
        behaviour: The defender's behaviour (:data:`robotsoccer.skills.intercept.BEHAVIOURS`).
        model: Model file for ``net`` (``.npz``) or ``lookup`` (JSON).
        ta_mode: ``"hold"`` (TA chosen once, at the trigger) or ``"every_see"``.
        aim_offset_deg: The shooter aims this far left of the defender [deg] (paper: 4° wide).
        kick_power: The shooter's kick power (Soccer Server units; scales the robot launch).
        launch: ``"auto"``, ``"shooter"`` or ``"coach"`` (module docstring).
        sector_deg: Half-width of the ball's start bearing around -x from the defender [deg].
        max_time_s: Simulated time after which the trial is a MISS [s].
        defender_kick: Let the defender clear a kickable ball where the field model can kick
            (Soccer Server); False (default): it stops the ball with its body, as on kicker-less
            robots. Blocking reproduces the paper's §5 baselines (module docstring, "Measured").

    Raises:
        ValueError: An unknown behaviour, TA mode or launch, a missing model file name, or a
            sector outside [0, 90] or a time limit that is not positive.
    """

    name: str = "intercept"
    labels: tuple[str, ...] = ("SAVE", "GOAL", "MISS")

    def __init__(
        self,
        behaviour: str = "straight",
        model: str = "",
        ta_mode: str = "hold",
        aim_offset_deg: float = 0.0,
        kick_power: float = 100.0,
        launch: str = "auto",
        sector_deg: float = 45.0,
        max_time_s: float = 10.0,
        defender_kick: bool | str = False,
    ) -> None:
        check_behaviour(behaviour, model)
        if ta_mode not in TA_MODES:
            raise ValueError(f"unknown ta_mode {ta_mode!r} (known: {', '.join(TA_MODES)})")
        if launch not in LAUNCHES:
            raise ValueError(f"unknown launch {launch!r} (known: {', '.join(LAUNCHES)})")
        if not 0.0 <= sector_deg <= 90.0:
            raise ValueError(f"sector_deg must be in [0, 90], got {sector_deg!r}")
        if not max_time_s > 0.0:
            raise ValueError(f"max_time_s must be > 0, got {max_time_s!r}")
        self.behaviour = behaviour
        self.model = model
        self.ta_mode = ta_mode
        self.aim_offset_rad = math.radians(aim_offset_deg)
        self.kick_power = float(kick_power)
        self.launch = launch
        self.sector_rad = math.radians(sector_deg)
        self.max_time_s = float(max_time_s)
        self.defender_kick = _flag("defender_kick", defender_kick)
        self.defender_mind: DefenderMind | None = None
        self._judge_state: _Judge | None = None

    def players(self) -> tuple[PlayerRef, ...]:
        """Shooter and defender."""
        return (SHOOTER, DEFENDER)

    def plan(self, arena: Arena) -> LaunchPlan:
        """This drill's launch plan on `arena`'s field (cached per preset)."""
        preset = _preset_of(arena, None)
        return _cached_plan(preset, self.kick_power, self.launch)

    def setup(self, arena: Arena, rngs: TrialRngs) -> None:
        """Place defender, ball and shooter (and launch the ball for a coach launch)."""
        plan = self.plan(arena)
        rng = rngs["placement"]
        distance = float(rng.uniform(plan.min_distance_m, plan.max_distance_m))
        bearing = float(rng.uniform(-self.sector_rad, self.sector_rad))
        self.place(arena, plan, distance, bearing)

    def place(self, arena: Arena, plan: LaunchPlan, distance_m: float, bearing_rad: float) -> None:
        """Place everything for a ball `distance_m` from the defender at `bearing_rad` off -x.

        The coach's deterministic half of :meth:`setup` (tests place by hand through it).
        """
        dx, dy = plan.defender_x_m, 0.0
        ux, uy = math.cos(bearing_rad), math.sin(bearing_rad)  # ball -> defender
        bx, by = dx - distance_m * ux, dy - distance_m * uy
        aim = bearing_rad + self.aim_offset_rad
        ax, ay = math.cos(aim), math.sin(aim)
        gap = plan.shooter_gap_m
        if plan.launch == "coach":
            speed = plan.launch_speed_mps
            arena.place_ball(bx, by, speed * ax, speed * ay)
            arena.place_player(SHOOTER, bx - gap * ux, by - gap * uy, bearing_rad)
        elif plan.field_model == "robot_physics":  # a kicker fires along the heading: aim it
            arena.place_ball(bx, by)
            arena.place_player(SHOOTER, bx - gap * ax, by - gap * ay, aim)
        else:  # the server's kick takes a direction: face the defender, kick wide
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
        self._judge_state = _Judge(arena, (ball.x, ball.y), (defender.x, defender.y))

    def minds(self, arena: Arena, rngs: TrialRngs) -> dict[PlayerRef, Mind]:
        """The defender's behaviour, and the shooter when it launches the ball."""
        plan = self.plan(arena)
        policy = make_policy(self.behaviour, rngs["policy"], self.model)
        defender = DefenderMind(
            policy,
            plan.trigger_distance_m,
            ta_mode=self.ta_mode,
            kickable_distance_m=plan.kickable_distance_m if self.defender_kick else None,
            turn_tolerance_rad=plan.turn_tolerance_rad,
        )
        self.defender_mind = defender
        minds: dict[PlayerRef, Mind] = {DEFENDER: defender}
        if plan.launch == "shooter":
            aim = 0.0 if plan.field_model == "robot_physics" else self.aim_offset_rad
            minds[SHOOTER] = ShooterMind(DEFENDER, plan.kick_power, aim)
        return minds

    def judge(self, arena: Arena) -> Verdict | None:
        """SAVE, GOAL, MISS or carry on (module docstring)."""
        state = self._judge_state
        if state is None:
            raise RuntimeError("judge() before setup()")
        return state.judge(arena)

    def arena_settings(self, field_model: str, preset: str) -> dict[str, float]:
        """Robots: the ball-noise period of one scaled server cycle (module docstring)."""
        if field_model != "robot_physics":
            return {}
        plan = _cached_plan(robot_preset(preset), self.kick_power, self.launch)
        return {"ball_noise_period_s": plan.noise_period_s}

    def timeout(self, arena: Arena) -> Verdict:
        """Out of time: the ball stopped short of the defender."""
        return Verdict("MISS", "ball stopped short")

    def data(self) -> tuple[float, ...]:
        """The defender's example (BD, BA, previous BD, TA), or () without a decision."""
        mind = self.defender_mind
        if mind is None or mind.example is None:
            return ()
        return mind.example


def _flag(name: str, value: bool | str) -> bool:
    """A boolean option; the strings "true"/"false" (any case) too, e.g. from a command line."""
    if isinstance(value, bool):
        return value
    if isinstance(value, str) and value.lower() in ("true", "false"):
        return value.lower() == "true"
    raise ValueError(f"{name} must be true or false, got {value!r}")


class _Judge:
    """The coach's labelling rule for one trial (module docstring), on plain floats."""

    def __init__(
        self, arena: Arena, ball: tuple[float, float], defender: tuple[float, float]
    ) -> None:
        pitch = arena.pitch
        self.half_length = pitch.half_length_m
        self.half_width = pitch.half_width_m
        self.post = 0.5 * pitch.goal_width_m
        self.radius = pitch.ball_radius_m
        self.margin = 0.01 * pitch.half_length_m  # a ball this close to a wall touches it
        self.eps = SAVE_SPEED_PER_LENGTH * pitch.length_m
        self.jump2 = (0.25 * pitch.length_m) ** 2  # no ball moves this far in a tick
        self.x0, self.y0 = ball
        dx, dy = defender[0] - ball[0], defender[1] - ball[1]
        distance = math.hypot(dx, dy)
        self.ux, self.uy = dx / distance, dy / distance
        self.past = distance + pitch.player_radius_m + pitch.ball_radius_m
        self.approaching = False
        self.last = ball

    def judge(self, arena: Arena) -> Verdict | None:
        x, y, _, vx, vy = arena.ball_state()
        lx, ly = self.last
        self.last = (x, y)
        hl = self.half_length
        if (x - lx) ** 2 + (y - ly) ** 2 > self.jump2:
            return Verdict("GOAL", "the referee restarted play after a goal")
        if x >= hl and lx < hl:
            cross = ly + (hl - lx) * (y - ly) / (x - lx)
            if abs(cross) < self.post:
                return Verdict("GOAL", "ball crossed the goal line between the posts")
            return Verdict("MISS", "ball crossed the goal line wide of the posts")
        if x <= -hl:
            return Verdict("MISS", "ball crossed the shooter's goal line")
        edge = self.radius + self.margin
        if abs(y) >= self.half_width - edge:
            return Verdict("MISS", "ball reached a side line")
        if x >= hl - edge and abs(y) >= self.post:
            return Verdict("MISS", "ball reached the end line wide of the posts")
        along = vx * self.ux + vy * self.uy
        if along > self.eps:
            self.approaching = True
        elif self.approaching and along < -self.eps:
            return Verdict("SAVE", "ball moving back toward the shooter")
        if (x - self.x0) * self.ux + (y - self.y0) * self.uy > self.past:
            return self._past(x, y, vx, vy)
        return None

    def _past(self, x: float, y: float, vx: float, vy: float) -> Verdict:
        """The ball got past the defender: GOAL if its path crosses the goal mouth, else MISS."""
        if vx > 0.0:
            cross = y + (self.half_length - x) * vy / vx
            if abs(cross) < self.post:
                return Verdict("GOAL", "ball past the defender, heading between the posts")
        return Verdict("MISS", "ball past the defender, heading wide")
