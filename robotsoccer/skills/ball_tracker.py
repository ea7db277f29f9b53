"""The ball's velocity as one set-play player reckons it, and the kicks it makes (paper §7).

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
A first-time kick (a camera-guided receiver's) is instead bent round the body
(:func:`bent_direction`).

**Percepts that lag** (the robots' camera, §2: 50 ms). The tracker moves a percept's ball on
by its estimated velocity over the latency (:meth:`BallTracker.project`), and a mind does not
kick again until a percept shows its last kick (:meth:`BallTracker.fresh`). With **a camera**
(:class:`~robotsoccer.skills.ball_sense.CameraBall`) the tracker keeps the ball's velocity in
the field frame, fitted to the camera's sightings once a full window of them follows the last
kick (dead reckoning from the announced pass until then). On the Soccer Server (no latency)
these change nothing.

Angles are radians, left positive; distances metres; speeds m/s.
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from dataclasses import replace

from field_models.protocol import Action, Kick, Percept, SeenBall, Turn, wrap_angle
from robotsoccer.skills.ball_sense import BallSense, CameraBall, Vector

BLOCK_MARGIN_SHARE = 0.15
"""A ball seen within touching distance plus this share of the kick margin has met the body."""
CLEAR_MARGIN_SHARE = 0.3
"""A kick's path clears the body by touching distance plus this share of the kick margin."""
FIRST_TIME_BEND_RAD = math.radians(45.0)
"""A first-time kick on is bent by at most this to clear the kicker's body."""


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
        (:func:`bent_direction`; beyond its reach, the tap as before): the next player
        collects it with layer 1.
        """
        if not self.fresh(percept):
            return None, False  # the last kick does not show yet: wait for a percept that does
        ball = percept.ball
        if ball is not None:
            side = blocking_side(self.sense, ball.distance_m, ball.angle_rad, direction_rad)
            if first_time is not None:
                at = (math.hypot(*first_time), math.atan2(first_time[1], first_time[0]))
                side = blocking_side(self.sense, *at, direction_rad)
                bent = (
                    direction_rad
                    if side is None
                    else bent_direction(self.sense, *at, direction_rad, side)
                )
                if bent is not None:
                    return self.kick_to(percept, speed_mps, bent), True
            if side is not None:
                return self._tap(percept, side, direction_rad), False
        return self.kick_to(percept, speed_mps, direction_rad), True

    def _tap(self, percept: Percept, lateral: float, direction_rad: float) -> Kick | None:
        """Move the ball aside, clear of the path through the body, by the next percept."""
        sign = 1.0 if lateral >= 0.0 else -1.0
        shift = 1.5 * clearance(self.sense) - abs(lateral)
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


def clearance(sense: BallSense) -> float:
    """How far a kick's path must pass from the body's centre to clear it [m]."""
    return sense.touch_m + CLEAR_MARGIN_SHARE * (sense.reach_m - sense.touch_m)


def blocking_side(
    sense: BallSense, distance_m: float, angle_rad: float, direction_rad: float
) -> float | None:
    """The ball's lateral offset from a path through the body [m], or None if it is clear.

    The ball lies at (`distance_m`, `angle_rad`) in the body frame and is kicked toward
    `direction_rad`; positive offsets have the ball to the path's left.
    """
    bx, by = distance_m * math.cos(angle_rad), distance_m * math.sin(angle_rad)
    ux, uy = math.cos(direction_rad), math.sin(direction_rad)
    if bx * ux + by * uy >= 0.0:
        return None  # it runs away from the body
    lateral = -bx * uy + by * ux
    return lateral if abs(lateral) < clearance(sense) else None


def bent_direction(
    sense: BallSense, distance_m: float, angle_rad: float, direction_rad: float, lateral: float
) -> float | None:
    """The direction nearest `direction_rad` whose path clears the body, or None.

    It searches both ways in steps of a degree up to :data:`FIRST_TIME_BEND_RAD`, the way
    that makes the ball's offset from the path (`lateral`, positive with the ball to the
    path's left) grow first: that side clears soonest as long as the ball lies within a right
    angle of the path's reverse.
    """
    sign = 1.0 if lateral >= 0.0 else -1.0
    step = math.radians(1.0)
    for k in range(1, round(FIRST_TIME_BEND_RAD / step) + 1):
        for turn in (sign, -sign):
            bent = wrap_angle(direction_rad + turn * k * step)
            if blocking_side(sense, distance_m, angle_rad, bent) is None:
                return bent
    return None
