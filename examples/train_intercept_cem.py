"""Train a defender through the Gymnasium API with the cross-entropy method (torch policy).

    .venv/bin/python examples/train_intercept_cem.py [--field soccer_server] [--iterations 12]

The policy is a small torch net, (BD, BA, previous BD) → TA, as in the paper's §5. Its weights
are searched by the cross-entropy method: each iteration samples a population of weight vectors,
scores each on the same batch of episodes of ``robotsoccer/Intercept-v0`` (reward 1 per save), and
refits the sampling distribution to the best. It prints the learning curve: saves of the mean
policy on held-out episodes, beside the straight defender (TA = 0) on the same episodes.
"""

from __future__ import annotations

import argparse

import gymnasium as gym
import numpy as np
import torch

import robotsoccer.envs  # noqa: F401 (registers the environment ids)

HIDDEN = 4
# Inputs of order one: BD and previous BD over the 14-unit trigger, BA in units of about 2°
# (the ball's bearing at the trigger is small; the paper's lookup table spans ±7°).
SCALE = np.array([1 / 14.0, 30.0, 1 / 14.0], dtype=np.float32)


def make_policy() -> torch.nn.Sequential:
    """The paper's 3-4-1 shape with a tanh hidden layer; TA in radians."""
    return torch.nn.Sequential(
        torch.nn.Linear(3, HIDDEN), torch.nn.Tanh(), torch.nn.Linear(HIDDEN, 1)
    )


def saves(env: gym.Env, policy: torch.nn.Module, seed: int, episodes: int) -> float:
    """Share of saves over `episodes` episodes of the seed's stream."""
    total = 0.0
    obs, _ = env.reset(seed=seed)
    for _ in range(episodes):
        with torch.no_grad():
            ta = policy(torch.from_numpy(obs * SCALE)).numpy()
        _, reward, _, _, _ = env.step(ta.astype(np.float32))
        total += float(reward)
        obs, _ = env.reset()
    return total / episodes


def main() -> None:
    """Run the search and print the learning curve."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--field", default="soccer_server")
    parser.add_argument("--iterations", type=int, default=12)
    parser.add_argument("--population", type=int, default=24)
    parser.add_argument("--episodes", type=int, default=100, help="per candidate")
    parser.add_argument("--test-episodes", type=int, default=600)
    args = parser.parse_args()
    torch.manual_seed(0)
    rng = np.random.default_rng(0)
    env = gym.make("robotsoccer/Intercept-v0", field_model=args.field, ball_noise=0.05).unwrapped
    policy = make_policy()
    params = torch.nn.utils.parameters_to_vector(policy.parameters()).detach().numpy()
    mean, std = np.zeros_like(params), np.full_like(params, 0.5)
    straight = torch.nn.Sequential(torch.nn.Linear(3, 1))
    torch.nn.init.zeros_(straight[0].weight)
    torch.nn.init.zeros_(straight[0].bias)
    test_seed = 10_000
    baseline = saves(env, straight, test_seed, args.test_episodes)
    print(f"straight (TA = 0): {100 * baseline:.1f}% saves on {args.test_episodes} test episodes")
    print("iteration  episodes  best candidate  mean policy on test")
    for it in range(args.iterations):
        candidates = mean + std * rng.standard_normal((args.population, len(mean)))
        scores = []
        for theta in candidates:
            vector = torch.from_numpy(theta).float()
            torch.nn.utils.vector_to_parameters(vector, policy.parameters())
            # Common random numbers: every candidate meets the same episodes this iteration.
            scores.append(saves(env, policy, 1000 * it, args.episodes))
        elite = candidates[np.argsort(scores)[-max(2, args.population // 4) :]]
        mean, std = elite.mean(axis=0), elite.std(axis=0) + 0.02
        torch.nn.utils.vector_to_parameters(torch.from_numpy(mean).float(), policy.parameters())
        test = saves(env, policy, test_seed, args.test_episodes)
        episodes = (it + 1) * args.population * args.episodes
        print(f"{it + 1:9d}  {episodes:8d}  {100 * max(scores):13.1f}%  {100 * test:18.1f}%")


if __name__ == "__main__":
    main()
