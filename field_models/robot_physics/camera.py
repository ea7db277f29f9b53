"""The overhead camera: noisy, delayed, sometimes blind detections of the ball and the robots.

The paper's vision system (§2, processing cycle steps i–ii) perceives the positions of the robots
and the ball and hands them to the host computer. This module models it as a seeded, separate
layer between the world's truth and the host (shared `specs/robot_physics.md` §2.4, §5 item 4):

* **Frames** are captured every `period_ticks` physics ticks, at ticks that are multiples of the
  period (tick 0, p, 2p, ...). The preset's default is 30 Hz, i.e. 8 ticks at 240 Hz.
* **Latency**: a frame captured at tick `t` is delivered at exactly `t + latency_ticks`
  (default 50 ms = 12 ticks). Frames leave in capture order (FIFO).
* **Noise**: independent Gaussian noise on each position axis (σ = `position_sigma_m`) and on the
  heading (σ = `heading_sigma_rad`); headings are reported wrapped to [-π, π).
* **Missed detections**: independent per object per frame, the ball with `ball_miss_prob`, each
  robot with `robot_miss_prob`. A missed object is absent from the frame.
* **Perfect perception** (`config.perfect`): no noise, no misses and zero latency, i.e. a frame
  captured at `t` is delivered at `t`. No random numbers are drawn then.

Detections carry the robot's identity (`PlayerRef`); the paper's robots have an identification
code, and CMUnited's vision reports each robot's id, position and orientation.

Randomness comes from one generator passed in. Each frame draws a fixed number of variates (one
vectorised normal draw and one uniform draw of 3n+2 and n+1 values for n robots), whatever is
detected, so a trial's numbers depend on its seed alone.
"""

from __future__ import annotations

import math
from collections import deque
from collections.abc import Callable, Sequence
from dataclasses import dataclass

from field_models.protocol import TWO_PI, PlayerRef, wrap_angle
from field_models.records import positional_maker
from field_models.robot_physics.config import CameraConfig
from field_models.seeding import Rng, Stream

_NEVER = 1 << 62
"""A tick that never comes."""


@dataclass(frozen=True, slots=True)
class BallDetection:
    """The ball as the camera saw it, in the field frame [m]."""

    x: float
    y: float


@dataclass(frozen=True, slots=True)
class RobotDetection:
    """A robot as the camera saw it: identity, field position [m], heading in [-π, π) [rad]."""

    ref: PlayerRef
    x: float
    y: float
    heading: float


@dataclass(frozen=True, slots=True)
class Frame:
    """One camera frame.

    Attributes:
        capture_tick: Tick at which the world was sampled.
        delivery_tick: Tick at which the frame reaches the host (capture plus latency).
        ball: The ball's detection, or None when the camera missed it.
        robots: Detected robots, in the camera's `refs` order; missed robots are absent.
    """

    capture_tick: int
    delivery_tick: int
    ball: BallDetection | None
    robots: tuple[RobotDetection, ...]


_make_ball = positional_maker(BallDetection)
_make_robot = positional_maker(RobotDetection)
_make_frame = positional_maker(Frame)


class OverheadCamera:
    """A seeded overhead camera with frame rate, latency, Gaussian noise and missed detections.

    Args:
        config: Noise, miss probabilities and the perfect-perception switch. The frame rate and
            latency in it are given again, converted to ticks, by the next two arguments.
        refs: The robots on the field; `capture` takes their poses in this order.
        period_ticks: Ticks between two captures (>= 1).
        latency_ticks: Ticks from capture to delivery (>= 0); ignored (zero) when perfect.
        rng: The trial's camera generator.
    """

    def __init__(
        self,
        config: CameraConfig,
        refs: tuple[PlayerRef, ...],
        *,
        period_ticks: int,
        latency_ticks: int,
        rng: Rng,
    ) -> None:
        if period_ticks < 1:
            raise ValueError(f"period_ticks must be >= 1, got {period_ticks}")
        if latency_ticks < 0:
            raise ValueError(f"latency_ticks must be >= 0, got {latency_ticks}")
        self.config = config
        self.refs = refs
        self.period_ticks = period_ticks
        self.latency_ticks = 0 if config.perfect else latency_ticks
        # Lists straight from a project stream; a numpy generator's arrays are unpacked.
        self._normals: Callable[[int], list[float]]
        self._uniforms: Callable[[int], list[float]]
        if isinstance(rng, Stream):
            self._normals, self._uniforms = rng.standard_normal_list, rng.random_list
        else:
            self._normals = lambda n: rng.standard_normal(n).tolist()
            self._uniforms = lambda n: rng.random(n).tolist()
        self._pending: deque[Frame] = deque()
        self._perfect = config.perfect
        self._pos_sigma = config.position_sigma_m
        self._head_sigma = config.heading_sigma_rad
        self._ball_miss = config.ball_miss_prob
        self._robot_miss = config.robot_miss_prob
        self._n = len(refs)
        self.next_delivery_tick = _NEVER
        """The delivery tick of the oldest frame not delivered yet (a huge one when none)."""

    def capture_due(self, tick: int) -> bool:
        """Whether a frame is captured at `tick` (ticks that are multiples of the period)."""
        return tick % self.period_ticks == 0

    def capture(
        self,
        tick: int,
        ball_x: float,
        ball_y: float,
        robot_poses: Sequence[tuple[float, float, float]],
    ) -> None:
        """Sample the true state at `tick` into a frame queued for delivery after the latency.

        Args:
            tick: The capture tick.
            ball_x: True ball x [m].
            ball_y: True ball y [m].
            robot_poses: True (x [m], y [m], heading [rad]) of each robot, in `refs` order.
        """
        if len(robot_poses) != self._n:
            raise ValueError(f"expected {self._n} robot poses, got {len(robot_poses)}")
        if self._perfect:
            frame = self._exact_frame(tick, ball_x, ball_y, robot_poses)
        else:
            frame = self._noisy_frame(tick, ball_x, ball_y, robot_poses)
        self._pending.append(frame)
        if len(self._pending) == 1:
            self.next_delivery_tick = frame.delivery_tick

    def deliver(self, tick: int) -> list[Frame]:
        """Frames whose delivery tick has come (at or before `tick`), oldest first."""
        pending = self._pending
        out: list[Frame] = []
        while pending and pending[0].delivery_tick <= tick:
            out.append(pending.popleft())
        self.next_delivery_tick = pending[0].delivery_tick if pending else _NEVER
        return out

    def _exact_frame(
        self,
        tick: int,
        ball_x: float,
        ball_y: float,
        robot_poses: Sequence[tuple[float, float, float]],
    ) -> Frame:
        """Truth as a frame delivered at once (perfect perception)."""
        robots = tuple(
            RobotDetection(ref, x, y, wrap_angle(h))
            for ref, (x, y, h) in zip(self.refs, robot_poses, strict=True)
        )
        return Frame(tick, tick, BallDetection(ball_x, ball_y), robots)

    def _noisy_frame(
        self,
        tick: int,
        ball_x: float,
        ball_y: float,
        robot_poses: Sequence[tuple[float, float, float]],
    ) -> Frame:
        """Truth plus Gaussian noise, minus missed objects, delivered after the latency."""
        n = self._n
        # One vectorised draw each: [ball dx, ball dy, (dx, dy, dheading) per robot] as unit
        # normals, and [ball, robot...] uniforms for the misses.
        z = self._normals(2 + 3 * n)
        u = self._uniforms(1 + n)
        ps = self._pos_sigma
        hs = self._head_sigma
        ball = (
            None if u[0] < self._ball_miss else _make_ball(ball_x + ps * z[0], ball_y + ps * z[1])
        )
        robots: list[RobotDetection] = []
        miss = self._robot_miss
        make = _make_robot
        pi, two_pi = math.pi, TWO_PI
        for i, (ref, (x, y, h)) in enumerate(zip(self.refs, robot_poses, strict=True)):
            if u[1 + i] < miss:
                continue
            k = 2 + 3 * i
            heading = h + hs * z[k + 2]
            if not -pi <= heading < pi:  # wrap_angle, inlined (field_models.protocol)
                heading = (heading + pi) % two_pi - pi
            robots.append(make(ref, x + ps * z[k], y + ps * z[k + 1], heading))
        return _make_frame(tick, tick + self.latency_ticks, ball, tuple(robots))
