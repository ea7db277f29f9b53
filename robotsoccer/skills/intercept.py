"""Layer 1 as client minds: the interception defender and the shooter of the drill (paper §5).

**The defender** (:class:`DefenderMind`) follows the paper's training procedure (§5, the list
under Figure 6; BD = ball distance, BA = ball angle, TA = "the angle to turn *after* facing the
ball"), in our reading (``ta_mode="hold"``):

* while BD > the trigger distance (14 units; the drill's plan): TURN(BA) — watch and face the ball;
* the first time BD <= the trigger distance: TA is chosen by the behaviour from (BD, BA,
  previous BD), and the example (BD, BA, previous BD, TA) is recorded (:attr:`DefenderMind.
  example`, once per trial);
* from then on, at every percept: TURN(BA + TA), DASH(100) — two body actions in one decision
  (the arena runs them in order). TA is *held*, so ``straight`` (TA = 0) keeps watching the ball
  and moving directly toward it, as the paper says it does. ``ta_mode="every_see"`` recomputes
  TA at every percept instead (``random`` draws anew; the first TA is still the one recorded).

Details the paper leaves open, chosen here:

* **previous BD** is the distance of the previous *sighting* (the last percept that had the
  ball); on the first sighting it is BD itself.
* **Ball not seen**: DASH(100) only once triggered (the defender turned away from the ball,
  Figure 5); before the trigger, nothing (it has nothing to face).
* **Kicking**: when a kickable distance is given (Soccer Server: ``kickable_area_m``) and BD is
  within it, the defender kicks with power 100 away from its own goal: toward the bearing of
  ``"g r"`` + 180°, else (own goal not in view, as when it faces the shooter) toward ``"g l"``,
  else straight ahead. Robots without a kicker get no kickable distance: they block.
* **TA is clipped to ±90°**, a safety net only (random draws lie in ±45°; the net, lookup and
  analytic rules could in principle return anything).
* **Turn tolerance**: a turn smaller than ``turn_tolerance_rad`` is left out (a dash alone, or
  nothing before the trigger). 0 (the default, the Soccer Server) never leaves one out, as the
  paper's client; robots use a few times the camera's heading noise, because a robot stops to
  spin for a whole camera period on every turn however small (the robots' host).

**Behaviours** (:class:`Behaviour`), each a small :class:`TurnPolicy`
(:mod:`robotsoccer.skills.turn_policies`):

* ``still`` — never moves (the paper's "if the defender remains still" check); no policy;
* ``straight`` — TA = 0;
* ``random`` — TA uniform in [-45°, 45°] from the trial's ``"policy"`` stream (training);
* ``net`` — the interception net, evaluated in plain Python (no torch is imported; the file is
  read once per process, :func:`load_net_function`);
* ``lookup`` — the one-dimensional table BA -> TA (:class:`~learning.lookup.LookupTable`, a
  JSON file, read once per process);
* ``analytic`` — Mike Bowling's rule: the ball's motion vector from its two previous positions,
  extended x3, i.e. its position two sensory steps ahead; TA turns toward that point
  (:func:`learning.analytic.analytic_turn_angle_xy`).

**Heading estimate (analytic).** The two sightings must be expressed in one frame. The
defender keeps a heading estimate: the sum of the turns it commanded, a turn counting from the
first percept *observed* after the tick it was commanded on: the motion skill's record of turns
in flight (:class:`~robotsoccer.skills.motion.TurnsInFlight`) with a settle of one tick (on the
Soccer Server a turn runs in the next cycle, so this is exact up to the server's turn noise);
it decides on the percept as it came (neither the team minds' hold nor the set play's rotated
view: the turn toward BA + TA is re-aimed at every percept). Each sighting is stored as a
position in that reckoned frame. TA does not depend on the frame's orientation, only on the two
positions relative to the defender. Its own displacement is not reckoned: exact while it stands
(before the trigger, which is when ``hold`` chooses TA); in ``every_see`` mode, and on robots
(whose turns show in the camera only after the link, the turn itself and the camera latency),
the estimate is approximate.

**The shooter** (:class:`AimedShooterMind`) kicks once, at its first percept, toward the defender as
it sees it plus an aim offset (the paper's shooter "kicks the ball directly towards the
defender with a fixed power"), then stands.

Per-percept cost is a few float operations; the policies are called once per trial in ``hold``
mode. Angles are radians, left positive; distances metres.
"""

from __future__ import annotations

import math
import os
from enum import StrEnum
from pathlib import Path
from typing import Protocol

from field_models.arena import FieldFacts
from field_models.protocol import Action, Dash, Kick, Percept, PlayerRef, wrap_angle
from field_models.registry import field_facts
from field_models.seeding import Rng
from learning.interception_file import (
    TurnAngleFunction,
    load_turn_function,
    read_net_file,
    training_spread,
)
from learning.lookup import LookupTable
from robotsoccer.options import choice
from robotsoccer.skills.motion import TurnsInFlight, turn_then_go
from robotsoccer.skills.turn_policies import (
    AnalyticPolicy,
    LookupPolicy,
    NetPolicy,
    Point,
    RandomPolicy,
    TrainedDomainPolicy,
    straight_policy,
)


class Behaviour(StrEnum):
    """The defender's behaviours (module docstring)."""

    STILL = "still"
    STRAIGHT = "straight"
    RANDOM = "random"
    NET = "net"
    LOOKUP = "lookup"
    ANALYTIC = "analytic"

    @property
    def reads_model(self) -> bool:
        """Whether the behaviour reads a model file (``net``, ``lookup``)."""
        return self in (Behaviour.NET, Behaviour.LOOKUP)


class TaMode(StrEnum):
    """When TA is chosen: once at the trigger and held, or at every percept after it."""

    HOLD = "hold"
    EVERY_SEE = "every_see"


TA_CLIP_RAD = math.radians(90.0)
"""Any TA is clipped to ±90° (a safety net; see the module docstring)."""

DASH_POWER = 100.0
"""The defender's dash power (paper: "DASH()" at full power)."""

KICK_POWER = 100.0
"""The defender's clearing kick power."""


class TurnPolicy(Protocol):
    """A behaviour's rule for TA, the turn after facing the ball [rad, left positive]."""

    def __call__(
        self,
        ball_distance_m: float,
        ball_angle_rad: float,
        previous_ball_distance_m: float,
        previous_ball_xy_m: Point | None,
        ball_xy_m: Point,
        /,
    ) -> float:
        """TA from BD, BA and previous BD; the two sightings as positions in one frame [m]."""
        ...


# ----------------------------------------------------------------------------- model files

Triple = tuple[float, float, float]
"""(BD [m], BA [rad], previous BD [m]): a statistic of a net's three inputs."""

_NETS: dict[tuple[str, int, int, float], TurnAngleFunction] = {}
_TABLES: dict[tuple[str, int, int], LookupTable] = {}
_SPREADS: dict[tuple[str, int, int, float], tuple[Triple, Triple]] = {}


def file_key(path: str | os.PathLike[str]) -> tuple[str, int, int]:
    """Cache key of a model file: its resolved path, modification time and size."""
    resolved = Path(path).resolve()
    try:
        stat = resolved.stat()
    except OSError:
        return str(resolved), -1, -1  # the loader reports the missing file
    return str(resolved), stat.st_mtime_ns, stat.st_size


def load_net_function(
    path: str | os.PathLike[str], distance_factor: float = 1.0
) -> TurnAngleFunction:
    """The plain-Python net of a model file, read once per process (keyed by path and mtime).

    Never imports torch (:mod:`learning.interception_file`). `distance_factor`: 1 on the field
    it was trained on; :func:`transfer_distance_factor` on another.

    Raises:
        learning.features.ModelFileError: The file is missing, corrupt or not a net.
    """
    key = (*file_key(path), distance_factor)
    function = _NETS.get(key)
    if function is None:
        function = _NETS[key] = load_turn_function(path, distance_factor)
    return function


def trained_domain(
    policy: TurnPolicy, path: str | os.PathLike[str], distance_factor: float = 1.0
) -> TrainedDomainPolicy:
    """`policy` (the net of `path`) asked only inside that net's training domain.

    Raises:
        learning.features.ModelFileError: The file is missing, corrupt or not a net.
    """
    key = (*file_key(path), distance_factor)
    spread = _SPREADS.get(key)
    if spread is None:  # read once per process, as the net itself (load_net_function)
        spread = _SPREADS[key] = training_spread(read_net_file(path), distance_factor)
    return TrainedDomainPolicy(policy, *spread)


def transfer_distance_factor(path: str | os.PathLike[str], facts: FieldFacts) -> float:
    """How a net's distances scale onto the field of `facts`: this unit over its training field's.

    1 on the field it was trained on (or where its provenance names none). On another field a
    distance of k drill units here enters the net as k units of its own field (the transfer
    study: distances in drill units through the stored distance scale).

    Raises:
        learning.features.ModelFileError: The file is unreadable.
        ValueError: Its training field or preset is not known here.
    """
    origin = model_origin(path)
    if origin is None or Path(path).suffix != ".npz":
        return 1.0
    try:
        trained = field_facts(origin[0], origin[1])
    except (OSError, ValueError) as exc:  # PresetError is a ValueError
        raise ValueError(
            f"model {path} was trained on {origin[0]} `{origin[1]}`, which is not known here: "
            f"its distances cannot be put in this field's units ({exc})"
        ) from None
    return facts.unit_m / trained.unit_m


def load_lookup_table(path: str | os.PathLike[str]) -> LookupTable:
    """A lookup-table file, read once per process (keyed by path and mtime).

    Raises:
        learning.features.ModelFileError: The file is missing, corrupt or not a table.
    """
    key = file_key(path)
    table = _TABLES.get(key)
    if table is None:
        table = _TABLES[key] = LookupTable.load(path)
    return table


def model_origin(path: str | os.PathLike[str]) -> tuple[str, str] | None:
    """The (field model, preset) a net or lookup file was trained on; None where not recorded.

    A net's provenance names them; a lookup table built from a net records them in its
    ``built_from``.

    Raises:
        learning.features.ModelFileError: The file is unreadable.
    """
    key = file_key(path)
    if key not in _ORIGINS:
        if Path(path).suffix == ".npz":
            provenance = read_net_file(path).provenance
            _ORIGINS[key] = (provenance.field_model, provenance.preset)
        else:
            built = load_lookup_table(path).built_from
            model, preset = built.get("field_model"), built.get("preset")
            both = isinstance(model, str) and isinstance(preset, str)
            _ORIGINS[key] = (str(model), str(preset)) if both else None
    return _ORIGINS[key]


_ORIGINS: dict[tuple[str, int, int], tuple[str, str] | None] = {}


def model_decision(path: str | os.PathLike[str]) -> str:
    """What a model file decides: ``"turn"`` (TA; every lookup table) or ``"lead"``.

    Raises:
        learning.features.ModelFileError: The file is unreadable.
    """
    key = file_key(path)
    if key not in _DECISIONS:
        suffix = Path(path).suffix
        _DECISIONS[key] = read_net_file(path).schema.decision if suffix == ".npz" else "turn"
    return _DECISIONS[key]


_DECISIONS: dict[tuple[str, int, int], str] = {}


def make_policy(
    behaviour: Behaviour | str, rng: Rng, model: str = "", distance_factor: float = 1.0
) -> TurnPolicy | None:
    """The TA rule of a behaviour; None for ``still`` (which never moves).

    Args:
        behaviour: A :class:`Behaviour` (or its name).
        rng: The trial's ``"policy"`` stream (used by ``random``).
        model: The model file of ``net`` (``.npz``) or ``lookup`` (JSON).
        distance_factor: The net's distance factor (:func:`transfer_distance_factor`).

    Raises:
        ValueError: Unknown behaviour, or a model file missing for ``net``/``lookup``.
        learning.features.ModelFileError: The model file is unreadable.
    """
    kind = check_behaviour(behaviour, model)
    if kind is Behaviour.STILL:
        return None
    if kind is Behaviour.STRAIGHT:
        return straight_policy
    if kind is Behaviour.RANDOM:
        return RandomPolicy(rng)
    if kind is Behaviour.NET:
        return NetPolicy(load_net_function(model, distance_factor))
    if kind is Behaviour.LOOKUP:
        return LookupPolicy(load_lookup_table(model))
    return AnalyticPolicy()


def check_behaviour(behaviour: Behaviour | str, model: str = "") -> Behaviour:
    """The behaviour named, checked: known, and given a model file where it needs one.

    Raises:
        ValueError: An unknown behaviour (listing the known ones), or no model file.
    """
    kind = choice(Behaviour, behaviour, "behaviour")
    if kind.reads_model and not model:
        raise ValueError(f"behaviour {kind.value!r} needs a model file (option model=...)")
    return kind


# ----------------------------------------------------------------------------- minds


class DefenderMind:
    """The interception defender (module docstring): watch, choose TA at the trigger, dash.

    Args:
        policy: The behaviour's TA rule; None stands still (``still``).
        trigger_distance_m: TA is chosen the first time BD is at most this (the drill plan's) [m].
        ta_mode: When TA is chosen (:class:`TaMode`, or its name).
        kickable_distance_m: Kick (clear) when BD is at most this [m]; None never kicks.
        turn_tolerance_rad: Leave out turns smaller than this [rad]; 0 keeps every turn.
        ta_clip_rad: |TA| is clipped to this [rad].
        decision_period_ticks: Decide on a percept only when at least this many ticks have
            passed since the last percept it decided on, and ignore the others entirely, as a
            slower sensor would (previous BD is then the previous *decision's* sighting); 0
            decides on every percept. The ``task`` scaling sets it (drill module docstring).

    Attributes:
        example: (BD [m], BA [rad], previous BD [m], TA [rad]) recorded at the trigger, or None.
        triggered: True once BD came within the trigger distance.
        turn_angle_rad: The TA in use (0 before the trigger).
    """

    def __init__(
        self,
        policy: TurnPolicy | None,
        trigger_distance_m: float,
        *,
        ta_mode: TaMode | str = TaMode.HOLD,
        kickable_distance_m: float | None = None,
        turn_tolerance_rad: float = 0.0,
        ta_clip_rad: float = TA_CLIP_RAD,
        decision_period_ticks: int = 0,
    ) -> None:
        self.policy = policy
        self.decision_period_ticks = decision_period_ticks
        self._next_decision_tick = -1
        self.trigger_distance_m = trigger_distance_m
        self.every_see = choice(TaMode, ta_mode, "ta_mode") is TaMode.EVERY_SEE
        self.kickable_distance_m = kickable_distance_m
        self.turn_tolerance_rad = turn_tolerance_rad
        self.ta_clip_rad = ta_clip_rad
        self.example: tuple[float, float, float, float] | None = None
        self.triggered = False
        self.turn_angle_rad = 0.0
        self._previous_distance_m: float | None = None
        self._previous_xy: Point | None = None
        # Its turns: a turn shows in percepts observed after the tick it was commanded on.
        self.turns = TurnsInFlight(settle=1)

    def decides_at(self, tick: int) -> bool:
        """Whether a percept delivered at `tick` is one this defender decides on."""
        return not self.decision_period_ticks or tick >= self._next_decision_tick

    def act(self, percept: Percept) -> tuple[Action, ...]:
        """One decision per percept (module docstring)."""
        policy = self.policy
        if policy is None:
            return ()
        if self.decision_period_ticks:
            if percept.tick < self._next_decision_tick:
                return ()
            self._next_decision_tick = percept.tick + self.decision_period_ticks
        ball = percept.ball
        if ball is None:
            return (Dash(DASH_POWER),) if self.triggered else ()
        bd, ba = ball.distance_m, ball.angle_rad
        heading = self._heading_at(percept.observed_tick) + ba
        xy = (bd * math.cos(heading), bd * math.sin(heading))
        previous_bd = bd if self._previous_distance_m is None else self._previous_distance_m
        previous_xy = self._previous_xy
        self._previous_distance_m, self._previous_xy = bd, xy
        if not self.triggered:
            if bd > self.trigger_distance_m:
                return self._turn(percept.tick, ba, ())
            self.triggered = True
            self.turn_angle_rad = self._choose(policy, bd, ba, previous_bd, previous_xy, xy)
            self.example = (bd, ba, previous_bd, self.turn_angle_rad)
        elif self.every_see:
            self.turn_angle_rad = self._choose(policy, bd, ba, previous_bd, previous_xy, xy)
        if self.kickable_distance_m is not None and bd <= self.kickable_distance_m:
            return (Kick(KICK_POWER, clearing_direction(percept)),)
        return self._turn(percept.tick, ba + self.turn_angle_rad, (Dash(DASH_POWER),))

    def _choose(
        self,
        policy: TurnPolicy,
        bd: float,
        ba: float,
        previous_bd: float,
        previous_xy: Point | None,
        xy: Point,
    ) -> float:
        ta = policy(bd, ba, previous_bd, previous_xy, xy)
        clip = self.ta_clip_rad
        return clip if ta > clip else -clip if ta < -clip else ta

    def _turn(self, tick: int, angle: float, then: tuple[Action, ...]) -> tuple[Action, ...]:
        """Turn by `angle` (wrapped) then `then`; the turn is left out below the tolerance."""
        actions = turn_then_go(wrap_angle(angle), then, least_turn_rad=self.turn_tolerance_rad)
        self.turns.note(actions, tick)
        return actions

    def _heading_at(self, observed_tick: int) -> float:
        """The reckoned heading the percept observed at `observed_tick` was taken with."""
        self.turns.in_flight(observed_tick)
        return self.turns.shown_rad


def clearing_direction(percept: Percept) -> float:
    """Kick direction away from the own goal: "g r" + 180°, else toward "g l", else ahead."""
    own = percept.landmark("g r")
    if own is not None:
        return wrap_angle(own.angle_rad + math.pi)
    other = percept.landmark("g l")
    if other is not None:
        return other.angle_rad
    return 0.0


class AimedShooterMind:
    """Kick once, at the first percept, toward the defender as seen plus an aim offset (§5).

    Args:
        target: The defender.
        kick_power: Kick power (server units; robots: kicker power).
        aim_offset_rad: Added to the seen direction (the paper's "aims slightly wide") [rad].

    The target is the seen player with its team and number, else the one seen player of unknown
    identity or of its team, else straight ahead (the coach placed the shooter facing it).
    """

    def __init__(self, target: PlayerRef, kick_power: float, aim_offset_rad: float = 0.0) -> None:
        self.target = target
        self.kick_power = kick_power
        self.aim_offset_rad = aim_offset_rad
        self.kicked = False
        self.done = False

    def act(self, percept: Percept) -> tuple[Action, ...]:
        """Kick at the first percept, then stand (and want no more percepts: ``done``)."""
        if self.kicked:
            return ()
        self.kicked = self.done = True
        return (Kick(self.kick_power, self._target_angle(percept) + self.aim_offset_rad),)

    def _target_angle(self, percept: Percept) -> float:
        target = self.target
        fallback = None
        for seen in percept.players:
            if seen.team == target.team and seen.number == target.number:
                return seen.angle_rad
            if seen.team in (None, target.team) and fallback is None:
                fallback = seen.angle_rad
        return 0.0 if fallback is None else fallback
