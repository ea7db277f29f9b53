"""Standard learning interfaces over the drills: Gymnasium and PettingZoo environments.

* :mod:`robotsoccer.envs.intercept` — the paper's layer-1 decision (TA from BD, BA, previous BD)
  as ``robotsoccer/Intercept-v0`` on any field model;
* :mod:`robotsoccer.envs.intercept_vector` — many of those decisions stepped as one batch
  (``gymnasium.make_vec("robotsoccer/Intercept-v0", num_envs=...)``, the Soccer Server's batched
  drill engine);
* :mod:`robotsoccer.envs.passing` — the pass drill's decisions (layer 2's choice of receiver,
  layer 1's TA for the receiver and the defenders) as a PettingZoo parallel environment,
  :func:`~robotsoccer.envs.passing.pass_parallel_env`;
* :mod:`robotsoccer.envs.match` — a whole match, every player (or some) an agent, in the
  field's own actions or the team minds' macro-actions (:mod:`robotsoccer.envs.macros`), as a
  PettingZoo parallel environment, :func:`~robotsoccer.envs.match.match_parallel_env`, on the
  loop it shares with half-field offense (:mod:`robotsoccer.envs.play`, agent names in
  :mod:`robotsoccer.envs.agents`);
* :mod:`robotsoccer.envs.hfo` — half-field offense in HFO's shape (attackers against defenders
  and a goalie), :func:`~robotsoccer.envs.hfo.half_field_offense_env`, and
  :mod:`robotsoccer.envs.hfo_eval`, the attackers' goal rate for a ball-holder policy;
* :mod:`robotsoccer.envs.control` — per-step control: ``robotsoccer/GoToBall-v0``
  (:mod:`robotsoccer.envs.go_to_ball`) and ``robotsoccer/Score-v0``
  (:mod:`robotsoccer.envs.score`) on either field model (spaces in
  :mod:`robotsoccer.envs.control_spaces`; ``gymnasium.make_vec`` gives Gymnasium's sync or,
  with ``vectorization_mode="async"``, multi-process vector environments).

Every environment draws frames (``render_mode="rgb_array"`` or ``"human"``,
:mod:`robotsoccer.envs.rendering`).

Importing this package registers the ids with Gymnasium.
"""

from __future__ import annotations

from gymnasium.envs.registration import register, registry

from robotsoccer.envs.go_to_ball import GoToBallEnv
from robotsoccer.envs.hfo import HalfFieldOffenseEnv, half_field_offense_env
from robotsoccer.envs.intercept import InterceptEnv
from robotsoccer.envs.intercept_vector import InterceptVectorEnv
from robotsoccer.envs.match import MatchParallelEnv, match_parallel_env
from robotsoccer.envs.passing import PassParallelEnv, pass_parallel_env
from robotsoccer.envs.score import ScoreEnv

INTERCEPT_ID = "robotsoccer/Intercept-v0"
"""The versioned Gymnasium id of :class:`~robotsoccer.envs.intercept.InterceptEnv`."""

if INTERCEPT_ID not in registry:
    register(
        id=INTERCEPT_ID,
        entry_point="robotsoccer.envs.intercept:InterceptEnv",
        vector_entry_point="robotsoccer.envs.intercept_vector:make_intercept_vector_env",
    )

GO_TO_BALL_ID = "robotsoccer/GoToBall-v0"
"""The versioned Gymnasium id of :class:`~robotsoccer.envs.go_to_ball.GoToBallEnv`."""
SCORE_ID = "robotsoccer/Score-v0"
"""The versioned Gymnasium id of :class:`~robotsoccer.envs.score.ScoreEnv`."""

for _id, _entry in ((GO_TO_BALL_ID, "go_to_ball:GoToBallEnv"), (SCORE_ID, "score:ScoreEnv")):
    if _id not in registry:
        # No step limit here: each task's own time limit truncates (max_time_s).
        register(id=_id, entry_point=f"robotsoccer.envs.{_entry}")

__all__ = [
    "GO_TO_BALL_ID",
    "INTERCEPT_ID",
    "SCORE_ID",
    "GoToBallEnv",
    "HalfFieldOffenseEnv",
    "InterceptEnv",
    "InterceptVectorEnv",
    "MatchParallelEnv",
    "PassParallelEnv",
    "ScoreEnv",
    "half_field_offense_env",
    "match_parallel_env",
    "pass_parallel_env",
]
