"""Standard learning interfaces over the drills: Gymnasium and PettingZoo environments.

* :mod:`robotsoccer.envs.intercept` — the paper's layer-1 decision (TA from BD, BA, previous BD)
  as ``robotsoccer/Intercept-v0`` on any field model;
* :mod:`robotsoccer.envs.intercept_vector` — many of those decisions stepped as one batch
  (``gymnasium.make_vec("robotsoccer/Intercept-v0", num_envs=...)``, the Soccer Server's batched
  drill engine);
* :mod:`robotsoccer.envs.passing` — the pass drill's decisions (layer 2's choice of receiver,
  layer 1's TA for the receiver and the defenders) as a PettingZoo parallel environment,
  :func:`~robotsoccer.envs.passing.pass_parallel_env`.

Importing this package registers the ids with Gymnasium.
"""

from __future__ import annotations

from gymnasium.envs.registration import register, registry

from robotsoccer.envs.intercept import InterceptEnv
from robotsoccer.envs.intercept_vector import InterceptVectorEnv
from robotsoccer.envs.passing import PassParallelEnv, pass_parallel_env

INTERCEPT_ID = "robotsoccer/Intercept-v0"
"""The versioned Gymnasium id of :class:`~robotsoccer.envs.intercept.InterceptEnv`."""

if INTERCEPT_ID not in registry:
    register(
        id=INTERCEPT_ID,
        entry_point="robotsoccer.envs.intercept:InterceptEnv",
        vector_entry_point="robotsoccer.envs.intercept_vector:make_intercept_vector_env",
    )

__all__ = [
    "INTERCEPT_ID",
    "InterceptEnv",
    "InterceptVectorEnv",
    "PassParallelEnv",
    "pass_parallel_env",
]
