"""The interception drill (paper §5, Figure 6): a shooter kicks at a defender who must stop it.

The drill's parts, each in a module of its own: its options, one typed record
(:mod:`robotsoccer.drills.intercept_options`); the geometry and the launch on a field, scaled
from the paper's (:mod:`robotsoccer.drills.intercept_plan`); the coach's labels SAVE, GOAL and
MISS (:mod:`robotsoccer.drills.intercept_judge`); the defender's mind
(:mod:`robotsoccer.drills.intercept_minds`). This module is the drill that places the players,
gives them their minds and reads the verdict. Placement draws, in this order, the
distance and the bearing from ``rngs["placement"]``.

**Defender** (:mod:`robotsoccer.skills.intercept`): the behaviour (option ``behaviour``: still,
straight, random, net, lookup, analytic; ``model`` the file of net/lookup), ``ta_mode`` ("hold":
TA chosen once at the trigger; "every_see"). By default it stops the ball with its body
(``defender_kick=False``), a calibrated choice: the paper's §5 baselines (still hit 35%, straight
53%) are matched that way, and the 1998 kickable area (1.885 m) is a far bigger target than the
body (0.885 m). With ``defender_kick=True`` it clears a ball within reach of an aimable kick with
power 100 away from its goal. It leaves out turns smaller than three sigmas of the sensor's
heading noise (a robot stops to spin for a whole camera period on each turn; 0 on the server).
Option ``client``: ``see`` (default, the paper's client: one decision per see, "turn, then
dash") or ``cycle`` (a command every cycle from a world model, :mod:`robotsoccer.skills.cycle`;
TA held, no decision period; it runs on the one-trial path, not the batch).

:meth:`InterceptDrill.data` returns the defender's example (BD [m], BA [rad], previous BD [m],
TA [rad]) recorded at the trigger, or ``()`` when no decision happened.
:meth:`InterceptDrill.measures` returns, for a trial whose defender triggered, how far it got
from the trigger to the verdict (in units), that time, and the sensor updates in it.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

from field_models.arena import Arena, FieldFacts
from field_models.protocol import Mind, PlayerRef, wrap_angle
from field_models.seeding import TrialRngs
from robotsoccer.drills.base import Verdict
from robotsoccer.drills.intercept_judge import DEFLECTED_STOPPED, STOPPED_SHORT, InterceptJudge
from robotsoccer.drills.intercept_minds import AnyDefender, defender_mind
from robotsoccer.drills.intercept_options import (
    Decision,
    InterceptOptions,
    Launch,
    Shot,
)
from robotsoccer.drills.intercept_plan import (
    DEFENDER,
    SHOOTER,
    LaunchPlan,
    ablated,
    cached_launch_plan,
)
from robotsoccer.skills.intercept import (
    AimedShooterMind,
    Behaviour,
    model_decision,
    model_origin,
    transfer_distance_factor,
)


class InterceptDrill:
    """The paper's Figure 6 trial on any field model; labels SAVE, GOAL or MISS.

    Built from an :class:`~robotsoccer.drills.intercept_options.InterceptOptions` record, or
    from its fields as keywords (the registry's ``make_drill`` and a command line's
    ``--option NAME=VALUE`` give them so); :data:`OPTIONS` names the record, whose fields are
    the drill's option names.

    Args:
        options: The drill's options; None: built from `keywords`.
        **keywords: The options' fields by name, where `options` is not given.

    Raises:
        ValueError: A bad option (:class:`~robotsoccer.drills.intercept_options.InterceptOptions`),
            or both a record and keywords.
    """

    name: str = "intercept"
    labels: tuple[str, ...] = ("SAVE", "GOAL", "MISS")
    OPTIONS = InterceptOptions

    def __init__(self, options: InterceptOptions | None = None, /, **keywords: Any) -> None:
        if options is not None and keywords:
            raise ValueError("give the intercept drill an options record or keywords, not both")
        self.options = options if options is not None else InterceptOptions(**keywords)
        o = self.options
        self.behaviour, self.model, self.ta_mode = o.behaviour, o.model, o.ta_mode
        self.client, self.decision, self.shot = o.client, o.decision, o.shot
        self.launch, self.scaling, self.kick_power = o.launch, o.scaling, o.kick_power
        self.launch_speed_mps, self.launch_speed_max_mps = (
            o.launch_speed_mps,
            o.launch_speed_max_mps,
        )
        self.lead_time_scale = o.lead_time_scale
        self.trigger_scale, self.launch_speed_scale = o.trigger_scale, o.launch_speed_scale
        self.turn_tolerance_deg = o.turn_tolerance_deg
        self.aim_offset_rad = math.radians(o.aim_offset_deg)
        self.sector_rad = math.radians(o.sector_deg)
        self.max_time_s = o.max_time_s
        self.defender_kick, self.transfer = o.defender_kick, o.transfer
        self.defender_mind: AnyDefender | None = None
        self._aim_offset_trial_rad = self.aim_offset_rad
        self._judge_state: InterceptJudge | None = None
        self._plan: LaunchPlan | None = None
        self._plan_facts: FieldFacts | None = None

    def players(self) -> tuple[PlayerRef, ...]:
        """Shooter and defender."""
        return (SHOOTER, DEFENDER)

    def plan(self, arena: Arena) -> LaunchPlan:
        """This drill's launch plan on `arena`'s field (cached per field)."""
        facts = arena.facts
        if facts is not self._plan_facts:  # one look-up per trial, not one per call
            self._plan, self._plan_facts = self.checked_plan(facts), facts
        assert self._plan is not None
        return self._plan

    def plan_for(self, facts: FieldFacts) -> LaunchPlan:
        """This drill's launch plan on a field (cached per field), with the ablations applied."""
        plan = cached_launch_plan(facts, self.kick_power, self.launch, self.scaling)
        speed_scale = self.launch_speed_scale
        if self.launch_speed_mps:
            speed = self.launch_speed_mps
            if self.launch_speed_max_mps:
                speed = 0.5 * (speed + self.launch_speed_max_mps)
            speed_scale *= speed / plan.launch_speed_mps
        return ablated(plan, facts, self.trigger_scale, speed_scale, self.turn_tolerance_deg)

    def distance_factor(self, facts: FieldFacts) -> float:
        """The net's distance factor on this field (1 on the field it was trained on).

        A transfer run applying a net trained on another field converts distances through
        :func:`~robotsoccer.skills.intercept.transfer_distance_factor`.
        """
        if not (self.transfer and self.model and self.behaviour is Behaviour.NET):
            return 1.0
        return transfer_distance_factor(self.model, facts)

    def checked_plan(self, facts: FieldFacts) -> LaunchPlan:
        """The plan on a field, after refusing a model file trained elsewhere (not a transfer).

        Raises:
            ValueError: The model file was trained on another field and ``transfer`` is off.
        """
        self._check_origin(facts)
        self._check_decision()
        return self.plan_for(facts)

    def _check_decision(self) -> None:
        """Refuse a model file that decides the other thing (a TA net for the lead, ...)."""
        if not self.model:
            return
        decides = model_decision(self.model)
        if decides != self.decision.value:
            raise ValueError(
                f"model {self.model} decides the {decides}, this run's decision is "
                f"{self.decision.value!r}: train a {self.decision.value} model for it"
            )

    def _check_origin(self, facts: FieldFacts) -> None:
        """Refuse a model file trained on another field (unless this is a transfer run)."""
        if not self.model or self.transfer:
            return
        origin = model_origin(self.model)
        here = (facts.model, facts.preset)
        if origin is None or (origin[0], Path(origin[1]).stem) != (here[0], Path(here[1]).stem):
            trained = "an unrecorded field" if origin is None else f"{origin[0]} `{origin[1]}`"
            raise ValueError(
                f"model {self.model} was trained on {trained}, this run is {here[0]} "
                f"`{here[1]}`: give option transfer=true to test it across fields"
            )

    def field_settings(self, facts: FieldFacts) -> dict[str, float | bool]:
        """The field settings the drill needs where they differ from the field's own.

        The plan's ball-noise period; every landmark in the percepts for the lead decision.
        """
        plan = self.plan_for(facts)
        settings: dict[str, float | bool] = {}
        if not math.isclose(plan.noise_period_s, facts.ball_noise_period_s):
            settings["ball_noise_period_s"] = plan.noise_period_s
        if self.decision is Decision.LEAD:
            settings["all_landmarks"] = True  # the lead defender localises itself
        return settings

    def inputs(self) -> tuple[str, ...]:
        """The model file of ``net`` or ``lookup``."""
        return (self.model,) if self.model else ()

    def setup(self, arena: Arena, rngs: TrialRngs) -> None:
        """Place defender, ball and shooter (and launch the ball for a coach launch)."""
        plan = self.plan(arena)
        rng = rngs["placement"]
        distance = float(rng.uniform(plan.min_distance_m, plan.max_distance_m))
        bearing = float(rng.uniform(-self.sector_rad, self.sector_rad))
        target = None
        if self.shot is Shot.GOAL_MOUTH:
            pitch = arena.facts.pitch
            half = 0.5 * pitch.goal_width_m - pitch.ball_radius_m
            target = float(rng.uniform(-half, half))
        speed = None
        if self.launch_speed_max_mps:
            if plan.launch is not Launch.COACH:
                raise ValueError("launch_speed_max_mps needs a coach launch (launch=coach)")
            speed = float(rng.uniform(self.launch_speed_mps, self.launch_speed_max_mps))
        self.place(arena, plan, distance, bearing, target, speed)

    def place(
        self,
        arena: Arena,
        plan: LaunchPlan,
        distance_m: float,
        bearing_rad: float,
        target_y_m: float | None = None,
        speed_mps: float | None = None,
    ) -> None:
        """Place everything for a ball `distance_m` from the defender at `bearing_rad` off -x.

        The coach's deterministic half of :meth:`setup` (tests place by hand through it).
        `target_y_m`: aim at this point of the defended goal line instead of the defender;
        `speed_mps`: a coach launch at this speed instead of the plan's.
        """
        dx, dy = plan.defender_x_m, 0.0
        ux, uy = math.cos(bearing_rad), math.sin(bearing_rad)  # ball -> defender
        bx, by = dx - distance_m * ux, dy - distance_m * uy
        offset = self.aim_offset_rad
        if target_y_m is not None:
            line_x = arena.facts.pitch.half_length_m
            offset += wrap_angle(math.atan2(target_y_m - by, line_x - bx) - bearing_rad)
        self._aim_offset_trial_rad = offset
        aim = bearing_rad + offset
        ax, ay = math.cos(aim), math.sin(aim)
        gap = plan.shooter_gap_m
        if plan.launch is Launch.COACH:
            speed = plan.launch_speed_mps if speed_mps is None else speed_mps
            arena.place_ball(bx, by, speed * ax, speed * ay)
            arena.place_player(SHOOTER, bx - gap * ux, by - gap * uy, bearing_rad)
        elif not plan.aimable_kick:  # a kicker fires along the heading: aim the shooter
            arena.place_ball(bx, by)
            arena.place_player(SHOOTER, bx - gap * ax, by - gap * ay, aim)
        else:  # the kick takes a direction: face the defender, kick wide
            arena.place_ball(bx, by)
            arena.place_player(SHOOTER, bx - gap * ux, by - gap * uy, bearing_rad)
        arena.place_player(DEFENDER, dx, dy, bearing_rad + math.pi)
        self.start_judging(arena)
        self.defender_mind = None

    def start_judging(self, arena: Arena) -> None:
        """Take the ball's and the defender's present positions as the trial's start.

        :meth:`place` calls it; a test that moves objects by hand afterwards calls it again.
        """
        ball = arena.ball_state()
        defender = arena.player_state(DEFENDER)
        plan = self.plan(arena)
        self._judge_state = InterceptJudge(
            arena,
            plan,
            (ball.x, ball.y),
            (defender.x, defender.y),
            touches=self.shot is Shot.GOAL_MOUTH,
        )

    def minds(self, arena: Arena, rngs: TrialRngs) -> dict[PlayerRef, Mind]:
        """The defender (``intercept_minds``), and the shooter when it launches the ball."""
        plan = self.plan(arena)
        factor = self.distance_factor(arena.facts)
        defender = defender_mind(self.options, arena, plan, rngs, factor)
        self.defender_mind = defender
        minds: dict[PlayerRef, Mind] = {DEFENDER: defender}
        if plan.launch is Launch.SHOOTER:
            aim = self._aim_offset_trial_rad if plan.aimable_kick else 0.0
            minds[SHOOTER] = AimedShooterMind(DEFENDER, plan.kick_power, aim)
        return minds

    def judge(self, arena: Arena) -> Verdict | None:
        """SAVE, GOAL, MISS or carry on (:mod:`robotsoccer.drills.intercept_judge`)."""
        state = self._judge_state
        if state is None:
            raise RuntimeError("judge() before setup()")
        mind = self.defender_mind
        if mind is not None and mind.triggered and state.trigger is None:
            state.note_trigger(arena)
        return state.judge(arena)

    def timeout(self, arena: Arena) -> Verdict:
        """Out of time: a deflected ball that stopped is a SAVE; else the ball stopped short."""
        state = self._judge_state
        if state is not None:
            state.finish(arena)
            if state.deflected:
                return Verdict("SAVE", DEFLECTED_STOPPED)
        return Verdict("MISS", STOPPED_SHORT)

    def data(self) -> tuple[float, ...]:
        """The defender's example (BD, BA, previous BD, TA), or () without a decision."""
        mind = self.defender_mind
        if mind is None or mind.example is None:
            return ()
        return mind.example

    def measures(self) -> dict[str, float]:
        """From the trigger to the verdict: the defender's travel [units], time, sensor updates.

        Empty when the defender never triggered.
        """
        state = self._judge_state
        if state is None or state.trigger is None or state.end is None:
            return {}
        (t0, x0, y0), (t1, x1, y1) = state.trigger, state.end
        plan = state.plan
        seconds = t1 - t0
        return {
            "defender_travel_units": math.hypot(x1 - x0, y1 - y0) / plan.unit_m,
            "trigger_to_end_s": seconds,
            "updates_after_trigger": seconds / plan.sensor_period_s,
        }
