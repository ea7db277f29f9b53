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

This module is the environment (spaces, seeds, checked actions, rewards); one trial with its
pauses at the agents' decisions is :class:`~robotsoccer.envs.pass_episode.PassEpisode`.
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

from field_models.protocol import LEFT, RIGHT
from field_models.registry import FIELD_MODELS
from robotsoccer.drills.base import Verdict
from robotsoccer.envs.checks import checked_seed
from robotsoccer.envs.intercept import MAX_DISTANCE_UNITS, SKIP_LIMIT
from robotsoccer.envs.pass_episode import (
    ATTRIBUTES,
    DEFENDER_AGENTS,
    PASSER_AGENT,
    RECEIVER_AGENT,
    RECEIVER_SLOTS,
    Observation,
    PassEpisode,
)
from robotsoccer.envs.rendering import RENDER_MODES, ArenaView, check_render_mode
from robotsoccer.runs.runner import DrillOption, TrialSpec
from robotsoccer.skills.intercept import TA_CLIP_RAD

AGENT_DECISIONS = ("chooser", "model", "interceptor", "net")
"""Drill options that would take the agents' decisions: refused."""
ANGLE_BOUND_DEG = 180.0
"""The attributes' lower bound: angles lie in [-180, 180] degrees, the rest is >= 0."""
WINNERS = {"SUCCESS": LEFT, "FAILURE": RIGHT}
"""The team rewarded for each label (MISS: nobody)."""

ActionValue: TypeAlias = Any
"""A receiver slot (int) for the passer, a TA array of shape (1,) for an interceptor."""


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
        self._episode: PassEpisode | None = None

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
            episode = PassEpisode(spec, trial, self.possible_agents)
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
    episode: PassEpisode, agents: list[str], end: dict[str, Any]
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
