"""The interception drill's defender, built from the drill's options on one field (paper §5).

Three defenders: the paper's TA defender on the see client (:mod:`robotsoccer.skills.intercept`:
"turn, then dash" at each see), the same decision on a per-cycle client
(:mod:`robotsoccer.skills.cycle`) and the lead defender (:mod:`robotsoccer.skills.lead`: a
meeting time in place of TA). The drill (:mod:`robotsoccer.drills.intercept`) asks
:func:`defender_mind` for the one its options name.
"""

from __future__ import annotations

from field_models.arena import Arena, FieldFacts
from field_models.seeding import TrialRngs
from robotsoccer.drills.intercept_options import ClientKind, Decision, InterceptOptions
from robotsoccer.drills.intercept_plan import LaunchPlan, decision_ticks
from robotsoccer.skills.cycle import CycleDefenderMind
from robotsoccer.skills.intercept import (
    Behaviour,
    DefenderMind,
    TaMode,
    TurnPolicy,
    load_net_function,
    make_policy,
)
from robotsoccer.skills.lead import LeadDefenderMind, ScaledLead, lead_policy

AnyDefender = DefenderMind | CycleDefenderMind | LeadDefenderMind
"""Any of the drill's defenders."""


def defender_mind(
    options: InterceptOptions,
    arena: Arena,
    plan: LaunchPlan,
    rngs: TrialRngs,
    distance_factor: float,
) -> AnyDefender:
    """The defender the options name: lead, per-cycle TA or the paper's TA on the see client.

    Args:
        options: The drill's options.
        arena: The trial's field.
        plan: The drill's launch plan there.
        rngs: The trial's streams (``policy`` for a random behaviour).
        distance_factor: A net's distance factor on this field (1: the field it was trained on;
            :meth:`robotsoccer.drills.intercept.InterceptDrill.distance_factor`).
    """
    if options.decision is Decision.LEAD:
        return lead_mind(options, arena, plan, rngs, distance_factor)
    if options.client is ClientKind.CYCLE:
        return cycle_mind(options, arena, plan, rngs, distance_factor)
    return turn_mind(options, arena, plan, rngs, distance_factor)


def lead_mind(
    options: InterceptOptions,
    arena: Arena,
    plan: LaunchPlan,
    rngs: TrialRngs,
    distance_factor: float,
) -> LeadDefenderMind:
    """The lead defender (:mod:`robotsoccer.skills.lead`)."""
    net = None
    if options.behaviour is Behaviour.NET:
        net = load_net_function(options.model, distance_factor)
        if options.lead_time_scale != 1.0:
            net = ScaledLead(net, options.lead_time_scale)
    policy = lead_policy(options.behaviour.value, rngs["policy"], net, plan.arrival_time_s)
    return LeadDefenderMind(
        policy,
        arena.facts,
        plan.max_distance_m,  # decide at the first full velocity fit: no time to wait
        replan=options.behaviour is Behaviour.ANALYTIC,
        kickable_distance_m=plan.kickable_distance_m if options.defender_kick else None,
        turn_tolerance_rad=plan.turn_tolerance_rad,
    )


def turn_mind(
    options: InterceptOptions,
    arena: Arena,
    plan: LaunchPlan,
    rngs: TrialRngs,
    distance_factor: float,
) -> DefenderMind:
    """The paper's TA defender (:mod:`robotsoccer.skills.intercept`)."""
    policy = make_policy(options.behaviour, rngs["policy"], options.model, distance_factor)
    return DefenderMind(
        policy,
        plan.trigger_distance_m,
        ta_mode=options.ta_mode,
        kickable_distance_m=plan.kickable_distance_m if options.defender_kick else None,
        turn_tolerance_rad=plan.turn_tolerance_rad,
        decision_period_ticks=decision_ticks(plan, arena.facts),
    )


def cycle_mind(
    options: InterceptOptions,
    arena: Arena,
    plan: LaunchPlan,
    rngs: TrialRngs,
    distance_factor: float,
) -> CycleDefenderMind:
    """The TA defender on a per-cycle client (:mod:`robotsoccer.skills.cycle`).

    Raises:
        ValueError: The plan sets a decision period (the ``task`` scaling), or TA is chosen at
            every see (the cycle client holds it).
    """
    if decision_ticks(plan, arena.facts):
        raise ValueError(CYCLE_PERIOD_ERROR)
    if options.ta_mode is not TaMode.HOLD:
        raise ValueError("client 'cycle' holds TA: use ta_mode=hold")
    policy = make_policy(options.behaviour, rngs["policy"], options.model, distance_factor)
    return cycle_defender(
        policy,
        arena.facts,
        plan,
        kickable_distance_m=plan.kickable_distance_m if options.defender_kick else None,
    )


CYCLE_PERIOD_ERROR = "client 'cycle' acts every cycle: this plan sets a decision period"


def cycle_defender(
    policy: TurnPolicy | None,
    facts: FieldFacts,
    plan: LaunchPlan,
    kickable_distance_m: float | None = None,
) -> CycleDefenderMind:
    """Layer 1's TA defender on a per-cycle client, with `policy` and the plan's trigger.

    The one way the drills build it (the interception drill's ``client=cycle``, the set
    play's).

    Raises:
        ValueError: The plan sets a decision period (the cycle client acts every cycle).
    """
    if decision_ticks(plan, facts):
        raise ValueError(CYCLE_PERIOD_ERROR)
    return CycleDefenderMind(
        policy, facts, plan.trigger_distance_m, kickable_distance_m=kickable_distance_m
    )
