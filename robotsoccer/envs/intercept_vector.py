"""Many interception episodes at once: a Gymnasium vector environment over the batched drill.

:class:`InterceptVectorEnv` is ``num_envs`` copies of :class:`~robotsoccer.envs.intercept.
InterceptEnv` stepped together by the batched drill engine
(:mod:`robotsoccer.drills.intercept_batch`) instead of one trial at a time. Each sub-environment
poses the paper's layer-1 decision (§5): the observation is (BD [units], BA [rad], previous BD
[units]) at the defender's trigger, the action is TA [rad], and the episode ends at the coach's
verdict with reward 1 for a SAVE.

**Exactly the single environment.** Sub-environment i after ``reset(seed=s)`` plays the episode
stream of ``InterceptEnv`` reset with seed ``s + i`` (Gymnasium's convention for vector seeds):
the same trials, the same observations, the same outcome for the same actions (a test checks
it). A list of seeds gives each sub-environment its own.

**Autoreset.** Every episode is one decision (a contextual bandit), so each step ends every
sub-environment. The mode is Gymnasium's ``SAME_STEP``: ``step`` returns the verdicts' rewards
and, as observations, the next episodes' first observations; the finished episodes' own
observations are in ``infos["final_obs"]`` (and ``infos["_final_obs"]``), as Gymnasium's vector
environments put them.

**How.** A step runs two batches: the trials played to their verdicts with the given TAs
(:func:`~robotsoccer.drills.intercept_batch.play_batch`), then the next trials up to their
decisions (:func:`~robotsoccer.drills.intercept_batch.decisions_batch`), skipping trials in
which the defender never decides, as the single environment does. Replaying the part of a trial
before its decision costs about half a trial; it keeps the batch in lockstep, which is what makes
it fast.

Only field models with a batch arena (today the Soccer Server) are supported; on the robot
table ``gymnasium.make_vec("robotsoccer/Intercept-v0", ...)`` gives a ``SyncVectorEnv`` over
``InterceptEnv`` (:func:`make_intercept_vector_env`).

**Frames.** The batch keeps arrays, not arenas, so ``render_mode="rgb_array"`` draws each
sub-environment's present decision by playing its trial to that decision on the one-trial path
(the same trial, bit for bit: see above). That costs a trial per sub-environment per frame.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Sequence
from typing import Any

import gymnasium as gym
import numpy as np
import numpy.typing as npt
from gymnasium.vector import AutoresetMode
from gymnasium.vector.utils import batch_space

from field_models.registry import PAPER_FIELD
from robotsoccer.drills.intercept_batch import batch_reason, decisions_batch, play_batch
from robotsoccer.envs.checks import SEED_LIMIT, checked_seed, checked_seeds, checked_turns
from robotsoccer.envs.intercept import MAX_DISTANCE_UNITS, SKIP_LIMIT, InterceptEnv, _Episode
from robotsoccer.envs.rendering import ArenaView
from robotsoccer.skills.intercept import TA_CLIP_RAD


class InterceptVectorEnv(gym.vector.VectorEnv[np.ndarray, np.ndarray, np.ndarray]):
    """``num_envs`` interception decisions stepped as one batch (module docstring).

    Args:
        num_envs: Sub-environments.
        field_model: A field model with a batch arena (default: the paper's, the Soccer Server).
        preset: Its preset; None: the model's default.
        ball_noise: Ball-motion noise; None: the preset's.
        drill_options: Further options of the interception drill (as ``InterceptEnv``).
        render_mode: None or ``"rgb_array"`` (module docstring).

    Raises:
        ValueError: The field or the drill options cannot run batched, or another render mode.
    """

    metadata: dict[str, Any] = {  # noqa: RUF012 (Gymnasium's class attribute)
        "render_modes": ["rgb_array"],
        "autoreset_mode": AutoresetMode.SAME_STEP,
    }

    def __init__(
        self,
        num_envs: int,
        field_model: str = PAPER_FIELD[0],
        preset: str | None = None,
        ball_noise: float | None = None,
        drill_options: dict[str, Any] | None = None,
        render_mode: str | None = None,
    ) -> None:
        if num_envs < 1:
            raise ValueError(f"num_envs must be >= 1, got {num_envs}")
        if render_mode not in (None, "rgb_array"):
            raise ValueError(f"render_mode must be None or 'rgb_array' here, got {render_mode!r}")
        self.render_mode = render_mode
        self._view = ArenaView(render_mode, title="Intercept-v0")
        single = InterceptEnv(field_model, preset, ball_noise, drill_options)
        why = batch_reason(single.spec_)
        if why is not None:
            raise ValueError(f"no batched interception here: {why}")
        self.spec_ = single.spec_
        self.unit_m = single.unit_m
        self.num_envs = num_envs
        self.single_observation_space = single.observation_space
        self.single_action_space = single.action_space
        self.observation_space = batch_space(self.single_observation_space, num_envs)
        self.action_space = batch_space(self.single_action_space, num_envs)
        self._seeds = np.zeros(num_envs, dtype=np.uint64)
        self._trials = np.zeros(num_envs, dtype=np.int64)  # the trial each sub-env is at
        self._obs = np.zeros((num_envs, 3), dtype=np.float32)
        self._ready = False

    def reset(
        self, *, seed: int | Sequence[int] | None = None, options: dict[str, Any] | None = None
    ) -> tuple[np.ndarray, dict[str, Any]]:
        """Start every sub-environment's episode stream (module docstring) at its first decision.

        `seed`: one int (sub-environment i gets ``seed + i``), one per sub-environment, or None
        (seeds drawn from the vector environment's own generator, itself seeded from the OS).

        Raises:
            ValueError: A seed that is not a whole number in [0, 2^64) (``seed + i`` included),
                or a list of seeds of another length.
        """
        if seed is None:
            if not hasattr(self, "_np_random") or self._np_random is None:
                self._np_random, _ = gym.utils.seeding.np_random(None)
            seeds = [int(s) for s in self._np_random.integers(2**31 - 1, size=self.num_envs)]
        elif isinstance(seed, int | np.integer) and not isinstance(seed, bool):
            first = checked_seed(seed)
            assert first is not None
            if first + self.num_envs > SEED_LIMIT:
                raise ValueError(f"seed + i must be below 2**64 for all {self.num_envs} envs")
            seeds = [first + i for i in range(self.num_envs)]
            self._np_random, _ = gym.utils.seeding.np_random(first)
        else:
            seeds = checked_seeds(seed, self.num_envs)
        # uint64: a seed up to 2^64 - 1 fits; the batch reads the same 64 bits as int64.
        self._seeds = np.array(seeds, dtype=np.uint64)
        self._trials = np.zeros(self.num_envs, dtype=np.int64)
        self._next_decisions(np.ones(self.num_envs, dtype=bool))
        self._ready = True
        return self._obs.copy(), {"trial": self._trials.copy(), "seed": self._seeds.copy()}

    def step(
        self, actions: npt.ArrayLike
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, dict[str, Any]]:
        """Play every episode to its verdict with TA = `actions`; start the next ones."""
        if not self._ready:
            raise RuntimeError("step() before reset()")
        ta = np.clip(checked_turns(actions, self.num_envs), -TA_CLIP_RAD, TA_CLIP_RAD)
        results = play_batch(self.spec_, self._batch_seeds(), self._trials, ta)
        labels = np.array([r.label for r in results])
        rewards = (labels == "SAVE").astype(np.float64)
        infos: dict[str, Any] = {
            "label": labels,
            "reason": np.array([r.reason for r in results]),
            "ticks": np.array([r.ticks for r in results]),
            "trial": self._trials.copy(),
            "final_obs": self._obs.copy(),
            "_final_obs": np.ones(self.num_envs, dtype=bool),
        }
        self._trials += 1
        self._next_decisions(np.ones(self.num_envs, dtype=bool))
        done = np.ones(self.num_envs, dtype=bool)
        return self._obs.copy(), rewards, done, np.zeros(self.num_envs, dtype=bool), infos

    def _batch_seeds(self) -> npt.NDArray[np.int64]:
        """The seeds as the batch takes them: int64 holding the same 64 bits.

        The streams mix the seed modulo 2^64, so a seed above 2^63 gives the numbers the single
        environment gives it.
        """
        return self._seeds.astype(np.int64)

    def render(self) -> tuple[np.ndarray, ...] | None:
        """Each sub-environment's field at its present decision (module docstring)."""
        if self.render_mode is None or not self._ready:
            return None
        frames = []
        for seed, trial in zip(self._seeds.tolist(), self._trials.tolist(), strict=True):
            episode = _Episode(dataclasses.replace(self.spec_, seed=seed), trial)
            episode.run_to_decision()
            frames.append(self._view.frame(episode.arena))
        return tuple(frames)

    def _next_decisions(self, pending: npt.NDArray[np.bool_]) -> None:
        """From each pending sub-env's present trial on, find the first with a decision."""
        for _ in range(SKIP_LIMIT):
            rows = np.flatnonzero(pending)
            if not rows.size:
                return
            found = decisions_batch(self.spec_, self._batch_seeds()[rows], self._trials[rows])
            decided = ~np.isnan(found[:, 0])
            u = self.unit_m
            bd, ba, previous = found[decided].T
            self._obs[rows[decided]] = np.stack(
                (np.minimum(bd / u, MAX_DISTANCE_UNITS), ba,
                 np.minimum(previous / u, MAX_DISTANCE_UNITS)), axis=1,
            )  # fmt: skip
            self._trials[rows[~decided]] += 1
            pending[rows[decided]] = False
        raise RuntimeError(f"no decision in {SKIP_LIMIT} trials in a row: check the drill options")


def make_intercept_vector_env(
    num_envs: int = 1, **kwargs: Any
) -> gym.vector.VectorEnv[Any, Any, Any]:
    """``gymnasium.make_vec``'s entry point (``vector_entry_point``) for ``Intercept-v0``.

    The batched :class:`InterceptVectorEnv` where the field has a batch arena; elsewhere (the
    robot table) a ``SyncVectorEnv`` over ``InterceptEnv`` with its ``SAME_STEP`` autoreset,
    so both behave alike.
    """
    single = InterceptEnv(**kwargs)
    if batch_reason(single.spec_) is None:
        return InterceptVectorEnv(num_envs, **kwargs)
    return CheckedSyncVectorEnv(
        [lambda: InterceptEnv(**kwargs) for _ in range(num_envs)],
        autoreset_mode=AutoresetMode.SAME_STEP,
    )


class CheckedSyncVectorEnv(gym.vector.SyncVectorEnv):
    """Gymnasium's ``SyncVectorEnv`` that refuses a batch of actions of the wrong shape.

    Gymnasium itself would hand the first ``num_envs`` rows out and drop the rest.
    """

    def step(
        self, actions: npt.ArrayLike
    ) -> tuple[Any, np.ndarray, np.ndarray, np.ndarray, dict[str, Any]]:
        """Check the batch (:func:`~robotsoccer.envs.checks.checked_turns`), then step."""
        turns = checked_turns(actions, self.num_envs)
        return super().step(turns.reshape(self.num_envs, 1))
