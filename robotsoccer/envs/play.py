"""Play with players as agents: what the match and half-field offense environments share.

:class:`PlayParallelEnv`: a match-like drill (:mod:`robotsoccer.envs.match`,
:mod:`robotsoccer.envs.hfo`) with players as agents; a subclass builds it and reads its score.

**Agents** are players, ``left_1`` … ``right_N`` (``controlled``); the others are team minds.

**Steps.** The drill runs on the runners' own :class:`~robotsoccer.runs.runner.TrialLoop`
(paused as the pass environment pauses it): ``reset`` and each ``step`` run the field tick by
tick, every mind acting on its percepts, to the next tick on which a controlled player gets a
percept (a see on the Soccer Server, a camera frame on the robots: every player's on the same
tick there). The agents whose percepts came
then are the deciding ones (``infos[agent]["deciding"]``), each deciding on its own percept,
sampled before any of them acted; the step hands their actions to the field at that tick,
exactly where a team mind's would go. The others' actions are optional: given, they replace
the held action (or macro) for the agent's next percept. An agent's observation is the one of
its last percept, held between its percepts.

**Actions** (``action=``):

* ``"commands"`` (default) and ``"primitives"``: the field's action vocabulary, as in the
  per-step environments (:mod:`robotsoccer.envs.control_spaces`): the Soccer Server's
  parametrised dash/turn/kick in HFO's form, ``Box(-1, 1, (8,))``, or ``Discrete(6)``
  STOP/FORWARD/BACKWARD/TURN_LEFT/TURN_RIGHT/KICK; both are the shared
  :data:`~field_models.protocol.Action` records the minds send, which the robots' host turns
  into its primitives. An action is held: sent again every command period until the agent's
  next decision.
* ``"macro"``: one skill of the team minds per decision (:mod:`robotsoccer.envs.macros`):
  ``Discrete(5 + team size)``, AUTO (the team mind's own choice), INTERCEPT, GO_HOME, SHOOT,
  DRIBBLE, PASS_k; the observation is then a dict with the vector as ``"observation"`` and
  the open macros as ``"action_mask"``. A macro outside the mask is refused.

**Observations** are the per-step environments' percept vector
(:class:`~robotsoccer.envs.control_spaces.ObservationBuilder`, layout in
:func:`~robotsoccer.envs.control_spaces.observation_names`): from the agent's percept only,
egocentric, distances over the pitch length: the ball (seen flag, distance, direction, motion),
the agent's localised pose, the opponents' goal as target, its teammates then opponents,
nearest first, each with a seen flag (the mask of the slots), and the share of time left. The
pose entries of a right-team agent are mirrored (x, y and heading turned by a half turn), so
that every agent sees itself attack toward +x.

**Rewards** (``reward_weights``, a small record, each step's terms in
``infos[agent]["reward_terms"]``): ``goal`` (weight 1) +1 for each goal the agent's team
scored in the step, -1 for each it conceded; ``possession`` (weight 0) +1 when the agent's
team touched the ball last at the step's end, -1 when the other team did.

**Ends.** The drill's verdict ends every agent (terminated, or truncated where the subclass
says the end is a time limit); ``infos`` carry its label and reason, and ``agents`` empties.

**Seeds** as in every environment of the project: ``reset(seed=s)`` starts the episode stream
of experiment seed `s`, episode k drawing its random numbers from trial k's named streams;
``reset()`` continues the stream. The same seed and actions give the same episode.
"""

from __future__ import annotations

import math
from typing import Any, TypeAlias, cast

import numpy as np
import numpy.typing as npt
from gymnasium import spaces
from gymnasium.utils import seeding
from pettingzoo import ParallelEnv

from field_models.arena import Arena, FieldFacts
from field_models.protocol import LEFT, RIGHT, Action, Mind, Percept, PlayerRef
from field_models.registry import make_arena
from field_models.seeding import TrialRngs
from robotsoccer.drills.base import Drill, Verdict
from robotsoccer.envs.agents import agent_name
from robotsoccer.envs.checks import checked_seed
from robotsoccer.envs.control_spaces import (
    COMMAND_PERIOD_S,
    DEFAULT_TURN_STEP_RAD,
    ObservationBuilder,
    action_space,
    decode_action,
    reward_weights,
)
from robotsoccer.envs.macros import Macro, MacroMind, checked_macro, macro_count, macro_mask
from robotsoccer.envs.rendering import RENDER_MODES, ArenaView, check_render_mode
from robotsoccer.runs.runner import TrialLoop
from robotsoccer.runs.spec import ResolvedSpec
from robotsoccer.skills.team import TeamMind

ACTION_MODES = ("commands", "primitives", "macro")
"""The action modes (module docstring)."""
DEFAULT_WEIGHTS = {"goal": 1.0, "possession": 0.0}
"""The reward terms and their default weights (module docstring)."""
SKIP_LIMIT = 100
"""reset() gives up after this many episodes in a row that end before any agent decides."""
MIRRORED = slice(7, 11)
"""The pose entries (x, y, cos and sin of the heading) mirrored for a right-team agent."""

Observation: TypeAlias = npt.NDArray[np.float32] | dict[str, npt.NDArray[Any]]
"""The percept vector, or with macros a dict of it and the action mask."""


class _HeldActions:
    """A controlled player's mind in the full-action modes: what its agent chose last."""

    def __init__(self) -> None:
        self.actions: tuple[Action, ...] = ()

    def act(self, percept: Percept) -> tuple[Action, ...]:
        return self.actions


class PlayParallelEnv(ParallelEnv[str, Observation, Any]):
    """A match-like drill with some players as agents (module docstring); subclassed.

    A subclass builds its drill (:meth:`_new_drill`), names the controlled players and reads
    the score and the last touch; this class runs the loop and the agents' side.

    Args:
        resolved: What is played, resolved once (:class:`~robotsoccer.runs.spec.ResolvedSpec`):
            the field model and preset, its settings (the play environments see every
            landmark; ``perfect_perception``: the sensor without noise, misses or latency), its
            facts and the players on it, in order.
        controlled: The controlled players.
        action: An action mode (:data:`ACTION_MODES`).
        reward_weights: Weights replacing the defaults of :data:`DEFAULT_WEIGHTS`.
        turn_step_rad: A discrete TURN_LEFT/TURN_RIGHT's turn [rad].
        render_mode: None, ``"rgb_array"`` or ``"human"``.

    Raises:
        ValueError: An unknown action mode, reward term or render mode, no controlled player.
    """

    # PettingZoo's class attribute (mutable, as PettingZoo declares it).
    metadata: dict[str, Any] = {  # noqa: RUF012
        "name": "robotsoccer_play_v0",
        "render_modes": RENDER_MODES,
        "render_fps": 30,
    }

    def __init__(
        self,
        resolved: ResolvedSpec,
        controlled: tuple[PlayerRef, ...],
        *,
        action: str = "commands",
        reward_weights: dict[str, float] | None = None,
        turn_step_rad: float = DEFAULT_TURN_STEP_RAD,
        render_mode: str | None = None,
    ) -> None:
        if action not in ACTION_MODES:
            raise ValueError(f"unknown action {action!r} (modes: {', '.join(ACTION_MODES)})")
        if not controlled:
            raise ValueError("no controlled player: name at least one agent")
        if not (isinstance(turn_step_rad, int | float) and 0.0 < turn_step_rad <= math.pi):
            raise ValueError(f"turn_step_rad must be in (0, pi], got {turn_step_rad!r}")
        self.render_mode = check_render_mode(render_mode)
        self._view = ArenaView(render_mode, title=self.metadata["name"])
        self.resolved = resolved
        self.field_model = resolved.spec.field_model
        self.preset = resolved.spec.preset
        self.field_options = resolved.options
        self.facts: FieldFacts = resolved.facts
        players = resolved.players
        self.action_mode = action
        self.weights = _weights(reward_weights)
        self.turn_step_rad = float(turn_step_rad)
        self.players = players
        self.refs = {agent_name(ref): ref for ref in controlled}
        self.possible_agents: list[str] = list(self.refs)
        self.agents: list[str] = []
        period = min(self.facts.sensor_period_s, COMMAND_PERIOD_S)
        self.command_ticks = max(1, round(period / self.facts.dt_s))
        self.team_sizes = {t: sum(1 for p in players if p.team == t) for t in (LEFT, RIGHT)}
        self._builders = {a: self._builder(ref) for a, ref in self.refs.items()}
        self._observation_spaces = {a: self._observation_space(a) for a in self.refs}
        self._action_spaces = {a: self._action_space(ref) for a, ref in self.refs.items()}
        self._experiment_seed: int | None = None
        self._next_episode = 0
        self._episode: _PlayEpisode | None = None
        self._arena: Arena | None = None  # the last episode's, for render()

    # ------------------------------------------------------------------ the subclass's part

    def _new_drill(self) -> Drill:
        """A fresh drill for one episode."""
        raise NotImplementedError

    def _score(self, drill: Drill) -> tuple[int, int]:
        """Goals of the left and right team so far."""
        raise NotImplementedError

    def _holder(self, drill: Drill) -> PlayerRef | None:
        """The player that touched the ball last, or None."""
        raise NotImplementedError

    def _end_info(self, verdict: Verdict) -> tuple[bool, dict[str, Any]]:
        """(whether the end is a truncation, what ``infos`` carry at the end)."""
        return False, {"label": verdict.label, "reason": verdict.reason}

    def _step_info(self, drill: Drill) -> dict[str, Any]:
        """What ``infos`` carry at every step, besides the common entries."""
        return {}

    # ------------------------------------------------------------------ spaces

    def _builder(self, ref: PlayerRef) -> ObservationBuilder:
        other = RIGHT if ref.team == LEFT else LEFT
        return ObservationBuilder(self.facts, self.team_sizes[ref.team] - 1,
                                  self.team_sizes[other])  # fmt: skip

    def _observation_space(self, agent: str) -> spaces.Space[Any]:
        vector = self._builders[agent].space
        if self.action_mode != "macro":
            return vector
        count = macro_count(self.team_sizes[self.refs[agent].team])
        mask = spaces.Box(0, 1, (count,), dtype=np.int8)
        return spaces.Dict({"observation": vector, "action_mask": mask})

    def _action_space(self, ref: PlayerRef) -> spaces.Space[Any]:
        if self.action_mode == "macro":
            return spaces.Discrete(macro_count(self.team_sizes[ref.team]))
        return action_space(self.action_mode)

    def observation_space(self, agent: str) -> spaces.Space[Any]:
        """The agent's observation space (the same object at every call)."""
        return _lookup(self._observation_spaces, agent)

    def action_space(self, agent: str) -> spaces.Space[Any]:
        """The agent's action space (the same object at every call)."""
        return _lookup(self._action_spaces, agent)

    # ------------------------------------------------------------------ PettingZoo API

    def reset(
        self, seed: int | None = None, options: dict[str, Any] | None = None
    ) -> tuple[dict[str, Observation], dict[str, dict[str, Any]]]:
        """Start the next episode of the stream and run it to the first decision.

        `options` is not used (PettingZoo's API test passes some).

        Raises:
            ValueError: A seed that is not None or a whole number in [0, 2^64).
            RuntimeError: :data:`SKIP_LIMIT` episodes in a row ended before a decision.
        """
        seed = checked_seed(seed)
        if seed is not None:
            self._experiment_seed, self._next_episode = int(seed), 0
        elif self._experiment_seed is None:
            rng, _ = seeding.np_random(None)  # OS entropy, as Gymnasium's first unseeded reset
            self._experiment_seed = int(rng.integers(2**31 - 1))
        for _ in range(SKIP_LIMIT):
            index = self._next_episode
            self._next_episode += 1
            episode = _PlayEpisode(self, self._experiment_seed, index)
            self._arena = episode.arena
            if episode.advance() is None:
                self._episode = episode
                self.agents = list(self.possible_agents)
                if self.render_mode == "human":
                    self.render()
                return episode.observations(self.agents), self._infos(episode, self.agents, {})
        raise RuntimeError(f"{SKIP_LIMIT} episodes in a row ended before any agent decided")

    def step(
        self, actions: dict[str, Any]
    ) -> tuple[
        dict[str, Observation],
        dict[str, float],
        dict[str, bool],
        dict[str, bool],
        dict[str, dict[str, Any]],
    ]:
        """Hand the agents' actions to the field; run on to the next decision or the end.

        Raises:
            RuntimeError: No episode is running (before ``reset``, or after the end).
            ValueError: An unknown agent, no action from a deciding agent, or an action outside
                its space or mask; nothing is applied then.
        """
        episode = self._episode
        if episode is None:
            raise RuntimeError("step() before reset(), or after the episode ended: call reset()")
        unknown = sorted(set(actions) - set(self.agents))
        if unknown:
            raise ValueError(f"unknown agents {unknown} (live agents: {self.agents})")
        missing = [a for a in episode.deciding if a not in actions]
        if missing:
            raise ValueError(f"{missing} decide at this step but got no action")
        chosen = {a: self._checked(a, value, episode) for a, value in actions.items()}
        episode.apply(chosen)
        before = self._score(episode.drill)
        verdict = episode.advance()
        after = self._score(episode.drill)
        holder = self._holder(episode.drill)
        live = list(self.agents)
        rewards, terms = {}, {}
        for agent in live:
            terms[agent] = self._terms(self.refs[agent].team, before, after, holder)
            rewards[agent] = float(sum(terms[agent].values()))
        truncated, end = False, dict[str, Any]()
        if verdict is not None:
            truncated, end = self._end_info(verdict)
            self._episode, self.agents = None, []
        infos = self._infos(episode, live, end)
        for agent in live:
            infos[agent]["reward_terms"] = terms[agent]
        done = verdict is not None
        if self.render_mode == "human":
            self.render()
        return (
            episode.observations(live),
            rewards,
            dict.fromkeys(live, done and not truncated),
            dict.fromkeys(live, done and truncated),
            infos,
        )

    def render(self) -> Any:
        """The field now: an RGB array (``"rgb_array"``), or logged to rerun (``"human"``)."""
        return self._view.render(self._arena)

    def close(self) -> None:
        """Close the viewer's recording, if any."""
        self._view.close()

    # ------------------------------------------------------------------ helpers

    def _checked(self, agent: str, value: Any, episode: _PlayEpisode) -> int | tuple[Action, ...]:
        """An action checked against the agent's space (and its mask when it decides)."""
        if self.action_mode != "macro":
            top = self.facts.player_top_speed_mps
            held = decode_action(self.action_mode, value, top, self.turn_step_rad)
            return cast(tuple[Action, ...], held)  # not "wheels": body actions
        count = macro_count(self.team_sizes[self.refs[agent].team])
        index = checked_macro(agent, value, count)
        mask = episode.masks.get(agent)
        if agent in episode.deciding and mask is not None and not mask[index]:
            allowed = [int(i) for i in np.flatnonzero(mask)]
            raise ValueError(
                f"{agent}'s macro {index} is not open on its percept: its action_mask allows "
                f"{allowed}"
            )
        return index

    def _terms(
        self,
        team: str,
        before: tuple[int, int],
        after: tuple[int, int],
        holder: PlayerRef | None,
    ) -> dict[str, float]:
        """One agent's reward terms for one step (module docstring)."""
        own = 0 if team == LEFT else 1
        goals = (after[own] - before[own]) - (after[1 - own] - before[1 - own])
        held = 0.0 if holder is None else (1.0 if holder.team == team else -1.0)
        return {
            "goal": self.weights["goal"] * goals,
            "possession": self.weights["possession"] * held,
        }

    def _infos(
        self, episode: _PlayEpisode, agents: list[str], end: dict[str, Any]
    ) -> dict[str, dict[str, Any]]:
        common = {
            "tick": episode.arena.tick,
            "episode": episode.index,
            "seed": episode.seed,
            "score": self._score(episode.drill),
            **self._step_info(episode.drill),
            **end,
        }
        return {
            agent: {
                "player": str(self.refs[agent]),
                "deciding": agent in episode.deciding,
                **common,
            }
            for agent in agents
        }


class _PlayEpisode:
    """One episode: the drill, its arena and minds, the loop with a pause at every decision."""

    def __init__(self, env: PlayParallelEnv, seed: int, index: int) -> None:
        self.env, self.seed, self.index = env, seed, index
        rngs = TrialRngs(seed, index)
        self.drill = drill = env._new_drill()
        self.arena = arena = make_arena(env.field_model, env.preset, env.players, rngs,
                                        env.field_options)  # fmt: skip
        drill.setup(arena, rngs)
        minds: dict[PlayerRef, Mind] = dict(drill.minds(arena, rngs))
        self.macro_minds: dict[str, MacroMind] = {}
        self.held: dict[str, _HeldActions] = {}
        for agent, ref in env.refs.items():
            mind = minds[ref]
            if env.action_mode == "macro":
                assert isinstance(mind, TeamMind), "the drill's players are team minds"
                macro = MacroMind(mind.number, mind.setup, interception=mind.interception,
                                  lead=mind.lead, evaluator=mind.evaluator,
                                  pass_threshold=mind.pass_threshold)  # fmt: skip
                self.macro_minds[agent] = macro
                minds[ref] = macro
            else:
                self.held[agent] = minds[ref] = _HeldActions()
        self.agent_of = {ref: agent for agent, ref in env.refs.items()}
        for builder in env._builders.values():
            builder.reset()
        observer = None if env.action_mode == "macro" else self._resend
        self.loop = TrialLoop(arena, drill, minds, observer=observer)
        self.deciding: tuple[str, ...] = ()
        self.held_obs: dict[str, npt.NDArray[np.float32]] = {
            a: np.zeros(env._builders[a].space.shape or (0,), np.float32) for a in env.refs
        }
        self.masks: dict[str, npt.NDArray[np.int8]] = {}
        if env.action_mode == "macro":
            for agent, ref in env.refs.items():
                blank = np.zeros(macro_count(env.team_sizes[ref.team]), np.int8)
                blank[[Macro.AUTO, Macro.GO_HOME]] = 1
                self.masks[agent] = blank
        self._settled: list[Percept] = []
        self._sent = dict.fromkeys(env.refs, -env.command_ticks)

    def advance(self) -> Verdict | None:
        """Run to the next decision (None, :attr:`deciding` set) or to the end."""
        self.deciding = ()
        return self.loop.run(pause=self._pause)

    def apply(self, chosen: dict[str, int | tuple[Action, ...]]) -> None:
        """Give the checked actions to the agents' minds (macros or held actions)."""
        for agent, value in chosen.items():
            if isinstance(value, int):
                self.macro_minds[agent].macro = value
            else:
                self.held[agent].actions = value

    def observations(self, agents: list[str]) -> dict[str, Observation]:
        """Each agent's observation of its last percept (copies)."""
        if self.env.action_mode != "macro":
            return {a: self.held_obs[a].copy() for a in agents}
        return {
            a: {"observation": self.held_obs[a].copy(), "action_mask": self.masks[a].copy()}
            for a in agents
        }

    def _pause(self, percept: Percept) -> bool:
        """Whether agents decide on this tick, from `percept` on (the loop's pause rule).

        At the first controlled percept of a tick the rest of the tick is read too, so that
        the agents deciding on one tick decide in one step; the percepts read are not asked
        about again when the loop goes on.
        """
        if percept.player not in self.agent_of or any(percept is p for p in self._settled):
            return False
        pending = self.loop.pending()
        start = next(i for i, p in enumerate(pending) if p is percept)
        deciding = [p for p in pending[start:] if p.player in self.agent_of]
        self._settled = deciding
        for p in deciding:
            self._observe(p)
        self.deciding = tuple(dict.fromkeys(self.agent_of[p.player] for p in deciding))
        return True

    def _observe(self, percept: Percept) -> None:
        """The agent's observation (and mask) of `percept`."""
        env, arena = self.env, self.arena
        agent = self.agent_of[percept.player]
        facts = env.facts
        goal_x = facts.pitch.half_length_m * (1.0 if percept.player.team == LEFT else -1.0)
        left = max(0.0, 1.0 - arena.tick / self.loop.max_ticks)
        vector = env._builders[agent].build(percept, (goal_x, 0.0), left, facts.dt_s)
        if percept.player.team == RIGHT:
            vector[MIRRORED] = -vector[MIRRORED]  # a half turn: every agent attacks +x
        self.held_obs[agent] = vector
        macro = self.macro_minds.get(agent)
        if macro is not None:
            size = env.team_sizes[percept.player.team]
            self.masks[agent] = macro_mask(percept, macro.setup, size)

    def _resend(self, arena: Arena, percepts: list[Percept]) -> None:
        """The loop's observer: send held actions again every command period between percepts."""
        tick = arena.tick
        got = {p.player for p in percepts}
        for agent, proxy in self.held.items():
            ref = self.env.refs[agent]
            if ref in got:
                self._sent[agent] = tick
            elif proxy.actions and tick - self._sent[agent] >= self.env.command_ticks:
                arena.submit(ref, proxy.actions)
                self._sent[agent] = tick


def _weights(given: dict[str, float] | None) -> dict[str, float]:
    return reward_weights(DEFAULT_WEIGHTS, given)


def _lookup(table: dict[str, spaces.Space[Any]], agent: str) -> spaces.Space[Any]:
    try:
        return table[agent]
    except KeyError:
        raise ValueError(f"unknown agent {agent!r} (agents: {list(table)})") from None
