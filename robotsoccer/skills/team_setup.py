"""A match team's plan and the team minds' constants (:mod:`robotsoccer.skills.team`).

:class:`TeamSetup` is one team's plan on one field (the match drill fills it from the field's
facts); the constants tune the steps of the module docstring of :mod:`robotsoccer.skills.team`;
:class:`BallPolicy` is layer 3's hook on the ball (:mod:`robotsoccer.skills.layer3`).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Protocol

from field_models.arena import BallLaw
from field_models.protocol import Action, Percept, wrap_angle
from robotsoccer.skills.localise import Pose
from robotsoccer.skills.setplay import KickPowers

LOOK_MODES = ("body", "neck")
"""How a team mind looks (:attr:`TeamSetup.look`)."""
TURN_LATENCIES = ("hold", "reckon")
"""How a team mind treats a percept that does not show its last turn yet
(:attr:`TeamSetup.turn_latency`: the two settings of :mod:`robotsoccer.skills.motion`)."""
RECEIVER_HALVES = ("unknown", "estimated")
"""What layer 2's tree is told of the receiver's half in open play (:attr:`TeamSetup.
receiver_half`)."""
REVERSE_HOLD_TICKS = 10
"""With steady turns, a turn the other way within this many ticks of the last needs ..."""
REVERSE_MIN_RAD = math.radians(60.0)
"""... more than this (a ball that moved behind the player still turns it)."""
REVERSE_HOLD_S = 1.0
"""With the dead band, the steady turns' hold in seconds: :data:`REVERSE_HOLD_TICKS` of the
Soccer Server's 100 ms cycles, the same time on every field (on the robots' 4.2 ms ticks the
10-tick hold is 42 ms, shorter than one turn: README, "The robots: do new frames ...")."""
REVERSE_MIN_BAND_RAD = math.radians(120.0)
"""With the dead band, a turn back within the hold needs more than this (a ball or a point that
jumped behind still turns the player). Measured on the robots' baseline match, 2 games a
preset, before the push approach drove with the dead band: 60° left 42-43 reversals per
robot-minute, 120° 19-23, 179° 16."""
BACK_SWITCH_RAD = math.radians(30.0)
"""With the dead band, a player driving forwards (backwards) to a point switches to backwards
(forwards) only when the point is this far behind (ahead of) its side."""
MEMORY_TICKS = 20
"""With steady turns, a ball seen this recently is trusted where it was (going home)."""
SEARCH_TURN_RAD = math.radians(60.0)
"""A player that sees no ball turns this far per decision to find it."""
FACING_RAD = math.radians(12.0)
"""Within this of the heading a player runs; farther, it turns first."""
CHASE_MARGIN_UNITS = 2.0
"""Hysteresis of the chaser rule [units]."""
BALL_SHIFT_X = 0.4
"""A home shifts this share of the ball's x toward the ball."""
BALL_SHIFT_Y = 0.2
"""... and this share of the ball's offset in y."""
NEAR_REACHES = 3.0
"""A ball within this many reaches is near: turn to it before running (no circling), and
layer 1's net is not asked (it learned to meet a ball from afar, §5)."""
COMING_SHARE = 0.1
"""The ball comes toward the player when its distance fell by this share of the reach since
the last percept (the net's case, §5)."""
MIN_PASS_UNITS = 6.0
"""Teammates nearer than this are not passed to (the ball would barely leave)."""
GOALIE_RANGE_UNITS = 5.0
"""The goalie keeps within this of the goal's centre line [units], half the ball's y."""
PUSH_LINE_SHARE = 0.5
"""A pushing player runs through the ball when it stands behind it within this share of its
distance behind, off the ball's line to the goal (about 27°: the push goes goalward)."""
MEET_SPEED_MPS = 0.2
"""A pushing team meets a ball head-on only when it rolls faster than this [m/s]."""
AHEAD_UNITS = -5.0
"""A teammate is a pass candidate when at least this far ahead of the passer (negative: a
little behind is fine)."""


class BallPolicy(Protocol):
    """A learned choice of where to send the ball (layer 3, :mod:`robotsoccer.skills.layer3`).

    The mind asks it where the layered team would ask layer 2's tree (step 3's *pass*), and
    tells it every percept's sighting of the ball, for its rewards.
    """

    def decide(
        self, number: int, percept: Percept, pose: Pose | None, ball_xy: tuple[float, float] | None
    ) -> tuple[str, tuple[Action, ...]] | None:
        """(intent, actions) of its kick, or None: the layered team's rule decides."""
        ...

    def observe(self, number: int, tick: int, ball_xy: tuple[float, float] | None) -> None:
        """Player `number` saw the ball at `ball_xy` (field frame [m]), or did not (None)."""
        ...


@dataclass(frozen=True, slots=True)
class TeamSetup:
    """One team's plan on one field (the match drill fills it from the field's facts).

    Attributes:
        attack_right: The team attacks the goal at +x.
        home: Formation home of each uniform number, field frame [m].
        goalie: The goalie's number, or None.
        landmarks: The field's landmarks (:attr:`FieldFacts.landmarks`).
        unit_m: One drill unit [m].
        reach_m: Kick reach the minds trust (a share of the true reach: sensor noise) [m].
        blocked_m: An opponent this close in the path ends a dribble [m].
        shoot_range_m: The goal this close: shoot [m].
        pass_range_m: Teammates farther than this are not passed to [m].
        trigger_distance_m: Layer 1's trigger distance on the field [m].
        goalie_zone_m: The goalie chases a ball this close to its goal [m].
        home_tolerance_m: Close enough to home [m].
        powers: The field's kick powers.
        half_length_m: Half the pitch's length [m].
        half_width_m: Half its width [m].
        dt_s: One tick [s].
        latency_s: The sensor's latency [s].
        spin_accel_radps2: How fast a player's spin can build up: its acceleration over its
            half-size [rad/s²].
        sensor_period_s: Time between two percepts [s] (the lead's velocity fit).
        ball_law: How the free ball slows down (the lead's prediction); None: it does not.
        steady_turns: Turn without dithering (issue 28): a turn is added to the heading the
            localiser keeps until two landmarks fix it again, and a turn the other way from the
            last one within :data:`REVERSE_HOLD_TICKS` is left out unless it exceeds
            :data:`REVERSE_MIN_RAD`, and a player facing where it last saw the ball without
            seeing it forgets that place (it searches on, one way), and one that is not the
            chaser and saw the ball within :data:`MEMORY_TICKS` goes on home instead of turning
            back to look; a player home stays so until twice the home tolerance away.
            False: the paper's client (turns forgotten until seen).
        push_kick: The players move the ball by pushing it with their bodies (no aimable kick:
            the 1997 small-size robots, `specs/robot_physics.md`): a push sends the ball where
            the body goes, so the minds play it from behind (module docstring, "Pushing").
        lead_from_m: A lead net is asked only of a ball this far or farther when a meeting
            starts: the nearest a shot of its drill is at the trigger (nearer, it would answer
            outside what it learned, and the player meets the ball straight, τ = 0) [m].
        lead_trigger_m: A pushing team's goalie meets a shot on target from this near [m]:
            layer 1's drill's trigger distance (its farthest shot).
        goalie_depth_m: How far in front of its goal line the goalie stands [m].
        sees_all_round: The sensor sees the whole field whatever a player's heading (the
            robots' overhead camera): a ball seen within :data:`MEMORY_TICKS` and missing now
            was missed by the camera, and the player keeps its last command instead of turning
            to search. False: a view cone (the Soccer Server).
        player_radius_m: A player's half size [m] (how far behind the ball it stands).
        goal_width_m: The goal's width [m] (a pushing team's goalie meets shots on target).
        turn_tolerance_rad: Meeting a ball, turns smaller than this are left out (layer 1's
            drill: three sigmas of the sensor's heading noise) [rad].
        look: ``"body"``: the player looks where its body points (the paper's client, no
            neck). ``"neck"`` (issue 28; with :attr:`steady_turns`): it looks with its neck and
            view modes (:mod:`robotsoccer.skills.team_look`); a player off the ball keeps its
            body pointed where it walks, and one that sees no ball walks home while it scans.
        dead_band: Drive on a small heading error instead of re-turning at every percept (issue
            28 item 5, the robots' dithering; :meth:`~robotsoccer.skills.team_base.MindBase.
            _drive_to`): a player going home, or round the ball to push it, turns only when
            driving on would miss its point by more than its tolerance, drives backwards to a
            point behind it, slows so that it can stop there within the loop's latency
            (:meth:`arrive_power`), stays home until twice the tolerance away, and a turn the
            other way within :data:`REVERSE_HOLD_S` of the last is left out unless it exceeds
            :data:`REVERSE_MIN_BAND_RAD` (not while meeting a ball: layer 1 re-aims at every
            percept). False (default): every result as before.
        top_speed_mps: A player's top speed running straight [m/s] (the dead band's arrival).
        turn_latency: How a player treats a percept that does not show its last turn yet
            (:data:`TURN_LATENCIES`, the motion skill's settings, :class:`~robotsoccer.skills.
            motion.TurnsInFlight`; a turn shows after :meth:`turn_ticks`): ``"hold"`` (default)
            decides nothing until a percept shows it, the body going on with its last command;
            ``"reckon"`` decides at every percept, turned into the frame of the turns sent (as
            the set play's minds do; measured in the README's "One motion skill (issue 23,
            measured)").
        receiver_half: What the passer tells layer 2's tree of the receiver's half of the
            attributes (:data:`RECEIVER_HALVES`; open play has no ``say`` report):
            ``"unknown"`` (default, every result as before) or ``"estimated"``: from the
            passer's own view (:func:`learning.pass_features.estimated_receiver_half`; issue 28
            goal 4).
    """

    attack_right: bool
    home: Mapping[int, tuple[float, float]]
    goalie: int | None
    landmarks: tuple[tuple[str, float, float], ...]
    unit_m: float
    reach_m: float
    blocked_m: float
    shoot_range_m: float
    pass_range_m: float
    trigger_distance_m: float
    goalie_zone_m: float
    home_tolerance_m: float
    powers: KickPowers
    half_length_m: float
    half_width_m: float
    dt_s: float
    latency_s: float
    spin_accel_radps2: float
    sensor_period_s: float = 0.1
    ball_law: BallLaw | None = None
    steady_turns: bool = False
    push_kick: bool = False
    lead_from_m: float = 0.0
    lead_trigger_m: float = 0.0
    goalie_depth_m: float = 0.0
    sees_all_round: bool = False
    player_radius_m: float = 0.0
    goal_width_m: float = 0.0
    turn_tolerance_rad: float = 0.0
    look: str = "body"
    dead_band: bool = False
    top_speed_mps: float = 0.0
    turn_latency: str = "hold"
    receiver_half: str = "unknown"

    def __post_init__(self) -> None:
        if self.look not in LOOK_MODES:
            raise ValueError(f"look: expected one of {', '.join(LOOK_MODES)}; got {self.look!r}")
        if self.turn_latency not in TURN_LATENCIES:
            known = ", ".join(TURN_LATENCIES)
            raise ValueError(f"turn_latency: expected one of {known}; got {self.turn_latency!r}")
        check_receiver_half(self.receiver_half)

    def turn_ticks(self, angle_rad: float) -> int:
        """Ticks until a percept shows a turn by `angle_rad` done: latency plus the spin.

        A body that spins up at ``spin_accel`` and down again turns by a in about
        sqrt(|a| / spin_accel) (the robots' host plans its turns so, `robot_physics.host`).
        """
        spin = math.sqrt(abs(angle_rad) / self.spin_accel_radps2)
        return math.ceil((self.latency_s + spin) / self.dt_s)

    def reverse_hold_ticks(self) -> int:
        """Ticks after a turn within which a small turn back is left out (steady turns)."""
        if self.dead_band:
            return math.ceil(REVERSE_HOLD_S / self.dt_s - 1e-9)
        return REVERSE_HOLD_TICKS

    def reverse_min_rad(self) -> float:
        """The least turn back that the steady turns' hold lets through [rad]."""
        return REVERSE_MIN_BAND_RAD if self.dead_band else REVERSE_MIN_RAD

    def arrive_power(self, distance_m: float) -> float:
        """The dash power [0, 100] at which a player can still stop within `distance_m`.

        A player sees itself `latency_s` late and decides again a sensor period later, then
        brakes at its acceleration: v·L + v²/(2a) = d gives the top speed v that stops in d
        (on the robots 80% power overshoots a 5 cm home by about 20 cm: a turn round and back).
        """
        accel = self.spin_accel_radps2 * self.player_radius_m
        if accel <= 0.0 or self.top_speed_mps <= 0.0:
            return 100.0
        lag = self.latency_s + self.sensor_period_s
        speed = accel * (math.sqrt(lag * lag + 2.0 * max(distance_m, 0.0) / accel) - lag)
        return min(100.0, 100.0 * speed / self.top_speed_mps)

    @property
    def goal_xy(self) -> tuple[float, float]:
        """The opponents' goal centre [m]."""
        return (self.half_length_m if self.attack_right else -self.half_length_m, 0.0)

    @property
    def own_goal_xy(self) -> tuple[float, float]:
        """The team's own goal centre [m]."""
        return (-self.goal_xy[0], 0.0)


def check_receiver_half(value: str) -> None:
    """Refuse a receiver half that is not one of :data:`RECEIVER_HALVES`, naming them.

    Raises:
        ValueError: In one line.
    """
    if value not in RECEIVER_HALVES:
        known = ", ".join(RECEIVER_HALVES)
        raise ValueError(f"receiver_half: expected one of {known}; got {value!r}")


def goal_direction(
    percept: Percept, pose: Pose | None, attack_right: bool, goal_xy: tuple[float, float]
) -> tuple[float, float] | None:
    """(distance [m], angle [rad]) of the opponents' goal: its seen flag, else from the pose.

    The flag is the sensor's own reading (``g r`` at +x, ``g l`` at -x); without it the pose
    gives the way to `goal_xy`; None when neither is known.
    """
    mark = percept.landmark("g r" if attack_right else "g l")
    if mark is not None:
        return (mark.distance_m, mark.angle_rad)
    if pose is None:
        return None
    gx, gy = goal_xy
    return (
        math.hypot(gx - pose.x, gy - pose.y),
        wrap_angle(math.atan2(gy - pose.y, gx - pose.x) - pose.heading),
    )


def in_shooting_range(goal: tuple[float, float] | None, shoot_range_m: float) -> bool:
    """The teams' one shooting rule: the goal known and within `shoot_range_m`.

    `goal` is :func:`goal_direction`'s answer; `shoot_range_m` the team's
    :attr:`TeamSetup.shoot_range_m`.
    The layered and baseline minds shoot by it, and layer 3's shot-range guard asks it
    (:mod:`robotsoccer.skills.layer3`), so both teams shoot from the same distances.
    """
    return goal is not None and goal[0] <= shoot_range_m
