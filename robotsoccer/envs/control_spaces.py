"""Actions, observations and reward weights of the per-step control environments.

Shared by :mod:`robotsoccer.envs.control` (go to the ball, score) on both field models.

**Actions** (``action=``; every kind goes through the field's own actuation path: on the
robots the central host, the radio link and the firmware, so latency, loss and the watchdog
apply unless ``ideal_actuation=True``):

* ``"wheels"`` — ``Box(-1, 1, (2,))``: left and right wheel speed as a share of the top wheel
  speed. Values outside [-1, 1] are clipped to it (the Box's bounds). Only on a field whose
  arena drives wheels (:class:`~field_models.arena.WheelDrive`: the robots).
* ``"primitives"`` — ``Discrete(6)``, :class:`DiscreteAction`: STOP, FORWARD, BACKWARD,
  TURN_LEFT, TURN_RIGHT, KICK. Each is one body action of the shared vocabulary, which the
  robots' host sends as exactly one primitive: ``Dash(0)`` → STOP, ``Dash(±100)`` →
  FORWARD/BACKWARD at top speed, ``Turn(±turn_step_rad)`` → a timed TURN, ``Kick(100, 0)`` →
  KICK (or a push, on a robot without a kicker). On the Soccer Server the same actions are its
  ``dash``, ``turn`` and ``kick``.
* ``"commands"`` — ``Box(-1, 1, (8,))``, the Soccer Server's parametrised commands in the form
  of Hausknecht & Stone's HFO agents: ``[dash, turn, kick, dash power, dash direction, turn
  moment, kick power, kick direction]``. The largest of the first three picks the command
  (ties: the first); then power = 100·p for a dash (negative: backwards), 50·(p + 1) for a
  kick, and each direction or moment = π·d [rad]. Clipped to [-1, 1] first.

An action is *held*: it is sent again every command period (a camera frame on the robots, a
cycle on the Soccer Server: :data:`COMMAND_PERIOD_S` at most) until the next step.

**Observations** (:class:`ObservationBuilder`): a fixed-size float32 vector built from the
learning player's *percept* only (what the host made of the camera frame, or the see message:
latency, noise and misses included), egocentric, distances over the pitch length L. See
:func:`observation_names` for the exact layout:

* ``ball``: seen (0/1), distance / L, cos and sin of its angle (zeros when not seen);
* ``ball_motion``: change of the ball's egocentric x and y since the previous percept that saw
  it, in L per second (zeros when either percept missed it);
* ``self``: localised (0/1), x / (L/2), y / (W/2), cos and sin of the heading, from the seen
  landmarks (:class:`~robotsoccer.skills.localise.Localiser`; zeros until it is localised);
* ``target``: known (0/1), distance / L, cos and sin of its angle: the point to face (go to
  the ball) or the opponents' goal (score), from the localised pose;
* ``teammate_i`` / ``opponent_i``: seen, distance / L, cos, sin, nearest first (players of an
  unknown team fill the opponents' slots after the known ones);
* ``time_left``: the share of the episode's time still to run.

Every entry is clipped to the observation space's bounds. ``privileged=True`` makes the
observation a ``Dict`` with the vector as ``"observation"`` and the true state as ``"state"``
(:func:`state_vector`), for a critic that may read truth.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from enum import IntEnum
from typing import Any

import numpy as np
import numpy.typing as npt
from gymnasium import spaces

from field_models.arena import FieldFacts
from field_models.protocol import Action, Dash, Kick, Percept, PlayerRef, Truth, Turn, wrap_angle
from robotsoccer.skills.localise import Localiser

ACTION_KINDS = ("wheels", "primitives", "commands")
"""The action kinds (module docstring)."""
COMMAND_PERIOD_S = 0.1
"""A held action is sent again at least this often [s] (every frame when frames come faster)."""
DEFAULT_TURN_STEP_RAD = math.radians(30.0)
"""A discrete TURN_LEFT/TURN_RIGHT asks for a turn by this much each command period."""
MAX_DISTANCE_L = 2.0
MAX_MOTION_L_PER_S = 10.0
MAX_STATE = 5.0
"""Observation bounds: distances [L], ball motion [L/s], entries of the true state."""

FloatArray = npt.NDArray[np.float32]


class DiscreteAction(IntEnum):
    """The ``"primitives"`` actions (module docstring)."""

    STOP = 0
    FORWARD = 1
    BACKWARD = 2
    TURN_LEFT = 3
    TURN_RIGHT = 4
    KICK = 5


def action_space(kind: str) -> spaces.Space[Any]:
    """The Gymnasium space of an action kind."""
    if kind == "wheels":
        return spaces.Box(-1.0, 1.0, shape=(2,), dtype=np.float32)
    if kind == "primitives":
        return spaces.Discrete(len(DiscreteAction))
    return spaces.Box(-1.0, 1.0, shape=(8,), dtype=np.float32)


Held = tuple[float, float] | tuple[Action, ...]
"""What a step sends every command period: wheel speeds (left, right) [m/s] or body actions."""


def decode_action(kind: str, action: object, top_speed_mps: float, turn_step_rad: float) -> Held:
    """Check `action` against `kind` and turn it into what the arena is sent.

    Raises:
        ValueError: A wrong shape or type, NaN or infinity, or a discrete action out of range;
            the message names the problem.
    """
    if kind == "primitives":
        return _discrete(_discrete_index(action), turn_step_rad)
    size = 2 if kind == "wheels" else 8
    values = np.asarray(action, dtype=np.float64) if _numeric(action) else None
    if values is None or values.shape != (size,):
        got = "a non-numeric value" if values is None else f"shape {values.shape}"
        raise ValueError(f"{kind} action must be an array of shape ({size},), got {got}")
    if not np.all(np.isfinite(values)):
        raise ValueError(f"{kind} action has NaN or infinite entries: {values.tolist()}")
    values = np.clip(values, -1.0, 1.0)  # the Box's documented bounds
    if kind == "wheels":
        return (float(values[0]) * top_speed_mps, float(values[1]) * top_speed_mps)
    choice = int(np.argmax(values[:3]))
    if choice == 0:
        return (Dash(100.0 * float(values[3]), math.pi * float(values[4])),)
    if choice == 1:
        return (Turn(math.pi * float(values[5])),)
    return (Kick(50.0 * (float(values[6]) + 1.0), math.pi * float(values[7])),)


def _numeric(action: object) -> bool:
    """Whether `action` converts to a float array (numbers, lists of them, arrays)."""
    try:
        np.asarray(action, dtype=np.float64)
    except (TypeError, ValueError):
        return False
    return True


def _discrete_index(action: object) -> int:
    """The index of a ``Discrete(6)`` action, checked."""
    value = np.asarray(action) if _numeric(action) else None
    if value is None or value.shape not in ((), (1,)):
        shape = "a non-numeric value" if value is None else f"shape {value.shape}"
        raise ValueError(f"primitives action must be one integer, got {shape}")
    scalar = value.reshape(()).item()
    if isinstance(scalar, float):
        if not math.isfinite(scalar):
            raise ValueError(f"primitives action is NaN or infinite: {scalar}")
        if not scalar.is_integer():
            raise ValueError(f"primitives action must be an integer, got {scalar}")
    index = int(scalar)
    if not 0 <= index < len(DiscreteAction):
        raise ValueError(f"primitives action must be in 0..{len(DiscreteAction) - 1}, got {index}")
    return index


def _discrete(index: int, turn_step_rad: float) -> tuple[Action, ...]:
    """The body action of a discrete action (module docstring)."""
    act = DiscreteAction(index)
    if act is DiscreteAction.FORWARD:
        return (Dash(100.0),)
    if act is DiscreteAction.BACKWARD:
        return (Dash(-100.0),)
    if act is DiscreteAction.TURN_LEFT:
        return (Turn(turn_step_rad),)
    if act is DiscreteAction.TURN_RIGHT:
        return (Turn(-turn_step_rad),)
    if act is DiscreteAction.KICK:
        return (Kick(100.0, 0.0),)
    return (Dash(0.0),)


# ----------------------------------------------------------------------------- observations


def observation_names(teammates: int, opponents: int) -> tuple[str, ...]:
    """The observation vector's entries, in order (module docstring)."""
    names = ["ball_seen", "ball_distance", "ball_cos", "ball_sin", "ball_dx", "ball_dy"]
    names += ["self_known", "self_x", "self_y", "self_cos", "self_sin"]
    names += ["target_known", "target_distance", "target_cos", "target_sin"]
    for group, count in (("teammate", teammates), ("opponent", opponents)):
        for i in range(count):
            names += [f"{group}{i}_{part}" for part in ("seen", "distance", "cos", "sin")]
    return (*names, "time_left")


_BOUNDS = {
    "seen": (0.0, 1.0),
    "known": (0.0, 1.0),
    "left": (0.0, 1.0),
    "distance": (0.0, MAX_DISTANCE_L),
    "dx": (-MAX_MOTION_L_PER_S, MAX_MOTION_L_PER_S),
    "dy": (-MAX_MOTION_L_PER_S, MAX_MOTION_L_PER_S),
    "x": (-1.5, 1.5),
    "y": (-1.5, 1.5),
    "cos": (-1.0, 1.0),
    "sin": (-1.0, 1.0),
}
"""Bounds of an entry by the last part of its name."""


def _bounds(names: tuple[str, ...]) -> tuple[FloatArray, FloatArray]:
    """Lower and upper bounds of each named entry."""
    pairs = [_BOUNDS[name.rsplit("_", 1)[-1]] for name in names]
    return np.array([p[0] for p in pairs], np.float32), np.array([p[1] for p in pairs], np.float32)


class ObservationBuilder:
    """Builds the observation vector from the learner's percepts (module docstring).

    Args:
        facts: The field's facts (pitch, landmarks).
        teammates: Teammate slots.
        opponents: Opponent slots.
    """

    def __init__(self, facts: FieldFacts, teammates: int, opponents: int) -> None:
        self.names = observation_names(teammates, opponents)
        self.low, self.high = _bounds(self.names)
        self.space = spaces.Box(self.low, self.high, dtype=np.float32)
        self.teammates, self.opponents = teammates, opponents
        self._length = facts.pitch.length_m
        self._half = (facts.pitch.half_length_m, facts.pitch.half_width_m)
        self._landmarks = facts.landmarks
        self.reset()

    def reset(self) -> None:
        """Forget the previous episode (pose, last ball sighting)."""
        self.localiser = Localiser(self._landmarks)
        self._last_ball: tuple[float, float, int] | None = None

    def build(
        self, percept: Percept, target_xy: tuple[float, float], time_left: float, dt_s: float
    ) -> FloatArray:
        """The observation of `percept` (also updates the pose and the ball's last sighting)."""
        length = self._length
        out = np.zeros(len(self.names), np.float32)
        ball = percept.ball
        if ball is not None:
            bx = ball.distance_m * math.cos(ball.angle_rad)
            by = ball.distance_m * math.sin(ball.angle_rad)
            out[0:4] = (1.0, ball.distance_m / length, math.cos(ball.angle_rad),
                        math.sin(ball.angle_rad))  # fmt: skip
            last = self._last_ball
            if last is not None and percept.observed_tick > last[2]:
                elapsed = (percept.observed_tick - last[2]) * dt_s
                out[4:6] = ((bx - last[0]) / elapsed / length, (by - last[1]) / elapsed / length)
            self._last_ball = (bx, by, percept.observed_tick)
        else:
            self._last_ball = None
        pose = self.localiser.update(percept)
        if pose is not None:
            out[6:11] = (1.0, pose.x / self._half[0], pose.y / self._half[1],
                         math.cos(pose.heading), math.sin(pose.heading))  # fmt: skip
            tx, ty = target_xy[0] - pose.x, target_xy[1] - pose.y
            angle = wrap_angle(math.atan2(ty, tx) - pose.heading)
            out[11:15] = (1.0, math.hypot(tx, ty) / length, math.cos(angle), math.sin(angle))
        self._players(percept, out)
        out[-1] = time_left
        return np.clip(out, self.low, self.high)

    def _players(self, percept: Percept, out: FloatArray) -> None:
        """Fill the teammate and opponent slots, nearest first."""
        if not (self.teammates or self.opponents):
            return
        own = percept.player.team
        mates = sorted((s for s in percept.players if s.team == own), key=lambda s: s.distance_m)
        known = sorted(
            (s for s in percept.players if s.team not in (own, None)), key=lambda s: s.distance_m
        )
        unknown = sorted((s for s in percept.players if s.team is None), key=lambda s: s.distance_m)
        start = 15
        for seen_list, slots in ((mates, self.teammates), ([*known, *unknown], self.opponents)):
            for i, seen in enumerate(seen_list[:slots]):
                j = start + 4 * i
                out[j : j + 4] = (1.0, seen.distance_m / self._length, math.cos(seen.angle_rad),
                                  math.sin(seen.angle_rad))  # fmt: skip
            start += 4 * slots


def state_space(players: int) -> spaces.Box:
    """The true state's space for this many players (:func:`state_vector`)."""
    size = 4 + 6 * players
    return spaces.Box(-MAX_STATE, MAX_STATE, shape=(size,), dtype=np.float32)


def state_vector(truth: Truth, order: tuple[PlayerRef, ...], facts: FieldFacts) -> FloatArray:
    """The true state for a privileged critic, in the field frame.

    Ball x / (L/2), y / (W/2), vx and vy over the ball's top speed; then per player in
    `order`: x / (L/2), y / (W/2), cos and sin of the heading, vx and vy over the players' top
    speed. Clipped to ±:data:`MAX_STATE`.
    """
    hl, hw = facts.pitch.half_length_m, facts.pitch.half_width_m
    vb, vp = facts.ball_max_speed_mps, facts.player_top_speed_mps
    ball = truth.ball
    values = [ball.x / hl, ball.y / hw, ball.vx / vb, ball.vy / vb]
    for ref in order:
        s = truth.players[ref]
        values += [s.x / hl, s.y / hw, math.cos(s.heading), math.sin(s.heading), s.vx / vp,
                   s.vy / vp]  # fmt: skip
    return np.clip(np.array(values, np.float32), -MAX_STATE, MAX_STATE)


# ----------------------------------------------------------------------------- rewards


def reward_weights(
    defaults: Mapping[str, float], given: Mapping[str, float] | None
) -> dict[str, float]:
    """The defaults with `given` weights replacing them.

    Raises:
        ValueError: An unknown term, or a weight that is not a finite number.
    """
    weights = dict(defaults)
    for name, value in (given or {}).items():
        if name not in weights:
            raise ValueError(f"unknown reward term {name!r} (terms: {', '.join(weights)})")
        if not isinstance(value, int | float) or not math.isfinite(value):
            raise ValueError(f"reward weight {name!r} must be a finite number, got {value!r}")
        weights[name] = float(value)
    return weights
