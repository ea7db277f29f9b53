"""Layer 2 as client minds: the passer, its receivers and the defenders (paper §6, Figures 9–13).

One trial's conversation, through the field model's own say/hear (the Soccer Server's ``say``
with its length and hearing limits; on the robots the central host relays the text):

1. **Intention** (Figure 9). At its first percept the passer, placed behind the ball, says
   :data:`~robotsoccer.skills.pass_messages.INTENT`.
2. **Reports** (Figure 10). A receiver that heard the intention turns to face the ball. Once it
   faces it, it says its report in its own time slot,
   :data:`~robotsoccer.skills.pass_receivers.REPORT_SLOT_PERIODS` sensor periods apart by
   uniform number. The slots exist because the 1996 server lets a player hear
   only one message every two cycles (``hear_decay`` 2, ``hear_inc`` 1), so three replies in
   one cycle would be lost. A report is ``r<NN>`` and then the receiver's view
   (:func:`learning.pass_codec.encode_view`): the passer's distance and direction, and every
   other player it sees. When the field's say limit cannot hold that view (rcssserver 19 allows
   10 characters), it says only ``r<NN>d<distance>``, its distance to the passer. Then the passer
   decides on its own half of the attributes; the receiver's half is *unknown* (§6: "marked as
   unknown").
3. **Choice** (Figure 11). The passer waits for every report, or :data:`REPORT_WAIT_PERIODS`
   sensor periods. It then finds each receiver in its own view: by uniform number where the
   view shows it, else by the distance that receiver reported (the distance between two players
   is the same from either end). It builds the 174 attributes for each candidate and picks one
   with its :class:`Chooser`.
4. **Announcement** (Figure 12). It says ``k<NN>`` and kicks toward the receiver. On a field
   without an aimable kick, the coach launches the ball along the passer's chosen direction
   instead (:attr:`PasserMind.pass_direction_rad`).
5. **Interception** (Figure 13). The chosen receiver and the defenders go for the ball with
   layer 1's interception (:class:`~robotsoccer.skills.intercept.DefenderMind`). The other
   receivers stand still from the announcement on.

Choosers (the rows of Table 2 and those beyond it):

* ``random``: a receiver drawn from the trial's ``"policy"`` stream (training);
* ``tree``: the decision tree's highest success confidence (forced to pass, as in Table 2),
  the Laplace-corrected share of successes at the leaf
  (:meth:`learning.pass_tree.PassTree.success_confidence`);
* ``boost``: gradient-boosted trees' highest probability of success (beyond the paper;
  :class:`learning.pass_boost.PassBoost`);
* ``closest``: the nearest seen receiver (the paper's heuristic, 64%);
* ``analytic``: "can any defender reach the ball's path before the receiver?". This is
  predicted with the field's own ball law and the players' top speed: the receiver with the
  largest time margin is chosen.

Distances inside the attributes are in units (Soccer Server metres, the field's ``unit_m``) and
angles in degrees (:mod:`learning.pass_features`). The minds work in metres and radians.

This module is the passer (:class:`PasserMind`, its choosers and the analytic margin); the
receivers and waiting defenders are :mod:`robotsoccer.skills.pass_receivers`, the texts they
say :mod:`robotsoccer.skills.pass_messages`.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from enum import StrEnum
from typing import Protocol

import numpy as np

from field_models.arena import BallLaw, FieldFacts
from field_models.protocol import Action, Kick, Percept, Say, SeenPlayer
from field_models.seeding import Rng
from learning.pass_features import (
    RECEIVER_FEEL_M,
    estimated_receiver_half,
    pass_attributes,
    passer_attributes,
    unknown_half,
)
from robotsoccer.options import choice
from robotsoccer.skills.pass_messages import INTENT, Report, announce_text, parse_report

REPORT_WAIT_PERIODS = 12.0
"""The passer decides at the latest this many sensor periods after its intention."""


class PassEvaluator(Protocol):
    """A learned pass evaluator: the tree or the boosted trees."""

    def success_confidence(self, x: np.ndarray) -> float:
        """The confidence that a pass with attributes `x` (174,) succeeds."""
        ...


class Chooser(StrEnum):
    """How the passer picks its receiver (module docstring)."""

    RANDOM = "random"
    TREE = "tree"
    BOOST = "boost"
    CLOSEST = "closest"
    ANALYTIC = "analytic"


def view_arrays(
    seen: Sequence[SeenPlayer], own_team: str, unit_m: float
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Seen players as (distance [units], angle [deg], team: +1 mate, -1 opponent, 0 unknown)."""
    distance = np.array([s.distance_m / unit_m for s in seen], dtype=float)
    angle = np.array([math.degrees(s.angle_rad) for s in seen], dtype=float)
    team = np.array(
        [0 if s.team is None else (1 if s.team == own_team else -1) for s in seen], dtype=np.int8
    )
    return distance, angle, team


def open_play_attributes(
    percept: Percept, index: int, unit_m: float, receiver_half: str = "unknown"
) -> np.ndarray:
    """The tree's attributes of a pass to ``percept.players[index]`` in open play (§6).

    The passer's half comes from its own view. Open play has no say/hear exchange, so the
    receiver's half is ``"unknown"``, or ``"estimated"`` from what the passer sees
    (:func:`learning.pass_features.estimated_receiver_half`; a team's
    :attr:`~robotsoccer.skills.team_setup.TeamSetup.receiver_half`).
    """
    seen = percept.players[index]
    others = [s for i, s in enumerate(percept.players) if i != index]
    dist, ang, team = view_arrays(others, percept.player.team, unit_m)
    receiver = (seen.distance_m / unit_m, math.degrees(seen.angle_rad))
    mine = passer_attributes(*receiver, dist, ang, team)
    feel = RECEIVER_FEEL_M / unit_m
    theirs = (
        estimated_receiver_half(*receiver, dist, ang, team, feel_distance=feel)
        if receiver_half == "estimated"
        else unknown_half()
    )
    return pass_attributes(mine, theirs)


@dataclass(frozen=True, slots=True)
class PassPhysics:
    """What the analytic chooser needs to know about the field (from its facts).

    Attributes:
        ball: How a free ball slows down.
        pass_speed_mps: The ball's speed as the pass leaves [m/s].
        player_speed_mps: A player's top speed [m/s].
        reach_m: How close a player must come to the ball to take it [m].
    """

    ball: BallLaw
    pass_speed_mps: float
    player_speed_mps: float
    reach_m: float


def analytic_margin(
    physics: PassPhysics,
    receiver: tuple[float, float],
    opponents: Sequence[tuple[float, float]],
) -> float:
    """Time [s] to spare before any opponent could take the pass (< 0: one gets there first).

    Positions are (distance [m], angle [rad]) from the passer. The ball runs along the
    receiver's direction under the field's ball law, and the path is sampled every half reach.
    Each player runs straight at top speed to a point on the path and takes the ball there if
    it arrives no later than the ball. The receiver takes it at the first point it can. The
    margin is the least time by which any opponent is late at a point before that one.
    """
    rd, ra = receiver
    step = 0.5 * max(physics.reach_m, 1e-3)
    along = np.arange(step, rd + step, step)
    ball_t = np.array(
        [_or_inf(physics.ball.time_to_cover(s, physics.pass_speed_mps)) for s in along]
    )
    xs, ys = along * math.cos(ra), along * math.sin(ra)

    def arrival(d: float, a: float) -> np.ndarray:
        gap = np.hypot(xs - d * math.cos(a), ys - d * math.sin(a)) - physics.reach_m
        return np.maximum(gap, 0.0) / physics.player_speed_mps

    in_time = arrival(rd, ra) <= ball_t
    end = int(np.argmax(in_time)) + 1 if in_time.any() else len(along)
    margin = math.inf
    for d, a in opponents:
        margin = min(margin, float(np.min(arrival(d, a)[:end] - ball_t[:end])))
    return margin


def _or_inf(t: float | None) -> float:
    return math.inf if t is None else t


PassOption = tuple[int, float, float, np.ndarray]
"""One receiver the passer weighs: (number, pass direction [rad], tree confidence, its 174
attributes); :meth:`PasserMind.option` builds it."""


class PasserMind:
    """The passer (module docstring): intention, wait for reports, choose, announce, kick.

    Args:
        receivers: The uniform numbers of its receivers (its teammates in the region).
        chooser: How it picks (:class:`Chooser`, or its name).
        rng: The trial's ``"policy"`` stream (``random``).
        facts: The field's facts: its unit, tick and the time between two percepts (how long
            the passer waits for the reports).
        kick_power: The pass's kick power; None: the field has no aimable kick (the coach
            launches the ball along :attr:`pass_direction_rad`).
        tree: The learned evaluator (``tree``, ``boost``).
        physics: The field's numbers (``analytic``).
        use_reports: False decides on the passer's own half only, the receivers' half unknown
            (as on a field whose says cannot hold a report; the reports still identify them).

    Attributes:
        chosen: The receiver's number once chosen.
        confidence: The tree's success confidence in the chosen receiver (nan without a tree).
        attributes: The 174 attributes of the chosen receiver.
        pass_direction_rad: The pass's direction relative to the passer's heading [rad].
        decided_tick: The tick of the decision.
        candidates: How many receivers the passer could find in its view.
        reports: How many reports it heard.
        pick: An outside chooser, (percept, options) -> index into options, used instead of
            the chooser's rule (a learning environment's agent, :mod:`robotsoccer.envs.passing`);
            None (default): the rule.
    """

    def __init__(
        self,
        receivers: Sequence[int],
        chooser: Chooser | str,
        rng: Rng,
        facts: FieldFacts,
        *,
        kick_power: float | None,
        tree: PassEvaluator | None = None,
        physics: PassPhysics | None = None,
        use_reports: bool = True,
    ) -> None:
        self.receivers = tuple(receivers)
        self.use_reports = use_reports
        self.chooser = choice(Chooser, chooser, "chooser")
        if self.chooser in (Chooser.TREE, Chooser.BOOST) and tree is None:
            raise ValueError(
                f"chooser {self.chooser.value!r} needs a model file (option model=...)"
            )
        if self.chooser is Chooser.ANALYTIC and physics is None:
            raise ValueError("chooser 'analytic' needs the field's pass physics")
        self.rng = rng
        self.unit_m = facts.unit_m
        self.kick_power = kick_power
        self.tree = tree
        self.physics = physics
        self.wait_ticks = round(REPORT_WAIT_PERIODS * facts.sensor_period_s / facts.dt_s)
        self.intent_tick: int | None = None
        self.heard: dict[int, Report] = {}
        self.chosen: int | None = None
        self.confidence = math.nan
        self.attributes: np.ndarray | None = None
        self.pass_direction_rad: float | None = None
        self.decided_tick: int | None = None
        self.candidates = 0
        self.reports = 0
        self.done = False
        self.pick: Callable[[Percept, list[PassOption]], int] | None = None

    def act(self, percept: Percept) -> tuple[Action, ...]:
        """Say the intention, gather reports, then decide once and kick."""
        if self.chosen is not None:
            self.done = True
            return ()
        if self.intent_tick is None:
            self.intent_tick = percept.tick
            return (Say(INTENT),)
        for heard in percept.heard:
            report = parse_report(heard.text)
            if report is not None and report.number in self.receivers:
                self.heard.setdefault(report.number, report)
        everyone = len(self.heard) == len(self.receivers)
        if not everyone and percept.tick - self.intent_tick < self.wait_ticks:
            return ()
        return self._decide(percept)

    def _decide(self, percept: Percept) -> tuple[Action, ...]:
        own = percept.player.team
        found: dict[int, int | None] = dict(self.find_receivers(percept, own))
        self.candidates, self.reports = len(found), len(self.heard)
        if not found:  # nobody in view: kick ahead, to the first receiver by number
            found = {self.receivers[0]: None}
        options: list[PassOption] = []
        for number, index in found.items():
            options.append(self.option(percept, own, number, index))
        pick = self._pick(percept, options) if self.pick is None else self.pick(percept, options)
        number, angle, confidence, x = options[pick]
        self.chosen, self.confidence, self.attributes = number, confidence, x
        self.pass_direction_rad, self.decided_tick = angle, percept.tick
        actions: list[Action] = [Say(announce_text(number))]
        if self.kick_power is not None:
            actions.append(Kick(self.kick_power, angle))
        return tuple(actions)

    def find_receivers(self, percept: Percept, own: str) -> dict[int, int]:
        """Receiver number → index in the percept's players, for the receivers in view."""
        found: dict[int, int] = {}
        seen = percept.players
        for i, s in enumerate(seen):
            if s.team == own and s.number in self.receivers:
                found[int(s.number)] = i
        for number, report in self.heard.items():
            if number in found:
                continue
            taken = set(found.values())
            best, best_gap = None, 3.0  # units: a wider gap is someone else
            for i, s in enumerate(seen):
                if i in taken or s.team not in (own, None) or s.number is not None:
                    continue
                gap = abs(s.distance_m / self.unit_m - report.passer_distance_units)
                if gap < best_gap:
                    best, best_gap = i, gap
            if best is not None:
                found[number] = best
        return found

    def option(self, percept: Percept, own: str, number: int, index: int | None) -> PassOption:
        """(number, direction [rad], tree confidence, attributes) of passing to one receiver."""
        seen = percept.players
        if index is None:
            return number, 0.0, math.nan, pass_attributes(unknown_half(), unknown_half())
        target = seen[index]
        others = [s for i, s in enumerate(seen) if i != index]
        dist, ang, team = view_arrays(others, own, self.unit_m)
        mine = passer_attributes(
            target.distance_m / self.unit_m, math.degrees(target.angle_rad), dist, ang, team
        )
        report = self.heard.get(number)
        use = report is not None and self.use_reports
        theirs = report.half if use and report is not None else unknown_half()
        x = pass_attributes(mine, theirs)
        confidence = math.nan
        if self.tree is not None:
            confidence = self.tree.success_confidence(x)
        return number, target.angle_rad, confidence, x

    def _pick(self, percept: Percept, options: list[PassOption]) -> int:
        """The index of the chosen option, by the chooser's rule."""
        if len(options) == 1:
            return 0
        if self.chooser is Chooser.RANDOM:
            return int(self.rng.integers(len(options)))
        if self.chooser in (Chooser.TREE, Chooser.BOOST):
            return int(np.argmax([o[2] for o in options]))
        if self.chooser is Chooser.CLOSEST:
            return int(np.argmin([o[3][0] for o in options]))  # "passer receiver distance"
        return self._pick_analytic(percept, options)

    def _pick_analytic(self, percept: Percept, options: list[PassOption]) -> int:
        assert self.physics is not None
        own = percept.player.team
        opponents = [(s.distance_m, s.angle_rad) for s in percept.players if s.team != own]
        margins = []
        for _, angle, _, x in options:
            receiver = (float(x[0]) * self.unit_m, angle)
            margins.append(analytic_margin(self.physics, receiver, opponents))
        return int(np.argmax(margins))
