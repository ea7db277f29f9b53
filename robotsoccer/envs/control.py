"""Per-step control environments on either field model: go to the ball, and score.

Where :class:`~robotsoccer.envs.intercept.InterceptEnv` poses one decision per trial, these
give a policy the body every step, as robot-soccer RL users expect (rSoccer's ``VSS-v0``):

* ``robotsoccer/GoToBall-v0`` (:class:`~robotsoccer.envs.go_to_ball.GoToBallEnv`): one
  player alone with a still ball. It must reach the ball and face a target point (that
  class's docstring).
* ``robotsoccer/Score-v0`` (:class:`~robotsoccer.envs.score.ScoreEnv`): one learning player
  in a small-sided match (3 v 3 by default, on the robots the ``vss`` preset), everyone else
  driven by the baseline team minds (:mod:`robotsoccer.skills.team`) under the match's
  referee. The episode ends on a goal, on the ball leaving play (the referee's next call: a
  throw-in, goal kick or corner on an open field, a drop ball for a ball stuck on the walled
  table) or on the time limit.

Both run on every field model (``field_model=...``): the Soccer Server twin takes the same
task in that field's own commands. Actions, observations and reward weights are documented
in :mod:`robotsoccer.envs.control_spaces`. This module is what the tasks share
(:class:`ControlEnv`); each task is a module of its own.

**One step** is ``frames_per_step`` percepts of the learning player (default one: a camera
frame on the robots, a see on the Soccer Server). The action is sent when the step starts and
held (sent again every command period) until the step ends; the field runs tick by tick, the
other players' minds act on their own percepts, and the coach judges every tick on the truth.
The observation is built from the learner's last percept.

**Options.** ``perfect_perception`` (the sensor without noise, misses or latency) and
``ideal_actuation`` (on the robots: no link latency, loss or rate limit and no watchdog; the
Soccer Server's commands already act in the next cycle, unlost) switch the imperfections off;
``privileged`` adds the true state to the observation; ``max_time_s`` the time limit (a
truncation); ``reward_weights`` replaces any of the task's weights (an unknown term is
refused); ``render_mode`` ``"rgb_array"`` or ``"human"`` (:mod:`robotsoccer.envs.rendering`).

**Seeds** follow :class:`~robotsoccer.envs.intercept.InterceptEnv`: ``reset(seed=s)`` starts
the episode stream of experiment seed `s`, episode k drawing every random number from trial
k's named streams (:mod:`field_models.seeding`), so the same seed and actions give the same
episode in any process. ``reset()`` continues the stream; the first one without a seed draws
one from the OS.

**Bad input.** ``step`` before ``reset`` (or after the end) raises RuntimeError; an action of
the wrong shape or type, or with NaN or infinity, a ValueError naming it; Box actions outside
their bounds are clipped to them. An unknown action kind, preset or ``reset`` option is
refused in one line.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, ClassVar

import gymnasium as gym
from gymnasium import spaces

from field_models.arena import Arena, FieldFacts, FieldOptions, WheelDrive
from field_models.protocol import Mind, Percept, PlayerRef
from field_models.registry import FIELD_MODELS, field_facts, make_arena
from field_models.seeding import TrialRngs
from robotsoccer.envs.control_spaces import (
    ACTION_KINDS,
    COMMAND_PERIOD_S,
    DEFAULT_TURN_STEP_RAD,
    Held,
    ObservationBuilder,
    action_space,
    decode_action,
    reward_weights,
    state_space,
    state_vector,
)
from robotsoccer.envs.rendering import RENDER_MODES, ArenaView

SKIP_LIMIT = 100
"""reset() gives up after this many episodes in a row that end before the first step."""
TIME_OUT = "TIME_OUT"
"""The label of an episode cut by the time limit (a truncation)."""


@dataclass(frozen=True)
class ControlOptions:
    """The options of a control environment, checked (module docstring, "Options").

    Attributes:
        action: The action kind (:data:`~robotsoccer.envs.control_spaces.ACTION_KINDS`); None:
            ``wheels`` on a field that drives wheels, else ``commands``.
        frames_per_step: The learner's percepts per step (a whole number >= 1).
        perfect_perception: The sensor without noise, misses or latency.
        ideal_actuation: On the robots, no link latency, loss or rate limit and no watchdog.
        privileged: Add the true state to the observation.
        max_time_s: The time limit [s] (a truncation); None: the task's.
        reward_weights: Weights replacing any of the task's (an unknown term is refused).
        turn_step_rad: A discrete turn's angle [rad].
        render_mode: None, ``"rgb_array"`` or ``"human"`` (:mod:`robotsoccer.envs.rendering`).
        render_width: An ``"rgb_array"`` frame's width [pixels].

    Raises:
        ValueError: A `frames_per_step` that is not a whole number >= 1, a `max_time_s` that
            is not a finite number > 0.
    """

    action: str | None = None
    frames_per_step: int = 1
    perfect_perception: bool = False
    ideal_actuation: bool = False
    privileged: bool = False
    max_time_s: float | None = None
    reward_weights: dict[str, float] | None = None
    turn_step_rad: float = DEFAULT_TURN_STEP_RAD
    render_mode: str | None = None
    render_width: int = 480

    def __post_init__(self) -> None:
        steps = self.frames_per_step
        if not isinstance(steps, int) or steps < 1:
            raise ValueError(f"frames_per_step must be a whole number >= 1: {steps!r}")
        limit = self.max_time_s
        if limit is not None and not (math.isfinite(limit) and limit > 0.0):
            raise ValueError(f"max_time_s must be a finite number > 0, got {limit!r}")


class ControlEnv(gym.Env[Any, Any]):
    """What both tasks share: the episode loop, actions, observations, rewards, frames.

    A task fills in the class attributes and the ``_task_*`` hooks.

    Args:
        field_model: Any registered field model (default: the first).
        preset: Its preset; None: the task's default.
        options: The options (:class:`ControlOptions`); None: built from `keywords`.
        **keywords: The options' fields by name (``action=``, ``frames_per_step=``, ...),
            where `options` is not given: a Gymnasium ``make``'s keywords.

    Raises:
        ValueError: A bad option, or both a record and keywords; an unknown action kind for
            the field, an unknown preset.
    """

    # Gymnasium's class attribute.
    metadata: dict[str, Any] = {"render_modes": RENDER_MODES, "render_fps": 30}  # noqa: RUF012
    default_weights: ClassVar[dict[str, float]] = {}
    sparse_term: ClassVar[str] = ""

    def __init__(
        self,
        field_model: str = FIELD_MODELS[0],
        preset: str | None = None,
        options: ControlOptions | None = None,
        **keywords: Any,
    ) -> None:
        if options is not None and keywords:
            raise ValueError("give the environment an options record or keywords, not both")
        self.options = o = options if options is not None else ControlOptions(**keywords)
        action, perfect_perception = o.action, o.perfect_perception
        self.field_model = field_model
        self.preset = preset or self._default_preset(field_model)
        self.field_options = FieldOptions(perfect_perception=perfect_perception, all_landmarks=True)
        self.facts: FieldFacts = field_facts(field_model, self.preset, self.field_options)
        self.players = self._task_players(self.facts)
        probe = self._build_arena(TrialRngs(0, 0))
        drives = isinstance(probe, WheelDrive)
        self.action_kind = action or ("wheels" if drives else "commands")
        if self.action_kind not in ACTION_KINDS:
            raise ValueError(f"unknown action {action!r} (kinds: {', '.join(ACTION_KINDS)})")
        if self.action_kind == "wheels" and not drives:
            raise ValueError(f"action 'wheels' needs a field that drives wheels, not {field_model}")
        self.frames_per_step = o.frames_per_step
        self.ideal_actuation = o.ideal_actuation
        self.privileged = o.privileged
        self.turn_step_rad = float(o.turn_step_rad)
        self.weights = reward_weights_for(self, o.reward_weights)
        facts = self.facts
        self.max_time_s = o.max_time_s or self._default_max_time_s(facts)
        self.max_ticks = max(1, round(self.max_time_s / facts.dt_s))
        period = min(facts.sensor_period_s, COMMAND_PERIOD_S)
        self.command_ticks = max(1, round(period / facts.dt_s))
        self.builder = ObservationBuilder(facts, *self._task_slots())
        self.action_space = action_space(self.action_kind)
        self.observation_space: spaces.Space[Any] = self.builder.space
        if o.privileged:
            self.observation_space = spaces.Dict(
                {"observation": self.builder.space, "state": state_space(len(self.players))}
            )
        self.render_mode = o.render_mode
        self._view = ArenaView(o.render_mode, o.render_width, title=type(self).__name__)
        self._experiment_seed: int | None = None
        self._next_episode = 0
        self._arena: Arena | None = None
        self._percept: Percept | None = None
        self._minds: dict[PlayerRef, Mind] = {}
        self._held: Held | None = None
        self._running = False

    # ------------------------------------------------------------------ Gymnasium API

    def reset(
        self, *, seed: int | None = None, options: dict[str, Any] | None = None
    ) -> tuple[Any, dict[str, Any]]:
        """Start the next episode of the stream and run it to the learner's first percept.

        Raises:
            ValueError: Any `options` (none are taken).
        """
        super().reset(seed=seed)
        if options:
            raise ValueError(f"unknown reset options {sorted(options)} (none are taken)")
        if seed is not None:
            self._experiment_seed, self._next_episode = int(seed), 0
        elif self._experiment_seed is None:
            self._experiment_seed = int(self.np_random.integers(2**31 - 1))
        for _ in range(SKIP_LIMIT):
            episode = self._next_episode
            self._next_episode += 1
            if self._start(TrialRngs(self._experiment_seed, episode)):
                self._running = True
                info = {"episode": episode, "seed": self._experiment_seed}
                if self.render_mode == "human":
                    self.render()
                return self._observation(), info
        raise RuntimeError(f"{SKIP_LIMIT} episodes in a row ended before their first step")

    def step(self, action: Any) -> tuple[Any, float, bool, bool, dict[str, Any]]:
        """Hold `action` for one step (module docstring); the reward and its terms in info."""
        arena = self._arena
        if arena is None or not self._running:
            raise RuntimeError("step() before reset(), or after the episode ended: call reset()")
        held = decode_action(self.action_kind, action, self.facts.player_top_speed_mps,
                             self.turn_step_rad)  # fmt: skip
        self._held = held
        self._send(held)
        before = self._task_potentials(arena)
        label, sparse = self._advance(self.frames_per_step)
        after = self._task_potentials(arena)
        weights = self.weights
        terms = {name: weights[name] * (after[name] - value) for name, value in before.items()}
        terms["time"] = -weights["time"]
        terms[self.sparse_term] = weights[self.sparse_term] * sparse
        truncated = label == TIME_OUT
        terminated = label is not None and not truncated
        self._running = label is None
        info: dict[str, Any] = {"reward_terms": terms, "tick": arena.tick, "label": label or ""}
        info |= self._task_info(label)
        if self.render_mode == "human":
            self.render()
        reward = float(sum(terms.values()))
        return self._observation(), reward, terminated, truncated, info

    def render(self) -> Any:
        """The present frame: an RGB array (``"rgb_array"``), or logged to rerun (``"human"``)."""
        return self._view.render(self._arena)

    def close(self) -> None:
        """Close the viewer's recording."""
        self._view.close()

    # ------------------------------------------------------------------ the episode

    def _build_arena(self, rngs: TrialRngs) -> Arena:
        return make_arena(self.field_model, self.preset, self.players, rngs, self.field_options)

    def _start(self, rngs: TrialRngs) -> bool:
        """Build and place episode `rngs`, run to the first percept; False: it ended first."""
        arena = self._arena = self._build_arena(rngs)
        if self.ideal_actuation and isinstance(arena, WheelDrive):
            arena.ideal_actuation()
        self._minds = self._task_setup(arena, rngs)
        arena.listen(frozenset(self._minds) | {self.learner})
        self.builder.reset()
        self._held = None
        self._percept = None
        label, _ = self._advance(1)
        return label is None

    def _advance(self, frames: int) -> tuple[str | None, float]:
        """Step ticks until the learner got `frames` percepts or the episode ended.

        Returns the end's label and sparse reward, or (None, 0) when the step just ends.
        """
        arena = self._arena
        assert arena is not None
        learner, minds, held = self.learner, self._minds, self._held
        start, period, seen = arena.tick, self.command_ticks, 0
        while True:
            percepts = arena.step()
            tick = arena.tick
            got = None
            for percept in percepts:
                player = percept.player
                if player is learner or player == learner:
                    got = percept
                    continue
                mind = minds.get(player)
                if mind is not None:
                    arena.submit(player, mind.act(percept))
            if got is not None:
                self._percept = got
            outcome = self._task_judge(arena)
            if outcome is not None:
                return outcome
            if tick >= self.max_ticks:
                return TIME_OUT, 0.0
            if got is not None:
                seen += 1
                if seen >= frames:
                    return None, 0.0
            if held is not None and (got is not None or (tick - start) % period == 0):
                self._send(held)

    def _send(self, held: Held) -> None:
        """Send the held action to the learner through the field's actuation path."""
        arena = self._arena
        assert arena is not None
        if self.action_kind == "wheels":
            assert isinstance(arena, WheelDrive)
            left, right = held
            arena.submit_wheels(self.learner, float(left), float(right))  # type: ignore[arg-type]
        else:
            arena.submit(self.learner, held)  # type: ignore[arg-type]

    def _observation(self) -> Any:
        arena, percept = self._arena, self._percept
        assert arena is not None and percept is not None
        left = max(0.0, 1.0 - arena.tick / self.max_ticks)
        vector = self.builder.build(percept, self._task_target(), left, self.facts.dt_s)
        if not self.privileged:
            return vector
        return {"observation": vector, "state": state_vector(arena.truth(), self.players,
                                                             self.facts)}  # fmt: skip

    # ------------------------------------------------------------------ the task's part

    learner: PlayerRef

    def _default_preset(self, field_model: str) -> str:
        """The preset used when none is named."""
        return field_facts(field_model).preset

    def _default_max_time_s(self, facts: FieldFacts) -> float:
        raise NotImplementedError

    def _task_players(self, facts: FieldFacts) -> tuple[PlayerRef, ...]:
        raise NotImplementedError

    def _task_slots(self) -> tuple[int, int]:
        """Teammate and opponent slots of the observation."""
        return (0, 0)

    def _task_setup(self, arena: Arena, rngs: TrialRngs) -> dict[PlayerRef, Mind]:
        """Place everything for a new episode; the other players' minds."""
        raise NotImplementedError

    def _task_judge(self, arena: Arena) -> tuple[str, float] | None:
        """After each tick: (label, sparse reward) when the episode ends, else None."""
        raise NotImplementedError

    def _task_potentials(self, arena: Arena) -> dict[str, float]:
        """The shaping potentials: each term's reward is its weight × the potential's gain."""
        raise NotImplementedError

    def _task_target(self) -> tuple[float, float]:
        """The field point of the observation's ``target`` entries [m]."""
        raise NotImplementedError

    def _task_info(self, label: str | None) -> dict[str, Any]:
        return {}


def reward_weights_for(env: ControlEnv, given: dict[str, float] | None) -> dict[str, float]:
    """The task's default weights with `given` ones replacing them (unknown terms refused)."""
    return reward_weights(type(env).default_weights, given)
