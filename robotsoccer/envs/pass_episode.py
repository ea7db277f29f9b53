"""One trial of the pass drill with a pause at every agent's decision (the pass environment).

:class:`PassEpisode` runs one trial of :class:`~robotsoccer.drills.passing.PassDrill` for
:class:`~robotsoccer.envs.passing.PassParallelEnv`: it stops the runner's loop just before the
passer chooses its receiver (§6, Figure 11) and before each interceptor chooses its turn angle
TA (§5; Figure 13), holds each agent's observation of its decision, and hands the agents'
choices to the drill's own minds. The agents, their observations and the decision rules are
described in :mod:`robotsoccer.envs.passing`'s docstring.
"""

from __future__ import annotations

from typing import Any, TypeAlias

import numpy as np
import numpy.typing as npt

from field_models.protocol import LEFT, Percept, PlayerRef
from learning.pass_features import ATTRIBUTE_NAMES
from robotsoccer.drills.base import Verdict
from robotsoccer.drills.passing import DEFENDERS, PASSER, RECEIVERS, PassDrill
from robotsoccer.envs.intercept import MAX_DISTANCE_UNITS
from robotsoccer.runs.runner import TrialLoop, TrialSpec, build_trial
from robotsoccer.skills.intercept import DefenderMind
from robotsoccer.skills.pass_messages import announced_number, parse_report
from robotsoccer.skills.pass_receivers import ReceiverMind, WaitingInterceptorMind
from robotsoccer.skills.passing import PasserMind, PassOption

PASSER_AGENT = "passer"
"""The passer's agent name (left 1)."""
RECEIVER_AGENT = "receiver"
"""The agent of whichever receiver the passer chose."""
DEFENDER_AGENTS: dict[str, PlayerRef] = {f"defender_{ref.number}": ref for ref in DEFENDERS}
"""Defender agent names and their players (right 1–4)."""
RECEIVER_SLOTS: tuple[PlayerRef, ...] = RECEIVERS
"""The passer's action i passes to ``RECEIVER_SLOTS[i]`` (left 2, 3, 4)."""
ATTRIBUTES = len(ATTRIBUTE_NAMES)

Observation: TypeAlias = npt.NDArray[Any] | dict[str, npt.NDArray[Any]]
"""The passer's dict observation, or an interceptor's (BD, BA, previous BD)."""
Option: TypeAlias = PassOption
"""One of the passer's candidates: (number, direction [rad], confidence, 174 attributes)."""


class _HeldTurn:
    """An interceptor's TA rule: whatever its agent chose (the layer-1 policy protocol)."""

    def __init__(self) -> None:
        self.ta_rad = 0.0

    def __call__(self, *_: object) -> float:
        return self.ta_rad


class _Watch:
    """One interceptor's layer-1 decision inside the pass drill: when it comes, what it sees.

    The drill's mind hands percepts to its layer-1 :class:`DefenderMind` only from the
    announcement on (a receiver only if it is the one announced); the watch mirrors that rule,
    and the mind's own trigger and previous sighting, to stop just before the mind chooses TA.
    """

    def __init__(
        self, agent: str, mind: ReceiverMind | WaitingInterceptorMind, unit_m: float
    ) -> None:
        self.agent = agent
        self.mind = mind
        self.unit_m = unit_m
        self.previous_bd: float | None = None
        self.features = np.zeros(3, dtype=np.float32)

    @property
    def interceptor(self) -> DefenderMind:
        """The layer-1 mind inside (the environment plays the paper's turn-angle decision)."""
        inner = self.mind.interceptor
        assert isinstance(inner, DefenderMind), "the pass environment takes a turn-angle net"
        return inner

    def decides(self, percept: Percept) -> bool:
        """Whether the layer-1 mind chooses TA on `percept` (then its features are ready)."""
        layer1 = self.interceptor
        ball = percept.ball
        if layer1.triggered or layer1.policy is None or ball is None or not self._engaged(percept):
            return False
        bd = ball.distance_m
        previous = bd if self.previous_bd is None else self.previous_bd
        if bd > layer1.trigger_distance_m:
            self.previous_bd = bd  # DefenderMind's "previous BD": the last sighting it acted on
            return False
        u = self.unit_m
        self.features = np.array(
            [min(bd / u, MAX_DISTANCE_UNITS), ball.angle_rad,
             min(previous / u, MAX_DISTANCE_UNITS)], dtype=np.float32,
        )  # fmt: skip
        return True

    def _engaged(self, percept: Percept) -> bool:
        """Whether the drill's mind passes `percept` on to its layer-1 mind (Figure 13)."""
        mind = self.mind
        if isinstance(mind, WaitingInterceptorMind):
            if mind.still:
                return False
            return mind.started or any(announced_number(h.text) is not None for h in percept.heard)
        if mind.chosen is not None:
            return mind.chosen
        for heard in percept.heard:  # the first announcement heard settles it, as in the mind
            number = announced_number(heard.text)
            if number is not None:
                return number == mind.number
        return False


class PassEpisode:
    """One trial of the drill, run by the runner's loop with a pause at every agent's decision.

    It sets the passer's outside chooser (:attr:`~robotsoccer.skills.passing.PasserMind.pick`),
    shows the agent the candidates the mind is about to weigh through its
    :meth:`~robotsoccer.skills.passing.PasserMind.find_receivers` and
    :meth:`~robotsoccer.skills.passing.PasserMind.option`, and reads the rest of a tick with
    :meth:`~robotsoccer.runs.runner.TrialLoop.pending`.
    """

    def __init__(self, spec: TrialSpec, trial: int, agents: list[str]) -> None:
        rngs, drill, arena = build_trial(spec, trial)
        assert isinstance(drill, PassDrill)
        drill.setup(arena, rngs)
        minds = drill.minds(arena, rngs)
        passer = minds[PASSER]
        assert isinstance(passer, PasserMind)
        # The drill's chooser is the one thing replaced: the mind finds its candidates, builds
        # their attributes, announces and kicks as ever, but the agent picks (§6, Figure 11).
        passer.pick = self._pick
        self.passer = passer
        self.trial, self.seed = trial, spec.seed
        self.arena = arena
        unit = arena.facts.unit_m
        self.turns = {agent: _HeldTurn() for agent in agents if agent != PASSER_AGENT}
        self.watches: dict[PlayerRef, _Watch] = {}
        for ref in RECEIVERS:
            self._watch(RECEIVER_AGENT, ref, minds, unit)
        for agent, ref in DEFENDER_AGENTS.items():
            if agent in self.turns:
                self._watch(agent, ref, minds, unit)
        self.loop = TrialLoop(arena, drill, minds)
        self.deciding: tuple[str, ...] = ()
        self.choice: int | None = None  # the chosen receiver's number
        self.held: dict[str, Observation] = {a: _blank(a) for a in agents}
        self.mask = np.zeros(len(RECEIVER_SLOTS), dtype=np.int8)
        self._settled: list[Percept] = []  # percepts of the open tick already asked about

    def _watch(self, agent: str, ref: PlayerRef, minds: dict[PlayerRef, Any], unit: float) -> None:
        mind = minds[ref]
        assert isinstance(mind, ReceiverMind | WaitingInterceptorMind)
        assert isinstance(mind.interceptor, DefenderMind), "the environment plays TA decisions"
        mind.interceptor.policy = self.turns[agent]
        self.watches[ref] = _Watch(agent, mind, unit)

    @property
    def tick(self) -> int:
        """The arena's tick."""
        return self.arena.tick

    def player(self, agent: str) -> str | None:
        """The player an agent is (the receiver's once chosen), as ``left2``."""
        if agent == PASSER_AGENT:
            return str(PASSER)
        if agent == RECEIVER_AGENT:
            return None if self.choice is None else str(PlayerRef(LEFT, self.choice))
        return str(DEFENDER_AGENTS[agent])

    def observations(self, agents: list[str]) -> dict[str, Observation]:
        """Each agent's observation: the one of its decision (zeros before it), copied.

        The passer's ``action_mask`` is all zeros whenever it is not deciding: no choice left.
        """
        out = {agent: _copy(self.held[agent]) for agent in agents}
        view = out.get(PASSER_AGENT)
        if isinstance(view, dict) and PASSER_AGENT not in self.deciding:
            view["action_mask"] = np.zeros_like(self.mask)
        return out

    def advance(self) -> Verdict | None:
        """Run to the next decision (None, :attr:`deciding` set) or to the verdict."""
        self.deciding = ()
        return self.loop.run(pause=self._is_decision)

    def decide(self, chosen: dict[str, int | float]) -> None:
        """Hold the deciding agents' checked actions (slot, TA) for their minds."""
        for agent, value in chosen.items():
            if agent == PASSER_AGENT:
                self.choice = RECEIVER_SLOTS[int(value)].number
            else:
                self.turns[agent].ta_rad = float(value)

    def _pick(self, percept: Percept, options: list[Option]) -> int:
        """The passer's pick: the option of the agent's receiver (replaces the drill chooser)."""
        numbers = [number for number, *_ in options]
        assert self.choice in numbers, "the agent's receiver is one of the mind's candidates"
        return numbers.index(self.choice)

    def _is_decision(self, percept: Percept) -> bool:
        """Whether agents decide on this tick, from `percept` on (the loop's pause rule).

        Asked of each percept before its mind acts. At the first deciding one, the rest of the
        tick is asked too, so that the agents deciding on one tick decide in one step: each
        decides on its own percept, sampled before any of them acted (the minds' own state is
        per player, so asking ahead changes nothing). The percepts asked about are not asked
        again when the loop goes on.
        """
        if any(percept is seen for seen in self._settled):
            return False
        agent = self._decision(percept)
        if agent is None:
            return False
        rest = _open_tick_after(self.loop, percept)
        later = [self._decision(other) for other in rest]
        self._settled = [percept, *rest]
        self.deciding = (agent, *(a for a in later if a is not None))
        return True

    def _decision(self, percept: Percept) -> str | None:
        """The agent deciding on `percept` (its observation then held), or None."""
        if percept.player == PASSER:
            return PASSER_AGENT if self._passer_decides(percept) else None
        watch = self.watches.get(percept.player)
        if watch is None or not watch.decides(percept):
            return None
        self.held[watch.agent] = watch.features.copy()
        return watch.agent

    def _passer_decides(self, percept: Percept) -> bool:
        """The drill passer's rule: every report heard (this percept's too), or the wait over."""
        passer = self.passer
        if passer.chosen is not None or passer.intent_tick is None:
            return False
        heard = set(passer.heard) | _reported(percept, passer)
        waited = percept.tick - passer.intent_tick >= passer.wait_ticks
        if len(heard) < len(passer.receivers) and not waited:
            return False
        self.held[PASSER_AGENT] = self._passer_view(percept)
        return True

    def _passer_view(self, percept: Percept) -> dict[str, npt.NDArray[Any]]:
        """The 174 attributes of each candidate, as the mind is about to build them."""
        passer = self.passer
        for heard in percept.heard:  # file this percept's reports, as the mind's act() will
            report = parse_report(heard.text)
            if report is not None and report.number in passer.receivers:
                passer.heard.setdefault(report.number, report)
        own = percept.player.team
        found: dict[int, int | None] = dict(passer.find_receivers(percept, own))
        if not found:  # the mind's blind pass: straight ahead, to the first receiver
            found = {passer.receivers[0]: None}
        x = np.full((len(RECEIVER_SLOTS), ATTRIBUTES), np.nan)
        for number, index in found.items():
            x[_numbers().index(number)] = passer.option(percept, own, number, index)[3]
        self.mask = np.array([number in found for number in _numbers()], dtype=np.int8)
        known = ~np.isnan(x)
        return {
            "observation": np.where(known, x, 0.0).astype(np.float32),
            "known": known.astype(np.int8),
            "action_mask": self.mask.copy(),
        }


def _numbers() -> list[int]:
    return [ref.number for ref in RECEIVER_SLOTS]


def _reported(percept: Percept, passer: PasserMind) -> set[int]:
    """The receivers whose reports `percept` brings."""
    reports = (parse_report(heard.text) for heard in percept.heard)
    return {r.number for r in reports if r is not None and r.number in passer.receivers}


def _blank(agent: str) -> Observation:
    """An agent's observation before its decision: zeros (and an empty action mask)."""
    if agent != PASSER_AGENT:
        return np.zeros(3, dtype=np.float32)
    shape = (len(RECEIVER_SLOTS), ATTRIBUTES)
    return {
        "observation": np.zeros(shape, dtype=np.float32),
        "known": np.zeros(shape, dtype=np.int8),
        "action_mask": np.zeros(len(RECEIVER_SLOTS), dtype=np.int8),
    }


def _copy(observation: Observation) -> Observation:
    if isinstance(observation, dict):
        return {key: value.copy() for key, value in observation.items()}
    return observation.copy()


def _open_tick_after(loop: TrialLoop, percept: Percept) -> list[Percept]:
    """The percepts of the loop's open tick after `percept` (paused on), not yet handed out."""
    pending = loop.pending()
    index = next(i for i, p in enumerate(pending) if p is percept)
    return pending[index + 1 :]
