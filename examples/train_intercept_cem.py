"""Train a defender through the Gymnasium API with the cross-entropy method (torch policy).

    .venv/bin/python examples/train_intercept_cem.py [--field soccer_server] [--iterations 15]

The policy is a small torch net, (BD, BA, previous BD) → TA, the paper's 3-4-1 shape (§5). Its
weights are searched by the cross-entropy method: each iteration samples a population of weight
vectors, scores each on the same episodes of ``robotsoccer/Intercept-v0`` (reward 1 per save),
and refits the sampling distribution to the best quarter. Episodes run through the vector
environment (``gymnasium.make_vec``): on the Soccer Server one batched step plays every
candidate's episodes at once (:class:`~robotsoccer.envs.intercept_vector.InterceptVectorEnv`);
on the robots it is a ``SyncVectorEnv``. It prints the learning curve: saves of the mean policy
on held-out episodes, with a 95% interval, beside the straight defender (TA = 0) on the same
episodes.
"""

from __future__ import annotations

import argparse
import time

import gymnasium as gym
import numpy as np
import torch

import robotsoccer.envs  # noqa: F401 (registers the environment ids)
from robotsoccer.stats import wilson_interval

HIDDEN = 4
# Inputs of order one: BD and previous BD over the 14-unit trigger, BA in units of about 2°
# (the ball's bearing at the trigger is small; the paper's lookup table spans ±7°).
SCALE = np.array([1 / 14.0, 30.0, 1 / 14.0], dtype=np.float32)
TEST_SEED = 10_000_000
"""Held-out episodes: seeds far from the training ones (sub-environment i uses seed + i)."""


def make_policy() -> torch.nn.Sequential:
    """The paper's 3-4-1 shape with a tanh hidden layer; TA in radians."""
    return torch.nn.Sequential(
        torch.nn.Linear(3, HIDDEN), torch.nn.Tanh(), torch.nn.Linear(HIDDEN, 1)
    )


def saves(env: gym.vector.VectorEnv, policy: torch.nn.Module, seed: int) -> int:
    """Saves in one episode per sub-environment, the episodes of seed `seed` onward."""
    obs, _ = env.reset(seed=seed)
    with torch.no_grad():
        ta = policy(torch.from_numpy(obs * SCALE)).numpy()
    _, rewards, _, _, _ = env.step(ta.astype(np.float32))
    return int(np.sum(rewards))


def percent(k: int, n: int) -> str:
    """``k/n`` as a percentage with its 95% Wilson interval."""
    low, high = wilson_interval(k, n)
    return f"{100 * k / n:5.1f}% [{100 * low:.1f}, {100 * high:.1f}]"


def main(argv: list[str] | None = None) -> None:
    """Run the search and print the learning curve."""
    parser = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0])
    parser.add_argument("--field", default="soccer_server")
    parser.add_argument("--iterations", type=int, default=15)
    parser.add_argument("--population", type=int, default=24)
    parser.add_argument("--episodes", type=int, default=200, help="per candidate")
    parser.add_argument("--test-episodes", type=int, default=5000)
    parser.add_argument("--seed", type=int, default=0)
    args = parser.parse_args(argv)
    torch.manual_seed(args.seed)
    rng = np.random.default_rng(args.seed)
    options = {"field_model": args.field, "ball_noise": 0.05}
    train = gym.make_vec("robotsoccer/Intercept-v0", num_envs=args.episodes, **options)
    test = gym.make_vec("robotsoccer/Intercept-v0", num_envs=args.test_episodes, **options)
    policy = make_policy()
    params = torch.nn.utils.parameters_to_vector(policy.parameters()).detach().numpy()
    mean, std = np.zeros_like(params), np.full_like(params, 0.5)
    straight = torch.nn.Sequential(torch.nn.Linear(3, 1))
    torch.nn.init.zeros_(straight[0].weight)
    torch.nn.init.zeros_(straight[0].bias)
    n = args.test_episodes
    print(f"straight (TA = 0): {percent(saves(test, straight, TEST_SEED), n)} saves, n = {n}")
    print("iteration  episodes  best candidate  mean policy on test (95% interval)")
    start = time.perf_counter()
    for it in range(args.iterations):
        candidates = mean + std * rng.standard_normal((args.population, len(mean)))
        scores = []
        for theta in candidates:
            vector = torch.from_numpy(theta).float()
            torch.nn.utils.vector_to_parameters(vector, policy.parameters())
            # Common random numbers: every candidate meets the same episodes this iteration.
            scores.append(saves(train, policy, args.seed * 1_000_000 + it * args.episodes))
        elite = candidates[np.argsort(scores)[-max(2, args.population // 4) :]]
        mean, std = elite.mean(axis=0), elite.std(axis=0) + 0.02
        torch.nn.utils.vector_to_parameters(torch.from_numpy(mean).float(), policy.parameters())
        episodes = (it + 1) * args.population * args.episodes
        best = 100 * max(scores) / args.episodes
        tested = percent(saves(test, policy, TEST_SEED), n)
        print(f"{it + 1:9d}  {episodes:8d}  {best:13.1f}%  {tested}")
    print(f"{time.perf_counter() - start:.1f} s for the search")


if __name__ == "__main__":
    main()
