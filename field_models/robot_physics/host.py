"""The central host: camera frames in, one egocentric percept per robot out; actions to primitives.

The paper's off-board computer (§2, Figures 1–2) makes the camera's perception available to one
client mind per robot, and sends each mind's navigation commands to its robot over the wireless
link. Here the host sits between the camera (:mod:`field_models.robot_physics.camera`) and the
link (:mod:`field_models.robot_physics.link`):

**Percepts** (DESIGN.md §2). On each delivered frame, :meth:`CentralHost.percepts` builds one
:class:`~field_models.protocol.Percept` per robot, in `refs` order:

* the robot's own pose is its detection in this frame; when the camera missed it, its last
  detected pose (from an earlier frame; no dead reckoning); when it was never detected, the
  percept has no ball and no players (only heard messages);
* the ball: distance [m] and angle [rad, left of the heading positive] from that pose, or None
  when the camera missed it in this frame; rates of change are not reported (a client that wants
  them keeps the previous distance, as the paper's interception skill does, §5);
* other robots: distance, angle, team and number from this frame's detections only; a robot the
  camera missed is absent (unknown), not carried over;
* `observed_tick` is the frame's capture tick, `tick` the decision tick (its delivery);
* heard: the messages relayed to this robot since its previous percept;
* landmarks: the two goals (``"g l"``, ``"g r"``: the centres of the goal lines), placed from
  the robot's pose on the known field, as the Soccer Server's see gives its goals.

**Actions to primitives**, and the timing of several body actions in one decision, are the
actuation's: :class:`~field_models.robot_physics.host_actuation.HostActuation`, a mixin of
:class:`CentralHost` (:mod:`field_models.robot_physics.host_actuation` says how each action
becomes a primitive). Says are relayed here, with the percepts' heard messages.
"""

from __future__ import annotations

import math

from field_models.arena import ArenaEvent
from field_models.protocol import (
    TWO_PI,
    Action,
    Heard,
    Percept,
    PlayerRef,
    SeenBall,
    SeenLandmark,
    SeenPlayer,
    wrap_angle,
)
from field_models.records import positional_maker
from field_models.robot_physics.camera import Frame
from field_models.robot_physics.config import RobotPhysicsPreset
from field_models.robot_physics.host_actuation import DASH_HOLD_PERIODS, NEVER, HostActuation
from field_models.robot_physics.link import Link

_make_percept = positional_maker(Percept)
_make_ball = positional_maker(SeenBall)
_make_player = positional_maker(SeenPlayer)
_make_landmark = positional_maker(SeenLandmark)

Pose = tuple[float, float, float]
"""(x [m], y [m], heading [rad]) in the field frame."""


class CentralHost(HostActuation):
    """Builds percepts from frames and translates client actions into link commands.

    Args:
        refs: The robots, in the order percepts are returned.
        preset: The robot-physics preset (robot limits, kicker, tick length).
        link: The link the commands go out on.
        frame_period_ticks: Ticks per camera period (T in the module docstring).
        keep_events: Keep sent commands and messages for :meth:`drain_events`; turn off when
            nobody drains them (the list would grow).
    """

    def __init__(
        self,
        refs: tuple[PlayerRef, ...],
        preset: RobotPhysicsPreset,
        link: Link,
        *,
        frame_period_ticks: int,
        keep_events: bool = True,
    ) -> None:
        if frame_period_ticks < 1:
            raise ValueError(f"frame_period_ticks must be >= 1, got {frame_period_ticks}")
        self.refs = refs
        self.preset = preset
        self.link = link
        self.frame_period_ticks = frame_period_ticks
        self.keep_events = keep_events
        robot = preset.robot
        self._dt_s = preset.dt_s
        self._vmax = robot.max_wheel_speed_mps
        self._max_rate = robot.max_turn_rate_radps
        self._spin_accel = 2.0 * robot.wheel_accel_mps2 / robot.track_m
        self._period_s = frame_period_ticks * preset.dt_s
        self._hold_ticks = DASH_HOLD_PERIODS * frame_period_ticks
        self._kick_half_angle = None if robot.kicker is None else robot.kicker.half_angle_rad
        self._arcs = robot.turn_style == "arc"
        self._index = {ref: i for i, ref in enumerate(refs)}
        self._row_by_id = {id(ref): i for i, ref in enumerate(refs)}
        self._poses: list[Pose | None] = [None] * len(refs)
        self._heard: list[list[Heard]] = [[] for _ in refs]
        self._seq = 0
        self._events: list[ArenaEvent] = []
        self._min_ticks = link.packet_period_ticks
        self._pending: list[list[Action]] = [[] for _ in refs]
        self._release_at = [NEVER] * len(refs)
        self.dropped = 0  # the counters and the release tick: HostActuation's attributes
        self.dropped_dashes = 0
        self.next_release_tick = NEVER
        half_length = 0.5 * preset.field.length_m
        self._goals = (("g l", -half_length, 0.0), ("g r", half_length, 0.0))

    # ------------------------------------------------------------------------ perception

    def _row(self, ref: PlayerRef) -> int:
        """`ref`'s row in :attr:`refs`, -1 if it is not there.

        The camera's detections and the percepts' players are the very objects of :attr:`refs`,
        so an identity look-up (no PlayerRef hash, a Python-level call) finds them; an equal
        copy falls back to ==.
        """
        i = self._row_by_id.get(id(ref), -1)
        if i >= 0 and self.refs[i] is ref:
            return i
        return self._index.get(ref, -1)

    def pose_estimate(self, ref: PlayerRef) -> Pose | None:
        """The host's newest detected pose of `ref`, or None if never detected."""
        return self._poses[self._index[ref]]

    def percepts(
        self, frame: Frame, tick: int, only: frozenset[PlayerRef] | None = None
    ) -> list[Percept]:
        """One egocentric percept per robot, in `refs` order, from a delivered frame.

        With `only`, percepts are built for those robots alone (the rest would go unread); the
        others' heard messages are dropped as if their percepts had been delivered.
        """
        poses = self._poses
        # Each detection once, with its robot's row, so the loop below compares rows (ints), not
        # identities (dataclass equality is the costliest part of building a percept).
        seen = []
        row = self._row
        for det in frame.robots:
            ref = det.ref
            i = row(ref)
            if i >= 0:
                poses[i] = (det.x, det.y, det.heading)
            seen.append((i, det.x, det.y, ref.team, ref.number))
        ball = frame.ball
        observed = frame.capture_tick
        out: list[Percept] = []
        hypot, atan2 = math.hypot, math.atan2
        # wrap_angle inlined below (the same comparisons and arithmetic, field_models.protocol).
        pi, two_pi = math.pi, TWO_PI
        make_percept, make_ball = _make_percept, _make_ball
        make_player, make_landmark = _make_player, _make_landmark
        heard_lists = self._heard
        goals = self._goals
        for i, ref in enumerate(self.refs):
            heard_list = heard_lists[i]
            if only is not None and ref not in only:
                heard_list.clear()
                continue
            heard = tuple(heard_list)
            heard_list.clear()
            pose = poses[i]
            if pose is None:
                out.append(make_percept(ref, tick, observed, None, (), heard, (), 0.0))
                continue
            px, py, heading = pose
            seen_ball = None
            if ball is not None:
                dx = ball.x - px
                dy = ball.y - py
                a = atan2(dy, dx) - heading
                if not -pi <= a < pi:
                    a = (a + pi) % two_pi - pi
                seen_ball = make_ball(hypot(dx, dy), a, None, None)
            players = [
                make_player(
                    hypot(x - px, y - py),
                    a if -pi <= (a := atan2(y - py, x - px) - heading) < pi
                    else (a + pi) % two_pi - pi,
                    team,
                    number,
                )
                for row, x, y, team, number in seen
                if row != i
            ]  # fmt: skip
            landmarks = []
            for name, gx, gy in goals:
                dx = gx - px
                dy = gy - py
                a = atan2(dy, dx) - heading
                if not -pi <= a < pi:
                    a = (a + pi) % two_pi - pi
                landmarks.append(make_landmark(name, hypot(dx, dy), a))
            out.append(
                make_percept(
                    ref, tick, observed, seen_ball, tuple(players), heard, tuple(landmarks), 0.0
                )
            )
        return out

    def drain_events(self) -> list[ArenaEvent]:
        """Commands sent and messages relayed since the last call, oldest first."""
        events, self._events = self._events, []
        return events

    def _relay(self, sender: PlayerRef, text: str, tick: int) -> None:
        """Put a said message into every other robot's heard buffer."""
        source = self._poses[self._index[sender]]
        for i, ref in enumerate(self.refs):
            if ref == sender:
                continue
            direction = None
            listener = self._poses[i]
            if source is not None and listener is not None:
                direction = wrap_angle(
                    math.atan2(source[1] - listener[1], source[0] - listener[0]) - listener[2]
                )
            self._heard[i].append(Heard(text, sender, direction, tick))
