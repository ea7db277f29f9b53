"""The paper's pass drill (layer 2, §6) as a PettingZoo parallel environment, on any field model.

Each trial of :class:`~robotsoccer.drills.passing.PassDrill` (Figures 9–13) holds the decisions
the paper learns: the passer's choice of receiver (layer 2, §6) and, once the pass is announced,
each interceptor's turn angle TA (layer 1, §5: "the receiver's task is identical to that of the
defender"). Here agents take them; everything else is the drill's own minds, unchanged.

**Agents** (:attr:`PassParallelEnv.possible_agents`; all live from ``reset`` to the verdict):

* ``"passer"`` (left 1) chooses the receiver (§6, Figure 11). Action ``Discrete(3)``: slot
  0, 1, 2 = receiver left 2, 3, 4. It acts once, on the very percept on which the drill's
  :class:`~robotsoccer.skills.passing.PasserMind` would choose (every report heard, or the wait
  over), and the mind then announces and kicks as usual. Observation, a dict:
  ``"observation"`` (3, 174), row i the paper's 174 attributes of a pass to slot i
  (:data:`learning.pass_features.ATTRIBUTE_NAMES`) exactly as the passer builds them, unknown as
  0; ``"known"`` (3, 174), 1 where that attribute is known (§6: "marked as *unknown*"); and
  ``"action_mask"`` (3,), the receivers the passer found in its view (seen, or matched to a
  report). Those are its only choices, as in the drill; with nobody found it is the drill's
  blind pass straight ahead, to left 2.
* ``"receiver"``, whichever receiver the passer chose (``infos["receiver"]["player"]``), and
  ``"defender_1"`` … ``"defender_4"`` (right 1–4) take layer 1's decision: TA [rad] in
  ``Box(-pi/2, pi/2, (1,))``, once, at their first percept within the trigger distance after
  they heard the announcement (Figure 13). The observation is (BD [units], BA [rad], previous
  BD [units]) at that percept, as in :class:`~robotsoccer.envs.intercept.InterceptEnv`; the
  interceptor then turns by BA + TA and dashes at every percept (``ta_mode="hold"``). With
  drill option ``defenders="still"`` the defenders never move and are not agents.

The other two receivers stand still from the announcement and the four players elsewhere never
move, as in the drill (Figure 12: "the non-receivers remain stationary"): they are not agents.

**Steps.** ``reset`` runs a trial up to the passer's decision; each ``step`` applies the
deciding agents' actions and runs the trial on to the next decision or to the verdict
(:meth:`~robotsoccer.runs.runner.TrialLoop.run` with a pause). ``infos[agent]["deciding"]``
says who decides. Agents that decide on the same tick decide in the same step, each on its own
percept, sampled before any of them acted (the drill's minds act on one tick's percepts in
turn, none seeing the others' actions of that tick). PettingZoo's parallel API keeps every live
agent in ``agents``, so the other agents' actions are accepted and ignored (any value, or none):
an agent acts once per trial, but stays live to the verdict to get its reward. An agent's
observation is the one of its decision, held afterwards (zeros before it; the passer's
``action_mask`` is all zeros whenever it is not deciding). ``infos`` also give each agent's
player, the trial, the seed and the tick.

**Rewards** come at the verdict: SUCCESS gives 1 to the passer and the receiver, FAILURE
(a defender took the ball) gives 1 to the defenders, MISS gives 0 to everyone, and every step
before gives 0. The verdict terminates every agent (the drill's time limit is a MISS, part of
the task, not a truncation), ``agents`` empties, and ``infos`` carry the label and reason.

**Seeds** follow :class:`~robotsoccer.envs.intercept.InterceptEnv` (Gymnasium's convention):
``reset(seed=s)`` starts the episode stream of experiment seed `s`, and episode k is trial k of
the pass drill with seed `s` (a trial that ends before the passer decides is skipped). ``reset()``
without a seed continues the stream; the first one draws a seed from the OS. The same seed and
the same actions give the same episode.

**The drill, reproduced.** The drill's own interceptor is ``straight`` (TA = 0). With TA = 0
for every interceptor and the receiver a drill chooser would pick, an episode ends exactly as
that trial of the drill with that chooser (a test checks it with ``closest``). The drill options
``chooser``, ``model``, ``interceptor`` and ``net`` are the agents' to decide and are refused.

``pass_parallel_env("robot_physics")`` builds one. ``render_mode="rgb_array"`` draws the field
at each decision and at the verdict; ``"human"`` streams it to the rerun viewer
(:mod:`robotsoccer.envs.rendering`; whole recordings: ``robotsoccer demo --drill pass
--record``).
"""

from __future__ import annotations

import dataclasses
import math
from typing import Any, TypeAlias

import numpy as np
import numpy.typing as npt
from gymnasium import spaces
from gymnasium.utils import seeding
from pettingzoo import ParallelEnv

from field_models.protocol import LEFT, RIGHT, Percept, PlayerRef
from field_models.registry import FIELD_MODELS
from learning.pass_features import ATTRIBUTE_NAMES
from robotsoccer.drills.base import Verdict
from robotsoccer.drills.passing import DEFENDERS, PASSER, RECEIVERS, PassDrill
from robotsoccer.envs.checks import checked_seed
from robotsoccer.envs.intercept import MAX_DISTANCE_UNITS, SKIP_LIMIT
from robotsoccer.envs.rendering import RENDER_MODES, ArenaView, check_render_mode
from robotsoccer.runs.runner import DrillOption, TrialLoop, TrialSpec, build_trial
from robotsoccer.skills.intercept import TA_CLIP_RAD, DefenderMind
from robotsoccer.skills.passing import (
    PasserMind,
    PassOption,
    ReceiverMind,
    WaitingInterceptorMind,
    announced_number,
    parse_report,
)

PASSER_AGENT = "passer"
"""The passer's agent name (left 1)."""
RECEIVER_AGENT = "receiver"
"""The agent of whichever receiver the passer chose."""
DEFENDER_AGENTS: dict[str, PlayerRef] = {f"defender_{ref.number}": ref for ref in DEFENDERS}
"""Defender agent names and their players (right 1–4)."""
RECEIVER_SLOTS: tuple[PlayerRef, ...] = RECEIVERS
"""The passer's action i passes to ``RECEIVER_SLOTS[i]`` (left 2, 3, 4)."""
AGENT_DECISIONS = ("chooser", "model", "interceptor", "net")
"""Drill options that would take the agents' decisions: refused."""
ATTRIBUTES = len(ATTRIBUTE_NAMES)
ANGLE_BOUND_DEG = 180.0
"""The attributes' lower bound: angles lie in [-180, 180] degrees, the rest is >= 0."""
WINNERS = {"SUCCESS": LEFT, "FAILURE": RIGHT}
"""The team rewarded for each label (MISS: nobody)."""

Observation: TypeAlias = npt.NDArray[Any] | dict[str, npt.NDArray[Any]]
"""The passer's dict observation, or an interceptor's (BD, BA, previous BD)."""
ActionValue: TypeAlias = Any
"""A receiver slot (int) for the passer, a TA array of shape (1,) for an interceptor."""
Option: TypeAlias = PassOption
"""One of the passer's candidates: (number, direction [rad], confidence, 174 attributes)."""


def pass_parallel_env(
    field_model: str = FIELD_MODELS[0],
    preset: str | None = None,
    render_mode: str | None = None,
    **drill_options: DrillOption,
) -> PassParallelEnv:
    """The pass drill's decisions as a PettingZoo parallel environment (module docstring).

    Args:
        field_model: A registered field model (default: the first registered).
        preset: Its preset; None: the model's default.
        render_mode: None, ``"rgb_array"`` or ``"human"``.
        **drill_options: Further options of the pass drill (``defenders``, ``max_time_s``,
            ``receiver_half``, ``transfer``).

    Returns:
        The environment.
    """
    return PassParallelEnv(field_model, preset, drill_options=drill_options,
                           render_mode=render_mode)  # fmt: skip


class PassParallelEnv(ParallelEnv[str, Observation, ActionValue]):
    """The passer's, receiver's and defenders' decisions in the pass drill (module docstring).

    Args:
        field_model: A registered field model (default: the first registered).
        preset: Its preset; None: the model's default.
        ball_noise: Ball-motion noise; None: the preset's.
        drill_options: Further options of the pass drill (``chooser``, ``model``,
            ``interceptor`` and ``net`` excepted: the agents decide).
        render_mode: None, ``"rgb_array"`` or ``"human"`` (module docstring).

    Raises:
        ValueError: A refused drill option, or an unknown render mode.
    """

    # PettingZoo's class attribute (mutable, as PettingZoo declares it).
    metadata: dict[str, Any] = {  # noqa: RUF012
        "name": "robotsoccer_pass_v0",
        "render_modes": RENDER_MODES,
        "render_fps": 30,
    }

    def __init__(
        self,
        field_model: str = FIELD_MODELS[0],
        preset: str | None = None,
        ball_noise: float | None = None,
        drill_options: dict[str, DrillOption] | None = None,
        render_mode: str | None = None,
    ) -> None:
        self.render_mode = check_render_mode(render_mode)
        self._view = ArenaView(render_mode, title="robotsoccer_pass_v0")
        self._shown: Any = None  # the arena render() draws: the last episode's
        options = dict(drill_options or {})
        refused = sorted(set(options) & set(AGENT_DECISIONS))
        if refused:
            raise ValueError(
                f"drill options {refused} are the agents' decisions in this environment"
            )
        spec = TrialSpec(drill="pass", field_model=field_model, preset=preset)
        self.spec_ = spec.with_options(**options).with_field(ball_noise=ball_noise)
        self.defenders_act = options.get("defenders", "intercept") != "still"
        defenders = list(DEFENDER_AGENTS) if self.defenders_act else []
        self.possible_agents: list[str] = [PASSER_AGENT, RECEIVER_AGENT, *defenders]
        self.agents: list[str] = []
        self._observation_spaces, self._action_spaces = _spaces(self.possible_agents)
        self._experiment_seed: int | None = None
        self._next_trial = 0
        self._episode: _PassEpisode | None = None

    def observation_space(self, agent: str) -> spaces.Space[Any]:
        """The agent's observation space (the same object at every call)."""
        return _lookup(self._observation_spaces, agent)

    def action_space(self, agent: str) -> spaces.Space[Any]:
        """The agent's action space (the same object at every call)."""
        return _lookup(self._action_spaces, agent)

    def reset(
        self, seed: int | None = None, options: dict[str, Any] | None = None
    ) -> tuple[dict[str, Observation], dict[str, dict[str, Any]]]:
        """Run the next trial up to the passer's decision (`options` is not used).

        Raises:
            RuntimeError: :data:`~robotsoccer.envs.intercept.SKIP_LIMIT` trials in a row ended
                before the passer decided.
            ValueError: A seed that is not None or a whole number in [0, 2^64).
        """
        seed = checked_seed(seed)
        if seed is not None:
            self._experiment_seed, self._next_trial = int(seed), 0
        elif self._experiment_seed is None:
            rng, _ = seeding.np_random(None)  # OS entropy, as Gymnasium's first unseeded reset
            self._experiment_seed = int(rng.integers(2**31 - 1))
        for _ in range(SKIP_LIMIT):
            trial = self._next_trial
            self._next_trial += 1
            spec = dataclasses.replace(self.spec_, seed=self._experiment_seed)
            episode = _PassEpisode(spec, trial, self.possible_agents)
            if episode.advance() is None:
                self._episode = episode
                self._shown = episode.arena
                if self.render_mode == "human":
                    self.render()
                self.agents = list(self.possible_agents)
                return episode.observations(self.agents), _infos(episode, self.agents, {})
        raise RuntimeError(f"no pass in {SKIP_LIMIT} trials in a row: check the drill options")

    def step(
        self, actions: dict[str, ActionValue]
    ) -> tuple[
        dict[str, Observation],
        dict[str, float],
        dict[str, bool],
        dict[str, bool],
        dict[str, dict[str, Any]],
    ]:
        """Apply the deciding agents' actions; run on to the next decision or the verdict.

        Raises:
            RuntimeError: No episode is running (before ``reset``, or after the verdict).
            ValueError: An unknown agent name, no action from a deciding agent, or an action
                outside its space (the passer: a slot not in its ``action_mask``). The episode
                is left at the same decision.
        """
        episode = self._episode
        if episode is None:
            raise RuntimeError("step() before reset(), or after the episode ended")
        unknown = sorted(set(actions) - set(self.possible_agents))
        if unknown:
            raise ValueError(f"unknown agents {unknown} (agents: {self.possible_agents})")
        missing = [agent for agent in episode.deciding if agent not in actions]
        if missing:
            raise ValueError(f"{missing} decide at this step but got no action")
        chosen = {
            agent: _checked(agent, actions[agent], self._action_spaces[agent], episode.mask)
            for agent in episode.deciding
        }  # every action checked before any is applied
        episode.decide(chosen)
        verdict = episode.advance()
        live = list(self.agents)
        rewards = dict.fromkeys(live, 0.0)
        end: dict[str, Any] = {}
        if verdict is not None:
            rewards = {a: _reward(a, verdict) for a in live}
            end = {"label": verdict.label, "reason": verdict.reason, "ticks": episode.tick}
            self._episode, self.agents = None, []
        done = verdict is not None
        if self.render_mode == "human":
            self.render()
        return (
            episode.observations(live),
            rewards,
            dict.fromkeys(live, done),
            dict.fromkeys(live, False),
            _infos(episode, live, end),
        )

    def render(self) -> Any:
        """The field now: an RGB array (``"rgb_array"``), or logged to rerun (``"human"``)."""
        return self._view.render(self._shown)

    def close(self) -> None:
        """Close the viewer's recording, if any."""
        self._view.close()


# ----------------------------------------------------------------------------- one trial


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


class _PassEpisode:
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


# ----------------------------------------------------------------------------- helpers


def _spaces(
    agents: list[str],
) -> tuple[dict[str, spaces.Space[Any]], dict[str, spaces.Space[Any]]]:
    """Each agent's observation and action space (module docstring)."""
    shape = (len(RECEIVER_SLOTS), ATTRIBUTES)
    passer_view = spaces.Dict(
        {
            "observation": spaces.Box(-ANGLE_BOUND_DEG, np.inf, shape, dtype=np.float32),
            "known": spaces.Box(0, 1, shape, dtype=np.int8),
            "action_mask": spaces.Box(0, 1, (len(RECEIVER_SLOTS),), dtype=np.int8),
        }
    )
    observations: dict[str, spaces.Space[Any]] = {PASSER_AGENT: passer_view}
    actions: dict[str, spaces.Space[Any]] = {PASSER_AGENT: spaces.Discrete(len(RECEIVER_SLOTS))}
    for agent in agents[1:]:
        observations[agent] = spaces.Box(
            low=np.array([0.0, -math.pi, 0.0], dtype=np.float32),
            high=np.array([MAX_DISTANCE_UNITS, math.pi, MAX_DISTANCE_UNITS], dtype=np.float32),
        )
        actions[agent] = spaces.Box(-TA_CLIP_RAD, TA_CLIP_RAD, (1,), dtype=np.float32)
    return observations, actions


def _infos(
    episode: _PassEpisode, agents: list[str], end: dict[str, Any]
) -> dict[str, dict[str, Any]]:
    """Per agent: deciding or not, its player, trial, seed and tick (the verdict at the end)."""
    common = {"trial": episode.trial, "seed": episode.seed, "tick": episode.tick, **end}
    return {
        agent: {"deciding": agent in episode.deciding, "player": episode.player(agent), **common}
        for agent in agents
    }


def _lookup(table: dict[str, spaces.Space[Any]], agent: str) -> spaces.Space[Any]:
    try:
        return table[agent]
    except KeyError:
        raise ValueError(f"unknown agent {agent!r} (agents: {list(table)})") from None


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


def _checked(
    agent: str, action: ActionValue, space: spaces.Space[Any], mask: npt.NDArray[np.int8]
) -> int | float:
    """An agent's action checked against its space: the passer's slot, or TA [rad]."""
    if agent == PASSER_AGENT:
        return _receiver_slot(action, mask)
    assert isinstance(space, spaces.Box)
    return _turn_angle(agent, action, space)


def _receiver_slot(action: ActionValue, mask: npt.NDArray[np.int8]) -> int:
    """The passer's action as a receiver slot, checked against its space and mask."""
    value = np.asarray(action)
    if value.shape != () or not np.issubdtype(value.dtype, np.integer):
        raise ValueError(
            f"the passer's action is a receiver slot, an integer in 0..{len(mask) - 1} "
            f"(Discrete({len(mask)})), got {action!r}"
        )
    slot = int(value)
    if not 0 <= slot < len(mask):
        raise ValueError(f"receiver slot {slot} is outside 0..{len(mask) - 1}")
    if not mask[slot]:
        allowed = [i for i in range(len(mask)) if mask[i]]
        raise ValueError(
            f"receiver slot {slot} ({RECEIVER_SLOTS[slot]}) is not in the passer's view: "
            f"choose one its observation's action_mask allows, {allowed}"
        )
    return slot


def _turn_angle(agent: str, action: ActionValue, space: spaces.Box) -> float:
    """An interceptor's action as TA [rad], checked against its space's bounds."""
    try:
        value = np.asarray(action, dtype=np.float64)
    except (TypeError, ValueError) as error:
        raise ValueError(
            f"{agent}'s action is TA [rad], an array of shape (1,); got {action!r}"
        ) from error
    if value.size != 1 or value.ndim > 1:
        raise ValueError(f"{agent}'s action is TA [rad], of shape (1,); got shape {value.shape}")
    ta = float(value.reshape(-1)[0])
    low, high = float(space.low[0]), float(space.high[0])
    if not low <= ta <= high:  # nan fails too
        raise ValueError(f"{agent}'s TA must be in [{low}, {high}] rad, got {ta!r}")
    return min(max(ta, -TA_CLIP_RAD), TA_CLIP_RAD)  # the float32 bound is a hair wider


def _reward(agent: str, verdict: Verdict) -> float:
    """1 to the agents of the team the label favours (module docstring), else 0."""
    team = LEFT if agent in (PASSER_AGENT, RECEIVER_AGENT) else RIGHT
    return 1.0 if WINNERS.get(verdict.label) == team else 0.0
