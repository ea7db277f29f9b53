"""A match team's plan on a field: formations, ranges and powers in units (issue 11's match).

:func:`team_setup` turns the field's facts and layer 1's launch plan into the
:class:`~robotsoccer.skills.team_setup.TeamSetup` every mind of a team shares; the numbers it
uses are the constants below, in the drill's units. :func:`kickoff_spots` places both teams
for a kick-off.
"""

from __future__ import annotations

import math

from field_models.arena import FieldFacts
from field_models.protocol import LEFT, RIGHT, PlayerRef
from robotsoccer.drills.intercept_plan import LaunchPlan
from robotsoccer.drills.layered import control_reach
from robotsoccer.skills.lead import VELOCITY_SPAN_S
from robotsoccer.skills.motion import dribble_power
from robotsoccer.skills.setplay import KickPowers
from robotsoccer.skills.team_setup import TeamSetup

FORMATIONS: dict[int, dict[int, tuple[float, float]]] = {
    11: {
        1: (-50.0, 0.0),
        2: (-36.0, 20.0),
        3: (-38.0, 7.0),
        4: (-38.0, -7.0),
        5: (-36.0, -20.0),
        6: (-16.0, 22.0),
        7: (-19.0, 8.0),
        8: (-19.0, -8.0),
        9: (-16.0, -22.0),
        10: (2.0, 10.0),
        11: (2.0, -10.0),
    },
    5: {
        1: (-50.0, 0.0),
        2: (-30.0, 14.0),
        3: (-30.0, -14.0),
        4: (-2.0, 12.0),
        5: (-2.0, -12.0),
    },
    3: {1: (-50.0, 0.0), 2: (-25.0, 12.0), 3: (-5.0, -10.0)},
    2: {1: (-50.0, 0.0), 2: (-5.0, 0.0)},
}
"""Formation homes of the left team [units] (module docstring); number 1 keeps goal. The 3- and
2-a-side ones are for small-sided games (the VSS table's 3 v 3, ``robotsoccer/Score-v0``)."""
KICKER = {11: 10, 5: 4, 3: 3, 2: 2}
"""Who kicks off."""
GOALIE = 1
"""Who keeps goal: number 1 of every formation."""
BLOCKED_UNITS = 8.0
"""An opponent this close in the path ends a dribble [units]."""
SHOOT_RANGE_UNITS = 25.0
PASS_RANGE_UNITS = 30.0
"""Longest shot and pass [units], or less where the field's kick cannot carry the ball."""
GOALIE_ZONE_UNITS = 16.5
"""The goalie goes for a ball this close to its goal (the penalty area's depth) [units]."""
HOME_TOLERANCE_UNITS = 2.0
GOALIE_DEPTH_UNITS = 2.0
"""The goalie's stance in front of its goal line on a field with an aimable kick [units]."""
SAFE_REACH_SHARE = 0.85
"""Minds kick when the ball seems within this share of their reach (sensor noise)."""
CARRY_SHARE = 0.6
"""Shots and passes are aimed at most this share of how far a kick carries the ball."""


def team_setup(facts: FieldFacts, plan: LaunchPlan, n: int, team: str) -> TeamSetup:
    """One team of `n`'s plan on this field: homes, ranges, powers, the goalie's stance.

    `plan` is layer 1's launch plan on this field (trigger, the goal-mouth drill's distances).
    How the minds turn, look and ask the tree (:class:`~robotsoccer.skills.team_setup.
    TeamSetup`'s mind settings) is left at its defaults: the match's options set it.
    """
    unit = facts.unit_m
    sign = 1.0 if team == LEFT else -1.0
    powers = kick_powers(facts, plan.kick_power)
    carry = CARRY_SHARE * carry_m(facts, powers.shot)
    pass_carry = CARRY_SHARE * carry_m(facts, powers.passing)
    push = facts.kick is None or not facts.kick.aimable
    return TeamSetup(
        attack_right=team == LEFT,
        home={k: (sign * x * unit, sign * y * unit) for k, (x, y) in FORMATIONS[n].items()},
        goalie=GOALIE,
        landmarks=facts.landmarks,
        unit_m=unit,
        reach_m=SAFE_REACH_SHARE * control_reach(facts),
        blocked_m=BLOCKED_UNITS * unit,
        shoot_range_m=min(SHOOT_RANGE_UNITS * unit, carry),
        pass_range_m=min(PASS_RANGE_UNITS * unit, pass_carry),
        trigger_distance_m=plan.trigger_distance_m,
        goalie_zone_m=GOALIE_ZONE_UNITS * unit,
        home_tolerance_m=HOME_TOLERANCE_UNITS * unit,
        powers=powers,
        half_length_m=facts.pitch.half_length_m,
        half_width_m=facts.pitch.half_width_m,
        dt_s=facts.dt_s,
        latency_s=facts.sensor_latency_s or 0.0,
        spin_accel_radps2=facts.player_accel_mps2 / facts.pitch.player_radius_m,
        sensor_period_s=facts.sensor_period_s,
        ball_law=facts.ball,
        top_speed_mps=facts.player_top_speed_mps,
        push_kick=push,
        # The nearest a shot of layer 1's goal-mouth drill is at its trigger: the nearest
        # start, less the flight at the players' top speed (its fastest shot) during the
        # velocity fit (robotsoccer.experiments.lead_study).
        lead_from_m=plan.min_distance_m - VELOCITY_SPAN_S * facts.player_top_speed_mps,
        lead_trigger_m=plan.max_distance_m,
        # A pushing goalie stands where layer 1's goal-mouth drill put its defender (it
        # meets shots as it learned there); elsewhere two units out, as before.
        goalie_depth_m=(
            facts.pitch.half_length_m - plan.defender_x_m if push else GOALIE_DEPTH_UNITS * unit
        ),
        # The walled table is seen by an overhead camera (specs/robot_physics.md §2).
        sees_all_round=facts.walled,
        player_radius_m=facts.pitch.player_radius_m,
        goal_width_m=facts.pitch.goal_width_m,
        turn_tolerance_rad=plan.turn_tolerance_rad,
    )


def kick_powers(facts: FieldFacts, pass_power: float) -> KickPowers:
    """Dribble, pass and shot powers on this field (pass: layer 1's launch power).

    The dribble is the set play's too (:func:`~robotsoccer.skills.motion.dribble_power`): a
    kick with the field's aimable kick, else a push.

    Raises:
        ValueError: No kick sends the ball a dribble's way.
    """
    kick = facts.kick
    if kick is None or not kick.aimable:
        return KickPowers(dribble=dribble_power(facts, 0.0, None), passing=100.0, shot=100.0)
    margin = SAFE_REACH_SHARE * (control_reach(facts) - facts.touch_distance_m)
    dribble = dribble_power(facts, margin, kick.speed_per_power_mps)
    return KickPowers(dribble=dribble, passing=pass_power, shot=100.0)


def carry_m(facts: FieldFacts, power: float) -> float:
    """How far a kick of `power` carries the ball before it stops (or in 10 s) [m]."""
    kick = facts.kick
    speed = kick.speed(power) if kick is not None else facts.player_top_speed_mps
    return facts.ball.distance_in(speed, 10.0)


JITTER_UNITS = 1.0
"""Kick-off spots are moved by up to this in x and y from the ``placement`` stream."""


def kickoff_spots(
    facts: FieldFacts,
    n: int,
    kicker_team: str,
    jitter: dict[PlayerRef, tuple[float, float]],
) -> dict[PlayerRef, tuple[float, float, float]]:
    """Every player's spot when `kicker_team` kicks off: own half, out of the circle."""
    unit = facts.unit_m
    circle = 10.0 * unit
    spots: dict[PlayerRef, tuple[float, float, float]] = {}
    for team in (LEFT, RIGHT):
        sign = 1.0 if team == LEFT else -1.0
        for number, (hx, hy) in FORMATIONS[n].items():
            ref = PlayerRef(team, number)
            jx, jy = jitter.get(ref, (0.0, 0.0))
            x = min(hx + JITTER_UNITS * jx, -1.0) * unit
            y = (hy + JITTER_UNITS * jy) * unit
            if team == kicker_team and number == KICKER[n]:
                x, y = -(facts.touch_distance_m + 0.3 * unit), 0.0
            elif math.hypot(x, y) < circle:
                scale = circle / max(math.hypot(x, y), 1e-9)
                x, y = x * scale, y * scale
            heading = 0.0 if team == LEFT else math.pi
            spots[ref] = (sign * x, sign * y, heading)
    return spots
