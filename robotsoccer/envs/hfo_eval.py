"""The attackers' goal rate in half-field offense for a ball-holder policy: layer 3's yardstick.

Layer 3 learns the ball holder's choice (TPOT-RL: where to send the ball). To compare learners
on equal terms, :func:`goal_rate` plays the same episodes for any such choice: episode k of
experiment seed `seed` is ``reset(seed=seed)`` followed by k plain ``reset()`` calls of
:class:`~robotsoccer.envs.hfo.HalfFieldOffenseEnv` in macro mode, the attackers controlled.

A **policy** is ``policy(observation, mask) -> macro``: the attacker's percept vector and its
macro mask (:mod:`robotsoccer.envs.macros`), asked only when the attacker holds the ball (its
mask opens the kicks); every other decision is ``AUTO``, the team mind's own play (chase,
intercept, go home). So the policies differ in the holder's choice alone. Two are here:

* :func:`handwritten` — ``AUTO`` on the ball too: the team minds' hand-written rule (shoot
  within range, pass when an opponent blocks the path, dribble otherwise);
* :class:`RandomHolder` — a uniformly random kick among those open (SHOOT, DRIBBLE, PASS_k),
  from its own seeded generator.

``python -m robotsoccer.envs.hfo_eval --episodes 500`` prints the table for both in-process
field models (``--fields`` names others).
"""

from __future__ import annotations

import argparse
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import numpy.typing as npt

from field_models.registry import FIELD_MODELS
from robotsoccer.envs.hfo import GOAL, OUTCOMES, HalfFieldOffenseEnv
from robotsoccer.envs.macros import KICKS, PASS_BASE, Macro
from robotsoccer.stats import wilson_interval

Policy = Callable[[npt.NDArray[np.float32], npt.NDArray[np.int8]], int]
"""The ball holder's choice: (percept vector, macro mask) -> macro index."""


def handwritten(observation: npt.NDArray[np.float32], mask: npt.NDArray[np.int8]) -> int:
    """The team minds' own rule on the ball: ``AUTO``."""
    return int(Macro.AUTO)


class RandomHolder:
    """A uniformly random kick among the open ones (SHOOT, DRIBBLE, PASS_k).

    Args:
        seed: Its generator's seed (the same seed, the same choices on the same episodes).
    """

    def __init__(self, seed: int = 0) -> None:
        self.rng = np.random.default_rng(seed)

    def __call__(self, observation: npt.NDArray[np.float32], mask: npt.NDArray[np.int8]) -> int:
        """One of the open kicks, uniformly."""
        kicks = [i for i in np.flatnonzero(mask) if i in KICKS or i >= PASS_BASE]
        return int(kicks[int(self.rng.integers(len(kicks)))])


@dataclass
class GoalRate:
    """Outcomes of a run of episodes: counts by HFO status, the goal rate and its interval.

    Attributes:
        episodes: Episodes played.
        outcomes: Count of each status (:data:`~robotsoccer.envs.hfo.OUTCOMES`).
        holder_choices: Decisions the policy took (the ball held).
        cpu_s: CPU seconds of the run.
    """

    episodes: int = 0
    outcomes: dict[str, int] = field(default_factory=lambda: dict.fromkeys(OUTCOMES, 0))
    holder_choices: int = 0
    cpu_s: float = field(default=0.0, compare=False)

    @property
    def goals(self) -> int:
        """Episodes that ended in a goal."""
        return self.outcomes[GOAL]

    @property
    def rate(self) -> float:
        """The share of episodes that ended in a goal."""
        return self.goals / self.episodes if self.episodes else 0.0

    @property
    def interval(self) -> tuple[float, float]:
        """The 95% Wilson interval of the goal rate."""
        return wilson_interval(self.goals, self.episodes)


def goal_rate(
    policy: Policy,
    field_model: str = FIELD_MODELS[0],
    episodes: int = 500,
    seed: int = 0,
    **env_options: Any,
) -> GoalRate:
    """Play `episodes` episodes of seed `seed` with `policy` on the ball (module docstring).

    Args:
        policy: The ball holder's choice.
        field_model: A registered field model.
        episodes: How many episodes.
        seed: The experiment seed of the episode stream.
        **env_options: Further options of :class:`~robotsoccer.envs.hfo.HalfFieldOffenseEnv`
            (``offense``, ``defense``, ``goalie``, ``preset`` …; ``action`` and ``controlled``
            are this function's).

    Raises:
        ValueError: Fewer than 1 episode, or an option the environment refuses.
    """
    if episodes < 1:
        raise ValueError(f"episodes must be at least 1, got {episodes!r}")
    refused = sorted({"action", "controlled"} & set(env_options))
    if refused:
        raise ValueError(f"options {refused} are goal_rate's own (macro actions, the offense)")
    env = HalfFieldOffenseEnv(field_model, action="macro", controlled="offense", **env_options)
    result = GoalRate()
    start = time.process_time()
    for k in range(episodes):
        observations, infos = env.reset(seed=seed if k == 0 else None)
        while env.agents:
            actions: dict[str, int] = {}
            for agent in env.agents:
                view = observations[agent]
                assert isinstance(view, dict)
                mask = view["action_mask"]
                holds = infos[agent]["deciding"] and bool(mask[Macro.SHOOT])
                if holds:
                    result.holder_choices += 1
                    actions[agent] = int(policy(view["observation"], mask))
                else:
                    actions[agent] = int(Macro.AUTO)
            observations, _, _, _, infos = env.step(actions)
        status = next(iter(infos.values()))["status"]
        result.outcomes[status] += 1
        result.episodes += 1
    result.cpu_s = time.process_time() - start
    return result


TABLE_HEAD = (
    "| holder's choice | field | n | goals | goal rate [95% CI] | other outcomes "
    "| holder decisions | CPU s |\n|---|---|---|---|---|---|---|---|"
)
"""The head of :func:`table_row`'s table."""


def table_row(name: str, field_model: str, result: GoalRate) -> str:
    """One markdown row: policy, field, n, goals, rate and interval, other outcomes, choices."""
    low, high = result.interval
    others = ", ".join(f"{k} {v}" for k, v in result.outcomes.items() if k != GOAL)
    return (
        f"| {name} | {field_model} | {result.episodes} | {result.goals} | "
        f"{100 * result.rate:.1f}% [{100 * low:.1f}, {100 * high:.1f}] | {others} | "
        f"{result.holder_choices} | {result.cpu_s:.0f} |"
    )


def main(argv: list[str] | None = None) -> None:
    """Print the hand-written and random holders' goal rates on every field model."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--episodes", type=int, default=500)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--fields", nargs="*", default=None)
    args = parser.parse_args(argv)
    if args.fields is None:  # the in-process engines, as robotsoccer bench times them
        from robotsoccer.bench import drill_models

        args.fields = list(drill_models())
    print(TABLE_HEAD)
    for field_model in args.fields:
        for name, policy in (("hand-written (AUTO)", handwritten),
                             ("uniform random kick", RandomHolder(args.seed))):  # fmt: skip
            result = goal_rate(policy, field_model, args.episodes, args.seed)
            print(table_row(name, field_model, result), flush=True)


if __name__ == "__main__":
    main()
