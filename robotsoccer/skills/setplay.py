"""The set play's shared skills and signals (paper §7, Figure 15).

Every mind of the set play reads percepts only and acts with the field model's actions, so the
same code runs on the Soccer Server model and on the robots. (On a field whose players have no
aimable kick, the set-play drill's coach carries out the ``Kick`` a mind sends, as layers 1
and 2's drills launch the ball there: :mod:`robotsoccer.drills.setplay`.) The set play is
built of:

* what a player knows of the ball and of its own heading —
  :mod:`robotsoccer.skills.ball_sense` (:class:`~robotsoccer.skills.ball_sense.BallSense`,
  :class:`~robotsoccer.skills.ball_sense.Heading`,
  :class:`~robotsoccer.skills.ball_sense.CameraBall`);
* the ball's velocity as it reckons it, and the compensated kicks made with it —
  :mod:`robotsoccer.skills.ball_tracker`;
* the skills and signals below, shared by every role;
* the minds of the roles: the starter and the winger
  (:class:`~robotsoccer.skills.setplay_carrier.CarrierMind`), the receivers
  (:class:`~robotsoccer.skills.setplay_receiver.SetPlayReceiverMind`); the defenders are
  layer 1's interception minds (:mod:`robotsoccer.skills.intercept`), placed by the drill.

A player comes up to the ball slowly enough to stop beside it, and stands with a dash of no
power (:data:`STAND`): a robot would otherwise drive on into the ball.

Skills, each a small function of one percept (their turns toward a bearing are the motion
skill's turn then go, :func:`~robotsoccer.skills.motion.turn_then_go`):

* :func:`chase` — face the ball and run at it (the approach of a dribble);
* :func:`approach` — the same, slowing down near the ball so as not to run into it;
* :func:`dribble` — with the ball within reach, kick it a short way toward a direction; else
  chase it;
* :func:`shoot` — kick at full power toward the opponents' goal (the landmark ``"g r"`` for the
  left team); turn to look for it while it is out of view;
* :func:`kick_to` — kick toward a seen teammate at pass power;
* :func:`receive` — get to a ball passed to the player: layer 1's interception, then stand in
  its path and let it come (:func:`arrives`);
* :func:`reach_entry` — where a ball will come into reach within a few periods (a
  camera-guided receiver's first-time kick);
* :func:`shot_direction` — where in the goal mouth to shoot, away from the goalie;
* :func:`opponent_in_path` — Figure 15's "predetermined distance" test (also the team minds',
  :mod:`robotsoccer.skills.team`).

The signals are :data:`WINGER_CALL` (the winger calls from the first pass's announcement on)
and :data:`WINGER_CUE` (the first receiver's kick to the winger). Angles are radians, left
positive; distances metres.
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from dataclasses import dataclass

from field_models.protocol import Action, Dash, Kick, Mind, Percept, SeenPlayer, Turn, wrap_angle
from robotsoccer.skills.ball_sense import Vector
from robotsoccer.skills.ball_tracker import BallTracker
from robotsoccer.skills.motion import turn_then_go

WINGER_CUE = "wing"
"""What the first receiver says as it kicks to the winger (the winger and last receivers wake)."""
WINGER_CALL = "open"
"""What the winger says at each percept from the first pass's announcement until the cue: the
receiver holding the ball hears from which direction (the server's hear carries it, §2.6)."""
STAND: tuple[Action, ...] = (Dash(0.0),)
"""Stand still: a dash of no power (on the robots the host stops the wheels; a robot would
otherwise keep driving on its last dash for a while, and push the ball)."""
SEARCH_TURN_RAD = math.radians(60.0)
"""A player looking for the ball or the goal turns this far per decision."""
FACING_RAD = math.radians(10.0)
"""Within this of the heading, a player runs instead of turning."""
PATH_HALF_ANGLE_RAD = math.radians(30.0)
"""An opponent within this of the direction of play is "in the path" (Figure 15)."""
SLOW_ZONE_REACHES = 2.0
"""An approaching player slows down from this many kick reaches from the ball."""
STILL_SHARE = 0.05
"""A ball slower than this share of the pass speed counts as at rest (no stopping kick)."""
RECEIVE_PERIODS = 2.0
"""A receiver stops running when the ball will reach it within this many sensor periods."""
SHOT_AIM_SHARE = 0.6
"""A shot aims this share of the goal's half width off its centre, away from the goalie."""


@dataclass(frozen=True)
class KickPowers:
    """Kick powers of one field (server units; a coach kick on a field without an aimable kick).

    Attributes:
        dribble: A short kick ahead, a few units.
        passing: A pass (layer 1's launch power on the field).
        shot: A shot on goal.
    """

    dribble: float
    passing: float
    shot: float


def goal_bearing(percept: Percept, attack_right: bool) -> tuple[float, float] | None:
    """(distance [m], angle [rad]) of the opponents' goal, or None while it is out of view."""
    mark = percept.landmark("g r" if attack_right else "g l")
    return None if mark is None else (mark.distance_m, mark.angle_rad)


def chase(percept: Percept, *, dash: float = 100.0) -> tuple[Action, ...]:
    """Face the ball and run at it; look for it when it is out of view."""
    ball = percept.ball
    if ball is None:
        return (Turn(SEARCH_TURN_RAD),)
    return turn_then_go(ball.angle_rad, (Dash(dash),), facing_rad=FACING_RAD, turn_only=True)


def approach(percept: Percept, reach_m: float, slow: float = 40.0) -> tuple[Action, ...]:
    """Chase the ball, slowing down within :data:`SLOW_ZONE_REACHES` reaches of it.

    A player that runs into a rolling ball knocks it away (the server's collisions, the robots'
    push), so it comes up to the ball gently, at dash power `slow` at the last, and stands
    where it can kick it.
    """
    ball = percept.ball
    if ball is None or ball.distance_m > SLOW_ZONE_REACHES * reach_m:
        return chase(percept)
    if ball.distance_m <= reach_m:
        return STAND
    gap = (ball.distance_m - reach_m) / ((SLOW_ZONE_REACHES - 1.0) * reach_m)
    return chase(percept, dash=max(slow, 100.0 * min(1.0, gap)))


def dribble(
    percept: Percept, direction_rad: float, reach_m: float, power: float
) -> tuple[Action, ...]:
    """Kick the ball a short way toward `direction_rad` (relative) when in reach, else chase it."""
    ball = percept.ball
    if ball is not None and ball.distance_m <= reach_m:
        return (Kick(power, wrap_angle(direction_rad)),)
    return chase(percept)


def shoot(percept: Percept, attack_right: bool, reach_m: float, power: float) -> tuple[Action, ...]:
    """A shot at the goal when the ball is in reach and the goal in view.

    Out of reach it chases the ball; with the goal out of view it turns to look for it.
    """
    ball = percept.ball
    if ball is None or ball.distance_m > reach_m:
        return chase(percept)
    goal = goal_bearing(percept, attack_right)
    if goal is None:
        return (Turn(SEARCH_TURN_RAD),)
    return (Kick(power, goal[1]),)


def shot_direction(percept: Percept, goal: tuple[float, float], half_width_m: float) -> float:
    """Where to shoot: inside the goal mouth, on the side away from the opponent nearest it.

    The goal is seen as (distance, angle) of its centre; the aim is :data:`SHOT_AIM_SHARE` of
    the half width from the centre, taken as across the line of sight (the goalie stands on
    the centre line, and a shot at it is a shot at the goalie). 0 half width: the centre.
    """
    distance, angle = goal
    if half_width_m <= 0.0 or distance <= 0.0:
        return angle
    offset = math.atan2(SHOT_AIM_SHARE * half_width_m, distance)
    own = percept.player.team
    keeper = min(
        (s for s in percept.players if s.team not in (own, None)),
        key=lambda s: abs(wrap_angle(s.angle_rad - angle)) + abs(s.distance_m - distance),
        default=None,
    )
    if keeper is None:
        return angle
    side = -1.0 if wrap_angle(keeper.angle_rad - angle) > 0.0 else 1.0
    return wrap_angle(angle + side * offset)


def kick_to(percept: Percept, number: int, power: float) -> tuple[Action, ...]:
    """Kick toward the teammate `number` when it is in view; else turn to look for it."""
    mate = find_teammate(percept, number)
    if mate is None:
        return (Turn(SEARCH_TURN_RAD),)
    return (Kick(power, mate.angle_rad),)


def find_teammate(percept: Percept, number: int) -> SeenPlayer | None:
    """The teammate with uniform `number` in view (its number seen), or None."""
    own = percept.player.team
    for seen in percept.players:
        if seen.team == own and seen.number == number:
            return seen
    return None


def opponent_in_path(percept: Percept, direction_rad: float, within_m: float) -> bool:
    """Whether an opponent is seen within `within_m` and near the direction of play."""
    own = percept.player.team
    for seen in percept.players:
        if seen.team in (own, None) or seen.distance_m > within_m:
            continue
        if abs(wrap_angle(seen.angle_rad - direction_rad)) <= PATH_HALF_ANGLE_RAD:
            return True
    return False


def heard_text(percept: Percept, text: str) -> bool:
    """Whether `text` was heard since the previous percept."""
    return any(h.text == text for h in percept.heard)


def face_ball(percept: Percept, within_rad: float = FACING_RAD) -> tuple[Action, ...]:
    """Turn to the ball if it is more than `within_rad` off the heading; else stand.

    A player looking with its neck waits with a wider `within_rad`: the head keeps the ball.
    """
    ball = percept.ball
    if ball is None:
        return STAND
    return turn_then_go(ball.angle_rad, STAND, facing_rad=within_rad, turn_only=True)


def heard_tick(percept: Percept, texts: Iterable[str]) -> int:
    """The tick a message in `texts` was said (its hear tick), else the percept's tick - 1."""
    wanted = set(texts)
    for heard in percept.heard:
        if heard.text in wanted and heard.tick:
            return heard.tick
    return percept.tick - 1


def receive(
    percept: Percept, raw: Percept, tracker: BallTracker, interceptor: Mind
) -> tuple[Action, ...]:
    """Get to a ball passed to this player: layer 1's interception, then let it come.

    * The ball out of view (it ran past): turn to look for it.
    * The ball behind (it got past): go after it (:func:`approach`).
    * The ball will pass within reach before the next percept but one (:func:`arrives`):
      face it and stand. Running on at it would double the closing speed and halve the time
      it is in reach, and the player acts on discrete percepts.
    * Otherwise layer 1's interception (§5) takes the player into the ball's path; it gets
      the percept as it came (`raw`), `percept` being the player's reckoned view of it.
    """
    ball = percept.ball
    if ball is None:
        return (Turn(SEARCH_TURN_RAD),)
    if abs(ball.angle_rad) > 0.5 * math.pi:
        return approach(percept, tracker.sense.reach_m, tracker.sense.approach_power)
    if arrives(percept, tracker):
        return face_ball(percept)
    return interceptor.act(raw)


def reach_entry(percept: Percept, tracker: BallTracker, periods: float) -> Vector | None:
    """Where the ball comes into reach [m, body frame], if it does within `periods`; else None.

    The ball's motion is the tracker's, relative to the moving player; the time is its entry
    into the kick reach (its first crossing of the reach circle), not its closest approach: a
    kick armed now must find it within the reach before the next decision. A ball in reach
    now is where it is.
    """
    ball = percept.ball
    if ball is None or not tracker.known:
        return None
    rx = ball.distance_m * math.cos(ball.angle_rad)
    ry = ball.distance_m * math.sin(ball.angle_rad)
    reach = tracker.sense.reach_m
    if ball.distance_m <= reach:
        return rx, ry
    vx, vy = tracker.closing_velocity(percept)
    speed2 = vx * vx + vy * vy
    if speed2 <= 0.0:
        return None
    along = rx * vx + ry * vy
    disc = along * along - speed2 * (ball.distance_m**2 - reach * reach)
    if along >= 0.0 or disc < 0.0:
        return None  # moving away, or passing wide of the reach
    entry_s = (-along - math.sqrt(disc)) / speed2
    if entry_s > periods * tracker.sense.sensor_period_s:
        return None
    return rx + vx * entry_s, ry + vy * entry_s


def arrives(percept: Percept, tracker: BallTracker, periods: float = RECEIVE_PERIODS) -> bool:
    """Whether the ball, as the tracker reckons its motion, will pass within reach soon.

    Soon: within `periods` sensor periods (:data:`RECEIVE_PERIODS` by default).
    """
    ball = percept.ball
    if ball is None or not tracker.known:
        return False
    vx, vy = tracker.closing_velocity(percept)
    speed2 = vx * vx + vy * vy
    if speed2 <= 0.0:
        return False
    rx = ball.distance_m * math.cos(ball.angle_rad)
    ry = ball.distance_m * math.sin(ball.angle_rad)
    t = -(rx * vx + ry * vy) / speed2  # time of the closest approach [s]
    if t < 0.0:
        return False
    miss = abs(rx * vy - ry * vx) / math.sqrt(speed2)
    sense = tracker.sense
    return miss <= sense.reach_m and t <= periods * sense.sensor_period_s
