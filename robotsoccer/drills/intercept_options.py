"""The interception drill's options as one typed record (:class:`InterceptOptions`).

The drill (:mod:`robotsoccer.drills.intercept`) is built from these options, by keyword
(``InterceptDrill(behaviour="net", model=...)``, ``make_drill("intercept", {...})``, a command
line's ``--option NAME=VALUE``) or from a record (``InterceptDrill(InterceptOptions(...))``).
Text values (a command line's) are turned into their kinds here, once, and every option is
checked here, so a bad one is refused in one line before any field is built. What each option
does is told where it acts: the launch plan (:mod:`robotsoccer.drills.intercept_plan`), the
judge (:mod:`robotsoccer.drills.intercept_judge`) and the drill.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from enum import StrEnum

from robotsoccer.options import choice, duration, flag
from robotsoccer.skills.intercept import Behaviour, TaMode, check_behaviour

DEFAULT_SECTOR_DEG = 45.0
"""Half-width of the ball's start bearing (calibrated: the paper draws the sector, no number)."""


class Launch(StrEnum):
    """Who sets the ball moving (:mod:`robotsoccer.drills.intercept_plan`, "Launch")."""

    AUTO = "auto"
    SHOOTER = "shooter"
    COACH = "coach"


class Decision(StrEnum):
    """What the defender decides at the trigger (:mod:`robotsoccer.drills.intercept`)."""

    TURN = "turn"
    LEAD = "lead"


class ClientKind(StrEnum):
    """How the defender's client acts (:mod:`robotsoccer.drills.intercept`, "Defender")."""

    SEE = "see"
    CYCLE = "cycle"


class Shot(StrEnum):
    """Where the ball is aimed (:class:`InterceptOptions`, ``shot``)."""

    DEFENDER = "defender"
    GOAL_MOUTH = "goal_mouth"


class Scaling(StrEnum):
    """How the paper's drill is carried to a field (:mod:`robotsoccer.drills.intercept_plan`)."""

    AUTO = "auto"
    LITERAL = "literal"
    SENSOR_UPDATES = "sensor_updates"
    TASK = "task"


@dataclass(frozen=True, slots=True)
class InterceptOptions:
    """The options of one interception drill, checked (text values turned into their kinds).

    Attributes:
        behaviour: The defender's behaviour (:class:`~robotsoccer.skills.intercept.Behaviour`).
        model: Model file for ``net`` (``.npz``) or ``lookup`` (JSON).
        ta_mode: ``hold`` (TA chosen once, at the trigger) or ``every_see``.
        aim_offset_deg: The shooter aims this far left of the defender [deg] (paper: 4° wide).
        kick_power: The shooter's kick power in the literal drill (scales the matched launch).
        launch: ``auto``, ``shooter`` or ``coach`` (:mod:`robotsoccer.drills.intercept_plan`).
        scaling: ``auto``, ``literal``, ``sensor_updates`` or ``task`` (the same module).
        sector_deg: Half-width of the ball's start bearing around -x from the defender [deg].
        max_time_s: Simulated time after which the trial is a MISS [s].
        defender_kick: Let the defender clear a ball within reach of an aimable kick; False
            (default): it stops the ball with its body (a calibrated choice,
            :mod:`robotsoccer.drills.intercept`).
        transfer: Accept a model file trained on another field model or preset (the
            transfer study); False (default) refuses one whose provenance is not this field.
        trigger_scale: Multiply the plan's trigger distance by this (an ablation; 1: as
            planned).
        launch_speed_scale: Multiply the plan's launch speed by this (an ablation; the noise
            period and the trigger stay as planned).
        turn_tolerance_deg: The defender's turn tolerance [deg] instead of the plan's (an
            ablation); None: the plan's (three sigmas of the sensor's heading noise).
        decision: ``turn`` (the paper's TA) or ``lead`` (a meeting time,
            :mod:`robotsoccer.skills.lead`).
        shot: ``defender`` (the paper's: at the defender, plus the aim offset) or
            ``goal_mouth`` (at a point drawn uniformly across the goal mouth).
        launch_speed_mps: The ball's launch speed [m/s] in place of the plan's; 0: the plan's.
        launch_speed_max_mps: With `launch_speed_mps`, draw each trial's speed uniformly
            between the two [m/s] (a coach launch); 0: one speed. The plan's numbers
            (arrival time, ...) are those of the middle speed.
        client: ``see`` (the paper's client: decides at each see, "turn, then dash") or
            ``cycle`` (a command every cycle from a world model,
            :mod:`robotsoccer.skills.cycle`; the turn decision only, no decision period).
        lead_time_scale: Multiply a lead net's τ by this; 1 (default): τ in seconds as the
            net gives it. With ``transfer=true`` a net's distances are in drill units and its τ
            stays a time in seconds; the transfer study's check rows give the test drill's
            flight time over the training drill's here, so that τ keeps its share of the flight
            (:func:`robotsoccer.experiments.transfer.lead_time_scale`).

    Raises:
        ValueError: An unknown behaviour, TA mode, launch or scaling, a missing model file
            name, or a sector outside [0, 90] or a time limit that is not positive, or a scale
            that is not positive or a negative tolerance.
    """

    behaviour: Behaviour = Behaviour.STRAIGHT
    model: str = ""
    ta_mode: TaMode = TaMode.HOLD
    aim_offset_deg: float = 0.0
    kick_power: float = 100.0
    launch: Launch = Launch.AUTO
    scaling: Scaling = Scaling.AUTO
    sector_deg: float = DEFAULT_SECTOR_DEG
    max_time_s: float = 10.0
    defender_kick: bool = False
    transfer: bool = False
    trigger_scale: float = 1.0
    launch_speed_scale: float = 1.0
    turn_tolerance_deg: float | None = None
    decision: Decision = Decision.TURN
    shot: Shot = Shot.DEFENDER
    launch_speed_mps: float = 0.0
    launch_speed_max_mps: float = 0.0
    client: ClientKind = ClientKind.SEE
    lead_time_scale: float = 1.0

    def __post_init__(self) -> None:
        # The checks run in this order so that, of several bad options, the same one is named
        # first whatever way the drill was built.
        self._set("behaviour", check_behaviour(self.behaviour, self.model))
        self._set("client", choice(ClientKind, self.client, "client"))
        self._set("decision", choice(Decision, self.decision, "decision"))
        self._set("shot", choice(Shot, self.shot, "shot"))
        self._check_decision()
        self._check_launch_speeds()
        self._check_lead_time_scale()
        self._set("ta_mode", choice(TaMode, self.ta_mode, "ta_mode"))
        self._set("launch", choice(Launch, self.launch, "launch"))
        self._set("scaling", choice(Scaling, self.scaling, "scaling"))
        self._check_numbers()
        self._set("defender_kick", flag("defender_kick", self.defender_kick))
        self._set("transfer", flag("transfer", self.transfer))

    def _set(self, name: str, value: object) -> None:
        """Store a checked value (the record is frozen once built)."""
        object.__setattr__(self, name, value)

    def _check_decision(self) -> None:
        """Refuse a decision that the behaviour or the client cannot play."""
        if self.decision is Decision.LEAD and self.behaviour is Behaviour.LOOKUP:
            raise ValueError("decision 'lead' has no lookup table: choose another behaviour")
        if self.decision is Decision.LEAD and self.client is ClientKind.CYCLE:
            raise ValueError("client 'cycle' plays the turn decision: use client=see for 'lead'")

    def _check_launch_speeds(self) -> None:
        """A launch speed >= 0; a range needs 0 < launch_speed_mps <= launch_speed_max_mps."""
        given, given_max = self.launch_speed_mps, self.launch_speed_max_mps
        if not (math.isfinite(float(given)) and float(given) >= 0.0):
            raise ValueError(f"launch_speed_mps must be >= 0, got {given!r}")
        low, high = float(given), float(given_max)
        if high and not (math.isfinite(high) and high >= low > 0.0):
            raise ValueError(
                "launch_speed_max_mps needs 0 < launch_speed_mps <= launch_speed_max_mps, got "
                f"{given!r} and {given_max!r}"
            )
        self._set("launch_speed_mps", low)
        self._set("launch_speed_max_mps", high)

    def _check_lead_time_scale(self) -> None:
        """A finite scale > 0, other than 1 only for a lead net."""
        scale = self.lead_time_scale
        if not (math.isfinite(float(scale)) and float(scale) > 0.0):
            raise ValueError(f"lead_time_scale must be a finite number > 0, got {scale!r}")
        if float(scale) != 1.0 and not (
            self.decision is Decision.LEAD and self.behaviour is Behaviour.NET
        ):
            raise ValueError("lead_time_scale scales a lead net: give decision=lead behaviour=net")
        self._set("lead_time_scale", float(scale))

    def _check_numbers(self) -> None:
        """The sector, the time limit, the kick power, the ablation scales and tolerance."""
        if not 0.0 <= self.sector_deg <= 90.0:
            raise ValueError(f"sector_deg must be in [0, 90], got {self.sector_deg!r}")
        max_time_s = duration("max_time_s", self.max_time_s)
        if not self.kick_power > 0.0:
            raise ValueError(f"kick_power must be > 0, got {self.kick_power!r}")
        for name in ("trigger_scale", "launch_speed_scale"):
            scale = getattr(self, name)
            if not float(scale) > 0.0:
                raise ValueError(f"{name} must be > 0, got {scale!r}")
        tolerance = self.turn_tolerance_deg
        if tolerance is not None and not float(tolerance) >= 0.0:
            raise ValueError(f"turn_tolerance_deg must be >= 0, got {tolerance!r}")
        self._set("trigger_scale", float(self.trigger_scale))
        self._set("launch_speed_scale", float(self.launch_speed_scale))
        self._set("turn_tolerance_deg", None if tolerance is None else float(tolerance))
        self._set("kick_power", float(self.kick_power))
        self._set("sector_deg", float(self.sector_deg))
        self._set("max_time_s", float(max_time_s))
