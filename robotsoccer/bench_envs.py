"""What the environment layers cost: the score, match and half-field offense environments.

The match and half-field offense are timed by :func:`match_env_figures` and
:func:`hfo_env_figures`.

:func:`score_env_figures` runs the score environment (3 v 3, the learner's actions uniform in
its Box with a fixed seed) for a number of ticks, then the same field, preset, players
and baseline minds without the environment (the match drill's loop: arena, minds, referee;
the learner there is a baseline mind too) for as many ticks, in the same process, one after
the other. Times are this process's CPU seconds (``time.process_time``), not wall seconds: on
a machine shared with other jobs the wall clock charges one run with the others' work, while
the question is what the layer itself costs. The ratio of the speeds is the environment
layer's share of the cost
(observations, rewards, the coach's checks, episode resets); rSoccer's Python layer costs 40-60%
of its physics, the target here is at most 20% (a ratio of at least 0.8).
"""

from __future__ import annotations

import time
from typing import Any

import numpy as np

from field_models.registry import make_arena
from field_models.seeding import TrialRngs
from robotsoccer.drills.match import MatchDrill
from robotsoccer.envs.score import ScoreEnv
from robotsoccer.runs.runner import TrialLoop


def env_run(field_model: str, ticks: int, seed: int = 0) -> tuple[int, int, float]:
    """(steps, ticks, CPU seconds) of the score environment over at least `ticks` ticks."""
    env = ScoreEnv(field_model)
    # Drawn up front: sampling the Box costs more than an environment step.
    shape = env.action_space.shape or ()
    actions = np.random.default_rng(seed).uniform(-1.0, 1.0, (4096, *shape)).astype(np.float32)
    steps = done_ticks = 0
    start = time.process_time()
    episode_seed = seed
    while done_ticks < ticks:
        env.reset(seed=episode_seed)
        episode_seed += 1
        ended = False
        while not ended:
            action = actions[steps % len(actions)]
            _, _, terminated, truncated, info = env.step(action)
            steps += 1
            ended = terminated or truncated
        done_ticks += info["tick"]
    return steps, done_ticks, time.process_time() - start


def bare_run(field_model: str, ticks: int, seed: int = 0) -> float:
    """CPU seconds of the same field and minds stepping `ticks` ticks without the env layer."""
    env = ScoreEnv(field_model)  # the same preset, options and players
    dt = env.facts.dt_s
    drill = MatchDrill(left="baseline", right="baseline", players=env.players_per_side,
                       half_time_s=ticks * dt)  # fmt: skip
    drill.max_time_s = ticks * dt  # one half: no half-time restart
    rngs = TrialRngs(seed, 0)
    arena = make_arena(field_model, env.preset, env.players, rngs, env.field_options)
    start = time.process_time()
    drill.setup(arena, rngs)
    TrialLoop(arena, drill, drill.minds(arena, rngs)).run()
    return time.process_time() - start


def score_env_figures(field_model: str, ticks: int) -> dict[str, Any]:
    """Steps/s and real-time factor of the score env, the bare arena's, and their ratio."""
    steps, env_ticks, env_wall = env_run(field_model, ticks)
    bare_wall = bare_run(field_model, env_ticks)
    dt = ScoreEnv(field_model).facts.dt_s
    env_rtf = env_ticks * dt / env_wall
    bare_rtf = env_ticks * dt / bare_wall
    return {
        "steps_per_s": round(steps / env_wall),
        "realtime_factor": round(env_rtf, 1),
        "bare_realtime_factor": round(bare_rtf, 1),
        "env_to_bare_ratio": round(env_rtf / bare_rtf, 3),
    }


# ----------------------------------------------------------------------------- the match envs


def match_env_figures(field_model: str, half_time_s: float, seed: int = 0) -> dict[str, Any]:
    """A whole match through the match environment, and the same match without it.

    The environment is :class:`~robotsoccer.envs.match.MatchParallelEnv` with every player an
    agent, at the field's own team size.

    Two runs through the environment: ``commands`` (each agent's parametrised command drawn
    uniformly, up front, from a fixed seed) and ``macro`` with ``AUTO`` for every agent (every
    agent its team mind: the same match as the drill's, so the ratio of its real-time factor to
    the bare loop's is the environment layer's share of the cost). CPU seconds, as above.

    Returns:
        Steps per second (one step: the agents deciding on one tick), agent decisions per
        second and real-time factor of each run; the bare match's real-time factor; the ratio.
    """
    from robotsoccer.drills.match import MatchDrill
    from robotsoccer.envs.match import MatchParallelEnv

    out: dict[str, Any] = {}
    rng = np.random.default_rng(seed)
    commands = rng.uniform(-1.0, 1.0, (4096, 8)).astype(np.float32)
    dt = 0.0
    for action in ("commands", "macro"):
        env = MatchParallelEnv(field_model, half_time_s=half_time_s, action=action)
        dt = env.facts.dt_s
        steps = decisions = 0
        start = time.process_time()
        _, infos = env.reset(seed=seed)
        while env.agents:
            if action == "macro":
                actions: dict[str, Any] = dict.fromkeys(env.agents, 0)
            else:
                actions = {a: commands[(steps + i) % 4096] for i, a in enumerate(env.agents)}
            decisions += sum(1 for a in env.agents if infos[a]["deciding"])
            _, _, _, _, infos = env.step(actions)
            steps += 1
        cpu = time.process_time() - start
        ticks = next(iter(infos.values()))["tick"]
        out[f"{action}_steps_per_s"] = round(steps / cpu)
        out[f"{action}_agent_steps_per_s"] = round(decisions / cpu)
        out[f"{action}_realtime_factor"] = round(ticks * dt / cpu, 1)
    drill = MatchDrill(left="baseline", right="baseline", half_time_s=half_time_s)
    facts = MatchParallelEnv(field_model, half_time_s=half_time_s).facts
    rngs = TrialRngs(seed, 0)
    arena = make_arena(field_model, None, drill.players_for(facts), rngs, env.field_options)
    start = time.process_time()
    drill.setup(arena, rngs)
    TrialLoop(arena, drill, drill.minds(arena, rngs)).run()
    bare = 2.0 * half_time_s / (time.process_time() - start)
    out["bare_realtime_factor"] = round(bare, 1)
    out["macro_to_bare_ratio"] = round(out["macro_realtime_factor"] / bare, 3)
    return out


def hfo_env_figures(field_model: str, episodes: int, seed: int = 0) -> dict[str, Any]:
    """Half-field offense (2 attackers as agents against a defender and a goalie) in macro mode.

    Every attacker plays ``AUTO`` (the team minds), the hand-written baseline of
    :mod:`robotsoccer.envs.hfo_eval`; CPU seconds as above.

    Returns:
        Steps per second, episodes per second and the real-time factor.
    """
    from robotsoccer.envs.hfo import HalfFieldOffenseEnv

    env = HalfFieldOffenseEnv(field_model, action="macro")
    steps = ticks = 0
    start = time.process_time()
    for k in range(episodes):
        env.reset(seed=seed if k == 0 else None)
        infos: dict[str, Any] = {}
        while env.agents:
            _, _, _, _, infos = env.step(dict.fromkeys(env.agents, 0))
            steps += 1
        ticks += next(iter(infos.values()))["tick"]
    cpu = time.process_time() - start
    return {
        "steps_per_s": round(steps / cpu),
        "episodes_per_s": round(episodes / cpu, 1),
        "realtime_factor": round(ticks * env.facts.dt_s / cpu, 1),
    }
