"""Skills built on the two learned layers, and the minds of the set play (paper §7, Figure 15).

Every mind reads percepts only and acts with the field model's actions, so the same code runs on
the Soccer Server model and on the robots. (On a field whose players have no aimable kick, the
set-play drill's coach carries out the ``Kick`` a mind sends, as layers 1 and 2's drills
launch the ball there: :mod:`robotsoccer.drills.setplay`.)

**Ball sense.** A kick *adds* to the ball's velocity (the Soccer Server's kick, §2.3 of
``specs/soccer_server.md``), so a player that kicks a rolling ball where it wants it must know
how the ball is rolling. The 1996 server reports no distance or direction changes, so each
player keeps a :class:`BallTracker`: a dead-reckoned estimate of the ball's velocity in its
own body frame, from what it knows happened to the ball — at rest at the start of the play;
a teammate's pass announced toward it (the ball then runs along the line from where it sees
it, at the field's pass speed, slowing by the field's ball law); its own kicks; its own turns
(which rotate its frame); the ball arriving at its body (stopped). Every kick the minds make
is then *compensated*: the kick that turns the estimated velocity into the wanted one
(:meth:`BallTracker.kick_to`), within the kick's top power. A kick whose path would run back
through the kicker's own body (a ball stopped in front, a target behind) is preceded by a tap
that moves the ball aside (:meth:`BallTracker.aim`): the server would bounce it off the body.

**Percepts that lag** (the robots' camera, §2: 50 ms). Each mind views its percept through a
:class:`Heading` (the turns it commanded that the percept cannot show yet; a ball the camera
missed for a frame or two is recalled where it was) and its tracker (the ball moved on by its
estimated velocity over the latency, :meth:`BallTracker.project`), and does not kick again
until a percept shows its last kick (:meth:`BallTracker.fresh`). It comes up to the ball
slowly enough to stop beside it, and stands with a dash of no power (:data:`STAND`): a robot
would otherwise drive on into the ball. On the Soccer Server (no latency) these change nothing.

**A camera** (the robots: a pose from the goals in every percept, :attr:`BallSense.track_window`
> 0). A receiver then keeps the ball's velocity in the field frame, fitted to the camera's
sightings once a full window of them follows the last kick (:class:`CameraBall`; dead
reckoning from the announced pass until then), and reckons its own heading now from the
camera's last two poses rather than from the turns it commanded (a robot carries a turn out
only in part before its next command). It meets the pass with layer 1, stands still for the
last :data:`SET_PERIODS` periods (so that the heading its kick is aimed by is known), and sends
its kick on first time as soon as the ball will come into reach within a period
(:func:`reach_entry`): the drill's coach fires it when the ball gets there. A first-time kick
whose path would run back into the body is bent round it (:meth:`BallTracker.aim`). It checks
afterwards that the ball went, and meets it again if not. Carriers dribble by dead reckoning
(their own kicks), as on the server; a winger uses the camera while it collects.

Skills, each a small function of one percept:

* :func:`chase` — face the ball and run at it (the approach of a dribble);
* :func:`approach` — the same, slowing down near the ball so as not to run into it;
* :func:`dribble` — with the ball within reach, kick it a short way toward a direction; else
  chase it;
* :func:`shoot` — kick at full power toward the opponents' goal (the landmark ``"g r"`` for the
  left team); turn to look for it while it is out of view;
* :func:`kick_to` — kick toward a seen teammate at pass power;
* :func:`receive` — get to a ball passed to the player: layer 1's interception, then stand in
  its path and let it come (:func:`arrives`);
* :func:`shot_direction` — where in the goal mouth to shoot, away from the goalie.

Minds of the play (the drill :mod:`robotsoccer.drills.setplay` places them):

* :class:`CarrierMind` — the player that starts with the ball, and the winger. It dribbles
  toward the goal until it sees an opponent within :attr:`CarrierMind.blocked_distance_m` in
  its path (Figure 15's "predetermined distance"). Then, as §7 says, it *stops dribbling and
  considers its options*: it stops the ball (a kick against its motion), turns until it sees
  both its receivers (they may be outside its 90° view cone, §4), and only then hands over to
  layer 2's :class:`~robotsoccer.skills.passing.PasserMind` (intention, the two nearest
  teammates' reports, the tree's choice, the announcement); standing by a ball at rest, it
  cannot lose it while they talk (if it rolls off all the same, it follows and stops it
  again). It kicks the pass itself, compensated. The winger first
  waits, calling :data:`WINGER_CALL` from the first pass's announcement on, and collects the
  pass with layer 1's interception once it hears the cue :data:`WINGER_CUE`.
* :class:`SetPlayReceiverMind` — layer 2's :class:`~robotsoccer.skills.passing.ReceiverMind`
  (face the ball, report, intercept with layer 1 once chosen); once the ball is in reach it
  kicks on at once, as the paper's receiver does: a first receiver to the winger (saying the
  cue), toward the winger as seen or else as last heard calling; a last receiver at the goal,
  as seen or else where it saw the goal before the play reached it (it looks for the goal
  while it waits, then turns with the ball to see it before shooting), on the side of the
  goal mouth away from the goalie (:func:`shot_direction`). The last receivers
  listen only from the winger's call (or cue) on, so the first pass's conversation is not
  theirs.

Headings are reckoned from the player's own turns (as the interception defender does,
:mod:`robotsoccer.skills.intercept`); angles are radians, left positive; distances metres.
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from dataclasses import dataclass, replace

from field_models.arena import BallLaw
from field_models.protocol import (
    Action,
    Dash,
    Kick,
    Mind,
    Percept,
    Say,
    SeenBall,
    SeenPlayer,
    Turn,
    wrap_angle,
)
from robotsoccer.skills.lead import BallTrack
from robotsoccer.skills.localise import Localiser
from robotsoccer.skills.passing import PasserMind, ReceiverMind, announced_number

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
VIEW_HALF_ANGLE_RAD = math.radians(40.0)
"""A carrier turns so that its receivers lie within this of its heading: inside the Soccer
Server's 45° half view cone (§4), with a margin for their jitter and the quantised directions."""
LOOK_DECISIONS = 4
"""A carrier turns at most this many times looking for its receivers, then asks anyway."""
SLOW_ZONE_REACHES = 2.0
"""An approaching player slows down from this many kick reaches from the ball."""
STILL_SHARE = 0.05
"""A ball slower than this share of the pass speed counts as at rest (no stopping kick)."""
RECEIVE_PERIODS = 2.0
"""A receiver stops running when the ball will reach it within this many sensor periods."""
BLOCK_MARGIN_SHARE = 0.15
"""A ball seen within touching distance plus this share of the kick margin has met the body."""
CLEAR_MARGIN_SHARE = 0.3
"""A kick's path clears the body by touching distance plus this share of the kick margin."""
ONE_TOUCH_PERIODS = 1.0
"""A camera-guided receiver sends its kick on when the ball will come into reach within this
many sensor periods: the kick then stays armed until the next decision (drill module)."""
FIRST_TIME_BEND_RAD = math.radians(45.0)
"""A first-time kick on is bent by at most this to clear the kicker's body."""
SET_PERIODS = 3.0
"""A camera-guided receiver stops turning and stands when the ball will come into reach within
this many sensor periods: a turn shows in its percepts only after the camera's latency and the
turn's own time (:attr:`BallSense.turn_settle_ticks`), and the kick on is aimed relative to a
heading it must know."""
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


class BallTracker:
    """The ball's velocity as one player reckons it, in its body frame (module docstring).

    Args:
        sense: The field's ball and kick.

    Attributes:
        known: Whether the estimate stands on something (else it is taken as at rest).
    """

    def __init__(self, sense: BallSense) -> None:
        self.sense = sense
        self.vx = 0.0
        self.vy = 0.0
        self.known = False
        self._tick: int | None = None
        self.kicked_tick = -1
        self.camera = CameraBall(sense) if sense.track_window > 0 else None
        self._fit: tuple[int, Vector] | None = None  # (tick, body-frame velocity) of the camera
        self._frame: float | None = None  # the body frame's heading in the field [rad]
        self._world: tuple[Vector, int] | None = None  # (field-frame velocity, its tick)

    def observe(self, raw: Percept) -> tuple[float, float] | None:
        """Take the camera's view of the ball and of the player's own heading (robots).

        `raw` is the percept as it came. Returns (the heading now in the field frame, the turn
        since the sample) [rad] for :meth:`Heading.view`, or None without a camera pose. With
        the pose the estimate is kept in the field frame between percepts and turned into
        the body frame of the heading now (:meth:`CameraBall.update`), rather than rotated by
        each turn commanded: a robot's turn is not carried out whole before the next command. The
        velocity fitted to the sightings replaces the dead reckoning once its window is full;
        a kick (the player's own, or a teammate's pass to it) restarts the fit from the first
        percept that can show it (:meth:`note`, :meth:`launched`).
        """
        camera = self.camera
        if camera is None:
            return None
        turn, fit = camera.update(raw)
        if turn is None:
            return None
        frame = camera.heading_now
        self._frame = frame
        if self._world is not None:
            (wx, wy), tick = self._world
            cos, sin = math.cos(-frame), math.sin(-frame)
            self.vx, self.vy = cos * wx - sin * wy, sin * wx + cos * wy
            self._tick = tick
        if fit is not None:
            self._fit = (raw.tick, fit)
            self.vx, self.vy = fit
            self.known, self._tick = True, raw.tick
        return frame, turn

    def fresh(self, percept: Percept) -> bool:
        """Whether `percept` was sampled after the player's last kick showed (its settle time).

        On a field with sensor latency (the robots' camera) a percept may show the ball as it
        lay before the kick: the player neither kicks again on it nor takes the ball for
        stopped at its body.
        """
        return percept.observed_tick >= self.kicked_tick + self.sense.turn_settle_ticks

    def project(self, percept: Percept) -> Percept:
        """`percept` with its ball moved on to where it is now, by the estimated velocity.

        A percept reaches the player its sensor latency after it was sampled (the robots'
        camera: 50 ms, in which a pass runs 2 units); the player's own motion in that time is
        not reckoned.
        """
        ball = percept.ball
        lag = (percept.tick - percept.observed_tick) * self.sense.law.dt_s
        if ball is None or lag <= 0.0 or not self.known:
            return percept
        self._advance(percept.tick)
        ox, oy = (0.0, 0.0) if self.camera is None else self.camera.own_velocity
        x = ball.distance_m * math.cos(ball.angle_rad) + (self.vx - ox) * lag
        y = ball.distance_m * math.sin(ball.angle_rad) + (self.vy - oy) * lag
        return replace(percept, ball=SeenBall(math.hypot(x, y), math.atan2(y, x)))

    def rest(self, tick: int) -> None:
        """The ball is at rest at `tick` (the start of a set play)."""
        self.vx = self.vy = 0.0
        self.known, self._tick = True, tick

    def launched(self, percept: Percept, speed_mps: float, kick_tick: int) -> None:
        """A teammate kicked the ball toward this player at `kick_tick` with `speed_mps`.

        The ball runs from where the player sees it toward the player (the passer aimed at it).
        """
        ball = percept.ball
        if ball is None:
            return
        heading = ball.angle_rad + math.pi
        self.vx, self.vy = speed_mps * math.cos(heading), speed_mps * math.sin(heading)
        self.known, self._tick = True, kick_tick
        self._fit = None
        if self.camera is not None:  # sightings from before the pass would bend the fit
            self.camera.restart(kick_tick + self.sense.turn_settle_ticks)
        self._advance(percept.tick)

    def detach(self) -> None:
        """Reckon the ball from here on without the camera (dead reckoning, as on the server).

        A carrier dribbles by its own kicks, which it knows better than a fit that lags them.
        """
        self.camera = None
        self._fit = self._world = self._frame = None

    def closing_velocity(self, percept: Percept) -> Vector:
        """The ball's velocity relative to the moving player [m/s, body frame].

        The camera gives the player's own motion (:attr:`CameraBall.own_velocity`); without
        it the player is taken as still.
        """
        vx, vy = self.velocity(percept)
        if self.camera is None:
            return vx, vy
        ox, oy = self.camera.own_velocity
        return vx - ox, vy - oy

    def fitted(self, percept: Percept) -> Vector | None:
        """The camera's velocity fit for this percept [m/s, body frame], or None (not ready)."""
        fit = self._fit
        return fit[1] if fit is not None and fit[0] == percept.tick else None

    def velocity(self, percept: Percept) -> Vector:
        """The estimate at this percept [m/s, body frame]; a ball at the body has stopped.

        Where the camera's fit is ready for this percept (:meth:`observe`), it is the estimate:
        it sees a ball that bounced off a body or was pushed, which dead reckoning cannot.
        """
        self._advance(percept.tick)
        fit = self._fit
        if fit is not None and fit[0] == percept.tick:
            self.vx, self.vy = fit[1]
            return self.vx, self.vy
        ball = percept.ball
        if ball is not None and self._at_body(ball.distance_m) and self.fresh(percept):
            self.vx = self.vy = 0.0  # it met the body (a block, or the player ran into it)
        return self.vx, self.vy

    def note(self, actions: Iterable[Action], tick: int) -> None:
        """Account for the actions the player sends at `tick`: kicks add, turns rotate."""
        for action in actions:
            if isinstance(action, Kick):
                self.kicked_tick = tick
                self._fit = None
                if self.camera is not None:  # the kick may fire up to a period later
                    self.camera.restart(tick + self.sense.turn_settle_ticks)
                speed = self.sense.speed(action.power)
                self.vx += speed * math.cos(action.direction_rad)
                self.vy += speed * math.sin(action.direction_rad)
            elif isinstance(action, Turn) and self._frame is None:
                cos, sin = math.cos(-action.angle_rad), math.sin(-action.angle_rad)
                self.vx, self.vy = cos * self.vx - sin * self.vy, sin * self.vx + cos * self.vy
        frame = self._frame
        if frame is not None and self._tick is not None:  # kept in the field frame (observe)
            cos, sin = math.cos(frame), math.sin(frame)
            self._world = (
                (cos * self.vx - sin * self.vy, sin * self.vx + cos * self.vy),
                self._tick,
            )

    def aim(
        self,
        percept: Percept,
        speed_mps: float,
        direction_rad: float,
        *,
        first_time: Vector | None = None,
    ) -> tuple[Kick | None, bool]:
        """The kick toward `direction_rad` at `speed_mps`, and whether it is that kick.

        A ball kicked from where it lies would run through the player's own body when the
        direction points back past it (the server then bounces it off the body, §4). The
        player then first taps the ball aside, out of that path, and kicks at its next
        percept: (tap, False). A `first_time` kick (a camera-guided receiver's, armed as the
        ball comes: no time for a tap; the body-frame point where it will meet the ball) is
        instead bent by the least angle that clears the body from there
        (:data:`FIRST_TIME_BEND_RAD` at most; beyond, the tap as before): the next player
        collects it with layer 1.
        """
        if not self.fresh(percept):
            return None, False  # the last kick does not show yet: wait for a percept that does
        ball = percept.ball
        if ball is not None:
            side = self._blocking_side(ball.distance_m, ball.angle_rad, direction_rad)
            if first_time is not None:
                at = (math.hypot(*first_time), math.atan2(first_time[1], first_time[0]))
                side = self._blocking_side(*at, direction_rad)
                bent = direction_rad if side is None else self._bend(*at, direction_rad, side)
                if bent is not None:
                    return self.kick_to(percept, speed_mps, bent), True
            if side is not None:
                return self._tap(percept, side, direction_rad), False
        return self.kick_to(percept, speed_mps, direction_rad), True

    def _bend(
        self, distance_m: float, angle_rad: float, direction_rad: float, lateral: float
    ) -> float | None:
        """The direction nearest `direction_rad` whose path clears the body, or None.

        It searches both ways in steps of a degree, the way that makes the ball's offset from
        the path (`lateral`, positive with the ball to the path's left) grow first: that side
        clears soonest as long as the ball lies within a right angle of the path's reverse.
        """
        sign = 1.0 if lateral >= 0.0 else -1.0
        step = math.radians(1.0)
        for k in range(1, round(FIRST_TIME_BEND_RAD / step) + 1):
            for turn in (sign, -sign):
                bent = wrap_angle(direction_rad + turn * k * step)
                if self._blocking_side(distance_m, angle_rad, bent) is None:
                    return bent
        return None

    def _blocking_side(
        self, distance_m: float, angle_rad: float, direction_rad: float
    ) -> float | None:
        """The ball's lateral offset from a path through the body [m], or None if it is clear."""
        bx, by = distance_m * math.cos(angle_rad), distance_m * math.sin(angle_rad)
        ux, uy = math.cos(direction_rad), math.sin(direction_rad)
        if bx * ux + by * uy >= 0.0:
            return None  # it runs away from the body
        lateral = -bx * uy + by * ux
        return lateral if abs(lateral) < self._clearance() else None

    def _clearance(self) -> float:
        sense = self.sense
        return sense.touch_m + CLEAR_MARGIN_SHARE * (sense.reach_m - sense.touch_m)

    def _tap(self, percept: Percept, lateral: float, direction_rad: float) -> Kick | None:
        """Move the ball aside, clear of the path through the body, by the next percept."""
        sign = 1.0 if lateral >= 0.0 else -1.0
        shift = 1.5 * self._clearance() - abs(lateral)
        speed = shift / self.sense.sensor_period_s
        nx, ny = -math.sin(direction_rad) * sign, math.cos(direction_rad) * sign
        return self.kick_velocity(percept, speed * nx, speed * ny)

    def kick_velocity(self, percept: Percept, wx: float, wy: float) -> Kick | None:
        """The kick that gives the ball the velocity (wx, wy) [m/s, body frame], within power."""
        speed = math.hypot(wx, wy)
        if speed <= 0.0:
            return self.stop(percept, 0.0)
        return self.kick_to(percept, speed, math.atan2(wy, wx))

    def kick_to(self, percept: Percept, speed_mps: float, direction_rad: float) -> Kick | None:
        """The kick that sends the ball at `speed_mps` toward `direction_rad` (relative).

        Where that needs more than the top power, the fastest ball along the direction that
        the top power can give; where no kick can send it that way, the kick that stops it.
        None: nothing to kick (the ball already moves so).
        """
        vx, vy = self.velocity(percept)
        ux, uy = math.cos(direction_rad), math.sin(direction_rad)
        dx, dy = speed_mps * ux - vx, speed_mps * uy - vy
        top = self.sense.speed(self.sense.max_power)
        if math.hypot(dx, dy) > top:
            along = vx * ux + vy * uy
            disc = along * along - (vx * vx + vy * vy) + top * top
            if disc < 0.0 or along + math.sqrt(disc) <= 0.0:
                return self._stop_kick(vx, vy)
            reach = along + math.sqrt(disc)
            dx, dy = reach * ux - vx, reach * uy - vy
        return self._kick(dx, dy)

    def stop(self, percept: Percept, still_mps: float) -> Kick | None:
        """The kick against the ball's motion that stops it; None when it is slower than still."""
        vx, vy = self.velocity(percept)
        if math.hypot(vx, vy) <= still_mps or not self.fresh(percept):
            return None
        return self._stop_kick(vx, vy)

    def _stop_kick(self, vx: float, vy: float) -> Kick | None:
        top = self.sense.speed(self.sense.max_power)
        speed = math.hypot(vx, vy)
        scale = min(1.0, top / speed) if speed > 0.0 else 0.0
        return self._kick(-vx * scale, -vy * scale)

    def _kick(self, dx: float, dy: float) -> Kick | None:
        speed = math.hypot(dx, dy)
        if speed <= 0.0:
            return None
        power = min(self.sense.max_power, speed / self.sense.speed_per_power_mps)
        return Kick(power, math.atan2(dy, dx))

    def _at_body(self, distance_m: float) -> bool:
        sense = self.sense
        return distance_m <= sense.touch_m + BLOCK_MARGIN_SHARE * (sense.reach_m - sense.touch_m)

    def _advance(self, tick: int) -> None:
        """Slow the estimate down by the field's ball law from its tick to `tick`."""
        if self._tick is None or tick <= self._tick:
            self._tick = tick if self._tick is None else self._tick
            return
        law, elapsed = self.sense.law, (tick - self._tick) * self.sense.law.dt_s
        self._tick = tick
        speed = math.hypot(self.vx, self.vy)
        if speed <= 0.0:
            return
        if law.kind == "constant":
            factor = max(0.0, speed - law.decel_mps2 * elapsed) / speed
        else:
            factor = law.decay_per_tick ** (elapsed / law.dt_s)
        self.vx *= factor
        self.vy *= factor


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
    reckons it faces, as the interception defender does (:mod:`robotsoccer.skills.intercept`):
    a turn counts from the first percept observed after the tick it was commanded on.
    """

    def __init__(self, settle_ticks: int = 1, recall_ticks: int = 0) -> None:
        self.settle_ticks = settle_ticks
        self.recall_ticks = recall_ticks
        self.rad = 0.0
        self.unseen_rad = 0.0
        """The turns commanded that the last percept viewed does not show yet [rad]."""
        self.bearings: dict[str, float] = {}
        self._turns: list[tuple[int, float]] = []  # (tick commanded, angle), maybe not seen yet
        self._ball: tuple[int, float, float] | None = None  # (tick, distance, bearing)

    def note(self, actions: Iterable[Action], tick: int) -> None:
        """Add the turns the player sends at `tick`."""
        for action in actions:
            if isinstance(action, Turn):
                self.rad = wrap_angle(self.rad + action.angle_rad)
                self._turns.append((tick, action.angle_rad))

    def view(self, percept: Percept, camera: tuple[float, float] | None = None) -> Percept:
        """`percept` in the frame of the turns commanded so far, its ball recalled if missed.

        A turn shows in percepts observed :attr:`settle_ticks` after it was commanded. A ball
        the sensor missed but that was seen within :attr:`recall_ticks` is put back where it
        was last seen (a missed camera detection is not a ball gone out of sight).

        `camera`: (the heading now in the field frame, the turn since the sample) [rad], from
        the camera's poses (:meth:`CameraBall.update`): they replace the reckoning from the
        turns commanded, which a robot carries out only in part before its next command.
        """
        turns = self._turns
        while turns and turns[0][0] + self.settle_ticks <= percept.observed_tick:
            turns.pop(0)
        unseen = sum(angle for _, angle in turns)
        if camera is not None:
            self.rad, unseen = wrap_angle(camera[0]), camera[1]
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


def goal_bearing(percept: Percept, attack_right: bool) -> tuple[float, float] | None:
    """(distance [m], angle [rad]) of the opponents' goal, or None while it is out of view."""
    mark = percept.landmark("g r" if attack_right else "g l")
    return None if mark is None else (mark.distance_m, mark.angle_rad)


def chase(percept: Percept, *, dash: float = 100.0) -> tuple[Action, ...]:
    """Face the ball and run at it; look for it when it is out of view."""
    ball = percept.ball
    if ball is None:
        return (Turn(SEARCH_TURN_RAD),)
    if abs(ball.angle_rad) > FACING_RAD:
        return (Turn(ball.angle_rad),)
    return (Dash(dash),)


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


def _face_ball(percept: Percept) -> tuple[Action, ...]:
    """Turn to the ball if it is off the heading; else stand."""
    ball = percept.ball
    if ball is not None and abs(ball.angle_rad) > FACING_RAD:
        return (Turn(ball.angle_rad),)
    return STAND


def _heard_tick(percept: Percept, texts: Iterable[str]) -> int:
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
        return _face_ball(percept)
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


class CarrierMind:
    """Dribble toward the goal, stop the ball, look, then pass by the tree (module docstring).

    Args:
        passer: Layer 2's passer, to hand over to (its receivers are the two nearest). It is
            built without a kick power: this mind kicks the pass itself.
        interceptor: Layer 1's interception, for a winger collecting the ball; None: the
            player starts with the ball (at rest).
        sense: The field's ball and kick.
        attack_right: It attacks the goal at +x (``"g r"``).
        blocked_distance_m: An opponent this close in the path ends the dribble [m].
        powers: The field's kick powers.
        calls_after: The receivers of the pass before this player's (a winger calls from their
            announcement on); empty: it never calls.

    Attributes:
        phase: ``"wait"``, ``"collect"``, ``"dribble"``, ``"look"``, ``"pass"``, ``"deliver"``
            or ``"done"``.
        passed_tick: The tick of its pass kick, or None.
    """

    def __init__(
        self,
        passer: PasserMind,
        interceptor: Mind | None,
        *,
        sense: BallSense,
        attack_right: bool,
        blocked_distance_m: float,
        powers: KickPowers,
        calls_after: tuple[int, ...] = (),
    ) -> None:
        self.passer = passer
        self.interceptor = interceptor
        self.sense = sense
        self.reach_m = sense.reach_m
        self.attack_right = attack_right
        self.blocked_distance_m = blocked_distance_m
        self.powers = powers
        self.calls_after = calls_after
        self.phase = "dribble" if interceptor is None else "wait"
        self.passed_tick: int | None = None
        self.tracker = BallTracker(sense)
        if interceptor is None:
            self.tracker.detach()  # it starts with the ball: it dribbles
        self.heading = sense.heading()
        self._raw: Percept | None = None
        self.calling = False
        self.looks = 0
        self.done = False

    @property
    def raw(self) -> Percept:
        """The percept of the decision under way, as it came (for layer 1 and layer 2's minds)."""
        assert self._raw is not None, "act() first"
        return self._raw

    @property
    def pass_speed_mps(self) -> float:
        """The ball's speed as a pass leaves [m/s]."""
        return self.sense.speed(self.powers.passing)

    def act(self, percept: Percept) -> tuple[Action, ...]:
        """One decision (module docstring).

        Layer 1 and layer 2's minds get the percept as it came; this mind's own skills see it
        in its reckoned frame (:meth:`Heading.view`).
        """
        if not self.tracker.known and self.interceptor is None:
            self.tracker.rest(percept.tick)  # a set play starts with the ball at rest
        self._raw = percept
        view = self.heading.view(percept, self.tracker.observe(percept))
        view = self.tracker.project(view)
        self._see(view)
        actions = self._decide(view)
        self.tracker.note(actions, percept.tick)
        self.heading.note(actions, percept.tick)
        return actions

    def _see(self, percept: Percept) -> None:
        """Remember where the receivers and the goal were seen."""
        own = percept.player.team
        for seen in percept.players:
            if seen.team == own and seen.number in self.passer.receivers:
                self.heading.remember(f"mate{seen.number}", seen.angle_rad)

    def _decide(self, percept: Percept) -> tuple[Action, ...]:
        if self.phase == "wait":
            return self._wait(percept)
        if self.phase == "collect":
            if not self._in_reach(percept):
                assert self.interceptor is not None
                return receive(percept, self.raw, self.tracker, self.interceptor)
            self.phase = "dribble"
            self.tracker.detach()
        if self.phase == "dribble":
            return self._dribble(percept)
        if self.phase == "look":
            return self._look(percept)
        if self.phase == "pass":
            return self._pass(percept)
        if self.phase == "deliver":
            return self._deliver(percept)
        return ()

    def _wait(self, percept: Percept) -> tuple[Action, ...]:
        """A winger: face the ball, call from the first pass on, wake on the cue."""
        if heard_text(percept, WINGER_CUE):
            kick_tick = _heard_tick(percept, (WINGER_CUE,))
            self.tracker.launched(percept, self.pass_speed_mps, kick_tick)
            self.phase = "collect"
            self.calling = False
            return self._decide(percept)
        for heard in percept.heard:
            if announced_number(heard.text) in self.calls_after:
                self.calling = True
        actions = _face_ball(percept)
        return (*actions, Say(WINGER_CALL)) if self.calling else actions

    def _in_reach(self, percept: Percept) -> bool:
        ball = percept.ball
        return ball is not None and ball.distance_m <= self.reach_m

    def _dribble(self, percept: Percept) -> tuple[Action, ...]:
        goal = goal_bearing(percept, self.attack_right)
        if not self._in_reach(percept):
            return approach(percept, self.reach_m, self.sense.approach_power)
        if goal is None:
            return self._hold(percept, (Turn(SEARCH_TURN_RAD),))  # look for the goal
        direction = goal[1]
        if opponent_in_path(percept, direction, self.blocked_distance_m):
            self.phase = "look"  # §7: it stops dribbling and considers its options
            return self._hold(percept, ())
        kick, _ = self.tracker.aim(percept, self.sense.speed(self.powers.dribble), direction)
        return self._follow(percept) if kick is None else (kick,)

    def _follow(self, percept: Percept) -> tuple[Action, ...]:
        """The ball rolls as wanted: keep up with it at its pace."""
        vx, vy = self.tracker.velocity(percept)
        power = 100.0 * min(1.0, math.hypot(vx, vy) / self.sense.top_speed_mps)
        return chase(percept, dash=power)

    def _hold(self, percept: Percept, then: tuple[Action, ...]) -> tuple[Action, ...]:
        """Stand, stop the ball (a kick against its motion) if it rolls, then `then`."""
        kick = self.tracker.stop(percept, STILL_SHARE * self.pass_speed_mps)
        then = then or STAND
        return then if kick is None else (kick, *then)

    def _look(self, percept: Percept) -> tuple[Action, ...]:
        """Turn until both receivers are in view (or give up looking), then ask."""
        if not self._in_reach(percept):
            return approach(percept, self.reach_m, self.sense.approach_power)
        turn = self._turn_to_receivers(percept)
        if turn is None or self.looks >= LOOK_DECISIONS:
            self.phase = "pass"
            return self._pass(percept)
        self.looks += 1
        return self._hold(percept, (Turn(turn),))

    def _turn_to_receivers(self, percept: Percept) -> float | None:
        """The turn that brings every receiver into view; None when they are in view now."""
        bearings = [self.heading.relative(f"mate{n}") for n in self.passer.receivers]
        seen = {s.number for s in percept.players if s.team == percept.player.team}
        if all(n in seen for n in self.passer.receivers) and all(
            b is not None and abs(b) <= VIEW_HALF_ANGLE_RAD for b in bearings
        ):
            return None
        known = [b for b in bearings if b is not None]
        if len(known) < len(bearings):
            return SEARCH_TURN_RAD if not known else known[0]
        mid = math.atan2(sum(math.sin(b) for b in known), sum(math.cos(b) for b in known))
        return None if abs(mid) < math.radians(2.0) else mid

    def _pass(self, percept: Percept) -> tuple[Action, ...]:
        """Layer 2's exchange beside the ball; then the pass, kicked here (compensated)."""
        actions = self.passer.act(self.raw)
        if self.passer.chosen is None:
            if not self._in_reach(percept):
                return actions + approach(percept, self.reach_m, self.sense.approach_power)
            return actions + self._hold(percept, ())
        self.phase = "deliver"
        direction = self.passer.pass_direction_rad or 0.0
        self.heading.remember("target", direction)
        return actions + self._deliver(percept)

    def _deliver(self, percept: Percept) -> tuple[Action, ...]:
        """Kick the pass once the ball is in reach, toward the receiver as seen or remembered."""
        chosen = self.passer.chosen
        if not self._in_reach(percept) or chosen is None:
            return approach(percept, self.reach_m, self.sense.approach_power)
        target = find_teammate(percept, chosen)
        direction = target.angle_rad if target is not None else self.heading.relative("target")
        kick, passed = self.tracker.aim(percept, self.pass_speed_mps, direction or 0.0)
        if passed:
            self.passed_tick = percept.tick
            self.phase = "done"
            self.done = True
        return () if kick is None else (kick,)


class SetPlayReceiverMind:
    """A receiver of the set play (module docstring).

    Args:
        receiver: Layer 2's receiver (reports; intercepts with layer 1's net once chosen).
        next_teammate: The winger's number (the first receivers kick to it); None: shoot.
        sense: The field's ball and kick.
        attack_right: It attacks the goal at +x.
        powers: The field's kick powers.
        armed: It listens from the start (the first receivers); False: from the winger's call
            or cue on, looking for the goal meanwhile.
        goal_half_width_m: Half the goal's width [m] (a shot aims inside it, away from the
            goalie: :func:`shot_direction`); 0: at the centre.

    Attributes:
        kicked_tick: The tick of its kick on (to the winger, or the shot), or None.
    """

    def __init__(
        self,
        receiver: ReceiverMind,
        next_teammate: int | None,
        *,
        sense: BallSense,
        attack_right: bool,
        powers: KickPowers,
        armed: bool = True,
        goal_half_width_m: float = 0.0,
    ) -> None:
        self.receiver = receiver
        self.goal_half_width_m = goal_half_width_m
        self.next_teammate = next_teammate
        self.sense = sense
        self.reach_m = sense.reach_m
        self.attack_right = attack_right
        self.powers = powers
        self.armed = armed
        self.kicked_tick: int | None = None
        self.tracker = BallTracker(sense)
        self.heading = sense.heading()
        self._raw: Percept | None = None
        self.done = False

    @property
    def raw(self) -> Percept:
        """The percept of the decision under way, as it came (for layer 1 and layer 2's minds)."""
        assert self._raw is not None, "act() first"
        return self._raw

    @property
    def shoots(self) -> bool:
        """Whether it shoots (a last receiver) rather than kicking to the winger."""
        return self.next_teammate is None

    def act(self, percept: Percept) -> tuple[Action, ...]:
        """Report and intercept as layer 2's receiver; holding the ball, kick on.

        Layer 1 and layer 2's minds get the percept as it came; this mind's own skills see it
        in its reckoned frame (:meth:`Heading.view`).
        """
        self._raw = percept
        view = self.heading.view(percept, self.tracker.observe(percept))
        view = self.tracker.project(view)
        self._see(view)
        actions = self._decide(view)
        self.tracker.note(actions, percept.tick)
        self.heading.note(actions, percept.tick)
        return actions

    def _see(self, percept: Percept) -> None:
        goal = goal_bearing(percept, self.attack_right)
        if goal is not None:
            self.heading.remember("goal", goal[1])
        for heard in percept.heard:
            if heard.text == WINGER_CALL and heard.direction_rad is not None:
                self.heading.remember("call", heard.direction_rad)
        if self.next_teammate is not None:
            mate = find_teammate(percept, self.next_teammate)
            if mate is not None:
                self.heading.remember("call", mate.angle_rad)

    def _decide(self, percept: Percept) -> tuple[Action, ...]:
        if not self.armed:
            if not (heard_text(percept, WINGER_CUE) or heard_text(percept, WINGER_CALL)):
                return self._look_for_goal(percept)
            self.armed = True
        if self.receiver.chosen is not True:
            actions = self.receiver.act(self.raw)
            if self.receiver.chosen is True:
                self._pass_announced(percept)
            self.done = self.receiver.done
            return actions
        if self.kicked_tick is not None:
            after = self._after_kick(percept)
            if after != "again":
                self.done = after == "done"
                return STAND if after == "wait" else ()
            self.kicked_tick = None  # the ball never came into reach: meet it again
        ball = percept.ball
        if ball is not None and ball.distance_m <= self.reach_m:
            return self._kick_on(percept)
        if self.tracker.camera is not None:
            return self._meet(percept)
        return receive(percept, self.raw, self.tracker, self.receiver.interceptor)

    def _meet(self, percept: Percept) -> tuple[Action, ...]:
        """A camera-guided receiver meets the pass and kicks it on first time (robots).

        The camera shows the ball its latency late and a decision comes once a frame, so a
        receiver that waits to see the ball in reach sees it after it has hit its body and
        bounced off (the robot's restitution, ``robot.elasticity``): it sends its kick on as
        soon as the ball will come into reach within :data:`ONE_TOUCH_PERIODS` sensor periods
        (the kicker fires when the ball reaches it: :mod:`robotsoccer.drills.setplay`). A ball
        no longer coming at it (deflected, or stopped short) it comes up to gently
        (:func:`approach`), so as not to push it away; else layer 1 takes it into the path.
        """
        ball = percept.ball
        if ball is None:
            return receive(percept, self.raw, self.tracker, self.receiver.interceptor)
        entry = reach_entry(percept, self.tracker, ONE_TOUCH_PERIODS)
        if entry is not None:
            return self._kick_on(percept, entry)
        if arrives(percept, self.tracker, SET_PERIODS):
            return STAND  # no more turns: the kick's direction is reckoned from a still heading
        vx, vy = self.tracker.velocity(percept)
        closing = -(vx * math.cos(ball.angle_rad) + vy * math.sin(ball.angle_rad))
        if closing < STILL_SHARE * self.sense.speed(self.powers.passing):
            return approach(percept, self.reach_m, self.sense.approach_power)
        return receive(percept, self.raw, self.tracker, self.receiver.interceptor)

    def _after_kick(self, percept: Percept) -> str:
        """After the kick on: ``"done"``, ``"wait"`` (to see where the ball went) or ``"again"``.

        On the Soccer Server a kick is a kick: done. A camera-guided receiver's kick fires only
        if the ball comes into reach while it is armed, so the receiver stands until a percept
        shows the ball beyond its slow zone (done) or its fitted velocity shows the ball still
        by it and slow (the kick missed: again).
        """
        ball = percept.ball
        if self.tracker.camera is None:
            return "done"
        if ball is None or not self.tracker.fresh(percept):
            return "wait"
        if ball.distance_m > SLOW_ZONE_REACHES * self.reach_m:
            return "done"
        fit = self.tracker.fitted(percept)
        if fit is not None and math.hypot(*fit) < 0.5 * self.sense.speed(self.powers.passing):
            return "again"
        return "wait"

    def _look_for_goal(self, percept: Percept) -> tuple[Action, ...]:
        """A last receiver, before the play reaches it: find the goal once, then face the ball."""
        if self.shoots and self.heading.relative("goal") is None:
            return (Turn(SEARCH_TURN_RAD),)
        return _face_ball(percept)

    def _pass_announced(self, percept: Percept) -> None:
        """The pass to it was just announced: the ball comes at the pass speed."""
        texts = [h.text for h in percept.heard if announced_number(h.text) is not None]
        kick_tick = _heard_tick(percept, texts)
        self.tracker.launched(percept, self.sense.speed(self.powers.passing), kick_tick)

    def _kick_on(self, percept: Percept, entry: Vector | None = None) -> tuple[Action, ...]:
        """Kick to the winger, or shoot; `entry`: where an armed kick will meet the ball."""
        if self.next_teammate is None:
            return self._shoot(percept, entry)
        winger = find_teammate(percept, self.next_teammate)
        direction = winger.angle_rad if winger is not None else self.heading.relative("call")
        if direction is None:  # never seen nor heard: hold the ball and look
            return self._stop_then(percept, (Turn(SEARCH_TURN_RAD),))
        speed = self.sense.speed(self.powers.passing)
        kick, kicked = self.tracker.aim(
            percept, speed, direction, first_time=self._first(percept, entry)
        )
        if not kicked:
            return () if kick is None else (kick,)
        self.kicked_tick = percept.tick
        return (Say(WINGER_CUE),) if kick is None else (Say(WINGER_CUE), kick)

    def _first(self, percept: Percept, entry: Vector | None) -> Vector | None:
        """Where a camera-guided receiver's first-time kick meets the ball; None without camera.

        At `entry` when it is given, else where the player reckons the ball now.
        """
        ball = percept.ball
        if self.tracker.camera is None or (entry is None and ball is None):
            return None
        if entry is not None or ball is None:
            return entry
        return ball.distance_m * math.cos(ball.angle_rad), ball.distance_m * math.sin(
            ball.angle_rad
        )

    def _shoot(self, percept: Percept, entry: Vector | None = None) -> tuple[Action, ...]:
        """Shoot at the goal in view; else stop the ball and turn to where the goal was seen."""
        goal = goal_bearing(percept, self.attack_right)
        if goal is None:
            remembered = self.heading.relative("goal")
            turn = SEARCH_TURN_RAD if remembered is None else remembered
            return self._stop_then(percept, (Turn(turn),))
        direction = shot_direction(percept, goal, self.goal_half_width_m)
        speed = self.sense.speed(self.powers.shot)
        kick, kicked = self.tracker.aim(
            percept, speed, direction, first_time=self._first(percept, entry)
        )
        if kicked:
            self.kicked_tick = percept.tick
        return () if kick is None else (kick,)

    def _stop_then(self, percept: Percept, then: tuple[Action, ...]) -> tuple[Action, ...]:
        kick = self.tracker.stop(percept, STILL_SHARE * self.sense.speed(self.powers.passing))
        return then if kick is None else (kick, *then)
