"""What the drills on both learned layers share (the pass drill, the set play, the match).

:class:`LayeredDrill` holds layer 1's plan on a field, the check that the tree and net were
trained on it, and the builders of layer 1's interception for receivers and defenders on the
see-triggered and the per-cycle client; :func:`load_evaluator` reads a tree once per process;
:func:`control_reach` is the coach's "control of the ball".
"""

from __future__ import annotations

import functools
import math
import os
from pathlib import Path
from typing import Any

from field_models.arena import FieldFacts
from field_models.protocol import Mind
from field_models.seeding import Rng
from learning.pass_boost import load_pass_boost
from learning.pass_features import PASS_SCHEMA
from learning.pass_tree_file import load_pass_tree
from robotsoccer.drills.intercept_minds import cycle_defender
from robotsoccer.drills.intercept_options import Launch, Scaling
from robotsoccer.drills.intercept_plan import LaunchPlan, cached_launch_plan, decision_ticks
from robotsoccer.skills.cycle import CycleDefenderMind
from robotsoccer.skills.intercept import (
    Behaviour,
    DefenderMind,
    file_key,
    load_net_function,
    make_policy,
    model_decision,
    transfer_distance_factor,
)
from robotsoccer.skills.lead import LeadDefenderMind
from robotsoccer.skills.passing import Chooser, PassEvaluator

CONTROL_MARGIN_UNITS = 0.25
"""On a field without a kick, touching plus this much is "control" of the ball."""


@functools.lru_cache(maxsize=8)
def _model_file(key: tuple[str, int, int], boost: bool) -> tuple[PassEvaluator, dict[str, Any]]:
    """A tree or boosted-trees file, read once per process (keyed by path, mtime and size)."""
    if boost:
        return load_pass_boost(key[0], schema=PASS_SCHEMA)
    return load_pass_tree(key[0], schema=PASS_SCHEMA)


def load_evaluator(
    path: str | os.PathLike[str], *, boost: bool = False
) -> tuple[PassEvaluator, dict[str, Any]]:
    """The evaluator in `path` and its provenance (cached per process while it is unchanged)."""
    return _model_file(file_key(path), boost)


class LayeredDrill:
    """What a drill on both learned layers shares: layer 1's plan and the model files' origins.

    A subclass sets ``model`` (the pass tree or boosted trees, or ""), ``chooser``, ``net`` (the
    interception net, or ""), ``transfer`` and ``_checked`` (None) in its constructor.
    """

    model: str
    chooser: Chooser
    net: str
    transfer: bool
    _checked: FieldFacts | None

    def plan(self, facts: FieldFacts) -> LaunchPlan:
        """Layer 1's plan on this field: launch, trigger distance, turn tolerance."""
        return cached_launch_plan(facts, 100.0, Launch.AUTO, Scaling.AUTO)

    def field_settings(self, facts: FieldFacts) -> dict[str, float]:
        """Layer 1's ball-noise period where it differs from the field's own."""
        plan = self.plan(facts)
        if math.isclose(plan.noise_period_s, facts.ball_noise_period_s):
            return {}
        return {"ball_noise_period_s": plan.noise_period_s}

    def inputs(self) -> tuple[str, ...]:
        """The tree and net files the trials read."""
        return tuple(f for f in (self.model, self.net) if f)

    def _check_origins(self, facts: FieldFacts) -> None:
        """Refuse a tree or net trained on another field (unless this is a transfer run)."""
        if facts is self._checked:
            return
        self._checked = facts
        if self.transfer:
            return
        here = (facts.model, Path(facts.preset).stem)
        if self.model:
            _, provenance = load_evaluator(self.model, boost=self.chooser is Chooser.BOOST)
            origin = (str(provenance.get("field_model")), Path(str(provenance.get("preset"))).stem)
            if origin != here:
                raise ValueError(
                    f"tree {self.model} was trained on {origin[0]} `{origin[1]}`, this run is "
                    f"{here[0]} `{here[1]}`: give option transfer=true to test it across fields"
                )
        if self.net:
            from robotsoccer.skills.intercept import model_origin

            net_origin = model_origin(self.net)
            if net_origin is None or (net_origin[0], Path(net_origin[1]).stem) != here:
                trained = "an unrecorded field" if net_origin is None else str(net_origin)
                raise ValueError(
                    f"net {self.net} was trained on {trained}, this run is {here[0]} "
                    f"`{here[1]}`: give option transfer=true to test it across fields"
                )

    def _distance_factor(self, facts: FieldFacts, behaviour: Behaviour) -> float:
        """The net's distance scaling on this field: 1, or the transfer run's factor."""
        if self.transfer and self.net and behaviour is Behaviour.NET:
            return transfer_distance_factor(self.net, facts)
        return 1.0

    def interceptor_for(
        self,
        facts: FieldFacts,
        plan: LaunchPlan,
        rng: Rng,
        behaviour: Behaviour,
        kickable_distance_m: float | None = None,
    ) -> Mind:
        """Layer 1's interception for a receiver or defender: the net's decision, as trained.

        A lead net (:mod:`robotsoccer.skills.lead`) meets the ball with its lead, deciding at
        its first full velocity fit within the farthest pass; everything else is the paper's
        turn-angle defender (:class:`~robotsoccer.skills.intercept.DefenderMind`).
        """
        factor = self._distance_factor(facts, behaviour)
        if behaviour is Behaviour.NET and self.net and model_decision(self.net) == "lead":
            return LeadDefenderMind(
                load_net_function(self.net, factor),
                facts,
                plan.max_distance_m,
                kickable_distance_m=kickable_distance_m,
                turn_tolerance_rad=plan.turn_tolerance_rad,
            )
        return DefenderMind(
            make_policy(behaviour, rng, self.net, factor),
            plan.trigger_distance_m,
            kickable_distance_m=kickable_distance_m,
            turn_tolerance_rad=plan.turn_tolerance_rad,
            decision_period_ticks=decision_ticks(plan, facts),
        )

    def cycle_interceptor_for(
        self,
        facts: FieldFacts,
        plan: LaunchPlan,
        rng: Rng,
        behaviour: Behaviour,
        kickable_distance_m: float | None = None,
    ) -> CycleDefenderMind:
        """Layer 1's interception on the per-cycle client: the same TA rule, every cycle.

        As the interception drill's ``client=cycle`` builds its defender
        (:func:`~robotsoccer.drills.intercept_minds.cycle_defender`).

        Raises:
            ValueError: The net is a lead net (the per-cycle client plays the turn decision),
                or the plan sets a decision period.
        """
        factor = self._distance_factor(facts, behaviour)
        if behaviour is Behaviour.NET and self.net and model_decision(self.net) == "lead":
            raise ValueError("client 'cycle' plays the turn decision: give a TA net or client=see")
        policy = make_policy(behaviour, rng, self.net, factor)
        return cycle_defender(policy, facts, plan, kickable_distance_m)


CYCLE_ON_ROBOTS = (
    "client=cycle is the Soccer Server's per-cycle client; the robots' host "
    "already acts on every tick"
)
"""The one-line refusal of ``client=cycle`` on the robots (pass drill, set play)."""


def control_reach(facts: FieldFacts) -> float:
    """Control of the ball: kick reach, or touching plus :data:`CONTROL_MARGIN_UNITS` [m]."""
    if facts.kick is not None:
        return facts.kick.reach_m
    return facts.touch_distance_m + CONTROL_MARGIN_UNITS * facts.unit_m
