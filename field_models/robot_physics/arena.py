"""The robot system as an arena: pymunk world + overhead camera + central host + link + firmware.

One tick (``1/physics_hz`` s), in this order (paper §2, Figures 1–2; DESIGN.md §2):

1. the world steps (wheel ramps, grip, contacts, rolling ball);
2. the host sends the body actions of earlier decisions that are due now (a decision's later
   actions, e.g. the Dash after a Turn: :mod:`field_models.robot_physics.host`); packets that
   arrive this tick reach the firmware of the robot they address (or all, for a broadcast);
   each robot's firmware turns its newest command into wheel-speed targets, and fires the
   kicker if the command was a KICK;
3. on camera ticks the camera captures the true poses; frames whose latency has elapsed reach the
   host, which builds one egocentric percept per robot and returns them to the runner;
4. the runner gives each percept to that robot's client mind and hands the actions back through
   :meth:`RobotArena.submit`; the host translates them to primitives and queues them on the link.

The coach side (`place_*`, `*_state`, `truth`) reads and writes the world directly.

Events (``keep_events``): the client's actions as command text (``"command"``), the primitives
the host sent (``"link"``); with ``trace`` also every percept delivered, written in the Soccer
Server's see form (``"see"``, :func:`~field_models.robot_physics.trace_text.percept_text`).
"""

from __future__ import annotations

import dataclasses
from collections.abc import Iterable

from field_models.arena import ArenaEvent, FieldFacts
from field_models.commands import render_command
from field_models.protocol import (
    Action,
    BodyState,
    ChangeView,
    Percept,
    PlayerRef,
    Truth,
    TurnNeck,
)
from field_models.robot_physics.camera import OverheadCamera
from field_models.robot_physics.config import RobotPhysicsPreset
from field_models.robot_physics.firmware import Firmware
from field_models.robot_physics.host import CentralHost
from field_models.robot_physics.link import Link
from field_models.robot_physics.motor import make_world
from field_models.robot_physics.trace_text import percept_text
from field_models.seeding import TrialRngs

_NEVER = 1 << 62
"""A tick that never comes."""

NO_WATCHDOG_TICKS = 1 << 40
"""The firmware timeout under :meth:`RobotArena.ideal_actuation`: longer than any trial."""


class RobotArena:
    """The mini-robot testbed behind the :class:`~field_models.arena.Arena` interface.

    Args:
        preset: The robot preset, options already applied (:func:`field_models.registry`).
        facts: Its facts.
        players: The robots, in a fixed order.
        rngs: The trial's generators ("movement", "camera", "link").
        keep_events: Keep commands and primitives for :meth:`drain_events`.
        trace: Also keep every delivered percept as a ``"see"`` event.
    """

    def __init__(
        self,
        preset: RobotPhysicsPreset,
        facts: FieldFacts,
        players: tuple[PlayerRef, ...],
        rngs: TrialRngs,
        *,
        keep_events: bool = False,
        trace: bool = False,
    ) -> None:
        self.preset = preset
        self.facts = facts
        self.players = players
        self.keep_events = keep_events or trace
        self.trace = trace
        self.world = make_world(preset, players, rngs["movement"])
        frame_ticks = preset.ticks(1.0 / preset.camera.frame_rate_hz, "camera.frame_rate_hz")
        self.camera = OverheadCamera(
            preset.camera,
            players,
            period_ticks=frame_ticks,
            latency_ticks=preset.ticks(preset.camera.latency_s, "camera.latency_s"),
            rng=rngs["camera"],
        )
        self._link_rng = rngs["link"]
        self.link = Link(
            preset.link,
            packet_period_ticks=preset.ticks(1.0 / preset.link.packets_per_s, "link.packets_per_s"),
            latency_ticks=preset.ticks(preset.link.latency_s, "link.latency_s"),
            rng=self._link_rng,
        )
        timeout = preset.ticks(preset.firmware.timeout_s, "firmware.timeout_s")
        self.firmware = [
            Firmware(ref, preset.robot, preset.firmware, timeout_ticks=timeout) for ref in players
        ]
        self._by_ref = {ref: i for i, ref in enumerate(players)}
        # The same rows by object identity: the callers' refs are mostly the arena's own objects,
        # and an identity look-up skips PlayerRef's Python-level hash.
        self._row_by_id = {id(ref): i for i, ref in enumerate(players)}
        self._firmware_fresh: list[int] = []  # rows whose firmware accepted a command now
        # No firmware's duration or watchdog ends before this tick (a lower bound).
        self._firmware_wake_tick = 0
        self._listeners: frozenset[PlayerRef] | None = None
        self._events: list[ArenaEvent] = []
        self.host = CentralHost(
            players, preset, self.link, frame_period_ticks=frame_ticks, keep_events=self.keep_events
        )

    @property
    def tick(self) -> int:
        """Ticks stepped since the trial began."""
        return self.world.tick

    # ------------------------------------------------------------------ coach side

    def place_player(self, ref: PlayerRef, x: float, y: float, heading: float) -> None:
        """Put a robot at rest at (x, y) [m] facing `heading` [rad]."""
        self.world.place_robot(self._by_ref[ref], x, y, heading)

    def place_ball(self, x: float, y: float, vx: float = 0.0, vy: float = 0.0) -> None:
        """Put the ball at (x, y) [m] moving at (vx, vy) [m/s]."""
        self.world.place_ball(x, y, vx, vy)

    def ball_state(self) -> BodyState:
        """The ball's exact state."""
        return self.world.ball_state()

    def player_state(self, ref: PlayerRef) -> BodyState:
        """A robot's exact state."""
        i = self._row_by_id.get(id(ref), -1)
        if i < 0 or self.players[i] is not ref:  # not one of the arena's own objects
            i = self._by_ref[ref]
        return self.world.robot_state(i)

    def truth(self) -> Truth:
        """Exact state of everything."""
        return self.world.truth()

    def score(self) -> tuple[int, int]:
        """The table has no referee: (0, 0); coaches judge goals from the ball."""
        return (0, 0)

    # ------------------------------------------------------------------ client side

    def step(self) -> list[Percept]:
        """Advance one tick; return the percepts whose camera frame reached the host now."""
        world = self.world
        world.step()
        tick = world.tick
        host = self.host
        if tick >= host.next_release_tick:  # the later actions of a decision (host docstring)
            host.release(tick)
        # Each part below runs only at its own events (its next-event tick says when), so a
        # quiet tick costs a few integer comparisons beside the physics.
        link = self.link
        if tick >= link.next_due_tick:
            fresh = self._firmware_fresh
            for command in link.deliver(tick):
                if command.robot is None:
                    for i, fw in enumerate(self.firmware):
                        if fw.receive(command, tick):
                            fresh.append(i)
                else:
                    robot = command.robot
                    i = self._row_by_id.get(id(robot), -1)
                    if i < 0 or self.players[i] is not robot:
                        i = self._by_ref[robot]
                    if self.firmware[i].receive(command, tick):
                        fresh.append(i)
        if tick >= self._firmware_wake_tick:
            self._run_firmware(range(len(self.firmware)), tick)
        elif self._firmware_fresh:
            self._run_firmware(sorted(set(self._firmware_fresh)), tick)
        camera = self.camera
        if tick % camera.period_ticks == 0:
            bx, by = world.ball_xy()
            camera.capture(tick, bx, by, world.robot_poses())
        if tick < camera.next_delivery_tick:
            return []
        frames = camera.deliver(tick)
        if not frames:
            return []
        percepts: list[Percept] = []
        for frame in frames:
            percepts.extend(host.percepts(frame, tick, self._listeners))
        if self.trace:
            self._events += [ArenaEvent(tick, "see", percept_text(p), p.player) for p in percepts]
        return percepts

    def _run_firmware(self, rows: Iterable[int], tick: int) -> None:
        """The firmware of robots `rows` (in order) that is due: wheel targets, and a kick.

        A firmware is due when a command reached it or its duration or watchdog ends
        (:meth:`Firmware.due`); the rows cover every one due now, so the others' are skipped
        as the firmware would skip them.
        """
        world = self.world
        firmware = self.firmware
        wake = self._firmware_wake_tick if tick < self._firmware_wake_tick else _NEVER
        for i in rows:
            fw = firmware[i]
            if fw.due(tick):
                left, right = fw.update(tick)
                world.set_wheel_targets(i, left, right)
                power = fw.take_kick()
                if power is not None:
                    world.kick(i, power)
            wake = min(wake, fw.wake_tick)
        self._firmware_fresh.clear()
        self._firmware_wake_tick = wake

    def listen(self, refs: frozenset[PlayerRef]) -> None:
        """Return percepts only for these robots (the host still tracks every robot's pose)."""
        self._listeners = None if refs >= frozenset(self.players) else refs

    def submit(self, ref: PlayerRef, actions: tuple[Action, ...]) -> None:
        """Translate a robot's actions into primitives and queue them on the link.

        Neck turns and view changes are logged and otherwise dropped here (the host's module
        docstring says why), so a decision that holds only those is no decision at all.
        """
        if not actions:
            return
        tick = self.world.tick
        if self.keep_events:
            self._events += [ArenaEvent(tick, "command", render_command(a), ref) for a in actions]
        actions = tuple(a for a in actions if not isinstance(a, TurnNeck | ChangeView))
        if actions:
            self.host.submit(ref, actions, tick)

    def submit_wheels(self, ref: PlayerRef, left_mps: float, right_mps: float) -> None:
        """Send wheel speeds [m/s] to a robot through host, link and firmware (WheelDrive)."""
        tick = self.world.tick
        if self.keep_events:
            text = f"(wheels {left_mps:.3f} {right_mps:.3f})"
            self._events.append(ArenaEvent(tick, "command", text, ref))
        self.host.wheels(ref, left_mps, right_mps, tick)

    def ideal_actuation(self) -> None:
        """No link latency, loss or rate limit and no firmware watchdog from now on (WheelDrive).

        The host's own timing (a turn's duration, a dash's hold) stays: it is the robots'
        behaviour, not an imperfection of the path.
        """
        ideal = dataclasses.replace(self.preset.link, loss_prob=0.0, latency_s=0.0)
        self.link = Link(ideal, packet_period_ticks=1, latency_ticks=0, rng=self._link_rng)
        self.host.ideal_link(self.link)
        for fw in self.firmware:
            fw.timeout_ticks = NO_WATCHDOG_TICKS

    def drain_events(self) -> list[ArenaEvent]:
        """Client commands, primitives sent and (tracing) percepts since the last call."""
        events = self._events + self.host.drain_events()
        events.sort(key=lambda e: e.tick)  # stable: the order they happened in within a tick
        self._events = []
        return events
