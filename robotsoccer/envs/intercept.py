"""The paper's layer-1 learning problem as a Gymnasium environment, on any field model.

The paper's defender makes one learned decision per trial (§5): when the ball first comes within
the trigger distance (14 units; the drill's plan), it picks TA, the angle to turn after facing
the ball, from (BD, BA, previous BD). This environment poses exactly that decision:

* :meth:`InterceptEnv.reset` places a trial of the interception drill
  (:class:`~robotsoccer.drills.intercept.InterceptDrill`) and runs it, with the shooter's kick
  and the defender watching the ball, up to the defender's first percept within the trigger
  distance. It returns that percept's (BD [units], BA [rad], previous BD [units]). A trial in
  which the ball never comes that close is skipped: nothing was decided in it.
* :meth:`InterceptEnv.step` takes TA [rad]. The defender turns by BA + TA and dashes at every
  percept, exactly as the drill's defender does, until the coach's verdict. The episode then
  ends: reward 1 for a SAVE, 0 for a GOAL or a MISS, and the label and reason in ``info``.

An episode is one trial: a contextual bandit, the setting the paper's net was trained in (it
regressed the TA of saves made with random TA). Distances are in drill units (field length /
105, :attr:`~field_models.arena.FieldFacts.unit_m`), so a policy means the same on every field.

**Seeds** follow Gymnasium: ``reset(seed=s)`` starts the episode stream of experiment seed `s`.
Episode k of that stream is trial k of the drill with seed `s`: the placement and noise that
``robotsoccer demo --drill intercept --seed s`` gives trial k. With TA = 0 an episode ends as
that trial does with ``behaviour=straight`` (a test checks it). ``reset()`` without a seed
continues the stream, and the first reset without one draws a seed from the OS.

Registered as ``robotsoccer/Intercept-v0``
(``gymnasium.make("robotsoccer/Intercept-v0", field_model="robot_physics")``).

**Frames**: ``render_mode="rgb_array"`` gives the field at the decision after ``reset`` and at
the verdict after ``step``; ``"human"`` streams them to the rerun viewer
(:mod:`robotsoccer.envs.rendering`).
"""

from __future__ import annotations

import dataclasses
import math
from typing import Any

import gymnasium as gym
import numpy as np
from gymnasium import spaces

from field_models.protocol import Mind, Percept, PlayerRef
from field_models.registry import FIELD_MODELS
from robotsoccer.drills.base import Verdict
from robotsoccer.drills.intercept import InterceptDrill
from robotsoccer.drills.intercept_plan import DEFENDER
from robotsoccer.envs.checks import checked_seed, checked_turns
from robotsoccer.envs.rendering import RENDER_MODES, ArenaView
from robotsoccer.runs.runner import TrialLoop, TrialSpec, build_trial
from robotsoccer.runs.spec import resolve
from robotsoccer.skills.intercept import TA_CLIP_RAD, DefenderMind

MAX_DISTANCE_UNITS = 60.0
"""The observation's distance bound (the drill places the ball at most 30 units away)."""
SKIP_LIMIT = 1000
"""reset() gives up after this many trials in a row without a decision."""


class _AgentTurn:
    """The defender's TA rule: whatever the agent chose for this episode (the policy protocol)."""

    def __init__(self) -> None:
        self.ta_rad = 0.0

    def __call__(self, *_: object) -> float:
        return self.ta_rad


class InterceptEnv(gym.Env[np.ndarray, np.ndarray]):
    """The defender's TA decision of the paper's interception drill (module docstring).

    Args:
        field_model: A registered field model (default: the first registered).
        preset: Its preset; None: the model's default.
        ball_noise: Ball-motion noise; None: the preset's.
        drill_options: Further options of the interception drill (``ta_mode`` excepted: the
            agent's TA is held, as in the paper).
        render_mode: None, ``"rgb_array"`` or ``"human"`` (module docstring).
    """

    # Gymnasium's class attribute.
    metadata: dict[str, Any] = {"render_modes": RENDER_MODES, "render_fps": 30}  # noqa: RUF012

    def __init__(
        self,
        field_model: str = FIELD_MODELS[0],
        preset: str | None = None,
        ball_noise: float | None = None,
        drill_options: dict[str, Any] | None = None,
        render_mode: str | None = None,
    ) -> None:
        self.render_mode = render_mode
        self._view = ArenaView(render_mode, title="Intercept-v0")
        self._shown: Any = None  # the arena render() draws: the last episode's
        options = {**(drill_options or {}), "behaviour": "analytic", "ta_mode": "hold"}
        spec = TrialSpec(drill="intercept", field_model=field_model, preset=preset)
        self.spec_ = spec.with_options(**options).with_field(ball_noise=ball_noise)
        self.observation_space = spaces.Box(
            low=np.array([0.0, -math.pi, 0.0], dtype=np.float32),
            high=np.array([MAX_DISTANCE_UNITS, math.pi, MAX_DISTANCE_UNITS], dtype=np.float32),
        )
        self.action_space = spaces.Box(
            low=np.array([-TA_CLIP_RAD], dtype=np.float32),
            high=np.array([TA_CLIP_RAD], dtype=np.float32),
        )
        self.unit_m = resolve(self.spec_).facts.unit_m  # the drill's options checked here too
        self._experiment_seed: int | None = None
        self._next_trial = 0
        self._episode: _Episode | None = None

    def reset(
        self, *, seed: int | None = None, options: dict[str, Any] | None = None
    ) -> tuple[np.ndarray, dict[str, Any]]:
        """Run the next trial up to the defender's decision; its (BD, BA, previous BD).

        Raises:
            ValueError: A seed that is not None or a whole number in [0, 2^64).
        """
        seed = checked_seed(seed)
        super().reset(seed=seed)
        if seed is not None:
            self._experiment_seed, self._next_trial = int(seed), 0
        elif self._experiment_seed is None:
            self._experiment_seed = int(self.np_random.integers(2**31 - 1))
        for _ in range(SKIP_LIMIT):
            trial = self._next_trial
            self._next_trial += 1
            episode = _Episode(dataclasses.replace(self.spec_, seed=self._experiment_seed), trial)
            if episode.run_to_decision():
                self._episode = episode
                self._shown = episode.arena
                if self.render_mode == "human":
                    self.render()
                info = {"trial": trial, "seed": self._experiment_seed}
                return episode.observation(), info
        raise RuntimeError(f"no decision in {SKIP_LIMIT} trials in a row: check the drill options")

    def step(self, action: np.ndarray) -> tuple[np.ndarray, float, bool, bool, dict[str, Any]]:
        """Turn by BA + TA and dash to the verdict; reward 1 for a SAVE.

        Raises:
            ValueError: An action that is not one finite number (shape (1,) or a scalar).
        """
        episode = self._episode
        if episode is None:
            raise RuntimeError("step() before reset(), or after the episode ended")
        turn = checked_turns(action, 1)[0]
        ta = float(np.clip(turn, -TA_CLIP_RAD, TA_CLIP_RAD))
        verdict = episode.finish(ta)
        self._episode = None
        reward = 1.0 if verdict.label == "SAVE" else 0.0
        info = {"label": verdict.label, "reason": verdict.reason, "ticks": episode.arena.tick}
        if self.render_mode == "human":
            self.render()
        return episode.observation(), reward, True, False, info

    def render(self) -> Any:
        """The field now: an RGB array (``"rgb_array"``), or logged to rerun (``"human"``)."""
        return self._view.render(self._shown)

    def close(self) -> None:
        """Close the viewer's recording, if any."""
        self._view.close()


class _Episode:
    """One trial of the drill, run by the runner's loop with a pause at the defender's decision."""

    def __init__(self, spec: TrialSpec, trial: int) -> None:
        rngs, drill, arena = build_trial(spec, trial)
        assert isinstance(drill, InterceptDrill)
        drill.setup(arena, rngs)
        minds: dict[PlayerRef, Mind] = drill.minds(arena, rngs)
        mind = drill.defender_mind
        assert isinstance(mind, DefenderMind), "the environment plays the paper's TA decision"
        self.turn = _AgentTurn()
        mind.policy = self.turn
        self.defender = mind
        self.arena = arena
        self.loop = TrialLoop(arena, drill, minds)
        self.unit_m = arena.facts.unit_m
        self.trigger_m = drill.plan(arena).trigger_distance_m
        self.previous_bd: float | None = None
        self.features = np.zeros(3, dtype=np.float32)

    def run_to_decision(self) -> bool:
        """Step until the defender's first percept within the trigger; False: the trial ended."""
        return self.loop.run(pause=self._is_decision) is None

    def finish(self, ta_rad: float) -> Verdict:
        """Let the defender act with TA = `ta_rad` and run the trial to its verdict."""
        self.turn.ta_rad = ta_rad
        verdict = self.loop.run()
        assert verdict is not None
        return verdict

    def observation(self) -> np.ndarray:
        """(BD [units], BA [rad], previous BD [units]) at the decision."""
        return self.features.copy()

    def _is_decision(self, percept: Percept) -> bool:
        """The defender's first percept with the ball within the trigger distance.

        Asked of every percept before the decision, so it also keeps the previous sighting's BD
        (the defender's own rule, :class:`~robotsoccer.skills.intercept.DefenderMind`).
        """
        if percept.player != DEFENDER or not self.defender.decides_at(percept.tick):
            return False
        if percept.ball is None:
            return False
        bd = percept.ball.distance_m
        previous = bd if self.previous_bd is None else self.previous_bd
        if bd > self.trigger_m:
            self.previous_bd = bd
            return False
        u = self.unit_m
        self.features = np.array(
            [min(bd / u, MAX_DISTANCE_UNITS), percept.ball.angle_rad,
             min(previous / u, MAX_DISTANCE_UNITS)], dtype=np.float32,
        )  # fmt: skip
        return True
