"""Learn the ball holder's choice in half-field offense with the cross-entropy method.

    .venv/bin/python examples/train_hfo_holder_cem.py [--field soccer_server] [--iterations 12]

The layer-3 decision (TPOT-RL's "where to send the ball") through the HFO environment
(:mod:`robotsoccer.envs.hfo`, 2 attackers against a defender and a goalie, macro actions): when
an attacker holds the ball it chooses SHOOT, DRIBBLE or a pass to a teammate it sees, the same
choices :class:`~robotsoccer.envs.hfo_eval.RandomHolder` draws from; every other decision is
the team mind's (AUTO). The policy is linear in the attacker's percept vector (plus a bias):
one score each for SHOOT, DRIBBLE and a pass (one weight column shared by every open pass, so
it does not depend on the teammate's number); the open choice with the highest score is taken.

The cross-entropy method searches the weights: each iteration samples a population of weight
vectors from a diagonal Gaussian, plays each on the same training episodes (common random
numbers: experiment seed :data:`TRAIN_SEED`, a new block of episodes each iteration) and refits
the Gaussian to the best fifth by goal rate. The mean policy is then measured on the held-out
episodes of :func:`~robotsoccer.envs.hfo_eval.goal_rate`'s table (seed 0, 500 episodes), where
the hand-written and random holders were measured, and printed beside them with 95% Wilson
intervals. Everything is seeded: the same arguments give the same numbers.
"""

from __future__ import annotations

import argparse
import time

import numpy as np
import numpy.typing as npt

from robotsoccer.envs.hfo_eval import (
    TABLE_HEAD,
    GoalRate,
    RandomHolder,
    goal_rate,
    handwritten,
    table_row,
)
from robotsoccer.envs.macros import PASS_BASE, Macro

TRAIN_SEED = 1_000
"""Training episodes come from this experiment seed; the held-out table's is 0."""
CHOICES = 3
"""Scores: SHOOT, DRIBBLE, a pass."""
Array = npt.NDArray[np.float64]


class LinearHolder:
    """The holder's choice by a linear score of the percept vector (module docstring).

    Args:
        weights: Flat weights, (observation size + 1) × :data:`CHOICES`.
    """

    def __init__(self, weights: Array) -> None:
        self.w = weights.reshape(-1, CHOICES)

    def __call__(self, observation: npt.NDArray[np.float32], mask: npt.NDArray[np.int8]) -> int:
        """The open kick with the highest score."""
        x = np.append(observation.astype(np.float64), 1.0)
        score = x @ self.w
        open_ = [int(i) for i in np.flatnonzero(mask)]
        options = [(score[0], int(Macro.SHOOT)), (score[1], int(Macro.DRIBBLE))]
        options += [(score[2], i) for i in open_ if i >= PASS_BASE]
        return max((s, -i, i) for s, i in options if i in open_)[2]


def train(field: str, iterations: int, population: int, episodes: int, seed: int) -> Array:
    """The mean weights after `iterations` of the cross-entropy method (module docstring)."""
    rng = np.random.default_rng(seed)
    size = (observation_size(field) + 1) * CHOICES
    mean, std = np.zeros(size), np.full(size, 0.5)
    elite = max(2, population // 5)
    for iteration in range(iterations):
        start = time.perf_counter()
        thetas = mean + std * rng.standard_normal((population, size))
        block = TRAIN_SEED + iteration  # a new block of training episodes each iteration
        rates = [goal_rate(LinearHolder(t), field, episodes, block).rate for t in thetas]
        best = thetas[np.argsort(rates)[::-1][:elite]]
        mean, std = best.mean(axis=0), best.std(axis=0) + 0.02
        top = sorted(rates)[::-1][:elite]
        print(
            f"iteration {iteration + 1}: population mean {np.mean(rates):.3f}, elite mean "
            f"{np.mean(top):.3f} on {episodes} episodes ({time.perf_counter() - start:.0f} s)",
            flush=True,
        )
    return mean


def observation_size(field: str) -> int:
    """The attackers' percept vector size on `field`."""
    from robotsoccer.envs.hfo import HalfFieldOffenseEnv

    env = HalfFieldOffenseEnv(field, action="macro")
    space = env.observation_space(env.possible_agents[0])
    return int(space["observation"].shape[0])  # type: ignore[index]


def main(argv: list[str] | None = None) -> dict[str, GoalRate]:
    """Train, then print the held-out table; return its rows by policy name."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--field", default="soccer_server")
    parser.add_argument("--iterations", type=int, default=12)
    parser.add_argument("--population", type=int, default=20)
    parser.add_argument("--episodes", type=int, default=60, help="training episodes per policy")
    parser.add_argument("--test-episodes", type=int, default=500)
    parser.add_argument("--seed", type=int, default=0)
    args = parser.parse_args(argv)
    start = time.perf_counter()
    mean = train(args.field, args.iterations, args.population, args.episodes, args.seed)
    trained_s = time.perf_counter() - start
    print(f"trained in {trained_s:.0f} s (wall)")
    print(TABLE_HEAD)
    rows: dict[str, GoalRate] = {}
    for name, policy in (
        ("hand-written (AUTO)", handwritten),
        ("uniform random kick", RandomHolder(0)),
        ("CEM linear (mean)", LinearHolder(mean)),
    ):
        result = rows[name] = goal_rate(policy, args.field, args.test_episodes, 0)
        print(table_row(name, args.field, result), flush=True)
    return rows


if __name__ == "__main__":
    main()
